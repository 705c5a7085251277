#include "coupling/mirror.h"

#include <algorithm>
#include <cassert>
#include <cstdio>
#include <memory>
#include <unordered_map>

#include "volume/mesh/tet_tables.h"
#include "volume/mesh/tet_topology.h"

namespace hdimesh::coupling
{

using namespace volume;
using surface::EdgeHandle;
using surface::FaceHandle;
using surface::HalfedgeHandle;
using surface::SurfaceMesh;
using surface::VertexHandle;

namespace
{

using Key = std::array<int, 3>;

constexpr int kMaxGrowRounds = 4;   // a refused cavity grows at most this many times
constexpr int kMaxGrownTets = 400;  // and to at most this many tets

struct KeyHash
{
    std::size_t operator()(const Key& k) const
    {
        std::size_t h = static_cast<std::size_t>(k[0]);
        h = h * 0x9E3779B97F4A7C15ull + static_cast<std::size_t>(k[1]);
        return h * 0x9E3779B97F4A7C15ull + static_cast<std::size_t>(k[2]);
    }
};

/// A surface triangle in tet-vertex ids, with its ref.
struct RefTriangle
{
    Triangle vertices;
    int ref = 0;
};

/// A surface change as the tets see it: the tets it destroys, the surface triangles it takes
/// away and those it puts in their place.
struct CavityChange
{
    std::vector<int> tets;
    std::vector<RefTriangle> removed, added;
    /// The worst Qe of the tets before the change, when their points no longer show it (a
    /// move, simulated at the new place); < 0: from the tets.
    double quality_before = -1.0;
};

class Mirror
{
public:
    Mirror(TetMesh& mesh, BoundaryMap& map, const MirrorOptions& options, MirrorStatistics* stats)
        : mesh_(mesh), map_(map), options_(options), stats_(stats)
    {
        if (!mesh_.has_adjacency()) mesh_.build_adjacency();
        vertex_tet_ = vertex_to_tet(mesh_);
        for (std::size_t i = 0; i < mesh_.triangles.size(); ++i)
            triangle_index_[sorted_triple(mesh_.triangles[i])] = static_cast<int>(i);
        if (!map_.surface.get_property_handle(face_ref_, surface::property_names::face_ref))
            face_ref_.invalidate();
        const surface::SurfaceProperties props(map_.surface);
        vertex_class_ = props.vertex_class;
    }

    surface::SurfaceHooks hooks(const std::shared_ptr<Mirror>& self) const
    {
        surface::SurfaceHooks h;
        h.allow_move = [self](const SurfaceMesh& s, VertexHandle v, const surface::Vec3d& p) {
            return self->count(MirrorStatistics::Move, self->allow_move(s, v, p));
        };
        h.on_move = [self](const SurfaceMesh& s, VertexHandle v, const surface::Vec3d&) {
            self->commit_move(v, s.point(v));
        };
        h.allow_split = [self](const SurfaceMesh& s, EdgeHandle e, const surface::Vec3d& p) {
            return self->count(MirrorStatistics::Split, self->allow_split(s, e, p));
        };
        h.on_split = [self](const SurfaceMesh&, VertexHandle a, VertexHandle b,
                            VertexHandle inserted) { self->commit_split(a, b, inserted); };
        h.allow_collapse = [self](const SurfaceMesh& s, HalfedgeHandle he) {
            return self->count(MirrorStatistics::Collapse, self->allow_collapse(s, he));
        };
        h.on_collapse = [self](const SurfaceMesh&, VertexHandle removed, VertexHandle kept) {
            self->commit_pending(MirrorStatistics::Collapse,
                                 {self->tet(removed), self->tet(kept), -1});
        };
        h.allow_flip = [self](const SurfaceMesh& s, EdgeHandle e) {
            return self->count(MirrorStatistics::Flip, self->allow_flip(s, e));
        };
        h.on_flip = [self](const SurfaceMesh&, VertexHandle a, VertexHandle b, VertexHandle,
                           VertexHandle) {
            self->commit_pending(MirrorStatistics::Flip, {self->tet(a), self->tet(b), -1});
        };
        h.allow_remove_vertex = [self](const SurfaceMesh& s, VertexHandle v,
                                       const std::vector<std::array<VertexHandle, 3>>& planned) {
            return self->count(MirrorStatistics::Remove, self->allow_remove(s, v, planned));
        };
        h.on_remove_vertex = [self](const SurfaceMesh&, VertexHandle removed,
                                    const std::vector<FaceHandle>&) {
            self->commit_pending(MirrorStatistics::Remove, {self->tet(removed), -1, -1});
        };
        return h;
    }

private:
    // What allow_* found, for the on_* that follows it.
    struct Pending
    {
        int operation = -1;
        std::array<int, 3> key{};  // the operation's tet vertices
        CavityFill fill;
        std::vector<int> cavity_vertices;
        std::vector<int> swallowed;  // interior vertices a grown cavity takes away
        std::vector<RefTriangle> removed, added;
        std::vector<std::pair<FillStage, int>> fill_stages;  // per side filled: stage, layers
        bool adds_vertex = false;
        Vec3 new_point = Vec3::Zero();
    };

