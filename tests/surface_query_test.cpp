// The hinted queries of the surface model: a closest-point search told a nearby primitive, a
// projection told a nearby model face, a size looked up on the face just projected onto, a
// "within this distance of the model?" decided by a descent from the hint face. The hint buys
// time: every distance must be the one of the search without it, whatever the hint (right, a
// neighbour, far away, out of range, stale), including the ties of points on shared edges and
// vertices; a projection for placing a vertex may take the foot on the hint's own sheet (the
// global one on a single sheet, up to the face it names at a tie). Checked on a bumpy grid
// built here against brute force, and on two sheets close together.
//
//   z = 0.3·sin(0.9 x)·cos(0.7 y) over the n×n grid, each square cut by one diagonal:
//
//     (0,n) +---+---+ ... +
//           | / | / |     |
//           +---+---+ ... +
//           | / | / |     |
//     (0,0) +---+---+ ... + (n,0)

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <vector>

#include "surface/detail/closest_point_tree.h"
#include "surface/detail/local_ops_geometry.h"
#include "surface/features.h"
#include "surface/local_ops.h"
#include "surface/surface_model.h"
#include "surface_fixtures.h"

using namespace hdimesh::surface;

namespace
{

double height(double x, double y) { return 0.3 * std::sin(0.9 * x) * std::cos(0.7 * y); }

SurfaceMesh bumpy_grid(int n)
{
    SurfaceMesh mesh = hdimesh::surface::fixtures::triangulated_grid(n, height);
    hdimesh::surface::fixtures::mark_all_smooth(mesh);
    return mesh;
}

std::vector<std::array<Vec3d, 3>> triangles_of(const SurfaceMesh& mesh)
{
    std::vector<std::array<Vec3d, 3>> triangles;
    for (auto f : mesh.faces())
    {
        auto fv = mesh.cfv_iter(f);
        const Vec3d a = mesh.point(*fv), b = mesh.point(*++fv), c = mesh.point(*++fv);
        triangles.push_back({a, b, c});
    }
    return triangles;
}

// Deterministic samples: uniform in the box [−1, n+1]² × [−1, 1] (near and far from the
// surface), plus every grid vertex and edge midpoint (points on several triangles: ties).
std::vector<Vec3d> sample_points(const SurfaceMesh& mesh, int n, int count)
{
    std::uint32_t state = 12345u;
    auto uniform = [&](double lo, double hi) {
        state = state * 1664525u + 1013904223u;
        return lo + (hi - lo) * (state >> 8) / double(1u << 24);
    };
    std::vector<Vec3d> points;
    for (int i = 0; i < count; ++i)
        points.emplace_back(uniform(-1, n + 1), uniform(-1, n + 1), uniform(-1, 1));
    for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
    for (auto e : mesh.edges())
    {
        const auto h = mesh.halfedge_handle(e, 0);
        points.push_back(
            0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h))));
    }
    return points;
}

double brute_force_distance(const std::vector<std::array<Vec3d, 3>>& triangles, const Vec3d& p)
{
    double best = std::numeric_limits<double>::max();
    for (const auto& t : triangles)
        best = std::min(best, (closest_point_on_triangle(p, t[0], t[1], t[2]) - p).norm());
    return best;
}

}  // namespace

