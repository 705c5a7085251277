#include "surface/remesh.h"

#include <algorithm>
#include <cassert>
#include <cstdlib>
#include <utility>

#include "common/errors.h"
#include "common/messages.h"
#include "surface/detail/local_ops_geometry.h"
#include "surface/detail/remesh_run.h"
#include "surface/hdi_projection.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface
{
namespace detail
{

RemeshRun::RemeshRun(SurfaceMesh& mesh, const RemeshOptions& options, const Projector& model,
                     const SurfaceHooks& hooks)
    : mesh(mesh), options(options), ctx(mesh, model, hooks, options.limits)
{
    ctx.limits.max_model_distance = options.max_model_distance;
    ctx.limits.min_angle_across_crease_deg = options.min_angle_across_crease_deg;
}

std::size_t RemeshRun::count_vertices() const
{
    std::size_t n = 0;
    const int vertex_count = static_cast<int>(mesh.n_vertices());
    for (int index = 0; index < vertex_count; ++index)
        if (!mesh.status(VertexHandle(index)).deleted()) ++n;
    return n;
}

// The edges of v's faces, in circulation order (shared ones twice): the flips that settle a
// vertex after a change are tried on them, and a flip changes the faces, so the list is
// taken before.
std::vector<EdgeHandle> RemeshRun::edges_of_faces_at(VertexHandle v) const
{
    std::vector<EdgeHandle> edges;
    for (auto f : mesh.vf_range(v))
        for (auto e : mesh.fe_range(f)) edges.push_back(e);
    return edges;
}

void RemeshRun::set_size(VertexHandle v)
{
    const Vec3d& p = mesh.point(v);
    mesh.property(ctx.props.vertex_size, v) =
        options.size_near ? options.size_near(p, ctx.model_face(v)) : options.size(p);
}

void RemeshRun::update_sizes()
{
    const int vertex_count = static_cast<int>(mesh.n_vertices());
    for (int index = 0; index < vertex_count; ++index)
        if (!mesh.status(VertexHandle(index)).deleted()) set_size(VertexHandle(index));
}

double RemeshRun::edge_size(EdgeHandle e) const
{
    const auto h = mesh.halfedge_handle(e, 0);
    return 0.5 * (mesh.property(ctx.props.vertex_size, mesh.from_vertex_handle(h)) +
                  mesh.property(ctx.props.vertex_size, mesh.to_vertex_handle(h)));
}

// Smooth vertices go first; a curve vertex only along its curve (try_collapse checks).
int RemeshRun::removal_rank(VertexHandle v) const
{
    switch (ctx.vertex_class(v))
    {
        case VertexClass::Smooth: return 0;
        case VertexClass::Ridge:
        case VertexClass::Boundary: return 1;
        case VertexClass::Corner: return 2;
    }
    return 2;
}

void split_long_edges(RemeshRun& run)
{
    SurfaceMesh& mesh = run.mesh;
    for (int pass = 0; pass < 10; ++pass)
    {
        std::vector<std::pair<double, EdgeHandle>> candidates;
        const int edge_count = static_cast<int>(mesh.n_edges());
        for (int index = 0; index < edge_count; ++index)
        {
            const EdgeHandle e(index);
            if (mesh.status(e).deleted()) continue;
            const double ratio = mesh.calc_edge_length(e) / run.edge_size(e);
            if (ratio > kTooLong) candidates.emplace_back(ratio, e);
        }
        if (candidates.empty()) return;
        std::sort(candidates.begin(), candidates.end(),
                  [](const auto& a, const auto& b) { return a.first > b.first; });
        std::size_t done = 0;
        for (const auto& [ratio, e] : candidates)
        {
            if (mesh.status(e).deleted() || mesh.calc_edge_length(e) <= kTooLong * run.edge_size(e))
                continue;
            const OpResult r = try_split(run.ctx, e);
            if (!r.done()) continue;
            run.set_size(r.vertex);
            ++done;
        }
        run.report.splits += done;
        if (done == 0) return;
    }
}

// Passes of collapses of the edges too short for their size, until one collapses nothing.
// Nothing moves between passes, so an edge refused in one pass is refused again in the next
// unless a later collapse touched an end's ring (a collapse's outcome reads the rings of its
// ends only): such an edge is not tried again. Not with a caller's allow_collapse hook, whose
// answer may read more. (The later passes were mostly such refusals: a neighbour would end
// too far.) Likewise an edge found long enough stays so until a collapse changes an end (its
// length and size read its ends only): almost every edge a later pass looks at is not short.
void collapse_short_edges(RemeshRun& run)
{
    SurfaceMesh& mesh = run.mesh;
    const bool skip_unchanged = !run.ctx.hooks.allow_collapse;
    // Per vertex: the count of collapses when a collapse last changed its ring; per edge: the
    // count when it was last refused, or last found not short (-1: not in this call).
    std::vector<long> ring_changed_at(skip_unchanged ? mesh.n_vertices() : 0, -1);
    std::vector<long> refused_at(skip_unchanged ? mesh.n_edges() : 0, -1);
    std::vector<long> long_enough_at(skip_unchanged ? mesh.n_edges() : 0, -1);
    long collapses = 0;
    for (int pass = 0; pass < 5; ++pass)
    {
        std::size_t done = 0;
        // (A collapse adds no edge: the edges in handle order, those deleted when reached
        // skipped, are the pass's edges without a list of them. By index: OpenMesh's
        // skipping iterator asks the virtual n_edges() at each step.)
        const int edge_count = static_cast<int>(mesh.n_edges());
        for (int index = 0; index < edge_count; ++index)
        {
            const EdgeHandle e(index);
            if (mesh.status(e).deleted()) continue;
            HalfedgeHandle hs[2] = {mesh.halfedge_handle(e, 0), mesh.halfedge_handle(e, 1)};
            if (skip_unchanged && std::max(refused_at[e.idx()], long_enough_at[e.idx()]) >= 0)
            {
                const long ends_changed_at =
                    std::max(ring_changed_at[mesh.from_vertex_handle(hs[0]).idx()],
                             ring_changed_at[mesh.to_vertex_handle(hs[0]).idx()]);
                if (long_enough_at[e.idx()] >= 0 && long_enough_at[e.idx()] >= ends_changed_at)
                {
                    assert(mesh.calc_edge_length(e) >= kTooShort * run.edge_size(e));
                    continue;
                }
                if (refused_at[e.idx()] >= 0 && refused_at[e.idx()] >= ends_changed_at)
                {
                    // (The layers read the two ends' stars only; a layer reading farther would
                    // make this skip wrong, which a debug build catches here.)
                    assert(collapse_status(run.ctx, hs[0], kTooLong * run.edge_size(e)) !=
                               OpStatus::Done &&
                           collapse_status(run.ctx, hs[1], kTooLong * run.edge_size(e)) !=
                               OpStatus::Done);
                    continue;
                }
            }
            const double h = run.edge_size(e);
            if (mesh.calc_edge_length(e) >= kTooShort * h)
            {
                if (skip_unchanged) long_enough_at[e.idx()] = collapses;
                continue;
            }
            if (run.removal_rank(mesh.from_vertex_handle(hs[1])) <
                run.removal_rank(mesh.from_vertex_handle(hs[0])))
                std::swap(hs[0], hs[1]);
            bool collapsed = false;
            for (const HalfedgeHandle hh : hs)
            {
                const OpResult r = try_collapse(run.ctx, hh, kTooLong * h);
                if (r.done())
                {
                    ++done;
                    collapsed = true;
                    if (skip_unchanged)
                    {
                        ++collapses;
                        ring_changed_at[r.vertex.idx()] = collapses;
                        for (auto w : mesh.vv_range(r.vertex)) ring_changed_at[w.idx()] = collapses;
                    }
                    break;
                }
            }
            if (skip_unchanged && !collapsed) refused_at[e.idx()] = collapses;
        }
        run.report.collapses += done;
        if (done == 0) return;
    }
}

// Flips toward `goal` over the live edges; with `only_at`, of the edges with an end it marks.
std::size_t flip_edges(RemeshRun& run, FlipGoal goal, const std::vector<char>* only_at)
{
    SurfaceMesh& mesh = run.mesh;
    // Valence flips: on a settled mesh most edges would not lower the valence deviation.
    // A valence table kept up to date over the pass refuses them without circulating four
    // rings per edge; try_flip repeats the test on the others and decides.
    // Per vertex its valence minus its ideal one (4 on the boundary, 6 inside), from one pass
    // over the edges (cheaper than a circulation and a boundary test per vertex).
    std::vector<int> valence_excess;
    if (goal == FlipGoal::Valence)
    {
        valence_excess.assign(mesh.n_vertices(), -6);
        std::vector<char> on_boundary(mesh.n_vertices(), 0);
        const int edge_count = static_cast<int>(mesh.n_edges());
        for (int index = 0; index < edge_count; ++index)
        {
            const EdgeHandle e(index);
            if (mesh.status(e).deleted()) continue;
            const auto h = mesh.halfedge_handle(e, 0);
            const VertexHandle a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
            ++valence_excess[a.idx()];
            ++valence_excess[b.idx()];
            if (mesh.is_boundary(e)) on_boundary[a.idx()] = on_boundary[b.idx()] = 1;
        }
        for (std::size_t i = 0; i < on_boundary.size(); ++i)
            if (on_boundary[i]) valence_excess[i] += 2;
    }
    auto deviation = [&](VertexHandle v, int delta) {
        return std::abs(valence_excess[v.idx()] + delta);
    };
    std::size_t done = 0;
    // (A flip adds no edge; one deleted when reached is skipped. The passes walk the
    // elements by index: OpenMesh's skipping iterator asks the virtual n_edges() at each
    // step.)
    const int edge_count = static_cast<int>(mesh.n_edges());
    for (int index = 0; index < edge_count; ++index)
    {
        const EdgeHandle e(index);
        if (mesh.status(e).deleted()) continue;
        if (only_at && !has_marked_end(mesh, e, *only_at)) continue;
        VertexHandle a, b, c, d;
        if (goal == FlipGoal::Valence)
        {
            if (mesh.is_boundary(e)) continue;  // a feature: never flipped
            const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
            a = mesh.from_vertex_handle(h0);
            b = mesh.to_vertex_handle(h0);
            c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h0));
            d = mesh.to_vertex_handle(mesh.next_halfedge_handle(h1));
            if (deviation(a, -1) + deviation(b, -1) + deviation(c, 1) + deviation(d, 1) >=
                deviation(a, 0) + deviation(b, 0) + deviation(c, 0) + deviation(d, 0))
                continue;
        }
        if (!try_flip(run.ctx, e, goal).done()) continue;
        ++done;
        if (goal == FlipGoal::Valence)
        {
            --valence_excess[a.idx()];
            --valence_excess[b.idx()];
            ++valence_excess[c.idx()];
            ++valence_excess[d.idx()];
        }
    }
    run.report.flips += done;
    return done;
}

