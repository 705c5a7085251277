#pragma once
// Reading and writing surface meshes: OBJ, OFF, STL, PLY (OpenMesh::IO; OBJ and OFF through our
// own triangle-soup reader so they can be repaired) and Medit .mesh (Vertices, Triangles with
// refs; written with Edges/Ridges/Corners for the features). Reading repairs what a user would
// expect (merges duplicate vertices, drops degenerate and repeated faces, makes orientation
// consistent and closed components outward) and reports it; what cannot be repaired (a
// non-manifold edge or vertex) is a InputError naming the file and the element.
// Writing goes to a temporary file in the same folder, then renames.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

struct ReadReport
{
    std::size_t merged_vertices = 0;
    std::size_t degenerate_faces = 0;  // dropped: a repeated vertex or zero area
    std::size_t duplicate_faces = 0;   // dropped: same three vertices as an earlier face
    std::size_t reoriented_faces = 0;
    std::size_t unused_vertices = 0;  // dropped: referenced by no face
    std::size_t components = 0;
    std::vector<std::string> warnings;  // one line per repair, naming the file
};

/// A triangle soup: what the readers produce before the mesh is built.
struct TriangleSoup
{
    std::vector<Vec3d> points;
    std::vector<std::array<int, 3>> triangles;
    std::vector<int> refs;  // per triangle (0 when the format has none)
};

/// Builds a mesh from a soup, repairing as described above. `source` names the input in
/// messages.
SurfaceMesh build_surface(TriangleSoup soup, const std::string& source,
                          ReadReport* report = nullptr);

/// Reads by extension (.obj .off .stl .ply .mesh, case-insensitive). Throws IoError
/// (cannot open) or InputError (malformed, unrepairable, empty).
SurfaceMesh read_surface(const std::string& path, ReadReport* report = nullptr);

/// The file's triangles as listed, nothing repaired (polygons split into fans), for a caller
/// that validates them itself: same formats and errors as read_surface. STL (ASCII or binary)
/// gives three points per facet, none merged; PLY (ASCII or binary) its vertex x, y, z and face
/// vertex_indices, other elements and properties skipped.
TriangleSoup read_triangle_soup(const std::string& path);

/// Whether read_surface reads this path's extension.
bool is_surface_path(const std::string& path);

/// Writes by extension, atomically. Throws IoError.
void write_surface(const SurfaceMesh& mesh, const std::string& path);

}  // namespace hdimesh::surface
