#include "volume/check/boundary_repair.h"

#include <algorithm>

#include "common/errors.h"
#include "volume/check/check.h"
#include "volume/mesh/boundary.h"

namespace hdimesh::volume
{

std::vector<std::string> BoundaryRepair::lines() const
{
    struct Line
    {
        int count;
        const char *verb, *one, *many, *tail;
    };
    const Line table[] = {
        {dropped_interior, "dropped", "interior triangle", "interior triangles",
         " (between two tets of the same ref)"},
        {dropped_duplicates, "dropped", "repeated triangle", "repeated triangles", ""},
        {turned_outward, "turned", "boundary triangle", "boundary triangles", " outward"},
        {added_boundary, "added", "boundary triangle", "boundary triangles",
         " from the tets' unshared faces (ref of their tet)"},
        {added_interface, "added", "interface triangle", "interface triangles",
         " between tets of two refs (the smaller ref)"},
    };
    std::vector<std::string> out;
    for (const Line& line : table)
        if (line.count > 0)
            out.push_back(std::string(line.verb) + " " + std::to_string(line.count) + " " +
                          (line.count == 1 ? line.one : line.many) + line.tail);
    return out;
}

BoundaryRepair repair_boundary(TetMesh& mesh, const BoundaryRepairOptions& options)
{
    BoundaryRepair repair;
    const int nt = static_cast<int>(mesh.triangles.size());
    if (static_cast<int>(mesh.triangle_refs.size()) != nt) mesh.triangle_refs.resize(nt, 0);
    const bool has_tet_refs = mesh.tet_refs.size() == mesh.tets.size();
    auto tet_ref = [&](int t) { return has_tet_refs ? mesh.tet_refs[t] : 0; };

    std::vector<char> required(nt, 0);
    for (int i : mesh.required_triangles)
        if (i >= 0 && i < nt) required[i] = 1;

    // the first listing of a face is the one kept
    const std::vector<ListedTriangle> declared = listed_triangles(mesh);

    std::vector<char> keep(nt, 1);
    std::vector<Triangle> added;
    std::vector<int> added_refs;
    const FaceGroups groups = group_tet_faces(mesh);
    for (int k = 0; k < groups.num_faces(); ++k)
    {
        const int uses = groups.start[k + 1] - groups.start[k];
        if (uses > 2) continue;  // a face of three tets: the checker's to name
        const TetFace& first = groups.uses[groups.start[k]];
        const Triangle face = face_vertices(mesh, first);
        const auto range = listings(declared, sorted_triple(face));

        if (uses == 2)
        {
            const TetFace& second = groups.uses[groups.start[k] + 1];
            const int ref_a = tet_ref(first.tet), ref_b = tet_ref(second.tet);
            if (ref_a == ref_b)
            {
                for (auto it = range.first; it != range.second; ++it)
                    if (!required[it->index])
                    {
                        keep[it->index] = 0;
                        ++repair.dropped_interior;
                    }
                continue;
            }
            if (range.first == range.second && options.add_interfaces)
            {
                // outward from the tet of the smaller ref, whose ref it takes
                added.push_back(ref_a < ref_b ? face : face_vertices(mesh, second));
                added_refs.push_back(std::min(ref_a, ref_b));
                ++repair.added_interface;
            }
        }
        else if (range.first == range.second)
        {
            added.push_back(face);
            added_refs.push_back(tet_ref(first.tet));
            ++repair.added_boundary;
            continue;
        }
        else if (Triangle& tri = mesh.triangles[range.first->index]; !same_orientation(tri, face))
        {
            std::swap(tri[1], tri[2]);
            ++repair.turned_outward;
        }
        for (auto it = std::next(range.first); it < range.second; ++it)
            if (!required[it->index])
            {
                keep[it->index] = 0;
                ++repair.dropped_duplicates;
            }
    }
    if (!repair.any()) return repair;

    // renumber the kept triangles in their order, the new ones after them
    std::vector<int> old2new(nt, -1);
    int next = 0;
    for (int i = 0; i < nt; ++i)
    {
        if (!keep[i]) continue;
        old2new[i] = next;
        mesh.triangles[next] = mesh.triangles[i];
        mesh.triangle_refs[next] = mesh.triangle_refs[i];
        ++next;
    }
    mesh.triangles.resize(next);
    mesh.triangle_refs.resize(next);
    for (int& i : mesh.required_triangles)
        if (i >= 0 && i < nt) i = old2new[i];  // required triangles are all kept
    mesh.triangles.insert(mesh.triangles.end(), added.begin(), added.end());
    mesh.triangle_refs.insert(mesh.triangle_refs.end(), added_refs.begin(), added_refs.end());
    mesh.classify_vertices();
    return repair;
}

RegionCurves mark_region_curves(TetMesh& mesh)
{
    RegionCurves added;
    std::vector<Edge> uses;
    uses.reserve(3 * mesh.triangles.size());
    for (const Triangle& tri : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            uses.push_back(
                {std::min(tri[k], tri[(k + 1) % 3]), std::max(tri[k], tri[(k + 1) % 3])});
    std::sort(uses.begin(), uses.end());
    std::vector<Edge> junctions;
    for (std::size_t i = 0; i < uses.size();)
    {
        std::size_t j = i;
        while (j < uses.size() && uses[j] == uses[i]) ++j;
        if (j - i >= 3) junctions.push_back(uses[i]);
        i = j;
    }
    if (junctions.empty()) return added;

    // listed already, as an edge or a ridge?
    std::vector<std::pair<Edge, int>> listed;
    for (std::size_t i = 0; i < mesh.edges.size(); ++i)
        listed.push_back({{std::min(mesh.edges[i][0], mesh.edges[i][1]),
                           std::max(mesh.edges[i][0], mesh.edges[i][1])},
                          static_cast<int>(i)});
    std::sort(listed.begin(), listed.end());
    std::vector<char> is_ridge(mesh.edges.size(), 0);
    for (int e : mesh.ridges)
        if (e >= 0 && e < static_cast<int>(is_ridge.size())) is_ridge[e] = 1;
    if (mesh.edge_refs.size() != mesh.edges.size()) mesh.edge_refs.resize(mesh.edges.size(), 0);
    std::vector<int> curves_at(mesh.num_vertices(), 0);
    for (const Edge& e : junctions)
    {
        ++curves_at[e[0]];
        ++curves_at[e[1]];
        auto it = std::lower_bound(listed.begin(), listed.end(), std::make_pair(e, -1));
        if (it != listed.end() && it->first == e)
        {
            if (is_ridge[it->second]) continue;
            mesh.ridges.push_back(it->second);
        }
        else
        {
            mesh.edges.push_back(e);
            mesh.edge_refs.push_back(0);
            mesh.ridges.push_back(static_cast<int>(mesh.edges.size()) - 1);
        }
        ++added.ridges;
    }
    std::vector<int> corners = mesh.corners;
    std::sort(corners.begin(), corners.end());
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (curves_at[v] >= 3 && !std::binary_search(corners.begin(), corners.end(), v))
        {
            mesh.corners.push_back(v);
            ++added.corners;
        }
    if (added.ridges + added.corners > 0) mesh.classify_vertices();
    return added;
}

std::vector<std::string> prepare_tet_input(TetMesh& mesh, const std::string& source, bool strict)
{
    std::vector<std::string> lines;
    if (!strict) lines = repair_boundary(mesh).lines();
    if (const RegionCurves curves = mark_region_curves(mesh); curves.ridges > 0)
        lines.push_back(std::to_string(curves.ridges) +
                        " ridge edges where three or more regions meet (" +
                        std::to_string(curves.corners) + " corners)");
    if (const auto violations = check_mesh(mesh); !violations.empty())
        throw InputError(source + ": the input mesh is not valid:\n" +
                         format_violations(violations));
    return lines;
}

}  // namespace hdimesh::volume
