// relocate_vertex: a vertex goes to the trial point where the worst Qe of its star is largest;
// a curve vertex stays on its curve; a star it cannot improve, or a caller's veto, leaves the
// mesh untouched.

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "surface/local_ops.h"
#include "surface/surface_quality.h"
#include "surface_fixtures.h"

using namespace hdimesh::surface;

namespace
{

double worst_qe_around(const SurfaceMesh& mesh, VertexHandle v)
{
    double worst = 1.0;
    for (auto f : mesh.vf_range(v))
    {
        std::vector<Vec3d> p;
        for (auto x : mesh.fv_range(f)) p.push_back(mesh.point(x));
        worst = std::min(worst, triangle_qe(p[0], p[1], p[2]));
    }
    return worst;
}

// Flat, in z = 0: a regular hexagon of unit radius around V, V at `centre`.
//
//        H2 ---- H1
//       /  \    /  \ .
//     H3 ---- V ---- H0
//       \  /    \  / .
//        H4 ---- H5
struct Hexagon
{
    SurfaceMesh mesh;
    VertexHandle centre;

    explicit Hexagon(const Vec3d& at)
    {
        centre = mesh.add_vertex(at);
        std::vector<VertexHandle> ring;
        for (int k = 0; k < 6; ++k)
            ring.push_back(
                mesh.add_vertex(Vec3d(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0)));
        for (int k = 0; k < 6; ++k) mesh.add_face(centre, ring[k], ring[(k + 1) % 6]);
        fixtures::mark_all_smooth(mesh);
        SurfaceProperties props(mesh);
        for (const VertexHandle v : ring)
            mesh.property(props.vertex_class, v) = VertexClass::Corner;
    }
};

// Flat, in z = 0: a ridge along x (curve 0: P-Q-R, P and R corners) with Q pushed toward P, so
// the triangle P Q T is a needle-like right triangle; T and U are corners too.
//
//       T (0.2,0.9)      U (1.7,0.9)
//      /  \         ___/   |
//     /     \   ___/       |
//    P ---- Q ------------ R       P = (0,0), Q = (0.3,0), R = (2,0)
//
// Faces: P Q T, Q U T, Q R U.
struct SqueezedRidge
{
    SurfaceMesh mesh;
    VertexHandle p, q, r, t, u;

    SqueezedRidge()
    {
        p = mesh.add_vertex(Vec3d(0, 0, 0));
        q = mesh.add_vertex(Vec3d(0.3, 0, 0));
        r = mesh.add_vertex(Vec3d(2, 0, 0));
        t = mesh.add_vertex(Vec3d(0.2, 0.9, 0));
        u = mesh.add_vertex(Vec3d(1.7, 0.9, 0));
        mesh.add_face(p, q, t);
        mesh.add_face(q, u, t);
        mesh.add_face(q, r, u);
        fixtures::mark_all_smooth(mesh);
        SurfaceProperties props(mesh);
        for (VertexHandle v : {p, r, t, u})
            mesh.property(props.vertex_class, v) = VertexClass::Corner;
        mesh.property(props.vertex_class, q) = VertexClass::Ridge;
        mesh.property(props.vertex_curve, q) = 0;
        for (auto [a, b] : {std::pair{p, q}, std::pair{q, r}})
            mesh.property(props.edge_curve, mesh.edge_handle(mesh.find_halfedge(a, b))) = 0;
    }
};

}  // namespace

TEST_CASE("an off-centre vertex of a regular hexagon goes where its worst triangle is best")
{
    Hexagon hexagon(Vec3d(0.45, 0.2, 0));
    const fixtures::PlaneProjector plane;
    OperatorContext ctx(hexagon.mesh, plane, {});
    const double before = worst_qe_around(hexagon.mesh, hexagon.centre);
    REQUIRE(relocate_vertex(ctx, hexagon.centre).done());
    const double after = worst_qe_around(hexagon.mesh, hexagon.centre);
    CHECK(after > before + 0.1);
    CHECK(after > 0.9);
    CHECK(hexagon.mesh.point(hexagon.centre)[2] == doctest::Approx(0.0));
}

TEST_CASE("a vertex at the centre of a regular hexagon is refused, nothing moved")
{
    Hexagon hexagon(Vec3d(0, 0, 0));
    const fixtures::PlaneProjector plane;
    OperatorContext ctx(hexagon.mesh, plane, {});
    const auto points = fixtures::points_of(hexagon.mesh);
    CHECK(relocate_vertex(ctx, hexagon.centre).status == OpStatus::Quality);
    CHECK(fixtures::points_of(hexagon.mesh) == points);
}