    int tet(VertexHandle v) const { return map_.tet_vertex_of(v); }

    /// Records why the operation being simulated is refused; returns false for `return`.
    bool refuse(MirrorStatistics::Refusal why) const
    {
        refusal_ = why;
        return false;
    }

    bool count(int operation, bool allowed)
    {
        if (!allowed && stats_)
        {
            ++stats_->refused[operation];
            ++stats_->refusals[refusal_];
        }
        return allowed;
    }

    int face_ref(const SurfaceMesh& s, FaceHandle f) const
    {
        return face_ref_.is_valid() ? s.property(face_ref_, f) : 0;
    }

    RefTriangle surface_triangle(const SurfaceMesh& s, FaceHandle f) const
    {
        RefTriangle t;
        int k = 0;
        for (auto v : s.fv_range(f)) t.vertices[k++] = tet(v);
        t.ref = face_ref(s, f);
        return t;
    }

    void ball(int v, std::vector<int>& out) const { vertex_ball(mesh_, vertex_tet_[v], v, out); }

    /// A live tet holding both a and b, or -1.
    int tet_with_edge(int a, int b) const
    {
        ball(a, scratch_);
        for (int t : scratch_)
            if (local_index(mesh_, t, b) >= 0) return t;
        return -1;
    }

    /// The tets around edge (a, b) into `tets`; false when no tet holds it (or the walk fails).
    bool shell_of(int a, int b, std::vector<int>& tets) const
    {
        const int seed = tet_with_edge(a, b);
        if (seed < 0) return refuse(MirrorStatistics::NoShell);
        EdgeShell shell;
        if (!edge_shell(mesh_, seed, a, b, shell)) return refuse(MirrorStatistics::NoShell);
        tets = std::move(shell.tets);
        return true;
    }

    // --- move: the ball's shapes, else its cavity refilled around the vertex's new place
    bool allow_move(const SurfaceMesh& s, VertexHandle sv, const surface::Vec3d& p)
    {
        const int v = tet(sv);
        const Vec3 to(p[0], p[1], p[2]);
        pending_ = Pending{};
        ball(v, scratch_);
        double worst_before = 1.0, worst_after = 1.0;
        bool inverted = false;
        for (int t : scratch_)
        {
            std::array<Vec3, 4> x;
            for (int k = 0; k < 4; ++k) x[k] = mesh_.points[mesh_.tets[t][k]];
            worst_before = std::min(worst_before, tet_quality(x[0], x[1], x[2], x[3]));
            x[local_index(mesh_, t, v)] = to;
            if (!(signed_volume6(x[0], x[1], x[2], x[3]) > 0.0)) inverted = true;
            worst_after = std::min(worst_after, tet_quality(x[0], x[1], x[2], x[3]));
        }
        if (!inverted && worst_after >= std::min(options_.min_quality, worst_before)) return true;
        // The ball cannot follow: its tets are taken out and the cavity, its surface triangles
        // at the new place, refilled (a coarse layer of tets under a surface being smoothed).
        Pending next;
        next.operation = MirrorStatistics::Move;
        next.key = {v, -1, -1};
        CavityChange change;
        change.tets = scratch_;
        change.quality_before = worst_before;
        for (auto f : s.vf_range(sv)) change.removed.push_back(surface_triangle(s, f));
        change.added = change.removed;
        const Vec3 from = mesh_.points[v];
        mesh_.points[v] = to;  // the filler reads points only
        const bool ok = simulate(change, next);
        mesh_.points[v] = from;
        if (!ok)
            return refuse(inverted ? MirrorStatistics::Inverted : MirrorStatistics::UnderFloor);
        pending_ = std::move(next);
        return true;
    }