TEST_CASE("closest point tree: a hinted query returns the exact hit, whatever the hint")
{
    const int n = 8;
    const SurfaceMesh mesh = bumpy_grid(n);
    const auto triangles = triangles_of(mesh);
    const ClosestPointTree tree = ClosestPointTree::from_triangles(triangles);
    const int count = static_cast<int>(triangles.size());
    const auto points = sample_points(mesh, n, 400);

    int wrong_distance = 0, differs = 0, queries = 0;
    for (std::size_t k = 0; k < points.size(); ++k)
    {
        const Vec3d& p = points[k];
        const auto exact = tree.closest(p);
        REQUIRE(exact.primitive >= 0);
        if (std::abs(exact.distance - brute_force_distance(triangles, p)) > 1e-12) ++wrong_distance;
        // The right face, a neighbour, one far away, the ends, none, out of range.
        const int hints[] = {exact.primitive,
                             (exact.primitive + 1) % count,
                             static_cast<int>(k * 7919 % count),
                             0,
                             count - 1,
                             -1,
                             count,
                             -5};
        for (const int hint : hints)
        {
            const auto hinted = tree.closest(p, hint);
            ++queries;
            if (hinted.primitive != exact.primitive || hinted.point != exact.point ||
                hinted.distance != exact.distance)
                ++differs;
        }
    }
    CHECK(queries == 8 * static_cast<int>(points.size()));
    CHECK(wrong_distance == 0);
    CHECK(differs == 0);
}

TEST_CASE(
    "closest point tree: off-surface ties (points over shared vertices) resolve as without a hint")
{
    // A point above a grid vertex, along the mean of its faces' normals (inside their normal
    // cone where the bump is convex): its closest point is the vertex itself, at exactly the
    // same distance from every triangle around it. The search picks the first of them in its
    // own order; a hinted search and the leaf tests that skip primitives by their boxes must
    // pick the same one (the remesher's outputs depend on which face it is: its hint, its normal).
    const int n = 8;
    const SurfaceMesh mesh = bumpy_grid(n);
    const auto triangles = triangles_of(mesh);
    const ClosestPointTree tree = ClosestPointTree::from_triangles(triangles);
    const int count = static_cast<int>(triangles.size());
    int differs = 0, at_vertex = 0, queries = 0;
    for (auto v : mesh.vertices())
    {
        Vec3d normal(0, 0, 0);
        for (auto f : mesh.vf_range(v)) normal += mesh.calc_face_normal(f);
        if (!(normal.norm() > 0.0)) continue;
        for (const double lift : {1e-6, 0.01, 0.2})
        {
            const Vec3d p = mesh.point(v) + lift * normal.normalized();
            const auto exact = tree.closest(p);
            REQUIRE(exact.primitive >= 0);
            if (exact.point == mesh.point(v)) ++at_vertex;
            for (const int hint : {exact.primitive, (exact.primitive + 1) % count,
                                   (exact.primitive + count / 2) % count, 0, -1})
            {
                const auto hinted = tree.closest(p, hint);
                ++queries;
                if (hinted.primitive != exact.primitive || hinted.point != exact.point ||
                    hinted.distance != exact.distance)
                    ++differs;
            }
        }
    }
    CHECK(queries > 0);
    CHECK(at_vertex > 0);  // the ties this test is about do occur
    CHECK(differs == 0);
}

TEST_CASE("closest point tree: a lazily built tree answers as the eager one, ties included")
{
    // The lazy tree splits a node when a search first opens it: after a few queries most of it
    // is unsplit, after many most is. Every answer (primitive, point, distance) must be the
    // eager tree's, hinted or not, at any stage: the points over the grid vertices (exact ties
    // between the faces around a vertex) and points sampled around the surface, in an order
    // that jumps across the grid.
    const int n = 8;
    const SurfaceMesh mesh = bumpy_grid(n);
    const auto triangles = triangles_of(mesh);
    const ClosestPointTree eager = ClosestPointTree::from_triangles(triangles);
    const int count = static_cast<int>(triangles.size());
    std::vector<Vec3d> points = sample_points(mesh, n, 200);
    for (auto v : mesh.vertices())
    {
        Vec3d normal(0, 0, 0);
        for (auto f : mesh.vf_range(v)) normal += mesh.calc_face_normal(f);
        if (normal.norm() > 0.0) points.push_back(mesh.point(v) + 0.01 * normal.normalized());
    }
    int differs = 0, queries = 0;
    for (const std::size_t per_tree : {std::size_t{1}, std::size_t{7}, points.size()})
    {
        ClosestPointTree lazy;
        for (std::size_t k = 0; k < points.size(); ++k)
        {
            if (k % per_tree == 0) lazy = ClosestPointTree::lazy_from_triangles(triangles);
            const Vec3d& p = points[(k * 37) % points.size()];
            const auto exact = eager.closest(p);
            const int hint =
                k % 3 == 0 ? -1
                           : (k % 3 == 1 ? exact.primitive : static_cast<int>(k * 7919 % count));
            const auto hit = hint < 0 ? lazy.closest(p) : lazy.closest(p, hint);
            ++queries;
            if (hit.primitive != exact.primitive || hit.point != exact.point ||
                hit.distance != exact.distance)
                ++differs;
        }
    }
    CHECK(queries == 3 * static_cast<int>(points.size()));
    CHECK(differs == 0);
    CHECK(ClosestPointTree::lazy_from_triangles({}).closest(Vec3d(0, 0, 0)).primitive == -1);
}

