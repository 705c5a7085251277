// The repair pass on surfaces as users have them: each defect built in code, repaired with a
// note (or refused with --strict), and the volume meshed from it passes the checker.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "common/errors.h"
#include "coupling/mesh_from_surface.h"
#include "fixtures.h"
#include "surface/soup_repair.h"
#include "volume/check/check.h"
#include "volume/check/surface_check.h"

using namespace hdimesh;
using coupling::mesh_volume_from_surface;
using coupling::VolumeFromSurfaceOptions;
using coupling::VolumeFromSurfaceReport;
using surface::TriangleSoup;
using surface::Vec3d;

namespace
{

/// A soup of a fixture's points and triangles, every ref 1.
template <class Points, class Triangles>
TriangleSoup soup_of(const Points& points, const Triangles& triangles)
{
    TriangleSoup soup;
    for (const auto& p : points) soup.points.emplace_back(p[0], p[1], p[2]);
    for (const auto& t : triangles) soup.triangles.push_back({t[0], t[1], t[2]});
    soup.refs.assign(soup.triangles.size(), 1);
    return soup;
}

TriangleSoup icosphere_soup(int levels)
{
    const hdi::TriangleSurface s = fixtures::icosphere(levels);
    return soup_of(s.points, s.triangles);
}

TriangleSoup cube_soup(int n)
{
    const fixtures::GridSurface s = fixtures::grid_cube(n);
    return soup_of(s.points, s.triangles);
}

VolumeFromSurfaceOptions uniform(double h)
{
    VolumeFromSurfaceOptions o;
    o.sizing.hsiz = h;
    o.adapt.verbosity = 0;
    o.source = "test";
    return o;
}

/// Meshes the soup, requires a valid mesh, returns the report.
VolumeFromSurfaceReport mesh_checked(const TriangleSoup& soup, const VolumeFromSurfaceOptions& o)
{
    VolumeFromSurfaceReport report;
    const volume::TetMesh mesh = mesh_volume_from_surface(soup, o, &report);
    const auto violations = volume::check_mesh(mesh);
    INFO(volume::format_violations(violations));
    REQUIRE(violations.empty());
    std::vector<volume::Vec3> points(mesh.points.begin(), mesh.points.end());
    std::vector<volume::Triangle> triangles(mesh.triangles.begin(), mesh.triangles.end());
    CHECK(volume::check_closed_surface(points, triangles).empty());
    return report;
}

int count_notes(const std::vector<std::string>& notes, const std::string& what)
{
    return static_cast<int>(std::count_if(notes.begin(), notes.end(), [&](const std::string& n) {
        return n.find(what) != std::string::npos;
    }));
}

/// Boundary edges of a soup.
int boundary_edges(const TriangleSoup& soup)
{
    std::map<std::pair<int, int>, int> uses;
    for (const auto& t : soup.triangles)
        for (int k = 0; k < 3; ++k)
            ++uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
    int open = 0;
    for (const auto& [e, n] : uses) open += n == 1;
    return open;
}

/// Removes the triangles using vertex v or any of its neighbours (its two-ring of faces).
void remove_two_ring(TriangleSoup& soup, int v)
{
    std::vector<char> near(soup.points.size(), 0);
    near[v] = 1;
    for (const auto& t : soup.triangles)
        if (std::find(t.begin(), t.end(), v) != t.end())
            for (int w : t) near[w] = 1;
    std::vector<std::array<int, 3>> kept;
    for (const auto& t : soup.triangles)
        if (!near[t[0]] && !near[t[1]] && !near[t[2]]) kept.push_back(t);
    soup.triangles = kept;
    soup.refs.assign(kept.size(), 1);
}

}  // namespace