    void commit_move(VertexHandle sv, const surface::Vec3d& p)
    {
        mesh_.points[tet(sv)] = surface::to_point(p);
        if (pending_.operation == MirrorStatistics::Move)
        {
            assert(pending_.key[0] == tet(sv));
            commit(MirrorStatistics::Move);  // the refilled ball
        }
        else if (stats_)
        {
            ++stats_->done[MirrorStatistics::Move];
        }
    }

    // --- the cavity operations
    bool allow_split(const SurfaceMesh& s, EdgeHandle e, const surface::Vec3d& p)
    {
        const HalfedgeHandle h = s.halfedge_handle(e, 0);
        const int a = tet(s.from_vertex_handle(h)), b = tet(s.to_vertex_handle(h));
        CavityChange change;
        if (!shell_of(a, b, change.tets)) return false;

        Pending next;
        next.operation = MirrorStatistics::Split;
        next.key = {a, b, -1};
        next.adds_vertex = true;
        next.new_point = surface::to_point(p);
        // The new vertex is the mesh's next id while the fill is computed (the filler reads
        // points only), and is taken out again until the commit.
        const int m = mesh_.add_vertex(next.new_point, 0, VertexClass::Surface);
        for (const HalfedgeHandle side : {h, s.opposite_halfedge_handle(h)})
        {
            const FaceHandle f = s.face_handle(side);
            if (!f.is_valid()) continue;
            const RefTriangle old = surface_triangle(s, f);
            change.removed.push_back(old);
            for (int end : {a, b})
            {
                RefTriangle half = old;
                std::replace(half.vertices.begin(), half.vertices.end(), end, m);
                change.added.push_back(half);
            }
        }
        const bool ok = simulate(change, next);
        mesh_.points.pop_back();
        mesh_.vertex_refs.pop_back();
        mesh_.vertex_classes.pop_back();
        if (ok) pending_ = std::move(next);
        return ok;
    }

    void commit_split(VertexHandle a, VertexHandle b, VertexHandle inserted)
    {
        assert(pending_.operation == MirrorStatistics::Split && pending_.key[0] == tet(a) &&
               pending_.key[1] == tet(b));
        (void)a;
        (void)b;
        // the class the surface gave it (its edge's: smooth, or the edge's curve)
        const auto cls = map_.surface.property(vertex_class_, inserted);
        const int m = mesh_.add_vertex(pending_.new_point, 0,
                                       to_vertex_class(surface::to_classification(cls)));
        map_.surface.property(map_.tet_vertex, inserted) = m;
        commit(MirrorStatistics::Split);
    }

