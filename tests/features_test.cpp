// The one feature detector (hdi::classify_features) on tiny surfaces built in code: ridges,
// corners, open-boundary curves, isolated spikes, non-manifold edges; the curve numbering in the
// caller's edge order; and the surface mesh's adapter (surface::detect_features), which must
// answer exactly as the arrays do.

#include "hdi/features.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "common/errors.h"
#include "surface/features.h"
#include "surface/surface_io.h"
#include "surface/surface_mesh.h"
#include "tests/fixtures.h"

using namespace hdimesh;
using hdi::EdgeEnds;
using hdi::FeatureClassification;
using hdi::FeatureOptions;
using hdi::Triangle3;
using hdi::Vec3;

namespace
{

constexpr double pi = 3.14159265358979323846;

using Surface = fixtures::GridSurface;
using fixtures::grid_cube;

/// Rings of `around` vertices at radii r0 < r1 < ... in the plane z = 0, joined by triangles;
/// `apex`: the centre, lifted to that height, joined to the first ring (0: a hole instead).
Surface disc(const std::vector<double>& radii, int around, double apex)
{
    Surface s;
    for (double r : radii)
        for (int i = 0; i < around; ++i)
            s.points.emplace_back(r * std::cos(2 * pi * i / around),
                                  r * std::sin(2 * pi * i / around), 0.0);
    for (std::size_t k = 0; k + 1 < radii.size(); ++k)
        for (int i = 0; i < around; ++i)
        {
            const int a = static_cast<int>(k) * around + i,
                      b = static_cast<int>(k) * around + (i + 1) % around;
            s.triangles.push_back({a, b, b + around});
            s.triangles.push_back({a, b + around, a + around});
        }
    if (apex > 0.0)
    {
        s.points.emplace_back(0.0, 0.0, apex);
        const int tip = static_cast<int>(s.points.size()) - 1;
        for (int i = 0; i < around; ++i) s.triangles.push_back({tip, (i + 1) % around, i});
    }
    return s;
}

/// The classification's invariants: an edge's curve is its ends' curve unless they are corners;
/// a curve vertex has exactly two edges on its curve; open curves are the one-triangle edges;
/// curves are numbered in the order of their first edge; the summary counts what it says.
void check_invariants(const Surface& s, const FeatureClassification& c)
{
    REQUIRE(c.vertex_class.size() == s.points.size());
    REQUIRE(c.edge_class.size() == c.edges.size());
    std::map<std::pair<int, int>, int> uses;  // triangles per edge
    for (const Triangle3& t : s.triangles)
        for (int i = 0; i < 3; ++i)
            ++uses[{std::min(t[i], t[(i + 1) % 3]), std::max(t[i], t[(i + 1) % 3])}];
    std::vector<int> curve_edges_at(s.points.size(), 0);
    std::vector<int> first_edge_of_curve;
    std::size_t ridge_edges = 0, boundary_edges = 0;
    for (std::size_t e = 0; e < c.edges.size(); ++e)
    {
        const Classification& ec = c.edge_class[e];
        const int a = c.edges[e][0], b = c.edges[e][1];
        const bool open = uses.at({std::min(a, b), std::max(a, b)}) == 1;
        if (open) CHECK(ec.dimension == Dimension::Curve);  // an open boundary is always a curve
        if (ec.dimension != Dimension::Curve)
        {
            CHECK(ec.dimension == Dimension::Surface);
            continue;
        }
        CHECK(ec.open_boundary == open);
        (open ? boundary_edges : ridge_edges) += 1;
        if (ec.id == static_cast<int>(first_edge_of_curve.size()))
            first_edge_of_curve.push_back(static_cast<int>(e));
        CHECK(ec.id < static_cast<int>(first_edge_of_curve.size()));  // numbered by first edge
        for (int v : {a, b})
        {
            const Classification& vc = c.vertex_class[static_cast<std::size_t>(v)];
            if (vc.dimension == Dimension::Corner) continue;
            CHECK(vc == ec);
            ++curve_edges_at[static_cast<std::size_t>(v)];
        }
    }
    std::size_t corners = 0;
    for (std::size_t v = 0; v < s.points.size(); ++v)
    {
        const Classification& vc = c.vertex_class[v];
        if (vc.dimension == Dimension::Curve) CHECK(curve_edges_at[v] == 2);
        if (vc.dimension == Dimension::Corner) CHECK(vc.id == static_cast<int>(corners++));
    }
    CHECK(c.summary.ridge_edges == ridge_edges);
    CHECK(c.summary.boundary_edges == boundary_edges);
    CHECK(c.summary.corners == corners);
    CHECK(c.summary.curves == first_edge_of_curve.size());
}

std::size_t count_class(const FeatureClassification& c, Dimension d)
{
    return static_cast<std::size_t>(
        std::count_if(c.vertex_class.begin(), c.vertex_class.end(),
                      [&](const Classification& x) { return x.dimension == d; }));
}

/// The surface as the surface tools build it from a file (surface_io's repairs find nothing here).
surface::SurfaceMesh to_mesh(const Surface& s)
{
    surface::TriangleSoup soup;
    for (const Vec3& p : s.points) soup.points.emplace_back(p[0], p[1], p[2]);
    soup.triangles = s.triangles;
    soup.refs.assign(s.triangles.size(), 0);
    return surface::build_surface(soup, "test surface");
}

/// The surface mesh's adapter answers as the arrays do, class and curve id per vertex and edge;
/// the arrays' own edge numbering (where a triangle first uses an edge) is the mesh's.
void check_mesh_agrees(const Surface& s, const FeatureOptions& options = {})
{
    surface::SurfaceMesh mesh = to_mesh(s);
    REQUIRE(mesh.n_vertices() == s.points.size());
    Surface arrays;
    for (auto v : mesh.vertices())
        arrays.points.emplace_back(mesh.point(v)[0], mesh.point(v)[1], mesh.point(v)[2]);
    for (auto f : mesh.faces())
    {
        auto fv = mesh.cfv_iter(f);
        const int a = fv->idx(), b = (++fv)->idx(), c = (++fv)->idx();
        arrays.triangles.push_back({a, b, c});
    }
    const FeatureClassification c =
        hdi::classify_features(arrays.points, arrays.triangles, options);
    check_invariants(arrays, c);
    const hdi::FeatureSummary summary = surface::detect_features(mesh, options);
    CHECK(summary.curves == c.summary.curves);
    CHECK(summary.corners == c.summary.corners);
    surface::SurfaceProperties props(mesh);
    for (auto v : mesh.vertices())
    {
        const Classification& vc = c.vertex_class[static_cast<std::size_t>(v.idx())];
        CHECK(mesh.property(props.vertex_class, v) == surface::to_vertex_class(vc));
        CHECK(mesh.property(props.vertex_curve, v) ==
              (vc.dimension == Dimension::Curve ? vc.id : surface::kNoCurve));
    }
    REQUIRE(mesh.n_edges() == c.edges.size());
    for (auto e : mesh.edges())
    {
        const auto h = mesh.halfedge_handle(e, 0);
        const EdgeEnds& ends = c.edges[static_cast<std::size_t>(e.idx())];
        CHECK(mesh.from_vertex_handle(h).idx() == ends[0]);  // the same edge numbering
        CHECK(mesh.to_vertex_handle(h).idx() == ends[1]);
        const Classification& ec = c.edge_class[static_cast<std::size_t>(e.idx())];
        CHECK(mesh.property(props.edge_curve, e) ==
              (ec.dimension == Dimension::Curve ? ec.id : surface::kNoCurve));
    }
}

}  // namespace