TEST_CASE("a ridge vertex slides along its curve to lift the squeezed triangle beside it")
{
    SqueezedRidge ridge;
    const fixtures::PlaneProjector plane;
    OperatorContext ctx(ridge.mesh, plane, {});
    const double before = worst_qe_around(ridge.mesh, ridge.q);
    REQUIRE(relocate_vertex(ctx, ridge.q).done());
    CHECK(worst_qe_around(ridge.mesh, ridge.q) > before + 0.1);
    const Vec3d q = ridge.mesh.point(ridge.q);
    CHECK(q[1] == doctest::Approx(0.0));  // on the curve
    CHECK(q[0] > 0.3);
    CHECK(q[0] < 2.0);
}

TEST_CASE("a caller's veto leaves the relocation undone")
{
    SqueezedRidge ridge;
    const fixtures::PlaneProjector plane;
    OperatorContext ctx(ridge.mesh, plane, {});
    const auto points = fixtures::points_of(ridge.mesh);
    RelocateOptions options;
    int asked = 0;
    options.accept = [&](const Vec3d&) { return ++asked, false; };
    CHECK(relocate_vertex(ctx, ridge.q, options).status == OpStatus::Geometry);
    CHECK(asked == 3);  // the three best legal trials
    CHECK(fixtures::points_of(ridge.mesh) == points);
}

// A tolerance-refined zone: every edge of the star is shorter than the band's floor. A move may
// still shorten an edge, down to the star's shortest (here V-H0), as long as none gets shorter.
TEST_CASE("a star below the band's floor may move while no edge gets shorter than its shortest")
{
    Hexagon hexagon(Vec3d(0.45, 0.2, 0));
    const fixtures::PlaneProjector plane;
    OperatorContext ctx(hexagon.mesh, plane, {});
    double shortest = 10.0;
    for (auto w : hexagon.mesh.vv_range(hexagon.centre))
        shortest =
            std::min(shortest, (hexagon.mesh.point(w) - hexagon.mesh.point(hexagon.centre)).norm());
    RelocateOptions options;
    options.min_length = 2.0;  // above every edge of the star
    const double before = worst_qe_around(hexagon.mesh, hexagon.centre);
    REQUIRE(relocate_vertex(ctx, hexagon.centre, options).done());
    CHECK(worst_qe_around(hexagon.mesh, hexagon.centre) > before + 0.1);
    for (auto w : hexagon.mesh.vv_range(hexagon.centre))
        CHECK((hexagon.mesh.point(w) - hexagon.mesh.point(hexagon.centre)).norm() >=
              shortest - 1e-12);
}

// An irregular ring, flat in z = 0: no equilateral apex nor George's point is the optimum, so
// the compass search after them gets the star's triangles closer to the goal.
TEST_CASE("the compass search takes the best trial closer to the goal")
{
    auto build = [](SurfaceMesh& mesh) {
        const VertexHandle centre = mesh.add_vertex(Vec3d(0.3, -0.2, 0));
        const double radius[6] = {1.0, 0.75, 1.25, 0.9, 1.15, 0.7};
        const double angle[6] = {0.0, 0.9, 2.0, 3.1, 4.1, 5.3};
        std::vector<VertexHandle> ring;
        for (int k = 0; k < 6; ++k)
            ring.push_back(mesh.add_vertex(
                Vec3d(radius[k] * std::cos(angle[k]), radius[k] * std::sin(angle[k]), 0)));
        for (int k = 0; k < 6; ++k) mesh.add_face(centre, ring[k], ring[(k + 1) % 6]);
        fixtures::mark_all_smooth(mesh);
        SurfaceProperties props(mesh);
        for (const VertexHandle v : ring)
            mesh.property(props.vertex_class, v) = VertexClass::Corner;
        return centre;
    };
    const fixtures::PlaneProjector plane;
    auto shortfall_after = [&](int search_steps) {
        SurfaceMesh mesh;
        const VertexHandle centre = build(mesh);
        OperatorContext ctx(mesh, plane, {});
        RelocateOptions options;
        options.goal = 1.0;  // every face falls short: the sum is the measure
        options.search_steps = search_steps;
        REQUIRE(relocate_vertex(ctx, centre, options).done());
        double sum = 0.0;
        for (auto f : mesh.vf_range(centre))
        {
            std::vector<Vec3d> p;
            for (auto x : mesh.fv_range(f)) p.push_back(mesh.point(x));
            sum += 1.0 - triangle_qe(p[0], p[1], p[2]);
        }
        return sum;
    };
    const double trials_only = shortfall_after(0);
    CHECK(shortfall_after(4) < trials_only - 1e-3);
}
