// The HDI model's accuracy: a plane and a paraboloid reproduced to round-off, the observed order
// of convergence on a sphere and a torus sampled at three resolutions, and fandisk (ridges,
// corners, thin parts) projected onto itself.

#include "hdi/hdi_surface.h"

#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <thread>
#include <vector>

#include "common/errors.h"
#include "hdi/features.h"
#include "hdi/obj_reader.h"
#include "tests/fixtures.h"

using namespace hdimesh::hdi;
using hdimesh::InputError;
using hdimesh::IoError;

namespace
{

constexpr double pi = 3.14159265358979323846;

using Surface = TriangleSurface;
using hdimesh::fixtures::icosphere;
using hdimesh::fixtures::mean_edge_length;

constexpr double torus_major = 1.0;
constexpr double torus_minor = 0.4;

/// Torus around z, an nu x nv parameter grid cut into triangles (outward normals).
Surface torus(int nu, int nv)
{
    Surface s;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j)
        {
            const double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
            s.points.emplace_back((torus_major + torus_minor * std::cos(v)) * std::cos(u),
                                  (torus_major + torus_minor * std::cos(v)) * std::sin(u),
                                  torus_minor * std::sin(v));
        }
    auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j)
        {
            s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return s;
}

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b)
{
    const Vec3 ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return a + t * ab;
}

/// Distance from p to the triangle abc, by brute force over its plane, edges and corners.
double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
    const Vec3 n = (b - a).cross(c - a).normalized();
    const Vec3 q = p - (p - a).dot(n) * n;  // in the plane
    const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                        (a - c).cross(q - c).dot(n) >= 0;
    if (inside) return std::abs((p - a).dot(n));
    return std::min({(p - closest_point_on_segment(p, a, b)).norm(),
                     (p - closest_point_on_segment(p, b, c)).norm(),
                     (p - closest_point_on_segment(p, c, a)).norm()});
}

/// Distance from p to the nearest triangle of s (brute force), and that triangle.
double distance_to_surface(const Vec3& p, const TriangleSurface& s, std::size_t* nearest = nullptr)
{
    double best = std::numeric_limits<double>::infinity();
    for (const Triangle3& t : s.triangles)
    {
        const Vec3& a = s.points[static_cast<std::size_t>(t[0])];
        // Cheap reject: the triangle's first corner is farther than its size plus the best so far.
        if ((p - a).norm() - (s.points[static_cast<std::size_t>(t[1])] - a).norm() -
                (s.points[static_cast<std::size_t>(t[2])] - a).norm() >
            best)
            continue;
        const double d = distance_to_triangle(p, a, s.points[static_cast<std::size_t>(t[1])],
                                              s.points[static_cast<std::size_t>(t[2])]);
        if (d < best)
        {
            best = d;
            if (nearest) *nearest = static_cast<std::size_t>(&t - s.triangles.data());
        }
    }
    return best;
}

double torus_distance(const Vec3& p)
{
    const double ring = std::hypot(p.x(), p.y()) - torus_major;
    return std::hypot(ring, p.z()) - torus_minor;
}

Vec3 torus_normal(const Vec3& p)
{
    const Vec3 centre = torus_major * Vec3(p.x(), p.y(), 0).normalized();
    return (p - centre).normalized();
}

/// Max |signed distance| after projecting points scattered within +-h/2 of the exact surface.
template <class Distance, class Normal>
double max_projection_error(const Surface& s, const HdiSurface& model, Distance distance,
                            Normal normal, std::uint32_t seed, int samples,
                            double* max_normal_error = nullptr)
{
    const double h = mean_edge_length(s);
    std::mt19937 random(seed);
    std::uniform_int_distribution<std::size_t> pick(0, s.triangles.size() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0, worst_normal = 0;
    for (int k = 0; k < samples; ++k)
    {
        const Triangle3& t = s.triangles[pick(random)];
        double a = unit(random), b = unit(random);
        if (a + b > 1) a = 1 - a, b = 1 - b;
        Vec3 p = (1 - a - b) * s.points[static_cast<std::size_t>(t[0])] +
                 a * s.points[static_cast<std::size_t>(t[1])] +
                 b * s.points[static_cast<std::size_t>(t[2])];
        p -= distance(p) * normal(p);  // onto the exact surface
        const Vec3 x = p + (unit(random) - 0.5) * h * normal(p);
        const Projection projection = model.project(x);
        REQUIRE(projection.status == ProjectionStatus::Ok);
        worst = std::max(worst, std::abs(distance(projection.point)));
        worst_normal =
            std::max(worst_normal, (projection.normal - normal(projection.point)).norm());
    }
    if (max_normal_error) *max_normal_error = worst_normal;
    return worst;
}

}  // namespace

