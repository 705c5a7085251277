// Thin parts: sizes bounded by the thickness, on the surface and in the volume.
#include "coupling/detail/thin_parts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surface/thickness.h"

namespace hdimesh::coupling::detail
{

ThinParts find_thin_parts(const surface::SurfaceMesh& input, const std::vector<double>& sizes,
                          double grade, const ThinPartOptions& options)
{
    ThinParts thin;
    const std::vector<double> thickness = surface::thickness_at_vertices(input);
    std::vector<double> bounds(input.n_vertices(), std::numeric_limits<double>::infinity());
    for (auto v : input.vertices())
    {
        const int i = v.idx();
        const double wanted = sizes[i];
        const double allowed = thickness[i] / options.thickness_per_size;
        if (!(allowed < wanted)) continue;
        bounds[i] = std::max(allowed, options.min_fraction * wanted);
        thin.points.push_back(surface::to_point(input.point(v)));
        thin.sizes.push_back(bounds[i]);
        thin.reach = std::max(thin.reach, grade > 0 ? (wanted - bounds[i]) / grade : 0.0);
    }
    if (!thin.points.empty()) thin.bounds = std::move(bounds);
    return thin;
}

ThinPartSize::ThinPartSize(std::shared_ptr<const SizeField> base, const ThinParts& thin,
                           double grade)
    : base_(std::move(base)), index_(thin.points), sizes_(thin.sizes), grade_(grade)
{
    lo_ = Vec3::Constant(std::numeric_limits<double>::infinity());
    hi_ = -lo_;
    for (const Vec3& p : thin.points)
    {
        lo_ = lo_.cwiseMin(p);
        hi_ = hi_.cwiseMax(p);
    }
    lo_ -= Vec3::Constant(thin.reach);
    hi_ += Vec3::Constant(thin.reach);
    smallest_ = sizes_.empty() ? 0.0 : *std::min_element(sizes_.begin(), sizes_.end());
}

double ThinPartSize::size(const Vec3& p) const
{
    const double base = base_->size(p);
    if ((p.array() < lo_.array()).any() || (p.array() > hi_.array()).any()) return base;
    // no bound reaches below base when even the smallest, grown from the nearest, does not:
    // the same answer as the full search, for one neighbour instead of kNearest
    int nearest[kNearest];
    double squared[kNearest];
    if (index_.nearest(p, 1, nearest, squared) == 0 ||
        smallest_ + grade_ * std::sqrt(squared[0]) >= base)
        return base;
    const int n = index_.nearest(p, kNearest, nearest, squared);
    double size = base;
    for (int k = 0; k < n; ++k)
        size = std::min(size, sizes_[nearest[k]] + grade_ * std::sqrt(squared[k]));
    return size;
}

}  // namespace hdimesh::coupling::detail
