#pragma once
// The surface mesh type of hdimesh and the names of the properties every surface algorithm
// shares (vertex class, feature curve, size, refs). One header so that the names exist once.

#include <cassert>
#include <cstdint>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "common/classification.h"

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
constexpr const char* vertex_curve = "hdimesh:v:curve";  // int, feature curve of a ridge/boundary vertex
constexpr const char* vertex_size = "hdimesh:v:size";    // double, target edge length at the vertex
constexpr const char* edge_curve = "hdimesh:e:curve";    // int, feature curve of a ridge/boundary edge
constexpr const char* face_ref = "hdimesh:f:ref";        // int, surface reference (material/patch)
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
    OpenMesh::VPropHandleT<int> vertex_curve;
    OpenMesh::VPropHandleT<double> vertex_size;
    OpenMesh::EPropHandleT<int> edge_curve;
    OpenMesh::FPropHandleT<int> face_ref;
    OpenMesh::VPropHandleT<int> vertex_model_face;

    explicit SurfaceProperties(SurfaceMesh& mesh)
    {
        if (!mesh.get_property_handle(vertex_class, property_names::vertex_class))
        {
            mesh.add_property(vertex_class, property_names::vertex_class);
            for (auto v : mesh.vertices()) mesh.property(vertex_class, v) = VertexClass::Smooth;
        }
        if (!mesh.get_property_handle(vertex_curve, property_names::vertex_curve))
        {
            mesh.add_property(vertex_curve, property_names::vertex_curve);
            for (auto v : mesh.vertices()) mesh.property(vertex_curve, v) = kNoCurve;
        }
        if (!mesh.get_property_handle(vertex_size, property_names::vertex_size))
        {
            mesh.add_property(vertex_size, property_names::vertex_size);
            for (auto v : mesh.vertices()) mesh.property(vertex_size, v) = 0.0;
        }
        if (!mesh.get_property_handle(edge_curve, property_names::edge_curve))
        {
            mesh.add_property(edge_curve, property_names::edge_curve);
            for (auto e : mesh.edges()) mesh.property(edge_curve, e) = kNoCurve;
        }
        if (!mesh.get_property_handle(face_ref, property_names::face_ref))
        {
            mesh.add_property(face_ref, property_names::face_ref);
            for (auto f : mesh.faces()) mesh.property(face_ref, f) = 0;
        }
        if (!mesh.get_property_handle(vertex_model_face, property_names::vertex_model_face))
        {
            mesh.add_property(vertex_model_face, property_names::vertex_model_face);
            for (auto v : mesh.vertices()) mesh.property(vertex_model_face, v) = -1;
        }
    }
};

}  // namespace hdimesh::surface
