// The closed-surface validation before a volume is meshed: one test per refusal, each asserting
// that the defect is found under its own name (and nothing else where the input has nothing
// else wrong), with the faces or loops it names; clean inputs, including sheets that nearly
// touch, pass.

#include "volume/check/surface_check.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "common/errors.h"
#include "fixtures.h"

using namespace hdimesh;
using namespace hdimesh::volume;

namespace
{

struct Surface
{
    std::vector<Vec3> points;
    std::vector<Triangle> triangles;
};

Surface sphere(int levels, const Vec3& centre = Vec3::Zero(), double radius = 1.0)
{
    const hdi::TriangleSurface s = fixtures::icosphere(levels);
    Surface out;
    for (const auto& p : s.points) out.points.push_back(centre + radius * p);
    out.triangles.assign(s.triangles.begin(), s.triangles.end());
    return out;
}

Surface cube(int n, const Vec3& origin = Vec3::Zero(), const Vec3& scale = Vec3::Ones())
{
    const fixtures::GridSurface s = fixtures::grid_cube(n);
    Surface out;
    for (const auto& p : s.points) out.points.push_back(origin + p.cwiseProduct(scale));
    out.triangles.assign(s.triangles.begin(), s.triangles.end());
    return out;
}

/// The four faces of the tet (a, b, c, d), outward.
Surface tet_surface(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    return {{a, b, c, d}, {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};
}

/// other's points appended (renumbered); `glue` maps some of other's vertices onto existing ones.
void append(Surface& s, const Surface& other, const std::vector<std::pair<int, int>>& glue = {})
{
    std::vector<int> old2new(other.points.size(), -1);
    for (const auto& [theirs, ours] : glue) old2new[theirs] = ours;
    for (std::size_t v = 0; v < other.points.size(); ++v)
        if (old2new[v] < 0)
        {
            old2new[v] = static_cast<int>(s.points.size());
            s.points.push_back(other.points[v]);
        }
    for (const auto& t : other.triangles)
        s.triangles.push_back({old2new[t[0]], old2new[t[1]], old2new[t[2]]});
}

std::vector<SurfaceDefectKind> kinds(const std::vector<SurfaceDefect>& defects)
{
    std::vector<SurfaceDefectKind> out;
    for (const auto& d : defects)
        if (out.empty() || out.back() != d.kind) out.push_back(d.kind);
    return out;
}

int count(const std::vector<SurfaceDefect>& defects, SurfaceDefectKind kind)
{
    return static_cast<int>(std::count_if(defects.begin(), defects.end(),
                                          [&](const SurfaceDefect& d) { return d.kind == kind; }));
}

std::string refusal(const Surface& s)
{
    try
    {
        require_closed_surface(s.points, s.triangles, "in.obj");
    }
    catch (const InputError& e)
    {
        return e.what();
    }
    return {};
}

}  // namespace

TEST_CASE("closed shells pass: an icosphere, a gridded cube, two disjoint spheres")
{
    CHECK(check_closed_surface(sphere(2).points, sphere(2).triangles).empty());
    const Surface box = cube(3);
    CHECK(check_closed_surface(box.points, box.triangles).empty());
    Surface two = sphere(1);
    append(two, sphere(1, Vec3(3, 0, 0)));
    CHECK(check_closed_surface(two.points, two.triangles).empty());
    CHECK(refusal(two).empty());
}

TEST_CASE("an open surface is refused, its boundary loops named in order")
{
    // two faces far apart removed from the sphere: two holes of three edges each
    Surface s = sphere(1);
    const Triangle first = s.triangles[0];
    s.triangles.erase(s.triangles.begin() + 70);
    s.triangles.erase(s.triangles.begin());
    const auto defects = check_closed_surface(s.points, s.triangles);
    REQUIRE(kinds(defects) == std::vector<SurfaceDefectKind>{SurfaceDefectKind::OpenBoundary});
    REQUIRE(defects.size() == 2);
    for (const auto& loop : defects)
    {
        CHECK(loop.vertices.size() == 3);
        CHECK(loop.faces.size() == 3);
    }
    // the loop of the first hole goes around the removed face's vertices
    std::vector<int> around = defects[0].vertices, removed(first.begin(), first.end());
    std::sort(around.begin(), around.end());
    std::sort(removed.begin(), removed.end());
    CHECK(around == removed);
    const std::string message = refusal(s);
    CHECK(message.rfind("in.obj: the surface is open: 2 boundary loops (loop 1: 3 edges through "
                        "vertices ",
                        0) == 0);
    CHECK(message.find("; loop 2: 3 edges") != std::string::npos);
}

TEST_CASE("a non-manifold edge is refused: two tets hinged on one edge")
{
    //        d            the edge a-b is in four faces: two of each tet
    //       /|\ .
    //      a-+-b
    //       \|/
    //        e
    Surface s = tet_surface(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, 0.3, 1));
    append(s, tet_surface(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, -1, 0), Vec3(0.5, 0.3, -1)),
           {{0, 0}, {1, 1}});
    const auto defects = check_closed_surface(s.points, s.triangles);
    REQUIRE(kinds(defects) == std::vector<SurfaceDefectKind>{SurfaceDefectKind::NonManifoldEdge});
    REQUIRE(defects.size() == 1);
    CHECK(defects[0].vertices == std::vector<int>{0, 1});
    CHECK(defects[0].faces.size() == 4);
    CHECK(refusal(s).find("in.obj: 1 non-manifold edge (in three or more triangles) (edge 1-2 in "
                          "triangles ") == 0);
}

