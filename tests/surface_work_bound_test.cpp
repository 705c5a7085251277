// No hang, ever (issue 41): the surface stages that loop stop at a work bound proportional to
// their input, with a note, and the pipeline goes on. A coarse sphere with sharp spikes (480
// triangles, a dozen vertices pushed out 2-3 radii) is meshed through the surface pass and the
// fill, the checker clean; a tolerance no model can reach stops the refinement at its bound.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

// OpenMesh's PropertyT<Vec3d>::push_back copies a default-constructed (deliberately
// uninitialized) VectorT: a -Wmaybe-uninitialized false positive once GCC inlines add_vertex here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "coupling/mesh_from_surface.h"
#include "surface/detail/tolerance_refinement.h"
#include "surface/remesh_surface.h"
#include "surface/surface_quality.h"
#include "surface_fixtures.h"
#include "volume/check/check.h"
#pragma GCC diagnostic pop

using namespace hdimesh;
using surface::Vec3d;

namespace
{

/// A coarse latitude-longitude sphere (12 rings of 20, the poles: 242 points, 480 triangles,
/// outward), `spikes` of its ring points pushed out to between `low` and `high` radii, chosen
/// by a fixed linear congruential sequence from `seed`.
surface::TriangleSoup spiky_sphere(int spikes, double low, double high, std::uint32_t seed)
{
    constexpr int rings = 12, around = 20;
    constexpr double pi = 3.14159265358979323846;
    surface::TriangleSoup soup;
    soup.points.emplace_back(0, 0, 1);
    for (int i = 1; i <= rings; ++i)
    {
        const double theta = pi * i / (rings + 1);
        for (int j = 0; j < around; ++j)
        {
            const double phi = 2 * pi * (j + 0.5 * (i % 2)) / around;
            soup.points.emplace_back(std::sin(theta) * std::cos(phi),
                                     std::sin(theta) * std::sin(phi), std::cos(theta));
        }
    }
    soup.points.emplace_back(0, 0, -1);
    const int south = static_cast<int>(soup.points.size()) - 1;
    auto ring = [](int i, int j) { return 1 + i * around + (j % around); };
    for (int j = 0; j < around; ++j) soup.triangles.push_back({0, ring(0, j), ring(0, j + 1)});
    for (int i = 0; i + 1 < rings; ++i)
        for (int j = 0; j < around; ++j)
        {
            const int a = ring(i, j), a1 = ring(i, j + 1), b = ring(i + 1, j),
                      b1 = ring(i + 1, j + 1);
            if (i % 2 == 0)
            {
                soup.triangles.push_back({a, b, a1});
                soup.triangles.push_back({a1, b, b1});
            }
            else
            {
                soup.triangles.push_back({a, b, b1});
                soup.triangles.push_back({a, b1, a1});
            }
        }
    for (int j = 0; j < around; ++j)
        soup.triangles.push_back({south, ring(rings - 1, j + 1), ring(rings - 1, j)});
    soup.refs.assign(soup.triangles.size(), 1);
    std::uint32_t state = seed;
    auto next = [&state]() {
        state = state * 1664525u + 1013904223u;
        return state >> 8;
    };
    std::vector<char> pushed(soup.points.size(), 0);
    for (int s = 0; s < spikes;)
    {
        const int v = 1 + static_cast<int>(next() % (rings * around));
        if (pushed[v]) continue;
        pushed[v] = 1;
        const double factor = low + (high - low) * (next() % 1000) / 999.0;
        soup.points[v] *= factor;
        ++s;
    }
    return soup;
}

double diagonal_of(const surface::TriangleSoup& soup)
{
    Vec3d lo = soup.points[0], hi = soup.points[0];
    for (const Vec3d& p : soup.points)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    return (hi - lo).norm();
}

}  // namespace

/// Tolerance options no vertex on the unit sphere can meet: the model points at radius 1.3,
/// nothing but the bounds to stop the splits.
surface::ToleranceOptions unreachable(int model_points)
{
    surface::ToleranceOptions tolerance;
    tolerance.tolerance = 0.01;
    for (const Vec3d& p : surface::fixtures::sphere_points(model_points))
        tolerance.model_points.push_back(1.3 * p);
    tolerance.min_length_ratio = 1e-9;
    tolerance.snap_min_angle_deg = 0.0;
    return tolerance;
}

