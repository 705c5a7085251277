#pragma once
// The cavity filler (issue 15): tets for any closed, outward-oriented set of triangles over a
// mesh's points, a hole left by a surface operation or a whole surface with several shells.
// Cheapest stage first:
//
//   1. fan from a cavity vertex          that sees every face not incident to it
//   2. fan from a kernel point           Chebyshev centre of the face half-spaces (a 3-D LP),
//                                        then smoothed inside the kernel (Schönhardt cavities)
//   3. exhaustive search                 small polyhedron reconnection (<= 32 points): the
//                                        max-min quality tetrahedralization, or a proof of none
//   4. advancing front with retreat      larger cavities and whole volumes (advancing_front.h)
//   5. grow the cavity                   by one layer of interior tets, then again from 1
//   6. give up                           nothing changed; the caller refuses its operation
//
// fill_cavity and refill_tets only compute: the mesh is not touched until commit_cavity.
// Steiner points are strictly inside the cavity, never on its faces. Every decision of
// topology uses the exact predicates of volume/mesh/predicates.h; ties go to the smaller vertex id,
// so the output is a function of the input alone.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "volume/fill/advancing_front.h"
#include "volume/mesh/size_field.h"
#include "volume/mesh/tet_mesh.h"
#include "volume/mesh/tet_topology.h"

namespace hdimesh::volume
{

/// The stage that produced a fill (or Failed), in cascade order.
enum class FillStage : std::uint8_t
{
    VertexFan = 0,
    KernelFan = 1,
    Exhaustive = 2,
    AdvancingFront = 3,
    Failed = 4,
};
inline constexpr int kNumFillStages = 5;

const char* to_string(FillStage stage);

struct CavityOptions
{
    /// A stage's fill is taken at once when its worst Qe reaches this; otherwise the cascade
    /// goes on and keeps the best valid fill found.
    double accept_quality = 0.2;
    /// Stages 1-2 are tried only on cavities with at most this many faces (a fan of a large
    /// convex surface is valid and all slivers).
    int max_fan_faces = 200;
    /// Stage 3: polyhedra with at most this many points (cavity vertices + candidates).
    int max_exhaustive_points = 32;
    /// Stage 3: search nodes at most (a node = one tet tried on one face).
    long exhaustive_node_budget = 20000;
    /// Stage 3 when stage 1 or 2 already filled the cavity below accept_quality: the search
    /// only looks for a better fill, with at most this many nodes.
    long improve_node_budget = 2000;
    /// Stage 4 (cavities with more faces than stage 3 takes, or when 1-3 failed).
    AdvancingFrontOptions front;
    /// Stage 5 (refill_tets only): layers of interior tets added at most.
    int max_grow_layers = 3;
};

/// A computed fill, not yet in the mesh.
struct CavityFill
{
    bool filled = false;
    FillStage stage = FillStage::Failed;
    /// Positive tets. Vertex ids index the mesh's points, and id mesh.num_vertices() + k is
    /// new_points[k].
    std::vector<TetVertices> tets;
    std::vector<Vec3> new_points;  ///< Steiner points, strictly inside
    int first_new_vertex = 0;      ///< the mesh's vertex count when the fill was computed
    /// The faces filled: the input faces, or the boundary of removed_tets after growing.
    std::vector<Triangle> faces;
    /// refill_tets: the live tets the fill replaces (the given ones plus the grown layers).
    std::vector<int> removed_tets;
    int ref = 0;  ///< ref of the new tets (refill_tets: the cavity's common tet ref)
    /// Per new tet, its ref, for a fill put together from cavities on both sides of an
    /// interface (empty: every tet takes `ref`).
    std::vector<int> tet_refs;
    int grown_layers = 0;
    double worst_quality = 0;  ///< min Qe over tets
    std::string failure;       ///< why not, when !filled
};

/// Fills the region bounded by `faces` (closed, each edge in exactly two faces with opposite
/// directions, outward-oriented; vertex ids into mesh.points). The mesh supplies points only.
/// field: sizes for interior points (nullptr: from the face sizes). Never throws on a cavity
/// that cannot be filled: filled = false with `failure` set.
CavityFill fill_cavity(const TetMesh& mesh, const std::vector<Triangle>& faces,
                       const SizeField* field, const CavityOptions& options = {});

/// Fills the hole left by removing the live tets `tets` (connected, one ref; needs adjacency),
/// growing it by whole layers of interior tets (never across mesh.triangles, a tet ref change
/// or the boundary) when stages 1-4 fail.
/// constraints: what may not be crossed when growing (nullptr: built from the mesh, O(mesh)).
CavityFill refill_tets(const TetMesh& mesh, const std::vector<int>& tets, const SizeField* field,
                       const CavityOptions& options = {},
                       const MeshConstraints* constraints = nullptr);

/// Puts a fill into the mesh in one step: adds new_points (Interior, ref 0), kills
/// removed_tets, adds the new tets with fill.ref into the freed slots first. Keeps the
/// adjacency when the mesh has it and is not empty (the new tets are linked to each other and
/// to the tets across fill.faces); into an empty mesh (a whole volume) the caller then runs
/// build_adjacency. mesh.triangles, refs and the classes of existing vertices are unchanged:
/// the faces are the cavity's boundary, kept exactly. Returns the new tet ids. O(n log n) in
/// the fill's size.
/// \pre fill.filled and mesh.num_vertices() == fill.first_new_vertex.
std::vector<int> commit_cavity(TetMesh& mesh, const CavityFill& fill);

/// Counts of fills by stage, for reports and benchmarks.
struct FillStatistics
{
    std::array<long, kNumFillStages> by_stage{};
    long grown = 0;  ///< fills that needed stage 5
    void add(const CavityFill& fill);
    std::string format() const;
};

}  // namespace hdimesh::volume
