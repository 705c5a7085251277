// The feature set the HDI model takes (detect_features: ridges by dihedral angle, the
// chain-length robustness rule, corners, open boundaries), feature chains and smooth patches, and
// the model's use of them: each side of a ridge fitted apart, points on a feature line projected
// onto its 1-D fit. The detector's own rules: tests/features_test.cpp.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "common/errors.h"
#include "hdi/features.h"
#include "hdi/hdi_surface.h"
#include "hdi/obj_reader.h"
#include "tests/fixtures.h"

using namespace hdimesh::hdi;
using hdimesh::InputError;
using hdimesh::IoError;

namespace
{

constexpr double pi = 3.14159265358979323846;

using Surface = hdimesh::fixtures::GridSurface;
using hdimesh::fixtures::grid_cube;

/// Two unit squares folded at 90 degrees along the line x = 1, z = 0 (an open "book").
///        B (x = 1, z in [0,1])
///        |
///        |
///  A ----+   (z = 0, x in [0,1])       fold: x = 1, z = 0, y in [0,1]
Surface fold(int n)
{
    Surface s;
    s.add_grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), n, n);  // A, normal +z
    s.add_grid(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), n, n);  // B, normal +x
    return s;
}

std::set<int> vertex_set(const std::vector<std::array<int, 2>>& edges)
{
    std::set<int> v;
    for (const auto& e : edges) v.insert({e[0], e[1]});
    return v;
}

}  // namespace

TEST_CASE("features: a cube's 12 edges are ridges, its 8 vertices corners, its 6 faces patches")
{
    const int n = 4;
    const Surface s = grid_cube(n);
    REQUIRE(s.points.size() == static_cast<std::size_t>(6 * n * n + 2));  // Euler: V = E - F + 2
    const FeatureSet f = detect_features(s.points, s.triangles);
    CHECK(f.ridge_edges.size() == static_cast<std::size_t>(12 * n));
    CHECK(f.boundary_edges.empty());
    REQUIRE(f.corners.size() == 8);
    for (int c : f.corners)
    {
        const Vec3& p = s.points[static_cast<std::size_t>(c)];
        for (int d = 0; d < 3; ++d) CHECK((p[d] == 0.0 || p[d] == 1.0));
    }
    // Every ridge edge lies on a cube edge: two of its coordinates are 0 or 1 at both ends.
    for (const auto& e : f.ridge_edges)
    {
        int on_cube_edge = 0;
        for (int d = 0; d < 3; ++d)
        {
            const double a = s.points[static_cast<std::size_t>(e[0])][d],
                         b = s.points[static_cast<std::size_t>(e[1])][d];
            if (a == b && (a == 0.0 || a == 1.0)) ++on_cube_edge;
        }
        CHECK(on_cube_edge == 2);
    }
    const std::vector<FeatureChain> chains = feature_chains(f, static_cast<int>(s.points.size()));
    CHECK(chains.size() == 12);
    for (const FeatureChain& c : chains)
    {
        CHECK_FALSE(c.closed);
        CHECK(c.vertices.size() == static_cast<std::size_t>(n + 1));
        CHECK(std::binary_search(f.corners.begin(), f.corners.end(), c.vertices.front()));
        CHECK(std::binary_search(f.corners.begin(), f.corners.end(), c.vertices.back()));
    }
    const std::vector<int> patch = smooth_patches(s.triangles, f);
    CHECK(std::set<int>(patch.begin(), patch.end()).size() == 6);
    // Ridges can be switched off; a closed cube then has no ridge, and its 8 vertices are
    // isolated spikes (angle defect 90 degrees, angle sum 270): corners still.
    FeatureOptions off;
    off.detect_ridges = false;
    const FeatureSet none = detect_features(s.points, s.triangles, off);
    CHECK(none.ridge_edges.empty());
    CHECK(none.corners == f.corners);
    // A ridge (and crease) angle above 90 degrees sees no cube edge.
    FeatureOptions obtuse;
    obtuse.ridge_angle_deg = 100;
    obtuse.crease_angle_deg = 100;
    CHECK(detect_features(s.points, s.triangles, obtuse).ridge_edges.empty());
}

