// What keeps a remeshed surface within its geometric tolerance (the Hausdorff targets of
// issue 6): spikes of the input kept as isolated corners, the refinement of the remesher where
// the output strays from the model either way, and the operator options it uses (a split onto a
// given model point, a collapse that refuses small angles). Tiny meshes built here, drawn.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <tuple>
#include <vector>

// OpenMesh's PropertyT<Vec3d>::push_back copies a default-constructed (deliberately
// uninitialized) VectorT: a -Wmaybe-uninitialized false positive once GCC inlines add_vertex here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "surface/detail/closest_point_tree.h"
#include "surface/detail/local_ops_geometry.h"
#include "surface/features.h"
#include "surface/local_ops.h"
#include "surface/remesh_surface.h"
#include "surface/surface_io.h"
#include "surface/surface_quality.h"
#include "surface_fixtures.h"
#pragma GCC diagnostic pop

using namespace hdimesh::surface;

namespace
{

using hdimesh::surface::fixtures::PlaneProjector;

// An n×n grid of unit squares in z = 0, each cut by its (i,j)-(i+1,j+1) diagonal, optionally
// with the vertex (cx, cy) lifted to `tip` (a spike). Unclassified.
SurfaceMesh grid(int n, int cx = -1, int cy = -1, double tip = 0.0)
{
    return hdimesh::surface::fixtures::triangulated_grid(
        n, [&](int i, int j) { return i == cx && j == cy ? tip : 0.0; });
}

// Classified as the operators expect: the rim is boundary curve 0, the rest smooth, one ref.
void classify_flat(SurfaceMesh& mesh)
{
    SurfaceProperties props(mesh);
    for (auto x : mesh.vertices())
    {
        const bool rim = mesh.is_boundary(x);
        mesh.property(props.vertex_class, x) = rim ? VertexClass::Boundary : VertexClass::Smooth;
        mesh.property(props.vertex_curve, x) = rim ? 0 : kNoCurve;
        mesh.property(props.vertex_size, x) = 1.0;
    }
    for (auto e : mesh.edges())
        mesh.property(props.edge_curve, e) = mesh.is_boundary(e) ? 0 : kNoCurve;
    for (auto f : mesh.faces()) mesh.property(props.face_ref, f) = 1;
}

using hdimesh::surface::fixtures::icosahedron;

using hdimesh::surface::fixtures::euler;
using hdimesh::surface::fixtures::sphere_points;

std::size_t boundary_loops(const SurfaceMesh& mesh)
{
    std::set<int> seen;
    std::size_t loops = 0;
    for (auto h : mesh.halfedges())
    {
        if (mesh.status(mesh.edge_handle(h)).deleted() || !mesh.is_boundary(h) ||
            seen.count(h.idx()))
            continue;
        ++loops;
        for (auto g = h; seen.insert(g.idx()).second; g = mesh.next_halfedge_handle(g))
        {
        }
    }
    return loops;
}

void check_manifold(const SurfaceMesh& mesh)
{
    for (auto v : mesh.vertices())
        if (!mesh.status(v).deleted()) CHECK(mesh.is_manifold(v));
    for (auto f : mesh.faces())
    {
        if (mesh.status(f).deleted()) continue;
        std::vector<Vec3d> p;
        for (auto v : mesh.fv_range(f)) p.push_back(mesh.point(v));
        CHECK(triangle_qe(p[0], p[1], p[2]) > 0.0);
    }
}

ClosestPointTree triangles_of(const SurfaceMesh& mesh)
{
    std::vector<std::array<Vec3d, 3>> tris;
    for (auto f : mesh.faces())
    {
        if (mesh.status(f).deleted()) continue;
        auto fv = mesh.cfv_iter(f);
        const Vec3d a = mesh.point(*fv), b = mesh.point(*++fv), c = mesh.point(*++fv);
        tris.push_back({a, b, c});
    }
    return ClosestPointTree::from_triangles(std::move(tris));
}

// The largest distance from the unit sphere of the output's edge midpoints and centroids (its
// vertices are on it), and of the sphere points to the output: the two halves of the Hausdorff
// distance as the remesher's refinement sees them.
std::array<double, 2> sphere_deviation(const SurfaceMesh& mesh, const std::vector<Vec3d>& points)
{
    double out_to_sphere = 0.0, points_to_out = 0.0;
    for (auto e : mesh.edges())
    {
        const auto h = mesh.halfedge_handle(e, 0);
        const Vec3d mid =
            0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
        out_to_sphere = std::max(out_to_sphere, 1.0 - mid.norm());
    }
    for (auto f : mesh.faces())
    {
        Vec3d c(0, 0, 0);
        for (auto v : mesh.fv_range(f)) c += mesh.point(v) / 3.0;
        out_to_sphere = std::max(out_to_sphere, 1.0 - c.norm());
    }
    const ClosestPointTree tree = triangles_of(mesh);
    for (const Vec3d& p : points) points_to_out = std::max(points_to_out, tree.closest(p).distance);
    return {out_to_sphere, points_to_out};
}

}  // namespace

