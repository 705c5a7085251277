#pragma once
// The geometry a remeshed surface must stay on, built from the input surface once: the input
// triangles (smooth vertices are projected onto them, or onto a smooth HDI model when one is
// plugged in) and the input feature curves (ridge and boundary vertices are projected onto
// their own curve only, so they slide along it and never jump to another ridge).

#include <functional>
#include <memory>
#include <vector>

#include "surface/closest_point_tree.h"
#include "surface/projector.h"
#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

class SurfaceModel final : public Projector
{
public:
    /// `input` must carry the feature classification (detect_features). The model copies the
    /// geometry it needs; `input` may be modified or destroyed afterwards.
    explicit SurfaceModel(const SurfaceMesh& input);

    /// A smooth-surface projection (e.g. the HDI model) used for smooth vertices instead of the
    /// closest point on the input triangles. Returning ok == false falls back to the triangles.
    using SmoothProjection = std::function<ProjectedPoint(const Vec3d&)>;
    void set_smooth_projection(SmoothProjection projection) { smooth_ = std::move(projection); }

    ProjectedPoint project(const Vec3d& p, VertexClass cls, int curve) const override;

    /// Closest point on the input triangles, with that triangle's normal.
    ProjectedPoint closest_on_input(const Vec3d& p) const;
    /// Distance from p to the input feature curve `curve` (infinity if there is none).
    double distance_to_curve(const Vec3d& p, int curve) const;

    /// Per-input-vertex principal curvature magnitude max(|k1|, |k2|), from a least-squares
    /// quadric fit over the 2-ring (used by curvature sizing); features get 0.
    const std::vector<double>& input_curvature() const { return curvature_; }
    const std::vector<Vec3d>& input_points() const { return points_; }
    /// A per-input-vertex value at p: barycentric interpolation on the closest input triangle.
    double interpolate(const Vec3d& p, const std::vector<double>& per_input_vertex) const;
    double diagonal() const { return diagonal_; }
    std::size_t curve_count() const { return curves_.size(); }

private:
    std::vector<Vec3d> points_;
    std::vector<Vec3d> face_normals_;
    std::vector<std::array<int, 3>> face_vertices_;
    std::vector<double> curvature_;
    ClosestPointTree triangles_;
    std::vector<ClosestPointTree> curves_;
    std::vector<std::vector<Vec3d>> curve_normals_;  // per segment: mean of the adjacent face normals
    SmoothProjection smooth_;
    double diagonal_ = 0.0;
};

}  // namespace hdimesh::surface
