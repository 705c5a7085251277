#include "coupling/boundary_model.h"

#include <algorithm>
#include <unordered_map>

namespace hdimesh::coupling
{

using namespace volume;

BoundaryModel::BoundaryModel(const TetMesh& mesh, const hdi::FeatureOptions& feature_options,
                             const hdi::HdiOptions& options)
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
        hdi::feature_set(hdi::classify_features(points, triangles, feature_options, {}, refs));
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

    hdi_ = std::make_unique<hdi::HdiSurface>(std::move(points), std::move(triangles), features,
                                             options);
}

BoundaryModel::~BoundaryModel() = default;

const surface::SurfaceModel& BoundaryModel::build_surface_model(
    const surface::SurfaceMesh& input, const surface::HdiProjectionOptions& options,
    double tolerance)
{
    surface_.emplace(input);
    surface::attach_hdi_projection(*surface_, *hdi_,
                                   surface::coarse_input_options(options, tolerance));
    return *surface_;
}

BoundaryFoot BoundaryModel::project(const Vec3& p, VertexClass cls) const
{
    BoundaryFoot foot;
    if (cls == VertexClass::Surface && on_surface_model_)
    {
        const surface::ProjectedPoint q = surface_->project(
            surface::to_vec3d(p), surface::VertexClass::Smooth, surface::kNoCurve);
        foot.target.point = q.ok ? surface::to_point(q.point) : p;
        foot.target.status = q.ok ? hdi::ProjectionStatus::Ok : hdi::ProjectionStatus::Failed;
        foot.exact = true;
        return foot;
    }
    foot.target = cls == VertexClass::Ridge ? hdi_->project_to_ridge(p) : hdi_->project(p);
    return foot;
}

}  // namespace hdimesh::coupling
