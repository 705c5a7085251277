#include "volume/fill/cavity.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <sstream>
#include <utility>

#include "volume/fill/advancing_front.h"
#include "volume/fill/detail/cavity_stages.h"
#include "volume/fill/detail/kernel.h"
#include "volume/mesh/predicates.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

const char* to_string(FillStage stage)
{
    switch (stage)
    {
        case FillStage::VertexFan: return "vertex fan";
        case FillStage::KernelFan: return "kernel fan";
        case FillStage::Exhaustive: return "exhaustive";
        case FillStage::AdvancingFront: return "advancing front";
        case FillStage::Failed: return "failed";
    }
    return "?";
}

namespace
{

using Key = std::array<int, 3>;

/// Empty when the faces are a closed, consistently oriented surface (every directed edge once,
/// its reverse once); else why not.
std::string closedness_defect(const std::vector<Triangle>& faces)
{
    if (faces.size() < 4) return "fewer than 4 faces";
    std::vector<std::pair<int, int>> directed;
    directed.reserve(3 * faces.size());
    for (const auto& f : faces)
        for (int k = 0; k < 3; ++k)
        {
            if (f[k] == f[(k + 1) % 3]) return "a face repeats a vertex";
            directed.emplace_back(f[k], f[(k + 1) % 3]);
        }
    std::sort(directed.begin(), directed.end());
    for (std::size_t i = 0; i + 1 < directed.size(); ++i)
        if (directed[i] == directed[i + 1])
        {
            std::ostringstream out;
            out << "edge " << directed[i].first << "-" << directed[i].second
                << " is used twice in the same direction (non-manifold or inconsistent)";
            return out.str();
        }
    for (const auto& e : directed)
        if (!std::binary_search(directed.begin(), directed.end(),
                                std::make_pair(e.second, e.first)))
        {
            std::ostringstream out;
            out << "edge " << e.first << "-" << e.second << " has no opposite face (open)";
            return out.str();
        }
    return {};
}

std::vector<int> cavity_vertices(const std::vector<Triangle>& faces)
{
    std::vector<int> v;
    v.reserve(faces.size() / 2 + 3);
    for (const auto& f : faces) v.insert(v.end(), f.begin(), f.end());
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
}

const Vec3& point_of(const std::vector<Vec3>& points, const std::vector<Vec3>& extra, int id)
{
    const int n = static_cast<int>(points.size());
    return id < n ? points[id] : extra[id - n];
}

double worst_quality_of(const std::vector<Vec3>& points, const std::vector<Vec3>& extra,
                        const std::vector<TetVertices>& tets)
{
    double worst = std::numeric_limits<double>::infinity();
    for (const auto& t : tets)
        worst = std::min(worst,
                         tet_quality(point_of(points, extra, t[0]), point_of(points, extra, t[1]),
                                     point_of(points, extra, t[2]), point_of(points, extra, t[3])));
    return worst;
}

/// Keeps the better of two fills (higher worst Qe; the earlier stage on a tie).
void keep_better(CavityFill& best, CavityFill& candidate)
{
    if (!candidate.filled) return;
    if (!best.filled || candidate.worst_quality > best.worst_quality) best = std::move(candidate);
}

}  // namespace

namespace detail
{

bool fill_by_vertex_fan(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                        CavityFill& fill)
{
    // A cone whose tets are all positive tiles the region: the tets' signed count at a point is
    // the surface's winding number there, 1 inside and 0 outside.
    const std::vector<int> vertices = cavity_vertices(faces);
    int best_apex = -1;
    double best_worst = -std::numeric_limits<double>::infinity();
    for (int v : vertices)
    {
        bool sees_all = true;
        for (const auto& f : faces)
        {
            if (f[0] == v || f[1] == v || f[2] == v) continue;
            if (orient3d(points[f[0]], points[f[1]], points[f[2]], points[v]) >= 0)
            {
                sees_all = false;
                break;
            }
        }
        if (!sees_all) continue;
        double worst = std::numeric_limits<double>::infinity();
        for (const auto& f : faces)
        {
            if (f[0] == v || f[1] == v || f[2] == v) continue;
            worst =
                std::min(worst, tet_quality(points[f[0]], points[f[2]], points[f[1]], points[v]));
            if (worst <= best_worst) break;  // cannot beat the apex found
        }
        if (worst > best_worst)
        {
            best_worst = worst;
            best_apex = v;
        }
    }
    if (best_apex < 0) return false;
    fill.tets.clear();
    fill.new_points.clear();
    for (const auto& f : faces)
        if (f[0] != best_apex && f[1] != best_apex && f[2] != best_apex)
            fill.tets.push_back(detail::cone_tet(f, best_apex));
    fill.worst_quality = best_worst;
    fill.stage = FillStage::VertexFan;
    fill.filled = true;
    return true;
}

}  // namespace detail