TEST_CASE("coincident points, duplicated and degenerate triangles: merged and dropped, noted")
{
    TriangleSoup soup = icosphere_soup(2);
    const int n = static_cast<int>(soup.points.size());
    // every triangle gets its own copy of its first point (an STL-like soup)
    for (auto& t : soup.triangles)
    {
        soup.points.push_back(soup.points[t[0]]);
        t[0] = static_cast<int>(soup.points.size()) - 1;
    }
    soup.triangles.push_back(soup.triangles[3]);  // a copy, same orientation
    soup.triangles.push_back({soup.triangles[5][0], soup.triangles[5][0], soup.triangles[5][1]});
    // a back-to-back pair: a zero-volume wall between two points of the sphere
    soup.triangles.push_back({0, 1, 2});
    soup.triangles.push_back({0, 2, 1});
    soup.refs.assign(soup.triangles.size(), 1);

    TriangleSoup repaired = soup;
    surface::SoupRepairReport report;
    surface::repair_soup(repaired, "soup", {}, &report);
    CHECK(report.merged_vertices == soup.triangles.size() - 4);
    CHECK(report.degenerate_faces == 1);
    CHECK(report.duplicate_faces == 3);
    CHECK(static_cast<int>(repaired.points.size()) == n);
    CHECK(repaired.triangles.size() == 320);
    CHECK(boundary_edges(repaired) == 0);
    CHECK(count_notes(report.notes, "soup: repaired: merged") == 1);

    const auto meshed = mesh_checked(soup, uniform(0.3));
    CHECK(count_notes(meshed.repairs, "dropped") == 2);
    VolumeFromSurfaceOptions strict = uniform(0.3);
    strict.repair.strict = true;
    CHECK_THROWS_AS(mesh_volume_from_surface(soup, strict), InputError);
}

TEST_CASE("a 3-edge hole and a 12-edge hole are closed, one note each")
{
    TriangleSoup soup = icosphere_soup(3);
    soup.triangles.erase(soup.triangles.begin() + 7);  // one triangle: 3 edges
    // a vertex of six neighbours far from that triangle: its two-ring leaves a 12-edge loop
    int centre = -1;
    for (int v = static_cast<int>(soup.points.size()) - 1; v >= 0 && centre < 0; --v)
    {
        int degree = 0;
        for (const auto& t : soup.triangles) degree += std::find(t.begin(), t.end(), v) != t.end();
        if (degree == 6 && (soup.points[v] - soup.points[soup.triangles[7][0]]).norm() > 1.0)
            centre = v;
    }
    REQUIRE(centre >= 0);
    remove_two_ring(soup, centre);
    REQUIRE(boundary_edges(soup) == 3 + 12);

    const auto report = mesh_checked(soup, uniform(0.1));
    CHECK(count_notes(report.repairs, "closed a hole of 3 edges") == 1);
    CHECK(count_notes(report.repairs, "closed a hole of 12 edges") == 1);

    VolumeFromSurfaceOptions strict = uniform(0.1);
    strict.repair.strict = true;
    CHECK_THROWS_WITH_AS(mesh_volume_from_surface(soup, strict),
                         doctest::Contains("the surface is open: 2 boundary loops"), InputError);
    // at a size 5 times smaller the 12-edge hole spans more than 10 local sizes: refused,
    // the loop named
    VolumeFromSurfaceOptions fine = uniform(0.02);
    fine.refine = false;
    CHECK_THROWS_WITH_AS(
        mesh_volume_from_surface(soup, fine),
        doctest::Contains("the surface is open: 1 boundary loop (loop 1: 12 edges"), InputError);
}

TEST_CASE("two balls pinched at one point: split into two solids, the copies apart")
{
    //    (  A  )(  B  )   B is A mirrored at the plane through A's rightmost point: the two
    //                     balls share that point, a pinched vertex of two closed fans
    TriangleSoup soup = icosphere_soup(2);
    const int n = static_cast<int>(soup.points.size());
    int right = 0;
    for (int v = 1; v < n; ++v)
        if (soup.points[v][0] > soup.points[right][0]) right = v;
    const double x = soup.points[right][0];
    for (int v = 0; v < n; ++v)
    {
        const Vec3d p = soup.points[v];
        soup.points.emplace_back(2 * x - p[0], p[1], p[2]);  // exact at the shared point
    }
    const std::size_t faces = soup.triangles.size();
    for (std::size_t f = 0; f < faces; ++f)
    {
        const auto t = soup.triangles[f];
        soup.triangles.push_back({n + t[0], n + t[2], n + t[1]});  // mirrored: turned back out
    }
    soup.refs.assign(soup.triangles.size(), 1);
    const auto report = mesh_checked(soup, uniform(0.2));
    CHECK(count_notes(report.repairs, "merged 1 coincident vertices") == 1);
    CHECK(count_notes(report.repairs, "split pinched vertex") == 1);
    CHECK(report.regions == 2);

    VolumeFromSurfaceOptions strict = uniform(0.2);
    strict.repair.strict = true;
    CHECK_THROWS_AS(mesh_volume_from_surface(soup, strict), InputError);
}

