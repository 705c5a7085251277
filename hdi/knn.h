#pragma once
// Exact k-nearest-neighbour search over a fixed set of 3-D points (a single kd-tree).
// FLANN stays behind this header: only Eigen types and plain arrays cross it.

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace hdimesh::hdi
{

struct Neighbour
{
    int index = -1;                 ///< index of the point in the indexed set
    double squared_distance = 0.0;  ///< squared Euclidean distance to the query
};

class KnnIndex
{
public:
    /// Indexes a copy of the points. An empty set is allowed (every query then finds nothing).
    explicit KnnIndex(const std::vector<Eigen::Vector3d>& points);
    ~KnnIndex();
    KnnIndex(KnnIndex&&) noexcept;
    KnnIndex& operator=(KnnIndex&&) noexcept;
    KnnIndex(const KnnIndex&) = delete;
    KnnIndex& operator=(const KnnIndex&) = delete;

    int size() const;
    const Eigen::Vector3d& point(int index) const;

    /// The min(k, size()) nearest points, nearest first: fills indices[0..n) and
    /// squared_distances[0..n) (caller-owned, at least k long) and returns n. Exact search.
    /// Thread-safe; allocates nothing of its own (the projection's hot path).
    int nearest(const Eigen::Vector3d& query, int k, int* indices, double* squared_distances) const;

    /// Convenience form of nearest() returning a vector.
    std::vector<Neighbour> nearest(const Eigen::Vector3d& query, int k) const;

    /// Every point within `radius` (inclusive) of the query, nearest first.
    std::vector<Neighbour> within_radius(const Eigen::Vector3d& query, double radius) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace hdimesh::hdi
