#pragma once
// What the remesher asks of the geometry: put a point back on the model, keeping its class.
// Implemented by SurfaceModel (input mesh + HDI) and, for tests, by the analytic SphereProjector.

#include <cmath>

#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

struct ProjectedPoint
{
    Vec3d point{0, 0, 0};
    Vec3d normal{0, 0, 0};  // unit surface normal at point (a ridge: either side's, or their mean)
    double k1 = 0.0, k2 = 0.0;  // principal curvatures where known (0 otherwise)
    bool ok = false;
    /// Where the model knows it: the index of the model face at (for a curve point: beside) the
    /// point, -1 otherwise. Opaque to the caller, who hands it back as the hint of a later query
    /// near the point (project_near): the projection then stays on the hint's part of the model.
    int face = -1;
};

class Projector
{
public:
    virtual ~Projector() = default;
    /// Projects p onto the model: a smooth vertex onto the surface, a ridge or boundary vertex
    /// onto its feature curve `curve`, a corner stays where it is.
    virtual ProjectedPoint project(const Vec3d& p, VertexClass cls, int curve) const = 0;
    /// project() for placing a vertex, told a model face near p (the `face` of an earlier
    /// projection of a neighbouring point, or -1): a model that searches for p may search
    /// locally from there and give the foot on the hint's own part of the model, which is
    /// project()'s unless another part passes nearer to p (a vertex then had better stay on its
    /// own sheet). Deterministic for a given hint; models without a search ignore the hint.
    virtual ProjectedPoint project_near(const Vec3d& p, VertexClass cls, int curve,
                                        int face_hint) const
    {
        static_cast<void>(face_hint);
        return project(p, cls, curve);
    }
    /// Distance from p (e.g. a centroid or an edge midpoint of the remeshed surface) to the
    /// smooth surface, told a model face near p as in project_near; 0 when the projection fails.
    /// Measured exactly by models with a search (project_near may stop at a local foot).
    virtual double distance_to_surface(const Vec3d& p, int face_hint) const
    {
        const ProjectedPoint on_model = project_near(p, VertexClass::Smooth, kNoCurve, face_hint);
        return on_model.ok ? (on_model.point - p).norm() : 0.0;
    }
    /// Whether distance_to_surface(p) <= distance. A model may answer without the full search
    /// when the hint face alone is near enough: the answer is the same.
    virtual bool near_model(const Vec3d& p, double distance, int face_hint) const
    {
        return distance_to_surface(p, face_hint) <= distance;
    }
};

/// The sphere of the given centre and radius (every class is projected radially): exact
/// geometry for the operator tests.
class SphereProjector final : public Projector
{
public:
    SphereProjector(Vec3d centre, double radius) : centre_(centre), radius_(radius) {}
    ProjectedPoint project(const Vec3d& p, VertexClass, int) const override
    {
        ProjectedPoint out;
        Vec3d d = p - centre_;
        const double len = d.norm();
        if (!(len > 0.0)) return out;
        d /= len;
        out.point = centre_ + radius_ * d;
        out.normal = d;
        out.k1 = out.k2 = 1.0 / radius_;
        out.ok = true;
        return out;
    }

private:
    Vec3d centre_;
    double radius_;
};

}  // namespace hdimesh::surface