TEST_CASE("features: a cube has 12 ridge curves between its 8 corners")
{
    //     +-------+      each face a 3 x 3 grid; every cube edge a ridge (90 degrees), every
    //    /|      /|      cube vertex a junction of three ridges: a corner
    //   +-------+ |
    //   | +-----|-+
    //   |/      |/
    //   +-------+
    const int n = 3;
    const Surface s = grid_cube(n);
    const FeatureClassification c = hdi::classify_features(s.points, s.triangles);
    check_invariants(s, c);
    CHECK(c.summary.curves == 12);
    CHECK(c.summary.ridge_edges == static_cast<std::size_t>(12 * n));
    CHECK(c.summary.boundary_edges == 0);
    CHECK(count_class(c, Dimension::Corner) == 8);
    CHECK(count_class(c, Dimension::Curve) == static_cast<std::size_t>(12 * (n - 1)));
    for (std::size_t v = 0; v < s.points.size(); ++v)
        if (c.vertex_class[v].dimension == Dimension::Corner)
            for (int d = 0; d < 3; ++d) CHECK((s.points[v][d] == 0.0 || s.points[v][d] == 1.0));
    check_mesh_agrees(s);

    // The caller's edge order numbers the curves: reversed, the curve of the last edge comes first.
    std::vector<EdgeEnds> reversed(c.edges.rbegin(), c.edges.rend());
    const FeatureClassification r = hdi::classify_features(s.points, s.triangles, {}, reversed);
    check_invariants(s, r);
    CHECK(r.summary.curves == 12);
    std::map<int, int> c2r;  // the same curves, renumbered
    const std::size_t edge_count = c.edges.size();
    for (std::size_t e = 0; e < edge_count; ++e)
    {
        const Classification& ce = c.edge_class[e];
        const Classification& re = r.edge_class[edge_count - 1 - e];
        REQUIRE(ce.dimension == re.dimension);
        if (ce.dimension == Dimension::Curve)
            CHECK(c2r.emplace(ce.id, re.id).first->second == re.id);
    }
    CHECK(c2r.size() == 12);
    std::size_t last_curve_edge = edge_count - 1;
    while (c.edge_class[last_curve_edge].dimension != Dimension::Curve) --last_curve_edge;
    CHECK(c2r.at(c.edge_class[last_curve_edge].id) == 0);  // its curve comes first now
    for (std::size_t v = 0; v < s.points.size(); ++v)
        CHECK(r.vertex_class[v].dimension == c.vertex_class[v].dimension);
    // Refs on the faces: still the same curves (every face border is a ridge already).
    std::vector<int> refs(s.triangles.size());
    for (std::size_t t = 0; t < refs.size(); ++t) refs[t] = static_cast<int>(t / (2 * n * n));
    CHECK(hdi::classify_features(s.points, s.triangles, {}, {}, refs).summary.curves == 12);
    // A list that misses an edge is refused.
    std::vector<EdgeEnds> short_list(c.edges.begin() + 1, c.edges.end());
    CHECK_THROWS_AS(hdi::classify_features(s.points, s.triangles, {}, short_list), InputError);
}

