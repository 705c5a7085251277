// The local operators of surface/ on tiny meshes built here, each drawn, each checked for the
// invariants the remesher relies on: vertices on the model, consistent outward orientation,
// Euler characteristic, classes and curves kept, and refusals that leave the mesh untouched.

#include <doctest/doctest.h>

#include <cmath>
#include <map>

#include "surface/local_ops.h"
#include "surface/surface_quality.h"
#include "surface_fixtures.h"

using namespace hdimesh::surface;

namespace
{

using hdimesh::surface::fixtures::PlaneProjector;

using hdimesh::surface::fixtures::icosahedron;

// A flat n×n grid of unit squares in z = 0, each cut by its (i,j)-(i+1,j+1) diagonal.
SurfaceMesh grid(int n)
{
    SurfaceMesh mesh =
        hdimesh::surface::fixtures::triangulated_grid(n, [](int, int) { return 0.0; });
    SurfaceProperties props(mesh);
    for (auto x : mesh.vertices())
    {
        mesh.property(props.vertex_curve, x) = kNoCurve;
        mesh.property(props.vertex_class, x) =
            mesh.is_boundary(x) ? VertexClass::Boundary : VertexClass::Smooth;
        if (mesh.is_boundary(x)) mesh.property(props.vertex_curve, x) = 0;
    }
    for (auto e : mesh.edges())
        mesh.property(props.edge_curve, e) = mesh.is_boundary(e) ? 0 : kNoCurve;
    for (auto x : mesh.faces()) mesh.property(props.face_ref, x) = 1;
    return mesh;
}

using hdimesh::surface::fixtures::vertex_at;

int euler(const SurfaceMesh& mesh)
{
    int v = 0, e = 0, f = 0;
    for (auto x : mesh.vertices())
        if (!mesh.status(x).deleted()) ++v;
    for (auto x : mesh.edges())
        if (!mesh.status(x).deleted()) ++e;
    for (auto x : mesh.faces())
        if (!mesh.status(x).deleted()) ++f;
    return v - e + f;
}

// Every face of a closed mesh around the origin faces outward; every vertex is on the sphere.
void check_on_unit_sphere(const SurfaceMesh& mesh)
{
    for (auto v : mesh.vertices())
        CHECK(mesh.point(v).norm() == doctest::Approx(1.0).epsilon(1e-12));
    for (auto f : mesh.faces())
    {
        std::vector<Vec3d> p;
        for (auto v : mesh.fv_range(f)) p.push_back(mesh.point(v));
        const Vec3d n = OpenMesh::cross(p[1] - p[0], p[2] - p[0]);
        CHECK(OpenMesh::dot(n, p[0] + p[1] + p[2]) > 0.0);
        CHECK(triangle_qe(p[0], p[1], p[2]) > 0.0);
    }
}

// Plane faces face +z with positive area.
void check_planar_up(const SurfaceMesh& mesh)
{
    for (auto f : mesh.faces())
    {
        std::vector<Vec3d> p;
        for (auto v : mesh.fv_range(f)) p.push_back(mesh.point(v));
        CHECK(OpenMesh::cross(p[1] - p[0], p[2] - p[0])[2] > 0.0);
        for (const auto& q : p) CHECK(q[2] == 0.0);
    }
}

double total_area(const SurfaceMesh& mesh)
{
    double a = 0.0;
    for (auto f : mesh.faces()) a += mesh.calc_face_area(f);
    return a;
}

}  // namespace

TEST_CASE("split puts the new vertex on the model and keeps the sphere closed and outward")
{
    //   an icosahedron edge (a, b) is cut at its midpoint, which is pushed out onto the sphere:
    //        c              c
    //       / \            /|\       .
    //      a---b   ->     a-m-b
    //       \ /            \|/
    //        d              d
    SurfaceMesh mesh = icosahedron();
    SphereProjector sphere(Vec3d(0, 0, 0), 1.0);
    SurfaceHooks hooks;
    VertexHandle seen_a, seen_b, seen_new;
    hooks.on_split = [&](const SurfaceMesh&, VertexHandle a, VertexHandle b, VertexHandle m) {
        seen_a = a;
        seen_b = b;
        seen_new = m;
    };
    OperatorContext ctx(mesh, sphere, hooks);
    const EdgeHandle e = *mesh.edges().begin();
    const auto h = mesh.halfedge_handle(e, 0);
    const VertexHandle a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
    const OpResult r = try_split(ctx, e);
    REQUIRE(r.done());
    CHECK(mesh.n_vertices() == 13);
    CHECK(mesh.n_faces() == 22);
    CHECK(euler(mesh) == 2);
    CHECK(seen_new == r.vertex);
    CHECK(((seen_a == a && seen_b == b) || (seen_a == b && seen_b == a)));
    CHECK(mesh.valence(r.vertex) == 4);
    CHECK(mesh.property(ctx.props.vertex_class, r.vertex) == VertexClass::Smooth);
    for (auto f : mesh.vf_range(r.vertex)) CHECK(mesh.property(ctx.props.face_ref, f) == 1);
    check_on_unit_sphere(mesh);
}