TEST_CASE("a double cone pinched at its apex: two solids, each tip its own, quality kept")
{
    // two cones of 12 sides on the z axis share their apex at the origin (an hourglass): the
    // pinched vertex splits into one copy per cone, moved into its own fan
    constexpr double pi = 3.14159265358979323846;
    constexpr int around = 12, rings = 4;
    TriangleSoup soup;
    soup.points.push_back({0, 0, 0});  // the apex
    auto ring = [&](int cone, int i) { return 1 + (cone * rings + (i - 1)) * around; };
    for (int cone = 0; cone < 2; ++cone)
        for (int i = 1; i <= rings; ++i)
            for (int j = 0; j < around; ++j)
            {
                const double r = double(i) / rings, a = 2 * pi * j / around;
                soup.points.push_back({r * std::cos(a), r * std::sin(a), (cone ? 2 : -2) * r});
            }
    for (int cone = 0; cone < 2; ++cone)
    {
        const bool up = cone == 1;
        auto add = [&](int a, int b, int c) {
            soup.triangles.push_back(up ? std::array<int, 3>{a, b, c}
                                        : std::array<int, 3>{a, c, b});
        };
        for (int j = 0; j < around; ++j)
        {
            const int j1 = (j + 1) % around;
            add(0, ring(cone, 1) + j1, ring(cone, 1) + j);
            for (int i = 1; i < rings; ++i)
            {
                const int a = ring(cone, i), b = ring(cone, i + 1);
                add(a + j, a + j1, b + j1);
                add(a + j, b + j1, b + j);
            }
        }
        const int base = static_cast<int>(soup.points.size());  // the base's centre
        soup.points.push_back({0, 0, up ? 2.0 : -2.0});
        for (int j = 0; j < around; ++j)
            add(base, ring(cone, rings) + j, ring(cone, rings) + (j + 1) % around);
    }
    soup.refs.assign(soup.triangles.size(), 1);
    // a size at which the split tips stay apart after the remesh (coarser, they cross: refused)
    const auto report = mesh_checked(soup, uniform(0.15));
    CHECK(count_notes(report.repairs, "split pinched vertex") == 1);
    CHECK(report.regions == 2);
    MESSAGE("double cone: min Qe " << report.min_quality << ", " << report.tets << " tets");
    CHECK(report.min_quality > 0.3);

    VolumeFromSurfaceOptions strict = uniform(0.15);
    strict.repair.strict = true;
    CHECK_THROWS_AS(mesh_volume_from_surface(soup, strict), InputError);
}

TEST_CASE("a sphere with two triangles pushed through each other: the fold cut out, refilled")
{
    TriangleSoup soup = icosphere_soup(3);
    // a vertex pushed past its neighbour: its fan folds over the neighbour's
    const auto& t = soup.triangles[100];
    const Vec3d v = soup.points[t[0]], w = soup.points[t[1]];
    soup.points[t[0]] = w + 0.4 * (w - v);
    VolumeFromSurfaceReport report;
    {
        std::vector<volume::Vec3> points;
        for (const auto& p : soup.points) points.emplace_back(p[0], p[1], p[2]);
        std::vector<volume::Triangle> triangles(soup.triangles.begin(), soup.triangles.end());
        REQUIRE_FALSE(volume::check_closed_surface(points, triangles).empty());
    }
    report = mesh_checked(soup, uniform(0.15));
    // the fold and the ring around it cut out, the hole closed, nothing left crossing
    CHECK(count_notes(report.repairs, "repaired: cut out") == 1);
    CHECK(report.input_crossings == 0);
}

