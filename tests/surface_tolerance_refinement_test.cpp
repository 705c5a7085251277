// The two-sided tolerance refinement on its own (ToleranceRefinement): splits until the output
// is within the tolerance of the model both ways, on the model, closed.

#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

// OpenMesh's PropertyT<Vec3d>::push_back copies a default-constructed (deliberately
// uninitialized) VectorT: a -Wmaybe-uninitialized false positive once GCC inlines add_vertex here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "surface/detail/tolerance_refinement.h"
#include "surface_fixtures.h"
#pragma GCC diagnostic pop

using namespace hdimesh::surface;

TEST_CASE(
    "the refinement alone brings the icosahedron within the tolerance of the sphere both ways")
{
    //      *          the icosahedron (edges ≈ 1.05) at size 1: no edge is too long, but its
    //    / | \        faces sink up to 0.2 below the unit sphere and pass far from the sphere
    //   *--*--*       points; the refinement splits there, nothing else runs
    SurfaceMesh mesh = fixtures::icosahedron();
    const SphereProjector sphere(Vec3d(0, 0, 0), 1.0);
    RemeshOptions loop;
    loop.size = [](const Vec3d&) { return 1.0; };
    ToleranceOptions tolerance;
    tolerance.tolerance = 0.04;
    tolerance.model_points = fixtures::sphere_points(300);
    tolerance.min_length_ratio = 0.1;
    ToleranceRefinementOptions options;
    options.rounds = 20;
    options.short_edge_budget = 1.0;  // no size target to keep
    detail::ChangeLog log;
    detail::RemeshRun run(mesh, loop, sphere, log.wrap({}));
    detail::ToleranceKeeper keeper(run, tolerance);
    detail::ToleranceRefinement refinement(run, keeper, log, tolerance, options);
    run.update_sizes();
    CHECK(refinement.refine(false) > 0);
    CHECK(run.report.refinement_splits > 0);
    // Converged: a second call finds nothing far (its caches were kept up to date by the log).
    CHECK(refinement.refine(false) == 0);
    mesh.garbage_collection();

    CHECK(fixtures::euler(mesh) == 2);
    CHECK(fixtures::manifold_and_nondegenerate(mesh));
    double output_off = 0.0, points_off = 0.0;
    for (auto v : mesh.vertices())
        CHECK(mesh.point(v).norm() == doctest::Approx(1.0).epsilon(1e-9));
    for (auto f : mesh.faces())
    {
        Vec3d centroid(0, 0, 0);
        for (auto v : mesh.fv_range(f)) centroid += mesh.point(v) / 3.0;
        output_off = std::max(output_off, 1.0 - centroid.norm());
    }
    for (auto e : mesh.edges())
    {
        const auto h = mesh.halfedge_handle(e, 0);
        const Vec3d mid =
            0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
        output_off = std::max(output_off, 1.0 - mid.norm());
    }
    for (const Vec3d& p : tolerance.model_points)
        points_off = std::max(points_off, fixtures::distance_to_mesh(mesh, p));
    CHECK(output_off <= tolerance.tolerance + 1e-12);
    CHECK(points_off <= tolerance.tolerance + 1e-12);
}

TEST_CASE("without a tolerance the refinement changes nothing")
{
    SurfaceMesh mesh = fixtures::icosahedron();
    const SphereProjector sphere(Vec3d(0, 0, 0), 1.0);
    RemeshOptions loop;
    loop.size = [](const Vec3d&) { return 1.0; };
    const ToleranceOptions tolerance;  // 0: off
    const ToleranceRefinementOptions options;
    detail::ChangeLog log;
    detail::RemeshRun run(mesh, loop, sphere, log.wrap({}));
    detail::ToleranceKeeper keeper(run, tolerance);
    detail::ToleranceRefinement refinement(run, keeper, log, tolerance, options);
    const std::vector<Vec3d> before = fixtures::points_of(mesh);
    CHECK(refinement.refine(false) == 0);
    CHECK(refinement.refine(true) == 0);
    CHECK(fixtures::points_of(mesh) == before);
    CHECK(mesh.n_faces() == 20);
}
