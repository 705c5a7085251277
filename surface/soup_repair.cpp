// The repair pass over a triangle soup; see the header for the steps and their order.
#include "surface/soup_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>

#include "common/errors.h"

namespace hdimesh::surface
{
namespace
{

using Tri = std::array<int, 3>;
constexpr int kListed = 5;              // notes named one by one per kind, then a count
constexpr int kMaxHoleEdges = 300;      // the patch search is cubic in the loop's edges
constexpr double kPinchShift = 0.1;     // a pinch copy moves this fraction of its shortest edge
constexpr double kInsideWinding = 0.5;  // a point is inside a closed shell past this winding

std::string at(const Vec3d& p)
{
    char text[96];
    std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", p[0], p[1], p[2]);
    return text;
}

bool has_directed(const Tri& t, int a, int b)
{
    for (int k = 0; k < 3; ++k)
        if (t[k] == a && t[(k + 1) % 3] == b) return true;
    return false;
}

/// The uses of each undirected edge, sorted: runs of one edge, each with its faces.
class EdgeRuns
{
public:
    explicit EdgeRuns(const std::vector<Tri>& triangles) : run_of_(triangles.size())
    {
        uses_.reserve(3 * triangles.size());
        for (std::size_t f = 0; f < triangles.size(); ++f)
            for (int k = 0; k < 3; ++k)
                uses_.push_back(
                    {key(triangles[f][k], triangles[f][(k + 1) % 3]), static_cast<int>(f), k});
        std::sort(uses_.begin(), uses_.end());
        for (std::size_t i = 0; i < uses_.size(); ++i)
        {
            if (i == 0 || uses_[i].key != uses_[i - 1].key) first_.push_back(static_cast<int>(i));
            run_of_[uses_[i].face][uses_[i].side] = static_cast<int>(first_.size()) - 1;
        }
        first_.push_back(static_cast<int>(uses_.size()));
        partner_.assign(uses_.size(), -1);
        for (int r = 0; r < runs(); ++r)
            if (size(r) == 2)
            {
                partner_[first_[r]] = face(r, 1);
                partner_[first_[r] + 1] = face(r, 0);
            }
    }
    /// Pairs the 2k faces of run r around their edge, each face running the edge one way
    /// with the next one round (about the edge from its smaller vertex) running it the other:
    /// the wedges of solid of outward shells that touch along the edge. False when the
    /// directions do not alternate round the edge, or two faces lie at the same angle.
    bool pair_radially(int r, const std::vector<Vec3d>& points, const std::vector<Tri>& tris)
    {
        const int n = size(r);
        if (n < 4 || n % 2) return false;
        const auto [a, b] = edge(r);
        const Vec3d u = (points[b] - points[a]).normalized();
        Vec3d e1 = OpenMesh::cross(u, std::abs(u[0]) < 0.9 ? Vec3d(1, 0, 0) : Vec3d(0, 1, 0));
        e1.normalize();
        const Vec3d e2 = OpenMesh::cross(u, e1);
        struct Around
        {
            double angle;
            int use;
            bool forward;  // runs the edge a -> b
        };
        std::vector<Around> around;
        for (int i = 0; i < n; ++i)
        {
            const Tri& t = tris[face(r, i)];
            int c = t[0];
            for (int v : t)
                if (v != a && v != b) c = v;
            const Vec3d w = points[c] - points[a];
            around.push_back({std::atan2(OpenMesh::dot(w, e2), OpenMesh::dot(w, e1)), first_[r] + i,
                              has_directed(t, a, b)});
        }
        std::sort(around.begin(), around.end(),
                  [](const Around& x, const Around& y) { return x.angle < y.angle; });
        for (int i = 0; i < n; ++i)
        {
            const Around& x = around[i];
            const Around& y = around[(i + 1) % n];
            if (x.angle == y.angle || x.forward == y.forward) return false;
            // a face running b -> a has its solid on the side of growing angle
            if (!x.forward)
            {
                partner_[x.use] = uses_[y.use].face;
                partner_[y.use] = uses_[x.use].face;
            }
        }
        return true;
    }
    int runs() const { return static_cast<int>(first_.size()) - 1; }
    std::pair<int, int> edge(int r) const
    {
        const std::uint64_t k = uses_[first_[r]].key;
        return {static_cast<int>(k >> 32), static_cast<int>(k & 0xffffffffu)};
    }
    int size(int r) const { return first_[r + 1] - first_[r]; }
    int face(int r, int i) const { return uses_[first_[r] + i].face; }
    int side(int r, int i) const { return uses_[first_[r] + i].side; }
    /// The run of face f's edge from its corner k to k + 1 (flips keep the runs: a flip only
    /// reverses the direction of each edge).
    int run_of(int f, int k) const { return run_of_[f][k]; }
    /// The other face at f's edge k when that edge has exactly two faces, else -1.
    int other(int f, int k) const
    {
        const int r = run_of_[f][k];
        for (int i = first_[r]; i < first_[r + 1]; ++i)
            if (uses_[i].face == f && uses_[i].side == k) return partner_[i];
        return -1;
    }

private:
    struct Use
    {
        std::uint64_t key;
        int face, side;
        bool operator<(const Use& o) const
        {
            return key != o.key ? key < o.key : face != o.face ? face < o.face : side < o.side;
        }
    };
    static std::uint64_t key(int a, int b)
    {
        return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
               static_cast<std::uint32_t>(std::max(a, b));
    }
    std::vector<Use> uses_;
    std::vector<int> first_;
    std::vector<Tri> run_of_;
    std::vector<int> partner_;  // per use: the face across the edge (-1: none)
};

double triangle_area(const std::vector<Vec3d>& p, const Tri& t)
{
    return 0.5 * OpenMesh::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]).norm();
}