TEST_CASE("hdi: a tilted plane is reproduced to round-off")
{
    // A jittered 12 x 12 grid on the plane z = 0.3x - 0.2y + 1, each cell cut into two triangles.
    //   +--+--+
    //   | /| /|
    //   |/ |/ |
    //   +--+--+
    std::mt19937 random(5);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    auto height = [](double x, double y) { return 0.3 * x - 0.2 * y + 1.0; };
    Surface s;
    const int n = 12;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
        {
            const double x = i + jitter(random), y = j + jitter(random);
            s.points.emplace_back(x, y, height(x, y));
        }
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j)
        {
            const int a = i * n + j, b = (i + 1) * n + j, c = (i + 1) * n + j + 1,
                      d = i * n + j + 1;
            s.triangles.push_back({a, b, c});
            s.triangles.push_back({a, c, d});
        }
    const Vec3 exact_normal = Vec3(-0.3, 0.2, 1.0).normalized();
    for (auto weight : {HdiOptions::Weight::QuarticSpline, HdiOptions::Weight::Gaussian,
                        HdiOptions::Weight::Interpolating})
    {
        HdiOptions options;
        options.weight = weight;
        const HdiSurface model(s.points, s.triangles, FeatureSet{}, options);
        std::uniform_real_distribution<double> inside(2.0, n - 3.0), off(-2.0, 2.0);
        for (int k = 0; k < 200; ++k)
        {
            const double x = inside(random), y = inside(random);
            const Vec3 query = Vec3(x, y, height(x, y)) + off(random) * exact_normal;
            const Projection p = model.project(query);
            REQUIRE(p.status == ProjectionStatus::Ok);
            CHECK(std::abs((p.point - Vec3(0, 0, 1)).dot(exact_normal)) < 1e-12);
            // On a plane the projection is orthogonal: the point moves along the normal only.
            CHECK(((p.point - query) - (p.point - query).dot(exact_normal) * exact_normal).norm() <
                  1e-12);
            CHECK((p.normal - exact_normal).norm() < 1e-12);
            CHECK(std::abs(p.k1) < 1e-9);
            CHECK(std::abs(p.k2) < 1e-9);
            // The diffuse plane is the plane itself, in a right-handed frame.
            const DiffusePlane plane = model.diffuse_plane(query);
            REQUIRE(plane.ok);
            CHECK((plane.normal - exact_normal).norm() < 1e-9);
            CHECK(std::abs((plane.origin - Vec3(0, 0, 1)).dot(exact_normal)) < 1e-12);
            CHECK((plane.e1.cross(plane.e2) - plane.normal).norm() < 1e-12);
            CHECK(plane.window_radius > 0);
        }
    }
}

TEST_CASE("hdi: a paraboloid is reproduced to round-off where the diffuse frame is its axis")
{
    // z = 0.3x² - 0.2y² on a 9 x 9 grid (spacing 0.25) centred on the apex, with exact normals.
    // With 13 neighbours of a query on the axis the set is {apex, 4 at d, 4 at d√2, 4 at 2d}:
    // symmetric, so the diffuse plane is exactly horizontal and the quadratic patch is the
    // paraboloid itself: the projection, normal and curvatures are exact.
    //      . . o . .
    //      . o o o .
    //      o o X o o      X: apex, o: the 12 other neighbours
    //      . o o o .
    //      . . o . .
    const double a = 0.3, b = -0.2, spacing = 0.25;
    std::vector<Vec3> points, normals;
    for (int i = -4; i <= 4; ++i)
        for (int j = -4; j <= 4; ++j)
        {
            const double x = i * spacing, y = j * spacing;
            points.emplace_back(x, y, a * x * x + b * y * y);
            normals.push_back(Vec3(-2 * a * x, -2 * b * y, 1).normalized());
        }
    HdiOptions options;
    options.neighbours = 13;
    const HdiSurface model(points, normals, {}, FeatureSet{}, options);
    for (double lift : {-0.04, -0.01, 0.0, 0.02, 0.05})
    {
        const Projection p = model.project(Vec3(0, 0, lift));
        REQUIRE(p.status == ProjectionStatus::Ok);
        CHECK(p.point.norm() < 1e-14);
        CHECK((p.normal - Vec3(0, 0, 1)).norm() < 1e-14);
        // Curvatures of the graph at the apex: -2a and -2b (bending toward +z counts negative).
        CHECK(p.k1 == doctest::Approx(-2 * b).epsilon(1e-12));
        CHECK(p.k2 == doctest::Approx(-2 * a).epsilon(1e-12));
    }
}