TEST_CASE("Mmg's -noinsert, -noswap, -nomove: each kind of change refused, nothing changed")
{
    // the icosahedron again; with every kind turned off, no operator changes it
    SurfaceMesh mesh = icosahedron();
    SphereProjector sphere(Vec3d(0, 0, 0), 1.0);
    OperatorLimits off;
    off.insert = off.swap = off.move = false;
    OperatorContext ctx(mesh, sphere, {}, off);
    const EdgeHandle e = *mesh.edges().begin();
    const VertexHandle v = *mesh.vertices().begin();
    const Vec3d at = mesh.point(v);
    CHECK(try_split(ctx, e).status == OpStatus::Disabled);
    CHECK(try_collapse(ctx, mesh.halfedge_handle(e, 0), 10.0).status == OpStatus::Disabled);
    CHECK(try_remove_vertex(ctx, v).status == OpStatus::Disabled);
    CHECK(try_flip(ctx, e, FlipGoal::Valence).status == OpStatus::Disabled);
    CHECK(commit_move(ctx, v, at * 0.9, -1).status == OpStatus::Disabled);
    CHECK(mesh.n_vertices() == 12);
    CHECK(mesh.point(v) == at);
}

TEST_CASE(
    "split of a boundary edge makes a boundary vertex on the same curve, only its halves are curve "
    "edges")
{
    //  (0,0)---m---(1,0)  bottom boundary edge of the grid, m its midpoint
    SurfaceMesh mesh = grid(1);
    PlaneProjector plane;
    SurfaceHooks hooks;
    OperatorContext ctx(mesh, plane, hooks);
    const VertexHandle a = vertex_at(mesh, Vec3d(0, 0, 0)), b = vertex_at(mesh, Vec3d(1, 0, 0));
    const EdgeHandle e = mesh.edge_handle(mesh.find_halfedge(a, b));
    // Without a curve to project on (curve 0 is unknown to the plane projector, which ignores it),
    // the midpoint itself is used.
    const OpResult r = try_split(ctx, e);
    REQUIRE(r.done());
    CHECK(mesh.point(r.vertex) == Vec3d(0.5, 0, 0));
    CHECK(mesh.property(ctx.props.vertex_class, r.vertex) == VertexClass::Boundary);
    CHECK(mesh.property(ctx.props.vertex_curve, r.vertex) == 0);
    int curve_edges = 0;
    for (auto oh : mesh.voh_range(r.vertex))
    {
        const EdgeHandle x = mesh.edge_handle(oh);
        const bool is_half = mesh.to_vertex_handle(oh) == a || mesh.to_vertex_handle(oh) == b;
        CHECK((mesh.property(ctx.props.edge_curve, x) == 0) == is_half);
        curve_edges += is_half ? 1 : 0;
    }
    CHECK(curve_edges == 2);
    CHECK(total_area(mesh) == doctest::Approx(1.0));
    check_planar_up(mesh);
}

