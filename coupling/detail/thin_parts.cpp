// Thin parts: sizes bounded by the thickness, on the surface and in the volume.
#include "coupling/detail/thin_parts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hdi/knn.h"
#include "surface/thickness.h"

namespace hdimesh::coupling::detail
{

ThinParts find_thin_parts(const surface::SurfaceMesh& input, const std::vector<double>& sizes,
                          double grade, const ThinPartOptions& options)
{
    ThinParts thin;
    surface::ThicknessOptions rays;
    rays.workers = options.workers;
    const std::vector<double> thickness = surface::thickness_at_vertices(input, rays);
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

namespace
{

constexpr int kNearest = 8;              // bounded vertices giving a cell's first upper bound
constexpr double kCellsPerPoint = 16.0;  // grid cells per bounded vertex ...
constexpr long kMaxCells = 1L << 18;     // ... and at most this many (memory)

}  // namespace

ThinPartSize::ThinPartSize(std::shared_ptr<const SizeField> base, const ThinParts& thin,
                           double grade, Workers* workers)
    : base_(std::move(base)), points_(thin.points), sizes_(thin.sizes), grade_(grade)
{
    if (points_.empty() || !(grade_ > 0)) return;
    Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
    lo_ = -hi;
    for (const Vec3& p : points_)
    {
        lo_ = lo_.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    lo_ -= Vec3::Constant(thin.reach);
    hi += Vec3::Constant(thin.reach);
    const Vec3 extent = (hi - lo_).cwiseMax(Vec3::Constant(1e-12 * (hi - lo_).norm() + 1e-300));
    const double target = std::min(kCellsPerPoint * points_.size(), double(kMaxCells));
    cell_ = std::cbrt(extent.prod() / std::max(target, 1.0));
    auto count_cells = [&] {
        for (int k = 0; k < 3; ++k)
            n_[k] = static_cast<int>(std::min(std::ceil(extent[k] / cell_), double(kMaxCells)));
        for (int& n : n_) n = std::max(n, 1);
        return static_cast<double>(n_[0]) * n_[1] * n_[2];
    };
    while (count_cells() > kMaxCells) cell_ *= 1.25;

    // a cell's candidates: the vertices whose least over the cell is at most the least upper
    // bound any vertex gives over it (U); only they can give the least at a point in it
    const hdi::KnnIndex index(points_);
    const double smallest = *std::min_element(sizes_.begin(), sizes_.end());
    const double half_diagonal = 0.5 * std::sqrt(3.0) * cell_;
    // each cell's list is its own (the index answers const queries from any thread); the
    // lists joined in cell order: the same arrays on any number of threads
    const std::size_t num_cells = static_cast<std::size_t>(n_[0]) * n_[1] * n_[2];
    std::vector<std::vector<std::pair<double, int>>> cells(num_cells);
    parallel_for(workers, num_cells, [&](std::size_t first, std::size_t last) {
        int nearest[kNearest];
        double squared[kNearest];
        for (std::size_t c = first; c < last; ++c)
        {
            const int x = static_cast<int>(c % n_[0]), y = static_cast<int>(c / n_[0] % n_[1]),
                      z = static_cast<int>(c / n_[0] / n_[1]);
            const Vec3 centre = lo_ + cell_ * Vec3(x + 0.5, y + 0.5, z + 0.5);
            const int n = index.nearest(centre, kNearest, nearest, squared);
            double upper = std::numeric_limits<double>::infinity();
            for (int k = 0; k < n; ++k)
                upper = std::min(
                    upper, sizes_[nearest[k]] + grade_ * (std::sqrt(squared[k]) + half_diagonal));
            const double radius = (upper - smallest) / grade_ + half_diagonal;
            auto& cell = cells[c];
            for (const hdi::Neighbour& near : index.within_radius(centre, radius))
            {
                const double lower =
                    sizes_[near.index] +
                    grade_ * std::max(0.0, std::sqrt(near.squared_distance) - half_diagonal);
                if (lower <= upper) cell.push_back({lower, near.index});
            }
            std::sort(cell.begin(), cell.end());  // least first: a lookup stops early
        }
    });
    start_.reserve(num_cells + 1);
    start_.push_back(0);
    for (auto& cell : cells)
    {
        for (const auto& [lower, v] : cell)
        {
            candidates_.push_back(v);
            lower_.push_back(lower);
        }
        start_.push_back(static_cast<int>(candidates_.size()));
        std::vector<std::pair<double, int>>().swap(cell);
    }
}

double ThinPartSize::size(const Vec3& p) const
{
    const double base = base_->size(p);
    if (start_.empty()) return base;
    int cell = 0;
    for (int k = 2; k >= 0; --k)
    {
        const double at = std::floor((p[k] - lo_[k]) / cell_);
        if (!(at >= 0 && at < n_[k])) return base;  // outside every bound's reach (or NaN)
        cell = cell * n_[k] + static_cast<int>(at);
    }
    double size = base;
    for (int i = start_[cell]; i < start_[cell + 1] && lower_[i] < size; ++i)
    {
        const int v = candidates_[i];
        size = std::min(size, sizes_[v] + grade_ * (p - points_[v]).norm());
    }
    return size;
}

}  // namespace hdimesh::coupling::detail