/// Walks each component over paired edges from its smallest face, calling reach(f, k, g) for
/// every pairing met (g across f's edge k) before g joins; a face no walk reached seeds the
/// next component. Returns the number of components.
template <class Reach>
int walk_components(std::size_t faces, const EdgeRuns& edges, std::vector<int>& component,
                    Reach reach)
{
    component.assign(faces, -1);
    int count = 0;
    std::vector<int> stack;
    for (std::size_t seed = 0; seed < faces; ++seed)
    {
        if (component[seed] >= 0) continue;
        component[seed] = count;
        stack.assign(1, static_cast<int>(seed));
        while (!stack.empty())
        {
            const int f = stack.back();
            stack.pop_back();
            for (int k = 0; k < 3; ++k)
            {
                const int g = edges.other(f, k);
                if (g < 0) continue;
                reach(f, k, g);
                if (component[g] >= 0) continue;
                component[g] = count;
                stack.push_back(g);
            }
        }
        ++count;
    }
    return count;
}

/// Components over paired edges, numbered by their smallest face.
std::vector<int> face_components(const std::vector<Tri>& triangles, const EdgeRuns& edges,
                                 int& count)
{
    std::vector<int> component;
    count = walk_components(triangles.size(), edges, component, [](int, int, int) {});
    return component;
}

class Repair
{
public:
    Repair(TriangleSoup& soup, const std::string& source, const SoupRepairOptions& options,
           SoupRepairReport& report)
        : soup_(soup), source_(source), options_(options), report_(report)
    {
        if (soup_.refs.size() != soup_.triangles.size())
            soup_.refs.assign(soup_.triangles.size(), 0);
        origin_.resize(soup_.points.size());
        std::iota(origin_.begin(), origin_.end(), 0);
    }

    void run()
    {
        merge_identical_points();
        collapse_flat_triangles();
        drop_degenerate_and_duplicates();
        if (soup_.triangles.empty()) throw InputError(source_ + ": no triangles");
        orient_components();
        split_pinched_vertices();
        if (options_.close_holes && options_.local_size && !options_.strict) close_holes();
        turn_closed_components_outward();
        if (options_.tiny_shell_volume > 0 && !options_.strict) drop_tiny_shells();
        compact();
    }

private:
    void note(const std::string& text) { report_.notes.push_back(source_ + ": repaired: " + text); }
    void refuse(const std::string& text) const
    {
        throw InputError(source_ + ": " + text + " (--strict refuses what is otherwise repaired)");
    }