TEST_CASE("hdi: thin parts - nodes of the opposite sheet are dropped by their normal")
{
    // A strip folded back on itself: two sheets 0.1 apart, nodes 0.2 apart, so the nearest nodes
    // of a point on the top sheet include bottom-sheet nodes. One smooth patch (no features):
    // only the normal rule can tell the sheets apart.
    //   z=+0.05  o---o---o---o---o---o--.
    //                                     )  U-turn, radius 0.05
    //   z=-0.05  o---o---o---o---o---o--'
    const double half = 0.05, spacing = 0.2;
    std::vector<Vec3> section;  // along the strip, top sheet first
    for (int i = 0; i <= 10; ++i) section.emplace_back(i * spacing, 0, half);
    for (int k = 1; k < 4; ++k)
        section.emplace_back(2.0 + half * std::sin(pi * k / 4), 0, half * std::cos(pi * k / 4));
    for (int i = 10; i >= 0; --i) section.emplace_back(i * spacing, 0, -half);
    const int rows = 11;
    Surface s;
    for (const Vec3& p : section)
        for (int j = 0; j < rows; ++j) s.points.push_back(p + Vec3(0, j * spacing, 0));
    for (int i = 0; i + 1 < static_cast<int>(section.size()); ++i)
        for (int j = 0; j + 1 < rows; ++j)
        {
            const int a = i * rows + j, b = (i + 1) * rows + j;
            s.triangles.push_back({a, b, b + 1});
            s.triangles.push_back({a, b + 1, a + 1});
        }
    std::mt19937 random(9);
    // Away from the U-turn, whose nodes tilt the refined normals of the nodes next to it.
    std::uniform_real_distribution<double> inside(0.2, 1.0), lift(-0.02, 0.04);
    const HdiSurface model(s.points, s.triangles, FeatureSet{});
    HdiOptions no_filter;
    no_filter.normal_agreement = -1.0;  // every node admissible
    const HdiSurface unfiltered(s.points, s.triangles, FeatureSet{}, no_filter);
    double unfiltered_worst = 0;
    for (int k = 0; k < 100; ++k)
    {
        const Vec3 x(inside(random), inside(random), half + lift(random));
        const Projection p = model.project(x);
        REQUIRE(p.status == ProjectionStatus::Ok);
        CHECK(std::abs(p.point.z() - half) < 1e-12);
        CHECK((p.normal - Vec3(0, 0, 1)).norm() < 1e-12);
        unfiltered_worst =
            std::max(unfiltered_worst, std::abs(unfiltered.project(x).point.z() - half));
    }
    MESSAGE("thin strip: max error " << unfiltered_worst
                                     << " with the normal rule off, round-off with it on");
    CHECK(unfiltered_worst > 1e-3);  // the rule is what makes the difference
}

TEST_CASE("hdi: the sphere's projection error falls at order >= 2.5")
{
    double errors[3], spacings[3], normal_errors[3];
    for (int level = 0; level < 3; ++level)
    {
        const Surface s = icosphere(level + 2);
        const HdiSurface model(s.points, s.triangles, FeatureSet{});
        auto distance = [](const Vec3& p) { return p.norm() - 1.0; };
        auto normal = [](const Vec3& p) { return p.normalized(); };
        spacings[level] = mean_edge_length(s);
        errors[level] = max_projection_error(s, model, distance, normal,
                                             17u + static_cast<std::uint32_t>(level), 1000,
                                             &normal_errors[level]);
        // Curvatures of the unit sphere: 1.
        const Projection p = model.project(Vec3(0.3, -0.5, 0.8));
        CHECK(p.k1 == doctest::Approx(1.0).epsilon(0.05));
        CHECK(p.k2 == doctest::Approx(1.0).epsilon(0.05));
        MESSAGE("sphere: nodes " << s.points.size() << "  h " << spacings[level] << "  max error "
                                 << errors[level] << "  max normal error " << normal_errors[level]);
    }
    const double order_coarse =
        std::log(errors[0] / errors[1]) / std::log(spacings[0] / spacings[1]);
    const double order = std::log(errors[1] / errors[2]) / std::log(spacings[1] / spacings[2]);
    MESSAGE("sphere: observed order " << order_coarse << " (coarse pair), " << order
                                      << " (fine pair)");
    CHECK(order >= 2.5);
    CHECK(errors[2] < 1e-5);
}

