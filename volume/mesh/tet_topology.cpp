#include "volume/mesh/tet_topology.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>

#include "volume/mesh/geometry.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace
{

/// True when (l0, l1, l2, l3), a permutation of 0..3, is even, i.e. the tet listed in that
/// local order keeps the stored (positive) orientation.
bool is_even_permutation(int l0, int l1, int l2, int l3)
{
    const int p[4] = {l0, l1, l2, l3};
    int inversions = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) inversions += (p[i] > p[j]);
    return inversions % 2 == 0;
}

/// The vertex of tet t that is none of x, y, z.
int fourth_vertex(const TetVertices& tv, int x, int y, int z)
{
    for (int v : tv)
        if (v != x && v != y && v != z) return v;
    return -1;
}

template <std::size_t N>
std::array<int, N> sorted(std::array<int, N> a)
{
    std::sort(a.begin(), a.end());
    return a;
}

}  // namespace

void vertex_ball(const TetMesh& mesh, int seed, int v, std::vector<int>& ball)
{
    ball.clear();
    // Breadth-first over the faces through v. Which tets are in the ball: a stamp per tet slot,
    // one stamp per call (a linear search of the ball per neighbour cost as much as the rest of
    // a collapse); per thread, so that const callers on several threads stay safe.
    thread_local std::vector<std::uint32_t> stamp;
    thread_local std::uint32_t current = 0;
    if (stamp.size() < static_cast<std::size_t>(mesh.num_tet_slots()))
        stamp.resize(mesh.num_tet_slots() + mesh.num_tet_slots() / 4 + 16, 0);
    if (++current == 0)  // wrapped: every old stamp could match again
    {
        std::fill(stamp.begin(), stamp.end(), 0);
        current = 1;
    }
    ball.push_back(seed);
    stamp[seed] = current;
    for (std::size_t head = 0; head < ball.size(); ++head)
    {
        const int t = ball[head];
        const int lv = local_index(mesh, t, v);
        assert(lv >= 0);
        if (lv < 0) continue;  // a stale seed: never flood the mesh in a release build
        for (int f = 0; f < 4; ++f)
        {
            if (f == lv) continue;
            const int n = mesh.neighbors[t][f];
            if (n == kNoTet || stamp[n] == current) continue;
            stamp[n] = current;
            ball.push_back(n);
        }
    }
}

bool edge_shell(const TetMesh& mesh, int seed, int a, int b, EdgeShell& shell)
{
    shell.a = a;
    shell.b = b;
    shell.tets.clear();
    shell.ring.clear();
    shell.closed = false;

    const int la = local_index(mesh, seed, a), lb = local_index(mesh, seed, b);
    if (la < 0 || lb < 0 || la == lb) return false;
    int lc = -1, ld = -1;
    for (int k = 0; k < 4; ++k)
        if (k != la && k != lb) (lc < 0 ? lc : ld) = k;
    if (!is_even_permutation(la, lb, lc, ld)) std::swap(lc, ld);
    const int c0 = mesh.tets[seed][lc], d0 = mesh.tets[seed][ld];

    const int limit = mesh.num_tet_slots() + 1;
    // forward: from the tet with ring step (c, d), cross the face (a, b, d), opposite c
    shell.tets.push_back(seed);
    shell.ring.push_back(c0);
    shell.ring.push_back(d0);
    int t = seed, c = c0, d = d0;
    for (int steps = 0; steps < limit; ++steps)
    {
        const int next = mesh.neighbors[t][local_index(mesh, t, c)];
        if (next == kNoTet) break;
        if (next == seed)
        {
            shell.closed = true;
            if (shell.ring.back() != c0) return false;
            shell.ring.pop_back();
            return shell.ring.size() >= 3;
        }
        if (mesh.is_dead(next)) return false;
        const int e = fourth_vertex(mesh.tets[next], a, b, d);
        if (e < 0 || local_index(mesh, next, a) < 0 || local_index(mesh, next, b) < 0) return false;
        shell.tets.push_back(next);
        shell.ring.push_back(e);
        t = next;
        c = d;
        d = e;
    }
    // open: walk backward from the seed across the face (a, b, c0), opposite d0
    std::vector<int> back_tets, back_ring;
    t = seed;
    c = c0;
    d = d0;
    for (int steps = 0; steps < limit; ++steps)
    {
        const int prev = mesh.neighbors[t][local_index(mesh, t, d)];
        if (prev == kNoTet) break;
        if (prev == seed || mesh.is_dead(prev)) return false;
        const int e = fourth_vertex(mesh.tets[prev], a, b, c);
        if (e < 0) return false;
        back_tets.push_back(prev);
        back_ring.push_back(e);
        t = prev;
        d = c;
        c = e;
    }
    std::reverse(back_tets.begin(), back_tets.end());
    std::reverse(back_ring.begin(), back_ring.end());
    shell.tets.insert(shell.tets.begin(), back_tets.begin(), back_tets.end());
    shell.ring.insert(shell.ring.begin(), back_ring.begin(), back_ring.end());
    return true;
}

