// The refinement's snap (try_snap_vertex) and the point grid it takes its witnesses from, on
// tiny meshes built here: the snapped vertex is on the model, the far point comes within the
// tolerance, no witness ends farther than it was (or than the tolerance), the star keeps its
// angles and orientation; refusals leave the mesh untouched.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "surface/detail/closest_point_tree.h"
#include "surface/detail/point_grid.h"
#include "surface/local_ops.h"
#include "surface/surface_quality.h"
#include "surface_fixtures.h"

using namespace hdimesh::surface;

namespace
{

// A roof over the (x, y) plane: a crest along x = 2.2 of height 0.3, plane flanks of slope 0.3.
// Points are projected vertically (near enough for slopes of 0.3).
double roof(double x) { return 0.3 * (1.0 - std::abs(x - 2.2)); }

class RoofProjector final : public Projector
{
public:
    ProjectedPoint project(const Vec3d& p, VertexClass, int) const override
    {
        ProjectedPoint out;
        out.point = Vec3d(p[0], p[1], roof(p[0]));
        const double slope = p[0] < 2.2 ? 0.3 : -0.3;
        out.normal = Vec3d(-slope, 0, 1).normalize();
        out.ok = true;
        return out;
    }
};

// The 4×4 grid of unit squares on the roof (vertices at z = roof(x)), boundary vertices on
// curve 0, the four grid corners as corners.
SurfaceMesh roof_grid()
{
    SurfaceMesh mesh =
        hdimesh::surface::fixtures::triangulated_grid(4, [](int i, int) { return roof(i); });
    hdimesh::surface::fixtures::mark_all_smooth(mesh);
    // The rim is one boundary curve (0) between the four corners.
    SurfaceProperties props(mesh);
    for (auto v : mesh.vertices())
    {
        if (!mesh.is_boundary(v)) continue;
        const Vec3d p = mesh.point(v);
        const bool corner = (p[0] == 0 || p[0] == 4) && (p[1] == 0 || p[1] == 4);
        mesh.property(props.vertex_class, v) = corner ? VertexClass::Corner : VertexClass::Boundary;
        mesh.property(props.vertex_curve, v) = corner ? kNoCurve : 0;
    }
    for (auto e : mesh.edges())
        if (mesh.is_boundary(e)) mesh.property(props.edge_curve, e) = 0;
    return mesh;
}

using hdimesh::surface::fixtures::vertex_at;

using hdimesh::surface::fixtures::distance_to_mesh;

using hdimesh::surface::fixtures::moved_star_defects;
using hdimesh::surface::fixtures::MovedStarDefects;
using hdimesh::surface::fixtures::points_of;

// Model points: the roof sampled every half unit, and its crest.
std::vector<Vec3d> roof_samples()
{
    std::vector<Vec3d> samples;
    for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 8; ++j) samples.emplace_back(0.5 * i, 0.5 * j, roof(0.5 * i));
    for (int j = 0; j <= 8; ++j) samples.emplace_back(2.2, 0.5 * j, roof(2.2));
    return samples;
}

// The crest snaps' limits: tolerance 0.05, angles of at least 30°, the star's edges in
// [min_length, max_length], the roof samples as witnesses.
SnapOptions crest_snap_options(double min_length, double max_length)
{
    SnapOptions options;
    options.tolerance = 0.05;
    options.min_angle_deg = 30.0;
    options.min_length = min_length;
    options.max_length = max_length;
    options.witnesses = roof_samples();
    return options;
}

}  // namespace

TEST_CASE("snap moves a vertex onto the crest the chords cut, and takes no model point away")
{
    //   y                 The grid's vertices sit on the roof at integer x; the crest (x = 2.2,
    //   4 +---+---+-:-+   z = 0.3) runs between the columns x = 2 and 3, so the chords cut it:
    //     |  /|  /| :/|   the crest point T = (2.2, 2, 0.3) is 0.09 from the output. Snapping
    //   2 +---+---v-T-+   v = (2, 2) toward T brings T within the tolerance.
    //     |  /|  /| :/|
    //   0 +---+---+-:-+ x
    //     0   1   2   3   4
    SurfaceMesh mesh = roof_grid();
    RoofProjector model;
    SurfaceHooks hooks;
    int moves = 0;
    hooks.on_move = [&](const SurfaceMesh&, VertexHandle, const Vec3d&) { ++moves; };
    OperatorContext ctx(mesh, model, hooks);
    const VertexHandle v = vertex_at(mesh, Vec3d(2, 2, roof(2)));
    REQUIRE(v.is_valid());
    const Vec3d target(2.2, 2, roof(2.2));
    // (The grid's diagonals are 1.45 long; the snap stretches one to 1.6.)
    const SnapOptions options = crest_snap_options(0.66, 1.7);
    REQUIRE(distance_to_mesh(mesh, target) > 0.08);
    std::vector<double> before;
    for (const Vec3d& w : options.witnesses) before.push_back(distance_to_mesh(mesh, w));
    const std::size_t faces = mesh.n_faces(), vertices = mesh.n_vertices();

    const OpResult r = try_snap_vertex(ctx, v, target, options);
    REQUIRE(r.done());
    CHECK(moves == 1);
    CHECK(mesh.n_faces() == faces);
    CHECK(mesh.n_vertices() == vertices);
    const Vec3d p = mesh.point(v);
    CHECK(p[2] == doctest::Approx(roof(p[0])));  // on the model
    CHECK(distance_to_mesh(mesh, target) <= options.tolerance);
    for (std::size_t i = 0; i < options.witnesses.size(); ++i)
        CHECK(distance_to_mesh(mesh, options.witnesses[i]) <=
              std::max(options.tolerance, before[i]) + 1e-12);
    const MovedStarDefects defects =
        moved_star_defects(mesh, v, options.min_angle_deg, options.min_length, options.max_length);
    CHECK(defects.folded == 0);
    CHECK(defects.small_angles == 0);
    CHECK(defects.edges_out_of_band == 0);
}

