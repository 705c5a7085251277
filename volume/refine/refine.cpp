#include "volume/refine/refine.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstdint>
#include <string>

#include "common/errors.h"
#include "common/stage_timer.h"
#include "volume/mesh/blocks.h"
#include "volume/mesh/tet_tables.h"
#include "volume/refine/detail/child_build.h"
#include "volume/refine/detail/edge_table.h"
#include "volume/refine/refine_patterns.h"

namespace hdimesh::volume
{

namespace
{

/// The face rule with a before b.
int diagonal_start_ordered(const std::vector<Vec3>& points, int corner, int a, int b)
{
    const Vec3& pc = points[corner];
    const Vec3& pa = points[a];
    const Vec3& pb = points[b];
    const Vec3 mca = 0.5 * (pc + pa);
    const Vec3 mcb = 0.5 * (pc + pb);
    const double from_a = std::min(triangle_quality(mca, pa, mcb), triangle_quality(pa, pb, mcb));
    const double from_b = std::min(triangle_quality(mca, pa, pb), triangle_quality(mca, pb, mcb));
    return from_b > from_a + 1e-12 * std::max(from_a, from_b) ? b : a;
}

}  // namespace

int quad_diagonal_start(const std::vector<Vec3>& points, int corner, int a, int b)
{
    if (a > b) std::swap(a, b);  // fixed order: the result is a function of the face alone
    return diagonal_start_ordered(points, corner, a, b);
}

int quad_diagonal_start_by_position(const std::vector<Vec3>& points, int corner, int a, int b)
{
    const Vec3 &pa = points[a], &pb = points[b];
    if (std::lexicographical_compare(pb.data(), pb.data() + 3, pa.data(), pa.data() + 3))
        std::swap(a, b);
    return diagonal_start_ordered(points, corner, a, b);
}

namespace
{

using detail::ChildBuild;
using detail::EdgeTable;
using detail::pattern_builds;
using detail::PatternBuilds;

constexpr int kMaxDeferRounds = 16;  // simulations of a pass, each deferring the stuck tets' edges
constexpr double kRankCutTieBand = 1e-9;  // relative: L/h this near the threshold is a tie

/// Per split mask: the faces with two split edges, their corner and other two local vertices.
struct MaskFaces
{
    int two_split_faces = 0;
    std::array<int, 4> corner{};
    std::array<std::array<int, 2>, 4> others{};  // lower local index first
};

std::array<MaskFaces, 64> make_mask_faces()
{
    std::array<MaskFaces, 64> table{};
    for (int mask = 0; mask < 64; ++mask)
    {
        MaskFaces& info = table[mask];
        info.two_split_faces = faces_with_two_split_edges(mask);
        for (int f = 0; f < 4; ++f)
        {
            if (!((info.two_split_faces >> f) & 1)) continue;
            const auto& fv = tet::kFaceVertices[f];
            for (int k = 0; k < 3; ++k)
            {
                const int c = fv[k], a = fv[(k + 1) % 3], b = fv[(k + 2) % 3];
                if ((mask >> tet::kEdgeOfVertices[a][b]) & 1)
                    continue;  // corner: opposite the unsplit edge
                info.corner[f] = c;
                info.others[f] = {std::min(a, b), std::max(a, b)};
            }
        }
    }
    return table;
}

const std::array<MaskFaces, 64> kMaskFaces = make_mask_faces();

/// A tet with its split edges: vertices, midpoint id (or -1) per local edge, mask.
struct TetSplit
{
    TetVertices v;
    std::array<int, 6> midpoint;
    std::array<int, 6> slot;  // in the edge table, or -1
    int mask = 0;
};

/// What pass 1 decided for a tet: the pattern, and how it is built.
enum class Build : std::uint8_t
{
    Table = 0,            // the pattern's tets (Steiner point at the centroid if it has one)
    ConeCentroid = 1,     // every boundary triangle of the sub-polyhedron coned to the centroid
    ConePointAverage = 2  // ... to the average of the sub-polyhedron's points
};

std::uint16_t encode(int pattern, Build build)
{
    return static_cast<std::uint16_t>(pattern | (static_cast<int>(build) << 8));
}
int pattern_of(std::uint16_t choice) { return choice & 0xff; }
Build build_of(std::uint16_t choice) { return static_cast<Build>(choice >> 8); }

const ChildBuild& child_build(std::uint16_t choice)
{
    const PatternBuilds& b = pattern_builds();
    return build_of(choice) == Build::Table ? b.table[pattern_of(choice)]
                                            : b.cone[pattern_of(choice)];
}

/// Pass state shared by the steps below.
class RefinePass
{
public:
    RefinePass(TetMesh& mesh, const SizeField& field, int first_candidate_vertex,
               bool trust_adjacency, const QuadDiagonalRule* rule = nullptr,
               Workers* workers = nullptr)
        : mesh_(mesh), field_(field), first_candidate_(first_candidate_vertex),
          trust_adjacency_(trust_adjacency), rule_(rule), workers_(workers)
    {
    }