    bool allow_collapse(const SurfaceMesh& s, HalfedgeHandle h)
    {
        const VertexHandle sfrom = s.from_vertex_handle(h), sto = s.to_vertex_handle(h);
        const int from = tet(sfrom), to = tet(sto);
        Pending next;
        next.operation = MirrorStatistics::Collapse;
        next.key = {from, to, -1};
        CavityChange change;
        ball(from, change.tets);
        for (auto f : s.vf_range(sfrom))
        {
            const RefTriangle old = surface_triangle(s, f);
            change.removed.push_back(old);
            if (std::find(old.vertices.begin(), old.vertices.end(), to) != old.vertices.end())
                continue;  // one of the two triangles of the edge: it goes away
            RefTriangle moved = old;
            std::replace(moved.vertices.begin(), moved.vertices.end(), from, to);
            change.added.push_back(moved);
        }
        if (!simulate(change, next)) return false;
        pending_ = std::move(next);
        return true;
    }

    bool allow_flip(const SurfaceMesh& s, EdgeHandle e)
    {
        // (a, b, c) and (b, a, d) become (c, a, d) and (d, b, c)
        const HalfedgeHandle h = s.halfedge_handle(e, 0), o = s.opposite_halfedge_handle(h);
        const FaceHandle f0 = s.face_handle(h), f1 = s.face_handle(o);
        if (!f0.is_valid() || !f1.is_valid()) return refuse(MirrorStatistics::NoShell);
        const int a = tet(s.from_vertex_handle(h)), b = tet(s.to_vertex_handle(h));
        const int c = tet(s.to_vertex_handle(s.next_halfedge_handle(h)));
        const int d = tet(s.to_vertex_handle(s.next_halfedge_handle(o)));
        CavityChange change;
        if (!shell_of(a, b, change.tets)) return false;
        Pending next;
        next.operation = MirrorStatistics::Flip;
        next.key = {a, b, -1};
        const RefTriangle t0 = surface_triangle(s, f0), t1 = surface_triangle(s, f1);
        change.removed = {t0, t1};
        change.added = {{{c, a, d}, t0.ref}, {{d, b, c}, t1.ref}};
        if (!simulate(change, next)) return false;
        pending_ = std::move(next);
        return true;
    }

    bool allow_remove(const SurfaceMesh& s, VertexHandle sv,
                      const std::vector<std::array<VertexHandle, 3>>& planned)
    {
        const int v = tet(sv);
        Pending next;
        next.operation = MirrorStatistics::Remove;
        next.key = {v, -1, -1};
        CavityChange change;
        ball(v, change.tets);
        int ref = 0;
        for (auto f : s.vf_range(sv))
        {
            change.removed.push_back(surface_triangle(s, f));
            ref = change.removed.back().ref;
        }
        for (const auto& t : planned)
            change.added.push_back({{tet(t[0]), tet(t[1]), tet(t[2])}, ref});
        if (!simulate(change, next)) return false;
        pending_ = std::move(next);
        return true;
    }

    /// The cavity's fill and its checks; `out` gets the fill. False when the tets cannot follow
    /// the change. A cavity whose fill fails, or whose new surface edge is an edge of a kept
    /// tet, grows by the tets in the way (a layer across its inner faces, or that edge's
    /// shell) and is tried again: the tets right under a coarse boundary are often too few.
    bool simulate(const CavityChange& change, Pending& out) const
    {
        std::vector<int> cavity = change.tets;
        std::sort(cavity.begin(), cavity.end());
        cavity.erase(std::unique(cavity.begin(), cavity.end()), cavity.end());
        std::vector<int> grow;
        for (int round = 0;; ++round)
        {
            grow.clear();
            if (try_cavity(change, cavity, out, grow)) return true;
            if (round == kMaxGrowRounds || grow.empty()) return false;
            cavity.insert(cavity.end(), grow.begin(), grow.end());
            std::sort(cavity.begin(), cavity.end());
            cavity.erase(std::unique(cavity.begin(), cavity.end()), cavity.end());
            if (static_cast<int>(cavity.size()) > kMaxGrownTets) return false;
        }
    }

