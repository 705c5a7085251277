// hdi::KnnIndex against brute force: exact k nearest (order and distances), radius search, and
// the degenerate sets (empty, k larger than the set, duplicate points).

#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "hdi/knn.h"

using hdimesh::hdi::KnnIndex;
using hdimesh::hdi::Neighbour;
using Vec3 = Eigen::Vector3d;

namespace
{

std::vector<Vec3> random_points(int count, std::uint32_t seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    std::vector<Vec3> points(static_cast<std::size_t>(count));
    for (Vec3& p : points)
        p = Vec3(coordinate(random), coordinate(random), 0.3 * coordinate(random));
    return points;
}

std::vector<double> brute_force_squared_distances(const std::vector<Vec3>& points,
                                                  const Vec3& query)
{
    std::vector<double> d2;
    for (const Vec3& p : points) d2.push_back((p - query).squaredNorm());
    std::sort(d2.begin(), d2.end());
    return d2;
}

}  // namespace

TEST_CASE("knn: the k nearest agree with brute force, nearest first")
{
    const std::vector<Vec3> points = random_points(3000, 7);
    const KnnIndex index(points);
    REQUIRE(index.size() == 3000);
    const std::vector<Vec3> queries = random_points(200, 11);
    for (int k : {1, 5, 16, 40})
    {
        for (const Vec3& q : queries)
        {
            const std::vector<Neighbour> found = index.nearest(q, k);
            REQUIRE(static_cast<int>(found.size()) == k);
            const std::vector<double> expected = brute_force_squared_distances(points, q);
            for (int i = 0; i < k; ++i)
            {
                const Neighbour& n = found[static_cast<std::size_t>(i)];
                CHECK(n.squared_distance ==
                      doctest::Approx(expected[static_cast<std::size_t>(i)]).epsilon(1e-12));
                // The reported distance is the distance of the reported point.
                CHECK(n.squared_distance ==
                      doctest::Approx((points[static_cast<std::size_t>(n.index)] - q).squaredNorm())
                          .epsilon(1e-12));
                if (i > 0)
                    CHECK(found[static_cast<std::size_t>(i - 1)].squared_distance <=
                          n.squared_distance);
            }
        }
    }
}

TEST_CASE("knn: radius search returns exactly the points inside the ball")
{
    const std::vector<Vec3> points = random_points(2000, 3);
    const KnnIndex index(points);
    const std::vector<Vec3> queries = random_points(50, 5);
    for (const Vec3& q : queries)
    {
        const double radius = 0.2;
        const std::vector<Neighbour> found = index.within_radius(q, radius);
        std::vector<int> expected;
        for (std::size_t i = 0; i < points.size(); ++i)
            if ((points[i] - q).norm() <= radius) expected.push_back(static_cast<int>(i));
        std::vector<int> got;
        for (const Neighbour& n : found) got.push_back(n.index);
        std::sort(got.begin(), got.end());
        CHECK(got == expected);
        for (std::size_t i = 1; i < found.size(); ++i)
            CHECK(found[i - 1].squared_distance <= found[i].squared_distance);
    }
}

TEST_CASE("knn: empty set, k beyond the set, duplicate points")
{
    const KnnIndex empty(std::vector<Vec3>{});
    CHECK(empty.size() == 0);
    CHECK(empty.nearest(Vec3::Zero(), 4).empty());
    CHECK(empty.within_radius(Vec3::Zero(), 1.0).empty());

    //   three copies of (0,0,0) and one (1,0,0): all four found, the copies first at distance 0
    const std::vector<Vec3> points{Vec3::Zero(), Vec3(1, 0, 0), Vec3::Zero(), Vec3::Zero()};
    const KnnIndex index(points);
    const std::vector<Neighbour> found = index.nearest(Vec3(0.1, 0, 0), 10);
    REQUIRE(found.size() == 4);
    CHECK(found[3].index == 1);
    for (int i = 0; i < 3; ++i)
        CHECK(found[static_cast<std::size_t>(i)].squared_distance == doctest::Approx(0.01));
    int indices[2];
    double d2[2];
    CHECK(index.nearest(Vec3(0.9, 0, 0), 1, indices, d2) == 1);
    CHECK(indices[0] == 1);
    CHECK(index.point(1) == Vec3(1, 0, 0));
}
