#pragma once
// The geometry a remeshed surface must stay on, built from the input surface once: the input
// triangles (smooth vertices are projected onto them, or onto a smooth HDI model when one is
// plugged in) and the input feature curves (ridge and boundary vertices are projected onto
// their own curve only, so they slide along it and never jump to another ridge).

#include <functional>
#include <memory>
#include <vector>

#include "surface/projector.h"
#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

class ClosestPointTree;  // surface/detail: not installed

class SurfaceModel final : public Projector
{
public:
    /// `input` must carry the feature classification (detect_features) and no deleted elements
    /// (InputError otherwise). The model copies the geometry it needs; `input` may be
    /// modified or destroyed afterwards.
    explicit SurfaceModel(const SurfaceMesh& input);
    ~SurfaceModel() override;

    /// A smooth-surface projection (e.g. the HDI model) used for smooth vertices instead of the
    /// closest point on the input triangles. Returning ok == false falls back to the triangles.
    using SmoothProjection = std::function<ProjectedPoint(const Vec3d&)>;
    void set_smooth_projection(SmoothProjection projection) { smooth_ = std::move(projection); }
    bool has_smooth_projection() const { return static_cast<bool>(smooth_); }

    ProjectedPoint project(const Vec3d& p, VertexClass cls, int curve) const override;
    /// project() for placing a vertex near `face_hint` (an input face index, e.g. the `face` of
    /// the last projection of a neighbouring point). A smooth point goes onto the smooth
    /// projection when one is plugged in and succeeds; else onto the input triangles by
    /// closest_on_input with the hint and a local fraction of 1e-2: the foot where the descent
    /// from the hint stops (a local minimum of the distance over the input) when p is that
    /// near it, else the exact closest point. Without a hint, project().
    ProjectedPoint project_near(const Vec3d& p, VertexClass cls, int curve,
                                int face_hint) const override;
    /// Without a smooth projection: true at once when the descent from the hint face (see
    /// closest_on_input) meets a face within `distance`, else the exact search decides.
    bool near_model(const Vec3d& p, double distance, int face_hint) const override;
    /// Without a smooth projection: the exact distance to the input triangles, searched from
    /// where the descent from the hint stopped (a tight bound). With one: Projector's (through
    /// project_near, so a failed smooth projection measures to the placement's foot).
    double distance_to_surface(const Vec3d& p, int face_hint) const override;

    /// Closest point on the input triangles, with the model's normal there (foot_normal: the
    /// face's, or the vertex's or edge's when the foot is on one) and the face's index (`face`).
    /// With a hint, first a descent over the input from the hint face, to a face none of its
    /// neighbours beats (across its edges; around its corner for a foot at a corner). When p is
    /// within `local_fraction` of that face's shortest edge, its foot there is the answer: the
    /// foot on the hint's own sheet of the surface, which is the global one unless another
    /// sheet passes that near. Otherwise (an off-surface point, fraction 0, or no hint) the
    /// exact closest point, searched with the descent's face as the bound.
    ProjectedPoint closest_on_input(const Vec3d& p, int face_hint = -1,
                                    double local_fraction = 0.0) const;
    /// Distance from p to the input feature curve `curve` (infinity if there is none).
    double distance_to_curve(const Vec3d& p, int curve) const;