    /// The interior vertices a grown cavity swallows (their balls inside it) into `swallowed`;
    /// refuses when any other vertex is off the cavity's faces.
    bool collect_swallowed(const CavityChange& change, const std::vector<int>& cavity,
                           const std::vector<std::vector<Triangle>>& side_faces, const Pending& out,
                           std::vector<int>& swallowed) const
    {
        auto in_cavity = [&](int t) { return std::binary_search(cavity.begin(), cavity.end(), t); };
        if (cavity.size() > change.tets.size())
        {
            std::vector<int> on_faces;
            for (const auto& faces : side_faces)
                for (const auto& f : faces) on_faces.insert(on_faces.end(), f.begin(), f.end());
            std::sort(on_faces.begin(), on_faces.end());
            std::vector<int> vertices;
            for (int t : cavity)
                vertices.insert(vertices.end(), mesh_.tets[t].begin(), mesh_.tets[t].end());
            std::sort(vertices.begin(), vertices.end());
            vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
            for (int v : vertices)
            {
                if (std::binary_search(on_faces.begin(), on_faces.end(), v)) continue;
                if (std::find(out.key.begin(), out.key.end(), v) != out.key.end()) continue;
                ball(v, scratch_);
                const bool inside = std::all_of(scratch_.begin(), scratch_.end(), in_cavity);
                if (!inside || mesh_.vertex_classes[v] != VertexClass::Interior)
                    return refuse(MirrorStatistics::NoFill);
                swallowed.push_back(v);
            }
        }
        return true;
    }

    /// One try of simulate() on `cavity` (sorted). On a refusal that more tets may cure, `grow`
    /// gets them. Across an interface the cavity is one per side, refs never mixed: each side's
    /// faces are its tets' outer faces with the changed triangles swapped for the new ones
    /// (reversed on the side they face inward), filled on its own; the fills commit as one.
    bool try_cavity(const CavityChange& change, const std::vector<int>& cavity, Pending& out,
                    std::vector<int>& grow) const
    {
        auto in_cavity = [&](int t) { return std::binary_search(cavity.begin(), cavity.end(), t); };
        std::vector<int> refs;
        double worst_before = 1.0;
        for (int t : cavity)
        {
            refs.push_back(mesh_.tet_refs[t]);
            worst_before = std::min(worst_before, mesh_.quality(t));
        }
        std::sort(refs.begin(), refs.end());
        refs.erase(std::unique(refs.begin(), refs.end()), refs.end());
        if (refs.size() > 2) return refuse(MirrorStatistics::MixedRefs);  // one interface only
        if (change.quality_before >= 0.0) worst_before = change.quality_before;

        std::vector<std::pair<Key, Triangle>> removed;  // by vertex set, as the surface has it
        for (const auto& r : change.removed)
            removed.emplace_back(sorted_triple(r.vertices), r.vertices);
        std::sort(removed.begin(), removed.end());
        std::vector<std::vector<Triangle>> side_faces(refs.size());
        std::vector<int> across;  // kept tets of the same ref across the cavity's inner faces
        for (std::size_t side = 0; side < refs.size(); ++side)
        {
            const int ref = refs[side];
            std::size_t seen = 0, outward = 0;  // changed triangles met, and as outer faces
            std::vector<Triangle>& faces = side_faces[side];
            for (int t : cavity)
            {
                if (mesh_.tet_refs[t] != ref) continue;
                for (int f = 0; f < 4; ++f)
                {
                    const int n = mesh_.neighbors[t][f];
                    const bool inside = n != kNoTet && in_cavity(n);
                    if (inside && mesh_.tet_refs[n] == ref) continue;
                    const auto& lf = tet::kFaceVertices[f];
                    const Triangle tri{mesh_.tets[t][lf[0]], mesh_.tets[t][lf[1]],
                                       mesh_.tets[t][lf[2]]};
                    const Key key = sorted_triple(tri);
                    const auto it =
                        std::lower_bound(removed.begin(), removed.end(), key,
                                         [](const auto& r, const Key& k) { return r.first < k; });
                    if (it != removed.end() && it->first == key)
                    {
                        // a changed interface triangle: the tet across it changes too
                        if (n != kNoTet && !inside)
                        {
                            grow.push_back(n);
                            return refuse(MirrorStatistics::MissedTriangle);
                        }
                        ++seen;
                        if (same_orientation(tri, it->second)) ++outward;
                        continue;
                    }
                    if (n != kNoTet && !inside && mesh_.tet_refs[n] == ref) across.push_back(n);
                    faces.push_back(tri);
                }
            }
            if (seen != removed.size() || (outward != 0 && outward != seen))
                return refuse(MirrorStatistics::MissedTriangle);
            for (const auto& a : change.added)
                faces.push_back(outward > 0 || removed.empty()
                                    ? a.vertices
                                    : Triangle{a.vertices[0], a.vertices[2], a.vertices[1]});
            if (!cancel_opposite_faces(faces)) return refuse(MirrorStatistics::Folds);
        }
        if (!new_edges_are_new(change, cavity, grow)) return refuse(MirrorStatistics::EdgeInside);

        // A grown cavity may swallow an interior vertex (its ball inside): the fill drops it.
        std::vector<int> swallowed;
        if (!collect_swallowed(change, cavity, side_faces, out, swallowed)) return false;

        std::vector<CavityFill> fills(refs.size());
        for (std::size_t side = 0; side < refs.size(); ++side)
        {
            CavityFill& fill = fills[side];
            if (side_faces[side].empty())
            {
                fill.filled = true;  // the change only takes tets away (a flip over one tet)
                fill.first_new_vertex = mesh_.num_vertices();
                fill.worst_quality = 1.0;
            }
            else
            {
                fill = fill_cavity(mesh_, side_faces[side], nullptr, options_.cavity);
                if (!fill.filled)
                {
                    grow = std::move(across);
                    return refuse(MirrorStatistics::NoFill);
                }
                if (fill.worst_quality < std::min(options_.min_quality, worst_before))
                {
                    grow = std::move(across);
                    return refuse(MirrorStatistics::UnderFloor);
                }
            }
            fill.ref = refs[side];
        }
        out.fill_stages.clear();
        for (const CavityFill& fill : fills)
            if (!fill.tets.empty()) out.fill_stages.push_back({fill.stage, fill.grown_layers});
        out.fill = merge_fills(std::move(fills));
        out.fill.removed_tets = cavity;
        out.removed = change.removed;
        out.added = change.added;
        out.swallowed = std::move(swallowed);
        out.cavity_vertices.clear();
        for (int t : cavity)
            for (int v : mesh_.tets[t]) out.cavity_vertices.push_back(v);
        std::sort(out.cavity_vertices.begin(), out.cavity_vertices.end());
        out.cavity_vertices.erase(
            std::unique(out.cavity_vertices.begin(), out.cavity_vertices.end()),
            out.cavity_vertices.end());
        return true;
    }

