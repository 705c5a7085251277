#include "surface/hdi_projection.h"

#include <algorithm>
#include <memory>

#include "hdi/hdi_surface.h"

namespace hdimesh::surface
{

namespace
{

ProjectedPoint to_projected(const hdi::Projection& fit)
{
    ProjectedPoint out;
    if (fit.status == hdi::ProjectionStatus::Failed) return out;
    out.point = Vec3d(fit.point.x(), fit.point.y(), fit.point.z());
    out.normal = Vec3d(fit.normal.x(), fit.normal.y(), fit.normal.z());
    out.k1 = fit.k1;
    out.k2 = fit.k2;
    out.ok = true;
    return out;
}

// Most of the area: the facets are then no model of the smooth surface they sample.
constexpr double kCoarseAreaFraction = 0.5;

// Per input face, whether options ask for the HDI on it: with coarse_facet_tolerance, only on
// the shells most of whose area is on coarse facets (a coarse ball inside a flat box). Empty:
// on every face; all zero: nowhere.
std::vector<char> wanted_faces(const SurfaceModel& model, const HdiProjectionOptions& options)
{
    if (!(options.coarse_facet_tolerance > 0.0)) return {};
    const std::vector<int> shell = model.face_shells();
    const std::vector<double> coarse =
        model.coarse_area_fractions(options.coarse_facet_tolerance, shell);
    const auto wants = [&coarse](int s) { return coarse[s] > kCoarseAreaFraction; };
    int wanted = 0;
    for (std::size_t s = 0; s < coarse.size(); ++s) wanted += wants(static_cast<int>(s));
    if (wanted == static_cast<int>(coarse.size())) return {};
    std::vector<char> faces(shell.size(), 0);
    for (std::size_t f = 0; f < shell.size(); ++f) faces[f] = wants(shell[f]);
    return faces;
}

bool nowhere(const std::vector<char>& faces)
{
    return !faces.empty() && std::find(faces.begin(), faces.end(), 1) == faces.end();
}

// `surface` as model's smooth projection on the faces `only` (empty: all), trusted where it
// stays within the deviation bound of the facets.
void install(SurfaceModel& model, std::shared_ptr<const hdi::HdiSurface> surface,
             const HdiProjectionOptions& options, std::vector<char> only)
{
    const double max_deviation = options.max_deviation_fraction * model.diagonal();
    const double edge_fraction = options.max_deviation_edge_fraction;
    const SurfaceModel* facets = &model;
    model.set_smooth_projection([surface = std::move(surface), facets, max_deviation, edge_fraction,
                                 only = std::move(only)](const Vec3d& p) {
        if (!only.empty())
        {
            // a shell the facets model well enough: not ok sends p onto them
            const ProjectedPoint under = facets->closest_on_input(p);
            if (!under.ok || under.face < 0 || !only[under.face]) return ProjectedPoint{};
        }
        ProjectedPoint out = to_projected(surface->project(to_point(p)));
        if (!out.ok) return out;
        const ProjectedPoint on_facets = facets->closest_on_input(out.point);
        const double bound =
            std::max(max_deviation, edge_fraction * facets->shortest_edge(on_facets.face));
        out.ok = on_facets.ok && (on_facets.point - out.point).norm() <= bound;
        out.face = on_facets.face;
        return out;
    });
}

}  // namespace

ProjectedPoint HdiProjector::project(const Vec3d& p, VertexClass cls, int) const
{
    const hdi::Vec3 x(p[0], p[1], p[2]);
    switch (cls)
    {
        case VertexClass::Smooth: return to_projected(surface_.project(x));
        case VertexClass::Ridge:
        case VertexClass::Boundary: return to_projected(surface_.project_to_ridge(x));
        case VertexClass::Corner:
        {
            ProjectedPoint out = to_projected(surface_.project(x));
            out.point = p;
            out.ok = true;
            return out;
        }
    }
    return {};
}

HdiProjectionOptions coarse_input_options(HdiProjectionOptions base, double tolerance)
{
    base.coarse_facet_tolerance = tolerance;
    base.max_deviation_edge_fraction = 0.25;
    return base;
}

void attach_hdi_projection(SurfaceModel& model, const SurfaceMesh& input,
                           const HdiProjectionOptions& options)
{
    std::vector<char> only = wanted_faces(model, options);
    if (nowhere(only)) return;  // before the model is built
    OpenMesh::VPropHandleT<VertexClass> vertex_class;
    OpenMesh::EPropHandleT<int> edge_curve;
    const bool classified = input.get_property_handle(vertex_class, property_names::vertex_class) &&
                            input.get_property_handle(edge_curve, property_names::edge_curve);
    std::vector<hdi::Vec3> points;
    points.reserve(input.n_vertices());
    for (auto v : input.vertices())
    {
        const Vec3d p = input.point(v);
        points.emplace_back(p[0], p[1], p[2]);
    }
    std::vector<hdi::Triangle3> triangles;
    triangles.reserve(input.n_faces());
    for (auto f : input.faces())
    {
        auto fv = input.cfv_iter(f);
        const int a = fv->idx(), b = (++fv)->idx(), c = (++fv)->idx();
        triangles.push_back({a, b, c});
    }
    hdi::FeatureSet features;
    if (classified)
    {
        for (auto e : input.edges())
        {
            if (input.property(edge_curve, e) == kNoCurve || input.is_boundary(e)) continue;
            const auto h = input.halfedge_handle(e, 0);
            const int a = input.from_vertex_handle(h).idx(), b = input.to_vertex_handle(h).idx();
            features.ridge_edges.push_back({std::min(a, b), std::max(a, b)});
        }
        for (auto v : input.vertices())
            if (input.property(vertex_class, v) == VertexClass::Corner)
                features.corners.push_back(v.idx());
        std::sort(features.ridge_edges.begin(), features.ridge_edges.end());
    }
    features.boundary_edges = hdi::open_boundary_edges(triangles);

    hdi::HdiOptions hdi_options;
    hdi_options.neighbours = options.neighbours;
    auto surface = std::make_shared<const hdi::HdiSurface>(std::move(points), std::move(triangles),
                                                           features, hdi_options);
    install(model, surface, options, std::move(only));
}

void attach_hdi_projection(SurfaceModel& model, const hdi::HdiSurface& surface,
                           const HdiProjectionOptions& options)
{
    std::vector<char> only = wanted_faces(model, options);
    if (nowhere(only)) return;
    // Not owned: the caller's model outlives this one.
    install(model, std::shared_ptr<const hdi::HdiSurface>(&surface, [](const hdi::HdiSurface*) {}),
            options, std::move(only));
}

}  // namespace hdimesh::surface