    RefinePassResult run();

private:
    TetSplit collect(const EdgeTable& edges, int t) const
    {
        TetSplit s;
        s.v = mesh_.tets[t];
        for (int e = 0; e < 6; ++e)
            s.slot[e] = edges.find(s.v[tet::kEdgeVertices[e][0]], s.v[tet::kEdgeVertices[e][1]]);
        return resolve(s);
    }

    /// Midpoints and mask from the edge slots.
    TetSplit resolve(TetSplit s) const
    {
        s.mask = 0;
        for (int e = 0; e < 6; ++e)
        {
            s.midpoint[e] = s.slot[e] < 0 ? -1 : midpoint_[s.slot[e]];
            if (s.midpoint[e] >= 0) s.mask |= 1 << e;
        }
        return s;
    }

    int diagonal_start(int corner, int a, int b) const
    {
        if (rule_) return (*rule_)(corner, std::min(a, b), std::max(a, b));
        // a face on a rank's cut: the other rank numbers it apart
        if (on_rank_cut(corner) && on_rank_cut(a) && on_rank_cut(b))
            return quad_diagonal_start_by_position(mesh_.points, corner, a, b);
        return quad_diagonal_start(mesh_.points, corner, a, b);
    }

    int diagonal_bits(const TetSplit& s) const
    {
        const MaskFaces& info = kMaskFaces[s.mask];
        int bits = 0;
        for (int f = 0; f < 4; ++f)
        {
            if (!((info.two_split_faces >> f) & 1)) continue;
            const int a = s.v[info.others[f][0]], b = s.v[info.others[f][1]];
            if (diagonal_start(s.v[info.corner[f]], a, b) == b) bits |= 1 << f;
        }
        return bits;
    }

    /// Local point coordinates: vertices, exact midpoints of the split edges, centroid.
    void local_points(const TetSplit& s, std::array<Vec3, kPatternNumLocalPoints>& p) const
    {
        for (int k = 0; k < 4; ++k) p[k] = mesh_.points[s.v[k]];
        for (int e = 0; e < 6; ++e)
            if ((s.mask >> e) & 1)
                p[pattern_midpoint(e)] =
                    midpoint_position(s.v[tet::kEdgeVertices[e][0]], s.v[tet::kEdgeVertices[e][1]]);
        p[kPatternSteinerPoint] = 0.25 * (p[0] + p[1] + p[2] + p[3]);
    }

    /// Exactly the point add_midpoints() creates (a function of the unordered pair).
    Vec3 midpoint_position(int a, int b) const
    {
        if (a > b) std::swap(a, b);
        return 0.5 * (mesh_.points[a] + mesh_.points[b]);
    }

    static Vec3 point_average(const TetSplit& s, const std::array<Vec3, kPatternNumLocalPoints>& p)
    {
        Vec3 sum = p[0] + p[1] + p[2] + p[3];
        int n = 4;
        for (int e = 0; e < 6; ++e)
            if ((s.mask >> e) & 1) sum += p[pattern_midpoint(e)], ++n;
        return sum / n;
    }

    /// All children of the build positive with the local points p (apex: point 10).
    static bool children_positive(const ChildBuild& build,
                                  const std::array<Vec3, kPatternNumLocalPoints>& p)
    {
        for (const auto& c : build.tets)
            if (!(signed_volume6(p[c[0]], p[c[1]], p[c[2]], p[c[3]]) > 0.0)) return false;
        return true;
    }

    bool on_rank_cut(int v) const { return !on_rank_cut_.empty() && on_rank_cut_[v]; }

