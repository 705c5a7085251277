#pragma once
// What the cavity cascade (volume/fill/cavity.h) and its stage 4, the advancing front
// (volume/fill/advancing_front.h), share: their options and the fill they compute. Its own
// header so that the dependency runs one way: cavity -> advancing_front -> fill_common.

#include <cstdint>
#include <string>
#include <vector>

#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

struct AdvancingFrontOptions
{
    /// Quality floors, relaxed in this order as a face keeps failing; the last is "positive".
    std::vector<double> quality_floors{0.3, 0.1, 0.02, 0.0};
    int max_retreat_rounds = 10;
    /// Leftover groups with at most this many points go to stages 1-3.
    int max_leftover_points = 32;
    /// No new point closer than this fraction of the local size to a front vertex.
    double min_point_distance = 0.65;
    /// > 0: face attempts at most, over all retreat rounds (else enough for every tet the
    /// sizes ask for, many times over). A caller that may refuse (a mirrored surface operation)
    /// caps it: a cavity whose shortest face edge is tiny would otherwise get a huge budget.
    long max_attempts = 0;
};

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

}  // namespace hdimesh::volume