std::vector<int> vertex_to_tet(const TetMesh& mesh)
{
    std::vector<int> result(mesh.num_vertices(), -1);
    for (int t = mesh.num_tet_slots() - 1; t >= 0; --t)
    {
        if (mesh.is_dead(t)) continue;
        for (int v : mesh.tets[t]) result[v] = t;
    }
    return result;
}

std::vector<char> held_vertices(const TetMesh& mesh)
{
    std::vector<char> held(mesh.num_vertices(), 0);
    for (int v : mesh.required_vertices) held[v] = 1;
    for (int i : mesh.required_triangles)
        for (int v : mesh.triangles[i]) held[v] = 1;
    return held;
}

std::array<int, 3> sorted_face(const TetMesh& mesh, int t, int f)
{
    const auto& fv = tet::kFaceVertices[f];
    const auto& tv = mesh.tets[t];
    return sorted(std::array<int, 3>{tv[fv[0]], tv[fv[1]], tv[fv[2]]});
}

// ---------------------------------------------------------------------------------------------

MeshConstraints::MeshConstraints(const TetMesh& mesh)
{
    std::vector<std::pair<std::array<int, 3>, int>> keyed;
    keyed.reserve(mesh.triangles.size());
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        keyed.push_back({sorted(mesh.triangles[i]), static_cast<int>(i)});
    std::sort(keyed.begin(), keyed.end());
    faces_.reserve(keyed.size());
    face_triangle_.reserve(keyed.size());
    for (const auto& [key, index] : keyed)
    {
        faces_.push_back(key);
        face_triangle_.push_back(index);
    }
    edges_.reserve(mesh.edges.size());
    for (const auto& e : mesh.edges) edges_.push_back(sorted(e));
    std::sort(edges_.begin(), edges_.end());
    on_listed_face_.assign(mesh.num_vertices(), 0);
    for (const auto& face : faces_)
        for (int v : face) on_listed_face_[v] = 1;
    const std::vector<char> held = held_vertices(mesh);
    free_vertex_.assign(mesh.num_vertices(), 0);
    for (int v = 0; v < mesh.num_vertices(); ++v)
        free_vertex_[v] = mesh.vertex_classes[v] == VertexClass::Interior && !held[v];
    for (int v : mesh.corners) free_vertex_[v] = 0;
    for (const auto& e : mesh.edges)
        for (int v : e) free_vertex_[v] = 0;
    required_tets_ = mesh.required_tets;
    std::sort(required_tets_.begin(), required_tets_.end());
    surface_vertex_.assign(mesh.num_vertices(), 0);
    for (int v = 0; v < mesh.num_vertices(); ++v)
        surface_vertex_[v] = mesh.vertex_classes[v] == VertexClass::Surface && !held[v];
    for (int v : mesh.corners) surface_vertex_[v] = 0;
    for (const auto& e : mesh.edges)
        for (int v : e) surface_vertex_[v] = 0;
}

int MeshConstraints::listed_triangle(const std::array<int, 3>& face) const
{
    const auto key = sorted(face);
    const auto it = std::lower_bound(faces_.begin(), faces_.end(), key);
    if (it == faces_.end() || *it != key) return -1;
    return face_triangle_[it - faces_.begin()];
}

void MeshConstraints::insert_face(const std::array<int, 3>& key, int triangle)
{
    const auto it = std::lower_bound(faces_.begin(), faces_.end(), key);
    face_triangle_.insert(face_triangle_.begin() + (it - faces_.begin()), triangle);
    faces_.insert(it, key);
}

void MeshConstraints::erase_face(const std::array<int, 3>& key)
{
    const auto it = std::lower_bound(faces_.begin(), faces_.end(), key);
    assert(it != faces_.end() && *it == key);
    face_triangle_.erase(face_triangle_.begin() + (it - faces_.begin()));
    faces_.erase(it);
}

