// The worst-triangle cleanup (Cleanup): small angles raised by flips, collapses, removals and
// smart shifts, on the model, the rim and the topology kept.

#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

// OpenMesh's PropertyT<Vec3d>::push_back copies a default-constructed (deliberately
// uninitialized) VectorT: a -Wmaybe-uninitialized false positive once GCC inlines add_vertex here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "surface/detail/cleanup.h"
#include "surface/surface_quality.h"
#include "surface_fixtures.h"
#pragma GCC diagnostic pop

using namespace hdimesh::surface;

namespace
{

double min_angle(const SurfaceMesh& mesh)
{
    double worst = 180.0;
    for (auto f : mesh.faces())
    {
        if (mesh.status(f).deleted()) continue;
        auto fv = mesh.cfv_iter(f);
        const Vec3d a = mesh.point(*fv), b = mesh.point(*++fv), c = mesh.point(*++fv);
        worst = std::min(worst, triangle_min_angle_deg(a, b, c));
    }
    return worst;
}

}  // namespace

TEST_CASE(
    "the cleanup raises the worst angle of a spoiled grid and keeps it flat, its rim and its "
    "topology")
{
    //  (0,6) ------------ (6,6)     a 6×6 grid of unit squares in z = 0, its rim boundary
    //    |    /    /    /   |       curve 0; the interior vertex (3,3) pushed by (0.7, 0.6)
    //    |   /   X->   /    |       toward (4,4), which leaves needles around it
    //  (0,0) ------------ (6,0)
    SurfaceMesh mesh = fixtures::flat_grid_with_rim(6, false);
    const VertexHandle spoiled = fixtures::vertex_at(mesh, Vec3d(3, 3, 0));
    mesh.set_point(spoiled, Vec3d(3.7, 3.6, 0.0));
    const double before = min_angle(mesh);
    REQUIRE(before < 27.0);
    const std::size_t rim_before =
        std::count_if(mesh.vertices_begin(), mesh.vertices_end(),
                      [&](VertexHandle v) { return mesh.is_boundary(v); });

    const fixtures::PlaneProjector plane;
    RemeshOptions loop;
    loop.size = [](const Vec3d&) { return 1.0; };
    detail::ChangeLog log;
    detail::RemeshRun run(mesh, loop, plane, log.wrap({}));
    const ToleranceOptions tolerance;  // no tolerance to keep
    const CleanupOptions options;
    detail::ToleranceKeeper keeper(run, tolerance);
    detail::Cleanup cleanup(run, keeper, log, tolerance, options);
    run.update_sizes();
    cleanup.cleanup_worst_triangles();
    mesh.garbage_collection();

    CHECK(min_angle(mesh) > before);
    CHECK(fixtures::euler(mesh) == 1);
    CHECK(fixtures::manifold_and_nondegenerate(mesh));
    std::size_t rim_after = 0;
    for (auto v : mesh.vertices())
    {
        CHECK(mesh.point(v)[2] == 0.0);
        if (mesh.is_boundary(v)) ++rim_after;
    }
    CHECK(rim_after == rim_before);  // the rim's vertices neither move off it nor go
}