TEST_CASE(
    "closest point tree: alone_within tells whether another primitive is that close, as brute "
    "force does")
{
    // Points off the bumpy grid, over its vertices (the faces around a vertex tie exactly: never
    // alone) and sampled around it; each asked about its closest primitive with a bound just
    // above its distance (mostly alone) and one a bit larger (often not), on an eager tree and
    // on a lazy one that has not opened those nodes yet.
    const int n = 8;
    const SurfaceMesh mesh = bumpy_grid(n);
    const auto triangles = triangles_of(mesh);
    const ClosestPointTree eager = ClosestPointTree::from_triangles(triangles);
    std::vector<Vec3d> points = sample_points(mesh, n, 200);
    for (auto v : mesh.vertices())
    {
        Vec3d normal(0, 0, 0);
        for (auto f : mesh.vf_range(v)) normal += mesh.calc_face_normal(f);
        if (normal.norm() > 0.0) points.push_back(mesh.point(v) + 0.05 * normal.normalized());
    }
    int differs = 0, alone = 0, not_alone = 0;
    for (std::size_t k = 0; k < points.size(); ++k)
    {
        const Vec3d& p = points[k];
        const auto hit = eager.closest(p);
        REQUIRE(hit.primitive >= 0);
        for (const double factor : {1.0 + 1e-6, 1.5})
        {
            const double bound_d2 = hit.distance * hit.distance * factor;
            bool brute = true;
            for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
            {
                const auto& tri = triangles[t];
                if (t != hit.primitive &&
                    (closest_point_on_triangle(p, tri[0], tri[1], tri[2]) - p).sqrnorm() <=
                        bound_d2)
                    brute = false;
            }
            const ClosestPointTree lazy = ClosestPointTree::lazy_from_triangles(triangles);
            if (eager.alone_within(p, hit.primitive, bound_d2) != brute ||
                lazy.alone_within(p, hit.primitive, bound_d2) != brute)
                ++differs;
            (brute ? alone : not_alone) += 1;
        }
    }
    CHECK(alone > 0);
    CHECK(not_alone > 0);
    CHECK(differs == 0);
    CHECK(ClosestPointTree::lazy_from_triangles({}).alone_within(Vec3d(0, 0, 0), -1, 1.0));
}

TEST_CASE("closest point tree: hinted segment queries equal the exact ones")
{
    // A helix of 60 segments, queried from around it and at its own vertices (two segments each).
    std::vector<std::array<Vec3d, 2>> segments;
    auto helix = [](int i) { return Vec3d(std::cos(0.3 * i), std::sin(0.3 * i), 0.05 * i); };
    for (int i = 0; i < 60; ++i) segments.push_back({helix(i), helix(i + 1)});
    const ClosestPointTree tree = ClosestPointTree::from_segments(segments);
    int differs = 0;
    for (int k = 0; k <= 600; ++k)
    {
        const Vec3d p = k % 10 == 0
                            ? helix(k / 10)
                            : Vec3d(1.5 * std::cos(0.37 * k), 1.5 * std::sin(0.23 * k), 0.005 * k);
        const auto exact = tree.closest(p);
        double brute = std::numeric_limits<double>::max();
        for (const auto& s : segments)
            brute = std::min(brute, (closest_point_on_segment(p, s[0], s[1]) - p).norm());
        CHECK(exact.distance == doctest::Approx(brute).epsilon(1e-12));
        for (const int hint : {exact.primitive, (exact.primitive + 30) % 60, 0, 59, -1, 60})
        {
            const auto hinted = tree.closest(p, hint);
            if (hinted.primitive != exact.primitive || hinted.point != exact.point) ++differs;
        }
    }
    CHECK(differs == 0);
}

