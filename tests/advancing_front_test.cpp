// The advancing front (volume/fill/advancing_front.h) on small closed surfaces built in code. Every
// fill must hold: positive tets (exact orient3d), the enclosed volume conserved, the tets'
// boundary equal to the input faces as an oriented set (each interior face in two tets with
// opposite orientations), new points strictly inside (on no input face), a clean checker on the
// assembled mesh, and the same bytes on a rerun.

#include "volume/fill/advancing_front.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/mesh/predicates.h"
#include "volume/mesh/tet_tables.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

struct Surface
{
    std::vector<Vec3> points;
    std::vector<Triangle> faces;
};

Surface from_grid(const fixtures::GridSurface& grid)
{
    Surface s;
    s.points = grid.points;
    for (const auto& t : grid.triangles) s.faces.push_back({t[0], t[1], t[2]});
    return s;
}

/// The boundary of a union of unit voxels, each exposed voxel side an n x n grid, outward.
Surface voxel_surface(const std::set<std::array<int, 3>>& voxels, int n, const Vec3& scale)
{
    fixtures::GridSurface grid;
    const Vec3 x(scale[0], 0, 0), y(0, scale[1], 0), z(0, 0, scale[2]);
    for (const auto& v : voxels)
    {
        const Vec3 o = v[0] * x + v[1] * y + v[2] * z;
        auto empty = [&](int dx, int dy, int dz) {
            return !voxels.count({v[0] + dx, v[1] + dy, v[2] + dz});
        };
        if (empty(0, 0, -1)) grid.add_grid(o, y, x, n, n);
        if (empty(0, 0, 1)) grid.add_grid(o + z, x, y, n, n);
        if (empty(0, -1, 0)) grid.add_grid(o, x, z, n, n);
        if (empty(0, 1, 0)) grid.add_grid(o + y, z, x, n, n);
        if (empty(-1, 0, 0)) grid.add_grid(o, z, y, n, n);
        if (empty(1, 0, 0)) grid.add_grid(o + x, y, z, n, n);
    }
    return from_grid(grid);
}

Surface icosphere_surface(int levels, double radius, bool inward)
{
    const hdi::TriangleSurface ball = fixtures::icosphere(levels);
    Surface s;
    for (const auto& p : ball.points) s.points.push_back(radius * p);
    for (const auto& t : ball.triangles)
        s.faces.push_back(inward ? Triangle{t[0], t[2], t[1]} : Triangle{t[0], t[1], t[2]});
    return s;
}

