#include "coupling/boundary_projection.h"

#include <algorithm>
#include <limits>

#include "volume/mesh/tet_topology.h"

namespace hdimesh::coupling
{

using namespace volume;

namespace
{

/// Worst quality of the tets in `ball` if their vertex v were at p.
double ball_quality_at(const TetMesh& mesh, const std::vector<int>& ball, int v, const Vec3& p)
{
    double worst = 1.0;
    for (int t : ball)
    {
        const auto& tv = mesh.tets[t];
        const Vec3* q[4];
        for (int i = 0; i < 4; ++i) q[i] = tv[i] == v ? &p : &mesh.points[tv[i]];
        worst = std::min(worst, tet_quality(*q[0], *q[1], *q[2], *q[3]));
    }
    return worst;
}

/// The shortest edge at v in its ball.
double shortest_edge(const TetMesh& mesh, const std::vector<int>& ball, int v)
{
    double shortest = std::numeric_limits<double>::max();
    for (int t : ball)
        for (int w : mesh.tets[t])
            if (w != v) shortest = std::min(shortest, (mesh.points[w] - mesh.points[v]).norm());
    return shortest;
}

/// The boundary faces of v's ball through v lie in at most `planes` planes (normals parallel
/// to round-off): a flat surface vertex (1), or one on the straight line where two meet (2).
bool flat_at(const TetMesh& mesh, const std::vector<int>& ball, int v, std::size_t planes)
{
    std::vector<Vec3> normals;
    for (int t : ball)
        for (int f = 0; f < 4; ++f)
        {
            const auto& tv = mesh.tets[t];
            if (tv[f] == v || mesh.neighbors[t][f] != kNoTet) continue;
            const auto& fv = tet::kFaceVertices[f];
            const Vec3 n = (mesh.points[tv[fv[1]]] - mesh.points[tv[fv[0]]])
                               .cross(mesh.points[tv[fv[2]]] - mesh.points[tv[fv[0]]]);
            const bool known = std::any_of(normals.begin(), normals.end(), [&](const Vec3& m) {
                return n.dot(m) > 0.0 && n.cross(m).norm() <= 1e-12 * n.norm() * m.norm();
            });
            if (known) continue;
            normals.push_back(n);
            if (normals.size() > planes) return false;
        }
    return !normals.empty();
}

}  // namespace

ProjectionReport BoundaryProjector::project(TetMesh& mesh, const std::vector<int>& vertices) const
{
    ProjectionReport report;
    if (!mesh.has_adjacency()) mesh.build_adjacency();
    const std::vector<int> seeds = vertex_to_tet(mesh);
    const std::vector<char> held = held_vertices(mesh);
    const auto wanted = [&](int v) {
        const VertexClass cls = mesh.vertex_classes[v];
        // (a vertex no tet uses has nothing to keep valid)
        return (cls == VertexClass::Surface || cls == VertexClass::Ridge) && seeds[v] >= 0 &&
               !held[v];
    };
    // the model's queries (read-only) in parallel at the positions before any move; the moves
    // below stay serial, in the list's order
    std::vector<BoundaryFoot> feet(vertices.size());
    std::vector<Vec3> asked(vertices.size());
    parallel_for(options_.workers, vertices.size(), [&](std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i)
        {
            const int v = vertices[i];
            if (!wanted(v)) continue;
            asked[i] = mesh.points[v];
            feet[i] = model_.project(asked[i], mesh.vertex_classes[v]);
        }
    });
    std::vector<int> ball;
    for (std::size_t i = 0; i < vertices.size(); ++i)
    {
        const int v = vertices[i];
        if (!wanted(v)) continue;
        const VertexClass cls = mesh.vertex_classes[v];
        vertex_ball(mesh, seeds[v], v, ball);
        if (options_.keep_flat && flat_at(mesh, ball, v, 2)) continue;
        const Vec3 from = mesh.points[v];
        // a vertex listed twice moved since: asked again, as the serial loop did
        const BoundaryFoot foot = from == asked[i] ? feet[i] : model_.project(from, cls);
        const hdi::Projection& target = foot.target;
        const bool exact = foot.exact;
        // (the far-move test guards against a fit gone wrong, not the target's exact foot)
        if (target.status == hdi::ProjectionStatus::Failed ||
            (!exact && (target.point - from).norm() >
                           options_.max_move_fraction * shortest_edge(mesh, ball, v)))
        {
            ++report.failed;
            continue;
        }
        // shorten the move until no incident tet degenerates (the optimizer finishes later)
        double step = 1.0;
        for (int halving = 0; halving <= options_.max_halvings; ++halving, step *= 0.5)
        {
            const Vec3 candidate = from + step * (target.point - from);
            if (ball_quality_at(mesh, ball, v, candidate) > options_.min_quality_after_move)
            {
                mesh.points[v] = candidate;
                break;
            }
        }
        if (step == 1.0)
        {
            ++report.projected;
        }
        else
        {
            ++report.shortened;
            report.max_remaining_distance =
                std::max(report.max_remaining_distance, (target.point - mesh.points[v]).norm());
        }
    }
    return report;
}

ProjectionReport BoundaryProjector::project_all(TetMesh& mesh) const
{
    std::vector<int> boundary;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (mesh.vertex_classes[v] == VertexClass::Surface ||
            mesh.vertex_classes[v] == VertexClass::Ridge)
            boundary.push_back(v);
    return project(mesh, boundary);
}

}  // namespace hdimesh::coupling
