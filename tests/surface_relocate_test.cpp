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
