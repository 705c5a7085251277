#pragma once
// Models for the surface operator tests (header-only: only the surface tests need OpenMesh).

#include "surface/projector.h"

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

}  // namespace hdimesh::surface::fixtures