TEST_CASE(
    "a spike whose creases are dropped as noise stays an isolated corner, and the remesher keeps "
    "its tip")
{
    // A 6×6 grid in z = 0 with its centre vertex (3,3) lifted to z = 1.5: a spike whose angle
    // sum is far below 360° (defect > 60°). Its creases are short against min_ridge_length
    // (made long here, as for scan noise), so no ridge holds the tip: only the cone test does.
    //
    //      +---+---+---+
    //      |  /|  /|  /|
    //      | / | ^ | / |        ^ = the tip, 1.5 above the grid
    //      |/  |/ \|/  |
    //      +---+---+---+
    const Vec3d tip(3, 3, 1.5);
    SurfaceMesh input = grid(6, 3, 3, 1.5);
    FeatureOptions noise_only;
    noise_only.min_ridge_length = 10.0;  // every sharp chain is noise
    SurfaceMesh classified = input;
    const FeatureSummary summary = detect_features(classified, noise_only);
    CHECK(summary.ridge_edges == 0);
    SurfaceProperties props(classified);
    VertexHandle tip_vertex;
    for (auto v : classified.vertices())
        if ((classified.point(v) - tip).norm() < 1e-12) tip_vertex = v;
    REQUIRE(tip_vertex.is_valid());
    CHECK(classified.property(props.vertex_class, tip_vertex) == VertexClass::Corner);

    auto remeshed_tip_distance = [&](double cone_defect_deg, bool refine_to_tolerance) {
        SurfaceMesh mesh = input;
        SurfaceRemeshSettings settings;
        settings.features = noise_only;
        settings.features.cone_defect_deg = cone_defect_deg;
        settings.sizing.hsiz = 1.3;
        settings.iterations = 6;
        settings.refine_to_tolerance = refine_to_tolerance;
        // the size wins over the curvature everywhere: the case is the tip, not the sizing
        settings.tolerance_wins_area_fraction = 1.0;
        // the facets are the model (the spike's faces read as a coarse tessellation of a smooth
        // bump, which the HDI would round): the case is the tip on the facets
        settings.hdi_for_coarse_input = false;
        remesh_surface(mesh, settings);
        CHECK(euler(mesh) == euler(input));
        CHECK(boundary_loops(mesh) == 1);
        check_manifold(mesh);
        return triangles_of(mesh).closest(tip).distance;
    };
    // Kept exactly with the cone test; cut off by chords without it and without the tolerance
    // refinement. With the refinement the tip is reached exactly even without the cone test: a
    // move or split onto the input vertex at the tip is judged against the model where it is (a
    // triangle down the spike's side against the model under it; a split's new vertex against
    // the tip's own vertex normal), not against one face's normal, up to 120° off the others.
    CHECK(remeshed_tip_distance(60.0, true) < 1e-12);
    CHECK(remeshed_tip_distance(60.0, false) < 1e-12);
    CHECK(remeshed_tip_distance(400.0, false) > 0.05);
    CHECK(remeshed_tip_distance(400.0, true) < 1e-12);
}

TEST_CASE("a flat grid has no cone tip: no corner inside it")
{
    SurfaceMesh mesh = grid(4);
    detect_features(mesh);
    SurfaceProperties props(mesh);
    for (auto v : mesh.vertices())
        if (!mesh.is_boundary(v))
            CHECK(mesh.property(props.vertex_class, v) == VertexClass::Smooth);
}