CavityFill fill_cavity(const TetMesh& mesh, const std::vector<Triangle>& faces,
                       const SizeField* field, const CavityOptions& options)
{
    CavityFill fill;
    fill.first_new_vertex = mesh.num_vertices();
    fill.faces = faces;
    for (const auto& f : faces)
        for (int v : f)
            if (v < 0 || v >= mesh.num_vertices())
            {
                fill.failure = "a face names vertex " + std::to_string(v) + ", not in the mesh";
                return fill;
            }
    if (std::string defect = closedness_defect(faces); !defect.empty())
    {
        fill.failure = "the faces are not a closed oriented surface: " + defect;
        return fill;
    }

    const bool small = static_cast<int>(faces.size()) <= options.max_fan_faces;
    CavityFill best;
    best.first_new_vertex = fill.first_new_vertex;
    if (small)
    {
        CavityFill stages;
        if (detail::fill_small_cavity(mesh.points, faces, options, stages))
        {
            if (stages.worst_quality >= options.accept_quality)
            {
                stages.first_new_vertex = fill.first_new_vertex;
                stages.faces = faces;
                return stages;
            }
            keep_better(best, stages);
        }
    }

    CavityFill front;
    std::string failure;
    if (advance_front(mesh.points, faces, field, options.front, front.tets, front.new_points,
                      failure))
    {
        front.filled = true;
        front.stage = FillStage::AdvancingFront;
        front.worst_quality = worst_quality_of(mesh.points, front.new_points, front.tets);
        keep_better(best, front);
    }
    if (!best.filled)
    {
        fill.failure = small ? "no stage filled it (advancing front: " + failure + ")" : failure;
        return fill;
    }
    best.first_new_vertex = fill.first_new_vertex;
    best.faces = faces;
    return best;
}

namespace
{

/// The outward boundary faces of a set of live tets (flagged in `in_set`), and whether each
/// one may be crossed to grow the set.
struct CavityHull
{
    std::vector<Triangle> faces;
    std::vector<int> outside_tets;  ///< per face: the tet across it that growing would take, or -1
};

CavityHull cavity_hull(const TetMesh& mesh, const std::vector<int>& tets,
                       const std::vector<char>& in_set, const MeshConstraints& constraints, int ref)
{
    CavityHull hull;
    for (int t : tets)
        for (int f = 0; f < 4; ++f)
        {
            const int n = mesh.neighbors[t][f];
            if (n != kNoTet && in_set[n]) continue;
            const auto& lf = tet::kFaceVertices[f];
            hull.faces.push_back({mesh.tets[t][lf[0]], mesh.tets[t][lf[1]], mesh.tets[t][lf[2]]});
            const bool crossable = n != kNoTet && mesh.tet_refs[n] == ref &&
                                   !constraints.is_constrained_face(mesh, t, f) &&
                                   constraints.is_removable_tet(n);
            hull.outside_tets.push_back(crossable ? n : -1);
        }
    return hull;
}

/// Rounds of taking the tets at pinched hull edges, at most.
constexpr int kMaxPinchRepairs = 8;

/// The crossable tets outside the hull faces that hold a non-manifold hull edge (an edge used
/// more than once in the same direction), sorted.
std::vector<int> tets_across_pinched_edges(const CavityHull& hull)
{
    struct DirectedEdge
    {
        int from, to, face;
        bool operator<(const DirectedEdge& o) const
        {
            return from < o.from ||
                   (from == o.from && (to < o.to || (to == o.to && face < o.face)));
        }
    };
    std::vector<DirectedEdge> edges;
    edges.reserve(3 * hull.faces.size());
    for (int f = 0; f < static_cast<int>(hull.faces.size()); ++f)
        for (int k = 0; k < 3; ++k)
        {
            const int a = hull.faces[f][k], b = hull.faces[f][(k + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), f});
        }
    std::sort(edges.begin(), edges.end());
    std::vector<int> tets;
    for (std::size_t i = 0; i < edges.size();)
    {
        std::size_t j = i;
        while (j < edges.size() && edges[j].from == edges[i].from && edges[j].to == edges[i].to)
            ++j;
        if (j - i > 2)
            for (std::size_t k = i; k < j; ++k)
                if (hull.outside_tets[edges[k].face] >= 0)
                    tets.push_back(hull.outside_tets[edges[k].face]);
        i = j;
    }
    std::sort(tets.begin(), tets.end());
    tets.erase(std::unique(tets.begin(), tets.end()), tets.end());
    return tets;
}

}  // namespace

