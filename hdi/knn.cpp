// The only file of the project that includes FLANN. One exact kd-tree (KDTreeSingleIndex, which
// never approximates), searched through result sets that write straight into the caller's buffers
// so a query allocates nothing of ours.

#include "hdi/knn.h"

#include <algorithm>
#include <cassert>
#include <flann/flann.hpp>
#include <limits>

namespace hdimesh::hdi
{

namespace
{

using Distance = flann::L2_3D<double>;  // squared Euclidean distance, unrolled for 3-D
using Tree = flann::KDTreeSingleIndex<Distance>;

/// Keeps the `capacity` nearest points seen so far, sorted, in caller-owned arrays.
class BufferResultSet final : public flann::ResultSet<double>
{
public:
    BufferResultSet(int capacity, int* indices, double* squared_distances)
        : capacity_(capacity), indices_(indices), squared_distances_(squared_distances)
    {
    }

    bool full() const override { return count_ == capacity_; }
    double worstDist() const override { return worst_; }

    void addPoint(double squared_distance, size_t index) override
    {
        if (squared_distance >= worst_) return;
        int slot = count_ < capacity_ ? count_++ : capacity_ - 1;
        while (slot > 0 && squared_distances_[slot - 1] > squared_distance)
        {
            squared_distances_[slot] = squared_distances_[slot - 1];
            indices_[slot] = indices_[slot - 1];
            --slot;
        }
        squared_distances_[slot] = squared_distance;
        indices_[slot] = static_cast<int>(index);
        if (count_ == capacity_) worst_ = squared_distances_[capacity_ - 1];
    }

    int count() const { return count_; }

private:
    int capacity_;
    int* indices_;
    double* squared_distances_;
    int count_ = 0;
    double worst_ = std::numeric_limits<double>::infinity();
};

/// Collects every point within a fixed squared radius.
class RadiusResultSet final : public flann::ResultSet<double>
{
public:
    explicit RadiusResultSet(double squared_radius) : squared_radius_(squared_radius) {}

    bool full() const override { return true; }
    double worstDist() const override { return squared_radius_; }
    void addPoint(double squared_distance, size_t index) override
    {
        if (squared_distance <= squared_radius_)
            found.push_back({static_cast<int>(index), squared_distance});
    }

    std::vector<Neighbour> found;

private:
    double squared_radius_;
};

}  // namespace

struct KnnIndex::Impl
{
    std::vector<Eigen::Vector3d> points;
    std::vector<double> coordinates;  // points as a row-major n x 3 array, FLANN's input
    std::unique_ptr<Tree> tree;
};

KnnIndex::KnnIndex(const std::vector<Eigen::Vector3d>& points) : impl_(std::make_unique<Impl>())
{
    impl_->points = points;
    if (points.empty()) return;
    impl_->coordinates.resize(3 * points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
        for (int d = 0; d < 3; ++d) impl_->coordinates[3 * i + d] = points[i][d];
    flann::Matrix<double> dataset(impl_->coordinates.data(), points.size(), 3);
    // Leaves of 16 points: the model asks for ~16 neighbours, so a few leaves answer a query.
    impl_->tree = std::make_unique<Tree>(dataset, flann::KDTreeSingleIndexParams(16, true));
    impl_->tree->buildIndex();
}

KnnIndex::~KnnIndex() = default;
KnnIndex::KnnIndex(KnnIndex&&) noexcept = default;
KnnIndex& KnnIndex::operator=(KnnIndex&&) noexcept = default;

int KnnIndex::size() const { return static_cast<int>(impl_->points.size()); }

const Eigen::Vector3d& KnnIndex::point(int index) const
{
    assert(index >= 0 && index < size());
    return impl_->points[static_cast<std::size_t>(index)];
}

int KnnIndex::nearest(const Eigen::Vector3d& query, int k, int* indices,
                      double* squared_distances) const
{
    k = std::min(k, size());
    if (k <= 0) return 0;
    BufferResultSet result(k, indices, squared_distances);
    impl_->tree->findNeighbors(result, query.data(),
                               flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED, 0.0f));
    return result.count();
}

std::vector<Neighbour> KnnIndex::nearest(const Eigen::Vector3d& query, int k) const
{
    k = std::max(0, std::min(k, size()));
    std::vector<int> indices(static_cast<std::size_t>(k));
    std::vector<double> squared_distances(static_cast<std::size_t>(k));
    const int found = nearest(query, k, indices.data(), squared_distances.data());
    std::vector<Neighbour> result(static_cast<std::size_t>(found));
    for (int i = 0; i < found; ++i)
        result[static_cast<std::size_t>(i)] = {indices[i], squared_distances[i]};
    return result;
}

std::vector<Neighbour> KnnIndex::within_radius(const Eigen::Vector3d& query, double radius) const
{
    if (size() == 0 || radius < 0) return {};
    RadiusResultSet result(radius * radius);
    impl_->tree->findNeighbors(result, query.data(),
                               flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED, 0.0f));
    std::sort(result.found.begin(), result.found.end(), [](const Neighbour& a, const Neighbour& b) {
        return a.squared_distance < b.squared_distance ||
               (a.squared_distance == b.squared_distance && a.index < b.index);
    });
    return std::move(result.found);
}

}  // namespace hdimesh::hdi