// Shifts of the live vertices (smart: never lowering the worst Qe of a ball); with `only`,
// of the vertices it marks.
void shift_vertices(RemeshRun& run, bool smart, const std::vector<char>* only)
{
    SurfaceMesh& mesh = run.mesh;
    ShiftOptions shift;
    shift.smart = smart;
    const int vertex_count = static_cast<int>(mesh.n_vertices());  // (a shift adds no vertex)
    for (int index = 0; index < vertex_count; ++index)
    {
        const VertexHandle v(index);
        if (mesh.status(v).deleted()) continue;
        if (only && !is_marked(v, *only)) continue;
        if (shift_vertex(run.ctx, v, shift).done())
        {
            run.set_size(v);
            ++run.report.shifts;
        }
    }
}

void run_iterations(RemeshRun& run)
{
    for (int it = 0; it < run.options.iterations; ++it)
    {
        split_long_edges(run);
        collapse_short_edges(run);
        flip_edges(run, FlipGoal::Valence);
        shift_vertices(run, false);
        ++run.report.iterations;
        if (run.options.verbosity > 0)
            hdimesh::emit(run.options.messages, hdimesh::MessageKind::Trace,
                          "remesh: iteration %d: %zu vertices, %zu splits, %zu collapses, %zu "
                          "flips, %zu shifts\n",
                          it + 1, run.count_vertices(), run.report.splits, run.report.collapses,
                          run.report.flips, run.report.shifts);
    }
}

}  // namespace detail

RemeshReport remesh(SurfaceMesh& mesh, const RemeshOptions& options, const Projector& model,
                    const SurfaceHooks& hooks)
{
    if (!options.size) throw InputError("remesh: no size function given");
    detail::RemeshRun run(mesh, options, model, hooks);
    run.update_sizes();
    detail::run_iterations(run);
    if (options.verbosity > 0)
        hdimesh::emit(options.messages, hdimesh::MessageKind::Trace,
                      "remesh: %d iterations (%.2f s, cpu %.3f s): %zu vertices\n",
                      run.report.iterations, run.clock.wall_seconds(), run.clock.cpu_seconds(),
                      run.count_vertices());
    mesh.garbage_collection();
    return run.report;
}

RemeshReport remesh(SurfaceMesh& mesh, const RemeshOptions& options, const hdi::HdiSurface& model,
                    const SurfaceHooks& hooks)
{
    const HdiProjector projector(model);
    return remesh(mesh, options, projector, hooks);
}

}  // namespace hdimesh::surface
