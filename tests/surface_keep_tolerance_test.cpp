// The witnessed (tolerance-keeping) operators: a change is simulated first and refused when the
// output would stray farther from the model than the tolerance and than before.

#include <doctest/doctest.h>

#include <vector>

// OpenMesh's PropertyT<Vec3d>::push_back copies a default-constructed (deliberately
// uninitialized) VectorT: a -Wmaybe-uninitialized false positive once GCC inlines add_vertex here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "surface/detail/keep_tolerance.h"
#include "surface_fixtures.h"
#pragma GCC diagnostic pop

using namespace hdimesh::surface;

namespace
{

// A tent over the plane z = 0: the long edge ab lies on the plane, c and d 0.2 above it.
//
//              c (0, 0.5, 0.2)
//            /   \   (c above the plane)
//   a (-2,0,0)----(2,0,0) b      the quality flip ab -> cd raises the worst Qe (0.23 -> 0.65)
//            \   /               but lifts the output under ab's midpoint to z = 0.2
//              d (0, -0.5, 0.2)
struct Tent
{
    SurfaceMesh mesh;
    VertexHandle a, b, c, d;
    Tent()
    {
        a = mesh.add_vertex(Vec3d(-2, 0, 0));
        b = mesh.add_vertex(Vec3d(2, 0, 0));
        c = mesh.add_vertex(Vec3d(0, 0.5, 0.2));
        d = mesh.add_vertex(Vec3d(0, -0.5, 0.2));
        mesh.add_face(a, b, c);
        mesh.add_face(b, a, d);
        fixtures::mark_all_smooth(mesh);
    }
    EdgeHandle ab() const { return mesh.edge_handle(mesh.find_halfedge(a, b)); }
};

// Whether the tent's witnessed flip of ab is done with `tolerance`.
bool flip_with_tolerance(Tent& tent, double tolerance)
{
    const fixtures::PlaneProjector plane;
    RemeshOptions loop;
    loop.size = [](const Vec3d&) { return 1.0; };
    detail::RemeshRun run(tent.mesh, loop, plane, {});
    ToleranceOptions keep;
    keep.tolerance = tolerance;
    keep.model_points = {Vec3d(0, 0, 0)};  // the model under ab's midpoint
    keep.reference_size = 1.0;
    detail::ToleranceKeeper keeper(run, keep);
    return keeper.flip_keeping_tolerance(tent.ab());
}

}  // namespace

TEST_CASE("a witnessed flip that takes the output off the model is refused, nothing changed")
{
    Tent tent;
    const std::vector<Vec3d> before = fixtures::points_of(tent.mesh);
    CHECK_FALSE(flip_with_tolerance(tent, 0.05));
    CHECK(tent.mesh.find_halfedge(tent.a, tent.b).is_valid());
    CHECK_FALSE(tent.mesh.find_halfedge(tent.c, tent.d).is_valid());
    CHECK(fixtures::points_of(tent.mesh) == before);
}

TEST_CASE("the same flip within a wide tolerance is done, and the model point stays within it")
{
    Tent tent;
    CHECK(flip_with_tolerance(tent, 1.0));
    CHECK(tent.mesh.find_halfedge(tent.c, tent.d).is_valid());
    CHECK(fixtures::distance_to_mesh(tent.mesh, Vec3d(0, 0, 0)) <= 1.0);
    CHECK(fixtures::manifold_and_nondegenerate(tent.mesh));
}

namespace
{

// A flat strip between two curves (an open boundary on each side), z = 0; P1-P2 is a short
// curve edge, so P1 P2 Q1 is squeezed between the curves.
//
//   Q0 -------- Q1 -------- Q2 ----- Q3        y = 1 (curve 1)
//    |  \       | \  \        \  \    |
//    |    \     |  \    \       \  \  |
//   P0 -------- P1-P2 ---- P3 ------ P4        y = 0 (curve 0); P0, P4, Q0, Q3 corners
struct Strip
{
    SurfaceMesh mesh;
    VertexHandle p1, p2, p3;
    Strip()
    {
        const double px[5] = {0, 1, 1.3, 2.3, 3.3}, qx[4] = {0, 1.2, 2.4, 3.3};
        std::vector<VertexHandle> p, q;
        for (double x : px) p.push_back(mesh.add_vertex(Vec3d(x, 0, 0)));
        for (double x : qx) q.push_back(mesh.add_vertex(Vec3d(x, 1, 0)));
        p1 = p[1], p2 = p[2], p3 = p[3];
        mesh.add_face(p[0], p[1], q[0]);
        mesh.add_face(p[1], q[1], q[0]);
        mesh.add_face(p[1], p[2], q[1]);
        mesh.add_face(p[2], p[3], q[1]);
        mesh.add_face(p[3], q[2], q[1]);
        mesh.add_face(p[3], p[4], q[2]);
        mesh.add_face(p[4], q[3], q[2]);
        fixtures::mark_all_smooth(mesh);
        SurfaceProperties props(mesh);
        auto curve = [&](const std::vector<VertexHandle>& chain, int id) {
            for (std::size_t i = 0; i < chain.size(); ++i)
            {
                const bool end = i == 0 || i + 1 == chain.size();
                mesh.property(props.vertex_class, chain[i]) =
                    end ? VertexClass::Corner : VertexClass::Boundary;
                mesh.property(props.vertex_curve, chain[i]) = end ? kNoCurve : id;
                if (i > 0)
                    mesh.property(props.edge_curve,
                                  mesh.edge_handle(mesh.find_halfedge(chain[i - 1], chain[i]))) =
                        id;
            }
        };
        curve(p, 0);
        curve(q, 1);
    }
};

bool collapse_p2_with(Strip& strip, detail::CollapseFor purpose)
{
    const fixtures::PlaneProjector plane;
    RemeshOptions loop;
    loop.size = [](const Vec3d&) { return 1.0; };
    detail::RemeshRun run(strip.mesh, loop, plane, {});
    ToleranceOptions keep;
    keep.tolerance = 0.01;
    keep.model_points = fixtures::points_of(strip.mesh);  // the plane, under every vertex
    keep.reference_size = 1.0;
    detail::ToleranceKeeper keeper(run, keep);
    return keeper.collapse_keeping_tolerance(strip.mesh.find_halfedge(strip.p2, strip.p1), purpose);
}

}  // namespace

TEST_CASE("a triangle squeezed between two curves: its short curve edge collapses for the raise")
{
    Strip repair;
    CHECK_FALSE(collapse_p2_with(repair, detail::CollapseFor::Repair));  // smooth vertices only
    Strip raise;
    REQUIRE(collapse_p2_with(raise, detail::CollapseFor::Raise));
    raise.mesh.garbage_collection();
    CHECK(raise.mesh.n_faces() == 6);
    CHECK(fixtures::manifold_and_nondegenerate(raise.mesh));
    bool p1_to_p3 = false;  // the curve goes on from P1 straight to P3
    for (auto w : raise.mesh.vv_range(raise.p1))
        p1_to_p3 |= raise.mesh.point(w) == Vec3d(2.3, 0, 0);
    CHECK(p1_to_p3);
}
