#include "volume/optimize/optimize.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "common/stage_timer.h"
#include "volume/mesh/tet_tables.h"
#include "volume/mesh/tet_topology.h"
#include "volume/optimize/collapse.h"
#include "volume/optimize/edge_removal.h"
#include "volume/optimize/edge_split.h"
#include "volume/optimize/face_removal.h"
#include "volume/optimize/smooth.h"

namespace hdimesh::volume
{

namespace
{

enum OperatorIndex
{
    kEdgeRemoval = 0,
    kFaceRemoval = 1,
    kSmoothing = 2,
    kCollapse = 3,
    kSizeSmoothing = 4,
    kEdgeSplit = 5,
    kNumOperators = 6
};

const char* const kOperatorNames[kNumOperators] = {
    "edge removal", "multi-face removal", "smoothing", "collapse", "size smoothing", "edge split"};

struct QualitySummary
{
    double min = 0;
    double fraction_good = 0;  // Qe >= 0.5
};

QualitySummary summarize_quality(const TetMesh& mesh, const OperatorContext& context,
                                 Workers* workers)
{
    // the qualities not cached yet on the threads; the summary then reads the cache in order
    context.fill_quality_cache(mesh, workers);
    QualitySummary s;
    s.min = std::numeric_limits<double>::infinity();
    long live = 0, good = 0;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        const double q = context.quality(mesh, t);
        s.min = std::min(s.min, q);
        ++live;
        good += (q >= 0.5);
    }
    if (live == 0) s.min = 0;
    s.fraction_good = live > 0 ? static_cast<double>(good) / static_cast<double>(live) : 1.0;
    return s;
}

/// One optimization run over a mesh: the context, the counters, the work lists.
class Optimizer
{
public:
    Optimizer(TetMesh& mesh, const SizeField& field, const OptimizeOptions& options)
        : mesh_(mesh), options_(options)
    {
        if (!mesh_.has_adjacency()) mesh_.build_adjacency();
        context_ = OperatorContext(mesh_, &field);
        context_.enable_caches();
        context_.enable_change_stamps(mesh_);
        if (options_.leave_required_vertex_balls)
        {
            at_required_.assign(mesh_.num_vertices(), 0);
            for (int v : mesh_.required_vertices) at_required_[v] = 1;
        }
        for (int k = 0; k < kNumOperators; ++k) report_.operators.push_back({kOperatorNames[k]});
        report_.min_quality_before = summarize_quality(mesh_, context_, options_.workers).min;
        if (options_.verbosity >= 2)
            emit(options_.messages, MessageKind::Report, "%-6s %-20s %10s %10s %9s %9s %9s\n",
                 "sweep", "operator", "attempts", "successes", "min Qe", "%Qe>=0.5", "time(s)");
    }

