#include <algorithm>
#include <cmath>
#include <vector>

#include "surface/detail/local_ops_geometry.h"
#include "surface/detail/prefetch.h"
#include "surface/local_ops.h"

namespace hdimesh::surface
{
namespace
{

// A curve vertex moves toward the point of its curve that balances its two curve edges.
bool optimal_point_curve(const OperatorContext& ctx, VertexHandle v, Vec3d& optimal)
{
    const std::vector<Vec3d> ends = detail::curve_neighbour_points(ctx, v);
    if (ends.size() != 2) return false;
    optimal = 0.5 * (ends[0] + ends[1]);
    return true;
}

// The ball of v collected once per shift (the trial positions only move v): v's neighbours
// (the spokes, in the order of the circulation around v) and its faces, each with what no trial
// changes (its other two points, the length of its edge opposite v) and, with v where it is,
// its cross product. Every length, cross product and Qe is computed as detail::qe and
// detail::normal compute them on the face's points in face order: the same bits, computed once
// (they were five square roots and five divisions per face and trial, and as many again for
// the weights and the quality before).
class Ball
{
public:
    struct Spoke
    {
        Vec3d point;
        double length = 0.0;  // |point - v|, v where it is
    };
    struct Face
    {
        int a = 0, b = 0;  // the spokes after v in face order: (v, a, b) turns like the face
        int moved = 0;     // v's index in face order (detail::face_vertices)
        double outer_length = 0.0;  // |b - a|
        Vec3d cross;  // (p1 - p0) × (p2 - p0) of the points in face order, v where it is
        double cross_norm = 0.0;
    };

    // quality() at v's own position: every normal is unchanged, so it only asks for one that
    // is not degenerate (recomputing the normals cost more than the test).
    double quality_before = 1.0;

    Ball(const SurfaceMesh& mesh, VertexHandle v) : centre_(mesh.point(v))
    {
        scratch_.swap(kept());
        collect(mesh, v);
        for (const Face& face : scratch_.faces)
        {
            if (quality_before < 0.0) break;
            quality_before =
                unit_normal_ok(face)
                    ? std::min(quality_before, qe(face, spoke(face.a).length, spoke(face.b).length,
                                                  face.cross_norm))
                    : -1.0;
        }
    }
    ~Ball() { scratch_.swap(kept()); }
    Ball(const Ball&) = delete;
    Ball& operator=(const Ball&) = delete;

    const Vec3d& centre() const { return centre_; }
    const std::vector<Face>& faces() const { return scratch_.faces; }
    const Spoke& spoke(int index) const { return scratch_.spokes[index]; }

    // Qe of a face from its edges' lengths (v to a, v to b, the outer one) and its cross
    // product's norm, as triangle_qe computes it on the points in face order.
    static double qe(const Face& face, double length_a, double length_b, double cross_norm)
    {
        // Edge k of the face goes from its point k to its point k + 1.
        switch (face.moved)
        {
            case 0:
                return triangle_qe_from(length_a, face.outer_length, length_b,
                                        cross_norm);  // (v, a, b)
            case 1:
                return triangle_qe_from(length_b, length_a, face.outer_length,
                                        cross_norm);  // (b, v, a)
            default:
                return triangle_qe_from(face.outer_length, length_b, length_a,
                                        cross_norm);  // (a, b, v)
        }
    }

    // Worst Qe with v at p; -1 if a triangle turns more than the angle of cosine min_cos or
    // degenerates. Stops early, returning a value below `refused_below`, once the worst is under
    // it: the caller refuses any such move whatever the exact value (a smart shift's refused trials
    // were most of the polish's shifting).
    double quality(const Vec3d& p, double min_cos, double refused_below) const
    {
        // Each spoke's length is two faces' edge.
        std::vector<double>& length = scratch_.trial_lengths;
        length.resize(scratch_.spokes.size());
        for (std::size_t j = 0; j < length.size(); ++j)
            length[j] = (scratch_.spokes[j].point - p).norm();
        double worst = 1.0;
        for (const Face& face : scratch_.faces)
        {
            const Vec3d after = cross(face, p);
            const double after_norm = after.norm();
            if (!detail::turn_ok_cross(face.cross, face.cross_norm, after, after_norm, min_cos))
                return -1.0;
            worst = std::min(worst, qe(face, length[face.a], length[face.b], after_norm));
            if (worst < refused_below) return worst;
        }
        return worst;
    }

private:
    struct Scratch
    {
        std::vector<Spoke> spokes;
        std::vector<Face> faces;
        std::vector<HalfedgeHandle> around,
            back;  // v's outgoing halfedges in order; the backward walk's
        mutable std::vector<double> trial_lengths;  // quality()'s spoke lengths
        void swap(Scratch& o)
        {
            spokes.swap(o.spokes);
            faces.swap(o.faces);
            around.swap(o.around);
            back.swap(o.back);
            trial_lengths.swap(o.trial_lengths);
        }
    };