TEST_CASE(
    "collapse keeps a corner, refuses a curve vertex leaving its curve, and removes a smooth "
    "vertex")
{
    //   3x3 grid; the centre-ish vertex (1,1) is smooth, (0,0) a corner, (1,0) on the boundary
    //   (2,0)-(1,0) is a boundary edge, (1,0)-(1,1) crosses into the interior.
    //   (0,3)---(3,3)
    //     |  x  x  |
    //   (0,0)-(1,0)-(2,0)-(3,0)
    SurfaceMesh mesh = grid(3);
    PlaneProjector plane;
    SurfaceHooks hooks;
    OperatorContext ctx(mesh, plane, hooks);
    const VertexHandle corner = vertex_at(mesh, Vec3d(0, 0, 0));
    mesh.property(ctx.props.vertex_class, corner) = VertexClass::Corner;
    mesh.property(ctx.props.vertex_curve, corner) = kNoCurve;
    const VertexHandle b10 = vertex_at(mesh, Vec3d(1, 0, 0)), b20 = vertex_at(mesh, Vec3d(2, 0, 0));
    const VertexHandle s11 = vertex_at(mesh, Vec3d(1, 1, 0)), s22 = vertex_at(mesh, Vec3d(2, 2, 0));
    const double area = total_area(mesh);

    CHECK(try_collapse(ctx, mesh.find_halfedge(corner, b10), 0.0).status == OpStatus::Class);
    CHECK(try_collapse(ctx, mesh.find_halfedge(b10, s11), 0.0).status == OpStatus::Class);
    // An edge bound: moving (1,1) onto (2,2) would make edges longer than 1.5.
    CHECK(try_collapse(ctx, mesh.find_halfedge(s11, s22), 1.5).status == OpStatus::Quality);
    CHECK(mesh.n_faces() == 18);

    // Along the boundary curve: (1,0) goes onto (2,0); the curve stays a curve.
    REQUIRE(try_collapse(ctx, mesh.find_halfedge(b10, b20), 0.0).done());
    CHECK(mesh.status(b10).deleted());
    const HalfedgeHandle along = mesh.find_halfedge(corner, b20);
    REQUIRE(along.is_valid());
    CHECK(mesh.property(ctx.props.edge_curve, mesh.edge_handle(along)) == 0);
    CHECK(mesh.is_boundary(mesh.edge_handle(along)));
    mesh.garbage_collection();
    CHECK(euler(mesh) == 1);
    CHECK(total_area(mesh) == doctest::Approx(area));
    check_planar_up(mesh);
}

TEST_CASE("a collapse that would fold a triangle is refused")
{
    //   2x2 grid, centre c = (1,1); the ring vertex (1,2) is pulled down to (1,1.4), making the
    //   ring reflex there. Collapsing c onto (0,1) would turn (c, (2,2), (1,1.4)) into
    //   ((0,1), (2,2), (1,1.4)), which is upside down.
    //   (0,2)--(1,2)--(2,2)          (0,2)----------(2,2)
    //     |      |  /  |               |    (1,1.4) /  |
    //   (0,1)--(1,1)--(2,1)    ->    (0,1)--c-----(2,1)
    SurfaceMesh mesh = grid(2);
    PlaneProjector plane;
    SurfaceHooks hooks;
    OperatorContext ctx(mesh, plane, hooks);
    const VertexHandle centre = vertex_at(mesh, Vec3d(1, 1, 0));
    const VertexHandle left = vertex_at(mesh, Vec3d(0, 1, 0)),
                       top = vertex_at(mesh, Vec3d(1, 2, 0));
    mesh.set_point(top, Vec3d(1.0, 1.4, 0.0));
    check_planar_up(mesh);
    const auto faces_before = mesh.n_faces();
    const OpResult r = try_collapse(ctx, mesh.find_halfedge(centre, left), 0.0);
    CHECK(r.status == OpStatus::Geometry);
    CHECK(mesh.n_faces() == faces_before);
    CHECK(!mesh.status(centre).deleted());
    // Onto (0,0) nothing folds: done.
    CHECK(
        try_collapse(ctx, mesh.find_halfedge(centre, vertex_at(mesh, Vec3d(0, 0, 0))), 0.0).done());
    mesh.garbage_collection();
    check_planar_up(mesh);
    CHECK(total_area(mesh) ==
          doctest::Approx(4.0 - 0.6));  // the square minus the notch under (1,1.4)
}