    /// Collapses too-short edges with a free endpoint, shortest (relative to the size) first,
    /// pass after pass until one collapses nothing. Returns the number of collapses.
    /// `from`: the tets that hold every too-short edge (all live tets when null).
    long collapse_short_edges(const std::vector<int>* from = nullptr)
    {
        left_short_.clear();
        if (!options_.collapse)
        {
            left_short_ = (from ? short_edges(*from) : short_edges(all_live_tets(), true));
            return 0;
        }
        CollapseOptions collapse_options;
        collapse_options.min_quality = options_.collapse_min_quality;
        collapse_options.on_flat_boundary = options_.flat_boundary_moves;
        long total = 0;
        // the first pass sees every short edge; later ones only those of tets changed since,
        // as nothing else can have become collapsible
        std::vector<ShortEdge> candidates =
            (from ? short_edges(*from) : short_edges(all_live_tets(), true));
        int pass = 0;
        for (; pass < options_.max_sweeps && !candidates.empty(); ++pass)
        {
            const SweepCounters before = counters();
            const WallStopwatch stopwatch;
            context_.touched.clear();
            long collapsed = 0;
            for (const auto& candidate : candidates)
            {
                const int u = candidate.u, v = candidate.v;
                if (context_.vertex_tet[u] < 0 || context_.vertex_tet[v] < 0) continue;
                const Vec3& pu = mesh_.points[u];
                const Vec3& pv = mesh_.points[v];  // may have moved since the scan
                if (!measure_edge(*context_.field, pu, pv).too_short()) continue;
                // refused before, and no tet through either end changed since: refused again
                const std::uint64_t key = (static_cast<std::uint64_t>(u) << 32) | v;
                const auto memo = refused_collapses_.find(key);
                if (memo != refused_collapses_.end() && context_.vertex_changed(u) < memo->second &&
                    context_.vertex_changed(v) < memo->second)
                {
                    left_short_.push_back(candidate);
                    continue;
                }
                bool done = false;
                if (collapsible(u)) done = attempt_collapse(u, v, collapse_options);
                if (!done && collapsible(v)) done = attempt_collapse(v, u, collapse_options);
                collapsed += done;
                if (!done)
                {
                    left_short_.push_back(candidate);
                    refused_collapses_[key] = context_.changes() + 1;
                }
            }
            report_.operators[kCollapse].seconds += stopwatch.seconds();
            print_sweep("collapse", before);
            total += collapsed;
            if (collapsed == 0) break;
            // each live touched tet once (short_edges sorts what it finds: order is free)
            std::vector<int> changed;
            tet_mark_.resize(mesh_.num_tet_slots(), 0);
            for (int t : context_.touched)
                if (!mesh_.is_dead(t) && !tet_mark_[t]) tet_mark_[t] = 1, changed.push_back(t);
            for (int t : changed) tet_mark_[t] = 0;
            candidates = short_edges(changed);
        }
        // Every short edge left was a candidate that did not collapse, or is still pending: an
        // edge a collapse makes, or reshapes by moving its survivor, lies in a changed tet.
        if (pass == options_.max_sweeps)
            left_short_.insert(left_short_.end(), candidates.begin(), candidates.end());
        keep_short_edges_left();
        return total;
    }

    /// left_short_ becomes the too-short edges of the mesh, as short_edges(all_live_tets())
    /// would list them: drops repeats, edges gone with a collapsed vertex and edges a moved
    /// survivor lengthened, measures the others again and re-sorts.
    void keep_short_edges_left()
    {
        std::vector<ShortEdge> kept;
        kept.reserve(left_short_.size());
        std::sort(left_short_.begin(), left_short_.end(),
                  [](const ShortEdge& a, const ShortEdge& b) {
                      return a.u != b.u ? a.u < b.u : a.v < b.v;
                  });
        for (std::size_t k = 0; k < left_short_.size(); ++k)
        {
            const ShortEdge& e = left_short_[k];
            if (k > 0 && left_short_[k - 1].u == e.u && left_short_[k - 1].v == e.v) continue;
            if (context_.vertex_tet[e.u] < 0 || context_.vertex_tet[e.v] < 0) continue;
            context_.ball(mesh_, e.u, ball_);
            const bool is_edge = std::any_of(ball_.begin(), ball_.end(), [&](int t) {
                const auto& tv = mesh_.tets[t];
                return std::find(tv.begin(), tv.end(), e.v) != tv.end();
            });
            if (!is_edge) continue;
            const Vec3& pu = mesh_.points[e.u];
            const Vec3& pv = mesh_.points[e.v];
            const EdgeInField edge = measure_edge(*context_.field, pu, pv);
            if (edge.too_short()) kept.push_back({edge.in_field(), e.u, e.v});
        }
        std::sort(kept.begin(), kept.end());
        left_short_ = std::move(kept);
    }

    /// The tets around the ends of the short edges left: they hold every short edge while only
    /// those ends move.
    std::vector<int> tets_around_short_edges()
    {
        std::vector<int> tets;
        for (const ShortEdge& e : left_short_)
            for (int w : {e.u, e.v})
            {
                context_.ball(mesh_, w, ball_);
                tets.insert(tets.end(), ball_.begin(), ball_.end());
            }
        std::sort(tets.begin(), tets.end());
        tets.erase(std::unique(tets.begin(), tets.end()), tets.end());
        return tets;
    }