    /// The fills of an interface's two sides as one commit: the second side's Steiner points
    /// numbered after the first's, each tet with its side's ref.
    static CavityFill merge_fills(std::vector<CavityFill> fills)
    {
        if (fills.size() == 1) return std::move(fills.front());
        CavityFill merged = std::move(fills.front());
        merged.tet_refs.assign(merged.tets.size(), merged.ref);
        for (std::size_t side = 1; side < fills.size(); ++side)
        {
            const CavityFill& fill = fills[side];
            const int shift = static_cast<int>(merged.new_points.size());
            for (TetVertices t : fill.tets)
            {
                for (int& v : t)
                    if (v >= fill.first_new_vertex) v += shift;
                merged.tets.push_back(t);
                merged.tet_refs.push_back(fill.ref);
            }
            merged.new_points.insert(merged.new_points.end(), fill.new_points.begin(),
                                     fill.new_points.end());
            merged.faces.insert(merged.faces.end(), fill.faces.begin(), fill.faces.end());
            merged.worst_quality = std::min(merged.worst_quality, fill.worst_quality);
            merged.grown_layers = std::max(merged.grown_layers, fill.grown_layers);
        }
        return merged;
    }

    /// Drops each face met twice with opposite orientations (a tet face the change exposes as
    /// a new surface triangle). False when a face repeats any other way (the cavity folds).
    static bool cancel_opposite_faces(std::vector<Triangle>& faces)
    {
        std::vector<std::pair<Key, int>> keyed;
        keyed.reserve(faces.size());
        for (std::size_t i = 0; i < faces.size(); ++i)
            keyed.emplace_back(sorted_triple(faces[i]), static_cast<int>(i));
        std::sort(keyed.begin(), keyed.end());
        std::vector<char> drop(faces.size(), 0);
        for (std::size_t i = 0; i < keyed.size();)
        {
            std::size_t j = i;
            while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
            if (j - i > 2) return false;
            if (j - i == 2)
            {
                const Triangle& p = faces[keyed[i].second];
                const Triangle& q = faces[keyed[i + 1].second];
                if (!same_orientation(p, {q[0], q[2], q[1]})) return false;  // not opposite
                drop[keyed[i].second] = drop[keyed[i + 1].second] = 1;
            }
            i = j;
        }
        std::size_t k = 0;
        for (std::size_t i = 0; i < faces.size(); ++i)
            if (!drop[i]) faces[k++] = faces[i];
        faces.resize(k);
        return true;
    }