TEST_CASE("hdi: the torus's projection error falls at order >= 2.5")
{
    double errors[3], spacings[3], normal_errors[3];
    const int resolutions[3][2] = {{24, 10}, {48, 20}, {96, 40}};
    for (int level = 0; level < 3; ++level)
    {
        const Surface s = torus(resolutions[level][0], resolutions[level][1]);
        const HdiSurface model(s.points, s.triangles, FeatureSet{});
        spacings[level] = mean_edge_length(s);
        errors[level] = max_projection_error(s, model, torus_distance, torus_normal,
                                             29u + static_cast<std::uint32_t>(level), 1000,
                                             &normal_errors[level]);
        MESSAGE("torus: nodes " << s.points.size() << "  h " << spacings[level] << "  max error "
                                << errors[level] << "  max normal error " << normal_errors[level]);
    }
    const double order_coarse =
        std::log(errors[0] / errors[1]) / std::log(spacings[0] / spacings[1]);
    const double order = std::log(errors[1] / errors[2]) / std::log(spacings[1] / spacings[2]);
    MESSAGE("torus: observed order " << order_coarse << " (coarse pair), " << order
                                     << " (fine pair)");
    CHECK(order >= 2.5);
}

TEST_CASE("hdi: fandisk - smooth points project onto the surface, ridge points onto the ridges")
{
    const TriangleSurface input = read_obj(hdimesh::fixtures::data_path("fandisk.obj"));
    const FeatureSet features = detect_features(input.points, input.triangles);
    const HdiSurface model(input.points, input.triangles, features);
    const double diagonal = model.scale();
    REQUIRE(diagonal > 0);
    std::mt19937 random(2024);
    std::uniform_real_distribution<double> unit(0.0, 1.0);

    // Points within 0.2 % of the diagonal of random input triangles, moved off along the normal.
    double worst_distance = 0, worst_normal_dot = 1;
    int fallbacks = 0;
    const int smooth_samples = 300;
    for (int k = 0; k < smooth_samples; ++k)
    {
        const Triangle3& t = input.triangles[std::uniform_int_distribution<std::size_t>(
            0, input.triangles.size() - 1)(random)];
        const Vec3& a = input.points[static_cast<std::size_t>(t[0])];
        const Vec3& b = input.points[static_cast<std::size_t>(t[1])];
        const Vec3& c = input.points[static_cast<std::size_t>(t[2])];
        double u = unit(random), v = unit(random);
        if (u + v > 1) u = 1 - u, v = 1 - v;
        const Vec3 face_normal = triangle_normal(a, b, c);
        const Vec3 x =
            (1 - u - v) * a + u * b + v * c + (unit(random) - 0.5) * 0.004 * diagonal * face_normal;
        const Projection p = model.project(x);
        REQUIRE(p.status != ProjectionStatus::Failed);
        CHECK(p.status != ProjectionStatus::NotConverged);
        if (p.status == ProjectionStatus::LinearFallback) ++fallbacks;
        // Compared with the triangle nearest to where it landed: a point pushed off a face beside a
        // concave ridge may be nearer the other face, and is then rightly projected onto that one.
        std::size_t landed = 0;
        worst_distance = std::max(worst_distance, distance_to_surface(p.point, input, &landed));
        const Triangle3& l = input.triangles[landed];
        const Vec3 landed_normal = triangle_normal(input.points[static_cast<std::size_t>(l[0])],
                                                   input.points[static_cast<std::size_t>(l[1])],
                                                   input.points[static_cast<std::size_t>(l[2])]);
        worst_normal_dot = std::min(worst_normal_dot, p.normal.dot(landed_normal));
    }
    MESSAGE("fandisk smooth: max distance to the input "
            << worst_distance / diagonal << " of the diagonal, min normal . nearest face normal "
            << worst_normal_dot << ", linear fallbacks " << fallbacks);
    // The model is the smooth surface the facets approximate: on fandisk's tightest fillets
    // (radius ~0.13, nodes ~0.1 apart) the facets' sagitta h²κ/8 is ~1.3e-3 of the diagonal.
    CHECK(worst_distance <= 2e-3 * diagonal);
    CHECK(worst_normal_dot > 0.5);  // each point is fitted on its own side of the ridges

    // Points within 0.5 % of the diagonal of random ridge edges land on the ridge polyline.
    std::vector<std::array<int, 2>> lines = model.features().ridge_edges;
    REQUIRE(!lines.empty());
    auto distance_to_lines = [&](const Vec3& p) {
        double best = std::numeric_limits<double>::infinity();
        for (const auto& e : lines)
            best = std::min(
                best, (p - closest_point_on_segment(p, input.points[static_cast<std::size_t>(e[0])],
                                                    input.points[static_cast<std::size_t>(e[1])]))
                          .norm());
        return best;
    };
    double worst_ridge = 0, worst_travel = 0;
    for (int k = 0; k < 300; ++k)
    {
        const auto& e =
            lines[std::uniform_int_distribution<std::size_t>(0, lines.size() - 1)(random)];
        const Vec3 on = input.points[static_cast<std::size_t>(e[0])] +
                        unit(random) * (input.points[static_cast<std::size_t>(e[1])] -
                                        input.points[static_cast<std::size_t>(e[0])]);
        const Vec3 offset =
            Vec3(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5) * 0.005 * diagonal;
        const Projection p = model.project_to_ridge(on + offset);
        REQUIRE(p.status != ProjectionStatus::Failed);
        CHECK(p.status != ProjectionStatus::NotConverged);
        worst_ridge = std::max(worst_ridge, distance_to_lines(p.point));
        worst_travel = std::max(worst_travel, (p.point - on).norm());
        CHECK(std::abs(p.tangent.norm() - 1) < 1e-12);
    }
    MESSAGE("fandisk ridges: max distance to the input ridge lines "
            << worst_ridge / diagonal
            << " of the diagonal; max distance from the sampled ridge point "
            << worst_travel / diagonal);
    CHECK(worst_ridge <= 1e-3 * diagonal);
    CHECK(worst_travel <= 0.01 * diagonal);  // it lands near where it started, not on another ridge
}

