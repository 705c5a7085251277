#pragma once
// A uniform hash grid over a fixed set of points answering "which points lie within r of p":
// the refinement's snap asks it for the model points around a vertex's star (the points a move
// of that vertex may bring nearer to, or take away from, the output).

#include <cmath>
#include <cstdint>
#include <vector>

#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

class PointGrid
{
public:
    PointGrid() = default;
    /// `cell` > 0: the edge of a grid cell (queries of radius about `cell` open 27 cells; a
    /// radius r opens (2r/cell + 1)³). The grid keeps its own copy of the points, in cell order.
    PointGrid(const std::vector<Vec3d>& points, double cell);

    /// Indices (in the order given) of the points within `radius` of p, in increasing order.
    std::vector<std::size_t> within(const Vec3d& p, double radius) const;
    bool empty() const { return points_.empty(); }

private:
    // (Inline: a query asks them for each of its 27 to 64 cells.)
    std::int64_t coordinate(double x) const
    {
        return static_cast<std::int64_t>(std::floor(x / cell_));
    }
    std::int64_t key(std::int64_t i, std::int64_t j, std::int64_t k) const
    {
        // 21 bits per axis (cells wrap beyond ±2^20: only more points to filter, never fewer).
        constexpr std::int64_t mask = (std::int64_t(1) << 21) - 1;
        return ((i & mask) << 42) | ((j & mask) << 21) | (k & mask);
    }
    // The slot of `key` in the open-addressed table: the key's own, or the empty one where it
    // would go.
    std::size_t slot_of(std::int64_t key) const
    {
        // Fibonacci hashing: the product's top bits.
        const std::size_t mask = slot_key_.size() - 1;
        std::size_t slot = static_cast<std::size_t>(
            (static_cast<std::uint64_t>(key) * 0x9e3779b97f4a7c15ULL) >> shift_);
        while (slot_cell_[slot] >= 0 && slot_key_[slot] != key) slot = (slot + 1) & mask;
        return slot;
    }

    double cell_ = 1.0;
    int shift_ = 60;  // 64 - log2(slots)
    // The cells with points, in an open-addressed table (linear probing; a power of two of
    // slots, at most half full): key and cell number (-1: an empty slot). A cell's points are
    // [cell_first_[c], cell_first_[c + 1]) of points_ / indices_, in increasing index: the
    // points of a query's cells are contiguous (an unordered_map of vectors costs a cache miss
    // per cell and per vector).
    std::vector<std::int64_t> slot_key_;
    std::vector<int> slot_cell_;
    std::vector<std::size_t> cell_first_;
    std::vector<Vec3d> points_;
    std::vector<std::size_t> indices_;
};

}  // namespace hdimesh::surface