    /// Moves the free endpoints of the too-short edges that collapses could not remove toward
    /// their target lengths. Returns the number of moves.
    long equalize_short_edges()
    {
        if (!options_.move) return 0;
        const SweepCounters before = counters();
        const WallStopwatch stopwatch;
        SizeSmoothOptions size_options;
        size_options.min_quality = options_.collapse_min_quality;
        long moved = 0;
        for (const auto& candidate : left_short_)
            for (int w : {candidate.u, candidate.v})
            {
                if (!context_.constraints.is_free_vertex(w) || context_.vertex_tet[w] < 0) continue;
                ++report_.operators[kSizeSmoothing].attempts;
                const bool done = equalize_edge_sizes(mesh_, context_, w, size_options).moved;
                report_.operators[kSizeSmoothing].successes += done;
                moved += done;
            }
        report_.operators[kSizeSmoothing].seconds += stopwatch.seconds();
        print_sweep("sizes", before);
        return moved;
    }

    /// Sweeps over the tets below `threshold`: first all of them, then the ones still bad or
    /// created by the previous sweep, until a sweep changes nothing.
    void improve_below(double threshold)
    {
        std::vector<int> work;
        for (int t = 0; t < mesh_.num_tet_slots(); ++t)
            if (!mesh_.is_dead(t) && quality(t) < threshold && !left(t)) work.push_back(t);
        order_worst_first(work);
        for (int sweep = 0; sweep < options_.max_sweeps && !work.empty(); ++sweep)
        {
            const SweepCounters before = counters();
            context_.touched.clear();
            std::vector<int> still_bad;
            long successes = 0;
            for (int t : work)
            {
                if (mesh_.is_dead(t) || quality(t) >= threshold) continue;
                const int result = improve_tet(t, threshold);
                successes += (result != kNothing);
                if (result != kReplaced && quality(t) < threshold) still_bad.push_back(t);
            }
            ++report_.sweeps;
            print_sweep("sweep " + std::to_string(report_.sweeps), before);
            if (successes == 0) break;
            // next: the new or reshaped tets that are bad, and the tets still bad that have
            // a vertex in a changed tet — every operator tried on a tet only involves tets
            // through its vertices, so a stuck tet whose vertices saw no change stays stuck
            // (a per-vertex mark, reset after use, instead of a sorted list: linear)
            changed_vertex_.resize(mesh_.num_vertices(), 0);
            work.clear();
            for (int t : context_.touched)
            {
                if (mesh_.is_dead(t)) continue;
                for (int v : mesh_.tets[t]) changed_vertex_[v] = 1;
                if (quality(t) < threshold && !left(t)) work.push_back(t);
            }
            for (int t : still_bad)
            {
                if (mesh_.is_dead(t)) continue;
                const auto& tv = mesh_.tets[t];
                if (std::any_of(tv.begin(), tv.end(),
                                [&](int v) { return changed_vertex_[v] != 0; }))
                    work.push_back(t);
            }
            for (int t : context_.touched)
                if (!mesh_.is_dead(t))
                    for (int v : mesh_.tets[t]) changed_vertex_[v] = 0;
            order_worst_first(work);
        }
    }

    /// Splits an interior edge of each tet below `threshold` none of whose vertices may move
    /// (smoothing cannot reach it, and the swaps already failed on it), worst first. No sweep
    /// follows: the split placed its vertex already, and smoothing it again for Qe alone
    /// trades dihedral angles away. Returns the number of splits.
    long split_locked_tets(double threshold)
    {
        if (!options_.split) return 0;
        const SweepCounters before = counters();
        const WallStopwatch stopwatch;
        auto locked = [&](int t) {
            const auto& tv = mesh_.tets[t];
            return std::none_of(tv.begin(), tv.end(),
                                [&](int v) { return context_.constraints.is_free_vertex(v); });
        };
        std::vector<int> work;
        for (int t = 0; t < mesh_.num_tet_slots(); ++t)
            if (!mesh_.is_dead(t) && quality(t) < threshold && locked(t)) work.push_back(t);
        order_worst_first(work);
        long splits = 0;
        for (int t : work)
        {
            if (mesh_.is_dead(t) || quality(t) >= threshold || !locked(t)) continue;
            ++report_.operators[kEdgeSplit].attempts;
            const bool done = split_interior_edge(mesh_, context_, t).split;
            report_.operators[kEdgeSplit].successes += done;
            splits += done;
        }
        report_.operators[kEdgeSplit].seconds += stopwatch.seconds();
        print_sweep("split", before);
        return splits;
    }