    // One shift per vertex and iteration: the vectors' capacity is kept from one ball to the
    // next (no allocation per ball).
    static Scratch& kept()
    {
        static thread_local Scratch scratch;
        return scratch;
    }

    // (p1 - p0) × (p2 - p0) of the face's points in face order with v at p. (By a switch, not
    // through an array indexed by `moved`: its stores and loads of the points in pieces stalled.)
    Vec3d cross(const Face& face, const Vec3d& p) const
    {
        const Vec3d& a = spoke(face.a).point;
        const Vec3d& b = spoke(face.b).point;
        switch (face.moved)
        {
            case 0: return OpenMesh::cross(a - p, b - p);   // (v, a, b)
            case 1: return OpenMesh::cross(p - b, a - b);   // (b, v, a)
            default: return OpenMesh::cross(b - a, p - a);  // (a, b, v)
        }
    }

    // Whether detail::normal of the face, v where it is, is not degenerate (a unit vector).
    static bool unit_normal_ok(const Face& face)
    {
        // A norm where neither its squares nor the quotients under- or overflow gives a unit
        // vector.
        if (detail::norm_in_safe_range(face.cross_norm)) return true;
        const Vec3d normal = face.cross_norm > 0.0 ? face.cross / face.cross_norm : Vec3d(0, 0, 0);
        return normal.sqrnorm() > 0.5;
    }

    // The circulation around v (detail::collect_star's order). First the halfedges alone: a
    // chain of reads each waiting for the one before (the mesh is larger than the cache; the
    // chain was a fifth of a shift's time), walked both ways at once so two reads are under way,
    // until the two ends meet. Then the points and the faces' first halfedges, reads that do not
    // wait for one another (and were asked for during the walk).
    void collect(const SurfaceMesh& mesh, VertexHandle v)
    {
        Scratch& s = scratch_;
        s.spokes.clear();
        s.faces.clear();
        s.around.clear();
        s.back.clear();
        const HalfedgeHandle start = mesh.halfedge_handle(v);
        if (!start.is_valid()) return;
        // The reads of the second part asked for as soon as their addresses are known.
        auto ask_ahead = [&](HalfedgeHandle h) {
            detail::prefetch(&mesh.point(mesh.to_vertex_handle(h)));
            const FaceHandle f = mesh.face_handle(h);
            if (f.is_valid()) detail::prefetch(&mesh.face(f));
        };
        s.around.push_back(start);
        ask_ahead(start);
        for (HalfedgeHandle forth = start, back = start;;)
        {
            const HalfedgeHandle next =
                mesh.cw_rotated_halfedge_handle(forth);  // vf_range's direction
            if (next == back) break;
            s.around.push_back(forth = next);
            ask_ahead(forth);
            const HalfedgeHandle before = mesh.ccw_rotated_halfedge_handle(back);
            if (before == forth) break;
            s.back.push_back(back = before);
            ask_ahead(back);
        }
        s.around.insert(s.around.end(), s.back.rbegin(), s.back.rend());
        const int spoke_count = static_cast<int>(s.around.size());
        s.spokes.resize(spoke_count);
        for (int j = 0; j < spoke_count; ++j)
        {
            Spoke& spoke = s.spokes[j];
            spoke.point = mesh.point(mesh.to_vertex_handle(s.around[j]));
            spoke.length = (spoke.point - centre_).norm();
        }
        // h_j = v -> a_j; the face of h_j is (v, a_j, a_{j-1}): h_j follows the opposite of
        // h_{j-1}.
        for (int j = 0; j < spoke_count; ++j)
        {
            const HalfedgeHandle h = s.around[j];
            const FaceHandle f = mesh.face_handle(h);
            if (!f.is_valid()) continue;
            Face face;
            face.a = j;
            face.b = j > 0 ? j - 1 : spoke_count - 1;
            // face_vertices starts at the face's own halfedge.
            const HalfedgeHandle first = mesh.halfedge_handle(f);
            face.moved = first == h ? 0 : first == mesh.next_halfedge_handle(h) ? 2 : 1;
            face.outer_length = (spoke(face.b).point - spoke(face.a).point).norm();
            face.cross = cross(face, centre_);
            face.cross_norm = face.cross.norm();
            s.faces.push_back(face);
        }
    }

