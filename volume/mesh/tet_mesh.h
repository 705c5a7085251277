#pragma once
// TetMesh: the volume container. Flat arrays indexed by integer ids, owned in the open like
// Omega_h/Mmg so hot loops stay simple; the invariants below are what every operator keeps.
//
// Invariants (checked by check_mesh in volume/check/check.h):
//  - every live tet is positive: det(v1-v0, v2-v0, v3-v0) > 0 (numbering in tet_tables.h);
//  - neighbors[t][i] is the tet across face i (opposite local vertex i), or kNoTet on the
//    boundary, and the relation is symmetric; it is valid only after build_adjacency() and
//    until the next topology change that does not maintain it;
//  - triangles are the boundary (and interface) faces, oriented outward, each with a ref;
//  - a killed tet keeps its slot (tets[t][0] == kDeadTet) until compact().

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "common/classification.h"
#include "volume/mesh/geometry.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

/// What a vertex lies on. No operator may change a vertex's class (Omega_h's classification).
enum class VertexClass : std::uint8_t
{
    Interior = 0,  ///< strictly inside the volume
    Surface = 1,   ///< on a smooth part of the boundary (or of an interface between tet refs)
    Ridge = 2,     ///< on a feature curve (Medit Ridges, or a boundary edge of an open surface)
    Corner = 3,    ///< a fixed point (Medit Corners, or where ridges meet)
};

const char* to_string(VertexClass c);

/// The shared classification of a vertex of this class (common/classification.h); `id` is the
/// curve, surface or region it lies on where the caller knows it.
Classification to_classification(VertexClass c, int id = kNoModelEntity);
/// The class of a tet-mesh vertex that lies on `c` (an open-boundary curve is a Ridge here).
VertexClass to_vertex_class(const Classification& c);

inline constexpr int kNoTet = -1;    ///< neighbour across a boundary face
inline constexpr int kDeadTet = -1;  ///< tets[t][0] of a killed tet

using TetVertices = std::array<int, 4>;
using Triangle = std::array<int, 3>;

/// A triangle's vertices in increasing order: the key of a face whatever its orientation.
inline Triangle sorted_triple(const Triangle& t)
{
    Triangle s = t;
    if (s[0] > s[1]) std::swap(s[0], s[1]);
    if (s[1] > s[2]) std::swap(s[1], s[2]);
    if (s[0] > s[1]) std::swap(s[0], s[1]);
    return s;
}
/// True when u lists the vertices of t in the same cyclic order (same orientation).
inline bool same_orientation(const Triangle& t, const Triangle& u)
{
    for (int k = 0; k < 3; ++k)
        if (u[k] == t[0]) return u[(k + 1) % 3] == t[1] && u[(k + 2) % 3] == t[2];
    return false;
}
using Edge = std::array<int, 2>;

/// Old-to-new index maps returned by TetMesh::compact(); removed entities map to -1.
struct CompactionMaps
{
    std::vector<int> old2new_verts;
    std::vector<int> old2new_tets;
};

struct TetMesh
{
    // --- vertices
    std::vector<Vec3> points;
    std::vector<int> vertex_refs;
    std::vector<VertexClass> vertex_classes;

    // --- tetrahedra
    std::vector<TetVertices> tets;
    std::vector<int> tet_refs;
    std::vector<TetVertices> neighbors;  ///< see the invariants above; empty until built

    // --- boundary and feature entities kept from the input (Medit names)
    std::vector<Triangle> triangles;  ///< boundary and interface triangles, outward
    std::vector<int> triangle_refs;
    std::vector<Edge> edges;  ///< feature edges ("Edges" section)
    std::vector<int> edge_refs;
    std::vector<int> ridges;              ///< indices into edges
    std::vector<int> corners;             ///< vertex ids
    std::vector<int> required_vertices;   ///< vertex ids
    std::vector<int> required_edges;      ///< indices into edges
    std::vector<int> required_triangles;  ///< indices into triangles
    std::vector<int> required_tets;       ///< tet ids

    // --- construction
    int add_vertex(const Vec3& p, int ref = 0, VertexClass cls = VertexClass::Interior);
    int add_tet(const TetVertices& v, int ref = 0);
    int add_triangle(const Triangle& v, int ref = 0);
    /// Marks tet t dead; its slot and neighbours' links are left for the caller / compact().
    void kill_tet(int t);

    // --- queries
    int num_vertices() const { return static_cast<int>(points.size()); }
    int num_tet_slots() const { return static_cast<int>(tets.size()); }
    int num_live_tets() const;
    bool is_dead(int t) const { return tets[t][0] == kDeadTet; }
    bool has_adjacency() const { return neighbors.size() == tets.size(); }
    double volume(int t) const;
    double quality(int t) const;
    double total_volume() const;
    /// Bytes held by the arrays (capacity), for the memory benchmark.
    std::size_t memory_bytes() const;

    // --- topology
    /// Rebuilds neighbors in O(n): faces are bucketed by their smallest vertex and matched
    /// inside the bucket. Returns the number of faces found in more than two tets (those
    /// keep kNoTet links; check_mesh reports them).
    int build_adjacency();
    /// Whether tet t lists its local edge e in a scan that lists each edge about once: neither
    /// tet across its two faces at e has a smaller index, so the smallest tet around every edge
    /// lists it (a few others may too: deduplicate). Needs the adjacency.
    bool lists_edge(int t, int e) const
    {
        const auto& nb = neighbors[t];
        const int f = tet::kEdgeFaces[e][0], g = tet::kEdgeFaces[e][1];
        return (nb[f] == kNoTet || nb[f] > t) && (nb[g] == kNoTet || nb[g] > t);
    }

    /// Sets vertex_classes from triangles, ridges and corners: a vertex of a triangle is
    /// Surface, of a ridge edge Ridge, a corner Corner, else Interior.
    void classify_vertices();

    /// Drops dead tets and vertices used by no tet, triangle or edge; renumbers everything
    /// (adjacency included) and returns the maps.
    CompactionMaps compact();

    // --- the arrays, listed once: whatever renumbers vertices or tets (compact(),
    // renumber_spatially()) visits them through these, so a new array is added here only.
    /// f(array) for every array holding one value per vertex id.
    template <class F>
    void for_each_vertex_array(F&& f)
    {
        f(points);
        f(vertex_refs);
        f(vertex_classes);
    }
    /// f(array) for every array holding one value per tet slot, except neighbors (its values
    /// are tet ids: the renumbering maps them too).
    template <class F>
    void for_each_tet_array(F&& f)
    {
        f(tets);
        f(tet_refs);
    }
    /// f(id) on every stored vertex id (by reference): live tets, triangles, edges, corners,
    /// required vertices.
    template <class F>
    void for_each_vertex_id(F&& f)
    {
        for (auto& tv : tets)
            if (tv[0] != kDeadTet)
                for (int& v : tv) f(v);
        for (auto& tri : triangles)
            for (int& v : tri) f(v);
        for (auto& e : edges)
            for (int& v : e) f(v);
        for (int& v : corners) f(v);
        for (int& v : required_vertices) f(v);
    }
};

}  // namespace hdimesh::volume