void MeshConstraints::collapse_listed_faces(TetMesh& mesh, int from, int to)
{
    // the listed faces through `from`: the boundary faces of from's former ball, found by key
    std::vector<int> through;
    for (std::size_t i = 0; i < faces_.size(); ++i)
        if (faces_[i][0] == from || faces_[i][1] == from || faces_[i][2] == from)
            through.push_back(face_triangle_[i]);
    std::sort(through.begin(), through.end(), std::greater<int>());  // drops from the back first
    for (int i : through)
    {
        Triangle& tri = mesh.triangles[i];
        erase_face(sorted(tri));
        if (tri[0] == to || tri[1] == to || tri[2] == to)
        {
            const int last = static_cast<int>(mesh.triangles.size()) - 1;
            if (i != last)
            {
                const auto moved = sorted(mesh.triangles[last]);
                face_triangle_[std::lower_bound(faces_.begin(), faces_.end(), moved) -
                               faces_.begin()] = i;
                mesh.triangles[i] = mesh.triangles[last];
                if (mesh.triangle_refs.size() > static_cast<std::size_t>(last))
                    mesh.triangle_refs[i] = mesh.triangle_refs[last];
                // (a dropped triangle is never required: its vertices would be)
                for (int& r : mesh.required_triangles)
                    if (r == last) r = i;
            }
            mesh.triangles.pop_back();
            if (mesh.triangle_refs.size() > mesh.triangles.size()) mesh.triangle_refs.pop_back();
            continue;
        }
        for (int& v : tri)
            if (v == from) v = to;
        insert_face(sorted(tri), i);
    }
}

bool MeshConstraints::is_constrained_face(const TetMesh& mesh, int t, int f) const
{
    const int n = mesh.neighbors[t][f];
    if (n == kNoTet || mesh.tet_refs[n] != mesh.tet_refs[t]) return true;
    if (faces_.empty()) return false;
    // a face with a vertex on no listed face is not listed: skip the search (most faces)
    const auto& fv = tet::kFaceVertices[f];
    const auto& tv = mesh.tets[t];
    for (int k : fv)
        if (static_cast<std::size_t>(tv[k]) >= on_listed_face_.size() || !on_listed_face_[tv[k]])
            return false;
    return std::binary_search(faces_.begin(), faces_.end(), sorted_face(mesh, t, f));
}

bool MeshConstraints::is_constrained_edge(int a, int b) const
{
    if (edges_.empty()) return false;
    return std::binary_search(edges_.begin(), edges_.end(), Edge{std::min(a, b), std::max(a, b)});
}

bool MeshConstraints::is_removable_tet(int t) const
{
    return required_tets_.empty() ||
           !std::binary_search(required_tets_.begin(), required_tets_.end(), t);
}

void MeshConstraints::grow(int num_vertices)
{
    if (static_cast<int>(free_vertex_.size()) < num_vertices) free_vertex_.resize(num_vertices, 1);
    if (static_cast<int>(on_listed_face_.size()) < num_vertices)
        on_listed_face_.resize(num_vertices, 0);
    if (static_cast<int>(surface_vertex_.size()) < num_vertices)
        surface_vertex_.resize(num_vertices, 0);
}

OperatorContext::OperatorContext(const TetMesh& mesh, const SizeField* size_field)
    : field(size_field), constraints(mesh), vertex_tet(vertex_to_tet(mesh))
{
}

void OperatorContext::enable_caches()
{
    cache_enabled_ = true;
    quality_cache_.clear();
    forget_balls();
}

void OperatorContext::enable_change_stamps(const TetMesh& mesh)
{
    stamped_mesh_ = &mesh;
    vertex_stamp_.assign(mesh.num_vertices(), 0);
    changes_ = 0;
}

void OperatorContext::ball(const TetMesh& mesh, int v, std::vector<int>& ball) const
{
    if (!cache_enabled_)
    {
        vertex_ball(mesh, vertex_tet[v], v, ball);
        return;
    }
    for (const auto& cached : ball_cache_)
        if (cached.vertex == v)
        {
            ball = cached.tets;
#ifndef NDEBUG
            std::vector<int> fresh;
            vertex_ball(mesh, vertex_tet[v], v, fresh);
            assert(fresh == ball);  // a topology change bypassed replace_tets()
#endif
            return;
        }
    vertex_ball(mesh, vertex_tet[v], v, ball);
    CachedBall& slot = ball_cache_[next_ball_];
    next_ball_ = (next_ball_ + 1) % ball_cache_.size();
    slot.vertex = v;
    slot.tets = ball;
}

