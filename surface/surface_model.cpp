#include "surface/surface_model.h"

#include <cmath>
#include <limits>
#include <set>

#include <Eigen/Dense>

#include "surface/surface_quality.h"

namespace hdimesh::surface
{
namespace
{

Eigen::Vector3d to_eigen(const Vec3d& p) { return {p[0], p[1], p[2]}; }

// max(|k1|, |k2|) at v from z = a x² + b xy + c y² + d x + e y fitted to its 2-ring in the frame
// of the vertex normal; 0 when the ring is too small to fit.
double quadric_curvature(const SurfaceMesh& mesh, VertexHandle v, const Vec3d& normal)
{
    std::set<int> ring;
    for (auto w : mesh.vv_range(v))
    {
        ring.insert(w.idx());
        for (auto u : mesh.vv_range(w)) ring.insert(u.idx());
    }
    ring.erase(v.idx());
    if (ring.size() < 6 || !(normal.norm() > 0.0)) return 0.0;
    const Eigen::Vector3d n = to_eigen(normal).normalized();
    const Eigen::Vector3d seed = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d e1 = n.cross(seed).normalized();
    const Eigen::Vector3d e2 = n.cross(e1);
    const Eigen::Vector3d origin = to_eigen(mesh.point(v));
    Eigen::MatrixXd a(ring.size(), 5);
    Eigen::VectorXd rhs(ring.size());
    int row = 0;
    for (int idx : ring)
    {
        const Eigen::Vector3d d = to_eigen(mesh.point(VertexHandle(idx))) - origin;
        const double x = d.dot(e1), y = d.dot(e2);
        a.row(row) << x * x, x * y, y * y, x, y;
        rhs(row) = d.dot(n);
        ++row;
    }
    const Eigen::VectorXd c = a.colPivHouseholderQr().solve(rhs);
    if (!c.allFinite()) return 0.0;
    Eigen::Matrix2d shape;
    shape << 2 * c(0), c(1), c(1), 2 * c(2);
    const Eigen::Vector2d k = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(shape).eigenvalues();
    return std::max(std::abs(k(0)), std::abs(k(1)));
}

}  // namespace

SurfaceModel::SurfaceModel(const SurfaceMesh& input)
{
    // Read-only look-up: an unclassified input is all smooth, without curves.
    OpenMesh::VPropHandleT<VertexClass> vertex_class;
    OpenMesh::EPropHandleT<int> edge_curve;
    const bool classified = input.get_property_handle(vertex_class, property_names::vertex_class) &&
                            input.get_property_handle(edge_curve, property_names::edge_curve);
    auto curve_of = [&](EdgeHandle e) { return classified ? input.property(edge_curve, e) : kNoCurve; };
    auto is_smooth = [&](VertexHandle v) {
        return !classified || input.property(vertex_class, v) == VertexClass::Smooth;
    };
    diagonal_ = bounding_box_diagonal(input);
    points_.reserve(input.n_vertices());
    for (auto v : input.vertices()) points_.push_back(input.point(v));

    std::vector<std::array<Vec3d, 3>> tris;
    tris.reserve(input.n_faces());
    std::vector<Vec3d> face_normal_by_index(input.n_faces());
    for (auto f : input.faces())
    {
        auto fv = input.cfv_iter(f);
        const Vec3d a = input.point(*fv), b = input.point(*++fv), c = input.point(*++fv);
        tris.push_back({a, b, c});
        auto vi = input.cfv_iter(f);
        const int i0 = vi->idx(), i1 = (++vi)->idx(), i2 = (++vi)->idx();
        face_vertices_.push_back({i0, i1, i2});
        face_normals_.push_back(triangle_normal(a, b, c));
        face_normal_by_index[f.idx()] = face_normals_.back();
    }
    triangles_ = ClosestPointTree::from_triangles(std::move(tris));

    int curve_count = 0;
    for (auto e : input.edges()) curve_count = std::max(curve_count, curve_of(e) + 1);
    std::vector<std::vector<std::array<Vec3d, 2>>> segments(curve_count);
    curve_normals_.assign(curve_count, {});
    for (auto e : input.edges())
    {
        const int c = curve_of(e);
        if (c < 0) continue;
        const auto h = input.halfedge_handle(e, 0);
        segments[c].push_back({input.point(input.from_vertex_handle(h)), input.point(input.to_vertex_handle(h))});
        Vec3d n(0, 0, 0);
        for (int i = 0; i < 2; ++i)
        {
            const auto f = input.face_handle(input.halfedge_handle(e, i));
            if (f.is_valid()) n += face_normal_by_index[f.idx()];
        }
        const double len = n.norm();
        curve_normals_[c].push_back(len > 0 ? n / len : n);
    }
    for (const auto& s : segments) curves_.push_back(ClosestPointTree::from_segments(s));

    curvature_.assign(input.n_vertices(), 0.0);
    for (auto v : input.vertices())
    {
        if (!is_smooth(v)) continue;
        Vec3d n(0, 0, 0);
        for (auto f : input.vf_range(v)) n += face_normal_by_index[f.idx()] * input.calc_face_area(f);
        curvature_[v.idx()] = quadric_curvature(input, v, n);
    }
}

ProjectedPoint SurfaceModel::closest_on_input(const Vec3d& p) const
{
    ProjectedPoint out;
    const auto hit = triangles_.closest(p);
    if (hit.primitive < 0) return out;
    out.point = hit.point;
    out.normal = face_normals_[hit.primitive];
    out.ok = true;
    return out;
}

double SurfaceModel::interpolate(const Vec3d& p, const std::vector<double>& values) const
{
    const auto hit = triangles_.closest(p);
    if (hit.primitive < 0) return 0.0;
    const auto& fv = face_vertices_[hit.primitive];
    const Vec3d a = points_[fv[0]], b = points_[fv[1]], c = points_[fv[2]];
    // Barycentric coordinates of the hit point by sub-areas.
    const double area = OpenMesh::cross(b - a, c - a).norm();
    if (!(area > 0.0)) return (values[fv[0]] + values[fv[1]] + values[fv[2]]) / 3.0;
    const Vec3d q = hit.point;
    const double wa = OpenMesh::cross(b - q, c - q).norm() / area;
    const double wb = OpenMesh::cross(c - q, a - q).norm() / area;
    const double wc = std::max(0.0, 1.0 - wa - wb);
    return (wa * values[fv[0]] + wb * values[fv[1]] + wc * values[fv[2]]) / std::max(wa + wb + wc, 1e-300);
}

double SurfaceModel::distance_to_curve(const Vec3d& p, int curve) const
{
    if (curve < 0 || curve >= static_cast<int>(curves_.size()) || curves_[curve].empty())
        return std::numeric_limits<double>::infinity();
    return curves_[curve].closest(p).distance;
}

ProjectedPoint SurfaceModel::project(const Vec3d& p, VertexClass cls, int curve) const
{
    switch (cls)
    {
    case VertexClass::Corner:
    {
        ProjectedPoint out = closest_on_input(p);
        out.point = p;
        return out;
    }
    case VertexClass::Ridge:
    case VertexClass::Boundary:
    {
        if (curve < 0 || curve >= static_cast<int>(curves_.size()) || curves_[curve].empty()) return {};
        const auto hit = curves_[curve].closest(p);
        ProjectedPoint out;
        out.point = hit.point;
        out.normal = curve_normals_[curve][hit.primitive];
        out.ok = true;
        return out;
    }
    case VertexClass::Smooth:
        if (smooth_)
        {
            ProjectedPoint out = smooth_(p);
            if (out.ok) return out;
        }
        return closest_on_input(p);
    }
    return {};
}

}  // namespace hdimesh::surface