TEST_CASE(
    "refinement to a tolerance brings a coarse sphere within it both ways, closed and on the "
    "sphere")
{
    // The icosahedron (edges ≈ 1.05) at size 1.0: nothing is too long, but its faces sink up to
    // 0.2 below the unit sphere. With a tolerance, the remesher splits where the output strays
    // (centroids, edge midpoints) or passes far from a model point, until within it.
    const SphereProjector sphere(Vec3d(0, 0, 0), 1.0);
    const std::vector<Vec3d> points = sphere_points(300);
    auto run = [&](double tolerance) {
        SurfaceMesh mesh = icosahedron();
        SurfaceRemeshOptions options;
        options.loop.size = [](const Vec3d&) { return 1.0; };
        options.loop.iterations = 3;
        options.tolerance.tolerance = tolerance;
        options.tolerance.model_points = points;
        options.refinement.short_edge_budget = 1.0;  // no size target to keep here
        options.tolerance.min_length_ratio = 0.1;
        options.refinement.rounds = 20;
        const RemeshReport report = remesh_surface(mesh, options, sphere);
        CHECK(euler(mesh) == 2);
        CHECK(boundary_loops(mesh) == 0);
        check_manifold(mesh);
        for (auto v : mesh.vertices())
            CHECK(mesh.point(v).norm() == doctest::Approx(1.0).epsilon(1e-9));
        return std::make_pair(sphere_deviation(mesh, points), report);
    };
    const double tolerance = 0.04;
    const auto [coarse, coarse_report] = run(0.0);
    CHECK(coarse_report.refinement_splits == 0);
    CHECK(coarse[0] > 2.0 * tolerance);  // the test means something: the sizes alone stray
    const auto [refined, refined_report] = run(tolerance);
    CHECK(refined_report.refinement_splits > 0);
    CHECK(refined[0] <= tolerance + 1e-12);
    CHECK(refined[1] <= tolerance + 1e-12);
}

TEST_CASE(
    "after the polish, snaps and the angle repair keep the tolerance: within it both ways, fewer "
    "vertices")
{
    // The same coarse sphere, refined to the tolerance once with the final refinement's snaps
    // and angle repair and once without them (snap_min_angle_deg = 0): snapping a vertex onto
    // a far model point costs no vertex where a split would add one, and neither path leaves
    // the tolerance, the sphere or the topology, nor lets the worst angle fall below the
    // repair's reach.
    const SphereProjector sphere(Vec3d(0, 0, 0), 1.0);
    const std::vector<Vec3d> points = sphere_points(300);
    auto run = [&](double snap_min_angle_deg) {
        SurfaceMesh mesh = icosahedron();
        SurfaceRemeshOptions options;
        options.loop.size = [](const Vec3d&) { return 1.0; };
        options.loop.iterations = 3;
        options.tolerance.tolerance = 0.04;
        options.tolerance.model_points = points;
        // No split before the polish (a spent budget), any number after it: the far places
        // are all left to the final refinement, where the snaps are.
        options.tolerance.reference_size = 1.0;
        options.refinement.short_edge_budget = 0.0;
        options.refinement.final_short_edge_budget = 1.0;
        options.tolerance.min_length_ratio = 0.1;
        options.refinement.rounds = 20;
        options.tolerance.snap_min_angle_deg = snap_min_angle_deg;
        // Both paths start the final refinement from the same mesh (nothing before it reads
        // the snap angle); the whole mesh polished, as when this comparison was set up. With the
        // polish only at triangles under Qe 0.7 (the default) this sphere's snap path ends with
        // 111 vertices against 107: snaps save vertices on most meshes, not on every one.
        options.polish.below_quality = 2.0;
        const RemeshReport report = remesh_surface(mesh, options, sphere);
        CHECK(euler(mesh) == 2);
        check_manifold(mesh);
        for (auto v : mesh.vertices())
            CHECK(mesh.point(v).norm() == doctest::Approx(1.0).epsilon(1e-9));
        const auto deviation = sphere_deviation(mesh, points);
        CHECK(deviation[0] <= options.tolerance.tolerance + 1e-12);
        CHECK(deviation[1] <= options.tolerance.tolerance + 1e-12);
        double min_angle = 180.0;
        for (auto f : mesh.faces())
        {
            const auto p = hdimesh::surface::detail::face_points(mesh, f);
            min_angle = std::min(min_angle, triangle_min_angle_deg(p[0], p[1], p[2]));
        }
        return std::make_tuple(report, mesh.n_vertices(), min_angle);
    };
    const auto [plain, plain_vertices, plain_angle] = run(0.0);
    const auto [snapped, snapped_vertices, snapped_angle] = run(25.0);
    CHECK(plain.refinement_snaps == 0);
    CHECK(snapped.refinement_snaps > 0);
    CHECK(snapped_vertices <= plain_vertices);
    CHECK(snapped_angle >= 20.0);
    MESSAGE("vertices " << plain_vertices << " -> " << snapped_vertices << ", min angle "
                        << plain_angle << " -> " << snapped_angle << ", snaps "
                        << snapped.refinement_snaps);
}