void OperatorContext::forget_balls() const
{
    for (auto& cached : ball_cache_) cached.vertex = -1;
}

double OperatorContext::shape(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) const
{
    if (field == nullptr || !field->anisotropic()) return tet_quality(a, b, c, d);
    return metric_tet_quality(field->metric(0.25 * (a + b + c + d)), a, b, c, d);
}

double OperatorContext::tet_shape(const TetMesh& mesh, int t) const
{
    const auto& v = mesh.tets[t];
    return shape(mesh.points[v[0]], mesh.points[v[1]], mesh.points[v[2]], mesh.points[v[3]]);
}

double OperatorContext::quality(const TetMesh& mesh, int t) const
{
    if (!cache_enabled_) return tet_shape(mesh, t);
    if (static_cast<std::size_t>(t) >= quality_cache_.size())
        quality_cache_.resize(std::max<std::size_t>(t + 1, mesh.tets.size()),
                              std::numeric_limits<double>::quiet_NaN());
    double& cached = quality_cache_[t];
    if (std::isnan(cached)) cached = tet_shape(mesh, t);
    // a stale entry means some change bypassed tets_changed(): catch it in debug builds
    assert(cached == tet_shape(mesh, t));
    return cached;
}

void OperatorContext::fill_quality_cache(const TetMesh& mesh, Workers* workers) const
{
    if (!cache_enabled_) return;
    if (quality_cache_.size() < mesh.tets.size())
        quality_cache_.resize(mesh.tets.size(), std::numeric_limits<double>::quiet_NaN());
    parallel_for(workers, mesh.tets.size(), [&](std::size_t first, std::size_t last) {
        for (std::size_t t = first; t < last; ++t)
            if (!mesh.is_dead(static_cast<int>(t)) && std::isnan(quality_cache_[t]))
                quality_cache_[t] = tet_shape(mesh, static_cast<int>(t));
    });
}

double OperatorContext::worst_quality(const TetMesh& mesh, const std::vector<int>& tets) const
{
    double worst = std::numeric_limits<double>::infinity();
    for (int t : tets) worst = std::min(worst, quality(mesh, t));
    return worst;
}

void OperatorContext::tets_changed(const int* begin, const int* end)
{
    touched.insert(touched.end(), begin, end);
    if (stamped_mesh_)
    {
        ++changes_;
        for (const int* t = begin; t != end; ++t)
            for (int v : stamped_mesh_->tets[*t])
            {
                if (v < 0) break;  // a dead slot
                if (static_cast<std::size_t>(v) >= vertex_stamp_.size())
                    vertex_stamp_.resize(v + 1 + v / 4, 0);
                vertex_stamp_[v] = changes_;
            }
    }
    if (!cache_enabled_) return;
    for (const int* t = begin; t != end; ++t)
        if (static_cast<std::size_t>(*t) < quality_cache_.size())
            quality_cache_[*t] = std::numeric_limits<double>::quiet_NaN();
}

bool OperatorContext::too_long(const Vec3& p, const Vec3& q) const
{
    if (field == nullptr) return false;
    return measure_edge(*field, p, q).too_long();
}

bool OperatorContext::too_short(const Vec3& p, const Vec3& q) const
{
    if (field == nullptr) return false;
    return measure_edge(*field, p, q).too_short();
}

double OperatorContext::size_quality(const Vec3& p, const Vec3& q) const
{
    if (field == nullptr) return 1.0;
    return measure_edge(*field, p, q).quality();
}

// ---------------------------------------------------------------------------------------------

namespace
{

/// A face of the cavity's hull: its sorted vertices and the tet outside it (with that tet's
/// local face index), or kNoTet on the mesh boundary.
struct HullFace
{
    std::array<int, 3> key;
    int outside_tet;
    int outside_face;
    bool matched = false;
};

}  // namespace