TEST_CASE("features: a folded strip's ridge ends on its open boundary at two corners")
{
    //   z
    //   |  B (x = 1)
    //   |  |
    //   |  |____ fold: x = 1, z = 0, y in [0,1], 90 degrees: a ridge of 4 edges
    //   A (z = 0)    open boundary all around: 4 curves between the fold's ends and the 4
    //                square corners (turns of 90 degrees, above the boundary's 75)
    const int n = 4;
    Surface s;
    s.add_grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), n, n);  // A, normal +z
    s.add_grid(Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), n, n);  // B, normal -x (as A's, inward)
    const FeatureClassification c = hdi::classify_features(s.points, s.triangles);
    check_invariants(s, c);
    CHECK(c.summary.ridge_edges == static_cast<std::size_t>(n));
    CHECK(c.summary.boundary_edges == static_cast<std::size_t>(6 * n));
    CHECK(c.summary.corners == 6);
    for (std::size_t e = 0; e < c.edges.size(); ++e)
        if (c.edge_class[e].dimension == Dimension::Curve && !c.edge_class[e].open_boundary)
            for (int v : c.edges[e]) CHECK((s.points[v].x() == 1.0 && s.points[v].z() == 0.0));
    check_mesh_agrees(s);
    // A fold of 35 degrees: a crease, kept because the chain is long (its length, 1, is more
    // than twice min_ridge_length of the diagonal).
    Surface shallow;
    shallow.add_grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), n, n);
    const double a = 35 * pi / 180;
    shallow.add_grid(Vec3(1, 0, 0), Vec3(std::cos(a), 0, std::sin(a)), Vec3(0, 1, 0), n, n);
    const FeatureClassification crease = hdi::classify_features(shallow.points, shallow.triangles);
    check_invariants(shallow, crease);
    CHECK(crease.summary.ridge_edges == static_cast<std::size_t>(n));
    FeatureOptions no_creases;
    no_creases.crease_angle_deg = no_creases.ridge_angle_deg;
    CHECK(
        hdi::classify_features(shallow.points, shallow.triangles, no_creases).summary.ridge_edges ==
        0);
}

