#pragma once
// Local topology over TetMesh's `neighbors` adjacency, shared by the optimization operators:
// a vertex's ball, an edge's ordered shell, what the operators must leave alone (boundary and
// interface triangles, feature edges, non-interior vertices), and the one commit primitive
// that swaps a set of tets for another filling the same region while keeping the adjacency.

#include <array>
#include <cstdint>
#include <vector>

#include "common/parallel.h"
#include "common/size_field.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// Local index (0..3) of vertex v in tet t, or -1. Inline: every walk asks it per tet.
inline int local_index(const TetMesh& mesh, int t, int v)
{
    const auto& tv = mesh.tets[t];
    for (int k = 0; k < 4; ++k)
        if (tv[k] == v) return k;
    return -1;
}

/// The tets containing vertex v, walked from `seed` (a live tet containing v) across the faces
/// through v, in a fixed breadth-first order. `ball` is cleared first.
void vertex_ball(const TetMesh& mesh, int seed, int v, std::vector<int>& ball);

/// The tets around edge (a, b) in order. Tet tets[i] has vertices {a, b, ring[i], ring[i+1]}
/// and (a, b, ring[i], ring[i+1]) is positively oriented: seen from b the ring turns
/// counter-clockwise. Closed shell: ring.size() == tets.size() (indices taken modulo the size).
/// Open shell (the edge touches the boundary): ring.size() == tets.size() + 1.
struct EdgeShell
{
    int a = -1, b = -1;
    std::vector<int> tets;
    std::vector<int> ring;
    bool closed = false;
};

/// Fills `shell` for the edge (a, b) of the live tet `seed`. Returns false when the walk finds
/// an inconsistent adjacency (should not happen in a valid mesh).
bool edge_shell(const TetMesh& mesh, int seed, int a, int b, EdgeShell& shell);

/// One live tet per vertex (-1 for a vertex no tet uses), the smallest id.
std::vector<int> vertex_to_tet(const TetMesh& mesh);

/// Per vertex: required, or a vertex of a required triangle. Such vertices stay where they are
/// (Mmg's rule; a rank's cut too, whose two sides must agree on it).
std::vector<char> held_vertices(const TetMesh& mesh);

/// The sorted vertex triple of face f of tet t.
std::array<int, 3> sorted_face(const TetMesh& mesh, int t, int f);

/// What the optimization operators may not touch (the boundary stays fixed).
class MeshConstraints
{
public:
    MeshConstraints() = default;
    explicit MeshConstraints(const TetMesh& mesh);

    /// Face f of tet t is on the boundary, between two tet refs, or listed in mesh.triangles.
    bool is_constrained_face(const TetMesh& mesh, int t, int f) const;
    /// Edge (a, b) is a listed feature edge (mesh.edges).
    bool is_constrained_edge(int a, int b) const;
    /// Vertex v may move or disappear: interior and not required.
    bool is_free_vertex(int v) const { return free_vertex_[v] != 0; }
    /// Tet t may be removed (not required).
    bool is_removable_tet(int t) const;
    /// Vertex v is on a smooth part of the boundary and nothing else holds it (not required,
    /// on no feature edge, no corner): a collapse may move it within a flat boundary.
    bool is_surface_vertex(int v) const
    {
        return static_cast<std::size_t>(v) < surface_vertex_.size() && surface_vertex_[v] != 0;
    }
    /// Index in mesh.triangles of the listed face with these vertices (any order), or -1.
    int listed_triangle(const std::array<int, 3>& face) const;
    /// Keeps the listed faces current after a collapse on the boundary moved `from` onto `to`:
    /// mesh.triangles through both are dropped (the last moved into their slot), `from` is `to`
    /// in the others.
    void collapse_listed_faces(TetMesh& mesh, int from, int to);

    /// Keeps the per-vertex flags sized after vertices were added (new ones are interior).
    void grow(int num_vertices);

private:
    void insert_face(const std::array<int, 3>& key, int triangle);
    void erase_face(const std::array<int, 3>& key);

    std::vector<std::array<int, 3>> faces_;  // sorted triples, sorted
    std::vector<int> face_triangle_;         // per entry of faces_: its index in mesh.triangles
    std::vector<char> surface_vertex_;
    std::vector<std::array<int, 2>> edges_;  // sorted pairs, sorted
    std::vector<char> free_vertex_;
    std::vector<char> on_listed_face_;  // per vertex: a vertex of some face in faces_
    std::vector<int> required_tets_;    // sorted
};

/// The state every operator reads and keeps current: the size field (nullptr: no size checks),
/// the constraints, and one live tet per vertex (so balls need no global search).
struct OperatorContext
{
    const SizeField* field = nullptr;
    MeshConstraints constraints;
    std::vector<int> vertex_tet;
    /// Tets created or reshaped by operators (appended, never cleared here): the driver's
    /// next work list.
    std::vector<int> touched;