TEST_CASE(
    "surface model: hinted projections find the same foot, hinted distances and sizes are exact")
{
    const int n = 8;
    const SurfaceMesh mesh = bumpy_grid(n);
    const SurfaceModel model(mesh);
    // A linear field: barycentric interpolation reproduces it exactly on every triangle.
    auto linear = [](const Vec3d& p) { return 1.0 + p[0] + 2.0 * p[1] - 0.5 * p[2]; };
    std::vector<double> values;
    for (auto v : mesh.vertices()) values.push_back(linear(mesh.point(v)));
    const auto points = sample_points(mesh, n, 300);
    const int faces = static_cast<int>(mesh.n_faces());

    int elsewhere = 0, farther = 0, distance_differs = 0, off_field = 0, shortcut_off = 0,
        differs = 0;
    for (std::size_t k = 0; k < points.size(); ++k)
    {
        const Vec3d& p = points[k];
        const ProjectedPoint exact = model.project(p, VertexClass::Smooth, kNoCurve);
        REQUIRE(exact.ok);
        REQUIRE(exact.face >= 0);
        const double d = (exact.point - p).norm();
        for (const int hint : {exact.face, static_cast<int>(k * 31 % faces), -1, faces + 3})
        {
            // One sheet: the same foot (a point on a shared edge or vertex may name either face).
            const ProjectedPoint hinted =
                model.project_near(p, VertexClass::Smooth, kNoCurve, hint);
            if (!hinted.ok || (hinted.point - exact.point).norm() > 1e-12) ++elsewhere;
            if (hinted.ok && (hinted.point - p).norm() > d + 1e-15) ++farther;
            if (model.distance_to_surface(p, hint) != d) ++distance_differs;
        }
        // A size looked up where a point was just projected: on the hint face without a search,
        // equal to the searched value up to rounding; any other hint: the search, exactly.
        const Vec3d q = exact.point;
        const double searched = model.interpolate(q, values);
        if (std::abs(searched - linear(q)) > 1e-9) ++off_field;
        if (std::abs(model.interpolate(q, values, exact.face) - searched) >
            1e-12 * std::abs(searched))
            ++shortcut_off;
        if (model.interpolate(q, values, (exact.face + faces / 2) % faces) != searched) ++differs;
    }
    CHECK(elsewhere == 0);
    CHECK(farther == 0);
    CHECK(distance_differs == 0);
    CHECK(differs == 0);
    CHECK(off_field == 0);
    CHECK(shortcut_off == 0);
}

