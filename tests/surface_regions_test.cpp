// Shells, nesting and regions of a closed surface: what is inside what, which shells bound
// voids, which solids are separate regions, and every region's faces turned outward of it.

#include "volume/check/surface_regions.h"

#include <doctest/doctest.h>

#include <vector>

#include "fixtures.h"
#include "volume/check/surface_check.h"

using namespace hdimesh;
using namespace hdimesh::volume;

namespace
{

struct Surface
{
    std::vector<Vec3> points;
    std::vector<Triangle> triangles;

    void add_sphere(const Vec3& centre, double radius, bool inward = false, int levels = 1)
    {
        const hdi::TriangleSurface s = fixtures::icosphere(levels);
        const int base = static_cast<int>(points.size());
        for (const auto& p : s.points) points.push_back(centre + radius * p);
        for (auto t : s.triangles)
        {
            if (inward) std::swap(t[1], t[2]);
            triangles.push_back({base + t[0], base + t[1], base + t[2]});
        }
    }
};

/// Signed volume of a set of faces (> 0: outward of what they enclose).
double enclosed_volume(const std::vector<Vec3>& points, const std::vector<Triangle>& faces)
{
    double volume6 = 0;
    for (const auto& t : faces) volume6 += points[t[0]].dot(points[t[1]].cross(points[t[2]]));
    return volume6 / 6;
}

}  // namespace

TEST_CASE("winding numbers: inside, outside, a hair inside a face, an inward shell")
{
    Surface s;
    s.add_sphere(Vec3::Zero(), 1.0);
    std::vector<int> all(s.triangles.size());
    for (std::size_t f = 0; f < all.size(); ++f) all[f] = static_cast<int>(f);
    CHECK(winding_number(s.points, s.triangles, all, Vec3(0.1, 0.2, 0.3)) == 1);
    CHECK(winding_number(s.points, s.triangles, all, Vec3(2, 0, 0)) == 0);
    const auto& t = s.triangles[3];
    const Vec3 centroid = (s.points[t[0]] + s.points[t[1]] + s.points[t[2]]) / 3;
    CHECK(winding_number(s.points, s.triangles, all, centroid * (1 - 1e-13)) == 1);
    CHECK(winding_number(s.points, s.triangles, all, centroid * (1 + 1e-13)) == 0);
    for (auto& tri : s.triangles) std::swap(tri[1], tri[2]);
    CHECK(winding_number(s.points, s.triangles, all, Vec3(0.1, 0.2, 0.3)) == -1);
}

TEST_CASE("one shell: one region, an inward shell turned")
{
    Surface s;
    s.add_sphere(Vec3(1, 2, 3), 1.0, true);
    REQUIRE(check_closed_surface(s.points, s.triangles).empty());
    const SurfaceRegions regions = find_surface_regions(s.points, s.triangles);
    REQUIRE(regions.shells.size() == 1);
    REQUIRE(regions.regions.size() == 1);
    CHECK(regions.regions[0].ref == 1);
    CHECK(regions.shells[0].volume < 0);
    CHECK(regions.shells[0].turned);
    CHECK(regions.turned_shells == 1);
    CHECK(enclosed_volume(s.points, regions.region_faces(0)) > 0);
}

TEST_CASE("nested shells make a void; its faces point into the void either way they came")
{
    //   +-----------+
    //   |  solid    |    the outer sphere (r = 2) and the void (r = 1), both given
    //   |   (void)  |    outward as solids, or the void already inward
    //   +-----------+
    for (const bool void_inward : {false, true})
    {
        Surface s;
        s.add_sphere(Vec3::Zero(), 1.0,
                     void_inward);  // listed first: the numbering must not matter
        s.add_sphere(Vec3::Zero(), 2.0);
        REQUIRE(check_closed_surface(s.points, s.triangles).empty());
        const SurfaceRegions regions = find_surface_regions(s.points, s.triangles);
        REQUIRE(regions.shells.size() == 2);
        REQUIRE(regions.regions.size() == 1);
        const SurfaceRegion& region = regions.regions[0];
        // the outer shell comes first in the geometric order: its lowest point is lower
        CHECK(region.outer_shell == 0);
        CHECK(region.void_shells == std::vector<int>{1});
        CHECK(regions.shells[1].depth == 1);
        CHECK(regions.shells[1].parent == 0);
        CHECK(regions.shells[1].turned == !void_inward);
        CHECK(regions.turned_shells == (void_inward ? 0 : 1));
        // the region's faces enclose the shell between the spheres
        const double shell_volume = enclosed_volume(s.points, regions.region_faces(0));
        const double outer =
            enclosed_volume(s.points, {regions.triangles.begin() + 80, regions.triangles.end()});
        CHECK(shell_volume > 0);
        CHECK(shell_volume < outer);
    }
}

TEST_CASE("disjoint shells are separate regions, refs in geometric order")
{
    Surface s;
    s.add_sphere(Vec3(5, 0, 0), 1.0);
    s.add_sphere(Vec3(0, 0, 0), 1.0);
    const SurfaceRegions regions = find_surface_regions(s.points, s.triangles);
    REQUIRE(regions.regions.size() == 2);
    CHECK(regions.regions[0].ref == 1);
    CHECK(regions.regions[1].ref == 2);
    // the sphere at x = 0 is lower, so first, though it was listed second
    CHECK(regions.shells[0].faces.front() == 80);
    CHECK(regions.shells[1].faces.front() == 0);
    CHECK(regions.turned_shells == 0);
    for (int r = 0; r < 2; ++r)
    {
        CHECK(regions.regions[r].void_shells.empty());
        CHECK(enclosed_volume(s.points, regions.region_faces(r)) > 0);
    }
}

TEST_CASE("a solid inside a void is a region of its own")
{
    //   outer r = 3 (region 1) > void r = 2 > island r = 1 (region 2); beside them a sphere
    //   at x = 10 (region 3)
    Surface s;
    s.add_sphere(Vec3(10, 0, 0), 1.0);
    s.add_sphere(Vec3::Zero(), 1.0);
    s.add_sphere(Vec3::Zero(), 2.0);
    s.add_sphere(Vec3::Zero(), 3.0);
    REQUIRE(check_closed_surface(s.points, s.triangles).empty());
    const SurfaceRegions regions = find_surface_regions(s.points, s.triangles);
    REQUIRE(regions.shells.size() == 4);
    REQUIRE(regions.regions.size() == 3);
    CHECK(regions.shells[0].depth == 0);
    CHECK(regions.shells[1].depth == 1);
    CHECK(regions.shells[2].depth == 2);
    CHECK(regions.shells[2].parent == 1);
    CHECK(regions.shells[3].depth == 0);
    CHECK(regions.regions[0].void_shells == std::vector<int>{1});
    CHECK(regions.regions[1].outer_shell == 2);
    CHECK(regions.regions[1].void_shells.empty());
    CHECK(regions.regions[2].outer_shell == 3);
    CHECK(regions.turned_shells == 1);  // only the void
    for (int r = 0; r < 3; ++r) CHECK(enclosed_volume(s.points, regions.region_faces(r)) > 0);
}