/// The tolerance refinement on `mesh`, projected onto the unit sphere: one call, or a second
/// (the final one) after it; then the bounds reached are noted. The run's report.
surface::RemeshReport refine_on_sphere(surface::SurfaceMesh& mesh,
                                       const surface::ToleranceOptions& tolerance,
                                       const surface::ToleranceRefinementOptions& options,
                                       bool twice)
{
    const surface::SphereProjector sphere(Vec3d(0, 0, 0), 1.0);
    surface::RemeshOptions loop;
    loop.size = [](const Vec3d&) { return 1.0; };
    surface::detail::ChangeLog log;
    surface::detail::RemeshRun run(mesh, loop, sphere, log.wrap({}));
    surface::detail::ToleranceKeeper keeper(run, tolerance);
    surface::detail::ToleranceRefinement refinement(run, keeper, log, tolerance, options);
    run.update_sizes();
    refinement.refine(false);
    if (twice) refinement.refine(true);
    refinement.note_bounds_reached();
    mesh.garbage_collection();
    return run.report;
}

TEST_CASE("spiky coarse shapes go through the surface pass and the fill, the checker clean")
{
    struct Variant
    {
        int spikes;
        double low, high;
        std::uint32_t seed;
    };
    for (const Variant& variant :
         {Variant{12, 2.0, 3.0, 1}, Variant{12, 2.5, 3.0, 7}, Variant{16, 2.0, 2.5, 23}})
    {
        CAPTURE(variant.seed);
        const surface::TriangleSoup soup =
            spiky_sphere(variant.spikes, variant.low, variant.high, variant.seed);
        REQUIRE(soup.triangles.size() == 480);
        coupling::VolumeFromSurfaceOptions options;
        options.sizing.hsiz = 0.02 * diagonal_of(soup);  // adapt's --hsiz in the issue
        options.adapt.verbosity = 0;
        options.source = "spiky";
        coupling::VolumeFromSurfaceReport report;
        const volume::TetMesh mesh = coupling::mesh_volume_from_surface(soup, options, &report);
        const auto violations = volume::check_mesh(mesh);
        INFO(volume::format_violations(violations));
        CHECK(violations.empty());
        // The refinement's work stays far within its bound (20 x the faces the loop made).
        const surface::RemeshReport& remesh = report.remesh.report;
        CHECK(remesh.refinement_splits + remesh.refinement_snaps <=
              4 * static_cast<std::size_t>(report.surface_triangles));
        CHECK(remesh.notes.empty());
    }
}

TEST_CASE("a tolerance out of the model's reach stops the refinement at its bound, with a note")
{
    //   the icosahedron on the unit sphere; the model points at radius 1.3, which no vertex
    //   projected onto the sphere comes near: without a bound the splits would go on
    surface::SurfaceMesh mesh = surface::fixtures::icosahedron();
    const std::size_t faces = mesh.n_faces();
    const surface::ToleranceOptions tolerance = unreachable(200);
    surface::ToleranceRefinementOptions options;
    options.rounds = 1000;
    options.short_edge_budget = 1.0;
    options.work_per_face = 3.0;
    options.min_work = 100;
    // the bound is shared by the calls: the second does nothing
    const surface::RemeshReport report = refine_on_sphere(mesh, tolerance, options, true);
    CHECK(report.refinement_splits <= 3 * faces + 100);
    REQUIRE(report.notes.size() == 1);
    CHECK(report.notes[0].find("work bound") != std::string::npos);
    CHECK(surface::fixtures::euler(mesh) == 2);
    CHECK(surface::fixtures::manifold_and_nondegenerate(mesh));
}

TEST_CASE("the refinement splits no edge below its floor")
{
    // The same unreachable points, no work bound, 1000 rounds: the floor alone ends the splits.
    surface::SurfaceMesh mesh = surface::fixtures::icosahedron();
    surface::ToleranceOptions tolerance = unreachable(50);
    tolerance.min_split_length = 0.1;  // the splits end where edges are under 0.2
    surface::ToleranceRefinementOptions options;
    options.rounds = 1000;
    options.short_edge_budget = 1.0;
    options.work_per_face = -1.0;
    const surface::RemeshReport report = refine_on_sphere(mesh, tolerance, options, false);
    // Ended by the floor, not the rounds: no more triangles than equilateral ones of the floor's
    // side cover the sphere.
    const double floor_triangle = 0.25 * std::sqrt(3.0) * 0.1 * 0.1;
    CHECK(static_cast<double>(mesh.n_faces()) <= 4.0 * 3.14159265358979323846 / floor_triangle);
    CHECK(report.refinement_splits > 0);
    REQUIRE(report.notes.size() == 1);
    CHECK(report.notes[0].find("refused") != std::string::npos);
}
