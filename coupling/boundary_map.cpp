// GCC 12 sees OpenMesh's point property grow (add_vertex) as maybe uninitialized; the
// warning points into the headers, so it is silenced before them.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "coupling/boundary_map.h"

#include <algorithm>
#include <map>

#include "common/errors.h"
#include "volume/check/surface_check.h"
#include "volume/mesh/boundary.h"

namespace hdimesh::coupling
{

using namespace volume;

namespace
{

std::string face_name(const Triangle& t)
{
    return "(" + std::to_string(t[0] + 1) + ", " + std::to_string(t[1] + 1) + ", " +
           std::to_string(t[2] + 1) + ")";
}

}  // namespace

std::string coupled_surface_refusal(const TetMesh& mesh)
{
    if (!mesh.required_edges.empty() || !mesh.required_triangles.empty())
        return "required edges or triangles";
    for (int v : mesh.required_vertices)
        if (mesh.vertex_classes[v] != VertexClass::Interior) return "required boundary vertices";
    // The boundary and the interfaces between tet refs, each interface once: closed shells
    // apart from each other make one 2-manifold surface; an interface that meets the boundary
    // or another interface makes edges of three or more triangles.
    const std::vector<Triangle> faces = tet_surface_faces(mesh);
    std::vector<std::array<int, 3>> keys;
    keys.reserve(faces.size());
    for (const auto& f : faces) keys.push_back(sorted_triple(f));
    std::sort(keys.begin(), keys.end());
    for (const auto& t : mesh.triangles)
        if (!std::binary_search(keys.begin(), keys.end(), sorted_triple(t)))
            return "triangles inside the volume";
    // a closed 2-manifold: every edge in two faces, no pinched vertex (OpenMesh takes neither)
    SurfaceCheckOptions topology_only;
    topology_only.check_self_intersections = false;  // the faces of valid tets do not cross
    const std::vector<SurfaceDefect> defects =
        check_closed_surface(mesh.points, faces, topology_only);
    if (defects.empty()) return {};
    // (the boundary alone is then listed again, for the message only)
    return faces.size() != tet_boundary_faces(mesh).size()
               ? "interfaces between tet refs that meet the boundary or each other"
               : format_surface_defects(defects, "the tets' boundary", 1);
}

std::vector<surface::VertexHandle> BoundaryMap::tet_to_surface(int num_tet_vertices) const
{
    std::vector<surface::VertexHandle> out(num_tet_vertices);
    for (auto v : surface.vertices())
    {
        const int t = tet_vertex_of(v);
        if (t >= 0 && t < num_tet_vertices) out[t] = v;
    }
    return out;
}

BoundaryMap extract_boundary(const TetMesh& mesh)
{
    BoundaryMap map;
    auto& surf = map.surface;
    surf.add_property(map.tet_vertex, property_names::tet_vertex);
    const surface::SurfaceProperties props(surf);

    std::map<std::array<int, 3>, int> ref_of;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        ref_of[sorted_triple(mesh.triangles[i])] =
            i < mesh.triangle_refs.size() ? mesh.triangle_refs[i] : 0;

    std::vector<surface::VertexHandle> handle(mesh.num_vertices());
    auto vertex = [&](int v) {
        if (!handle[v].is_valid())
        {
            const Vec3& p = mesh.points[v];
            const surface::Vec3d point(p[0], p[1], p[2]);
            handle[v] = surf.add_vertex(point);
            surf.property(map.tet_vertex, handle[v]) = v;
            surf.property(props.vertex_class, handle[v]) =
                mesh.vertex_classes[v] == VertexClass::Interior
                    ? surface::VertexClass::Smooth
                    : surface::to_vertex_class(to_classification(mesh.vertex_classes[v]));
        }
        return handle[v];
    };
    for (const Triangle& f : tet_surface_faces_by_adjacency(mesh))  // (the precondition)
    {
        const auto face = surf.add_face(vertex(f[0]), vertex(f[1]), vertex(f[2]));
        if (!face.is_valid())
            throw TopologyError("the boundary face " + face_name(f) +
                                " makes a non-manifold surface (vertex ids from 1)");
        const auto it = ref_of.find(sorted_triple(f));
        surf.property(props.face_ref, face) = it == ref_of.end() ? 0 : it->second;
    }
    // The properties were added on an empty mesh: elements added since have their type's
    // default, not "no curve" and "no hint".
    for (auto v : surf.vertices())
    {
        surf.property(props.vertex_curve, v) = surface::kNoCurve;
        surf.property(props.vertex_model_face, v) = -1;
    }
    for (auto e : surf.edges()) surf.property(props.edge_curve, e) = surface::kNoCurve;
    // The curves write_back stored (ref: curve id + 1), so a surface extracted again after a
    // refinement keeps the ids of the model built from the first one.
    for (std::size_t i = 0; i < mesh.edges.size() && i < mesh.edge_refs.size(); ++i)
    {
        const int curve = mesh.edge_refs[i] - 1;
        const auto [a, b] = mesh.edges[i];
        if (curve < 0 || !handle[a].is_valid() || !handle[b].is_valid()) continue;
        const auto h = surf.find_halfedge(handle[a], handle[b]);
        if (!h.is_valid()) continue;
        surf.property(props.edge_curve, surf.edge_handle(h)) = curve;
        for (auto v : {handle[a], handle[b]})
            if (surf.property(props.vertex_class, v) != surface::VertexClass::Corner)
                surf.property(props.vertex_curve, v) = curve;
    }
    return map;
}

void write_back(const BoundaryMap& map, TetMesh& mesh)
{
    const auto& surf = map.surface;
    // const: the properties exist (extract_boundary made them, the remesher keeps them)
    OpenMesh::VPropHandleT<surface::VertexClass> vertex_class;
    OpenMesh::EPropHandleT<int> edge_curve;
    OpenMesh::FPropHandleT<int> face_ref;
    surf.get_property_handle(vertex_class, surface::property_names::vertex_class);
    surf.get_property_handle(edge_curve, surface::property_names::edge_curve);
    surf.get_property_handle(face_ref, surface::property_names::face_ref);

    mesh.triangles.clear();
    mesh.triangle_refs.clear();
    for (auto f : surf.faces())
    {
        Triangle t{};
        int k = 0;
        for (auto v : surf.fv_range(f)) t[k++] = map.tet_vertex_of(v);
        mesh.triangles.push_back(t);
        mesh.triangle_refs.push_back(face_ref.is_valid() ? surf.property(face_ref, f) : 0);
    }
    mesh.edges.clear();
    mesh.edge_refs.clear();
    mesh.ridges.clear();
    if (edge_curve.is_valid())
        for (auto e : surf.edges())
        {
            const int curve = surf.property(edge_curve, e);
            if (curve == surface::kNoCurve) continue;
            const auto h = surf.halfedge_handle(e, 0);
            mesh.ridges.push_back(static_cast<int>(mesh.edges.size()));
            mesh.edges.push_back({map.tet_vertex_of(surf.from_vertex_handle(h)),
                                  map.tet_vertex_of(surf.to_vertex_handle(h))});
            mesh.edge_refs.push_back(curve + 1);
        }
    mesh.corners.clear();
    std::fill(mesh.vertex_classes.begin(), mesh.vertex_classes.end(), VertexClass::Interior);
    for (auto v : surf.vertices())
    {
        const int t = map.tet_vertex_of(v);
        const surface::VertexClass c =
            vertex_class.is_valid() ? surf.property(vertex_class, v) : surface::VertexClass::Smooth;
        mesh.vertex_classes[t] = to_vertex_class(surface::to_classification(c));
        if (c == surface::VertexClass::Corner) mesh.corners.push_back(t);
    }
}

}  // namespace hdimesh::coupling
