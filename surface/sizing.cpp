#include "surface/sizing.h"

#include <algorithm>
#include <cmath>

namespace hdimesh::surface
{

SizeMap SizeMap::uniform(double size)
{
    SizeMap map;
    map.uniform_ = size;
    return map;
}

SizeMap SizeMap::per_input_vertex(const SurfaceModel& model, std::vector<double> sizes)
{
    SizeMap map;
    map.model_ = &model;
    map.sizes_ = std::move(sizes);
    double sum = 0.0;
    for (double s : map.sizes_) sum += s;
    map.uniform_ = map.sizes_.empty() ? 0.0 : sum / map.sizes_.size();
    return map;
}

double SizeMap::at(const Vec3d& p, int face_hint) const
{
    return model_ ? model_->interpolate(p, sizes_, face_hint) : uniform_;
}

double mean_edge_length(const SurfaceMesh& mesh)
{
    double sum = 0.0;
    for (auto e : mesh.edges()) sum += mesh.calc_edge_length(e);
    return mesh.n_edges() ? sum / mesh.n_edges() : 0.0;
}

std::vector<double> curvature_sizes(const SurfaceMesh& input, const SurfaceModel& model,
                                    const SizingOptions& options)
{
    OpenMesh::VPropHandleT<VertexClass> vertex_class;
    OpenMesh::VPropHandleT<int> vertex_curve;
    OpenMesh::EPropHandleT<int> edge_curve;
    const bool classified = input.get_property_handle(vertex_class, property_names::vertex_class) &&
                            input.get_property_handle(vertex_curve, property_names::vertex_curve) &&
                            input.get_property_handle(edge_curve, property_names::edge_curve);
    const double hausd = options.hausd > 0.0 ? options.hausd : 0.002 * model.diagonal();
    const double huge = options.hmax > 0.0 ? options.hmax : 0.1 * model.diagonal();
    std::vector<double> sizes(input.n_vertices(), huge);
    // The centroid of an equilateral triangle of side h on a sphere of curvature k strays h²k/6
    // from it (an edge's midpoint only h²k/8); the quadric fit underestimates k on a coarse input,
    // so take twice that margin: h = √(3·hausd/k).
    auto size_for = [&](double k) { return k > 0.0 ? std::sqrt(3.0 * hausd / k) : huge; };
    for (auto v : input.vertices())
    {
        const VertexClass cls = classified ? input.property(vertex_class, v) : VertexClass::Smooth;
        if (cls == VertexClass::Smooth)
        {
            sizes[v.idx()] = std::min(huge, size_for(model.input_curvature()[v.idx()]));
            continue;
        }
        if (cls == VertexClass::Corner) continue;  // the graded neighbours decide
        // Curve curvature: turning angle over the mean length of the two curve edges.
        std::vector<Vec3d> ends;
        for (auto h : input.voh_range(v))
            if (input.property(edge_curve, input.edge_handle(h)) == input.property(vertex_curve, v))
                ends.push_back(input.point(input.to_vertex_handle(h)));
        if (ends.size() != 2) continue;
        const Vec3d p = input.point(v);
        const Vec3d u = p - ends[0], w = ends[1] - p;
        const double lu = u.norm(), lw = w.norm();
        if (!(lu > 0.0) || !(lw > 0.0)) continue;
        const double turn = std::acos(std::clamp(OpenMesh::dot(u, w) / (lu * lw), -1.0, 1.0));
        sizes[v.idx()] = std::min(huge, size_for(2.0 * turn / (lu + lw)));
    }
    bound_and_grade(input, sizes, options);
    return sizes;
}

void bound_and_grade(const SurfaceMesh& input, std::vector<double>& sizes,
                     const SizingOptions& options)
{
    for (double& s : sizes)
    {
        if (options.hmin > 0.0) s = std::max(s, options.hmin);
        if (options.hmax > 0.0) s = std::min(s, options.hmax);
    }
    if (!(options.hgrad > 1.0)) return;
    // Relax along edges until no size exceeds its neighbour's plus (hgrad − 1)·distance.
    const double slope = options.hgrad - 1.0;
    // The edges' ends and lengths once, in edge order (the passes below repeat them; the
    // relaxation's result depends on that order).
    struct GradedEdge
    {
        int a, b;
        double length;
    };
    std::vector<GradedEdge> edges;
    edges.reserve(input.n_edges());
    for (auto e : input.edges())
    {
        const auto h = input.halfedge_handle(e, 0);
        edges.push_back({input.from_vertex_handle(h).idx(), input.to_vertex_handle(h).idx(),
                         input.calc_edge_length(e)});
    }
    for (int pass = 0; pass < 100; ++pass)
    {
        bool changed = false;
        for (const GradedEdge& edge : edges)
        {
            const int a = edge.a, b = edge.b;
            const double len = edge.length;
            if (sizes[a] > sizes[b] + slope * len + 1e-15)
            {
                sizes[a] = sizes[b] + slope * len;
                changed = true;
            }
            else if (sizes[b] > sizes[a] + slope * len + 1e-15)
            {
                sizes[b] = sizes[a] + slope * len;
                changed = true;
            }
        }
        if (!changed) break;
    }
    if (options.hmin > 0.0)
        for (double& s : sizes) s = std::max(s, options.hmin);
}

}  // namespace hdimesh::surface