TEST_CASE("the refinement's short-edge budget stops it: no split once the budget is spent")
{
    const SphereProjector sphere(Vec3d(0, 0, 0), 1.0);
    SurfaceMesh mesh = icosahedron();
    SurfaceRemeshOptions options;
    options.loop.size = [](const Vec3d&) { return 1.0; };
    options.loop.iterations = 3;
    options.tolerance.tolerance = 0.04;
    options.tolerance.reference_size = 1.0;
    options.refinement.short_edge_budget = 0.0;  // every edge shorter than 0.66 is over budget
    const RemeshReport report = remesh_surface(mesh, options, sphere);
    CHECK(report.refinement_splits == 0);
    CHECK(euler(mesh) == 2);
}

TEST_CASE("split onto a given model point puts the new vertex there, a curve edge ignores it")
{
    //  (0,2)---(1,2)---(2,2)
    //    |    /  |    /  |
    //    |  /    |  /    |         split the diagonal (0,0)-(1,1) with the vertex at (0.3, 0.6)
    //  (0,1)---(1,1)---(2,1)
    //    |    /  |    /  |
    //    |  /    |  /    |
    //  (0,0)---(1,0)---(2,0)
    SurfaceMesh mesh = grid(2);
    classify_flat(mesh);
    const PlaneProjector plane;
    const SurfaceHooks no_hooks;
    OperatorContext ctx(mesh, plane, no_hooks);
    auto edge_between = [&](const Vec3d& a, const Vec3d& b) -> EdgeHandle {
        for (auto e : mesh.edges())
        {
            const auto h = mesh.halfedge_handle(e, 0);
            const Vec3d p = mesh.point(mesh.from_vertex_handle(h)),
                        q = mesh.point(mesh.to_vertex_handle(h));
            if (((p - a).norm() < 1e-12 && (q - b).norm() < 1e-12) ||
                ((p - b).norm() < 1e-12 && (q - a).norm() < 1e-12))
                return e;
        }
        return EdgeHandle();
    };
    auto area = [&] {
        double sum = 0.0;
        for (auto f : mesh.faces())
            if (!mesh.status(f).deleted()) sum += mesh.calc_face_area(f);
        return sum;
    };
    const Vec3d target(0.3, 0.6, 0.0);
    const OpResult inner = try_split(ctx, edge_between(Vec3d(0, 0, 0), Vec3d(1, 1, 0)), &target);
    REQUIRE(inner.done());
    CHECK((mesh.point(inner.vertex) - target).norm() < 1e-15);
    CHECK(area() == doctest::Approx(4.0));  // the plane is still covered once
    for (auto f : mesh.faces())
    {
        std::vector<Vec3d> p;
        for (auto v : mesh.fv_range(f)) p.push_back(mesh.point(v));
        CHECK(OpenMesh::cross(p[1] - p[0], p[2] - p[0])[2] > 0.0);
    }
    // A boundary edge keeps its new vertex on its curve: the midpoint, whatever `at` says.
    const Vec3d off(1.2, -0.3, 0.0);
    const OpResult rim = try_split(ctx, edge_between(Vec3d(1, 0, 0), Vec3d(2, 0, 0)), &off);
    REQUIRE(rim.done());
    CHECK((mesh.point(rim.vertex) - Vec3d(1.5, 0, 0)).norm() < 1e-15);
    CHECK(mesh.property(ctx.props.vertex_class, rim.vertex) == VertexClass::Boundary);
    CHECK(area() == doctest::Approx(4.0));
}