TEST_CASE("flip raises the worst quality of a bad pair, refuses a curve edge and honours the hook")
{
    //      c (0.5, 1)           the diagonal a-b of this thin quad makes two needles;
    //   a /\ b                  the flip to c-d gives two fair triangles.
    //  (0,0)-(1,0)  ... built as a kite: a=(0,0) b=(1,0) c=(0.5,0.3) d=(0.5,-0.3)
    SurfaceMesh mesh;
    SurfaceProperties props(mesh);
    const VertexHandle a = mesh.add_vertex(Vec3d(0, 0, 0)), b = mesh.add_vertex(Vec3d(1, 0, 0));
    const VertexHandle c = mesh.add_vertex(Vec3d(0.5, 0.3, 0)),
                       d = mesh.add_vertex(Vec3d(0.5, -0.3, 0));
    mesh.add_face(a, b, c);
    mesh.add_face(b, a, d);
    SurfaceProperties init(mesh);
    for (auto e : mesh.edges()) mesh.property(init.edge_curve, e) = kNoCurve;
    for (auto f : mesh.faces()) mesh.property(init.face_ref, f) = 0;
    for (auto v : mesh.vertices()) mesh.property(init.vertex_class, v) = VertexClass::Boundary;
    PlaneProjector plane;
    SurfaceHooks hooks;
    bool veto = true;
    hooks.allow_flip = [&](const SurfaceMesh&, EdgeHandle) { return !veto; };
    OperatorContext ctx(mesh, plane, hooks);
    const EdgeHandle diagonal = mesh.edge_handle(mesh.find_halfedge(a, b));
    double before = 1.0;
    for (auto f : mesh.faces()) before = std::min(before, face_qe(mesh, f));

    CHECK(try_flip(ctx, diagonal, FlipGoal::Quality).status == OpStatus::Hook);
    veto = false;
    mesh.property(ctx.props.edge_curve, diagonal) = 3;
    CHECK(try_flip(ctx, diagonal, FlipGoal::Quality).status == OpStatus::Class);
    mesh.property(ctx.props.edge_curve, diagonal) = kNoCurve;
    REQUIRE(try_flip(ctx, diagonal, FlipGoal::Quality).done());
    CHECK(mesh.find_halfedge(c, d).is_valid());
    CHECK(!mesh.find_halfedge(a, b).is_valid());
    double after = 1.0;
    for (auto f : mesh.faces()) after = std::min(after, face_qe(mesh, f));
    CHECK(after > before);
    CHECK(total_area(mesh) == doctest::Approx(0.3));
    check_planar_up(mesh);
    // Flipping back would lower the quality: refused.
    CHECK(try_flip(ctx, mesh.edge_handle(mesh.find_halfedge(c, d)), FlipGoal::Quality).status ==
          OpStatus::Quality);
}

TEST_CASE("vertex removal retriangulates the hole better, conserving the area")
{
    //   a 4x4 grid whose vertex (2,2) is pushed next to (1,1): its fan of six triangles has
    //   needles; removing it and triangulating the hexagonal ring is better.
    SurfaceMesh mesh = grid(4);
    PlaneProjector plane;
    SurfaceHooks hooks;
    std::size_t new_faces = 0;
    hooks.on_remove_vertex = [&](const SurfaceMesh&, VertexHandle,
                                 const std::vector<FaceHandle>& faces) {
        new_faces = faces.size();
    };
    OperatorContext ctx(mesh, plane, hooks);
    const VertexHandle centre = vertex_at(mesh, Vec3d(2, 2, 0));
    mesh.set_point(centre, Vec3d(1.2, 1.25, 0));
    double before = 1.0;
    for (auto f : mesh.vf_range(centre)) before = std::min(before, face_qe(mesh, f));
    REQUIRE(try_remove_vertex(ctx, centre).done());
    CHECK(new_faces == 4);  // a hexagonal ring
    mesh.garbage_collection();
    CHECK(mesh.n_vertices() == 24);
    CHECK(mesh.n_faces() == 30);
    double after = 1.0;
    for (auto f : mesh.faces()) after = std::min(after, face_qe(mesh, f));
    CHECK(after > before);
    CHECK(total_area(mesh) == doctest::Approx(16.0));
    check_planar_up(mesh);
    CHECK(euler(mesh) == 1);
    // A boundary (curve) vertex is never removed.
    CHECK(try_remove_vertex(ctx, vertex_at(mesh, Vec3d(2, 0, 0))).status == OpStatus::Class);
}

// The 3x3 grid with its interior vertex (1,1) displaced to (1.6, 1.55), on the plane z = 0; the
// hooks count the moves. (Built in place: the hooks point back at it.)
struct DisplacedCentre
{
    SurfaceMesh mesh = grid(3);
    PlaneProjector plane;
    int moves = 0;
    OperatorContext ctx;
    VertexHandle v;
    const Vec3d displaced{1.6, 1.55, 0};

    DisplacedCentre() : ctx(mesh, plane, counting_moves(moves))
    {
        v = vertex_at(mesh, Vec3d(1, 1, 0));
        mesh.set_point(v, displaced);
    }
    DisplacedCentre(const DisplacedCentre&) = delete;
    DisplacedCentre& operator=(const DisplacedCentre&) = delete;

    static SurfaceHooks counting_moves(int& moves)
    {
        SurfaceHooks hooks;
        hooks.on_move = [&moves](const SurfaceMesh&, VertexHandle, const Vec3d&) { ++moves; };
        return hooks;
    }
};