    /// Sorts a work list worst first by quality band (kQualityBands per unit of Qe), by id
    /// inside a band, each tet once: the worst elements get the first pick of the operators,
    /// and inside a band the walk follows memory (ids follow space after adapt's renumbering)
    /// instead of jumping across a mesh far larger than the caches for every tet.
    void order_worst_first(std::vector<int>& work) const
    {
        std::sort(work.begin(), work.end());
        work.erase(std::unique(work.begin(), work.end()), work.end());
        std::vector<std::pair<long, int>> keyed;
        keyed.reserve(work.size());
        for (int t : work) keyed.push_back({quality_band(quality(t)), t});
        std::sort(keyed.begin(), keyed.end());
        for (std::size_t k = 0; k < keyed.size(); ++k) work[k] = keyed[k].second;
    }

    static constexpr double kQualityBands = 20;  // bands 0.05 wide
    static long quality_band(double q) { return static_cast<long>(std::floor(q * kQualityBands)); }

    OptimizeReport finish()
    {
        // measured before compact() renumbers the slots the cache is keyed by
        report_.min_quality_after = summarize_quality(mesh_, context_, options_.workers).min;
        mesh_.compact();
        if (options_.verbosity >= 2)
            emit(options_.messages, MessageKind::Report, "min Qe %.4f -> %.4f after %d sweeps\n",
                 report_.min_quality_before, report_.min_quality_after, report_.sweeps);
        return report_;
    }

private:
    enum TetOutcome
    {
        kNothing,   // no operator succeeded
        kReplaced,  // the tet was removed by a swap (its slot may hold a new tet)
        kMoved      // a vertex of the tet moved
    };

    using SweepCounters = std::array<std::array<long, 2>, kNumOperators>;

    double quality(int t) const { return context_.quality(mesh_, t); }

    /// A tet the sweeps leave alone (OptimizeOptions::leave_required_vertex_balls).
    bool left(int t) const
    {
        if (at_required_.empty()) return false;
        for (int v : mesh_.tets[t])
            if (v < static_cast<int>(at_required_.size()) && at_required_[v]) return true;
        return false;
    }

    SweepCounters counters() const
    {
        SweepCounters c;
        for (int k = 0; k < kNumOperators; ++k)
            c[k] = {report_.operators[k].attempts, report_.operators[k].successes};
        return c;
    }

    /// A too-short edge, ordered shortest first by band of L/hth (kRatioBands per unit), then
    /// by ids: the shortest go first, and inside a band the walk follows memory (see
    /// order_worst_first).
    struct ShortEdge
    {
        static constexpr double kRatioBands = 16;
        long band;  // floor(L / hth * kRatioBands)
        int u, v;   // u < v
        ShortEdge(double ratio, int u_, int v_)
            : band(static_cast<long>(std::floor(ratio * kRatioBands))), u(u_), v(v_)
        {
        }
        bool operator<(const ShortEdge& o) const
        {
            return band != o.band ? band < o.band : (u != o.u ? u < o.u : v < o.v);
        }
    };

    std::vector<int> all_live_tets() const
    {
        std::vector<int> result;
        result.reserve(mesh_.num_tet_slots());
        for (int t = 0; t < mesh_.num_tet_slots(); ++t)
            if (!mesh_.is_dead(t)) result.push_back(t);
        return result;
    }