    /// An edge of the new triangles that the old ones do not have must not be an edge of a tet
    /// kept outside the cavity: the boundary would pinch there (advancing_front.md §(d)).
    /// Else `grow` gets the kept tets that hold such an edge.
    bool new_edges_are_new(const CavityChange& change, const std::vector<int>& cavity,
                           std::vector<int>& grow) const
    {
        std::vector<std::array<int, 2>> old_edges;
        for (const auto& r : change.removed)
            for (int s = 0; s < 3; ++s)
                old_edges.push_back({std::min(r.vertices[s], r.vertices[(s + 1) % 3]),
                                     std::max(r.vertices[s], r.vertices[(s + 1) % 3])});
        std::sort(old_edges.begin(), old_edges.end());
        const int known = static_cast<int>(vertex_tet_.size());
        for (const auto& a : change.added)
            for (int s = 0; s < 3; ++s)
            {
                const int u = std::min(a.vertices[s], a.vertices[(s + 1) % 3]);
                const int w = std::max(a.vertices[s], a.vertices[(s + 1) % 3]);
                if (w >= known) continue;  // the split's new vertex: all its edges are new
                if (std::binary_search(old_edges.begin(), old_edges.end(),
                                       std::array<int, 2>{u, w}))
                    continue;
                ball(u, scratch_);
                for (int t : scratch_)
                    if (local_index(mesh_, t, w) >= 0 &&
                        !std::binary_search(cavity.begin(), cavity.end(), t))
                        grow.push_back(t);
            }
        return grow.empty();
    }

    void commit_pending(int operation, const std::array<int, 3>& key)
    {
        assert(pending_.operation == operation && pending_.key == key);
        (void)operation;
        (void)key;
        commit(operation);
    }

    void commit(int operation)
    {
        Pending p = std::move(pending_);
        pending_ = Pending{};
        const std::vector<int> ids = commit_cavity(mesh_, p.fill);
        if (stats_)
        {
            ++stats_->done[operation];
            for (const auto& [stage, layers] : p.fill_stages)
            {
                CavityFill side;
                side.filled = true;
                side.stage = stage;
                side.grown_layers = layers;
                stats_->fills.add(side);
            }
        }
        vertex_tet_.resize(mesh_.num_vertices(), -1);
        for (int v : p.cavity_vertices) vertex_tet_[v] = -1;
        for (int id : ids)
            for (int v : mesh_.tets[id]) vertex_tet_[v] = id;
        // the vertex a collapse or removal takes away is in no tet any more
        const bool takes_vertex =
            operation == MirrorStatistics::Collapse || operation == MirrorStatistics::Remove;
        for (int v : p.cavity_vertices)
            if (vertex_tet_[v] < 0 && !(takes_vertex && v == p.key[0]) &&
                !std::binary_search(p.swallowed.begin(), p.swallowed.end(), v))
                repair_vertex_tet(v, p.cavity_vertices);
        for (const auto& r : p.removed) remove_triangle(r.vertices);
        for (const auto& a : p.added) add_triangle(a);
    }

