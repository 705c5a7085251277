#include "volume/optimize/edge_split.h"

#include <algorithm>
#include <array>
#include <vector>

#include "volume/check/quality_report.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace
{

/// One candidate: the shell of an edge and where its new vertex would go.
struct SplitPlan
{
    EdgeShell shell;
    int ref = 0;
    bool legal = false;  // topology and constraints allow the split
    double worst_before = 0;
    double worst_after = 0;
    Vec3 point;
    bool keeps_angles = false;  // no new dihedral angle below the shell's smallest
};

double smallest_dihedral(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    const auto angles = dihedral_angles_deg(a, b, c, d);
    return *std::min_element(angles.begin(), angles.end());
}

SplitPlan plan_split(const TetMesh& mesh, const OperatorContext& context, int seed, int local_edge,
                     const EdgeSplitOptions& options)
{
    SplitPlan plan;
    // layers 1 and 2: topology and constraints
    if (!free_interior_shell(mesh, context, seed, local_edge, options.max_ring, plan.shell,
                             plan.ref))
        return plan;
    const int a = plan.shell.a, b = plan.shell.b;
    const int m = static_cast<int>(plan.shell.tets.size());
    plan.legal = true;
    plan.worst_before = context.worst_quality(mesh, plan.shell.tets);

    // layers 3 and 4: the new vertex sees, from each shell tet (a, b, r_i, r_i+1), the faces
    // (a, r_i, r_i+1) and (b, r_i+1, r_i), both positive with it on their side
    const auto& p = mesh.points;
    const auto& ring = plan.shell.ring;
    std::vector<std::array<Vec3, 3>> faces;
    faces.reserve(2 * m);
    for (int i = 0; i < m; ++i)
    {
        const Vec3& ri = p[ring[i]];
        const Vec3& rj = p[ring[(i + 1) % m]];
        faces.push_back({p[a], ri, rj});
        faces.push_back({p[b], rj, ri});
    }
    const PointPlacement placement =
        place_vertex(context, faces, 0.5 * (p[a] + p[b]), options.placement);
    plan.point = placement.point;
    plan.worst_after = placement.worst;
    // Qe can rise while a dihedral angle falls: a split must not trade one for the other
    double before = 180, after = 180;
    for (int i = 0; i < m; ++i)
    {
        const Vec3& ri = p[ring[i]];
        const Vec3& rj = p[ring[(i + 1) % m]];
        before = std::min(before, smallest_dihedral(p[a], p[b], ri, rj));
        after = std::min({after, smallest_dihedral(p[a], plan.point, ri, rj),
                          smallest_dihedral(plan.point, p[b], ri, rj)});
    }
    plan.keeps_angles = after >= std::min(before, options.min_dihedral_deg);
    return plan;
}

}  // namespace

EdgeSplitResult split_interior_edge(TetMesh& mesh, OperatorContext& context, int t,
                                    const EdgeSplitOptions& options)
{
    EdgeSplitResult result;
    SplitPlan best;
    for (int e = 0; e < 6; ++e)
    {
        SplitPlan plan = plan_split(mesh, context, t, e, options);
        if (!plan.legal || !plan.keeps_angles) continue;
        // the gain, not the value: shells differ, and only a rise of their worst helps
        if (!best.legal ||
            plan.worst_after - plan.worst_before > best.worst_after - best.worst_before)
            best = std::move(plan);
    }
    if (!best.legal) return result;
    result.worst_before = best.worst_before;
    result.worst_after = best.worst_after;
    if (!(best.worst_after > 0) || best.worst_after <= best.worst_before + options.min_gain)
        return result;

    const int a = best.shell.a, b = best.shell.b;
    const int ref = mesh.vertex_refs[a] == mesh.vertex_refs[b] ? mesh.vertex_refs[a] : 0;
    const int v = mesh.add_vertex(best.point, ref, VertexClass::Interior);
    const auto& ring = best.shell.ring;
    const int m = static_cast<int>(best.shell.tets.size());
    std::vector<TetVertices> added;
    added.reserve(2 * m);
    for (int i = 0; i < m; ++i)
    {
        added.push_back({a, v, ring[i], ring[(i + 1) % m]});
        added.push_back({v, b, ring[i], ring[(i + 1) % m]});
    }
    replace_tets(mesh, context, best.shell.tets, added, best.ref);
    result.split = true;
    result.new_vertex = v;
    return result;
}

}  // namespace hdimesh::volume