    Vec3d centre_;
    Scratch scratch_;
};

// George's optimal point for a smooth vertex: for each outer edge (a, b) of the ball, the apex
// of the equilateral triangle on (a, b) in the tangent plane, on the vertex's side; weights
// 1/Qe² so the worst triangles pull hardest. From the ball's faces (a, b: the points after v in
// face order), in the order of the circulation around v that collected them.
bool optimal_point_smooth(const Ball& ball, const Vec3d& n, Vec3d& optimal)
{
    Vec3d sum(0, 0, 0);
    double weight_sum = 0.0;
    const Vec3d& pv = ball.centre();
    for (const Ball::Face& face : ball.faces())
    {
        const Vec3d& pa = ball.spoke(face.a).point;
        const Vec3d& pb = ball.spoke(face.b).point;
        Vec3d ideal;  // (a, b, v) is counter-clockwise about n
        if (!detail::equilateral_apex(pa, pb, face.outer_length, n, ideal)) return false;
        // Qe of (v, a, b): the face's own when v comes first in it.
        const double cross_norm =
            face.moved == 0 ? face.cross_norm : OpenMesh::cross(pa - pv, pb - pv).norm();
        const double q = std::max(triangle_qe_from(ball.spoke(face.a).length, face.outer_length,
                                                   ball.spoke(face.b).length, cross_norm),
                                  0.05);
        const double w = 1.0 / (q * q);
        sum += w * ideal;
        weight_sum += w;
    }
    if (!(weight_sum > 0.0)) return false;
    optimal = sum / weight_sum;
    return true;
}

}  // namespace

OpResult shift_vertex(OperatorContext& ctx, VertexHandle v, const ShiftOptions& options)
{
    SurfaceMesh& mesh = ctx.mesh;
    OpResult result;
    const VertexClass cls = ctx.vertex_class(v);
    if (cls == VertexClass::Corner || mesh.is_isolated(v)) return refused(OpStatus::Class);
    if (cls == VertexClass::Smooth && mesh.is_boundary(v))
        return refused(OpStatus::Class);  // an unclassified boundary vertex: leave it alone
    const Vec3d p = mesh.point(v);
    const Ball ball(mesh, v);
    Vec3d optimal;
    Vec3d n(0, 0, 0);
    if (cls == VertexClass::Smooth)
    {
        // The tangent plane of the ball (its area-weighted normal): the vertex is on the model
        // already, so this is the plane of the local fit without another projection.
        for (const Ball::Face& face : ball.faces()) n += face.cross;
        if (!(n.norm() > 0.0)) return result;
        n = detail::tangent_normal(ctx, v, n.normalized());
        if (!optimal_point_smooth(ball, n, optimal)) return refused(OpStatus::Geometry);
    }
    else if (!optimal_point_curve(ctx, v, optimal))
        return refused(OpStatus::Class);

    const double min_cos = detail::cos_deg(ctx.limits.max_normal_turn_deg);
    const double old_quality = ball.quality_before;
    // Below this a trial is refused by one of the tests after ball.quality() below.
    const double refused_below =
        options.smart ? old_quality - 1e-12 : std::min(ctx.limits.min_new_quality, old_quality);
    // Three trials, halving the step; a step of 0 is one: p itself onto the model.
    const int trials = options.step > 0.0 ? 3 : 1;
    double step = options.step;
    for (int trial = 0; trial < trials; ++trial, step *= 0.5)
    {
        Vec3d target = p + step * (optimal - p);
        if (cls == VertexClass::Smooth)
            target -= OpenMesh::dot(target - p, n) * n;  // stay in the plane
        const ProjectedPoint projected =
            ctx.model.project_near(target, cls, ctx.vertex_curve(v), ctx.model_face(v));
        if (!projected.ok) continue;
        const Vec3d q = projected.point;
        const double new_quality = ball.quality(q, min_cos, refused_below);
        if (new_quality < ctx.limits.min_new_quality && new_quality < old_quality) continue;
        if (new_quality < 0.0) continue;
        if (options.smart && new_quality < old_quality - 1e-12) continue;
        if (options.accept && !options.accept(q)) return refused(OpStatus::Geometry);
        return commit_move(ctx, v, q, projected.face);
    }
    return refused(OpStatus::Quality);
}

}  // namespace hdimesh::surface