    OperatorContext() = default;
    OperatorContext(const TetMesh& mesh, const SizeField* size_field);

    /// Turns on two caches (off by default) for the optimizer's hot loops, which ask for the
    /// same things many times: tet qualities per slot, and the last few vertex balls. While
    /// they are on, every change of a tet's vertices or positions must go through
    /// tets_changed() and every change of topology through replace_tets() (the operators in
    /// volume/ do); a debug build checks every cached answer against a fresh one.
    void enable_caches();
    /// Qe of (a,b,c,d) as the operators judge shapes: in the field's metric at the centroid
    /// when the field is anisotropic, else the Euclidean Qe (tet_quality).
    double shape(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) const;
    /// shape() of live tet t, from the cache when it is on. Bitwise the same value.
    double quality(const TetMesh& mesh, int t) const;
    /// With the cache on, computes every live tet's quality not yet cached, on `workers` (null:
    /// one thread): each slot is written by one thread, and holds mesh.quality(t) as before.
    void fill_quality_cache(const TetMesh& mesh, Workers* workers) const;
    /// Minimum of quality() over a list of tets (+infinity for an empty list).
    double worst_quality(const TetMesh& mesh, const std::vector<int>& tets) const;
    /// The tets around vertex v, walked from vertex_tet[v] (vertex_ball's order), into `ball`.
    void ball(const TetMesh& mesh, int v, std::vector<int>& ball) const;
    /// Drops the cached balls (replace_tets calls it: the topology changed).
    void forget_balls() const;
    /// Records that the tets [begin, end) were created or reshaped: appended to touched, and
    /// their cached qualities dropped.
    void tets_changed(const int* begin, const int* end);
    void tets_changed(const std::vector<int>& tets)
    {
        tets_changed(tets.data(), tets.data() + tets.size());
    }

    /// Turns on change stamps (off by default): each tets_changed() counts one change and
    /// stamps the vertices of those tets with the count. An operator whose answer depends only
    /// on the tets through some vertices (their balls) answers the same while none of them is
    /// stamped after it was asked, so a driver may skip the repeat.
    void enable_change_stamps(const TetMesh& mesh);
    /// The changes counted so far.
    std::uint64_t changes() const { return changes_; }
    /// changes() when a tet through v last changed; 0 when none did since the stamps began.
    std::uint64_t vertex_changed(int v) const
    {
        return static_cast<std::size_t>(v) < vertex_stamp_.size() ? vertex_stamp_[v] : 0;
    }

    /// Edge (p, q) would be too long for the field (false without a field).
    bool too_long(const Vec3& p, const Vec3& q) const;
    /// Edge (p, q) would be too short for the field (false without a field).
    bool too_short(const Vec3& p, const Vec3& q) const;
    /// Qt of edge (p, q) (1 without a field).
    double size_quality(const Vec3& p, const Vec3& q) const;

private:
    double tet_shape(const TetMesh& mesh, int t) const;
    struct CachedBall
    {
        int vertex = -1;
        std::vector<int> tets;
    };
    bool cache_enabled_ = false;
    mutable std::vector<double> quality_cache_;     // per tet slot; NaN: not known
    mutable std::array<CachedBall, 4> ball_cache_;  // filled round-robin
    mutable std::size_t next_ball_ = 0;
    const TetMesh* stamped_mesh_ = nullptr;  // the mesh whose tets tets_changed() names
    std::vector<std::uint64_t> vertex_stamp_;
    std::uint64_t changes_ = 0;
};

/// Replaces the live tets `removed` by tets `added` (all of ref `ref`) that fill the same region
/// and share its outer faces. Reuses the freed slots first (so ids stay dense), then add_tet.
/// Keeps mesh.neighbors symmetric and context.vertex_tet valid for the vertices of `added`;
/// appends the new ids to context.touched.
/// Returns the ids of the new tets, in the order of `added`.
std::vector<int> replace_tets(TetMesh& mesh, OperatorContext& context,
                              const std::vector<int>& removed,
                              const std::vector<TetVertices>& added, int ref);

/// The legality every operator on an edge's shell shares (topology, then constraints): edge
/// local_edge of live tet seed is interior (a closed shell) with 3..max_ring tets, not a listed
/// feature edge, its tets of one ref, all removable, and no constrained face through the edge.
/// Fills `shell` and `ref` (the shell's tet ref); false when any of it fails.
bool free_interior_shell(const TetMesh& mesh, const OperatorContext& context, int seed,
                         int local_edge, int max_ring, EdgeShell& shell, int& ref);

}  // namespace hdimesh::volume