std::vector<int> replace_tets(TetMesh& mesh, OperatorContext& context,
                              const std::vector<int>& removed,
                              const std::vector<TetVertices>& added, int ref)
{
    assert(mesh.has_adjacency());
    context.forget_balls();
    auto is_removed = [&](int t) {
        return std::find(removed.begin(), removed.end(), t) != removed.end();
    };

    // 1. the hull of the cavity, with the links to mend
    std::vector<HullFace> hull;
    for (int t : removed)
        for (int f = 0; f < 4; ++f)
        {
            const int n = mesh.neighbors[t][f];
            if (n != kNoTet && is_removed(n)) continue;
            int back = -1;
            if (n != kNoTet)
                for (int g = 0; g < 4; ++g)
                    if (mesh.neighbors[n][g] == t) back = g;
            hull.push_back({sorted_face(mesh, t, f), n, back});
        }

    // 2. kill the old tets, place the new ones (freed slots first, in the order given)
    for (int t : removed) mesh.kill_tet(t);
    std::vector<int> ids;
    ids.reserve(added.size());
    for (std::size_t k = 0; k < added.size(); ++k)
    {
        int id;
        if (k < removed.size())
        {
            id = removed[k];
            mesh.tets[id] = added[k];
            mesh.tet_refs[id] = ref;
            mesh.neighbors[id] = {kNoTet, kNoTet, kNoTet, kNoTet};
        }
        else
        {
            id = mesh.add_tet(added[k], ref);
        }
        ids.push_back(id);
    }

    // 3. link every new face: to the hull, or to the other new tet that has it
    std::vector<std::array<int, 3>> new_face_keys(4 * ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k)
        for (int f = 0; f < 4; ++f) new_face_keys[4 * k + f] = sorted_face(mesh, ids[k], f);
    for (std::size_t k = 0; k < ids.size(); ++k)
        for (int f = 0; f < 4; ++f)
        {
            if (mesh.neighbors[ids[k]][f] != kNoTet) continue;  // linked from its partner
            const auto& key = new_face_keys[4 * k + f];
            bool linked = false;
            for (auto& h : hull)
            {
                if (h.matched || h.key != key) continue;
                h.matched = true;
                mesh.neighbors[ids[k]][f] = h.outside_tet;
                if (h.outside_tet != kNoTet) mesh.neighbors[h.outside_tet][h.outside_face] = ids[k];
                linked = true;
                break;
            }
            if (linked) continue;
            for (std::size_t j = k + 1; j < ids.size() && !linked; ++j)
                for (int g = 0; g < 4; ++g)
                    if (new_face_keys[4 * j + g] == key)
                    {
                        mesh.neighbors[ids[k]][f] = ids[j];
                        mesh.neighbors[ids[j]][g] = ids[k];
                        linked = true;
                        break;
                    }
            // an inner face already linked from its earlier partner stays as it is
        }
    // every interior hull face is matched; a boundary one may move with a collapse on the boundary
    assert(std::all_of(hull.begin(), hull.end(),
                       [](const HullFace& h) { return h.matched || h.outside_tet == kNoTet; }));

    // 4. surplus freed slots stay dead; the vertex map points at live tets
    for (std::size_t k = added.size(); k < removed.size(); ++k)
        mesh.neighbors[removed[k]] = {kNoTet, kNoTet, kNoTet, kNoTet};
    context.constraints.grow(mesh.num_vertices());
    if (static_cast<int>(context.vertex_tet.size()) < mesh.num_vertices())
        context.vertex_tet.resize(mesh.num_vertices(), -1);
    for (int id : ids)
        for (int v : mesh.tets[id]) context.vertex_tet[v] = id;
    // (the surplus slots stay dead until compact(): their cached qualities are never read)
    context.tets_changed(ids);
    return ids;
}

bool free_interior_shell(const TetMesh& mesh, const OperatorContext& context, int seed,
                         int local_edge, int max_ring, EdgeShell& shell, int& ref)
{
    const auto& ev = tet::kEdgeVertices[local_edge];
    const int a = mesh.tets[seed][ev[0]], b = mesh.tets[seed][ev[1]];
    if (!edge_shell(mesh, seed, a, b, shell) || !shell.closed) return false;
    const int m = static_cast<int>(shell.tets.size());
    if (m < 3 || m > max_ring) return false;
    const auto& constraints = context.constraints;
    if (constraints.is_constrained_edge(a, b)) return false;
    ref = mesh.tet_refs[seed];
    for (int i = 0; i < m; ++i)
    {
        const int t = shell.tets[i];
        if (mesh.tet_refs[t] != ref || !constraints.is_removable_tet(t)) return false;
        // the face shared with the next tet of the shell is opposite ring[i]
        if (constraints.is_constrained_face(mesh, t, local_index(mesh, t, shell.ring[i])))
            return false;
    }
    return true;
}

}  // namespace hdimesh::volume
