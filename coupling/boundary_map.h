#pragma once
// The tets' boundary as an OpenMesh surface, and the vertex correspondence between the two
// meshes: the coupled surface pass works on the surface, the mirror (coupling/mirror.h) keeps
// the tets in step, and write_back hands the result to the tets' own boundary arrays.
//
//   tets ──extract_boundary──> surface (+ "hdimesh:v:tet_vertex")
//     ^                            │ surface operators, mirrored into the tets
//     └──────── write_back ────────┘ triangles, refs, ridges, corners, vertex classes
//
// The correspondence lives on the surface only, as a vertex property: it survives OpenMesh's
// garbage collection, and the tets' side is rebuilt from it (tet_to_surface) when needed.

#include <string>
#include <vector>

#include "surface/surface_mesh.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::coupling
{

namespace property_names
{
constexpr const char* tet_vertex = "hdimesh:v:tet_vertex";  // int, the tet-mesh vertex id
}

/// Why the coupled surface pass cannot run on `mesh` (empty: it can): interfaces between tet
/// refs that meet the boundary or each other (a non-manifold surface; closed interface shells
/// apart from the rest are taken), required boundary entities the surface operators do not
/// know, or a boundary that is not a closed 2-manifold. adapt() then keeps the boundary.
std::string coupled_surface_refusal(const volume::TetMesh& mesh);

struct BoundaryMap
{
    surface::SurfaceMesh surface;
    OpenMesh::VPropHandleT<int> tet_vertex;

    int tet_vertex_of(surface::VertexHandle v) const { return surface.property(tet_vertex, v); }
    /// Per tet vertex, its surface vertex (invalid handle for a vertex off the boundary).
    std::vector<surface::VertexHandle> tet_to_surface(int num_tet_vertices) const;
};

/// The boundary and interface faces (volume::tet_surface_faces: the interfaces outward from
/// their smaller ref), as one surface with the refs of mesh.triangles (0 for
/// a face not listed) and the vertex classes of the tets (Surface → smooth, Ridge → ridge,
/// Corner → corner; curve ids from mesh.edges as write_back stores them, else the feature
/// detector's to run on it). \pre mesh has a valid adjacency (the faces are read off it) and
/// coupled_surface_refusal(mesh) is empty. Throws TopologyError naming the face when OpenMesh
/// cannot take it (a non-manifold vertex).
BoundaryMap extract_boundary(const volume::TetMesh& mesh);

/// The surface's faces become mesh.triangles (with their refs), its curve edges mesh.edges and
/// ridges (ref: curve id + 1), its corners mesh.corners; boundary vertices take the surface's
/// class, every other vertex is Interior. \pre the surface has no deleted elements and its
/// faces are the tets' boundary (check_consistency).
void write_back(const BoundaryMap& map, volume::TetMesh& mesh);

}  // namespace hdimesh::coupling
