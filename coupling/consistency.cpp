#include "coupling/consistency.h"

#include <algorithm>
#include <map>

#include "volume/mesh/boundary.h"

namespace hdimesh::coupling
{

using namespace volume;

namespace
{

// The rotation of t that starts at its smallest id: equal for equal oriented faces.
Triangle canonical(const Triangle& t)
{
    const int k = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
    return {t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
}

std::string name(const Triangle& t)
{
    return "(" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " + std::to_string(t[2]) +
           ")";
}

}  // namespace

std::vector<std::string> check_consistency(const BoundaryMap& map, const TetMesh& mesh,
                                           std::size_t max_reports)
{
    std::vector<std::string> out;
    auto report = [&](const std::string& line) {
        if (out.size() < max_reports) out.push_back(line);
    };
    const auto& surf = map.surface;
    OpenMesh::VPropHandleT<surface::VertexClass> vertex_class;
    OpenMesh::FPropHandleT<int> face_ref;
    const bool has_class =
        surf.get_property_handle(vertex_class, surface::property_names::vertex_class);
    const bool has_ref = surf.get_property_handle(face_ref, surface::property_names::face_ref);

    std::vector<int> owner(mesh.num_vertices(), -1);
    for (auto v : surf.vertices())
    {
        if (surf.status(v).deleted()) continue;
        const int t = map.tet_vertex_of(v);
        if (t < 0 || t >= mesh.num_vertices())
        {
            report("surface vertex " + std::to_string(v.idx()) + " names tet vertex " +
                   std::to_string(t) + ", out of range");
            continue;
        }
        if (owner[t] >= 0) report("tet vertex " + std::to_string(t) + " has two surface vertices");
        owner[t] = v.idx();
        const auto& p = surf.point(v);
        const Vec3& q = mesh.points[t];
        if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2])
            report("tet vertex " + std::to_string(t) + " is not where its surface vertex is");
        if (has_class)
        {
            const VertexClass expected =
                to_vertex_class(surface::to_classification(surf.property(vertex_class, v)));
            if (mesh.vertex_classes[t] != expected)
                report("tet vertex " + std::to_string(t) + " is " +
                       to_string(mesh.vertex_classes[t]) + ", its surface vertex " +
                       surface::to_string(surf.property(vertex_class, v)));
        }
    }

    std::map<Triangle, int> surface_faces;  // canonical oriented face -> ref
    for (auto f : surf.faces())
    {
        if (surf.status(f).deleted()) continue;
        Triangle t{};
        int k = 0;
        for (auto v : surf.fv_range(f)) t[k++] = map.tet_vertex_of(v);
        surface_faces[canonical(t)] = has_ref ? surf.property(face_ref, f) : 0;
    }
    std::vector<Triangle> tet_faces;
    for (const auto& t : tet_surface_faces(mesh)) tet_faces.push_back(canonical(t));
    std::sort(tet_faces.begin(), tet_faces.end());
    for (const auto& t : tet_faces)
        if (!surface_faces.count(t))
            report("tet boundary or interface face " + name(t) + " is not on the surface");
    for (const auto& [t, ref] : surface_faces)
        if (!std::binary_search(tet_faces.begin(), tet_faces.end(), t))
            report("surface face " + name(t) + " is not a tet boundary or interface face");

    if (mesh.triangles.size() != surface_faces.size())
        report(std::to_string(mesh.triangles.size()) + " listed triangles for " +
               std::to_string(surface_faces.size()) + " surface faces");
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        const auto it = surface_faces.find(canonical(mesh.triangles[i]));
        const int ref = i < mesh.triangle_refs.size() ? mesh.triangle_refs[i] : 0;
        if (it == surface_faces.end())
            report("listed triangle " + name(mesh.triangles[i]) + " is not on the surface");
        else if (it->second != ref)
            report("listed triangle " + name(mesh.triangles[i]) + " has ref " +
                   std::to_string(ref) + ", its surface face " + std::to_string(it->second));
    }
    return out;
}

}  // namespace hdimesh::coupling