    bool is_refined(int t) const { return choice_[t] != unsplit_; }
    /// Slot of child i of refined tet t: the parent's own slot for child 0, then its extra slots.
    int child_slot(int t, int i) const { return i == 0 ? t : extra_start_[ordinal_[t]] + i - 1; }

    /// A tet with no positive children in doubles, and the edge slot of each local edge.
    struct StuckTet
    {
        int tet;
        std::array<int, 6> slots;
    };

    int mark_edges(const EdgeTable& edges);
    std::vector<StuckTet> choose_patterns(const EdgeTable& edges);
    void add_midpoints(const EdgeTable& edges);
    void rebuild_tets();
    void link_children();
    void split_triangles(const EdgeTable& edges);
    void split_feature_edges(const EdgeTable& edges);

    TetMesh& mesh_;
    const SizeField& field_;
    int first_candidate_;
    bool trust_adjacency_;
    const QuadDiagonalRule* rule_;
    Workers* workers_;
    int num_vertices_before_ = 0;

    std::vector<int> midpoint_;          // per edge slot: vertex id, 1 while only marked, or -1
    std::vector<char> touched_;          // per vertex: an end of a split edge
    std::vector<char> on_rank_cut_;      // per vertex: on a rank's cut (empty: none)
    std::vector<std::uint16_t> choice_;  // per tet
    std::uint16_t unsplit_ = 0;
    std::vector<int> refined_;                       // the refined tets, increasing
    std::vector<std::array<int, 6>> refined_slots_;  // per refined tet: edge slot per local edge
    std::vector<int> ordinal_;                       // per tet: its index in refined_, or -1
    std::vector<int> extra_start_;       // per refined tet (ordinal): slot of its child 1
    std::vector<TetVertices> old_rows_;  // per refined tet (ordinal): its neighbours before
    long long num_children_ = 0;
    int num_new_points_ = 0;
    int num_fallbacks_ = 0;
    RefinePassResult result_;
};

/// The edges of tri as {low, high}, appended to out.
void add_triangle_edges(const Triangle& tri, std::vector<Edge>& out)
{
    for (int k = 0; k < 3; ++k)
        out.push_back({std::min(tri[k], tri[(k + 1) % 3]), std::max(tri[k], tri[(k + 1) % 3])});
}

/// The edges a split may not cut: those of required triangles and the required feature edges,
/// each as {low, high}, sorted. A cut between ranks is no user's requirement: its edges are
/// split as any other, and both sides split them alike (blocks.h kRankCutRef; a held one is
/// locked); only the optimizer leaves it.
std::vector<Edge> locked_edges(const TetMesh& mesh)
{
    std::vector<Edge> locked;
    for (int i : mesh.required_triangles)
        if (!is_rank_cut_ref(mesh.triangle_refs[i]) || is_held_cut_ref(mesh.triangle_refs[i]))
            add_triangle_edges(mesh.triangles[i], locked);
    for (int i : mesh.required_edges)
        locked.push_back({std::min(mesh.edges[i][0], mesh.edges[i][1]),
                          std::max(mesh.edges[i][0], mesh.edges[i][1])});
    std::sort(locked.begin(), locked.end());
    return locked;
}

int RefinePass::mark_edges(const EdgeTable& edges)
{
    midpoint_.assign(edges.num_edges(), -1);
    touched_.assign(mesh_.num_vertices(), 0);
    int marked = 0;
    const int nv = mesh_.num_vertices();
    const std::vector<Edge> locked = locked_edges(mesh_);
    // At a vertex of a locked edge the size is no finer than its locked edges' mean length, as
    // Mmg sets it: a tet on a coarse required triangle always has an edge as long as its
    // circumradius, and splitting it would only flatten the tets on the triangle, pass after pass.
    std::vector<double> locked_size;
    if (!locked.empty())
    {
        locked_size.assign(nv, 0.0);
        std::vector<int> count(nv, 0);
        for (const Edge& e : locked)
        {
            const double length = (mesh_.points[e[1]] - mesh_.points[e[0]]).norm();
            for (int v : e) locked_size[v] += length, ++count[v];
        }
        for (int v = 0; v < nv; ++v)
            if (count[v] > 0) locked_size[v] /= count[v];
    }
    // the field's queries in parallel, one flag per edge slot (rows by vertex); the marks are
    // then set serially, as before: touched_[b] belongs to another row
    std::vector<char> too_long(edges.num_edges(), 0);
    parallel_for(workers_, static_cast<std::size_t>(nv), [&](std::size_t first, std::size_t last) {
        for (int a = static_cast<int>(first); a < static_cast<int>(last); ++a)
        {
            const Vec3& pa = mesh_.points[a];
            for (int s = edges.row_begin(a), end = edges.row_end(a); s < end; ++s)
            {
                const int b = edges.upper(s);
                const Vec3& pb = mesh_.points[b];
                EdgeInField edge = measure_edge(field_, pa, pb);
                if (!locked.empty())
                {
                    if (std::binary_search(locked.begin(), locked.end(),
                                           Edge{std::min(a, b), std::max(a, b)}))
                        continue;
                    edge.size = std::max({edge.size, locked_size[a], locked_size[b]});
                }
                // on a rank's cut the two sides' fields may differ in the last bits (each
                // interpolates in its own tets): an edge at the threshold (a lattice) is kept
                if (on_rank_cut(a) && on_rank_cut(b)) edge.size *= 1 + kRankCutTieBand;
                too_long[s] = edge.too_long();
            }
        }
    });
    for (int a = 0; a < nv; ++a)
        for (int s = edges.row_begin(a), end = edges.row_end(a); s < end; ++s)
            if (too_long[s])
            {
                midpoint_[s] = 1;
                touched_[a] = touched_[edges.upper(s)] = 1;
                ++marked;
            }
    return marked;
}

/// Pass 1, a simulation: the pattern of every tet and a positive way to build it. Nothing is
/// changed; returns the edge slots of the tets that cannot be rebuilt positively.
std::vector<RefinePass::StuckTet> RefinePass::choose_patterns(const EdgeTable& edges)
{
    const int nt = mesh_.num_tet_slots();
    const PatternBuilds& builds = pattern_builds();
    unsplit_ = encode(find_refine_pattern(0, 0), Build::Table);
    choice_.assign(nt, unsplit_);
    refined_.clear();
    refined_slots_.clear();
    num_new_points_ = 0;
    num_fallbacks_ = 0;
    std::vector<StuckTet> stuck;
    std::array<Vec3, kPatternNumLocalPoints> p;
    p.fill(Vec3::Zero());
    num_children_ = nt;
    for (int t = 0; t < nt; ++t)
    {
        const auto& v = mesh_.tets[t];
        if (!(touched_[v[0]] | touched_[v[1]] | touched_[v[2]] | touched_[v[3]])) continue;
        const TetSplit s = collect(edges, t);
        if (s.mask == 0) continue;
        const int index = find_refine_pattern(s.mask, diagonal_bits(s));
        local_points(s, p);
        Build build = Build::Table;
        if (!children_positive(builds.table[index], p))
        {
            ++num_fallbacks_;
            const bool centroid_sees_all = children_positive(builds.cone[index], p);
            p[kPatternSteinerPoint] = point_average(s, p);
            if (centroid_sees_all)
                build = Build::ConeCentroid;
            else if (children_positive(builds.cone[index], p))
                build = Build::ConePointAverage;
            else
            {
                stuck.push_back({t, s.slot});
                continue;
            }
        }
        choice_[t] = encode(index, build);
        refined_.push_back(t);
        refined_slots_.push_back(s.slot);
        const ChildBuild& b = child_build(choice_[t]);
        num_children_ += static_cast<long long>(b.tets.size()) - 1;
        num_new_points_ += b.new_point;
    }
    return stuck;
}

void RefinePass::add_midpoints(const EdgeTable& edges)
{
    const int nv = mesh_.num_vertices();
    int marked = 0;
    for (int m : midpoint_) marked += (m >= 0);
    const std::size_t total = static_cast<std::size_t>(nv) + marked + num_new_points_;
    mesh_.points.reserve(total);
    mesh_.vertex_refs.reserve(total);
    mesh_.vertex_classes.reserve(total);
    for (int a = 0; a < nv; ++a)
        for (int s = edges.row_begin(a), end = edges.row_end(a); s < end; ++s)
        {
            if (midpoint_[s] < 0) continue;
            const int b = edges.upper(s);
            const int ref = mesh_.vertex_refs[a] == mesh_.vertex_refs[b] ? mesh_.vertex_refs[a] : 0;
            midpoint_[s] = mesh_.add_vertex(midpoint_position(a, b), ref, VertexClass::Interior);
        }
}

/// Pass 2: child 0 of a refined tet takes its parent's slot, the other children are appended;
/// unrefined tets keep their slot (and their neighbour links, but those to refined tets).
void RefinePass::rebuild_tets()
{
    const int nt = mesh_.num_tet_slots();
    const std::size_t total = static_cast<std::size_t>(num_children_);
    const int first_new_point = mesh_.num_vertices();
    mesh_.points.resize(first_new_point + num_new_points_);
    mesh_.vertex_refs.resize(first_new_point + num_new_points_);
    mesh_.vertex_classes.resize(first_new_point + num_new_points_, VertexClass::Interior);
    int next_point = first_new_point;

    // exact reserve for a big pass; a little slack so the small last passes do not copy all
    const std::size_t capacity = total + total / 16;
    if (mesh_.tets.capacity() < total) mesh_.tets.reserve(capacity);
    if (mesh_.tet_refs.capacity() < total) mesh_.tet_refs.reserve(capacity);
    if (mesh_.neighbors.capacity() < total) mesh_.neighbors.reserve(capacity);
    mesh_.tets.resize(total);
    mesh_.tet_refs.resize(total);
    ordinal_.assign(nt, -1);
    extra_start_.resize(refined_.size());
    old_rows_.resize(refined_.size());
    for (std::size_t r = 0; r < refined_.size(); ++r)
    {
        ordinal_[refined_[r]] = static_cast<int>(r);
        old_rows_[r] = mesh_.neighbors[refined_[r]];
    }
    mesh_.neighbors.resize(total);

    std::vector<int> required_children;
    std::vector<char> required;
    if (!mesh_.required_tets.empty())
    {
        required.assign(nt, 0);
        for (int t : mesh_.required_tets) required[t] = 1;
    }

    std::array<Vec3, kPatternNumLocalPoints> p;
    p.fill(Vec3::Zero());
    std::array<int, kPatternNumLocalPoints> g;
    g.fill(-1);
    int next_slot = nt;
    for (std::size_t r = 0; r < refined_.size(); ++r)
    {
        const int t = refined_[r];
        const std::uint16_t choice = choice_[t];
        TetSplit split;
        split.v = mesh_.tets[t];
        split.slot = refined_slots_[r];
        const TetSplit s = resolve(split);
        const int ref = mesh_.tet_refs[t];
        const ChildBuild& build = child_build(choice);
        for (int k = 0; k < 4; ++k) g[k] = s.v[k];
        for (int e = 0; e < 6; ++e) g[pattern_midpoint(e)] = s.midpoint[e];
        if (build.new_point)
        {
            const int id = next_point++;
            g[kPatternSteinerPoint] = id;
            local_points(s, p);
            const Vec3 position = build_of(choice) == Build::ConePointAverage
                                      ? point_average(s, p)
                                      : p[kPatternSteinerPoint];
            const int vref = mesh_.vertex_refs[s.v[0]];
            bool common = true;
            for (int k = 1; k < 4; ++k) common = common && mesh_.vertex_refs[s.v[k]] == vref;
            mesh_.points[id] = position;
            mesh_.vertex_refs[id] = common ? vref : 0;
            mesh_.vertex_classes[id] = VertexClass::Interior;
            result_.steiner_vertices.push_back(id);
        }
        const int n = static_cast<int>(build.tets.size());
        extra_start_[ordinal_[t]] = next_slot;
        next_slot += n - 1;
        for (int i = 0; i < n; ++i)
        {
            const auto& c = build.tets[i];
            const int slot = child_slot(t, i);
            mesh_.tets[slot] = {g[c[0]], g[c[1]], g[c[2]], g[c[3]]};
            mesh_.tet_refs[slot] = ref;
            if (!required.empty() && required[t] && i > 0) required_children.push_back(slot);
        }
    }
    mesh_.required_tets.insert(mesh_.required_tets.end(), required_children.begin(),
                               required_children.end());
}

/// Adjacency of the children: inside a parent from the pattern, across a parent face by
/// matching the two sides' children on that face (equal vertex sets, by conformity).
void RefinePass::link_children()
{
    auto& nb = mesh_.neighbors;
    struct FaceOnSide
    {
        std::array<int, 3> key;
        int slot, face;
    };
    std::array<FaceOnSide, 4> mine, theirs;  // a parent face has at most 4 child triangles
    auto gather = [&](int t, int f, std::array<FaceOnSide, 4>& out) {
        int n = 0;
        auto add = [&](int slot, int k) {
            const auto& fv = tet::kFaceVertices[k];
            std::array<int, 3> key = {mesh_.tets[slot][fv[0]], mesh_.tets[slot][fv[1]],
                                      mesh_.tets[slot][fv[2]]};
            std::sort(key.begin(), key.end());
            out[n++] = {key, slot, k};
        };
        if (!is_refined(t))
            add(t, f);
        else
            for (int cf : child_build(choice_[t]).on_parent_face[f])
                add(child_slot(t, cf / 4), cf % 4);
        return n;
    };

    // neighbours before the pass: rows of refined parents were saved (their slots now hold
    // child 0 and get rewritten below); an unrefined tet's row changes only at the face it
    // shares with a refined tet, when that face is linked
    auto old_neighbor = [&](int t, int f) {
        return is_refined(t) ? old_rows_[ordinal_[t]][f] : nb[t][f];
    };
    for (int t : refined_)
    {
        const ChildBuild& build = child_build(choice_[t]);
        const int n = static_cast<int>(build.tets.size());
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < 4; ++k)
            {
                const int link = build.link[4 * i + k];
                if (link >= 0) nb[child_slot(t, i)][k] = child_slot(t, link / 4);
            }
        for (int f = 0; f < 4; ++f)
        {
            const int other = old_neighbor(t, f);
            if (other == kNoTet)
            {
                for (int cf : build.on_parent_face[f]) nb[child_slot(t, cf / 4)][cf % 4] = kNoTet;
                continue;
            }
            if (is_refined(other) && other < t) continue;  // linked from the other side
            int g = 0;
            while (g < 4 && old_neighbor(other, g) != t) ++g;
            const auto& mine_faces = build.on_parent_face[f];
            if (g < 4 && mine_faces.size() == 1 &&
                (!is_refined(other) || child_build(choice_[other]).on_parent_face[g].size() == 1))
            {
                // an unsplit face: one child face on each side, no matching needed
                const int slot = child_slot(t, mine_faces[0] / 4);
                const int their_slot =
                    is_refined(other)
                        ? child_slot(other, child_build(choice_[other]).on_parent_face[g][0] / 4)
                        : other;
                const int their_face =
                    is_refined(other) ? child_build(choice_[other]).on_parent_face[g][0] % 4 : g;
                nb[slot][mine_faces[0] % 4] = their_slot;
                nb[their_slot][their_face] = slot;
                continue;
            }
            const int count_mine = gather(t, f, mine);
            if (g == 4)
            {
                for (int j = 0; j < count_mine; ++j) nb[mine[j].slot][mine[j].face] = kNoTet;
                continue;
            }
            const int count_theirs = gather(other, g, theirs);
            for (int j = 0; j < count_mine; ++j)
            {
                int link = kNoTet;
                for (int m = 0; m < count_theirs; ++m)
                    if (theirs[m].key == mine[j].key)
                    {
                        link = theirs[m].slot;
                        nb[theirs[m].slot][theirs[m].face] = mine[j].slot;
                    }
                nb[mine[j].slot][mine[j].face] = link;
            }
        }
    }
}

void RefinePass::split_triangles(const EdgeTable& edges)
{
    const int n = static_cast<int>(mesh_.triangles.size());
    std::vector<Triangle> triangles;
    std::vector<int> refs, first_child(n + 1, 0);
    triangles.reserve(n);
    refs.reserve(n);
    for (int i = 0; i < n; ++i)
    {
        first_child[i] = static_cast<int>(triangles.size());
        const Triangle v = mesh_.triangles[i];
        const int ref = mesh_.triangle_refs[i];
        std::array<int, 3> mid;  // mid[k]: midpoint of edge v[k] v[k+1], or -1
        int split = 0;
        for (int k = 0; k < 3; ++k)
        {
            const int slot = edges.find(v[k], v[(k + 1) % 3]);
            mid[k] = slot < 0 ? -1 : midpoint_[slot];
            if (mid[k] >= 0)
            {
                ++split;
                if (mesh_.vertex_classes[mid[k]] == VertexClass::Interior)
                {
                    mesh_.vertex_classes[mid[k]] = VertexClass::Surface;
                    mesh_.vertex_refs[mid[k]] = ref;
                }
            }
        }
        auto add = [&](int x, int y, int z) {
            triangles.push_back({x, y, z});
            refs.push_back(ref);
        };
        if (split == 0)
            add(v[0], v[1], v[2]);
        else if (split == 1)
        {
            for (int k = 0; k < 3; ++k)
                if (mid[k] >= 0)
                {
                    add(v[k], mid[k], v[(k + 2) % 3]);
                    add(mid[k], v[(k + 1) % 3], v[(k + 2) % 3]);
                }
        }
        else if (split == 3)
        {
            for (int k = 0; k < 3; ++k) add(v[k], mid[k], mid[(k + 2) % 3]);
            add(mid[0], mid[1], mid[2]);
        }
        else
        {
            // corner v[k] where edges k-1 and k are split; counter-clockwise c, a, b
            int k = 0;
            while (!(mid[k] >= 0 && mid[(k + 2) % 3] >= 0)) ++k;
            const int c = v[k], a = v[(k + 1) % 3], b = v[(k + 2) % 3];
            const int mca = mid[k], mcb = mid[(k + 2) % 3];
            add(c, mca, mcb);
            if (diagonal_start(c, a, b) == a)
            {
                add(mca, a, mcb);
                add(a, b, mcb);
            }
            else
            {
                add(mca, a, b);
                add(mca, b, mcb);
            }
        }
    }
    first_child[n] = static_cast<int>(triangles.size());
    std::vector<int> required;
    for (int i : mesh_.required_triangles)
        for (int k = first_child[i]; k < first_child[i + 1]; ++k) required.push_back(k);
    mesh_.required_triangles = std::move(required);
    mesh_.triangles = std::move(triangles);
    mesh_.triangle_refs = std::move(refs);
}

void RefinePass::split_feature_edges(const EdgeTable& edges)
{
    const int n = static_cast<int>(mesh_.edges.size());
    std::vector<char> is_ridge(n, 0);
    for (int r : mesh_.ridges) is_ridge[r] = 1;
    std::vector<Edge> split_edges;
    std::vector<int> refs, first_child(n + 1, 0);
    for (int i = 0; i < n; ++i)
    {
        first_child[i] = static_cast<int>(split_edges.size());
        const Edge e = mesh_.edges[i];
        const int ref = mesh_.edge_refs[i];
        const int slot = edges.find(e[0], e[1]);
        const int m = slot < 0 ? -1 : midpoint_[slot];
        if (m < 0)
        {
            split_edges.push_back(e);
            refs.push_back(ref);
            continue;
        }
        split_edges.push_back({e[0], m});
        split_edges.push_back({m, e[1]});
        refs.push_back(ref);
        refs.push_back(ref);
        mesh_.vertex_refs[m] = ref;
        if (is_ridge[i]) mesh_.vertex_classes[m] = VertexClass::Ridge;
    }
    first_child[n] = static_cast<int>(split_edges.size());
    auto remap = [&](std::vector<int>& list) {
        std::vector<int> out;
        for (int i : list)
            for (int k = first_child[i]; k < first_child[i + 1]; ++k) out.push_back(k);
        list = std::move(out);
    };
    remap(mesh_.ridges);
    remap(mesh_.required_edges);
    mesh_.edges = std::move(split_edges);
    mesh_.edge_refs = std::move(refs);
}

RefinePassResult RefinePass::run()
{
    const WallStopwatch stopwatch;
    if (mesh_.num_live_tets() != mesh_.num_tet_slots()) mesh_.compact();
    if (!trust_adjacency_ || !mesh_.has_adjacency()) mesh_.build_adjacency();
#ifndef NDEBUG
    {
        const std::vector<TetVertices> kept = mesh_.neighbors;
        mesh_.build_adjacency();
        assert(kept == mesh_.neighbors && "refine_pass: the adjacency vouched for is stale");
    }
#endif
    num_vertices_before_ = mesh_.num_vertices();
    on_rank_cut_.clear();
    for (std::size_t i = 0; i < mesh_.triangles.size(); ++i)
        if (is_rank_cut_ref(mesh_.triangle_refs[i]))
        {
            on_rank_cut_.resize(mesh_.num_vertices(), 0);
            for (int v : mesh_.triangles[i]) on_rank_cut_[v] = 1;
        }
    RefinePassReport& report = result_.report;
    report.pass = 1;
    {
        const EdgeTable edges(mesh_, first_candidate_);
#ifndef NDEBUG
        if (first_candidate_ > 0)  // the older edges vouched for: a full scan marks no more
        {
            const EdgeTable all(mesh_, 0);
            const int everywhere = mark_edges(all);
            assert(everywhere == mark_edges(edges) && "refine_pass: an older edge is too long");
        }
#endif
        report.edges_split = mark_edges(edges);
        // A tet flat in doubles may have no positive children: its split edges wait for a later
        // pass (the optimizer in between takes it apart); its neighbours are simulated again.
        for (int round = 0; report.edges_split > 0; ++round)
        {
            const std::vector<StuckTet> stuck = choose_patterns(edges);
            if (stuck.empty()) break;
            if (round == kMaxDeferRounds)
                throw InputError("refine: " + std::to_string(stuck.size()) +
                                 " tets cannot be split without a non-positive child (the first: "
                                 "tet " +
                                 std::to_string(stuck.front().tet) + "); the mesh is unchanged");
            for (const auto& stuck_tet : stuck)
                for (int slot : stuck_tet.slots)
                    if (slot >= 0 && midpoint_[slot] >= 0)
                    {
                        midpoint_[slot] = -1;
                        --report.edges_split;
                        ++report.deferred_edges;
                    }
        }
        if (report.edges_split > 0)
        {
            add_midpoints(edges);
            rebuild_tets();
            link_children();
            split_triangles(edges);
            split_feature_edges(edges);
        }
    }
    std::vector<std::uint16_t>().swap(choice_);
    std::vector<int>().swap(extra_start_);
    std::vector<int>().swap(ordinal_);
    std::vector<int>().swap(refined_);
    std::vector<std::array<int, 6>>().swap(refined_slots_);
    std::vector<TetVertices>().swap(old_rows_);

    for (int m = num_vertices_before_; m < num_vertices_before_ + report.edges_split; ++m)
        if (mesh_.vertex_classes[m] != VertexClass::Interior)
            result_.new_boundary_vertices.push_back(m);
    report.steiner_points = num_new_points_;
    report.fallback_tets = num_fallbacks_;
    report.tets = mesh_.num_tet_slots();
    report.vertices = mesh_.num_vertices();
    report.seconds = stopwatch.seconds();
    return std::move(result_);
}

}  // namespace