TEST_CASE("nodal shifting moves a displaced vertex back toward the balanced point, on the model")
{
    //   3x3 grid; the interior vertex (1,1) is displaced to (1.6, 1.55): shifting raises the
    //   worst Qe of its ball and keeps z = 0. Corners and curve ends do not move.
    DisplacedCentre grid_case;
    SurfaceMesh& mesh = grid_case.mesh;
    OperatorContext& ctx = grid_case.ctx;
    const int& moves = grid_case.moves;
    const VertexHandle v = grid_case.v;
    auto ball = [&]() {
        double q = 1.0;
        for (auto f : mesh.vf_range(v)) q = std::min(q, face_qe(mesh, f));
        return q;
    };
    const double before = ball();
    ShiftOptions smart;
    for (int i = 0; i < 5; ++i) shift_vertex(ctx, v, smart);
    CHECK(moves >= 1);
    CHECK(ball() > before);
    CHECK(mesh.point(v)[2] == 0.0);
    CHECK((mesh.point(v) - Vec3d(1, 1, 0)).norm() < (Vec3d(1.6, 1.55, 0) - Vec3d(1, 1, 0)).norm());
    check_planar_up(mesh);
    const VertexHandle corner = vertex_at(mesh, Vec3d(0, 0, 0));
    mesh.property(ctx.props.vertex_class, corner) = VertexClass::Corner;
    CHECK(shift_vertex(ctx, corner).status == OpStatus::Class);
    CHECK(mesh.point(corner) == Vec3d(0, 0, 0));
}

TEST_CASE(
    "nodal shifting asks the caller's accept layer with the point it would commit, before "
    "committing")
{
    //   The displaced vertex of the test above: a refusing layer leaves the mesh, the hint and
    //   the hooks untouched; an accepting one is asked with exactly the point then committed.
    DisplacedCentre grid_case;
    SurfaceMesh& mesh = grid_case.mesh;
    OperatorContext& ctx = grid_case.ctx;
    const int& moves = grid_case.moves;
    const VertexHandle v = grid_case.v;
    const Vec3d displaced = grid_case.displaced;
    const int hint = ctx.model_face(v);

    std::vector<Vec3d> asked;
    ShiftOptions refusing;
    refusing.accept = [&](const Vec3d& p) {
        asked.push_back(p);
        return false;
    };
    CHECK(shift_vertex(ctx, v, refusing).status == OpStatus::Geometry);
    CHECK(asked.size() == 1);  // refused: no smaller step is tried
    CHECK(mesh.point(v) == displaced);
    CHECK(ctx.model_face(v) == hint);
    CHECK(moves == 0);

    asked.clear();
    ShiftOptions accepting;
    accepting.accept = [&](const Vec3d& p) {
        asked.push_back(p);
        return true;
    };
    REQUIRE(shift_vertex(ctx, v, accepting).done());
    REQUIRE(asked.size() == 1);
    CHECK(mesh.point(v) == asked.front());
    CHECK(asked.front() != displaced);
    CHECK(moves == 1);
}

TEST_CASE(
    "quality measures: Qe of an equilateral triangle is 1, angles, Hausdorff of two parallel "
    "squares")
{
    const Vec3d a(0, 0, 0), b(1, 0, 0), c(0.5, std::sqrt(3.0) / 2.0, 0);
    CHECK(triangle_qe(a, b, c) == doctest::Approx(1.0));
    CHECK(triangle_min_angle_deg(a, b, c) == doctest::Approx(60.0));
    CHECK(triangle_qe(a, b, Vec3d(2, 0, 0)) == 0.0);
    SurfaceMesh lower = grid(2), upper = grid(2);
    for (auto v : upper.vertices()) upper.set_point(v, upper.point(v) + Vec3d(0, 0, 0.25));
    const auto d = hausdorff_distance(lower, upper);
    CHECK(d[0] == doctest::Approx(0.25));
    CHECK(d[1] == doctest::Approx(0.25));
    const QualityReport r = measure_quality(lower, 1.0);
    CHECK(r.faces == 8);
    CHECK(r.min_angle_deg == doctest::Approx(45.0));
    CHECK(r.max_angle_deg == doctest::Approx(90.0));
    // 12 unit edges (Qt = 1) and 4 diagonals of √2 (Qt = 0.707): all ≥ 0.66.
    CHECK(r.percent_qt_ge_066 == doctest::Approx(100.0));
}