    /// Per-input-vertex principal curvature magnitude max(|k1|, |k2|), from a least-squares
    /// quadric fit over the 2-ring (used by curvature sizing); features get 0.
    const std::vector<double>& input_curvature() const { return curvature_; }
    const std::vector<Vec3d>& input_points() const { return points_; }
    /// A per-input-vertex value at p: barycentric interpolation on the closest input triangle.
    /// `face_hint` only speeds up the exact search (the result does not depend on it); besides,
    /// a p within 1e-12·diagonal of the hint face is taken on it without a search (a size looked
    /// up right after a projection onto that face): the value then differs from the search's by
    /// rounding only.
    double interpolate(const Vec3d& p, const std::vector<double>& per_input_vertex,
                       int face_hint = -1) const;
    double diagonal() const { return diagonal_; }
    /// The shortest edge of input face `face` (0 for a negative index).
    double shortest_edge(int face) const;
    /// How far input face `face` may lie from the smooth surface it samples: its longest edge
    /// squared times its vertices' largest curvature, over 8 (a chord's sagitta; 0 for a
    /// negative index, and on features, whose curvature is 0).
    double chord_error(int face) const;
    /// The fraction of the input's area on faces whose chord_error exceeds `tolerance`.
    double coarse_area_fraction(double tolerance) const;
    /// Per input face, its shell: the connected component (over shared vertices) it is in,
    /// numbered from 0 in face order.
    std::vector<int> face_shells() const;
    /// coarse_area_fraction over each shell of `face_shell` (face_shells()) on its own.
    std::vector<double> coarse_area_fractions(double tolerance,
                                              const std::vector<int>& face_shell) const;
    std::size_t curve_count() const;

private:
    // The constructor's steps, in order.
    void build_faces(const SurfaceMesh& input, std::vector<Vec3d>& face_normal_by_index,
                     std::vector<int>& model_face_by_index);
    void build_vertex_faces();
    void build_curves(const SurfaceMesh& input, bool classified,
                      OpenMesh::EPropHandleT<int> edge_curve,
                      const std::vector<Vec3d>& face_normal_by_index,
                      const std::vector<int>& model_face_by_index);
    void build_curvatures(const SurfaceMesh& input, bool classified,
                          OpenMesh::VPropHandleT<VertexClass> vertex_class,
                          const std::vector<Vec3d>& face_normal_by_index);

    // A face's plane for the descent's lower bound on the distance to the face: |normal · p -
    // offset| is within margin + 1e-9 (|p_x| + |p_y| + |p_z|) of p's distance to the plane of
    // the exact triangle, and the descent's computed foot on it no nearer than that distance
    // less the same margin (an infinite margin for a triangle too flat to bound).
    struct FacePlane
    {
        Vec3d normal{0, 0, 0};
        double offset = 0.0;
        double margin = 0.0;
    };
    // The plane of the triangle (a, b, c) with its unit normal (triangle_normal).
    static FacePlane face_plane(const Vec3d& a, const Vec3d& b, const Vec3d& c,
                                const Vec3d& unit_normal);
    // closest_on_input's descent from a face over the input toward p: to the nearest neighbour
    // each step. With stop_d2 ≥ 0 (near_model's proof search): to the first nearer neighbour,
    // until a face within sqrt(stop_d2) of p.
    struct Descent
    {
        int face = -1;           // where it stopped
        Vec3d foot{0, 0, 0};     // p's closest point on that face
        bool converged = false;  // at a local minimum (not out of steps, nor stopped early at a
                                 // face within sqrt(stop_d2) of p, as near_model wants)
    };
    Descent descend(const Vec3d& p, int face, double stop_d2 = -1.0) const;
    // The model's normal at `foot`, a point of `face`: the face's, or the vertex's or the edge's
    // when the foot is at a corner or on an edge (not the normal of whichever face a tie named).
    Vec3d foot_normal(int face, const Vec3d& foot) const;
    // Whether a squared distance d2 is within `fraction` of the shortest edge of `face`.
    bool within_fraction_of_face(int face, double d2, double fraction) const;

    std::vector<Vec3d> points_;
    std::vector<Vec3d> face_normals_;
    std::vector<FacePlane> face_planes_;
    std::vector<Vec3d> vertex_normals_;  // angle-weighted
    std::vector<std::array<int, 3>> face_vertices_;
    std::vector<std::array<int, 3>> face_neighbours_;  // across each edge (-1: open boundary)
    // The faces around each input vertex: vertex_faces_[vertex_face_offsets_[v] ..
    // vertex_face_offsets_[v + 1]).
    std::vector<int> vertex_face_offsets_, vertex_faces_;
    std::vector<double> curvature_;
    // The input's triangles and each curve's segments, for closest points (by pointer: the tree
    // is private machinery, its header not installed).
    std::unique_ptr<const ClosestPointTree> triangles_;
    std::vector<ClosestPointTree> curves_;
    std::vector<std::vector<Vec3d>>
        curve_normals_;                          // per segment: mean of the adjacent face normals
    std::vector<std::vector<int>> curve_faces_;  // per segment: an adjacent input face (a hint)
    SmoothProjection smooth_;
    double diagonal_ = 0.0;
};

}  // namespace hdimesh::surface