TEST_CASE("needle and zero-area triangles: the flat one collapsed, the needle remeshed")
{
    TriangleSoup soup = cube_soup(2);
    // a T-junction: the point halfway along an edge (exact in binary) splits one triangle at
    // it and makes a flat triangle with the edge's ends
    const auto t = soup.triangles[0];
    const int m = static_cast<int>(soup.points.size());
    soup.points.push_back(0.5 * (soup.points[t[0]] + soup.points[t[1]]));
    soup.triangles[0] = {t[0], m, t[2]};
    soup.triangles.push_back({m, t[1], t[2]});
    soup.triangles.push_back({t[0], t[1], m});  // flat: closes the split edge's other side
    // a needle: a point a hair off the middle of another triangle's edge
    const auto u = soup.triangles[10];
    const int needle = static_cast<int>(soup.points.size());
    soup.points.push_back(0.5 * (soup.points[u[0]] + soup.points[u[1]]) + Vec3d(1e-7, 1e-7, 1e-7));
    soup.triangles[10] = {u[0], needle, u[2]};
    soup.triangles.push_back({needle, u[1], u[2]});
    soup.triangles.push_back({u[0], u[1], needle});
    soup.refs.assign(soup.triangles.size(), 1);
    const auto report = mesh_checked(soup, uniform(0.2));
    CHECK(count_notes(report.repairs, "collapsed 1 flat triangle") == 1);
}

TEST_CASE("two cubes sharing an edge: the edge split into one copy per solid")
{
    //   +---+
    //   | 2 |
    //   +---+---+    the cubes touch along one edge (4 triangles on it)
    //       | 1 |
    //       +---+
    TriangleSoup soup = cube_soup(2);
    const TriangleSoup one = soup;
    const int base = static_cast<int>(soup.points.size());
    for (const auto& p : one.points) soup.points.push_back(p + Vec3d(-1, 1, 0));
    for (const auto& t : one.triangles)
        soup.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    soup.refs.assign(soup.triangles.size(), 1);
    const auto report = mesh_checked(soup, uniform(0.2));
    CHECK(count_notes(report.repairs, "into 2 sheets") >= 2);
    CHECK(report.regions == 2);

    // three faces on an edge (a fin) stay refused, named
    TriangleSoup fin = cube_soup(1);
    fin.points.emplace_back(0.5, -1, 0.5);
    const auto t = fin.triangles[0];
    fin.triangles.push_back({t[0], t[1], static_cast<int>(fin.points.size()) - 1});
    fin.refs.assign(fin.triangles.size(), 1);
    CHECK_THROWS_WITH_AS(mesh_volume_from_surface(fin, uniform(0.2)),
                         doctest::Contains("non-manifold edge"), InputError);
}

TEST_CASE("a tiny closed shell outside the solid is dropped; one inside stays a void")
{
    TriangleSoup soup = icosphere_soup(2);
    const TriangleSoup ball = soup;
    auto add_ball = [&](const Vec3d& centre, double radius) {
        const int base = static_cast<int>(soup.points.size());
        for (const auto& p : ball.points) soup.points.push_back(centre + radius * p);
        for (const auto& t : ball.triangles)
            soup.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    };
    add_ball(Vec3d(3, 0, 0), 0.005);  // outside: dropped
    add_ball(Vec3d(0, 0, 0), 0.3);    // inside: a void, kept
    soup.refs.assign(soup.triangles.size(), 1);
    surface::SoupRepairReport report;
    TriangleSoup repaired = soup;
    surface::repair_soup(repaired, "balls", {}, &report);
    CHECK(report.dropped_shells == 1);
    CHECK(repaired.triangles.size() == 2 * ball.triangles.size());
    CHECK(count_notes(report.notes, "dropped a tiny closed shell at (") == 1);
}