    void merge_identical_points()
    {
        std::map<std::array<double, 3>, int> first_at;
        std::vector<int> renamed(soup_.points.size());
        for (std::size_t i = 0; i < soup_.points.size(); ++i)
        {
            const auto& p = soup_.points[i];
            const auto [it, inserted] =
                first_at.emplace(std::array<double, 3>{p[0], p[1], p[2]}, static_cast<int>(i));
            renamed[i] = it->second;
            if (!inserted) ++report_.merged_vertices;
        }
        for (auto& t : soup_.triangles)
            for (int& v : t)
            {
                if (v < 0 || v >= static_cast<int>(renamed.size()))
                    throw InputError(source_ + ": a triangle names vertex " +
                                     std::to_string(v + 1) + " of " +
                                     std::to_string(renamed.size()));
                v = renamed[v];
            }
        if (report_.merged_vertices)
            note("merged " + std::to_string(report_.merged_vertices) + " coincident vertices");
    }

    /// A flat triangle of three distinct points (a T-junction) loses its middle point to the
    /// nearer end: the triangle then repeats a point and is dropped, and its neighbours close
    /// up (removing it alone would leave a flat hole).
    void collapse_flat_triangles()
    {
        std::vector<int> renamed(soup_.points.size());
        std::iota(renamed.begin(), renamed.end(), 0);
        auto find = [&](int v) {
            while (renamed[v] != v) v = renamed[v] = renamed[renamed[v]];
            return v;
        };
        std::size_t collapsed = 0, first = 0;
        for (std::size_t f = 0; f < soup_.triangles.size(); ++f)
        {
            Tri t = soup_.triangles[f];
            for (int& v : t) v = find(v);
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || triangle_area(soup_.points, t) > 0)
                continue;
            if (options_.strict) refuse("triangle " + std::to_string(f + 1) + " has no area");
            // the shortest edge joins the middle point to its nearer end
            int k = 0;
            double shortest = std::numeric_limits<double>::infinity();
            for (int i = 0; i < 3; ++i)
            {
                const double l = (soup_.points[t[(i + 1) % 3]] - soup_.points[t[i]]).sqrnorm();
                if (l < shortest)
                {
                    shortest = l;
                    k = i;
                }
            }
            const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
            // the end is the one farther from the third point
            const bool a_is_end = (soup_.points[a] - soup_.points[c]).sqrnorm() >
                                  (soup_.points[b] - soup_.points[c]).sqrnorm();
            renamed[a_is_end ? b : a] = a_is_end ? a : b;
            if (collapsed++ == 0) first = f;
        }
        if (!collapsed) return;
        for (auto& t : soup_.triangles)
            for (int& v : t) v = find(v);
        note("collapsed " + std::to_string(collapsed) +
             " flat triangle(s) onto their longest edge (the first: triangle " +
             std::to_string(first + 1) + ")");
    }

    void drop_degenerate_and_duplicates()
    {
        // copies by their sorted vertices; each copy counts +1 or -1 by its orientation
        std::map<Tri, std::vector<int>> copies;
        std::vector<char> keep(soup_.triangles.size(), 1);
        std::size_t first_degenerate = 0;
        for (std::size_t f = 0; f < soup_.triangles.size(); ++f)
        {
            const Tri& t = soup_.triangles[f];
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
                !(triangle_area(soup_.points, t) > 0))
            {
                if (options_.strict) refuse("triangle " + std::to_string(f + 1) + " is degenerate");
                if (report_.degenerate_faces++ == 0) first_degenerate = f;
                keep[f] = 0;
                continue;
            }
            Tri key = t;
            std::sort(key.begin(), key.end());
            copies[key].push_back(static_cast<int>(f));
        }
        std::size_t first_duplicate = 0;
        for (auto& [key, faces] : copies)
        {
            if (faces.size() < 2) continue;
            if (options_.strict)
                refuse("triangles " + std::to_string(faces[0] + 1) + " and " +
                       std::to_string(faces[1] + 1) + " are the same triangle");
            auto positive = [&](int f) { return has_directed(soup_.triangles[f], key[0], key[1]); };
            int net = 0;
            for (int f : faces) net += positive(f) ? 1 : -1;
            // opposite copies cancel (a zero-volume wall); what is left counts once
            int kept = -1;
            for (int f : faces)
            {
                if (kept < 0 && net != 0 && positive(f) == (net > 0))
                    kept = f;
                else
                {
                    keep[f] = 0;
                    if (report_.duplicate_faces++ == 0) first_duplicate = faces[0];
                }
            }
        }
        std::vector<Tri> triangles;
        std::vector<int> refs;
        for (std::size_t f = 0; f < soup_.triangles.size(); ++f)
            if (keep[f])
            {
                triangles.push_back(soup_.triangles[f]);
                refs.push_back(soup_.refs[f]);
            }
        soup_.triangles = std::move(triangles);
        soup_.refs = std::move(refs);
        if (report_.degenerate_faces)
            note("dropped " + std::to_string(report_.degenerate_faces) +
                 " degenerate triangle(s) (the first: triangle " +
                 std::to_string(first_degenerate + 1) + ")");
        if (report_.duplicate_faces)
            note("dropped " + std::to_string(report_.duplicate_faces) +
                 " duplicated triangle(s) (the first: a copy of triangle " +
                 std::to_string(first_duplicate + 1) + ")");
    }

    /// Consistent orientation per component by a walk over shared edges.
    void orient_components()
    {
        const EdgeRuns edges = paired_edges(true);
        auto& tris = soup_.triangles;
        std::size_t flipped = 0;
        std::vector<int> component;
        walk_components(tris.size(), edges, component, [&](int f, int k, int g) {
            const auto [lo, hi] = edges.edge(edges.run_of(f, k));
            const int a = has_directed(tris[f], lo, hi) ? lo : hi;
            const int b = a == lo ? hi : lo;
            if (!has_directed(tris[g], a, b)) return;  // they agree
            if (component[g] >= 0)
                throw InputError(source_ + ": non-orientable surface (at triangle " +
                                 std::to_string(g + 1) + ")");
            if (options_.strict)
                refuse("triangles " + std::to_string(f + 1) + " and " + std::to_string(g + 1) +
                       " are oriented inconsistently");
            std::swap(tris[g][1], tris[g][2]);
            ++flipped;
        });
        report_.reoriented_faces += flipped;
        if (flipped)
            note("turned " + std::to_string(flipped) +
                 " triangle(s) to agree with their neighbours");
    }

    /// The edges, those of 2k faces paired round the edge (each pair then gets its own copy
    /// of the edge when the pinches split); any other non-manifold edge is refused.
    EdgeRuns paired_edges(bool noted)
    {
        EdgeRuns edges(soup_.triangles);
        int paired = 0;
        for (int r = 0; r < edges.runs(); ++r)
        {
            if (edges.size(r) <= 2) continue;
            const bool strict = options_.strict;
            if (!strict && edges.pair_radially(r, soup_.points, soup_.triangles))
            {
                if (noted && paired++ < kListed)
                    note("split the edge between vertices " +
                         std::to_string(origin_[edges.edge(r).first] + 1) + " and " +
                         std::to_string(origin_[edges.edge(r).second] + 1) + " at " +
                         at(soup_.points[edges.edge(r).first]) + " into " +
                         std::to_string(edges.size(r) / 2) + " sheets");
                continue;
            }
            throw InputError(source_ + ": non-manifold edge between vertices " +
                             std::to_string(origin_[edges.edge(r).first] + 1) + " and " +
                             std::to_string(origin_[edges.edge(r).second] + 1) + " (" +
                             std::to_string(edges.size(r)) + " triangles share it, at " +
                             at(soup_.points[edges.edge(r).first]) + ")" +
                             (strict ? std::string()
                                     : std::string(": not an even number of faces alternating "
                                                   "in direction round it, so no unambiguous "
                                                   "solid")));
        }
        if (paired > kListed) note("split " + std::to_string(paired - kListed) + " more edges");
        return edges;
    }

    /// One vertex per fan of triangles; every copy moves a little into its own fan.
    void split_pinched_vertices()
    {
        auto& tris = soup_.triangles;
        const EdgeRuns edges = paired_edges(false);
        const int np = static_cast<int>(soup_.points.size());
        std::vector<int> start(np + 1, 0);
        for (const Tri& t : tris)
            for (int v : t) ++start[v + 1];
        std::partial_sum(start.begin(), start.end(), start.begin());
        std::vector<int> faces_at(start.back()), fill(start.begin(), start.end() - 1);
        for (std::size_t f = 0; f < tris.size(); ++f)
            for (int v : tris[f]) faces_at[fill[v]++] = static_cast<int>(f);

        int listed = 0;
        std::vector<int> fan;  // per face around v: its fan's smallest position, union-find
        for (int v = 0; v < np; ++v)
        {
            const int n = start[v + 1] - start[v];
            if (n < 2) continue;
            const int* around = faces_at.data() + start[v];
            fan.resize(n);
            std::iota(fan.begin(), fan.end(), 0);
            auto find = [&](int i) {
                while (fan[i] != i) i = fan[i] = fan[fan[i]];
                return i;
            };
            auto position = [&](int g) {
                return static_cast<int>(std::find(around, around + n, g) - around);
            };
            for (int i = 0; i < n; ++i)
            {
                const Tri& t = tris[around[i]];
                for (int k = 0; k < 3; ++k)
                {
                    if (t[k] != v && t[(k + 1) % 3] != v) continue;  // edges at v only
                    const int g = edges.other(around[i], k);
                    if (g < 0) continue;
                    const int j = position(g);
                    if (j < n)
                    {
                        const int a = find(i), b = find(j);
                        if (a != b) fan[std::max(a, b)] = std::min(a, b);
                    }
                }
            }
            std::vector<int> roots;
            for (int i = 0; i < n; ++i)
                if (find(i) == i) roots.push_back(i);
            if (roots.size() < 2) continue;
            if (options_.strict)
                refuse("vertex " + std::to_string(origin_[v] + 1) + " at " + at(soup_.points[v]) +
                       " is pinched (" + std::to_string(roots.size()) +
                       " fans of triangles meet there)");
            const Vec3d p = soup_.points[v];
            for (std::size_t r = 0; r < roots.size(); ++r)
            {
                // the copy for this fan: the vertex itself for the first
                int copy = v;
                if (r > 0)
                {
                    copy = static_cast<int>(soup_.points.size());
                    soup_.points.push_back(p);
                    origin_.push_back(origin_[v]);
                    ++report_.split_vertices;
                }
                Vec3d ring(0, 0, 0);
                double shortest = std::numeric_limits<double>::infinity();
                int count = 0;
                for (int i = 0; i < n; ++i)
                {
                    if (find(i) != roots[r]) continue;
                    for (int& w : tris[around[i]])
                    {
                        if (w == v)
                        {
                            w = copy;
                            continue;
                        }
                        ring += soup_.points[w];
                        shortest = std::min(shortest, (soup_.points[w] - p).norm());
                        ++count;
                    }
                }
                const Vec3d into = ring / count - p;
                const double length = into.norm();
                if (length > 0) soup_.points[copy] = p + into * (kPinchShift * shortest / length);
            }
            if (listed++ < kListed)
                note("split pinched vertex " + std::to_string(origin_[v] + 1) + " at " + at(p) +
                     " into " + std::to_string(roots.size()) + " sheets");
        }
        if (listed > kListed)
            note("split " + std::to_string(listed - kListed) + " more pinched vertices");
    }

    /// The boundary loops, each closed by a minimum-area triangulation when it is small.
    void close_holes()
    {
        auto& tris = soup_.triangles;
        const auto& pts = soup_.points;
        const EdgeRuns edges(tris);
        int components = 0;
        const std::vector<int> component = face_components(tris, edges, components);
        std::vector<double> area(components, 0.0);
        for (std::size_t f = 0; f < tris.size(); ++f)
            area[component[f]] += triangle_area(pts, tris[f]);
        // boundary edges as their faces traverse them: next[a] = b, with the face
        std::vector<int> next(pts.size(), -1), face_of(pts.size(), -1);
        std::vector<int> starts;
        for (int r = 0; r < edges.runs(); ++r)
        {
            if (edges.size(r) != 1) continue;
            const int f = edges.face(r, 0), k = edges.side(r, 0);
            const int a = tris[f][k], b = tris[f][(k + 1) % 3];
            next[a] = b;  // one per vertex: pinches are split
            face_of[a] = f;
            starts.push_back(a);
        }
        std::vector<char> walked(pts.size(), 0);
        for (int s : starts)
        {
            if (walked[s]) continue;
            std::vector<int> loop;
            for (int v = s; v >= 0 && !walked[v]; v = next[v])
            {
                walked[v] = 1;
                loop.push_back(v);
            }
            if (loop.size() < 3 || next[loop.back()] != s) continue;  // not a simple loop
            if (static_cast<int>(loop.size()) > kMaxHoleEdges) continue;
            // the loop's extent: the largest distance between two of its points
            double extent = 0, size = 0;
            Vec3d centre(0, 0, 0);
            for (std::size_t i = 0; i < loop.size(); ++i)
            {
                for (std::size_t j = i + 1; j < loop.size(); ++j)
                    extent = std::max(extent, (pts[loop[j]] - pts[loop[i]]).sqrnorm());
                centre += pts[loop[i]];
                size += options_.local_size(pts[loop[i]]);
            }
            extent = std::sqrt(extent);
            centre /= static_cast<double>(loop.size());
            size /= static_cast<double>(loop.size());
            if (!(size > 0) || extent > options_.hole_size_factor * size) continue;
            double patch_area = 0;
            std::vector<Tri> patch = minimum_area_patch(loop, patch_area);
            if (patch_area > options_.max_hole_area_fraction * area[component[face_of[s]]])
                continue;
            const int ref = soup_.refs[face_of[s]];
            for (const Tri& t : patch)
            {
                tris.push_back(t);
                soup_.refs.push_back(ref);
            }
            ++report_.closed_holes;
            char text[160];
            std::snprintf(text, sizeof text,
                          "closed a hole of %zu edges at %s, %.2g local sizes across", loop.size(),
                          at(centre).c_str(), extent / size);
            note(text);
        }
    }

    /// The triangulation of the loop of least total area (no new point), oriented against the
    /// loop so it continues its faces.
    std::vector<Tri> minimum_area_patch(const std::vector<int>& loop, double& total) const
    {
        const int n = static_cast<int>(loop.size());
        const auto& pts = soup_.points;
        std::vector<double> cost(n * n, 0.0);
        std::vector<int> split(n * n, -1);
        for (int span = 2; span < n; ++span)
            for (int i = 0; i + span < n; ++i)
            {
                const int j = i + span;
                double best = std::numeric_limits<double>::infinity();
                for (int m = i + 1; m < j; ++m)
                {
                    const double c = cost[i * n + m] + cost[m * n + j] +
                                     triangle_area(pts, {loop[i], loop[m], loop[j]});
                    if (c < best)
                    {
                        best = c;
                        split[i * n + j] = m;
                    }
                }
                cost[i * n + j] = best;
            }
        total = cost[n - 1];
        std::vector<Tri> patch;
        std::vector<std::pair<int, int>> todo{{0, n - 1}};
        while (!todo.empty())
        {
            const auto [i, j] = todo.back();
            todo.pop_back();
            if (j - i < 2) continue;
            const int m = split[i * n + j];
            patch.push_back({loop[i], loop[j], loop[m]});  // reversed: the loop runs i -> m -> j
            todo.push_back({i, m});
            todo.push_back({m, j});
        }
        return patch;
    }

    /// Closed components enclose a positive volume.
    void turn_closed_components_outward()
    {
        auto& tris = soup_.triangles;
        const EdgeRuns edges(tris);
        int count = 0;
        const std::vector<int> component = face_components(tris, edges, count);
        report_.components = count;
        closed_.assign(count, 1);
        volume_.assign(count, 0.0);
        for (std::size_t f = 0; f < tris.size(); ++f)
        {
            const Tri& t = tris[f];
            for (int k = 0; k < 3; ++k)
                if (edges.size(edges.run_of(f, k)) != 2) closed_[component[f]] = 0;
            volume_[component[f]] += OpenMesh::dot(
                soup_.points[t[0]], OpenMesh::cross(soup_.points[t[1]], soup_.points[t[2]]));
        }
        int turned = 0;
        for (int c = 0; c < count; ++c) turned += closed_[c] && volume_[c] < 0;
        for (std::size_t f = 0; f < tris.size(); ++f)
        {
            const int c = component[f];
            if (!closed_[c] || !(volume_[c] < 0)) continue;
            std::swap(tris[f][1], tris[f][2]);
            ++report_.reoriented_faces;
        }
        report_.turned_shells = turned;
        if (turned) note("turned " + std::to_string(turned) + " closed shell(s) outward");
        for (double& v : volume_) v = std::abs(v) / 6.0;
        component_ = component;
    }

    /// Winding number of the closed component c around p (float solid angles: p is a point
    /// of another shell, well off c unless the two touch).
    double winding(int c, const Vec3d& p) const
    {
        double sum = 0;
        for (std::size_t f = 0; f < soup_.triangles.size(); ++f)
        {
            if (component_[f] != c) continue;
            const Tri& t = soup_.triangles[f];
            const Vec3d a = soup_.points[t[0]] - p, b = soup_.points[t[1]] - p,
                        d = soup_.points[t[2]] - p;
            const double la = a.norm(), lb = b.norm(), ld = d.norm();
            const double det = OpenMesh::dot(a, OpenMesh::cross(b, d));
            const double div = la * lb * ld + OpenMesh::dot(a, b) * ld + OpenMesh::dot(b, d) * la +
                               OpenMesh::dot(d, a) * lb;
            sum += 2.0 * std::atan2(det, div);
        }
        return sum / (4.0 * M_PI);
    }

    void drop_tiny_shells()
    {
        const int count = static_cast<int>(closed_.size());
        double total = 0;
        for (int c = 0; c < count; ++c)
            if (closed_[c]) total += volume_[c];
        std::vector<Vec3d> first_point(count);
        std::vector<char> has_point(count, 0);
        for (std::size_t f = 0; f < soup_.triangles.size(); ++f)
            if (!has_point[component_[f]])
            {
                has_point[component_[f]] = 1;
                first_point[component_[f]] = soup_.points[soup_.triangles[f][0]];
            }
        std::vector<char> drop(count, 0);
        int dropped = 0;
        for (int c = 0; c < count && count > 1; ++c)
        {
            if (!closed_[c] || !(volume_[c] < options_.tiny_shell_volume * total)) continue;
            bool inside = false;
            for (int o = 0; o < count && !inside; ++o)
                inside = o != c && closed_[o] && !drop[o] &&
                         std::abs(winding(o, first_point[c])) > kInsideWinding;
            if (inside) continue;
            drop[c] = 1;
            if (dropped++ < kListed)
                note("dropped a tiny closed shell at " + at(first_point[c]) + " (volume " +
                     std::to_string(volume_[c]) + ", inside no other shell)");
        }
        if (dropped > kListed)
            note("dropped " + std::to_string(dropped - kListed) + " more tiny shells");
        report_.dropped_shells = dropped;
        if (!dropped) return;
        std::vector<Tri> triangles;
        std::vector<int> refs;
        for (std::size_t f = 0; f < soup_.triangles.size(); ++f)
            if (!drop[component_[f]])
            {
                triangles.push_back(soup_.triangles[f]);
                refs.push_back(soup_.refs[f]);
            }
        soup_.triangles = std::move(triangles);
        soup_.refs = std::move(refs);
    }

    /// Only the points the triangles use, in order of first use.
    void compact()
    {
        std::vector<int> renamed(soup_.points.size(), -1);
        std::vector<Vec3d> points;
        report_.source_point.clear();
        for (auto& t : soup_.triangles)
            for (int& v : t)
            {
                if (renamed[v] < 0)
                {
                    renamed[v] = static_cast<int>(points.size());
                    points.push_back(soup_.points[v]);
                    report_.source_point.push_back(origin_[v]);
                }
                v = renamed[v];
            }
        report_.unused_vertices = soup_.points.size() - report_.merged_vertices - points.size();
        soup_.points = std::move(points);
    }

    TriangleSoup& soup_;
    const std::string& source_;
    const SoupRepairOptions& options_;
    SoupRepairReport& report_;
    std::vector<int> origin_;  // per point, the input point it comes from
    std::vector<char> closed_;
    std::vector<double> volume_;
    std::vector<int> component_;
};

}  // namespace

void repair_soup(TriangleSoup& soup, const std::string& source, const SoupRepairOptions& options,
                 SoupRepairReport* report)
{
    SoupRepairReport local;
    Repair(soup, source, options, local).run();
    if (report) *report = std::move(local);
}

}  // namespace hdimesh::surface
