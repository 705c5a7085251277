#pragma once
// The optimization driver (paper §3.7, §5): work lists of bad tets, each attacked by edge
// removal, multi-face removal (the 2-3 flip and larger sandwiches), smoothing of its free
// vertices and, when it is still bad, the collapse of one of them onto another of its vertices
// (kept when no new tet is worse than the ball's old worst); too-short edges collapsed first in
// the final optimization. Later sweeps revisit only the tets an operator created or reshaped
// and the stuck tets with a vertex in one of them, never the whole mesh. The boundary
// (mesh.triangles and every non-interior vertex) never changes. Deterministic: fixed traversal
// orders only.

#include <string>
#include <vector>

#include "common/messages.h"
#include "common/parallel.h"
#include "common/size_field.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

struct OptimizeOptions
{
    bool swap = true;      ///< edge removal / face removal (--noswap turns off)
    bool move = true;      ///< nodal shifting (--nomove)
    bool collapse = true;  ///< too-short edge collapse (derefinement)
    bool split =
        true;  ///< optimize_mesh's last stage: interior edge splits (volume/optimize/edge_split.h)
    double bad_quality = 0.2;           ///< elements below are "bad" (the paper's threshold)
    double target_quality = 0.5;        ///< optimize_mesh works on every tet below this
    double collapse_min_quality = 0.3;  ///< a collapse may not create a tet worse than this
    int max_sweeps = 10;
    /// The sweeps skip tets with a required vertex: a block's frozen faces (volume/mesh/
    /// blocks.h) are inside the next round's blocks, where those tets are worked; here they
    /// would stay stuck and be retried sweep after sweep.
    bool leave_required_vertex_balls = false;
    /// Surface vertices of flat parts of the boundary may also collapse along it and slide in
    /// its plane (CollapseOptions::on_flat_boundary, SmoothOptions::in_flat_boundary): in a
    /// metric, where no surface pass runs, the only coarsening and shaping of the boundary.
    bool flat_boundary_moves = false;
    int verbosity = 0;  ///< 2: a per-sweep table (operator, attempts, successes, min Qe, %
                        ///< Qe>=0.5, time) to `messages`, as Report lines
    MessageSink messages;
    /// The whole-mesh quality sweeps run on these threads (null: one); the result does not
    /// depend on them.
    Workers* workers = nullptr;
};

struct OperatorStats
{
    std::string name;
    long attempts = 0, successes = 0;
    double seconds = 0;
};

struct OptimizeReport
{
    std::vector<OperatorStats> operators;  ///< totals over all sweeps
    double min_quality_before = 0, min_quality_after = 0;
    int sweeps = 0;
};

/// After a refinement pass: remove elements below options.bad_quality (swaps + smoothing
/// around them only). Leaves the mesh compact with adjacency.
OptimizeReport improve_bad_elements(TetMesh& mesh, const SizeField& field,
                                    const OptimizeOptions& options = {});

/// The final optimization: collapse too-short edges, then swap/smooth until no operator
/// improves the worst element (cap). Leaves the mesh compact with adjacency.
/// In detail, up to three rounds of: collapse too-short edges (shortest L/hth first; passes
/// until none collapses), move the free ends of those left toward their target lengths,
/// collapse again, then sweep the tets below target_quality (worst first) with edge removal,
/// multi-face removal and smoothing (at most max_sweeps sweeps). A round that changes no edge ends
/// it. Last, each tet still below target_quality with no free vertex gets an interior edge split
/// (options.split, volume/optimize/edge_split.h).
OptimizeReport optimize_mesh(TetMesh& mesh, const SizeField& field,
                             const OptimizeOptions& options = {});

}  // namespace hdimesh::volume