TEST_CASE(
    "surface model: a vertex placed near its own sheet stays on it, its distance is to the nearest")
{
    // Two flat unit grids 0.006 apart (a thin slab, edges of length 1):
    //
    //   z = 0.006  +---+---+---+   upper sheet
    //              p (z = 0.004): 0.002 below the upper sheet, 0.004 above the lower one
    //   z = 0      +---+---+---+   lower sheet (the hint's)
    //
    // Told a lower face, the placement keeps p on the lower sheet (p is within a hundredth of an
    // edge of it: a vertex moved along its own sheet); the distance is to the upper one.
    const int n = 4;
    SurfaceMesh mesh =
        hdimesh::surface::fixtures::triangulated_grid(n, [](double, double) { return 0.0; });
    const SurfaceMesh upper =
        hdimesh::surface::fixtures::triangulated_grid(n, [](double, double) { return 0.006; });
    std::vector<VertexHandle> added;
    for (auto v : upper.vertices()) added.push_back(mesh.add_vertex(upper.point(v)));
    const int lower_faces = static_cast<int>(mesh.n_faces());
    for (auto f : upper.faces())
    {
        std::vector<VertexHandle> corners;
        for (auto v : upper.fv_range(f)) corners.push_back(added[v.idx()]);
        mesh.add_face(corners[0], corners[2], corners[1]);  // facing down, into the slab
    }
    hdimesh::surface::fixtures::mark_all_smooth(mesh);
    const SurfaceModel model(mesh);

    const Vec3d p(1.3, 2.6, 0.004);
    const ProjectedPoint exact = model.project(p, VertexClass::Smooth, kNoCurve);
    REQUIRE(exact.ok);
    CHECK(exact.point[2] == doctest::Approx(0.006));
    CHECK(exact.face >= lower_faces);
    const int lower_hint =
        0;  // the model numbers faces in the mesh's order: the lower sheet's first
    const ProjectedPoint placed = model.project_near(p, VertexClass::Smooth, kNoCurve, lower_hint);
    REQUIRE(placed.ok);
    CHECK(placed.face < lower_faces);
    CHECK(placed.point[2] == doctest::Approx(0.0));
    CHECK(placed.point[0] == doctest::Approx(1.3));
    CHECK(placed.point[1] == doctest::Approx(2.6));
    CHECK(model.distance_to_surface(p, lower_hint) == doctest::Approx(0.002));
    CHECK(model.near_model(p, 0.0025, lower_hint));
    CHECK_FALSE(model.near_model(p, 0.0015, lower_hint));
    // Farther than a hundredth of an edge from the hint's sheet: the search decides.
    const Vec3d q(1.3, 2.6, 0.0045 + 0.0075);
    CHECK(model.project_near(q, VertexClass::Smooth, kNoCurve, lower_hint).face >= lower_faces);
}

TEST_CASE("surface model: near_model decides as the exact distance does, from any hint")
{
    // The descent from the hint face may stop at a local minimum or run out of steps: then the
    // search decides. Limits around the sampled distances make both answers frequent.
    const int n = 8;
    const SurfaceMesh mesh = bumpy_grid(n);
    const SurfaceModel model(mesh);
    const auto points = sample_points(mesh, n, 300);
    const int faces = static_cast<int>(mesh.n_faces());
    int disagree = 0, near = 0, far = 0;
    for (std::size_t k = 0; k < points.size(); ++k)
    {
        const Vec3d& p = points[k];
        const ProjectedPoint exact = model.project(p, VertexClass::Smooth, kNoCurve);
        REQUIRE(exact.ok);
        const double d = (exact.point - p).norm();
        for (const double limit : {0.0, 0.5 * d, d, 1.5 * d + 1e-3, 0.05, 0.4})
            for (const int hint : {exact.face, static_cast<int>(k * 31 % faces), 0, -1, faces})
            {
                const bool answer = model.near_model(p, limit, hint);
                if (answer != (d <= limit)) ++disagree;
                (answer ? near : far) += 1;
            }
    }
    CHECK(disagree == 0);
    CHECK(near > 1000);
    CHECK(far > 1000);
}