TEST_CASE("snap asks allow_move with the point it would commit, and a veto changes nothing")
{
    // The crest snap of the case above, vetoed by the caller (the coupling code's hook).
    SurfaceMesh mesh = roof_grid();
    RoofProjector model;
    SurfaceHooks hooks;
    int asked = 0, moves = 0;
    const Vec3d target(2.2, 2, roof(2.2));
    hooks.allow_move = [&](const SurfaceMesh&, VertexHandle, const Vec3d& point) {
        CHECK(point[2] == doctest::Approx(roof(point[0])));  // on the model, where it would go
        ++asked;
        return false;
    };
    hooks.on_move = [&](const SurfaceMesh&, VertexHandle, const Vec3d&) { ++moves; };
    OperatorContext ctx(mesh, model, hooks);
    const VertexHandle v = vertex_at(mesh, Vec3d(2, 2, roof(2)));
    REQUIRE(v.is_valid());
    const SnapOptions options = crest_snap_options(0.66, 1.7);
    std::vector<Vec3d> before;
    for (auto w : mesh.vertices()) before.push_back(mesh.point(w));
    CHECK(try_snap_vertex(ctx, v, target, options).status == OpStatus::Hook);
    CHECK(asked == 1);
    CHECK(moves == 0);
    std::vector<Vec3d> after;
    for (auto w : mesh.vertices()) after.push_back(mesh.point(w));
    CHECK(after == before);
}

TEST_CASE(
    "snap refuses a corner, a boundary vertex past its curve neighbour, a worse star, and changes "
    "nothing")
{
    //   The same roof grid. (0,0) is a corner; the boundary vertex (2,0) may slide along y = 0
    //   between (1,0) and (3,0) only; an angle bound above the grid's 45° refuses any move.
    SurfaceMesh mesh = roof_grid();
    const SurfaceMesh original = mesh;
    RoofProjector model;
    OperatorContext ctx(mesh, model, {});
    SnapOptions options;
    options.tolerance = 0.05;
    options.witnesses = roof_samples();

    const VertexHandle corner = vertex_at(mesh, Vec3d(0, 0, roof(0)));
    REQUIRE(corner.is_valid());
    CHECK(try_snap_vertex(ctx, corner, Vec3d(0.3, 0.2, roof(0.3)), options).status ==
          OpStatus::Class);
    const VertexHandle boundary = vertex_at(mesh, Vec3d(2, 0, roof(2)));
    REQUIRE(boundary.is_valid());
    CHECK(try_snap_vertex(ctx, boundary, Vec3d(3.5, 0, roof(3.5)), options).status ==
          OpStatus::Class);
    SnapOptions strict = options;
    strict.min_angle_deg = 60.0;
    const VertexHandle v = vertex_at(mesh, Vec3d(2, 2, roof(2)));
    CHECK(try_snap_vertex(ctx, v, Vec3d(2.2, 2, roof(2.2)), strict).status == OpStatus::Quality);
    CHECK(points_of(mesh) == points_of(original));
}

TEST_CASE("snap shortens an edge already under the band only down to its floor")
{
    //   The roof grid with a band starting at 1.2: its unit edges are all under it. Snapping
    //   v = (2, 2) toward the crest shortens its edge to (3, 2) (to 0.8 the whole way): refused
    //   without a floor, done with a floor of 0.5, and no edge of the star ends under the floor.
    RoofProjector model;
    const Vec3d target(2.2, 2, roof(2.2));
    SnapOptions options = crest_snap_options(1.2, 3.0);
    {
        SurfaceMesh mesh = roof_grid();
        OperatorContext ctx(mesh, model, {});
        const std::vector<Vec3d> before = points_of(mesh);
        CHECK(try_snap_vertex(ctx, vertex_at(mesh, Vec3d(2, 2, roof(2))), target, options).status ==
              OpStatus::Quality);
        CHECK(points_of(mesh) == before);
    }
    SurfaceMesh mesh = roof_grid();
    OperatorContext ctx(mesh, model, {});
    const VertexHandle v = vertex_at(mesh, Vec3d(2, 2, roof(2)));
    options.floor_length = 0.5;
    REQUIRE(try_snap_vertex(ctx, v, target, options).done());
    CHECK(distance_to_mesh(mesh, target) <= options.tolerance);
    for (auto w : mesh.vv_range(v))
        CHECK((mesh.point(w) - mesh.point(v)).norm() >= options.floor_length);
}

TEST_CASE("point grid finds exactly the points within a radius")
{
    std::vector<Vec3d> points;
    for (int i = 0; i < 7; ++i)
        for (int j = 0; j < 7; ++j)
            for (int k = 0; k < 3; ++k) points.emplace_back(0.37 * i - 1.0, 0.41 * j, -0.29 * k);
    const PointGrid grid(points, 0.5);
    for (const Vec3d& centre : {Vec3d(0, 0, 0), Vec3d(0.5, 1.2, -0.3), Vec3d(-5, -5, -5)})
        for (const double radius : {0.0, 0.3, 0.8, 2.0})
        {
            std::vector<std::size_t> expected;
            for (std::size_t i = 0; i < points.size(); ++i)
                if ((points[i] - centre).norm() <= radius) expected.push_back(i);
            CHECK(grid.within(centre, radius) == expected);
        }
}
