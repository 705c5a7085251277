#include "volume/size/metric_fields.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "common/errors.h"
#include "volume/mesh/boundary.h"
#include "volume/mesh/geometry.h"
#include "volume/size/detail/point_memo.h"

namespace hdimesh::volume
{

namespace
{

std::vector<Metric> logs_of(const TetMesh& mesh, const std::vector<Metric>& metrics)
{
    if (static_cast<int>(metrics.size()) != mesh.num_vertices())
        throw InputError("vertex metrics: " + std::to_string(metrics.size()) + " metrics for " +
                         std::to_string(mesh.num_vertices()) + " vertices");
    std::vector<Metric> logs(metrics.size(), Metric::Zero());
    std::vector<char> used(metrics.size(), 0);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t))
            for (int v : mesh.tets[t])
                if (v >= 0 && v < mesh.num_vertices()) used[v] = 1;
    for (std::size_t v = 0; v < metrics.size(); ++v)
    {
        if (!used[v]) continue;
        const std::string problem = metric_problem(metrics[v]);
        if (!problem.empty())
            throw InputError("vertex metrics: the metric at vertex " + std::to_string(v + 1) +
                             " is " + problem);
        logs[v] = metric_log(metrics[v]);
    }
    return logs;
}

}  // namespace

BackgroundMeshMetric::BackgroundMeshMetric(const TetMesh& mesh, const std::vector<Metric>& metrics)
    : locator_(mesh), logs_(logs_of(mesh, metrics)), id_(detail::next_field_id())
{
}

Metric BackgroundMeshMetric::metric(const Vec3& p) const
{
    // every operator that looks at an edge asks its midpoint again: the last answers are kept
    // per thread, keyed by this field and the point's exact bits
    struct Remembered
    {
        std::uint64_t field = 0;
        Vec3 point;
        Metric metric;
    };
    constexpr std::size_t kSlots = 4096;
    thread_local std::vector<Remembered> remembered(kSlots);
    Remembered& slot = remembered[detail::point_slot(p, kSlots)];
    if (slot.field == id_ && slot.point == p) return slot.metric;
    slot.field = id_;
    slot.point = p;
    slot.metric = locate_metric(p);
    return slot.metric;
}

Metric BackgroundMeshMetric::locate_metric(const Vec3& p) const
{
    Metric log_m = Metric::Zero();
    if (const auto inside = locator_.locate(p))
    {
        for (int k = 0; k < 4; ++k) log_m += inside->weights[k] * logs_[inside->vertices[k]];
        return metric_exp(log_m);
    }
    const BoundaryPoint nearest = locator_.nearest_boundary_point(p);
    for (int k = 0; k < 3; ++k) log_m += nearest.weights[k] * logs_[nearest.vertices[k]];
    return metric_exp(log_m);
}

BoundedMetric::BoundedMetric(std::shared_ptr<const SizeField> inner, double hmin, double hmax)
    : inner_(std::move(inner)), hmin_(hmin), hmax_(hmax)
{
    if (!inner_) throw InputError("bounded metric: no metric to bound");
    if (!(std::isfinite(hmin) && hmin >= 0.0 && hmax >= hmin))
        throw InputError("bounded metric: hmin " + std::to_string(hmin) + ", hmax " +
                         std::to_string(hmax) + ": need 0 <= hmin <= hmax");
}

Metric BoundedMetric::metric(const Vec3& p) const
{
    return bound_metric(inner_->metric(p), hmin_, hmax_);
}

std::vector<Metric> metrics_from_medit(const std::vector<double>& values, int num_vertices,
                                       const std::string& source)
{
    if (values.size() != 6 * static_cast<std::size_t>(num_vertices))
        throw InputError(source + ": " + std::to_string(values.size()) + " metric values for " +
                         std::to_string(num_vertices) +
                         " vertices (6 per vertex: m11 m12 m22 m13 m23 m33)");
    std::vector<Metric> metrics(num_vertices);
    for (int v = 0; v < num_vertices; ++v)
    {
        metrics[v] = metric_from_medit(values.data() + 6 * static_cast<std::size_t>(v));
        const std::string problem = metric_problem(metrics[v]);
        if (!problem.empty())
            throw InputError(source + ": the metric at vertex " + std::to_string(v + 1) + " is " +
                             problem);
    }
    return metrics;
}

std::vector<Metric> sample_vertex_metrics(const TetMesh& mesh, const SizeField& field)
{
    std::vector<Metric> metrics(mesh.num_vertices());
    for (int v = 0; v < mesh.num_vertices(); ++v) metrics[v] = field.metric(mesh.points[v]);
    return metrics;
}

void grade_vertex_metrics(const TetMesh& mesh, std::vector<Metric>& metrics, double hgrad)
{
    if (!(std::isfinite(hgrad) && hgrad >= 1.0))
        throw InputError("gradation: hgrad " + std::to_string(hgrad) + " must be finite and >= 1");
    if (static_cast<int>(metrics.size()) != mesh.num_vertices())
        throw InputError("gradation: " + std::to_string(metrics.size()) + " metrics for " +
                         std::to_string(mesh.num_vertices()) + " vertices");
    constexpr int kMaxSweeps = 100;
    constexpr double kChanged = 1e-6;  // relative change of a metric that counts
    const VertexGraph graph = vertex_graph(mesh);
    const auto bound_by = [&](int i, int j) {
        const Vec3 e = mesh.points[i] - mesh.points[j];
        const double eta = 1.0 + (hgrad - 1.0) * metric_length(metrics[j], e);
        const Metric grown = metrics[j] / (eta * eta);
        const Metric both = intersect_metrics(metrics[i], grown);
        if ((both - metrics[i]).norm() <= kChanged * metrics[i].norm()) return false;
        metrics[i] = both;
        return true;
    };
    for (int sweep = 0; sweep < kMaxSweeps; ++sweep)
    {
        bool changed = false;
        for (int i = 0; i < mesh.num_vertices(); ++i)
            for (int n = graph.start[i]; n < graph.start[i + 1]; ++n)
                changed = bound_by(i, graph.neighbors[n]) || changed;
        if (!changed) break;
    }
}

Solutions field_at_vertices(const TetMesh& mesh, const SizeField& field)
{
    Solutions out;
    out.num_vertices = mesh.num_vertices();
    Solution one;
    one.type = field.anisotropic() ? SolType::Tensor : SolType::Scalar;
    one.values.reserve(static_cast<std::size_t>(mesh.num_vertices()) * sol_components(one.type));
    for (const Vec3& p : mesh.points)
    {
        if (!field.anisotropic())
        {
            one.values.push_back(field.size(p));
            continue;
        }
        for (double value : metric_to_medit(field.metric(p))) one.values.push_back(value);
    }
    out.solutions.push_back(std::move(one));
    return out;
}

}  // namespace hdimesh::volume