void append(Surface& to, const Surface& from)
{
    const int offset = static_cast<int>(to.points.size());
    to.points.insert(to.points.end(), from.points.begin(), from.points.end());
    for (const auto& t : from.faces)
        to.faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

double enclosed_volume(const std::vector<Vec3>& points, const std::vector<Triangle>& faces)
{
    double v = 0;
    for (const auto& t : faces)
        v += signed_volume(Vec3::Zero(), points[t[0]], points[t[1]], points[t[2]]);
    return v;
}

/// The faces as rotations with the smallest vertex first, so equal oriented faces compare equal.
Triangle canonical(const Triangle& t)
{
    Triangle r = t;
    while (r[0] > r[1] || r[0] > r[2]) r = {r[1], r[2], r[0]};
    return r;
}

struct Fill
{
    std::vector<TetVertices> tets;
    std::vector<Vec3> new_points;
    FrontReport report;
};

/// Runs the front, asserts every invariant of the file comment, returns the fill.
Fill fill_and_check(const Surface& s, const SizeField* field)
{
    Fill fill;
    std::string failure;
    const bool ok = advance_front(s.points, s.faces, field, AdvancingFrontOptions{}, fill.tets,
                                  fill.new_points, failure, &fill.report);
    INFO(failure);
    REQUIRE(ok);
    REQUIRE(!fill.tets.empty());
    CHECK(fill.report.tets == static_cast<long>(fill.tets.size()));
    CHECK(fill.report.new_points == static_cast<long>(fill.new_points.size()));

    std::vector<Vec3> all = s.points;
    all.insert(all.end(), fill.new_points.begin(), fill.new_points.end());
    const int n = static_cast<int>(all.size());

    // positive, and the volume of the faces
    double volume = 0;
    for (const auto& t : fill.tets)
    {
        for (int v : t) REQUIRE((v >= 0 && v < n));
        REQUIRE(orient3d(all[t[0]], all[t[1]], all[t[2]], all[t[3]]) > 0);
        volume += signed_volume(all[t[0]], all[t[1]], all[t[2]], all[t[3]]);
    }
    const double enclosed = enclosed_volume(s.points, s.faces);
    CHECK(std::abs(volume - enclosed) <= 1e-10 * std::abs(enclosed));

    // the oriented boundary of the tets is the input
    std::map<Triangle, int> oriented;  // canonical outward face -> count
    for (const auto& t : fill.tets)
        for (const auto& fv : tet::kFaceVertices)
            ++oriented[canonical({t[fv[0]], t[fv[1]], t[fv[2]]})];
    std::set<Triangle> input;
    for (const auto& f : s.faces) input.insert(canonical(f));
    for (const auto& [face, count] : oriented)
    {
        REQUIRE(count == 1);  // the same face twice the same way: overlapping tets
        const Triangle reverse = canonical({face[0], face[2], face[1]});
        const bool interior = oriented.count(reverse) > 0;
        if (!interior)
            REQUIRE(input.count(face) == 1);
        else
            REQUIRE(input.count(face) == 0);
    }
    for (const auto& f : input) REQUIRE(oriented.count(f) == 1);

    // new points strictly inside: on no input face (and, by the above, enclosed by them)
    std::vector<char> used(n, 0);
    for (const auto& t : fill.tets)
        for (int v : t) used[v] = 1;
    for (int v = static_cast<int>(s.points.size()); v < n; ++v)
    {
        REQUIRE(used[v]);
        for (const auto& f : s.faces)
        {
            if (orient3d(all[f[0]], all[f[1]], all[f[2]], all[v]) != 0) continue;
            int drop = 0;
            const Vec3 normal = (all[f[1]] - all[f[0]]).cross(all[f[2]] - all[f[0]]);
            normal.cwiseAbs().maxCoeff(&drop);
            const int a = orient2d(all[f[0]], all[f[1]], all[v], drop);
            const int b = orient2d(all[f[1]], all[f[2]], all[v], drop);
            const int c = orient2d(all[f[2]], all[f[0]], all[v], drop);
            const bool on_face = (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
            REQUIRE(!on_face);
        }
    }

    // the assembled mesh passes the checker
    TetMesh mesh;
    for (const Vec3& p : all) mesh.add_vertex(p);
    for (const auto& t : fill.tets) mesh.add_tet(t, 1);
    for (const auto& f : s.faces) mesh.add_triangle(f, 1);
    mesh.compact();
    mesh.classify_vertices();
    mesh.build_adjacency();
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(violations.empty());

    // byte-identical on a rerun
    Fill again;
    REQUIRE(advance_front(s.points, s.faces, field, AdvancingFrontOptions{}, again.tets,
                          again.new_points, failure, nullptr));
    REQUIRE(again.tets == fill.tets);
    REQUIRE(again.new_points.size() == fill.new_points.size());
    if (!fill.new_points.empty())  // memcmp on an empty vector's null data() is undefined
        CHECK(std::memcmp(again.new_points.data(), fill.new_points.data(),
                          fill.new_points.size() * sizeof(Vec3)) == 0);
    return fill;
}

double mean_edge(const Surface& s)
{
    double sum = 0;
    for (const auto& t : s.faces)
        for (int k = 0; k < 3; ++k) sum += (s.points[t[k]] - s.points[t[(k + 1) % 3]]).norm();
    return sum / (3.0 * s.faces.size());
}

}  // namespace

/*  The unit cube as 12 triangles (each side cut by one diagonal), h = 1/3: the front has to
    place interior points, several layers deep.

        +------+
       /|     /|
      +------+ |      12 faces, 8 vertices, no interior vertex given
      | +----|-+
      |/     |/
      +------+                                                                     */
TEST_CASE("cube of 12 faces with h = edge/3: interior points are created")
{
    const Surface cube = from_grid(fixtures::grid_cube(1));
    REQUIRE(cube.faces.size() == 12);
    const ConstantSize field(1.0 / 3.0);
    const Fill fill = fill_and_check(cube, &field);
    CHECK(fill.new_points.size() > 0);
    CHECK(fill.tets.size() > 12);
}

TEST_CASE("cube of 12 faces without a field: the face sizes")
{
    fill_and_check(from_grid(fixtures::grid_cube(1)), nullptr);
}

/*  An icosphere (320 faces) with h = its mean edge: the whole-volume case in small.      */
TEST_CASE("icosphere at its own edge length")
{
    const Surface sphere = icosphere_surface(2, 1.0, false);
    const ConstantSize field(mean_edge(sphere));
    const Fill fill = fill_and_check(sphere, &field);
    CHECK(fill.new_points.size() > 10);
}

/*  Two shells: the box [-1,1]^3 (each side 3 x 3) with a ball of radius 0.5 removed, the
    ball's faces turned to point into the void (outward from the domain).

        +-----------+
        |   .---.   |
        |  /     \  |    the void: no tet may enter it,
        |  \     /  |    and the enclosed volume is box - ball
        |   '---'   |
        +-----------+                                                                 */
TEST_CASE("box with a spherical void (two shells)")
{
    Surface s = from_grid(fixtures::grid_cube(3));
    for (Vec3& p : s.points) p = 2.0 * p - Vec3(1, 1, 1);
    append(s, icosphere_surface(1, 0.5, true));
    const ConstantSize field(0.45);
    fill_and_check(s, &field);
}

/*  An L-shape of three unit cubes, each exposed side a 2 x 2 grid: a reflex edge along z.

        +---+
        |   |
        +   +---+
        |       |     (seen from above; 1 unit high)
        +---+---+                                                                     */
TEST_CASE("L-shape with a reflex edge")
{
    const Surface s = voxel_surface({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 2, Vec3(1, 1, 1));
    const ConstantSize field(0.5);
    fill_and_check(s, &field);
}

/*  A thin slab 1 x 1 x 0.1, the big sides 5 x 5, h = 0.2: two sheets of the front face each
    other 0.5 h apart.

        +---------------------+
        +---------------------+   0.1 thick                                           */
TEST_CASE("thin slab: two sheets half a size apart")
{
    fixtures::GridSurface grid;
    const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 0.1);
    grid.add_grid(o, y, x, 5, 5);
    grid.add_grid(o + z, x, y, 5, 5);
    grid.add_grid(o, x, z, 5, 1);
    grid.add_grid(o + y, z, x, 1, 5);
    grid.add_grid(o, z, y, 1, 5);
    grid.add_grid(o + x, y, z, 5, 1);
    const ConstantSize field(0.2);
    fill_and_check(from_grid(grid), &field);
}

/*  A regular tet's 4 faces: one tet, nothing new.                                        */
TEST_CASE("a single tet's faces give that tet")
{
    Surface s;
    s.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    s.faces = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    const Fill fill = fill_and_check(s, nullptr);
    CHECK(fill.tets.size() == 1);
    CHECK(fill.new_points.empty());
}

TEST_CASE("an open surface is refused, nothing written")
{
    Surface s = from_grid(fixtures::grid_cube(1));
    s.faces.pop_back();
    std::vector<TetVertices> tets;
    std::vector<Vec3> new_points;
    std::string failure;
    CHECK(!advance_front(s.points, s.faces, nullptr, AdvancingFrontOptions{}, tets, new_points,
                         failure));
    CHECK(failure.find("open") != std::string::npos);
    CHECK(tets.empty());
    CHECK(new_points.empty());
}