TEST_CASE(
    "hdi: const queries are thread-safe - two threads reproduce the serial answers bit for bit")
{
    const Surface s = icosphere(3);
    const HdiSurface model(s.points, s.triangles, FeatureSet{});
    std::mt19937 random(77);
    std::uniform_real_distribution<double> coordinate(-1.2, 1.2);
    std::vector<Vec3> queries;
    for (int k = 0; k < 2000; ++k)
    {
        const Vec3 x(coordinate(random), coordinate(random), coordinate(random));
        if (x.norm() > 0.5) queries.push_back(x);
    }
    std::vector<Vec3> serial;
    for (const Vec3& q : queries) serial.push_back(model.project(q).point);
    std::vector<Vec3> first(queries.size()), second(queries.size());
    std::thread a([&] {
        for (std::size_t i = 0; i < queries.size(); ++i) first[i] = model.project(queries[i]).point;
    });
    std::thread b([&] {
        for (std::size_t i = queries.size(); i-- > 0;)
            second[i] = model.project(queries[i]).point;  // other order
    });
    a.join();
    b.join();
    CHECK(first == serial);
    CHECK(second == serial);
    // A copy shares the model and answers the same.
    const HdiSurface copy = model;
    CHECK(copy.project(queries[0]).point == serial[0]);
}

TEST_CASE("hdi: an empty model fails politely")
{
    const HdiSurface empty(std::vector<Vec3>{}, std::vector<Triangle3>{}, FeatureSet{});
    CHECK(empty.project(Vec3(1, 2, 3)).status == ProjectionStatus::Failed);
    CHECK(empty.project(Vec3(1, 2, 3)).point == Vec3(1, 2, 3));
    CHECK(empty.project_to_ridge(Vec3(1, 2, 3)).status == ProjectionStatus::Failed);
    CHECK_FALSE(empty.is_corner(0));
}