TEST_CASE("a pinched vertex is refused: two tets touching at one corner")
{
    Surface s = tet_surface(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
    append(s, tet_surface(Vec3(0, 0, 0), Vec3(0, -1, 0), Vec3(-1, 0, 0), Vec3(0, 0, -1)), {{0, 0}});
    const auto defects = check_closed_surface(s.points, s.triangles);
    REQUIRE(kinds(defects) == std::vector<SurfaceDefectKind>{SurfaceDefectKind::NonManifoldVertex});
    REQUIRE(defects.size() == 1);
    CHECK(defects[0].vertices == std::vector<int>{0});
    CHECK(defects[0].faces.size() == 6);
    CHECK(refusal(s).find("pinched (non-manifold) vertex") != std::string::npos);
}

TEST_CASE("a flipped face is refused: its three edges are traversed the same way twice")
{
    Surface s = sphere(1);
    std::swap(s.triangles[5][1], s.triangles[5][2]);
    const auto defects = check_closed_surface(s.points, s.triangles);
    REQUIRE(kinds(defects) ==
            std::vector<SurfaceDefectKind>{SurfaceDefectKind::InconsistentOrientation});
    REQUIRE(defects.size() == 3);
    for (const auto& d : defects)
        CHECK(std::find(d.faces.begin(), d.faces.end(), 5) != d.faces.end());
    CHECK(refusal(s).find("in.obj: inconsistent orientation: 3 edges are traversed the same way") ==
          0);
}

TEST_CASE("a duplicated face is refused as such, not as the non-manifold edges it makes")
{
    Surface s = sphere(1);
    const Triangle copy = {s.triangles[7][1], s.triangles[7][2], s.triangles[7][0]};
    s.triangles.push_back(copy);
    const auto defects = check_closed_surface(s.points, s.triangles);
    REQUIRE(kinds(defects) == std::vector<SurfaceDefectKind>{SurfaceDefectKind::DuplicateFace});
    REQUIRE(defects.size() == 1);
    CHECK(defects[0].faces == std::vector<int>{7, static_cast<int>(s.triangles.size()) - 1});
    CHECK(refusal(s).find("in.obj: 1 duplicated triangle (the same three vertices) (triangles 8, " +
                          std::to_string(s.triangles.size())) == 0);
}

TEST_CASE("a self-intersecting surface is refused: a sphere overlapping a copy of itself")
{
    Surface s = sphere(2);
    append(s, sphere(2, Vec3(0.5, 0.2, 0.1)));
    const auto defects = check_closed_surface(s.points, s.triangles);
    REQUIRE(kinds(defects) == std::vector<SurfaceDefectKind>{SurfaceDefectKind::SelfIntersection});
    const int half = static_cast<int>(s.triangles.size()) / 2;
    for (const auto& d : defects)
    {
        // only faces of different copies cross
        REQUIRE(d.faces.size() == 2);
        CHECK(d.faces[0] < half);
        CHECK(d.faces[1] >= half);
    }
    // the intersection curve crosses a ring of faces on each sphere
    CHECK(defects.size() >= 20);
    CHECK(refusal(s).find("in.obj: the surface intersects itself: ") == 0);

    SurfaceCheckOptions quick;
    quick.max_intersections = 1;
    CHECK(check_closed_surface(s.points, s.triangles, quick).size() == 1);
}

TEST_CASE("nearly touching sheets that do not meet pass")
{
    // two cubes, face to face a hair apart; a slab one millionth thick
    Surface s = cube(2);
    append(s, cube(2, Vec3(1 + 1e-9, 0.3, 0.2)));
    CHECK(check_closed_surface(s.points, s.triangles).empty());
    const Surface slab = cube(3, Vec3(0, 0, 0), Vec3(1, 1, 1e-6));
    CHECK(check_closed_surface(slab.points, slab.triangles).empty());

    // the same cubes overlapping by a hair do meet
    Surface overlap = cube(2);
    append(overlap, cube(2, Vec3(1 - 1e-9, 0.3, 0.2)));
    CHECK(count(check_closed_surface(overlap.points, overlap.triangles),
                SurfaceDefectKind::SelfIntersection) > 0);
}

TEST_CASE("a degenerate face is refused: a repeated vertex, or three points on a line")
{
    Surface s = sphere(1);
    s.triangles.push_back({3, 3, 7});
    auto defects = check_closed_surface(s.points, s.triangles);
    REQUIRE(kinds(defects) == std::vector<SurfaceDefectKind>{SurfaceDefectKind::DegenerateFace});
    CHECK(defects[0].faces == std::vector<int>{static_cast<int>(s.triangles.size()) - 1});
    CHECK(refusal(s).find("in.obj: 1 degenerate (zero-area) triangle (triangle " +
                          std::to_string(s.triangles.size()) + " (vertices 4 4 8))") == 0);

    // a pyramid over a pentagon whose vertex 1 sits on the edge 0-2: the base triangle
    // (0, 1, 2) has no area
    //
    //   4 +------+ 3
    //     |      |
    //     |      |
    //   0 +--+---+ 2
    //        1
    Surface flat;
    flat.points = {Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(1, 0, 0),
                   Vec3(1, 1, 0), Vec3(0, 1, 0),   Vec3(0.5, 0.5, 1)};
    flat.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 4, 3},  // base, seen from below
                      {0, 1, 5}, {1, 2, 5}, {2, 3, 5}, {3, 4, 5}, {4, 0, 5}};
    defects = check_closed_surface(flat.points, flat.triangles);
    REQUIRE(count(defects, SurfaceDefectKind::DegenerateFace) == 1);
    CHECK(defects[0].faces == std::vector<int>{0});
    CHECK(refusal(flat).find("degenerate (zero-area) triangle (triangle 1 (vertices 1 3 2))") !=
          std::string::npos);
}

