// The curve fit (fit_curve_vertex) on a tiny mesh built here: a boundary vertex slides along a
// zig-zag boundary polyline onto the zig its chords cut; the zig comes within the tolerance, the
// vertex stays on its curve, the star keeps its angles and orientation; refusals change nothing.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "surface/detail/closest_point_tree.h"
#include "surface/fit_curve_vertex.h"
#include "surface/surface_quality.h"
#include "surface_fixtures.h"

using namespace hdimesh::surface;

namespace
{

// The input's lower boundary (curve 0) zig-zags: a zig of depth 0.15 at x = 1.1.
const Vec3d kZigPolyline[] = {Vec3d(0, 0, 0), Vec3d(1.1, -0.15, 0), Vec3d(2, 0, 0), Vec3d(4, 0, 0)};

Vec3d closest_on_zig(const Vec3d& p)
{
    Vec3d best = kZigPolyline[0];
    for (int i = 0; i + 1 < 4; ++i)
    {
        const Vec3d a = kZigPolyline[i], b = kZigPolyline[i + 1];
        const double t = std::clamp(OpenMesh::dot(p - a, b - a) / (b - a).sqrnorm(), 0.0, 1.0);
        const Vec3d q = a + t * (b - a);
        if ((q - p).norm() < (best - p).norm()) best = q;
    }
    return best;
}

// The plane z = 0; curve 0 is the zig-zag polyline, the other boundary sides (curve 1) lie on
// the grid's own boundary.
class ZigProjector final : public Projector
{
public:
    ProjectedPoint project(const Vec3d& p, VertexClass cls, int curve) const override
    {
        ProjectedPoint out;
        out.point =
            cls == VertexClass::Boundary && curve == 0 ? closest_on_zig(p) : Vec3d(p[0], p[1], 0);
        out.normal = Vec3d(0, 0, 1);
        out.ok = true;
        return out;
    }
};

// The 4×4 grid of unit squares in z = 0: its lower side on curve 0, the other sides on curve 1,
// the four grid corners as corners.
SurfaceMesh zig_grid()
{
    SurfaceMesh mesh =
        hdimesh::surface::fixtures::triangulated_grid(4, [](int, int) { return 0.0; });
    hdimesh::surface::fixtures::mark_all_smooth(mesh);
    // The rim: curve 0 along y = 0, curve 1 the rest, between the four corners.
    SurfaceProperties props(mesh);
    auto curve_of = [](const Vec3d& a, const Vec3d& b) { return a[1] == 0 && b[1] == 0 ? 0 : 1; };
    for (auto v : mesh.vertices())
    {
        if (!mesh.is_boundary(v)) continue;
        const Vec3d p = mesh.point(v);
        const bool corner = (p[0] == 0 || p[0] == 4) && (p[1] == 0 || p[1] == 4);
        mesh.property(props.vertex_class, v) = corner ? VertexClass::Corner : VertexClass::Boundary;
        mesh.property(props.vertex_curve, v) = corner ? kNoCurve : curve_of(p, p);
    }
    for (auto e : mesh.edges())
    {
        if (!mesh.is_boundary(e)) continue;
        const auto h = mesh.halfedge_handle(e, 0);
        mesh.property(props.edge_curve, e) =
            curve_of(mesh.point(mesh.from_vertex_handle(h)), mesh.point(mesh.to_vertex_handle(h)));
    }
    return mesh;
}

using hdimesh::surface::fixtures::vertex_at;

using hdimesh::surface::fixtures::distance_to_mesh;

// The input's samples near the lower side: the polyline's vertices and edge midpoints.
std::vector<Vec3d> zig_witnesses()
{
    std::vector<Vec3d> points;
    for (int i = 0; i < 4; ++i) points.push_back(kZigPolyline[i]);
    for (int i = 0; i + 1 < 4; ++i) points.push_back(0.5 * (kZigPolyline[i] + kZigPolyline[i + 1]));
    return points;
}

using hdimesh::surface::fixtures::moved_star_defects;
using hdimesh::surface::fixtures::MovedStarDefects;
using hdimesh::surface::fixtures::points_of;

}  // namespace

