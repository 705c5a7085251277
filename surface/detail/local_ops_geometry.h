#pragma once
// Small geometric helpers shared by the operator files (split, collapse, flip, removal, shift):
// a face's vertices and points, optionally with one vertex moved, the star of a vertex for
// trials that move it, distances to a patch of triangles, and the angle tests.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "surface/detail/closest_point_tree.h"
#include "surface/local_ops.h"
#include "surface/surface_mesh.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface::detail
{

inline std::array<VertexHandle, 3> face_vertices(const SurfaceMesh& mesh, FaceHandle f)
{
    const HalfedgeHandle h = mesh.halfedge_handle(f);
    return {mesh.from_vertex_handle(h), mesh.to_vertex_handle(h),
            mesh.to_vertex_handle(mesh.next_halfedge_handle(h))};
}

/// The points of f with vertex `moved` (if it is one of f's) placed at `at`.
inline std::array<Vec3d, 3> face_points_with(const SurfaceMesh& mesh, FaceHandle f,
                                             VertexHandle moved, const Vec3d& at)
{
    const auto v = face_vertices(mesh, f);
    std::array<Vec3d, 3> p;
    for (int i = 0; i < 3; ++i) p[i] = v[i] == moved ? at : mesh.point(v[i]);
    return p;
}

inline std::array<Vec3d, 3> face_points(const SurfaceMesh& mesh, FaceHandle f)
{
    return face_points_with(mesh, f, VertexHandle(), Vec3d(0, 0, 0));
}

inline double qe(const std::array<Vec3d, 3>& p) { return triangle_qe(p[0], p[1], p[2]); }
inline Vec3d normal(const std::array<Vec3d, 3>& p) { return triangle_normal(p[0], p[1], p[2]); }

/// cos(degrees). A caller testing many triangles against one limit takes its cosine once and
/// tests with turn_ok_cos (no std::cos per tested triangle).
inline double cos_deg(double degrees) { return std::cos(degrees * M_PI / 180.0); }

/// The new normal turned by at most the angle whose cosine is `min_cos` from the old one (and is
/// not degenerate). The cosine once per operator, not per triangle: std::cos is costly.
inline bool turn_ok_cos(const Vec3d& old_normal, const Vec3d& new_normal, double min_cos)
{
    if (!(new_normal.sqrnorm() > 0.5)) return false;
    if (!(old_normal.sqrnorm() > 0.5))
        return true;  // the old triangle was degenerate: no reference
    return OpenMesh::dot(old_normal, new_normal) >= min_cos;
}

/// The new normal turned by at most the allowed angle from the old one (and is not degenerate).
inline bool turn_ok(const Vec3d& old_normal, const Vec3d& new_normal, double max_turn_deg)
{
    return turn_ok_cos(old_normal, new_normal, cos_deg(max_turn_deg));
}

/// Whether a cross product's norm is one whose squares and quotients neither under- nor overflow
/// (dividing by it then gives a unit vector, to rounding).
inline bool norm_in_safe_range(double norm) { return norm >= 1e-140 && norm <= 1e140; }

/// turn_ok_cos of the normals (triangle_normal) of two triangles given by their cross products
/// (b - a) × (c - a) and the norms of these: the same answer, mostly without the normals' six
/// divisions. Where no product under- or overflows, the cosine times both norms decides when it
/// is farther than 1e-12 of them from min_cos times both norms (either form's rounding is below
/// 1e-14 of them); nearer, or out of that range, the normals are made and tested.
inline bool turn_ok_cross(const Vec3d& old_cross, double old_norm, const Vec3d& new_cross,
                          double new_norm, double min_cos)
{
    if (norm_in_safe_range(old_norm) && norm_in_safe_range(new_norm) && std::abs(min_cos) <= 1.0)
    {
        const double scale = old_norm * new_norm;
        const double excess = OpenMesh::dot(old_cross, new_cross) - min_cos * scale;
        if (excess > 1e-12 * scale) return true;
        if (excess < -1e-12 * scale) return false;
    }
    auto unit = [](const Vec3d& n, double norm) { return norm > 0.0 ? n / norm : Vec3d(0, 0, 0); };
    return turn_ok_cos(unit(old_cross, old_norm), unit(new_cross, new_norm), min_cos);
}

/// A face around a vertex v, collected once for trial positions that move v only: its points in
/// face order, the index of v among them and its normal before the move.
struct StarFace
{
    std::array<Vec3d, 3> points;
    int moved = 0;
    Vec3d normal;

    std::array<Vec3d, 3> with_moved_at(const Vec3d& p) const
    {
        std::array<Vec3d, 3> after = points;
        after[moved] = p;
        return after;
    }
};

/// Distance from p to triangle t.
inline double distance_to_triangle(const Vec3d& p, const std::array<Vec3d, 3>& t)
{
    return std::sqrt((closest_point_on_triangle(p, t[0], t[1], t[2]) - p).sqrnorm());
}

/// Whether the squared distance from p to t, as closest_point_on_triangle measures it, is
/// certainly above d2: t's bounding box is farther, by a margin far above the rounding of that
/// measure (relative 1e-8, and 1e-8 of the coordinates' magnitude in distance: the same kind of
/// margin as ClosestPointTree::search prunes with). The patches' distance tests skip such
/// triangles without their closest point (most triangles of a 2-ring are this far from a
/// witness).
inline bool clearly_beyond(const Vec3d& p, const std::array<Vec3d, 3>& t, double d2)
{
    double box_d2 = 0.0, magnitude2 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
        const double lo = std::min({t[0][k], t[1][k], t[2][k]}),
                     hi = std::max({t[0][k], t[1][k], t[2][k]});
        const double d = std::max({lo - p[k], p[k] - hi, 0.0});
        box_d2 += d * d;
        const double m = std::max({std::abs(lo), std::abs(hi), std::abs(p[k])});
        magnitude2 += m * m;
    }
    return box_d2 > d2 * (1.0 + 1e-8) + 1e-16 * magnitude2;
}