TEST_CASE("features: an isolated crease (a spike of noise) is not a ridge")
{
    // A flat 150 x 150 grid (spacing h = 1/150) with one interior vertex lifted by h: a spike of
    // scan noise. Its sharp edges (a ring and a star of 6 edges around the lifted vertex) are each
    // a few h long, far below 5 % of the diagonal, and link no ridges: noise.
    //   . . . . .
    //   . . ^ . .     ^: lifted vertex
    //   . . . . .
    const int cells = 150;
    Surface s;
    s.add_grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), cells, cells);
    const int lifted = s.add(Vec3(0.5, 0.5, 0));
    s.points[static_cast<std::size_t>(lifted)].z() = 1.0 / cells;
    FeatureOptions keep_all;
    keep_all.min_ridge_length = 0;
    const FeatureSet raw = detect_features(s.points, s.triangles, keep_all);
    REQUIRE(!raw.ridge_edges.empty());  // the spike's edges are sharp at 45 degrees
    const FeatureSet f = detect_features(s.points, s.triangles);
    CHECK(f.ridge_edges.empty());
    // The open boundary is a feature: 4 x 150 edges, and a corner wherever it turns by 90 degrees.
    // The spike's tip, its creases gone, is an isolated cone: kept as a corner.
    CHECK(f.boundary_edges.size() == static_cast<std::size_t>(4 * cells));
    CHECK(f.corners.size() == 5);
    CHECK(std::binary_search(f.corners.begin(), f.corners.end(), lifted));
    // A triangle with flipped orientation is not mistaken for a crease.
    Surface flat;
    flat.add_grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 6, 6);
    std::swap(flat.triangles[20][1], flat.triangles[20][2]);
    CHECK(detect_features(flat.points, flat.triangles).ridge_edges.empty());
}

TEST_CASE("features: a fold - the ridge meets the boundary at corners; each side is fitted apart")
{
    const int n = 8;
    const Surface s = fold(n);
    const FeatureSet f = detect_features(s.points, s.triangles);
    REQUIRE(f.ridge_edges.size() == static_cast<std::size_t>(n));
    for (int v : vertex_set(f.ridge_edges))
    {
        CHECK(s.points[static_cast<std::size_t>(v)].x() == 1.0);
        CHECK(s.points[static_cast<std::size_t>(v)].z() == 0.0);
    }
    CHECK(f.boundary_edges.size() == static_cast<std::size_t>(6 * n));
    CHECK(f.corners.size() == 6);  // 2 where the fold meets the boundary, 4 square corners

    const HdiSurface model(s.points, s.triangles, f);
    for (int c : f.corners) CHECK(model.is_corner(c));
    CHECK_FALSE(model.is_corner(static_cast<int>(s.points.size())));  // out of range: not a corner
    // Just above face A, a hair from the fold (nearer A than B): projected onto plane A exactly,
    // B's nodes unused.
    for (double gap : {0.002, 0.02, 0.1})
    {
        const Projection p = model.project(Vec3(1 - gap, 0.43, 0.2 * gap));
        REQUIRE(p.status == ProjectionStatus::Ok);
        CHECK(std::abs(p.point.z()) < 1e-12);
        CHECK((p.normal - Vec3(0, 0, 1)).norm() < 1e-12);
        // Beside face B likewise.
        const Projection q = model.project(Vec3(1 + 0.2 * gap, 0.57, gap));
        REQUIRE(q.status == ProjectionStatus::Ok);
        CHECK(std::abs(q.point.x() - 1) < 1e-12);
        CHECK((q.normal - Vec3(1, 0, 0)).norm() < 1e-12);
    }
    // Near the fold: onto the fold line, exactly (a straight polyline).
    const Projection r = model.project_to_ridge(Vec3(0.97, 0.61, 0.04));
    REQUIRE(r.status == ProjectionStatus::Ok);
    CHECK((r.point - Vec3(1, 0.61, 0)).norm() < 1e-12);
    CHECK(std::abs(std::abs(r.tangent.y()) - 1) < 1e-12);
    CHECK(r.k1 < 1e-9);
    // Past the end of the fold: stops at its end corner.
    const Projection end = model.project_to_ridge(Vec3(1.0, -0.02, 0.0));
    CHECK((end.point - Vec3(1, 0, 0)).norm() < 1e-12);
}

