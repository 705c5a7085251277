#include "surface/detail/point_grid.h"

#include <algorithm>
#include <cmath>

namespace hdimesh::surface
{

PointGrid::PointGrid(const std::vector<Vec3d>& points, double cell) : cell_(cell)
{
    std::size_t slots = 16;
    shift_ = 60;
    while (slots < 2 * points.size()) slots *= 2, --shift_;
    slot_key_.assign(slots, 0);
    slot_cell_.assign(slots, -1);
    // Each point's cell (numbered in order of first appearance), and the cells' sizes.
    std::vector<int> cell_of(points.size());
    std::vector<std::size_t> count;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        const Vec3d& p = points[i];
        const std::int64_t k = key(coordinate(p[0]), coordinate(p[1]), coordinate(p[2]));
        const std::size_t slot = slot_of(k);
        if (slot_cell_[slot] < 0)
        {
            slot_key_[slot] = k;
            slot_cell_[slot] = static_cast<int>(count.size());
            count.push_back(0);
        }
        cell_of[i] = slot_cell_[slot];
        ++count[cell_of[i]];
    }
    cell_first_.assign(count.size() + 1, 0);
    for (std::size_t c = 0; c < count.size(); ++c) cell_first_[c + 1] = cell_first_[c] + count[c];
    std::vector<std::size_t> next(cell_first_.begin(), cell_first_.end() - 1);
    points_.resize(points.size());
    indices_.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        const std::size_t at = next[cell_of[i]]++;
        points_[at] = points[i];
        indices_[at] = i;
    }
}

std::vector<std::size_t> PointGrid::within(const Vec3d& p, double radius) const
{
    std::vector<std::size_t> found;
    if (empty() || !(radius >= 0.0)) return found;
    const double r2 = radius * radius;
    const std::int64_t lo[3] = {coordinate(p[0] - radius), coordinate(p[1] - radius),
                                coordinate(p[2] - radius)};
    const std::int64_t hi[3] = {coordinate(p[0] + radius), coordinate(p[1] + radius),
                                coordinate(p[2] + radius)};
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
            for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
            {
                const int c = slot_cell_[slot_of(key(i, j, k))];
                if (c < 0) continue;
                for (std::size_t at = cell_first_[c]; at < cell_first_[c + 1]; ++at)
                    if ((points_[at] - p).sqrnorm() <= r2) found.push_back(indices_[at]);
            }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
}

}  // namespace hdimesh::surface