TEST_CASE("a collapse that would leave an angle under the bound is refused and changes nothing")
{
    //  (0,2)---(1,2)---(2,2)
    //    |    /  |    /  |
    //    |  /    |  /    |      collapse (1,1) onto (0,0): the ring of (1,1) is pulled to the
    //  (0,1)---(1,1)---(2,1)    corner, its triangles get thin (about 18° at (2,1) and (1,2))
    //    |    /  |    /  |
    //    |  /    |  /    |
    //  (0,0)---(1,0)---(2,0)
    SurfaceMesh mesh = grid(2);
    classify_flat(mesh);
    const PlaneProjector plane;
    const SurfaceHooks no_hooks;
    OperatorContext ctx(mesh, plane, no_hooks);
    HalfedgeHandle centre_to_origin;
    for (auto h : mesh.halfedges())
        if ((mesh.point(mesh.from_vertex_handle(h)) - Vec3d(1, 1, 0)).norm() < 1e-12 &&
            mesh.point(mesh.to_vertex_handle(h)).norm() < 1e-12)
            centre_to_origin = h;
    REQUIRE(centre_to_origin.is_valid());
    // The smallest angle the collapse would leave, computed here from the ring.
    double smallest = 180.0;
    const VertexHandle centre = mesh.from_vertex_handle(centre_to_origin);
    for (auto f : mesh.vf_range(centre))
    {
        std::vector<Vec3d> p;
        bool removed = false;
        for (auto v : mesh.fv_range(f))
        {
            if (v == mesh.to_vertex_handle(centre_to_origin)) removed = true;
            p.push_back(v == centre ? Vec3d(0, 0, 0) : mesh.point(v));
        }
        if (!removed) smallest = std::min(smallest, triangle_min_angle_deg(p[0], p[1], p[2]));
    }
    REQUIRE(smallest < 25.0);
    const std::size_t faces = mesh.n_faces();
    const OpResult refused = try_collapse(ctx, centre_to_origin, 0.0, false, smallest + 1.0);
    CHECK(refused.status == OpStatus::Quality);
    CHECK(mesh.n_faces() == faces);
    CHECK(!mesh.status(centre).deleted());
    CHECK((mesh.point(centre) - Vec3d(1, 1, 0)).norm() < 1e-15);
    const OpResult done = try_collapse(ctx, centre_to_origin, 0.0, false, smallest - 1.0);
    CHECK(done.done());
}

TEST_CASE("the V tips of fandisk and spot are corners whose input wedge is under 20 degrees")
{
    // Two ridges meet at an acute angle with a single input facet between them; every output
    // triangle in that wedge has the wedge's angle or less at the tip, so a min angle of 20° is
    // out of reach while the ridges and the corner are kept (fandisk: 19.38°; spot: 16.66°).
    //
    //          ridge a
    //         /
    //   tip  <    wedge < 20°
    //         \   (ridge b)
    struct Tip
    {
        const char* model;
        Vec3d point;
        double wedge_deg;
    };
    for (const Tip& tip : {Tip{"fandisk", Vec3d(2.79093, 15.4688, -1.15892), 19.38},
                           Tip{"spot", Vec3d(0.0864529, -0.0640166, 0.98579), 16.66}})
    {
        INFO(tip.model);
        SurfaceMesh mesh = read_surface(std::string(HDIMESH_DATA_DIR) + "/" + tip.model + ".obj");
        FeatureOptions options;
        options.min_corner_spacing =
            0.005 * bounding_box_diagonal(mesh);  // as remesh_surface at h = 1 %
        detect_features(mesh, options);
        const SurfaceProperties props(mesh);
        VertexHandle v;
        for (auto w : mesh.vertices())
            if ((mesh.point(w) - tip.point).norm() < 1e-5) v = w;
        REQUIRE(v.is_valid());
        CHECK(mesh.property(props.vertex_class, v) == VertexClass::Corner);
        // Exactly two ridge edges at the tip, and one face between them spans the wedge.
        std::vector<VertexHandle> ridge_ends;
        for (auto h : mesh.voh_range(v))
            if (mesh.property(props.edge_curve, mesh.edge_handle(h)) != kNoCurve)
                ridge_ends.push_back(mesh.to_vertex_handle(h));
        REQUIRE(ridge_ends.size() == 2);
        double wedge = 360.0;
        for (auto f : mesh.vf_range(v))
        {
            std::set<VertexHandle> corners_of_f;
            for (auto w : mesh.fv_range(f)) corners_of_f.insert(w);
            if (!corners_of_f.count(ridge_ends[0]) || !corners_of_f.count(ridge_ends[1])) continue;
            wedge = triangle_angles_deg(mesh.point(v), mesh.point(ridge_ends[0]),
                                        mesh.point(ridge_ends[1]))[0];
        }
        CHECK(wedge == doctest::Approx(tip.wedge_deg).epsilon(0.001));
        CHECK(wedge < 20.0);
    }
}