    /// A vertex of the cavity in none of the new tets (a flip over one tet, or the removed
    /// vertex): a live tet from a neighbour's ball that still holds it, else any, else none.
    void repair_vertex_tet(int v, const std::vector<int>& around)
    {
        for (int u : around)
        {
            if (u == v || vertex_tet_[u] < 0) continue;
            ball(u, scratch_);
            for (int t : scratch_)
                if (local_index(mesh_, t, v) >= 0)
                {
                    vertex_tet_[v] = t;
                    return;
                }
        }
        // No neighbour's ball reaches it (its cavity neighbours left too): any live tet.
        for (int t = 0; t < mesh_.num_tet_slots(); ++t)
            if (!mesh_.is_dead(t) && local_index(mesh_, t, v) >= 0)
            {
                vertex_tet_[v] = t;
                return;
            }
    }

    void remove_triangle(const Triangle& t)
    {
        const auto it = triangle_index_.find(sorted_triple(t));
        if (it == triangle_index_.end()) return;
        const int i = it->second, last = static_cast<int>(mesh_.triangles.size()) - 1;
        triangle_index_.erase(it);
        if (i != last)
        {
            mesh_.triangles[i] = mesh_.triangles[last];
            mesh_.triangle_refs[i] = mesh_.triangle_refs[last];
            triangle_index_[sorted_triple(mesh_.triangles[i])] = i;
        }
        mesh_.triangles.pop_back();
        mesh_.triangle_refs.pop_back();
    }

    void add_triangle(const RefTriangle& t)
    {
        triangle_index_[sorted_triple(t.vertices)] = static_cast<int>(mesh_.triangles.size());
        mesh_.triangles.push_back(t.vertices);
        mesh_.triangle_refs.push_back(t.ref);
    }

    TetMesh& mesh_;
    BoundaryMap& map_;
    MirrorOptions options_;
    MirrorStatistics* stats_;
    std::vector<int> vertex_tet_;
    std::unordered_map<Key, int, KeyHash> triangle_index_;
    OpenMesh::FPropHandleT<int> face_ref_;
    OpenMesh::VPropHandleT<surface::VertexClass> vertex_class_;
    Pending pending_;
    mutable MirrorStatistics::Refusal refusal_ = MirrorStatistics::NoFill;
    mutable std::vector<int> scratch_;
};

}  // namespace

volume::CavityOptions mirror_cavity_options()
{
    volume::CavityOptions options;
    options.front.max_attempts = 500;
    options.front.max_retreat_rounds = 1;
    return options;
}

std::string MirrorStatistics::format() const
{
    static const char* names[kOperations] = {"move", "split", "collapse", "flip", "remove"};
    std::string out = "mirror:";
    char part[96];
    for (int k = 0; k < kOperations; ++k)
    {
        std::snprintf(part, sizeof part, " %s %ld (refused %ld)", names[k], done[k], refused[k]);
        out += part;
    }
    static const char* why[kRefusals] = {"no shell",    "mixed refs",  "missed triangle",
                                         "folds",       "edge inside", "no fill",
                                         "under floor", "inverted"};
    out += "\nrefused:";
    for (int k = 0; k < kRefusals; ++k)
        if (refusals[k] > 0)
        {
            std::snprintf(part, sizeof part, " %s %ld", why[k], refusals[k]);
            out += part;
        }
    return out + "\n" + fills.format() + "\n";
}

surface::SurfaceHooks make_hooks(TetMesh& mesh, BoundaryMap& map, const MirrorOptions& options,
                                 MirrorStatistics* stats)
{
    auto mirror = std::make_shared<Mirror>(mesh, map, options, stats);
    return mirror->hooks(mirror);
}

}  // namespace hdimesh::coupling