/// best2 lowered to the squared distance from p to t where that is smaller (t skipped when its
/// box is clearly beyond): the step of a search for the nearest of several triangles.
inline void lower_to_squared_distance(const Vec3d& p, const std::array<Vec3d, 3>& t, double& best2)
{
    if (!clearly_beyond(p, t, best2))
        best2 = std::min(best2, (closest_point_on_triangle(p, t[0], t[1], t[2]) - p).sqrnorm());
}

/// Distance from p to the nearest of `triangles` (a large value when there are none).
inline double distance_to_triangles(const Vec3d& p,
                                    const std::vector<std::array<Vec3d, 3>>& triangles)
{
    double best2 = 1e300;
    for (const auto& t : triangles) lower_to_squared_distance(p, t, best2);
    return std::sqrt(best2);
}

/// Whether distance_to_triangle(p, t) <= limit: the same answer, without the closest point when
/// t's box is clearly beyond the limit.
inline bool within_triangle(const Vec3d& p, const std::array<Vec3d, 3>& t, double limit)
{
    return !clearly_beyond(p, t, limit * limit) && distance_to_triangle(p, t) <= limit;
}

/// Whether distance_to_triangles(p, triangles) <= limit, decided at the first triangle within
/// it (most witnesses of a tolerance check are, and need no other).
inline bool within_triangles(const Vec3d& p, const std::vector<std::array<Vec3d, 3>>& triangles,
                             double limit)
{
    for (const auto& t : triangles)
        if (within_triangle(p, t, limit)) return true;
    return false;
}

/// Whether model point w, against the output near a change (its triangles before and after),
/// ends within the larger of `bound` and its distance before (plus `slack`): the change opens
/// no gap at w.
inline bool keeps_witness(const Vec3d& w, const std::vector<std::array<Vec3d, 3>>& before,
                          const std::vector<std::array<Vec3d, 3>>& after, double bound,
                          double slack)
{
    if (within_triangles(w, after, bound)) return true;
    return !(distance_to_triangles(w, after) > distance_to_triangles(w, before) + slack);
}