TEST_CASE("shift_vertex: a stale or missing model-face hint moves every vertex exactly the same")
{
    // The bumpy grid as the model; a copy with its interior vertices pushed off their place
    // (along x and y, then back onto the model) is smoothed twice: once with no hints, once with
    // every hint pointing at a far corner face. Positions must match bit for bit, every moved
    // vertex must lie on the model, and the hint must then name the face it lies on.
    const int n = 8;
    const SurfaceMesh input = bumpy_grid(n);
    const SurfaceModel model(input);
    SurfaceMesh start = input;
    {
        SurfaceProperties props(start);
        for (auto v : start.vertices())
        {
            if (start.is_boundary(v)) continue;
            const Vec3d p = start.point(v);
            const Vec3d pushed(p[0] + 0.2 * std::sin(3.1 * v.idx()),
                               p[1] + 0.2 * std::cos(1.7 * v.idx()), p[2]);
            start.set_point(v, model.project(pushed, VertexClass::Smooth, kNoCurve).point);
        }
    }
    auto folded_faces = [](const SurfaceMesh& mesh) {
        int folded = 0;
        for (auto f : mesh.faces())
        {
            auto fv = mesh.cfv_iter(f);
            const Vec3d a = mesh.point(*fv), b = mesh.point(*++fv), c = mesh.point(*++fv);
            if (!(OpenMesh::cross(b - a, c - a)[2] > 0.0)) ++folded;
        }
        return folded;
    };
    REQUIRE(folded_faces(start) == 0);
    SurfaceMesh no_hints = start, stale_hints = start;
    SurfaceProperties props_a(no_hints), props_b(stale_hints);
    for (auto v : stale_hints.vertices()) stale_hints.property(props_b.vertex_model_face, v) = 0;
    const SurfaceHooks hooks;
    OperatorContext ctx_a(no_hints, model, hooks), ctx_b(stale_hints, model, hooks);
    ShiftOptions options;
    options.smart = false;
    int moved = 0, differs = 0, off_model = 0, wrong_hint = 0;
    for (int pass = 0; pass < 3; ++pass)
        for (auto v : no_hints.vertices())
        {
            const bool a = shift_vertex(ctx_a, v, options).done();
            const bool b = shift_vertex(ctx_b, v, options).done();
            if (a != b || no_hints.point(v) != stale_hints.point(v)) ++differs;
            if (!a) continue;
            ++moved;
            const ProjectedPoint on_model =
                model.project(no_hints.point(v), VertexClass::Smooth, kNoCurve);
            if ((on_model.point - no_hints.point(v)).norm() > 1e-12) ++off_model;
            if (stale_hints.property(props_b.vertex_model_face, v) != on_model.face) ++wrong_hint;
        }
    CHECK(moved > 0);
    CHECK(differs == 0);
    CHECK(off_model == 0);
    CHECK(wrong_hint == 0);
    // The smoothing kept every triangle facing up (no fold).
    CHECK(folded_faces(no_hints) == 0);
}

TEST_CASE(
    "surface model: the normal of a foot on an edge or at a vertex is the model's there, not one "
    "face's")
{
    // A roof of four triangles over the square [-1, 1]², ridge along y at x = 0, height 1:
    //
    //   (-1, 1, 0) +-----+-----+ (1, 1, 0)      each side slopes at 45°; the ridge (0, y, 1)
    //              |   / | \   |                 from (0, -1, 1) to (0, 1, 1)
    //              |  /  |  \  |
    //   (-1,-1, 0) +-----+-----+ (1, -1, 0)
    //
    // Above the ridge the foot is on the ridge edge: the normal is the mean of the two sides'
    // (straight up), whichever face the search names. Far out beyond a ridge end the foot is
    // the ridge's end vertex: its angle-weighted normal.
    SurfaceMesh mesh;
    const VertexHandle a = mesh.add_vertex(Vec3d(-1, -1, 0)), b = mesh.add_vertex(Vec3d(0, -1, 1)),
                       c = mesh.add_vertex(Vec3d(1, -1, 0)), d = mesh.add_vertex(Vec3d(1, 1, 0)),
                       e = mesh.add_vertex(Vec3d(0, 1, 1)), f = mesh.add_vertex(Vec3d(-1, 1, 0));
    mesh.add_face(a, b, e);
    mesh.add_face(a, e, f);
    mesh.add_face(b, c, d);
    mesh.add_face(b, d, e);
    hdimesh::surface::fixtures::mark_all_smooth(mesh);
    const SurfaceModel model(mesh);
    const double side = 1.0 / std::sqrt(2.0);

    for (const int hint : {-1, 0, 1, 2, 3})
    {
        const ProjectedPoint above_ridge =
            model.project_near(Vec3d(0.0, 0.3, 2.0), VertexClass::Smooth, kNoCurve, hint);
        REQUIRE(above_ridge.ok);
        CHECK(above_ridge.point[0] == doctest::Approx(0.0));
        CHECK(above_ridge.point[2] == doctest::Approx(1.0));
        CHECK(above_ridge.normal[0] == doctest::Approx(0.0));
        CHECK(above_ridge.normal[2] == doctest::Approx(1.0));
        // Inside a face: that face's normal.
        const ProjectedPoint on_side =
            model.project_near(Vec3d(0.5, 0.0, 0.6), VertexClass::Smooth, kNoCurve, hint);
        REQUIRE(on_side.ok);
        CHECK(on_side.normal[0] == doctest::Approx(side));
        CHECK(on_side.normal[2] == doctest::Approx(side));
    }
    // Beyond the ridge's end (0, 1, 1), up and out along y: the foot is that vertex. Its faces
    // there span 90° on each side (two on the left, one on the right), so the angle-weighted
    // normal is straight up (a face's own would lean 45° to one side).
    for (const int hint : {-1, 0, 1, 2, 3})
    {
        const ProjectedPoint beyond =
            model.project_near(Vec3d(0.0, 3.0, 3.0), VertexClass::Smooth, kNoCurve, hint);
        REQUIRE(beyond.ok);
        CHECK(beyond.point == mesh.point(e));
        CHECK(beyond.normal[0] == doctest::Approx(0.0));
        CHECK(beyond.normal[1] == doctest::Approx(0.0));
        CHECK(beyond.normal[2] == doctest::Approx(1.0));
    }
}

