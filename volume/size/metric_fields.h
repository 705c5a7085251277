#pragma once
// Anisotropic fields: metrics given at a mesh's vertices (a tensor .sol, Gmsh NodeData, arrays)
// or by a function, bounded by hmin/hmax and graded by hgrad as Mmg does with -A. The metric
// between vertices is interpolated log-Euclidean: P1 in the tet of log M, then exp (Arsigny et
// al. 2006), which keeps it positive definite and interpolates sizes geometrically.

#include <functional>
#include <memory>
#include <vector>

#include "common/metric.h"
#include "common/size_field.h"
#include "common/sol_io.h"
#include "volume/mesh/point_locator.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// Metrics at the vertices of a tet mesh (its own copy), log-Euclidean P1 inside each tet;
/// outside the mesh, on the nearest boundary triangle. Const queries are thread-safe.
class BackgroundMeshMetric : public SizeField
{
public:
    /// Throws InputError when metrics.size() != mesh.num_vertices() or a metric used by a tet
    /// is not one (naming the vertex, from 1).
    BackgroundMeshMetric(const TetMesh& mesh, const std::vector<Metric>& metrics);
    double size(const Vec3& p) const override { return metric_mean_size(metric(p)); }
    bool anisotropic() const override { return true; }
    Metric metric(const Vec3& p) const override;

private:
    Metric locate_metric(const Vec3& p) const;

    TetLocator locator_;
    std::vector<Metric> logs_;  // log M per vertex
    std::uint64_t id_;          // keys this field's answers in the per-thread table of metric()
};

/// A metric given by a function of the point (an analytic metric, a Python callable).
class FunctionMetric : public SizeField
{
public:
    explicit FunctionMetric(std::function<Metric(const Vec3&)> metric) : metric_(std::move(metric))
    {
    }
    double size(const Vec3& p) const override { return metric_mean_size(metric(p)); }
    bool anisotropic() const override { return true; }
    Metric metric(const Vec3& p) const override { return metric_(p); }

private:
    std::function<Metric(const Vec3&)> metric_;
};

/// Another metric with its sizes bounded to [hmin, hmax] (-hmin, -hmax on a metric).
class BoundedMetric : public SizeField
{
public:
    /// Throws InputError unless inner is set and 0 <= hmin <= hmax (hmax may be +infinity).
    BoundedMetric(std::shared_ptr<const SizeField> inner, double hmin, double hmax);
    double size(const Vec3& p) const override { return metric_mean_size(metric(p)); }
    bool anisotropic() const override { return true; }
    Metric metric(const Vec3& p) const override;

private:
    std::shared_ptr<const SizeField> inner_;
    double hmin_, hmax_;
};

/// Metrics from six values per vertex in Medit's order; InputError naming the vertex (from 1)
/// and `source` when a value count is wrong or a metric is not one.
std::vector<Metric> metrics_from_medit(const std::vector<double>& values, int num_vertices,
                                       const std::string& source);

/// The field sampled at every vertex of the mesh, as metrics.
std::vector<Metric> sample_vertex_metrics(const TetMesh& mesh, const SizeField& field);

/// Mmg's -hgrad on metrics (Alauzet 2010): along every edge ij the metric at j, grown by
/// η = 1 + (hgrad-1)·ℓ_Mj(ij) (η⁻² Mj), bounds the metric at i by intersection, swept over the
/// edges until no metric changes (to 1e-6) or 100 sweeps. For h⁻²I metrics this is the scalar
/// H-correction of grade_vertex_sizes. Throws InputError when hgrad is not finite and >= 1.
void grade_vertex_metrics(const TetMesh& mesh, std::vector<Metric>& metrics, double hgrad);

/// The field at the mesh's vertices as a solution file holds it, for the next round as Mmg
/// writes OUT.sol: metrics (a tensor solution, Medit's order) when anisotropic, else sizes.
Solutions field_at_vertices(const TetMesh& mesh, const SizeField& field);

}  // namespace hdimesh::volume
