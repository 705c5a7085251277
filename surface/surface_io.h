#pragma once
// Reading and writing surface meshes: OBJ, OFF, STL, PLY (OpenMesh::IO; OBJ and OFF through our
// own triangle-soup reader so they can be repaired) and Medit .mesh (Vertices, Triangles with
// refs; written with Edges/Ridges/Corners for the features). Reading runs the one repair pass
// (surface/soup_repair.h: merges, drops, orients, splits pinches) and reports each repair;
// what stays ambiguous (a non-manifold edge) is an InputError naming the file and the element.
// Writing goes to a temporary file in the same folder, then renames.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "surface/soup_repair.h"
#include "surface/surface_mesh.h"
#include "surface/triangle_soup.h"

namespace hdimesh::surface
{

/// What the repair pass (surface/soup_repair.h) changed; `notes` names the file on each line.
using ReadReport = SoupRepairReport;

/// Builds a mesh from a soup, repaired by repair_soup with `repair` (holes stay open unless
/// it asks). `source` names the input in messages.
SurfaceMesh build_surface(TriangleSoup soup, const std::string& source,
                          ReadReport* report = nullptr, const SoupRepairOptions& repair = {});

/// Reads by extension (.obj .off .stl .ply .mesh, case-insensitive). Throws IoError
/// (cannot open) or InputError (malformed, unrepairable, empty).
SurfaceMesh read_surface(const std::string& path, ReadReport* report = nullptr,
                         const SoupRepairOptions& repair = {});

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
