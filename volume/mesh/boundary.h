#pragma once
// The tet complex seen from its faces and edges: which tets use each face, which faces are the
// boundary (used by exactly one tet), the unique edges, the volume a set of triangles encloses.
// Computed from the tets alone, never from mesh.neighbors or mesh.triangles, so the checker and
// the quality report can compare those stored arrays against the truth.

#include <utility>
#include <vector>

#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// One face of a live tet: tets[tet], local face `local_face` (tet_tables.h numbering).
struct TetFace
{
    int tet;
    int local_face;
};

/// Every distinct face (vertex set) of the live tets with the tets that use it:
/// the uses of face k are uses[start[k] .. start[k+1]). Faces are grouped in O(n) by their
/// smallest vertex, as TetMesh::build_adjacency does. Tets with a vertex id out of range are
/// skipped (check_mesh reports them).
struct FaceGroups
{
    std::vector<int> start;
    std::vector<TetFace> uses;
    int num_faces() const { return static_cast<int>(start.size()) - 1; }
};

FaceGroups group_tet_faces(const TetMesh& mesh);

/// The face's vertices as the tet lists them (outward when the tet is positive).
Triangle face_vertices(const TetMesh& mesh, const TetFace& face);

/// The faces used by exactly one live tet, oriented as that tet sees them (outward).
std::vector<Triangle> tet_boundary_faces(const TetMesh& mesh);

/// The boundary faces (above) and, once each, the faces between two live tets of different
/// refs (the interfaces), oriented outward from the tet with the smaller ref (as
/// repair_boundary lists them): one orientation per interface, consistent over each of its
/// closed shells.
std::vector<Triangle> tet_surface_faces(const TetMesh& mesh);

/// tet_surface_faces read off mesh.neighbors instead of grouping every face of the mesh: the
/// same faces in the same order (sorted by their sorted vertex triples), in time linear in the
/// tets with no sort of all faces. \pre the adjacency is valid (an assertions build compares).
std::vector<Triangle> tet_surface_faces_by_adjacency(const TetMesh& mesh);

/// One listing of mesh.triangles under its vertex set: ordered by the set, then by index, so
/// that equal_range over a set gives every listing of that face, the first listed first.
struct ListedTriangle
{
    Triangle key;  ///< sorted_triple of the triangle
    int index;     ///< into mesh.triangles
    bool operator<(const ListedTriangle& o) const
    {
        return key != o.key ? key < o.key : index < o.index;
    }
};

/// mesh.triangles with valid vertex ids, sorted (above).
std::vector<ListedTriangle> listed_triangles(const TetMesh& mesh);

/// The listings of the face with vertex set `key` (sorted), a range of `listed`.
std::pair<std::vector<ListedTriangle>::const_iterator, std::vector<ListedTriangle>::const_iterator>
listings(const std::vector<ListedTriangle>& listed, const Triangle& key);

/// Volume enclosed by a closed, outward-oriented triangle set (divergence theorem), computed
/// relative to the triangles' bounding-box centre so large offsets do not cost precision.
double enclosed_volume(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles);

/// Undirected edges of the live tets, each once as {low, high} id, sorted. O(n) with a
/// per-vertex bucket (no std::map), so it stays fast on millions of tets.
std::vector<Edge> unique_tet_edges(const TetMesh& mesh);

/// Vertex-to-vertex adjacency through the edges of live tets, in compressed rows:
/// the neighbours of v are neighbors[start[v] .. start[v+1]), sorted.
struct VertexGraph
{
    std::vector<int> start;
    std::vector<int> neighbors;
};

VertexGraph vertex_graph(const TetMesh& mesh);

}  // namespace hdimesh::volume
