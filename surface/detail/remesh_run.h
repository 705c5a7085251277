#pragma once
// What every stage of a remesh shares: the mesh, the operators' context (its hooks), the size
// each vertex is given and the report; and the loop's own steps, which later stages run again
// on part of the mesh (the polish's flips and shifts).

#include <cstddef>
#include <vector>

#include "common/stage_timer.h"
#include "surface/local_ops.h"
#include "surface/remesh.h"

namespace hdimesh::surface::detail
{

/// The loop splits an edge longer than this times its size and collapses one shorter than
/// kTooShort times it: Qt = min(h/L, L/h) ≥ 0.75 where it converges.
inline constexpr double kTooLong = 4.0 / 3.0;
inline constexpr double kTooShort = 4.0 / 5.0;

class RemeshRun
{
public:
    /// `hooks` as the operators see them (a stage may wrap the caller's, see ChangeLog).
    RemeshRun(SurfaceMesh& mesh, const RemeshOptions& options, const Projector& model,
              const SurfaceHooks& hooks);
    // Not copyable: the stages keep references to it.
    RemeshRun(const RemeshRun&) = delete;
    RemeshRun& operator=(const RemeshRun&) = delete;

    SurfaceMesh& mesh;
    const RemeshOptions& options;
    OperatorContext ctx;
    RemeshReport report;
    Stopwatch clock;  // since the start of the run (verbose lines)

    /// v's size property from the size function at its point.
    void set_size(VertexHandle v);
    /// set_size of every live vertex.
    void update_sizes();
    /// The size an edge is judged against: the mean of its ends' sizes.
    double edge_size(EdgeHandle e) const;
    std::size_t count_vertices() const;
    /// The edges of v's faces, in circulation order (shared ones twice): the flips that settle a
    /// vertex after a change are tried on them, and a flip changes the faces, so the list is
    /// taken before.
    std::vector<EdgeHandle> edges_of_faces_at(VertexHandle v) const;
    /// Which end of a short edge goes: smooth vertices first; a curve vertex only along its
    /// curve (try_collapse checks).
    int removal_rank(VertexHandle v) const;
};

/// options.iterations rounds of split, collapse, valence flips and shifts.
void run_iterations(RemeshRun& run);
void split_long_edges(RemeshRun& run);
void collapse_short_edges(RemeshRun& run);
/// Flips toward `goal` over the live edges; with `only_at`, of the edges with an end it marks.
std::size_t flip_edges(RemeshRun& run, FlipGoal goal, const std::vector<char>* only_at = nullptr);
/// Shifts of the live vertices (smart: never lowering the worst Qe of a ball); with `only`, of
/// the vertices it marks.
void shift_vertices(RemeshRun& run, bool smart, const std::vector<char>* only = nullptr);

/// Whether v is marked in `marks`, per vertex by handle index (a vertex added after they were
/// made is not).
inline bool is_marked(VertexHandle v, const std::vector<char>& marks)
{
    return static_cast<std::size_t>(v.idx()) < marks.size() && marks[v.idx()];
}

/// Whether an end of e is marked in `marks` (is_marked).
inline bool has_marked_end(const SurfaceMesh& mesh, EdgeHandle e, const std::vector<char>& marks)
{
    const auto h = mesh.halfedge_handle(e, 0);
    return is_marked(mesh.from_vertex_handle(h), marks) ||
           is_marked(mesh.to_vertex_handle(h), marks);
}

}  // namespace hdimesh::surface::detail