/// The faces around v in the order of OpenMesh's circulation (vf_range), into `out` (cleared
/// first: callers may keep its capacity from one vertex to the next). Each face's points in the
/// order of face_vertices, read off the halfedges around v (the circulators were a quarter of
/// a shift's time).
inline void collect_star(const SurfaceMesh& mesh, VertexHandle v, std::vector<StarFace>& out)
{
    out.clear();
    const HalfedgeHandle start = mesh.halfedge_handle(v);
    if (!start.is_valid()) return;
    HalfedgeHandle h = start;  // v -> a, then a -> b, b -> v around its face
    do
    {
        const FaceHandle f = mesh.face_handle(h);
        if (f.is_valid())
        {
            const HalfedgeHandle next = mesh.next_halfedge_handle(h);
            const Vec3d& pv = mesh.point(v);
            const Vec3d& pa = mesh.point(mesh.to_vertex_handle(h));
            const Vec3d& pb = mesh.point(mesh.to_vertex_handle(next));
            // face_vertices starts at the face's own halfedge.
            const HalfedgeHandle first = mesh.halfedge_handle(f);
            StarFace face;
            if (first == h)
                face.points = {pv, pa, pb}, face.moved = 0;
            else if (first == next)
                face.points = {pa, pb, pv}, face.moved = 2;
            else
                face.points = {pb, pv, pa}, face.moved = 1;
            face.normal = normal(face.points);
            out.push_back(face);
        }
        h = mesh.cw_rotated_halfedge_handle(h);  // vf_range's direction
    } while (h != start);
}

/// The star of v for trials that move v only, collected once: its faces (collect_star), the
/// other ends of its edges and v's place before the move.
struct TrialStar
{
    std::vector<StarFace> faces;
    std::vector<Vec3d> neighbours;
    Vec3d centre;

    TrialStar(const SurfaceMesh& mesh, VertexHandle v) : centre(mesh.point(v))
    {
        collect_star(mesh, v, faces);
        for (auto w : mesh.vv_range(v)) neighbours.push_back(mesh.point(w));
    }

    /// The band [min_length, max_length] (≤ 0: open) with v at p: no edge leaves it, nor gets
    /// farther out of it than it is (a long edge no longer, a short one no shorter).
    bool lengths_ok(const Vec3d& p, double min_length, double max_length) const
    {
        for (const Vec3d& w : neighbours)
        {
            const double length = (w - p).norm(), now = (w - centre).norm();
            if (max_length > 0.0 && length > max_length && length > now) return false;
            if (min_length > 0.0 && length < min_length && length < now) return false;
        }
        return true;
    }
};

/// The points of v's neighbours along its own curve (two for a vertex inside a curve).
inline std::vector<Vec3d> curve_neighbour_points(const OperatorContext& ctx, VertexHandle v)
{
    std::vector<Vec3d> ends;
    for (auto h : ctx.mesh.voh_range(v))
        if (ctx.edge_curve(ctx.mesh.edge_handle(h)) == ctx.vertex_curve(v))
            ends.push_back(ctx.mesh.point(ctx.mesh.to_vertex_handle(h)));
    return ends;
}

/// The apex of the equilateral triangle on (a, b), of side `length` = |b - a|, in the plane of
/// unit normal n, on the side where (a, b, apex) turns counter-clockwise about n; false when
/// b - a is parallel to n.
inline bool equilateral_apex(const Vec3d& a, const Vec3d& b, double length, const Vec3d& n,
                             Vec3d& apex)
{
    Vec3d side = OpenMesh::cross(n, b - a);
    const double norm = side.norm();
    if (!(norm > 0.0)) return false;
    side /= norm;
    apex = 0.5 * (a + b) + (std::sqrt(3.0) / 2.0) * length * side;
    return true;
}

