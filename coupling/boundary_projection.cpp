#include "coupling/boundary_projection.h"

#include <algorithm>
#include <limits>
#include <unordered_map>

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

}  // namespace

BoundaryProjector::BoundaryProjector(const TetMesh& mesh, const ProjectionOptions& options)
    : options_(options)
{
    // the model's nodes are the boundary vertices, renumbered densely
    std::unordered_map<int, int> mesh2model;
    std::vector<hdi::Vec3> points;
    auto model_id = [&](int v) {
        auto [it, inserted] = mesh2model.emplace(v, static_cast<int>(points.size()));
        if (inserted) points.push_back(mesh.points[v]);
        return it->second;
    };
    std::vector<std::array<int, 3>> triangles;
    triangles.reserve(mesh.triangles.size());
    for (const auto& tri : mesh.triangles)
        triangles.push_back({model_id(tri[0]), model_id(tri[1]), model_id(tri[2])});

    // features: detected on the input by the surface's rules (borders between triangle refs
    // included), plus the ridges and corners the file declares
    const std::vector<int> no_refs;
    const std::vector<int>& refs =
        mesh.triangle_refs.size() == mesh.triangles.size() ? mesh.triangle_refs : no_refs;
    hdi::FeatureSet features =
        hdi::feature_set(hdi::classify_features(points, triangles, options.features, {}, refs));
    for (int e : mesh.ridges)
    {
        const auto& edge = mesh.edges[e];
        auto a = mesh2model.find(edge[0]), b = mesh2model.find(edge[1]);
        if (a != mesh2model.end() && b != mesh2model.end())
            features.ridge_edges.push_back({a->second, b->second});
    }
    for (int v : mesh.corners)
        if (auto it = mesh2model.find(v); it != mesh2model.end())
            features.corners.push_back(it->second);
    std::sort(features.corners.begin(), features.corners.end());
    features.corners.erase(std::unique(features.corners.begin(), features.corners.end()),
                           features.corners.end());

    model_ = std::make_unique<hdi::HdiSurface>(std::move(points), std::move(triangles), features,
                                               options.model);
}

BoundaryProjector::~BoundaryProjector() = default;

ProjectionReport BoundaryProjector::project(TetMesh& mesh, const std::vector<int>& vertices) const
{
    ProjectionReport report;
    if (!mesh.has_adjacency()) mesh.build_adjacency();
    const std::vector<int> seeds = vertex_to_tet(mesh);
    std::vector<int> ball;
    for (int v : vertices)
    {
        const VertexClass cls = mesh.vertex_classes[v];
        if (cls != VertexClass::Surface && cls != VertexClass::Ridge) continue;
        if (seeds[v] < 0) continue;  // a vertex no tet uses has nothing to keep valid
        vertex_ball(mesh, seeds[v], v, ball);
        const Vec3 from = mesh.points[v];
        hdi::Projection target;
        const bool exact = cls == VertexClass::Surface && static_cast<bool>(surface_target_);
        if (exact)
        {
            const std::optional<Vec3> to = surface_target_(from);
            target.point = to.value_or(from);
            target.status = to ? hdi::ProjectionStatus::Ok : hdi::ProjectionStatus::Failed;
        }
        else
        {
            target =
                cls == VertexClass::Ridge ? model_->project_to_ridge(from) : model_->project(from);
        }
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