TEST_CASE(
    "shortcut tests decide as the exact ones: a triangle's box beyond a distance, a turn told by "
    "cross products")
{
    // Random triangles of the unit cube (and slivers among them), points near and far, limits
    // at the exact squared distance and around it; turn limits at the exact cosine and around it.
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto point = [&](double scale) {
        return Vec3d(scale * unit(random), scale * unit(random), scale * unit(random));
    };
    int skipped = 0, decided = 0;
    for (int trial = 0; trial < 20000; ++trial)
    {
        std::array<Vec3d, 3> t{point(1.0), point(1.0), point(1.0)};
        if (trial % 4 == 0) t[2] = t[0] + (0.5 + 1e-9 * unit(random)) * (t[1] - t[0]);  // a sliver
        const Vec3d p =
            (trial % 3 == 0 ? t[trial % 2] : Vec3d(0, 0, 0)) + point(trial % 2 ? 1e-3 : 2.0);
        const double exact2 = (closest_point_on_triangle(p, t[0], t[1], t[2]) - p).sqrnorm();
        for (const double factor :
             {0.0, 0.25, 1.0 - 1e-6, 1.0 - 1e-12, 1.0, 1.0 + 1e-12, 1.0 + 1e-6, 4.0})
        {
            const double limit2 = factor * exact2;
            // Beyond means the exact measure is above the limit (a skipped triangle could not
            // pass).
            if (detail::clearly_beyond(p, t, limit2))
            {
                ++skipped;
                CHECK(exact2 > limit2);
            }
        }

        // A second triangle sharing the first's a and b: the turn from the first to it.
        const std::array<Vec3d, 3> u{t[0], t[1], t[2] + point(trial % 2 ? 1e-6 : 0.5)};
        const Vec3d old_cross = OpenMesh::cross(t[1] - t[0], t[2] - t[0]),
                    new_cross = OpenMesh::cross(u[1] - u[0], u[2] - u[0]);
        const Vec3d old_normal = detail::normal(t), new_normal = detail::normal(u);
        const double cosine = OpenMesh::dot(old_normal, new_normal);
        for (const double min_cos :
             {cosine, std::nextafter(cosine, 2.0), std::nextafter(cosine, -2.0), cosine - 1e-13,
              cosine + 1e-13, cosine - 1e-3, cosine + 1e-3, 0.8191520442889918, -1.0, 1.0})
        {
            const bool exact = detail::turn_ok_cos(old_normal, new_normal, min_cos);
            CHECK(detail::turn_ok_cross(old_cross, old_cross.norm(), new_cross, new_cross.norm(),
                                        min_cos) == exact);
            ++decided;
        }
    }
    CHECK(skipped > 10000);  // the shortcut does skip
    CHECK(decided == 200000);
    // Degenerate triangles: no reference before (any turn passes), none after (always refused).
    const Vec3d zero(0, 0, 0), up(0, 0, 2);
    CHECK(detail::turn_ok_cross(zero, 0.0, up, 2.0, 0.9));
    CHECK(!detail::turn_ok_cross(up, 2.0, zero, 0.0, 0.9));
}