CavityFill refill_tets(const TetMesh& mesh, const std::vector<int>& tets, const SizeField* field,
                       const CavityOptions& options, const MeshConstraints* constraints)
{
    CavityFill failed;
    failed.first_new_vertex = mesh.num_vertices();
    if (!mesh.has_adjacency())
    {
        failed.failure = "refill_tets needs the mesh's adjacency";
        return failed;
    }
    if (tets.empty())
    {
        failed.failure = "no tets to refill";
        return failed;
    }
    for (int t : tets)
        if (t < 0 || t >= mesh.num_tet_slots() || mesh.is_dead(t))
        {
            failed.failure = "tet " + std::to_string(t) + " is not a live tet";
            return failed;
        }
    const int ref = mesh.tet_refs[tets.front()];
    for (int t : tets)
        if (mesh.tet_refs[t] != ref)
        {
            failed.failure = "the tets have different refs (" + std::to_string(ref) + ", " +
                             std::to_string(mesh.tet_refs[t]) + ")";
            return failed;
        }

    MeshConstraints local_constraints;
    if (constraints == nullptr)
    {
        local_constraints = MeshConstraints(mesh);
        constraints = &local_constraints;
    }

    std::vector<int> set = tets;
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    std::vector<char> in_set(mesh.tets.size(), 0);
    for (int t : set) in_set[t] = 1;

    std::string first_failure;
    for (int layer = 0;; ++layer)
    {
        CavityHull hull = cavity_hull(mesh, set, in_set, *constraints, ref);
        // a random union of tets may pinch at an edge (four hull faces on it): take the tets
        // across those faces until every hull edge is manifold, or nothing more may be taken
        for (int repair = 0; repair < kMaxPinchRepairs; ++repair)
        {
            const std::vector<int> pinch = tets_across_pinched_edges(hull);
            std::vector<int> taken;
            for (int n : pinch)
                if (!in_set[n])
                {
                    in_set[n] = 1;
                    taken.push_back(n);
                }
            if (taken.empty()) break;
            set.insert(set.end(), taken.begin(), taken.end());
            std::sort(set.begin(), set.end());
            hull = cavity_hull(mesh, set, in_set, *constraints, ref);
        }
        CavityFill fill = fill_cavity(mesh, hull.faces, field, options);
        if (fill.filled)
        {
            fill.removed_tets = set;
            fill.ref = ref;
            fill.grown_layers = layer;
            return fill;
        }
        if (first_failure.empty()) first_failure = fill.failure;
        if (layer >= options.max_grow_layers) break;
        // one layer more: every tet across a crossable hull face, in id order
        std::vector<int> grown;
        for (int n : hull.outside_tets)
            if (n >= 0 && !in_set[n])
            {
                in_set[n] = 1;
                grown.push_back(n);
            }
        if (grown.empty()) break;
        set.insert(set.end(), grown.begin(), grown.end());
        std::sort(set.begin(), set.end());
    }
    failed.failure = first_failure;
    return failed;
}

