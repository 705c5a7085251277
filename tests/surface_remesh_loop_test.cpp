// The plain move-and-split loop (remesh): sizes brought into band on a model, classes, topology
// and the model kept; no tolerance, polish or cleanup stage runs.

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

// OpenMesh's PropertyT<Vec3d>::push_back copies a default-constructed (deliberately
// uninitialized) VectorT: a -Wmaybe-uninitialized false positive once GCC inlines add_vertex here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "surface/remesh.h"
#include "surface/surface_quality.h"
#include "surface_fixtures.h"
#pragma GCC diagnostic pop

using namespace hdimesh::surface;
using hdimesh::surface::fixtures::euler;
using hdimesh::surface::fixtures::manifold_and_nondegenerate;

namespace
{

// The share of the live edges with Qt = min(h/L, L/h) ≥ 0.66 against the constant size h.
double share_in_band(const SurfaceMesh& mesh, double h)
{
    std::size_t in_band = 0, edges = 0;
    for (auto e : mesh.edges())
    {
        if (mesh.status(e).deleted()) continue;
        ++edges;
        if (size_quality(mesh.calc_edge_length(e), h) >= 0.66) ++in_band;
    }
    return edges > 0 ? static_cast<double>(in_band) / static_cast<double>(edges) : 0.0;
}

}  // namespace

TEST_CASE(
    "the loop on the icosahedron at h = 0.3: edges into band, on the sphere, closed and manifold")
{
    //        *            the icosahedron (12 vertices, edges ≈ 1.05) on the unit sphere,
    //      / | \          remeshed at a size of 0.3: every edge is too long at the start
    //    *---*---*
    SurfaceMesh mesh = fixtures::icosahedron();
    const SphereProjector sphere(Vec3d(0, 0, 0), 1.0);
    const double h = 0.3;
    RemeshOptions options;
    options.size = [h](const Vec3d&) { return h; };
    options.iterations = 6;
    REQUIRE(share_in_band(mesh, h) == 0.0);
    const RemeshReport report = remesh(mesh, options, sphere);
    CHECK(report.iterations == 6);
    CHECK(report.splits > 0);
    CHECK(report.refinement_splits == 0);  // no refinement in the loop
    CHECK(euler(mesh) == 2);
    CHECK(manifold_and_nondegenerate(mesh));
    for (auto v : mesh.vertices())
        CHECK(mesh.point(v).norm() == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(share_in_band(mesh, h) > 0.95);
    // The size property holds the size the loop judged each vertex by.
    const SurfaceProperties props(mesh);
    for (auto v : mesh.vertices()) CHECK(mesh.property(props.vertex_size, v) == h);
}

TEST_CASE(
    "the loop on a flat grid keeps its rim: boundary vertices stay on the boundary curve and "
    "corners stay put")
{
    //  (0,4)-------(4,4)     a 4×4 grid of unit squares in z = 0 at a size of 0.5: the rim is
    //    |  /  /  /  |       boundary curve 0, its four corners are corners; the loop splits
    //    | /  /  /   |       every edge, the rim's along the rim
    //  (0,0)-------(4,0)
    SurfaceMesh mesh = fixtures::flat_grid_with_rim(4, true);
    const fixtures::PlaneProjector plane;
    RemeshOptions options;
    options.size = [](const Vec3d&) { return 0.5; };
    options.iterations = 4;
    remesh(mesh, options, plane);
    CHECK(euler(mesh) == 1);
    CHECK(manifold_and_nondegenerate(mesh));
    const SurfaceProperties props(mesh);
    int corners = 0;
    for (auto v : mesh.vertices())
    {
        const Vec3d p = mesh.point(v);
        CHECK(p[2] == 0.0);
        const VertexClass cls = mesh.property(props.vertex_class, v);
        const bool on_rim = p[0] == 0.0 || p[0] == 4.0 || p[1] == 0.0 || p[1] == 4.0;
        CHECK(mesh.is_boundary(v) == on_rim);
        CHECK((cls != VertexClass::Smooth) == mesh.is_boundary(v));
        if (cls == VertexClass::Corner) ++corners;
    }
    CHECK(corners == 4);
    CHECK(share_in_band(mesh, 0.5) > 0.9);
}