TEST_CASE("a face naming a vertex that does not exist is refused before anything else")
{
    Surface s = sphere(0);
    s.triangles[2][1] = 99;
    const auto defects = check_closed_surface(s.points, s.triangles);
    REQUIRE(defects.size() == 1);
    CHECK(defects[0].kind == SurfaceDefectKind::VertexOutOfRange);
    CHECK(refusal(s) ==
          "in.obj: a triangle names a vertex that does not exist: 1 bad id "
          "(triangle 3 names vertex 100)");
}

TEST_CASE("several kinds are listed under one heading, one line each")
{
    Surface s = sphere(1);
    s.triangles.erase(s.triangles.begin());
    std::swap(s.triangles[30][1], s.triangles[30][2]);
    const std::string message = refusal(s);
    CHECK(message.find("in.obj: the surface cannot bound a volume:\n  the surface is open: ") == 0);
    CHECK(message.find("\n  inconsistent orientation: 3 edges") != std::string::npos);
}

TEST_CASE("coincident points are merged, so a per-face soup closes")
{
    // the tet's four faces, each with its own three points
    const Surface tet = tet_surface(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
    Surface soup;
    for (const auto& t : tet.triangles)
    {
        const int base = static_cast<int>(soup.points.size());
        for (int v : t) soup.points.push_back(tet.points[v]);
        soup.triangles.push_back({base, base + 1, base + 2});
    }
    CHECK(count(check_closed_surface(soup.points, soup.triangles),
                SurfaceDefectKind::OpenBoundary) == 4);
    CHECK(merge_coincident_points(soup.points, soup.triangles) == 8);
    CHECK(check_closed_surface(soup.points, soup.triangles).empty());
    // the first point at each place names it
    for (const auto& t : soup.triangles)
        for (int v : t) CHECK(v < 6);
}

TEST_CASE("the shared surfaces: four bound a volume as they are, the bunny is open with 5 holes")
{
    for (const char* name : {"spot.obj", "fandisk.obj", "rocker-arm.obj", "cheburashka.obj"})
    {
        CAPTURE(name);
        const hdi::TriangleSurface s = hdi::read_obj(fixtures::data_path(name));
        std::vector<Triangle> triangles(s.triangles.begin(), s.triangles.end());
        merge_coincident_points(s.points, triangles);
        const auto defects = check_closed_surface(s.points, triangles);
        INFO(format_surface_defects(defects, name));
        CHECK(defects.empty());
    }
    const hdi::TriangleSurface bunny = hdi::read_obj(fixtures::data_path("stanford-bunny.obj"));
    std::vector<Triangle> triangles(bunny.triangles.begin(), bunny.triangles.end());
    const auto defects = check_closed_surface(bunny.points, triangles);
    REQUIRE(kinds(defects) == std::vector<SurfaceDefectKind>{SurfaceDefectKind::OpenBoundary});
    CHECK(defects.size() == 5);
    for (const auto& loop : defects) CHECK(loop.vertices.size() == loop.faces.size());
}