TEST_CASE("features: an open tube's rims are closed feature lines; rim points land on the circle")
{
    // A cylinder of radius 1, 32 segments around, 6 rings: two boundary loops without corners.
    const int around = 32, rings = 6;
    Surface s;
    for (int r = 0; r < rings; ++r)
        for (int i = 0; i < around; ++i)
            s.points.emplace_back(std::cos(2 * pi * i / around), std::sin(2 * pi * i / around),
                                  0.2 * r);
    for (int r = 0; r + 1 < rings; ++r)
        for (int i = 0; i < around; ++i)
        {
            const int a = r * around + i, b = r * around + (i + 1) % around;
            s.triangles.push_back({a, b, b + around});
            s.triangles.push_back({a, b + around, a + around});
        }
    const FeatureSet f = detect_features(s.points, s.triangles);
    CHECK(f.ridge_edges.empty());
    CHECK(f.boundary_edges.size() == static_cast<std::size_t>(2 * around));
    CHECK(f.corners.empty());
    const std::vector<FeatureChain> chains = feature_chains(f, static_cast<int>(s.points.size()));
    REQUIRE(chains.size() == 2);
    for (const FeatureChain& c : chains)
    {
        CHECK(c.closed);
        CHECK(c.vertices.size() == static_cast<std::size_t>(around));
    }
    // The model adds the open boundary by itself, even from an empty feature set.
    const HdiSurface model(s.points, s.triangles, FeatureSet{});
    CHECK(model.features().boundary_edges.size() == static_cast<std::size_t>(2 * around));
    double worst = 0;
    for (int k = 0; k < 64; ++k)
    {
        const double angle = 2 * pi * (k + 0.37) / 64;
        const Vec3 x(1.01 * std::cos(angle), 1.01 * std::sin(angle), 0.01);
        const Projection p = model.project_to_ridge(x);
        REQUIRE(p.status == ProjectionStatus::Ok);
        worst = std::max(
            worst, std::abs(std::hypot(p.point.x(), p.point.y()) - 1.0) + std::abs(p.point.z()));
        CHECK(p.k1 == doctest::Approx(1.0).epsilon(0.05));  // a unit circle
    }
    MESSAGE("tube rim (32 segments): max distance of projected rim points from the circle "
            << worst);
    // The polyline's own chord sagitta is 1 - cos(pi/32) = 4.8e-3; the 1-D fit does far better.
    CHECK(worst < 2e-4);
}

TEST_CASE("features: fandisk's ridge network survives the noise rule whole")
{
    const TriangleSurface input = read_obj(hdimesh::fixtures::data_path("fandisk.obj"));
    FeatureOptions keep_all;
    keep_all.min_ridge_length = 0;
    const FeatureSet raw = detect_features(input.points, input.triangles, keep_all);
    const FeatureSet f = detect_features(input.points, input.triangles);
    MESSAGE("fandisk: " << f.ridge_edges.size() << " ridge edges, " << f.corners.size()
                        << " corners, "
                        << feature_chains(f, static_cast<int>(input.points.size())).size()
                        << " ridge lines");
    CHECK(f.ridge_edges == raw.ridge_edges);  // no fandisk ridge is noise
    CHECK(f.ridge_edges.size() == 722);  // the 45-degree ridges and the long 30-45 degree creases
    CHECK(f.boundary_edges.empty());
    CHECK(f.corners.size() == 25);  // 22 junctions of three ridges, 2 ridge ends, 1 sharp turn
}

TEST_CASE("features: bad indices are rejected with the triangle named")
{
    const std::vector<Vec3> points{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    const std::vector<Triangle3> triangles{{0, 1, 3}};
    CHECK_THROWS_AS(detect_features(points, triangles), InputError);
    CHECK_THROWS_WITH_AS(HdiSurface(points, triangles, FeatureSet{}),
                         doctest::Contains("triangle 0"), InputError);
    FeatureSet bad;
    bad.corners = {7};
    CHECK_THROWS_AS(HdiSurface(points, {{0, 1, 2}}, bad), InputError);
    HdiOptions options;
    options.neighbours = 1;
    CHECK_THROWS_AS(HdiSurface(points, {{0, 1, 2}}, FeatureSet{}, options), InputError);
}