std::vector<int> commit_cavity(TetMesh& mesh, const CavityFill& fill)
{
    assert(fill.filled);
    assert(mesh.num_vertices() == fill.first_new_vertex);
    assert(fill.tet_refs.empty() || fill.tet_refs.size() == fill.tets.size());
    for (const Vec3& p : fill.new_points) mesh.add_vertex(p, 0, VertexClass::Interior);

    // a fill into an empty mesh (a whole volume) has nothing to link to: the caller links the
    // whole mesh with build_adjacency once every region is in
    const bool linked = mesh.has_adjacency() && !mesh.tets.empty();
    // the links to mend: each hull face of the removed tets, with the tet outside it
    struct HullLink
    {
        Key key;
        int outside_tet, outside_face;
        bool operator<(const HullLink& o) const { return key < o.key; }
    };
    std::vector<HullLink> hull;
    // (a sorted list, not a flag per tet slot: a cavity is small, the mesh is not)
    std::vector<int> slots = fill.removed_tets;
    std::sort(slots.begin(), slots.end());
    if (linked)
        for (int t : fill.removed_tets)
            for (int f = 0; f < 4; ++f)
            {
                const int n = mesh.neighbors[t][f];
                if (n == kNoTet || std::binary_search(slots.begin(), slots.end(), n)) continue;
                int back = -1;
                for (int g = 0; g < 4; ++g)
                    if (mesh.neighbors[n][g] == t) back = g;
                const auto& lf = tet::kFaceVertices[f];
                hull.push_back(
                    {sorted_triple({mesh.tets[t][lf[0]], mesh.tets[t][lf[1]], mesh.tets[t][lf[2]]}),
                     n, back});
            }
    std::sort(hull.begin(), hull.end());

    for (int t : slots) mesh.kill_tet(t);
    std::vector<int> ids;
    ids.reserve(fill.tets.size());
    for (std::size_t k = 0; k < fill.tets.size(); ++k)
    {
        const int ref = fill.tet_refs.empty() ? fill.ref : fill.tet_refs[k];
        if (k < slots.size())
        {
            const int id = slots[k];
            mesh.tets[id] = fill.tets[k];
            mesh.tet_refs[id] = ref;
            ids.push_back(id);
        }
        else
        {
            ids.push_back(mesh.add_tet(fill.tets[k], ref));
        }
    }
    if (!linked) return ids;
    mesh.neighbors.resize(mesh.tets.size());
    for (std::size_t k = fill.tets.size(); k < slots.size(); ++k)
        mesh.neighbors[slots[k]] = {kNoTet, kNoTet, kNoTet, kNoTet};

    // A hull face no new tet covers is boundary now (a coupled change exposed it as a surface
    // triangle): its outside tet must not keep the link to the removed slot.
    for (const HullLink& h : hull) mesh.neighbors[h.outside_tet][h.outside_face] = kNoTet;
    // pair the new faces among themselves (sorted keys), then the unpaired ones with the hull
    struct FaceRecord
    {
        Key key;
        int tet, face;
        bool operator<(const FaceRecord& o) const
        {
            return key < o.key ||
                   (key == o.key && (tet < o.tet || (tet == o.tet && face < o.face)));
        }
    };
    std::vector<FaceRecord> records;
    records.reserve(4 * ids.size());
    for (int id : ids)
        for (int f = 0; f < 4; ++f)
        {
            const auto& lf = tet::kFaceVertices[f];
            const auto& tv = mesh.tets[id];
            records.push_back({sorted_triple({tv[lf[0]], tv[lf[1]], tv[lf[2]]}), id, f});
        }
    std::sort(records.begin(), records.end());
    for (std::size_t i = 0; i < records.size();)
    {
        if (i + 1 < records.size() && records[i].key == records[i + 1].key)
        {
            mesh.neighbors[records[i].tet][records[i].face] = records[i + 1].tet;
            mesh.neighbors[records[i + 1].tet][records[i + 1].face] = records[i].tet;
            i += 2;
            continue;
        }
        const auto it = std::lower_bound(hull.begin(), hull.end(), HullLink{records[i].key, 0, 0});
        if (it != hull.end() && it->key == records[i].key)
        {
            mesh.neighbors[records[i].tet][records[i].face] = it->outside_tet;
            mesh.neighbors[it->outside_tet][it->outside_face] = records[i].tet;
        }
        else
        {
            mesh.neighbors[records[i].tet][records[i].face] = kNoTet;
        }
        ++i;
    }
    return ids;
}

void FillStatistics::add(const CavityFill& fill)
{
    ++by_stage[static_cast<int>(fill.filled ? fill.stage : FillStage::Failed)];
    if (fill.filled && fill.grown_layers > 0) ++grown;
}

std::string FillStatistics::format() const
{
    std::ostringstream out;
    for (int s = 0; s < kNumFillStages; ++s)
    {
        if (s > 0) out << ", ";
        out << to_string(static_cast<FillStage>(s)) << " " << by_stage[s];
    }
    out << "; grown " << grown;
    return out.str();
}

}  // namespace hdimesh::volume
