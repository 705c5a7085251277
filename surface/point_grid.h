#pragma once
// A uniform hash grid over a fixed set of points answering "which points lie within r of p":
// the refinement's snap asks it for the model points around a vertex's star (the points a move
// of that vertex may bring nearer to, or take away from, the output).

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

class PointGrid
{
public:
    PointGrid() = default;
    /// `cell` > 0: the edge of a grid cell (queries of radius about `cell` open 27 cells; a
    /// radius r opens (2r/cell + 1)³). The grid keeps a pointer to `points`, which must outlive
    /// it unchanged: not copyable, so a copy cannot outlive them by accident.
    PointGrid(const std::vector<Vec3d>& points, double cell);
    PointGrid(const PointGrid&) = delete;
    PointGrid& operator=(const PointGrid&) = delete;

    /// Indices (in the order given) of the points within `radius` of p, in increasing order.
    std::vector<std::size_t> within(const Vec3d& p, double radius) const;
    bool empty() const { return points_ == nullptr || points_->empty(); }

private:
    std::int64_t key(std::int64_t i, std::int64_t j, std::int64_t k) const;
    std::int64_t coordinate(double x) const;

    const std::vector<Vec3d>* points_ = nullptr;
    double cell_ = 1.0;
    std::unordered_map<std::int64_t, std::vector<std::size_t>> cells_;
};

}  // namespace hdimesh::surface
