// Options to a size field (volume/size/size_spec.h).
#include "volume/size/size_spec.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/errors.h"
#include "volume/mesh/tet_tables.h"
#include "volume/size/metric_fields.h"
#include "volume/size/size_fields.h"

namespace hdimesh::volume
{

namespace
{

/// The pointwise minimum of two fields (gradation only shrinks sizes).
class MinimumSize : public SizeField
{
public:
    MinimumSize(std::shared_ptr<const SizeField> a, std::shared_ptr<const SizeField> b)
        : a_(std::move(a)), b_(std::move(b))
    {
    }
    double size(const Vec3& p) const override { return std::min(a_->size(p), b_->size(p)); }

private:
    std::shared_ptr<const SizeField> a_, b_;
};

/// Mean length of the tet edges at each vertex (each edge counted once per tet: good enough
/// for a size, and O(n) without an edge table).
std::vector<double> mean_incident_edge_length(const TetMesh& mesh)
{
    std::vector<double> sum(mesh.num_vertices(), 0.0);
    std::vector<int> count(mesh.num_vertices(), 0);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        for (const auto& e : tet::kEdgeVertices)
        {
            const int a = mesh.tets[t][e[0]], b = mesh.tets[t][e[1]];
            const double length = (mesh.points[a] - mesh.points[b]).norm();
            sum[a] += length;
            sum[b] += length;
            ++count[a];
            ++count[b];
        }
    }
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (count[v] > 0) sum[v] /= count[v];
    return sum;
}

void check_spec(const SizeSpec& spec, const TetMesh& input)
{
    const int given = int(spec.hsiz != 0) + int(!spec.vertex_sizes.empty()) +
                      int(!spec.vertex_metrics.empty()) + int(spec.benchmark != 0);
    if (given > 1)
        throw InputError(
            "give only one of hsiz, vertex sizes or metrics (sol) and a benchmark field");
    if (spec.hsiz != 0 && !(spec.hsiz > 0 && std::isfinite(spec.hsiz)))
        throw InputError("hsiz must be positive");
    if (!(spec.hmin >= 0) || !(spec.hmax >= 0)) throw InputError("hmin and hmax must be positive");
    if (spec.hmin > 0 && spec.hmax > 0 && spec.hmin > spec.hmax)
        throw InputError("hmin is larger than hmax");
    if (spec.hgrad != 0 && !(spec.hgrad > 1)) throw InputError("hgrad must be larger than 1");
    if (!spec.vertex_sizes.empty())
    {
        if (static_cast<int>(spec.vertex_sizes.size()) != input.num_vertices())
            throw InputError(std::to_string(spec.vertex_sizes.size()) +
                             " vertex sizes for a mesh of " + std::to_string(input.num_vertices()) +
                             " vertices");
        for (std::size_t v = 0; v < spec.vertex_sizes.size(); ++v)
            if (!(spec.vertex_sizes[v] > 0) || !std::isfinite(spec.vertex_sizes[v]))
                throw InputError("the size at vertex " + std::to_string(v + 1) +
                                 " is not a positive number");
    }
}

/// The anisotropic field of vertex metrics: graded, interpolated, bounded.
std::shared_ptr<const SizeField> make_metric_field(const SizeSpec& spec, const TetMesh& input)
{
    std::vector<Metric> metrics =
        metrics_from_medit(spec.vertex_metrics, input.num_vertices(), "vertex metrics");
    if (spec.hgrad > 0) grade_vertex_metrics(input, metrics, spec.hgrad);
    std::shared_ptr<const SizeField> field = std::make_shared<BackgroundMeshMetric>(input, metrics);
    if (spec.hmin > 0 || spec.hmax > 0)
        field = std::make_shared<BoundedMetric>(
            field, spec.hmin, spec.hmax > 0 ? spec.hmax : std::numeric_limits<double>::infinity());
    return field;
}

}  // namespace

std::shared_ptr<const SizeField> make_size_field(const SizeSpec& spec, const TetMesh& input)
{
    check_spec(spec, input);
    if (!spec.vertex_metrics.empty()) return make_metric_field(spec, input);
    std::shared_ptr<const SizeField> field;
    bool at_vertices = false;  // the field is already a background over the input
    std::vector<double> vertex_sizes;
    if (spec.hsiz > 0)
    {
        field = std::make_shared<ConstantSize>(spec.hsiz);
    }
    else if (spec.benchmark != 0)
    {
        field = std::make_shared<BenchmarkSize>(benchmark_case(spec.benchmark));
    }
    else
    {
        if (!spec.vertex_sizes.empty())
            vertex_sizes = spec.vertex_sizes;
        else
        {
            vertex_sizes = mean_incident_edge_length(input);
            for (std::size_t v = 0; v < vertex_sizes.size(); ++v)
                if (!(vertex_sizes[v] > 0))
                    throw InputError("input mesh: size at vertex " + std::to_string(v + 1) +
                                     " is not positive");
        }
        at_vertices = true;
    }

    if (spec.hgrad > 0)
    {
        if (!at_vertices) vertex_sizes = sample_vertex_sizes(input, *field);
        grade_vertex_sizes(input, vertex_sizes, spec.hgrad);
    }
    if (at_vertices || spec.hgrad > 0)
    {
        auto background = std::make_shared<BackgroundMeshSize>(input, vertex_sizes);
        field =
            field
                ? std::shared_ptr<const SizeField>(std::make_shared<MinimumSize>(field, background))
                : background;
    }
    if (spec.hmin > 0 || spec.hmax > 0)
        field = std::make_shared<ClampedSize>(
            field, spec.hmin, spec.hmax > 0 ? spec.hmax : std::numeric_limits<double>::infinity());
    return field;
}

}  // namespace hdimesh::volume
