#pragma once
// Models for the surface operator tests (header-only: only the surface tests need OpenMesh).

#include <vector>

#include "fixtures.h"
#include "surface/projector.h"
#include "surface/surface_mesh.h"

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

/// The icosahedron on the unit sphere (hdimesh::fixtures::icosphere(0)), outward, every vertex
/// smooth, no curves, face ref 1.
inline SurfaceMesh icosahedron()
{
    const hdi::TriangleSurface ico = hdimesh::fixtures::icosphere(0);
    SurfaceMesh mesh;
    std::vector<VertexHandle> v;
    for (const auto& p : ico.points) v.push_back(mesh.add_vertex(Vec3d(p.x(), p.y(), p.z())));
    for (const auto& t : ico.triangles) mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);
    SurfaceProperties props(mesh);  // after the elements: their properties get initialised
    for (auto x : mesh.vertices())
    {
        mesh.property(props.vertex_class, x) = VertexClass::Smooth;
        mesh.property(props.vertex_curve, x) = kNoCurve;
    }
    for (auto e : mesh.edges()) mesh.property(props.edge_curve, e) = kNoCurve;
    for (auto f : mesh.faces()) mesh.property(props.face_ref, f) = 1;
    return mesh;
}

}  // namespace hdimesh::surface::fixtures