TEST_CASE("surface model: a smooth vertex beside a ridge fits its own patch, not the one beyond")
{
    // A thin box, 2 × 1 × 0.05, its faces cut into lattice squares; the side strips are two
    // squares high, so a row of smooth vertices runs between the two ridges of each strip:
    //
    //     z = 0.05  +---+---+---+   (ridge)
    //               |   |   |   |
    //     z = 0.025 +---+---+---+   smooth vertices, a 2-ring away from the top and bottom
    //               |   |   |   |
    //     z = 0     +---+---+---+   (ridge)
    //
    // Every face is flat: every smooth vertex has curvature 0. A fit over a ring that crossed the
    // ridges saw the 90° turn as a curvature of about 1 / 0.05.
    const int nx = 16, ny = 8, nz = 2;
    const double sx = 2.0 / nx, sy = 1.0 / ny, sz = 0.05 / nz;
    SurfaceMesh mesh;
    std::map<std::array<int, 3>, VertexHandle> lattice;
    auto vertex = [&](int i, int j, int k) {
        auto [it, added] = lattice.try_emplace({i, j, k});
        if (added) it->second = mesh.add_vertex(Vec3d(i * sx, j * sy, k * sz));
        return it->second;
    };
    // one box face: lattice points p0 + a·u + b·w, outward when u × w points out
    auto add_face = [&](std::array<int, 3> p0, std::array<int, 3> u, std::array<int, 3> w, int nu,
                        int nw) {
        auto at = [&](int a, int b) {
            return vertex(p0[0] + a * u[0] + b * w[0], p0[1] + a * u[1] + b * w[1],
                          p0[2] + a * u[2] + b * w[2]);
        };
        for (int a = 0; a < nu; ++a)
            for (int b = 0; b < nw; ++b)
            {
                mesh.add_face(at(a, b), at(a + 1, b), at(a + 1, b + 1));
                mesh.add_face(at(a, b), at(a + 1, b + 1), at(a, b + 1));
            }
    };
    add_face({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, ny, nx);   // bottom, -z
    add_face({0, 0, nz}, {1, 0, 0}, {0, 1, 0}, nx, ny);  // top, +z
    add_face({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, nx, nz);   // y = 0, -y
    add_face({0, ny, 0}, {0, 0, 1}, {1, 0, 0}, nz, nx);  // y = 1, +y
    add_face({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, nz, ny);   // x = 0, -x
    add_face({nx, 0, 0}, {0, 1, 0}, {0, 0, 1}, ny, nz);  // x = 2, +x
    REQUIRE(mesh.n_vertices() == lattice.size());
    REQUIRE(fixtures::euler(mesh) == 2);
    detect_features(mesh);
    const SurfaceModel model(mesh);
    const SurfaceProperties props(mesh);
    int strip_vertices = 0;
    double worst = 0;
    for (auto v : mesh.vertices())
    {
        if (mesh.property(props.vertex_class, v) != VertexClass::Smooth) continue;
        worst = std::max(worst, model.input_curvature()[v.idx()]);
        const double z = mesh.point(v)[2];
        strip_vertices += z > 0 && z < 0.05 - 1e-12;
    }
    CHECK(strip_vertices == 2 * (nx - 1) + 2 * (ny - 1));
    CHECK(worst < 1e-9);
}
