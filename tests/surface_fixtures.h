#pragma once
// Models for the surface operator tests (header-only: only the surface tests need OpenMesh).

#include <algorithm>
#include <cmath>
#include <vector>

#include "fixtures.h"
#include "surface/detail/closest_point_tree.h"
#include "surface/projector.h"
#include "surface/surface_mesh.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface::fixtures
{

/// The plane z = 0 (normal +z) as a model: every class is projected vertically.
class PlaneProjector final : public Projector
{
public:
    ProjectedPoint project(const Vec3d& p, VertexClass, int) const override
    {
        ProjectedPoint out;
        out.point = Vec3d(p[0], p[1], 0.0);
        out.normal = Vec3d(0, 0, 1);
        out.ok = true;
        return out;
    }
};

/// Every vertex smooth with no curve and no model-face hint, every edge off curves, every face
/// ref 1: the starting classification of the operator tests, which then set their features.
inline void mark_all_smooth(SurfaceMesh& mesh)
{
    SurfaceProperties props(mesh);
    for (auto v : mesh.vertices())
    {
        mesh.property(props.vertex_class, v) = VertexClass::Smooth;
        mesh.property(props.vertex_curve, v) = kNoCurve;
        mesh.property(props.vertex_model_face, v) = -1;
    }
    for (auto e : mesh.edges()) mesh.property(props.edge_curve, e) = kNoCurve;
    for (auto f : mesh.faces()) mesh.property(props.face_ref, f) = 1;
}

/// The vertex at p (exactly, to 1e-12), or an invalid handle.
inline VertexHandle vertex_at(const SurfaceMesh& mesh, const Vec3d& p)
{
    for (auto v : mesh.vertices())
        if ((mesh.point(v) - p).norm() < 1e-12) return v;
    return VertexHandle();
}

/// Every vertex's point, in handle order (to assert that a refused operator moved nothing).
inline std::vector<Vec3d> points_of(const SurfaceMesh& mesh)
{
    std::vector<Vec3d> points;
    for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
    return points;
}

/// Exact distance from p to the mesh's triangles (brute force: the tests' meshes are tiny).
inline double distance_to_mesh(const SurfaceMesh& mesh, const Vec3d& p)
{
    double best = 1e300;
    for (auto f : mesh.faces())
    {
        auto fv = mesh.cfv_iter(f);
        const Vec3d a = mesh.point(*fv), b = mesh.point(*++fv), c = mesh.point(*++fv);
        best = std::min(best, (closest_point_on_triangle(p, a, b, c) - p).norm());
    }
    return best;
}

/// An n×n grid of unit squares over the (x, y) plane at heights height(i, j), each square cut
/// by its (i,j)-(i+1,j+1) diagonal. Unclassified: each test sets the properties it needs.
template <class Height>
SurfaceMesh triangulated_grid(int n, Height height)
{
    SurfaceMesh mesh;
    std::vector<VertexHandle> v;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) v.push_back(mesh.add_vertex(Vec3d(i, j, height(i, j))));
    auto at = [&](int i, int j) { return v[j * (n + 1) + i]; };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
            mesh.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            mesh.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    return mesh;
}

/// The n×n flat grid (triangulated_grid at z = 0), classified: the rim boundary curve 0 (its
/// four corners Corner when `corners`), the rest smooth, face ref 1.
inline SurfaceMesh flat_grid_with_rim(int n, bool corners)
{
    SurfaceMesh mesh = triangulated_grid(n, [](int, int) { return 0.0; });
    mark_all_smooth(mesh);
    SurfaceProperties props(mesh);
    const double far = static_cast<double>(n);
    for (auto v : mesh.vertices())
    {
        if (!mesh.is_boundary(v)) continue;
        const Vec3d p = mesh.point(v);
        const bool corner = corners && (p[0] == 0.0 || p[0] == far) && (p[1] == 0.0 || p[1] == far);
        mesh.property(props.vertex_class, v) = corner ? VertexClass::Corner : VertexClass::Boundary;
        mesh.property(props.vertex_curve, v) = corner ? kNoCurve : 0;
    }
    for (auto e : mesh.edges())
        mesh.property(props.edge_curve, e) = mesh.is_boundary(e) ? 0 : kNoCurve;
    return mesh;
}

/// The icosahedron on the unit sphere (hdimesh::fixtures::icosphere(0)), outward, every vertex
/// smooth, no curves, face ref 1.
inline SurfaceMesh icosahedron()
{
    const hdi::TriangleSurface ico = hdimesh::fixtures::icosphere(0);
    SurfaceMesh mesh;
    std::vector<VertexHandle> v;
    for (const auto& p : ico.points) v.push_back(mesh.add_vertex(Vec3d(p.x(), p.y(), p.z())));
    for (const auto& t : ico.triangles) mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);
    mark_all_smooth(mesh);  // after the elements: their properties get initialised
    return mesh;
}

/// What a move of v may not leave on a height-field mesh (every normal up): faces folded (normal
/// not up) or with an angle under min_angle_deg (up to rounding), and edges of v out of
/// [min_length, max_length].
struct MovedStarDefects
{
    int folded = 0, small_angles = 0, edges_out_of_band = 0;
};
inline MovedStarDefects moved_star_defects(const SurfaceMesh& mesh, VertexHandle v,
                                           double min_angle_deg, double min_length,
                                           double max_length)
{
    MovedStarDefects defects;
    for (auto f : mesh.faces())
    {
        auto fv = mesh.cfv_iter(f);
        const Vec3d a = mesh.point(*fv), b = mesh.point(*++fv), c = mesh.point(*++fv);
        if (!(triangle_normal(a, b, c)[2] > 0.0)) ++defects.folded;
        if (!(triangle_min_angle_deg(a, b, c) >= min_angle_deg - 1e-9)) ++defects.small_angles;
    }
    for (auto w : mesh.vv_range(v))
    {
        const double length = (mesh.point(w) - mesh.point(v)).norm();
        if (!(length >= min_length) || !(length <= max_length)) ++defects.edges_out_of_band;
    }
    return defects;
}

/// Points spread evenly over the unit sphere (a Fibonacci lattice): the "input vertices".
inline std::vector<Vec3d> sphere_points(int n)
{
    std::vector<Vec3d> points;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i)
    {
        const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
        points.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
    }
    return points;
}

/// V - E + F over the live elements (isolated vertices not counted).
inline long euler(const SurfaceMesh& mesh)
{
    long v = 0, e = 0, f = 0;
    for (auto x : mesh.vertices())
        if (!mesh.status(x).deleted() && !mesh.is_isolated(x)) ++v;
    for (auto x : mesh.edges())
        if (!mesh.status(x).deleted()) ++e;
    for (auto x : mesh.faces())
        if (!mesh.status(x).deleted()) ++f;
    return v - e + f;
}

/// Whether every live vertex is manifold and every live face has a positive Qe (not flat).
inline bool manifold_and_nondegenerate(const SurfaceMesh& mesh)
{
    for (auto v : mesh.vertices())
        if (!mesh.status(v).deleted() && !mesh.is_manifold(v)) return false;
    for (auto f : mesh.faces())
        if (!mesh.status(f).deleted() && !(face_qe(mesh, f) > 0.0)) return false;
    return true;
}

}  // namespace hdimesh::surface::fixtures
