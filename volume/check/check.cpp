#include "volume/check/check.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "volume/mesh/blocks.h"
#include "volume/mesh/boundary.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace
{

std::string ids(const Triangle& t)
{
    std::ostringstream out;
    out << "(" << t[0] << ", " << t[1] << ", " << t[2] << ")";
    return out.str();
}

/// Parity (0 even, 1 odd) of the permutation that sorts the three ids: two listings of the
/// same face have opposite orientations exactly when their parities differ.
int parity(const Triangle& t) { return ((t[0] > t[1]) + (t[0] > t[2]) + (t[1] > t[2])) % 2; }

class Checker
{
public:
    Checker(const TetMesh& mesh, const CheckOptions& options) : mesh_(mesh), options_(options) {}

    std::vector<MeshViolation> run()
    {
        check_array_sizes();
        check_coordinates();
        check_ids();
        check_volumes();
        const FaceGroups groups = group_tet_faces(mesh_);
        check_shared_faces(groups);
        if (!mesh_.neighbors.empty() && mesh_.has_adjacency()) check_adjacency(groups);
        check_declared_triangles(groups);
        check_boundary_manifold();
        check_enclosed_volume(groups);
        check_vertex_use();
        return std::move(violations_);
    }

private:
    void add(const char* kind, int element, const std::string& message)
    {
        violations_.push_back({kind, element, message});
    }

    void check_array_sizes()
    {
        auto expect = [&](std::size_t actual, std::size_t expected, const char* what) {
            if (actual == expected) return;
            add("array_size", -1,
                std::string(what) + " has " + std::to_string(actual) + " entries, expected " +
                    std::to_string(expected));
        };
        const std::size_t nv = mesh_.points.size(), nt = mesh_.tets.size();
        expect(mesh_.vertex_refs.size(), nv, "vertex_refs");
        expect(mesh_.vertex_classes.size(), nv, "vertex_classes");
        expect(mesh_.tet_refs.size(), nt, "tet_refs");
        expect(mesh_.triangle_refs.size(), mesh_.triangles.size(), "triangle_refs");
        expect(mesh_.edge_refs.size(), mesh_.edges.size(), "edge_refs");
        if (!mesh_.neighbors.empty()) expect(mesh_.neighbors.size(), nt, "neighbors");
    }

    void check_coordinates()
    {
        for (int v = 0; v < mesh_.num_vertices(); ++v)
            if (!mesh_.points[v].allFinite())
                add("nan_coordinate", v,
                    "vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
    }

    void check_ids()
    {
        const int nv = mesh_.num_vertices();
        auto bad = [nv](int v) { return v < 0 || v >= nv; };
        for (int t = 0; t < mesh_.num_tet_slots(); ++t)
        {
            if (mesh_.is_dead(t)) continue;
            const auto& tv = mesh_.tets[t];
            if (std::any_of(tv.begin(), tv.end(), bad))
            {
                usable_ = false;
                add("tet_vertex_out_of_range", t,
                    "tet " + std::to_string(t) + " has a vertex id outside [0, " +
                        std::to_string(nv) + ")");
            }
        }
        for (std::size_t i = 0; i < mesh_.triangles.size(); ++i)
        {
            const auto& tri = mesh_.triangles[i];
            if (std::any_of(tri.begin(), tri.end(), bad))
                add("triangle_vertex_out_of_range", static_cast<int>(i),
                    "triangle " + std::to_string(i) + " " + ids(tri) +
                        " has a vertex id outside [0, " + std::to_string(nv) + ")");
        }
        for (std::size_t i = 0; i < mesh_.edges.size(); ++i)
            if (bad(mesh_.edges[i][0]) || bad(mesh_.edges[i][1]))
                add("edge_vertex_out_of_range", static_cast<int>(i),
                    "edge " + std::to_string(i) + " has a vertex id outside [0, " +
                        std::to_string(nv) + ")");
        auto check_indices = [&](const std::vector<int>& list, int size, const char* what) {
            for (int i : list)
                if (i < 0 || i >= size)
                    add("entity_index_out_of_range", -1,
                        std::string(what) + " lists " + std::to_string(i) + ", outside [0, " +
                            std::to_string(size) + ")");
        };
        const int ne = static_cast<int>(mesh_.edges.size());
        check_indices(mesh_.ridges, ne, "ridges");
        check_indices(mesh_.required_edges, ne, "required_edges");
        check_indices(mesh_.corners, nv, "corners");
        check_indices(mesh_.required_vertices, nv, "required_vertices");
        check_indices(mesh_.required_triangles, static_cast<int>(mesh_.triangles.size()),
                      "required_triangles");
        check_indices(mesh_.required_tets, mesh_.num_tet_slots(), "required_tets");
    }

    bool usable_tet(int t) const
    {
        if (mesh_.is_dead(t)) return false;
        for (int v : mesh_.tets[t])
            if (v < 0 || v >= mesh_.num_vertices()) return false;
        return true;
    }

    bool usable_triangle(const Triangle& tri) const
    {
        for (int v : tri)
            if (v < 0 || v >= mesh_.num_vertices()) return false;
        return true;
    }

    void check_volumes()
    {
        for (int t = 0; t < mesh_.num_tet_slots(); ++t)
        {
            if (!usable_tet(t)) continue;
            const double volume = mesh_.volume(t);
            tet_volume_sum_ += volume;
            if (!(volume > 0.0))
            {
                std::ostringstream out;
                out << "tet " << t << " (" << mesh_.tets[t][0] << ", " << mesh_.tets[t][1] << ", "
                    << mesh_.tets[t][2] << ", " << mesh_.tets[t][3] << ") has volume " << volume
                    << " <= 0";
                add("non_positive_volume", t, out.str());
            }
        }
    }

    void check_shared_faces(const FaceGroups& groups)
    {
        for (int k = 0; k < groups.num_faces(); ++k)
        {
            const int count = groups.start[k + 1] - groups.start[k];
            const TetFace& first = groups.uses[groups.start[k]];
            if (count > 2)
            {
                add("face_shared_by_more_than_two", first.tet,
                    "face " + ids(face_vertices(mesh_, first)) + " is used by " +
                        std::to_string(count) + " tets (first: tet " + std::to_string(first.tet) +
                        ")");
            }
            else if (count == 2)
            {
                const TetFace& second = groups.uses[groups.start[k] + 1];
                if (parity(face_vertices(mesh_, first)) == parity(face_vertices(mesh_, second)))
                    add("face_same_orientation", second.tet,
                        "tets " + std::to_string(first.tet) + " and " + std::to_string(second.tet) +
                            " list face " + ids(face_vertices(mesh_, first)) +
                            " the same way: they lie on the same side of it");
            }
        }
    }

    void check_adjacency(const FaceGroups& groups)
    {
        const int nt = mesh_.num_tet_slots();
        // stale: every face's stored link against the recomputed one
        for (int k = 0; k < groups.num_faces(); ++k)
        {
            const int count = groups.start[k + 1] - groups.start[k];
            for (int i = 0; i < count; ++i)
            {
                const TetFace& use = groups.uses[groups.start[k] + i];
                const int expected = count == 2 ? groups.uses[groups.start[k] + 1 - i].tet : kNoTet;
                const int stored = mesh_.neighbors[use.tet][use.local_face];
                if (stored != expected)
                    add("adjacency_stale", use.tet,
                        "tet " + std::to_string(use.tet) + " face " +
                            std::to_string(use.local_face) + " links to " + std::to_string(stored) +
                            ", the faces say " + std::to_string(expected));
            }
        }
        // asymmetric: a link the neighbour does not return
        for (int t = 0; t < nt; ++t)
        {
            if (!usable_tet(t)) continue;
            for (int f = 0; f < 4; ++f)
            {
                const int n = mesh_.neighbors[t][f];
                if (n == kNoTet) continue;
                if (n < 0 || n >= nt || mesh_.is_dead(n))
                {
                    add("adjacency_asymmetric", t,
                        "tet " + std::to_string(t) + " face " + std::to_string(f) + " links to " +
                            std::to_string(n) + ", which is not a live tet");
                    continue;
                }
                const auto& back = mesh_.neighbors[n];
                if (std::find(back.begin(), back.end(), t) == back.end())
                    add("adjacency_asymmetric", t,
                        "tet " + std::to_string(t) + " face " + std::to_string(f) +
                            " links to tet " + std::to_string(n) + ", which does not link back");
            }
        }
    }

    /// mesh.triangles against the tets' faces: every boundary face listed once and outward;
    /// extra triangles only on interfaces between different refs.
    void check_declared_triangles(const FaceGroups& groups)
    {
        const std::vector<ListedTriangle> declared = listed_triangles(mesh_);
        for (std::size_t i = 1; i < declared.size(); ++i)
            if (declared[i].key == declared[i - 1].key)
                add("duplicate_triangle", declared[i].index,
                    "triangle " + std::to_string(declared[i].index) + " repeats triangle " +
                        std::to_string(declared[i - 1].index) + " " + ids(declared[i].key));

        boundary_triangle_.assign(mesh_.triangles.size(), 1);
        std::vector<char> matched(mesh_.triangles.size(), 0);
        for (int k = 0; k < groups.num_faces(); ++k)
        {
            const int count = groups.start[k + 1] - groups.start[k];
            const TetFace& first = groups.uses[groups.start[k]];
            const Triangle face = face_vertices(mesh_, first);
            const Triangle key = sorted_triple(face);
            const auto range = listings(declared, key);
            if (count == 1)
            {
                if (range.first == range.second)
                    add("missing_boundary_triangle", first.tet,
                        "boundary face " + ids(face) + " of tet " + std::to_string(first.tet) +
                            " is not in the triangles");
                for (auto it = range.first; it != range.second; ++it)
                {
                    matched[it->index] = 1;
                    if (parity(mesh_.triangles[it->index]) != parity(face))
                        add("boundary_triangle_reversed", it->index,
                            "triangle " + std::to_string(it->index) + " " +
                                ids(mesh_.triangles[it->index]) + " points into tet " +
                                std::to_string(first.tet));
                }
            }
            else
            {
                // a face inside the volume: a triangle there is an interface, not boundary
                const TetFace& second = groups.uses[groups.start[k] + 1];
                const bool interface = mesh_.tet_refs.size() == mesh_.tets.size() &&
                                       mesh_.tet_refs[first.tet] != mesh_.tet_refs[second.tet];
                for (auto it = range.first; it != range.second; ++it)
                {
                    matched[it->index] = 1;
                    boundary_triangle_[it->index] = 0;
                    if (!interface && !options_.allow_interior_triangles)
                        add("interior_triangle", it->index,
                            "triangle " + std::to_string(it->index) + " " + ids(key) +
                                " lies between tets " + std::to_string(first.tet) + " and " +
                                std::to_string(second.tet) + " of the same ref");
                }
            }
        }
        // only meaningful when the tets could all be read
        if (!usable_) return;
        for (const ListedTriangle& d : declared)
            if (!matched[d.index])
                add("triangle_not_a_tet_face", d.index,
                    "triangle " + std::to_string(d.index) + " " + ids(mesh_.triangles[d.index]) +
                        " is not a face of any tet");
    }

    /// Every boundary edge in exactly two boundary triangles with opposite directions, and every
    /// boundary vertex's link a single cycle.
    void check_boundary_manifold()
    {
        struct DirectedEdge
        {
            int low, high;
            bool forward;  // listed low -> high
            int triangle;
            bool operator<(const DirectedEdge& o) const
            {
                return low != o.low     ? low < o.low
                       : high != o.high ? high < o.high
                                        : triangle < o.triangle;
            }
        };
        std::vector<DirectedEdge> edges;
        std::vector<int> boundary;  // indices of the triangles taking part
        // a frozen cut between pieces (blocks, ranks) closes the piece's boundary, but two
        // parts of one piece may touch there at an edge or a vertex
        std::vector<char> on_cut(mesh_.num_vertices(), 0);
        for (std::size_t i = 0; i < mesh_.triangles.size(); ++i)
        {
            const auto& tri = mesh_.triangles[i];
            if (!boundary_triangle_[i] || !usable_triangle(tri)) continue;
            if (is_cut(static_cast<int>(i)))
                for (int v : tri) on_cut[v] = 1;
            boundary.push_back(static_cast<int>(i));
            for (int k = 0; k < 3; ++k)
            {
                const int a = tri[k], b = tri[(k + 1) % 3];
                edges.push_back({std::min(a, b), std::max(a, b), a < b, static_cast<int>(i)});
            }
        }
        std::sort(edges.begin(), edges.end());
        for (std::size_t i = 0; i < edges.size();)
        {
            std::size_t j = i + 1;
            while (j < edges.size() && edges[j].low == edges[i].low &&
                   edges[j].high == edges[i].high)
                ++j;
            const std::string where = "boundary edge (" + std::to_string(edges[i].low) + ", " +
                                      std::to_string(edges[i].high) + ")";
            // closed by a cut, where two parts of one piece may meet: not the surface's edge
            const bool at_cut =
                std::any_of(edges.begin() + i, edges.begin() + j,
                            [&](const DirectedEdge& e) { return is_cut(e.triangle); });
            if (j - i == 1)
            {
                if (options_.require_closed_boundary)
                    add("open_boundary_edge", edges[i].triangle,
                        where + " is in only one boundary triangle (" +
                            std::to_string(edges[i].triangle) + ")");
            }
            else if (!at_cut && j - i > 2)
            {
                add("nonmanifold_boundary_edge", edges[i].triangle,
                    where + " is in " + std::to_string(j - i) + " boundary triangles");
            }
            else if (!at_cut && edges[i].forward == edges[i + 1].forward)
            {
                add("boundary_edge_same_direction", edges[i + 1].triangle,
                    where + ": triangles " + std::to_string(edges[i].triangle) + " and " +
                        std::to_string(edges[i + 1].triangle) + " are oriented inconsistently");
            }
            i = j;
        }
        check_vertex_links(boundary, on_cut);
    }

    bool is_cut(int triangle) const
    {
        return static_cast<std::size_t>(triangle) < mesh_.triangle_refs.size() &&
               is_cut_ref(mesh_.triangle_refs[triangle]);
    }

    /// The link of a vertex v is the cycle of edges opposite v in its triangles: (a, b, c) at a
    /// gives b -> c. Several cycles mean the surface is pinched at v. Links broken at an edge
    /// (already reported) are skipped.
    void check_vertex_links(const std::vector<int>& boundary, const std::vector<char>& skip)
    {
        const int nv = mesh_.num_vertices();
        std::vector<int> start(nv + 1, 0);
        for (int i : boundary)
            for (int v : mesh_.triangles[i]) ++start[v + 1];
        for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
        std::vector<std::array<int, 2>> link(start[nv]);
        std::vector<int> fill(start.begin(), start.end() - 1);
        for (int i : boundary)
        {
            const auto& tri = mesh_.triangles[i];
            for (int k = 0; k < 3; ++k) link[fill[tri[k]]++] = {tri[(k + 1) % 3], tri[(k + 2) % 3]};
        }
        for (int v = 0; v < nv; ++v)
        {
            const int n = start[v + 1] - start[v];
            if (n == 0 || skip[v]) continue;
            auto first = link.begin() + start[v], last = link.begin() + start[v + 1];
            std::sort(first, last);
            bool well_defined = true;
            for (auto it = first + 1; it < last; ++it) well_defined &= (*it)[0] != (*(it - 1))[0];
            if (!well_defined) continue;
            auto next = [&](int from) -> int {
                auto it = std::lower_bound(first, last, std::array<int, 2>{from, -1});
                return (it != last && (*it)[0] == from) ? (*it)[1] : -1;
            };
            int steps = 0, at = (*first)[0];
            do
            {
                at = next(at);
                ++steps;
            } while (at != -1 && at != (*first)[0] && steps <= n);
            if (at == -1) continue;  // open link: an open boundary edge, reported already
            if (steps != n)
                add("nonmanifold_boundary_vertex", v,
                    "boundary vertex " + std::to_string(v) + " has " + std::to_string(n) +
                        " triangles but its link cycle has " + std::to_string(steps) +
                        ": the surface is pinched");
        }
    }

    void check_enclosed_volume(const FaceGroups& groups)
    {
        std::vector<Triangle> boundary;
        for (int k = 0; k < groups.num_faces(); ++k)
            if (groups.start[k + 1] - groups.start[k] == 1)
                boundary.push_back(face_vertices(mesh_, groups.uses[groups.start[k]]));
        const double enclosed = enclosed_volume(mesh_.points, boundary);
        const double scale = std::max(std::abs(tet_volume_sum_), std::abs(enclosed));
        const double difference = std::abs(tet_volume_sum_ - enclosed);
        if (!(difference <= options_.volume_relative_tolerance * scale))
        {
            std::ostringstream out;
            out.precision(17);
            out << "sum of tet volumes " << tet_volume_sum_
                << " != volume enclosed by the boundary " << enclosed << " (relative difference "
                << (scale > 0 ? difference / scale : difference) << ")";
            add("volume_mismatch", -1, out.str());
        }
    }

    void check_vertex_use()
    {
        if (!options_.report_unused_vertices && !options_.report_coincident_vertices) return;
        std::vector<char> used(mesh_.num_vertices(), 0);
        for (int t = 0; t < mesh_.num_tet_slots(); ++t)
            if (usable_tet(t))
                for (int v : mesh_.tets[t]) used[v] = 1;
        std::vector<int> used_ids;
        for (int v = 0; v < mesh_.num_vertices(); ++v)
        {
            if (used[v])
                used_ids.push_back(v);
            else if (options_.report_unused_vertices)
                add("unused_vertex", v, "vertex " + std::to_string(v) + " is used by no tet");
        }
        if (!options_.report_coincident_vertices) return;
        // lexicographic sort of the points: equal points become neighbours
        auto less = [&](int a, int b) {
            const Vec3 &p = mesh_.points[a], &q = mesh_.points[b];
            if (p.x() != q.x()) return p.x() < q.x();
            if (p.y() != q.y()) return p.y() < q.y();
            if (p.z() != q.z()) return p.z() < q.z();
            return a < b;
        };
        std::sort(used_ids.begin(), used_ids.end(), less);
        for (std::size_t i = 1; i < used_ids.size(); ++i)
        {
            const int a = used_ids[i - 1], b = used_ids[i];
            if (mesh_.points[a] == mesh_.points[b])
                add("coincident_vertices", b,
                    "vertices " + std::to_string(a) + " and " + std::to_string(b) +
                        " are at the same point");
        }
    }

    const TetMesh& mesh_;
    const CheckOptions& options_;
    std::vector<MeshViolation> violations_;
    std::vector<char> boundary_triangle_;  // per mesh.triangles: 0 when on an interior face
    double tet_volume_sum_ = 0.0;
    bool usable_ = true;  // every live tet's ids in range
};

}  // namespace

std::vector<MeshViolation> check_mesh(const TetMesh& mesh, const CheckOptions& options)
{
    return Checker(mesh, options).run();
}

std::string format_violations(const std::vector<MeshViolation>& violations, std::size_t max_lines)
{
    if (violations.empty()) return "no violations\n";
    std::map<std::string, int> per_kind;
    for (const auto& v : violations) ++per_kind[v.kind];
    std::ostringstream out;
    out << violations.size() << (violations.size() == 1 ? " violation:" : " violations:");
    for (const auto& [kind, count] : per_kind) out << " " << kind << " " << count;
    out << "\n";
    for (std::size_t i = 0; i < violations.size() && i < max_lines; ++i)
        out << "  " << violations[i].kind << ": " << violations[i].message << "\n";
    if (violations.size() > max_lines)
        out << "  ... and " << violations.size() - max_lines << " more\n";
    return out.str();
}

}  // namespace hdimesh::volume