    /// The too-short edges with a free endpoint among the edges of `tets` (live), sorted by
    /// L/hth then ids, each once. An edge is seen from every tet around it (about five): the
    /// pairs are deduplicated before the size field is evaluated, once per edge.
    /// The too-short edges of `tets` (every live tet when whole_mesh), sorted.
    std::vector<ShortEdge> short_edges(const std::vector<int>& tets, bool whole_mesh = false) const
    {
        // bucket the upper ends by the lower end (a counting sort, linear), then sort and
        // deduplicate each small bucket: the edges come out in (u, v) order, each once
        const int nv = mesh_.num_vertices();
        std::vector<int> bucket_start(nv + 1, 0);
        // over every live tet, the buckets shrink about fourfold (as refinement's EdgeTable)
        auto listed = [&](int t, int e) { return !whole_mesh || mesh_.lists_edge(t, e); };
        auto for_each_candidate = [&](auto&& visit) {
            for (int t : tets)
                for (int e = 0; e < 6; ++e)
                {
                    const auto& ev = tet::kEdgeVertices[e];
                    if (!listed(t, e)) continue;
                    int u = mesh_.tets[t][ev[0]], v = mesh_.tets[t][ev[1]];
                    if (!collapsible(u) && !collapsible(v)) continue;
                    if (u > v) std::swap(u, v);
                    visit(u, v);
                }
        };
        for_each_candidate([&](int u, int) { ++bucket_start[u + 1]; });
        for (int u = 0; u < nv; ++u) bucket_start[u + 1] += bucket_start[u];
        std::vector<int> upper(bucket_start[nv]);
        std::vector<int> fill(bucket_start.begin(), bucket_start.end() - 1);
        for_each_candidate([&](int u, int v) { upper[fill[u]++] = v; });

        std::vector<ShortEdge> result;
        for (int u = 0; u < nv; ++u)
        {
            const auto begin = upper.begin() + bucket_start[u];
            auto end = upper.begin() + bucket_start[u + 1];
            if (begin == end) continue;
            for (auto it = begin + 1; it != end; ++it)  // rows are short: insertion sort
            {
                const int x = *it;
                auto j = it;
                for (; j != begin && *(j - 1) > x; --j) *j = *(j - 1);
                *j = x;
            }
            end = std::unique(begin, end);
            const Vec3& pu = mesh_.points[u];
            for (auto it = begin; it != end; ++it)
            {
                const int v = *it;
                const Vec3& pv = mesh_.points[v];
                const EdgeInField edge = measure_edge(*context_.field, pu, pv);
                if (edge.too_short()) result.push_back({edge.in_field(), u, v});
            }
        }
        std::sort(result.begin(), result.end());
        return result;
    }

    /// A vertex that may collapse or move: free, or on a flat boundary when asked.
    bool collapsible(int v) const
    {
        return context_.constraints.is_free_vertex(v) ||
               (options_.flat_boundary_moves && context_.constraints.is_surface_vertex(v));
    }

    bool attempt_collapse(int from, int to, const CollapseOptions& collapse_options)
    {
        ++report_.operators[kCollapse].attempts;
        const bool done = collapse_edge(mesh_, context_, from, to, collapse_options).collapsed;
        report_.operators[kCollapse].successes += done;
        return done;
    }

    /// Tries the operators on tet t in a fixed order; the swaps first (cheap, topological),
    /// then the smoothing of its free vertices while it stays below the threshold, then, when
    /// neither changed anything, the collapse of a free vertex onto another vertex of t.
    TetOutcome improve_tet(int t, double threshold)
    {
        if (options_.swap)
        {
            WallStopwatch stopwatch;
            for (int e = 0; e < 6; ++e)
            {
                ++report_.operators[kEdgeRemoval].attempts;
                if (remove_edge(mesh_, context_, t, e, edge_removal_options_).removed)
                {
                    ++report_.operators[kEdgeRemoval].successes;
                    report_.operators[kEdgeRemoval].seconds += stopwatch.seconds();
                    return kReplaced;
                }
            }
            report_.operators[kEdgeRemoval].seconds += stopwatch.seconds();
            stopwatch.restart();
            for (int f = 0; f < 4; ++f)
            {
                ++report_.operators[kFaceRemoval].attempts;
                if (remove_multi_face(mesh_, context_, t, f).removed)
                {
                    ++report_.operators[kFaceRemoval].successes;
                    report_.operators[kFaceRemoval].seconds += stopwatch.seconds();
                    return kReplaced;
                }
            }
            report_.operators[kFaceRemoval].seconds += stopwatch.seconds();
        }
        TetOutcome outcome = kNothing;
        if (options_.move)
        {
            const WallStopwatch stopwatch;
            const TetVertices vertices = mesh_.tets[t];
            for (int v : vertices)
            {
                if (!collapsible(v)) continue;  // free, or on a flat boundary when asked
                ++report_.operators[kSmoothing].attempts;
                SmoothOptions smooth_options;
                smooth_options.good_enough = threshold;
                smooth_options.in_flat_boundary = options_.flat_boundary_moves;
                if (smooth_vertex(mesh_, context_, v, smooth_options).moved)
                {
                    ++report_.operators[kSmoothing].successes;
                    outcome = kMoved;
                    if (quality(t) >= threshold) break;
                }
            }
            report_.operators[kSmoothing].seconds += stopwatch.seconds();
        }
        if (options_.collapse && outcome == kNothing && quality(t) < threshold)
        {
            // a free vertex the sizes of its edges pin where its ball stays bad: remove it
            // when no tet its removal makes is worse than the worst it had
            CollapseOptions keep_worst;
            keep_worst.min_quality = 1.0;
            const TetVertices vertices = mesh_.tets[t];
            for (int v : vertices)
            {
                if (!context_.constraints.is_free_vertex(v)) continue;
                for (int u : vertices)
                    if (u != v && attempt_collapse(v, u, keep_worst)) return kReplaced;
            }
        }
        return outcome;
    }