TEST_CASE("features: a plane with a hole - the hole and the rim are closed boundary curves")
{
    //   . . . . . .     an annulus, radii 1 to 2, 24 vertices around: both boundaries turn by
    //   . .     . .     15 degrees per vertex (below 75), so they are closed loops without any
    //   . .     . .     corner; nothing inside is sharp
    //   . . . . . .
    const Surface s = disc({1.0, 1.25, 1.5, 1.75, 2.0}, 24, 0.0);
    const FeatureClassification c = hdi::classify_features(s.points, s.triangles);
    check_invariants(s, c);
    CHECK(c.summary.curves == 2);
    CHECK(c.summary.boundary_edges == 48);
    CHECK(c.summary.ridge_edges == 0);
    CHECK(c.summary.corners == 0);
    for (std::size_t v = 0; v < s.points.size(); ++v)
    {
        const double r = s.points[v].norm();
        const bool rim = std::abs(r - 1.0) < 1e-12 || std::abs(r - 2.0) < 1e-12;
        CHECK(c.vertex_class[v].dimension == (rim ? Dimension::Curve : Dimension::Surface));
        if (rim) CHECK(c.vertex_class[v].open_boundary);
    }
    check_mesh_agrees(s);
}

TEST_CASE("features: a cone tip on a smooth disc is an isolated corner")
{
    //        ^        tip at height 0.8 over a ring of radius 0.5 (16 around): its angle sum is
    //       / \       about 190 degrees, a defect of 170 (above 60) on a cone wide enough
    //   ___/   \___   (above 150); the rim at radius 2 is a closed boundary loop
    const Surface s = disc({0.5, 1.0, 1.5, 2.0}, 16, 0.8);
    FeatureOptions options;
    options.ridge_angle_deg = options.crease_angle_deg = 80;  // the cone's foot is not a ridge
    const FeatureClassification c = hdi::classify_features(s.points, s.triangles, options);
    check_invariants(s, c);
    const std::size_t tip = s.points.size() - 1;
    CHECK(c.vertex_class[tip].dimension == Dimension::Corner);
    CHECK(c.summary.corners == 1);  // nothing else: the rim is a closed loop
    CHECK(c.summary.curves == 1);
    check_mesh_agrees(s, options);
    // Off: a cone defect limit of 360 degrees.
    FeatureOptions off = options;
    off.cone_defect_deg = 360;
    CHECK(hdi::classify_features(s.points, s.triangles, off).vertex_class[tip].dimension ==
          Dimension::Surface);
    // Too sharp a spike (angle sum below the minimum) is not kept either: remeshing cannot
    // give it fair triangles.
    FeatureOptions narrow = options;
    narrow.cone_min_angle_sum_deg = 359;
    CHECK(hdi::classify_features(s.points, s.triangles, narrow).vertex_class[tip].dimension ==
          Dimension::Surface);
}

TEST_CASE("features: an edge of three triangles is a curve whatever its length")
{
    //        C
    //        |        three pages around a short spine (x = y = 0, z in [0, 0.1]); each page
    //   A ---+--- B   1 long: the spine is far below min_ridge_length of the diagonal but is
    //                 topology; its two ends, where three open boundaries meet it, are corners
    Surface s;
    const Vec3 spine(0, 0, 0.1);
    s.add_grid(Vec3(0, 0, 0), Vec3(-1, 0, 0), spine, 4, 2);
    s.add_grid(Vec3(0, 0, 0), Vec3(1, 0, 0), spine, 4, 2);
    s.add_grid(Vec3(0, 0, 0), Vec3(0, 1, 0), spine, 4, 2);
    const FeatureClassification c = hdi::classify_features(s.points, s.triangles);
    check_invariants(s, c);
    std::size_t spine_edges = 0;
    for (std::size_t e = 0; e < c.edges.size(); ++e)
    {
        const Vec3& a = s.points[c.edges[e][0]];
        const Vec3& b = s.points[c.edges[e][1]];
        if (a.x() == 0 && a.y() == 0 && b.x() == 0 && b.y() == 0)
        {
            ++spine_edges;
            CHECK(c.edge_class[e].dimension == Dimension::Curve);
            CHECK_FALSE(c.edge_class[e].open_boundary);
        }
    }
    CHECK(spine_edges == 2);
    const hdi::FeatureSet f = hdi::feature_set(c);
    CHECK(f.ridge_edges.size() == 2);
    for (std::size_t v = 0; v < s.points.size(); ++v)
        if (s.points[v].x() == 0 && s.points[v].y() == 0 &&
            (s.points[v].z() == 0 || s.points[v].z() == 0.1))
            CHECK(c.vertex_class[v].dimension == Dimension::Corner);
}
