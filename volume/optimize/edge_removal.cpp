#include "volume/optimize/edge_removal.h"

#include <algorithm>
#include <limits>

#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace
{

constexpr double kNever = -std::numeric_limits<double>::infinity();
constexpr double kFree = std::numeric_limits<double>::infinity();

/// The shell of the edge, its legality, and the best ring triangulation found.
struct EdgeRemovalPlan
{
    EdgeShell shell;
    int ref = 0;
    bool legal = false;  // topology and constraints allow a removal
    double worst_before = 0;
    double worst_after = kNever;
    std::vector<std::array<int, 3>> triangles;  // ring positions (i, k, j), i < k < j
};

/// Klincsek's program over the ring polygon: best[i][j] is the best worst quality of the tets
/// over a triangulation of the sub-polygon ri..rj (with the chord (ri, rj) as its base).
/// Partial triangulations whose worst is <= must_beat are dropped (a sub-polygon none of whose
/// triangulations beats it gets best = must_beat and no choice): the whole one's worst is at
/// most any part's, so nothing better than must_beat is lost, and the first best k is the same.
void best_triangulation(const TetMesh& mesh, const OperatorContext& context, EdgeRemovalPlan& plan,
                        double must_beat)
{
    const auto& ring = plan.shell.ring;
    const int m = static_cast<int>(ring.size());
    const auto& p = mesh.points;
    const Vec3& pa = p[plan.shell.a];
    const Vec3& pb = p[plan.shell.b];

    // chords that would be too long are forbidden (the ring's own edges exist already)
    std::vector<char> chord_ok(m * m, 1);
    if (context.field != nullptr)
        for (int i = 0; i < m; ++i)
            for (int j = i + 2; j < m; ++j)
                if (!(i == 0 && j == m - 1))
                    chord_ok[i * m + j] = !context.too_long(p[ring[i]], p[ring[j]]);
    auto usable = [&](int i, int j) { return j - i < 2 || chord_ok[i * m + j]; };

    std::vector<double> best(m * m, kFree);
    std::vector<int> choice(m * m, -1);
    for (int length = 2; length < m; ++length)
        for (int i = 0; i + length < m; ++i)
        {
            const int j = i + length;
            double best_here = must_beat;
            int best_k = -1;
            if (usable(i, j) || (i == 0 && j == m - 1))
                for (int k = i + 1; k < j; ++k)
                {
                    if (!usable(i, k) || !usable(k, j)) continue;
                    double value = std::min(best[i * m + k], best[k * m + j]);
                    if (value <= best_here) continue;
                    const Vec3 &ri = p[ring[i]], &rk = p[ring[k]], &rj = p[ring[j]];
                    value = std::min(value, context.shape(ri, rk, rj, pb));
                    if (value <= best_here) continue;
                    value = std::min(value, context.shape(ri, rj, rk, pa));
                    if (value > best_here)
                    {
                        best_here = value;
                        best_k = k;
                    }
                }
            best[i * m + j] = best_here;
            choice[i * m + j] = best_k;
        }
    plan.worst_after = choice[m - 1] < 0 ? kNever : best[m - 1];
    plan.triangles.clear();
    if (plan.worst_after == kNever) return;
    // unwind the choices into ring triangles
    std::vector<std::array<int, 2>> stack = {{0, m - 1}};
    while (!stack.empty())
    {
        const auto [i, j] = stack.back();
        stack.pop_back();
        if (j - i < 2) continue;
        const int k = choice[i * m + j];
        plan.triangles.push_back({i, k, j});
        stack.push_back({i, k});
        stack.push_back({k, j});
    }
}

EdgeRemovalPlan plan_edge_removal(const TetMesh& mesh, const OperatorContext& context, int seed,
                                  int local_edge, const EdgeRemovalOptions& options)
{
    EdgeRemovalPlan plan;
    // layers 1 and 2: topology and constraints
    if (!free_interior_shell(mesh, context, seed, local_edge, options.max_ring, plan.shell,
                             plan.ref))
        return plan;
    plan.legal = true;
    plan.worst_before = context.worst_quality(mesh, plan.shell.tets);
    // layers 3 and 4: geometry and quality, by the dynamic program
    best_triangulation(mesh, context, plan,
                       options.exact_worst_after ? kNever : plan.worst_before + options.min_gain);
    return plan;
}

EdgeRemovalResult summarize(const EdgeRemovalPlan& plan)
{
    EdgeRemovalResult result;
    result.worst_before = plan.worst_before;
    result.worst_after = plan.worst_after;
    result.ring_size = static_cast<int>(plan.shell.ring.size());
    return result;
}

}  // namespace

EdgeRemovalResult evaluate_edge_removal(const TetMesh& mesh, const OperatorContext& context,
                                        int seed, int local_edge, const EdgeRemovalOptions& options)
{
    return summarize(plan_edge_removal(mesh, context, seed, local_edge, options));
}

EdgeRemovalResult remove_edge(TetMesh& mesh, OperatorContext& context, int seed, int local_edge,
                              const EdgeRemovalOptions& options)
{
    const EdgeRemovalPlan plan = plan_edge_removal(mesh, context, seed, local_edge, options);
    EdgeRemovalResult result = summarize(plan);
    if (!plan.legal || plan.worst_after <= 0.0 ||
        plan.worst_after <= plan.worst_before + options.min_gain)
        return result;

    const auto& ring = plan.shell.ring;
    std::vector<TetVertices> added;
    added.reserve(2 * plan.triangles.size());
    for (const auto& [i, k, j] : plan.triangles)
    {
        added.push_back({ring[i], ring[k], ring[j], plan.shell.b});
        added.push_back({ring[i], ring[j], ring[k], plan.shell.a});
    }
    replace_tets(mesh, context, plan.shell.tets, added, plan.ref);
    result.removed = true;
    return result;
}

}  // namespace hdimesh::volume