    void print_sweep(const std::string& label, const SweepCounters& before)
    {
        if (options_.verbosity < 2) return;
        const QualitySummary q = summarize_quality(mesh_, context_, options_.workers);
        for (int k = 0; k < kNumOperators; ++k)
        {
            const long attempts = report_.operators[k].attempts - before[k][0];
            const long successes = report_.operators[k].successes - before[k][1];
            if (attempts == 0) continue;
            emit(options_.messages, MessageKind::Report,
                 "%-6s %-20s %10ld %10ld %9.4f %8.2f%% %9.3f\n", label.c_str(), kOperatorNames[k],
                 attempts, successes, q.min, 100.0 * q.fraction_good, report_.operators[k].seconds);
        }
    }

    TetMesh& mesh_;
    std::vector<char> changed_vertex_;  // scratch of improve_below, all zero between uses
    std::vector<char> at_required_;     // per vertex: required (leave_required_vertex_balls)
    // the collapses refused, by edge (u << 32 | v), with changes() + 1 at the refusal: the
    // options never change, so the verdict stands while no tet through u or v changes
    std::unordered_map<std::uint64_t, std::uint64_t> refused_collapses_;
    std::vector<char> tet_mark_;         // scratch per tet slot, all zero between uses
    std::vector<ShortEdge> left_short_;  // the short edges the last collapse_short_edges left
    std::vector<int> ball_;              // scratch
    OptimizeOptions options_;
    // only a removal matters here, not how good a refused one would have been
    const EdgeRemovalOptions edge_removal_options_ = [] {
        EdgeRemovalOptions o;
        o.exact_worst_after = false;
        return o;
    }();
    OperatorContext context_;
    OptimizeReport report_;
};

}  // namespace

OptimizeReport improve_bad_elements(TetMesh& mesh, const SizeField& field,
                                    const OptimizeOptions& options)
{
    Optimizer optimizer(mesh, field, options);
    optimizer.improve_below(options.bad_quality);
    return optimizer.finish();
}

OptimizeReport optimize_mesh(TetMesh& mesh, const SizeField& field, const OptimizeOptions& options)
{
    Optimizer optimizer(mesh, field, options);
    const double threshold = std::max(options.bad_quality, options.target_quality);
    // collapses open room for better shapes and the swaps and moves open new collapses:
    // alternate, a few rounds at most
    for (int round = 0; round < 3; ++round)
    {
        long changes = optimizer.collapse_short_edges();
        const long moved = optimizer.equalize_short_edges();
        if (moved > 0)
        {
            // the moves changed no topology: the balls are those of the short edges left
            const std::vector<int> around = optimizer.tets_around_short_edges();
            changes += moved + optimizer.collapse_short_edges(&around);
        }
        if (round > 0 && changes == 0) break;
        optimizer.improve_below(threshold);
    }
    // last: the bad tets no move can reach; nothing collapses their new vertices afterwards
    optimizer.split_locked_tets(threshold);
    return optimizer.finish();
}

}  // namespace hdimesh::volume
