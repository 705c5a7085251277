#pragma once
// The surface mesh type of hdimesh and the names of the properties every surface algorithm
// shares (vertex class, feature curve, size, refs). One header so that the names exist once.

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <cassert>
#include <cstdint>

#include "common/classification.h"
#include "common/point.h"

namespace hdimesh::surface
{

struct SurfaceTraits : public OpenMesh::DefaultTraits
{
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
    VertexAttributes(OpenMesh::Attributes::Status);
    EdgeAttributes(OpenMesh::Attributes::Status);
    HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
    FaceAttributes(OpenMesh::Attributes::Status);
};

using SurfaceMesh = OpenMesh::TriMesh_ArrayKernelT<SurfaceTraits>;
using Vec3d = OpenMesh::Vec3d;

/// The one conversion between OpenMesh's points and the point type of the other modules.
inline hdimesh::Vec3 to_point(const Vec3d& p) { return hdimesh::Vec3(p[0], p[1], p[2]); }
inline Vec3d to_vec3d(const hdimesh::Vec3& p) { return Vec3d(p[0], p[1], p[2]); }
using VertexHandle = OpenMesh::VertexHandle;
using EdgeHandle = OpenMesh::EdgeHandle;
using HalfedgeHandle = OpenMesh::HalfedgeHandle;
using FaceHandle = OpenMesh::FaceHandle;

/// What a vertex may do. An operator never changes a vertex's class: smooth vertices move on
/// the surface, ridge and boundary vertices slide along their curve, corners never move.
enum class VertexClass : std::uint8_t
{
    Smooth = 0,
    Ridge = 1,
    Boundary = 2,
    Corner = 3,
};

inline const char* to_string(VertexClass c)
{
    switch (c)
    {
        case VertexClass::Smooth: return "smooth";
        case VertexClass::Ridge: return "ridge";
        case VertexClass::Boundary: return "boundary";
        case VertexClass::Corner: return "corner";
    }
    return "?";
}

/// The shared classification of a surface vertex of this class (common/classification.h):
/// smooth on a surface, ridge and boundary on a curve (the boundary one open), a corner.
inline Classification to_classification(VertexClass c, int id = kNoModelEntity)
{
    switch (c)
    {
        case VertexClass::Smooth: return {Dimension::Surface, id, false};
        case VertexClass::Ridge: return {Dimension::Curve, id, false};
        case VertexClass::Boundary: return {Dimension::Curve, id, true};
        case VertexClass::Corner: return {Dimension::Corner, id, false};
    }
    return {Dimension::Surface, id, false};
}

/// The class of a surface vertex that lies on `c`. A volume classification has no surface
/// vertex; it is reported as Smooth only to keep the function total (an assert guards it).
inline VertexClass to_vertex_class(const Classification& c)
{
    switch (c.dimension)
    {
        case Dimension::Corner: return VertexClass::Corner;
        case Dimension::Curve: return c.open_boundary ? VertexClass::Boundary : VertexClass::Ridge;
        case Dimension::Surface: return VertexClass::Smooth;
        case Dimension::Volume: break;
    }
    assert(false && "a surface vertex never lies in a volume");
    return VertexClass::Smooth;
}

/// No feature curve (smooth vertex or edge; corners belong to several curves, so they have none).
constexpr int kNoCurve = -1;

namespace property_names
{
constexpr const char* vertex_class = "hdimesh:v:class";  // VertexClass
constexpr const char* vertex_curve =
    "hdimesh:v:curve";  // int, feature curve of a ridge/boundary vertex
constexpr const char* vertex_size = "hdimesh:v:size";  // double, target edge length at the vertex
constexpr const char* edge_curve =
    "hdimesh:e:curve";                             // int, feature curve of a ridge/boundary edge
constexpr const char* face_ref = "hdimesh:f:ref";  // int, surface reference (material/patch)
// int, the model face a vertex was last projected onto (ProjectedPoint::face; -1: none): the
// hint of the next projection near it. Projections do not depend on it; sizes interpolated on
// the hinted face may differ by rounding (SurfaceModel::interpolate).
constexpr const char* vertex_model_face = "hdimesh:v:model_face";
}  // namespace property_names

/// Handles of the shared properties, created on the mesh if missing (smooth, no curve, size 0,
/// ref 0). Cheap to construct; keep one per algorithm call.
struct SurfaceProperties
{
    OpenMesh::VPropHandleT<VertexClass> vertex_class;
    OpenMesh::VPropHandleT<int> vertex_curve, vertex_model_face;  // see property_names
    OpenMesh::VPropHandleT<double> vertex_size;
    OpenMesh::EPropHandleT<int> edge_curve;
    OpenMesh::FPropHandleT<int> face_ref;

    explicit SurfaceProperties(SurfaceMesh& mesh)
    {
        get_or_add(mesh, vertex_class, property_names::vertex_class, VertexClass::Smooth,
                   mesh.vertices());
        get_or_add(mesh, vertex_curve, property_names::vertex_curve, kNoCurve, mesh.vertices());
        get_or_add(mesh, vertex_size, property_names::vertex_size, 0.0, mesh.vertices());
        get_or_add(mesh, edge_curve, property_names::edge_curve, kNoCurve, mesh.edges());
        get_or_add(mesh, face_ref, property_names::face_ref, 0, mesh.faces());
        get_or_add(mesh, vertex_model_face, property_names::vertex_model_face, -1, mesh.vertices());
    }

private:
    // `handle` of the property `name`, added with `initial` on every element of `elements` if
    // missing.
    template <class Handle, class Value, class Elements>
    static void get_or_add(SurfaceMesh& mesh, Handle& handle, const char* name,
                           const Value& initial, Elements elements)
    {
        if (mesh.get_property_handle(handle, name)) return;
        mesh.add_property(handle, name);
        for (auto element : elements) mesh.property(handle, element) = initial;
    }
};

}  // namespace hdimesh::surface
