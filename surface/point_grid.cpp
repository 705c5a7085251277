#include "surface/point_grid.h"

#include <algorithm>
#include <cmath>

namespace hdimesh::surface
{

PointGrid::PointGrid(const std::vector<Vec3d>& points, double cell) : points_(&points), cell_(cell)
{
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        const Vec3d& p = points[i];
        cells_[key(coordinate(p[0]), coordinate(p[1]), coordinate(p[2]))].push_back(i);
    }
}

std::int64_t PointGrid::coordinate(double x) const { return static_cast<std::int64_t>(std::floor(x / cell_)); }

std::int64_t PointGrid::key(std::int64_t i, std::int64_t j, std::int64_t k) const
{
    // 21 bits per axis (cells wrap beyond ±2^20: only more points to filter, never fewer).
    constexpr std::int64_t mask = (std::int64_t(1) << 21) - 1;
    return ((i & mask) << 42) | ((j & mask) << 21) | (k & mask);
}

std::vector<std::size_t> PointGrid::within(const Vec3d& p, double radius) const
{
    std::vector<std::size_t> found;
    if (empty() || !(radius >= 0.0)) return found;
    const double r2 = radius * radius;
    const std::int64_t lo[3] = {coordinate(p[0] - radius), coordinate(p[1] - radius), coordinate(p[2] - radius)};
    const std::int64_t hi[3] = {coordinate(p[0] + radius), coordinate(p[1] + radius), coordinate(p[2] + radius)};
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
            for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
            {
                const auto it = cells_.find(key(i, j, k));
                if (it == cells_.end()) continue;
                for (const std::size_t index : it->second)
                    if (((*points_)[index] - p).sqrnorm() <= r2) found.push_back(index);
            }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
}

}  // namespace hdimesh::surface
