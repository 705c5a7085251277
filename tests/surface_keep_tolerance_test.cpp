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