TEST_CASE("fit_curve_vertex slides a boundary vertex onto the zig its chords cut")
{
    //   y                 The lower side's output chords run along y = 0; the input's boundary
    //   1 +---+---+---    dips to Z = (1.1, -0.15), 0.15 from the output (tolerance 0.05).
    //     |  /|  /|       Sliding v = (1, 0) along the polyline onto Z brings it in.
    //   0 +---v---+---+ x
    //          \ /
    //           Z
    SurfaceMesh mesh = zig_grid();
    ZigProjector model;
    SurfaceHooks hooks;
    int moves = 0;
    hooks.on_move = [&](const SurfaceMesh&, VertexHandle, const Vec3d&) { ++moves; };
    OperatorContext ctx(mesh, model, hooks);
    const VertexHandle v = vertex_at(mesh, Vec3d(1, 0, 0));
    REQUIRE(v.is_valid());
    CurveFitOptions options;
    options.tolerance = 0.05;
    options.min_angle_deg = 30.0;
    options.min_length = 0.66;
    options.max_length = 1.7;
    options.witnesses = zig_witnesses();
    const Vec3d zig = kZigPolyline[1];
    REQUIRE(distance_to_mesh(mesh, zig) > 0.1);
    const std::size_t faces = mesh.n_faces(), vertices = mesh.n_vertices();

    const OpResult r = fit_curve_vertex(ctx, v, options);
    REQUIRE(r.done());
    CHECK(moves == 1);
    CHECK(mesh.n_faces() == faces);
    CHECK(mesh.n_vertices() == vertices);
    const Vec3d p = mesh.point(v);
    CHECK((closest_on_zig(p) - p).norm() < 1e-12);  // on its curve
    for (const Vec3d& w : options.witnesses) CHECK(distance_to_mesh(mesh, w) <= options.tolerance);
    const MovedStarDefects defects =
        moved_star_defects(mesh, v, options.min_angle_deg, options.min_length, options.max_length);
    CHECK(defects.folded == 0);
    CHECK(defects.small_angles == 0);
    CHECK(defects.edges_out_of_band == 0);
}

TEST_CASE(
    "fit_curve_vertex refuses a smooth vertex, a corner and a vertex already near, and changes "
    "nothing")
{
    SurfaceMesh mesh = zig_grid();
    ZigProjector model;
    OperatorContext ctx(mesh, model, {});
    CurveFitOptions options;
    options.tolerance = 0.05;
    options.witnesses = zig_witnesses();
    const std::vector<Vec3d> before = points_of(mesh);
    CHECK(fit_curve_vertex(ctx, vertex_at(mesh, Vec3d(1, 1, 0)), options).status ==
          OpStatus::Class);
    CHECK(fit_curve_vertex(ctx, vertex_at(mesh, Vec3d(0, 0, 0)), options).status ==
          OpStatus::Class);
    // (3, 0): its chords follow the straight part of the polyline; nothing to gain.
    CHECK(fit_curve_vertex(ctx, vertex_at(mesh, Vec3d(3, 0, 0)), options).status ==
          OpStatus::Quality);
    CHECK(points_of(mesh) == before);
}

TEST_CASE(
    "fit_curve_vertex shortens an edge already under the band only with a floor, and never below "
    "it")
{
    // The grid's unit edges are all under a band starting at 1.2: the fit onto the zig Z shortens
    // v's edge to (2, 0) from 1 to 0.91. Without a floor that is refused; with a floor under 0.91
    // it is done (no edge newly leaves the band); with a floor over it, refused again.
    ZigProjector model;
    auto options_with_floor = [](double floor) {
        CurveFitOptions options;
        options.tolerance = 0.05;
        options.min_angle_deg = 30.0;
        options.min_length = 1.2;
        options.max_length = 3.0;
        options.floor_length = floor;
        options.witnesses = zig_witnesses();
        return options;
    };
    for (const double floor : {0.0, 0.95})
    {
        SurfaceMesh mesh = zig_grid();
        OperatorContext ctx(mesh, model, {});
        const std::vector<Vec3d> before = points_of(mesh);
        CHECK_FALSE(
            fit_curve_vertex(ctx, vertex_at(mesh, Vec3d(1, 0, 0)), options_with_floor(floor))
                .done());
        CHECK(points_of(mesh) == before);
    }
    SurfaceMesh mesh = zig_grid();
    OperatorContext ctx(mesh, model, {});
    const VertexHandle v = vertex_at(mesh, Vec3d(1, 0, 0));
    const CurveFitOptions options = options_with_floor(0.5);
    REQUIRE(fit_curve_vertex(ctx, v, options).done());
    for (auto w : mesh.vv_range(v))
        CHECK((mesh.point(w) - mesh.point(v)).norm() >= options.floor_length);
    CHECK(distance_to_mesh(mesh, kZigPolyline[1]) <= options.tolerance);
}