RefinePassResult refine_pass(TetMesh& mesh, const SizeField& field)
{
    return RefinePass(mesh, field, 0, false).run();
}

RefinePassResult refine_pass(TetMesh& mesh, const SizeField& field,
                             const RefinePassOptions& options)
{
    return RefinePass(mesh, field, options.first_candidate_vertex, options.adjacency_valid, nullptr,
                      options.workers)
        .run();
}

RefinePassResult refine_pass(TetMesh& mesh, const SizeField& field, const QuadDiagonalRule& rule)
{
    return RefinePass(mesh, field, 0, false, &rule).run();
}

RefineResult refine(TetMesh& mesh, const SizeField& field, const RefineOptions& options)
{
    RefineResult result;
    // Without projection between passes, an edge a pass did not split is still short enough in
    // the next, and every new edge has a new endpoint: later passes look only at edges with an
    // endpoint created by the previous pass.
    int first_candidate = 0;
    for (int pass = 1; pass <= options.max_passes; ++pass)
    {
        const int vertices_before = mesh.num_vertices();
        // the first pass builds the caller's adjacency; later ones keep what the previous built
        RefinePassResult r = RefinePass(mesh, field, first_candidate, pass > 1).run();
        first_candidate = vertices_before;
        r.report.pass = pass;
        result.passes.push_back(r.report);
        result.new_boundary_vertices.insert(result.new_boundary_vertices.end(),
                                            r.new_boundary_vertices.begin(),
                                            r.new_boundary_vertices.end());
        result.steiner_vertices.insert(result.steiner_vertices.end(), r.steiner_vertices.begin(),
                                       r.steiner_vertices.end());
        if (r.report.edges_split == 0)
        {
            result.converged = true;
            break;
        }
    }
    return result;
}

}  // namespace hdimesh::volume