/// The triangles of the 2-ring of v (every face touching a neighbour of v, which includes every
/// face of v), sorted by handle, with the index of v in each (-1: not one of its vertices): the
/// output near a star, to measure distances before and after a move of v.
struct TwoRingPatch
{
    std::vector<std::array<Vec3d, 3>> triangles;
    std::vector<int> moved;

    TwoRingPatch(const SurfaceMesh& mesh, VertexHandle v)
    {
        std::vector<FaceHandle> faces;
        for (auto w : mesh.vv_range(v))
            for (auto f : mesh.vf_range(w)) faces.push_back(f);
        std::sort(faces.begin(), faces.end());
        faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
        for (const FaceHandle f : faces)
        {
            const auto fv = face_vertices(mesh, f);
            triangles.push_back(face_points(mesh, f));
            moved.push_back(fv[0] == v ? 0 : fv[1] == v ? 1 : fv[2] == v ? 2 : -1);
        }
    }

    /// Triangle i with v at *v_at (nullptr: where it is).
    std::array<Vec3d, 3> triangle(std::size_t i, const Vec3d* v_at) const
    {
        std::array<Vec3d, 3> t = triangles[i];
        if (v_at && moved[i] >= 0) t[moved[i]] = *v_at;
        return t;
    }

    /// The patch's triangles with v at *v_at, into `out` (cleared first; a caller testing many
    /// points against one trial position keeps it).
    void triangles_at(const Vec3d* v_at, std::vector<std::array<Vec3d, 3>>& out) const
    {
        out.clear();
        for (std::size_t i = 0; i < triangles.size(); ++i) out.push_back(triangle(i, v_at));
    }

    /// Distance from p to the patch with v at *v_at (nullptr: where it is).
    double distance(const Vec3d& p, const Vec3d* v_at) const
    {
        double best2 = 1e300;
        for (std::size_t i = 0; i < triangles.size(); ++i)
            lower_to_squared_distance(p, triangle(i, v_at), best2);
        return std::sqrt(best2);
    }
};

/// The farthest from the model beyond `tolerance` (OperatorContext::distance_beyond) of the
/// samples of v's star (its faces' centroids, its edges' midpoints) with v at `at`: what a
/// move of v may not make worse beyond the tolerance.
inline double star_samples_beyond(const OperatorContext& ctx, VertexHandle v, const Vec3d& at,
                                  double tolerance)
{
    const SurfaceMesh& mesh = ctx.mesh;
    double worst = 0.0;
    for (auto f : mesh.vf_range(v))
    {
        const auto t = face_points_with(mesh, f, v, at);
        worst = std::max(worst, ctx.distance_beyond((t[0] + t[1] + t[2]) / 3.0, v, tolerance));
    }
    for (auto w : mesh.vv_range(v))
        worst = std::max(worst, ctx.distance_beyond(0.5 * (mesh.point(w) + at), v, tolerance));
    return worst;
}

/// The plane a smooth vertex's trial points stay in: the ball's unit normal `ball`, or with
/// OperatorLimits::shift_in_model_plane the model's normal at v turned to the ball's side.
inline Vec3d tangent_normal(const OperatorContext& ctx, VertexHandle v, const Vec3d& ball)
{
    if (!ctx.limits.shift_in_model_plane) return ball;
    const ProjectedPoint at =
        ctx.model.project_near(ctx.mesh.point(v), VertexClass::Smooth, kNoCurve, ctx.model_face(v));
    if (!at.ok || !(at.normal.norm() > 0.0)) return ball;
    const Vec3d m = at.normal.normalized();
    return OpenMesh::dot(m, ball) < 0.0 ? Vec3d(-m) : m;
}

/// How far a length is out of the band [lo, hi] (≤ 0 bounds: open), 0 inside.
inline double out_of_band(double length, double lo, double hi)
{
    if (lo > 0.0 && length < lo) return lo - length;
    if (hi > 0.0 && length > hi) return length - hi;
    return 0.0;
}

}  // namespace hdimesh::surface::detail
