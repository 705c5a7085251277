#include "hdi/features.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "common/errors.h"

namespace hdimesh::hdi
{

namespace
{

constexpr double pi = 3.14159265358979323846;

std::size_t slot(int i) { return static_cast<std::size_t>(i); }

// The vector arithmetic of the surface mesh (OpenMesh), term by term in its order, so that a
// decision at a threshold is the same whichever mesh asks.
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double length(const Vec3& a) { return std::sqrt(dot(a, a)); }

Vec3 unit_normal(const Vec3& a, const Vec3& b, const Vec3& c)
{
    const Vec3 u = b - a, v = c - a;
    const Vec3 n(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
    const double len = length(n);
    return len > 0.0 ? Vec3(n[0] / len, n[1] / len, n[2] / len) : Vec3(0, 0, 0);
}

// The cosine of the angle between a and b; 1 (no angle) when either is zero.
double cosine_between(const Vec3& a, const Vec3& b)
{
    const double na = length(a), nb = length(b);
    if (!(na > 0.0) || !(nb > 0.0)) return 1.0;
    return std::clamp(dot(a, b) / (na * nb), -1.0, 1.0);
}

double angle_between_deg(const Vec3& a, const Vec3& b)
{
    return std::acos(cosine_between(a, b)) * 180.0 / pi;
}

/// One triangle side along an edge; `forward` when the triangle runs from -> to along it (two
/// consistently oriented neighbours disagree on it).
struct Side
{
    int triangle;
    bool forward;
};

/// Compressed rows: row r is items[begin[r] .. begin[r + 1]).
template <class T>
struct Rows
{
    std::vector<int> begin;
    std::vector<T> items;

    int size(int r) const { return begin[slot(r) + 1] - begin[slot(r)]; }
    const T* row(int r) const { return items.data() + begin[slot(r)]; }
};

/// The edges of a triangle surface, the sides along each, and each vertex's edges and
/// triangles (in edge and triangle order).
struct EdgeTable
{
    std::vector<EdgeEnds> edges;
    Rows<Side> sides;             // per edge, in triangle order
    Rows<EdgeEnds> vertex_edges;  // per vertex: (other end, edge)
    Rows<int> vertex_triangles;   // per vertex

    bool open(int e) const { return sides.size(e) == 1; }
};

/// Fills rows from (row, item) pairs, keeping their order within a row.
template <class T>
Rows<T> make_rows(int row_count, const std::vector<std::pair<int, T>>& pairs)
{
    Rows<T> rows;
    rows.begin.assign(slot(row_count) + 1, 0);
    for (const auto& p : pairs) ++rows.begin[slot(p.first) + 1];
    std::partial_sum(rows.begin.begin(), rows.begin.end(), rows.begin.begin());
    rows.items.resize(pairs.size());
    std::vector<int> fill(rows.begin.begin(), rows.begin.end() - 1);
    for (const auto& p : pairs) rows.items[slot(fill[slot(p.first)]++)] = p.second;
    return rows;
}

/// Every non-degenerate triangle side, keyed by its sorted vertex pair, sorted by key and then
/// by triangle: the sides along one edge side by side.
struct KeyedSide
{
    EdgeEnds key;
    int triangle;
};

std::vector<KeyedSide> sorted_sides(const std::vector<Triangle3>& triangles)
{
    std::vector<KeyedSide> sides;
    sides.reserve(3 * triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (int i = 0; i < 3; ++i)
        {
            const int a = triangles[t][slot(i)], b = triangles[t][slot((i + 1) % 3)];
            if (a == b) continue;  // a degenerate triangle's collapsed side is no edge
            sides.push_back({{std::min(a, b), std::max(a, b)}, static_cast<int>(t)});
        }
    std::sort(sides.begin(), sides.end(), [](const KeyedSide& x, const KeyedSide& y) {
        return x.key != y.key ? x.key < y.key : x.triangle < y.triangle;
    });
    return sides;
}

/// The edge table of the triangles; with `given` edges, numbered as given (each must be a
/// side, and each side one of them), else in the order triangles first use them.
EdgeTable build_edge_table(int point_count, const std::vector<Triangle3>& triangles,
                           const std::vector<EdgeEnds>& given)
{
    EdgeTable table;
    std::vector<std::pair<int, int>> incidences;
    incidences.reserve(3 * triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (int i = 0; i < 3; ++i)
        {
            const Triangle3& tri = triangles[t];
            const bool repeated = (i > 0 && tri[slot(i)] == tri[0]) || (i > 1 && tri[2] == tri[1]);
            if (!repeated)
                incidences.push_back({tri[slot(i)], static_cast<int>(t)});  // once per triangle
        }
    table.vertex_triangles = make_rows(point_count, incidences);
    auto vertex_edge_rows = [&]() {
        std::vector<std::pair<int, EdgeEnds>> ends;
        ends.reserve(2 * table.edges.size());
        for (std::size_t e = 0; e < table.edges.size(); ++e)
        {
            const EdgeEnds& edge = table.edges[e];
            ends.push_back({edge[0], {edge[1], static_cast<int>(e)}});
            ends.push_back({edge[1], {edge[0], static_cast<int>(e)}});
        }
        table.vertex_edges = make_rows(point_count, ends);
    };

    // per triangle side (3 t + i, from corner i to i + 1): the edge it lies on (-1: degenerate)
    std::vector<int> side_edge(3 * triangles.size(), -1);
    if (given.empty())
    {
        // an edge is new unless a triangle up to this one (a's triangles, ascending) has it
        auto known_edge = [&](int t, int a, int b) {
            for (int k = 0; k < table.vertex_triangles.size(a); ++k)
            {
                const int u = table.vertex_triangles.row(a)[k];
                if (u > t) break;
                for (int j = 0; j < 3; ++j)
                {
                    const int c = triangles[slot(u)][slot(j)],
                              d = triangles[slot(u)][slot((j + 1) % 3)];
                    const int e = side_edge[slot(3 * u + j)];
                    if (e >= 0 && ((c == a && d == b) || (c == b && d == a))) return e;
                }
            }
            return -1;
        };
        for (std::size_t t = 0; t < triangles.size(); ++t)
            for (int i = 0; i < 3; ++i)
            {
                const int a = triangles[t][slot(i)], b = triangles[t][slot((i + 1) % 3)];
                if (a == b) continue;  // a degenerate triangle's collapsed side is no edge
                int e = known_edge(static_cast<int>(t), a, b);
                if (e < 0)
                {
                    e = static_cast<int>(table.edges.size());
                    table.edges.push_back({a, b});
                }
                side_edge[3 * t + slot(i)] = e;
            }
        vertex_edge_rows();
    }
    else
    {
        table.edges = given;
        for (std::size_t e = 0; e < given.size(); ++e)
        {
            const int a = given[e][0], b = given[e][1];
            if (a < 0 || b < 0 || a >= point_count || b >= point_count || a == b)
                throw InputError("features: edge " + std::to_string(e) + " has bad ends");
        }
        vertex_edge_rows();
        for (std::size_t t = 0; t < triangles.size(); ++t)
            for (int i = 0; i < 3; ++i)
            {
                const int a = triangles[t][slot(i)], b = triangles[t][slot((i + 1) % 3)];
                if (a == b) continue;
                int e = -1;
                for (int k = 0; k < table.vertex_edges.size(a) && e < 0; ++k)
                    if (table.vertex_edges.row(a)[k][0] == b) e = table.vertex_edges.row(a)[k][1];
                if (e < 0)
                    throw InputError("features: side " + std::to_string(i) + " of triangle " +
                                     std::to_string(t) + " is in no given edge");
                side_edge[3 * t + slot(i)] = e;
            }
    }

    std::vector<std::pair<int, Side>> edge_sides;
    edge_sides.reserve(side_edge.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (int i = 0; i < 3; ++i)
        {
            const int e = side_edge[3 * t + slot(i)];
            if (e < 0) continue;
            const bool forward = triangles[t][slot(i)] == table.edges[slot(e)][0];
            edge_sides.push_back({e, {static_cast<int>(t), forward}});
        }
    table.sides = make_rows(static_cast<int>(table.edges.size()), edge_sides);  // in triangle order
    for (int e = 0; e < static_cast<int>(table.edges.size()); ++e)
        if (table.sides.size(e) == 0)  // also a second edge between the same two vertices
            throw InputError("features: edge " + std::to_string(e) + " is a side of no triangle");
    return table;
}

/// A maximal run of sharp edges between corners (or a closed loop without any).
struct Chain
{
    std::vector<int> edges;  // consecutive along the run
    double length = 0.0;
    bool open = false;      // along an open boundary
    bool topology = false;  // has an edge of three or more triangles
};

/// The corner rules and the chains of sharp edges between corners, recomputed each round as
/// noise chains are dropped.
class FeatureGraph
{
public:
    FeatureGraph(const std::vector<Vec3>& points, const std::vector<Triangle3>& triangles,
                 const EdgeTable& table, const FeatureOptions& options, std::vector<char> sharp)
        : points_(points), triangles_(triangles), table_(table), options_(options),
          sharp_(std::move(sharp)), open_vertex_(points.size(), 0)
    {
        for (int e = 0; e < static_cast<int>(table_.edges.size()); ++e)
            if (table_.open(e))
                open_vertex_[slot(table_.edges[slot(e)][0])] =
                    open_vertex_[slot(table_.edges[slot(e)][1])] = 1;
    }

    /// Curves end, meet or turn sharply at corners; an isolated spike is one too.
    void find_corners()
    {
        const int n = static_cast<int>(points_.size());
        corner_.assign(slot(n), 0);
        sharp_degree_.assign(slot(n), 0);
        for (int e = 0; e < static_cast<int>(table_.edges.size()); ++e)
            if (sharp_[slot(e)])
            {
                ++sharp_degree_[slot(table_.edges[slot(e)][0])];
                ++sharp_degree_[slot(table_.edges[slot(e)][1])];
            }
        // Marked around the sharp vertices (few), not asked of every other vertex's ring.
        beside_sharp_.assign(slot(n), 0);
        for (int v = 0; v < n; ++v)
            if (sharp_degree_[slot(v)] > 0)
                for (int i = 0; i < table_.vertex_edges.size(v); ++i)
                    beside_sharp_[slot(table_.vertex_edges.row(v)[i][0])] = 1;
        std::vector<std::pair<double, int>> turn_corners;
        for (int v = 0; v < n; ++v)
        {
            const int degree = sharp_degree_[slot(v)];
            if (degree == 0)
            {
                if (is_cone_tip(v)) corner_[slot(v)] = 1;
                continue;
            }
            if (degree != 2)
            {
                corner_[slot(v)] = 1;
                continue;
            }
            int ends[2], open_edges = 0, found = 0;
            for (int i = 0; i < table_.vertex_edges.size(v); ++i)
            {
                const auto [other, e] = table_.vertex_edges.row(v)[i];
                if (!sharp_[slot(e)] || found == 2) continue;
                ends[found++] = other;
                open_edges += table_.open(e);
            }
            // An open boundary going on as an inner curve (only where the surface is not a
            // manifold): a curve is open all along or nowhere.
            if (open_edges == 1)
            {
                corner_[slot(v)] = 1;
                continue;
            }
            // An open boundary turns at corners like a ridge, at its own (lower) angle.
            const bool open = open_vertex_[slot(v)];
            const double limit =
                open ? options_.boundary_corner_turn_angle_deg : options_.corner_turn_angle_deg;
            const Vec3& p = points_[slot(v)];
            const double turn =
                angle_between_deg(p - points_[slot(ends[0])], points_[slot(ends[1])] - p);
            if (turn <= limit) continue;
            if (open)
                turn_corners.emplace_back(turn, v);  // may be thinned below
            else
                corner_[slot(v)] = 1;  // a ridge that turns sharply is a corner of the part
        }
        // Boundary turn corners closer than min_corner_spacing to a kept corner are zig-zag noise
        // at the scale of the target mesh: the sharpest turn of a cluster stays, the rest slide.
        std::sort(turn_corners.begin(), turn_corners.end(),
                  [](const auto& a, const auto& b) { return a.first > b.first; });
        std::vector<Vec3> kept;
        for (int v = 0; v < n; ++v)
            if (corner_[slot(v)]) kept.push_back(points_[slot(v)]);
        for (const auto& [turn, v] : turn_corners)
        {
            const Vec3& p = points_[slot(v)];
            const bool crowded = std::any_of(kept.begin(), kept.end(), [&](const Vec3& q) {
                return length(q - p) < options_.min_corner_spacing;
            });
            if (crowded) continue;
            corner_[slot(v)] = 1;
            kept.push_back(p);
        }
    }

    /// Maximal runs of sharp edges between corners (closed loops have no corner).
    std::vector<Chain> chains() const
    {
        std::vector<Chain> out;
        std::vector<char> visited(table_.edges.size(), 0);
        for (int e = 0; e < static_cast<int>(table_.edges.size()); ++e)
        {
            if (!sharp_[slot(e)] || visited[slot(e)]) continue;
            Chain chain;
            chain.open = table_.open(e);
            std::vector<int> forward, backward;
            visited[slot(e)] = 1;
            walk(table_.edges[slot(e)][1], e, visited, forward);
            walk(table_.edges[slot(e)][0], e, visited, backward);
            chain.edges.assign(backward.rbegin(), backward.rend());
            chain.edges.push_back(e);
            chain.edges.insert(chain.edges.end(), forward.begin(), forward.end());
            for (int ce : chain.edges)
            {
                const EdgeEnds& ends = table_.edges[slot(ce)];
                chain.length += length(points_[slot(ends[1])] - points_[slot(ends[0])]);
                chain.topology = chain.topology || table_.sides.size(ce) > 2;
            }
            out.push_back(std::move(chain));
        }
        return out;
    }

    std::vector<char>& sharp() { return sharp_; }
    const std::vector<char>& corner() const { return corner_; }

private:
    /// A spike of the input (a cone tip: angle defect above cone_defect_deg) is kept as a
    /// corner, or remeshing would cut it off; only when its cone is wide enough for fair
    /// triangles around it (angle sum at least cone_min_angle_sum_deg). Reads beside_sharp_.
    bool is_cone_tip(int v)
    {
        if (open_vertex_[slot(v)] || !(options_.cone_defect_deg < 360.0)) return false;
        // Only an isolated spike: next to a ridge the defect belongs to the ridge's geometry.
        if (beside_sharp_[slot(v)]) return false;
        // The angle sum is geometry only: computed once, though find_corners runs each round.
        if (angle_sum_.empty()) angle_sum_.assign(points_.size(), not_yet);
        double& sum = angle_sum_[slot(v)];
        if (sum == not_yet) sum = fan_angle_sum(v);
        if (std::isnan(sum)) return false;  // not one closed fan
        return 360.0 - sum > options_.cone_defect_deg && sum >= options_.cone_min_angle_sum_deg;
    }

    /// The sum of v's corner angles, taken clockwise around v from its last triangle (the order
    /// in which a mesh built triangle by triangle circulates, so the sums round alike); NaN when
    /// v's triangles are not one closed, consistently oriented fan.
    double fan_angle_sum(int v)
    {
        constexpr double not_a_fan = std::numeric_limits<double>::quiet_NaN();
        const int count = table_.vertex_triangles.size(v);
        if (count == 0) return not_a_fan;
        // each triangle's corner at v: the vertices after and before v (read once)
        ring_.clear();
        for (int i = 0; i < count; ++i)
        {
            const Triangle3& tri = triangles_[slot(table_.vertex_triangles.row(v)[i])];
            const int k = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
            ring_.push_back({tri[slot((k + 1) % 3)], tri[slot((k + 2) % 3)]});
        }
        const Vec3& p = points_[slot(v)];
        const int start = count - 1;
        int corner = start;
        double sum = 0.0;
        for (int step = 0; step < count; ++step)
        {
            const auto [a, b] = ring_[slot(corner)];
            sum += angle_between_deg(points_[slot(a)] - p, points_[slot(b)] - p);
            // clockwise: across the edge (v, a), into the triangle where a comes just before v
            int next = -1;
            for (int i = 0; i < count; ++i)
                if (ring_[slot(i)][1] == a)
                {
                    if (next >= 0) return not_a_fan;
                    next = i;
                }
            if (next < 0) return not_a_fan;
            if (next == start) return step == count - 1 ? sum : not_a_fan;
            corner = next;
        }
        return not_a_fan;
    }

    // Follows the curve from v (reached by edge `came`) through non-corner vertices of degree 2.
    void walk(int v, int came, std::vector<char>& visited, std::vector<int>& out) const
    {
        while (!corner_[slot(v)])
        {
            assert(sharp_degree_[slot(v)] == 2 && "a vertex inside a curve has two curve edges");
            int next = -1, next_end = -1;
            for (int i = 0; i < table_.vertex_edges.size(v); ++i)
            {
                const auto [other, e] = table_.vertex_edges.row(v)[i];
                if (e != came && sharp_[slot(e)]) next = e, next_end = other;
            }
            if (next < 0 || visited[slot(next)]) return;
            visited[slot(next)] = 1;
            out.push_back(next);
            v = next_end;
            came = next;
        }
    }

    static constexpr double not_yet = -1.0;

    const std::vector<Vec3>& points_;
    const std::vector<Triangle3>& triangles_;
    const EdgeTable& table_;
    const FeatureOptions& options_;
    std::vector<char> sharp_;        // per edge: 0 flat, 1 sharp, 2 a crease (kept in long chains)
    std::vector<char> open_vertex_;  // per vertex: on an open-boundary edge
    std::vector<char> corner_;
    std::vector<int> sharp_degree_;   // per vertex: its sharp edges (find_corners' round)
    std::vector<char> beside_sharp_;  // per vertex: a neighbour has a sharp edge (the same round)
    std::vector<double> angle_sum_;   // per vertex: the sum of its corner angles (not_yet)
    std::vector<std::array<int, 2>> ring_;  // fan_angle_sum's scratch: (after, before) per corner
};

/// Sharpness per edge: open, non-manifold and ref-border edges are sharp; inner edges by the
/// angle between their two faces' normals.
std::vector<char> sharp_edges(const std::vector<Vec3>& points,
                              const std::vector<Triangle3>& triangles, const std::vector<int>& refs,
                              const EdgeTable& table, const FeatureOptions& options)
{
    std::vector<Vec3> normal(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
        normal[t] = unit_normal(points[slot(triangles[t][0])], points[slot(triangles[t][1])],
                                points[slot(triangles[t][2])]);
    // An edge whose face normals' cosine is above that of the lowest sharp angle by a clear
    // margin is flat: its angle (an acos) is not computed. The margin is far above the rounding
    // of acos and of the degree conversion: the same decisions.
    const double lowest_sharp_deg = std::min(options.ridge_angle_deg, options.crease_angle_deg);
    const double flat_cosine = lowest_sharp_deg > 0.0
                                   ? std::cos(lowest_sharp_deg * pi / 180.0) + 1e-9
                                   : std::numeric_limits<double>::infinity();
    std::vector<char> sharp(table.edges.size(), 0);
    for (int e = 0; e < static_cast<int>(table.edges.size()); ++e)
    {
        if (table.sides.size(e) != 2)
        {
            sharp[slot(e)] = 1;  // an open boundary, or topology
            continue;
        }
        const Side s0 = table.sides.row(e)[0], s1 = table.sides.row(e)[1];
        if (!refs.empty() && refs[slot(s0.triangle)] != refs[slot(s1.triangle)])
        {
            sharp[slot(e)] = 1;  // a border between refs is kept like a ridge
            continue;
        }
        if (!options.detect_ridges) continue;
        const Vec3& n0 = normal[slot(s0.triangle)];
        const Vec3 n1 =
            s0.forward == s1.forward ? Vec3(-normal[slot(s1.triangle)]) : normal[slot(s1.triangle)];
        const double cosine = cosine_between(n0, n1);
        if (cosine >= flat_cosine) continue;
        const double angle = std::acos(cosine) * 180.0 / pi;
        if (angle > options.ridge_angle_deg)
            sharp[slot(e)] = 1;
        else if (angle > options.crease_angle_deg)
            sharp[slot(e)] = 2;  // a crease: kept only in long chains
    }
    return sharp;
}

/// The ends of a chain: of its first and last edge, those not shared with the next in line.
std::pair<int, int> chain_ends(const Chain& c, const EdgeTable& table)
{
    const EdgeEnds& first = table.edges[slot(c.edges.front())];
    if (c.edges.size() == 1) return {first[0], first[1]};
    auto free_end = [&](const EdgeEnds& e, int neighbour) {
        const EdgeEnds& n = table.edges[slot(neighbour)];
        const bool shared = n[0] == e[0] || n[1] == e[0];
        return shared ? e[1] : e[0];
    };
    const EdgeEnds& last = table.edges[slot(c.edges.back())];
    return {free_end(first, c.edges[1]), free_end(last, c.edges[c.edges.size() - 2])};
}

}  // namespace

FeatureClassification classify_features(const std::vector<Vec3>& points,
                                        const std::vector<Triangle3>& triangles,
                                        const FeatureOptions& options,
                                        const std::vector<EdgeEnds>& edges,
                                        const std::vector<int>& triangle_refs)
{
    const int point_count = static_cast<int>(points.size());
    check_triangle_indices(triangles, point_count);
    if (!triangle_refs.empty() && triangle_refs.size() != triangles.size())
        throw InputError("features: " + std::to_string(triangle_refs.size()) + " refs given for " +
                         std::to_string(triangles.size()) + " triangles");
    const EdgeTable table = build_edge_table(point_count, triangles, edges);
    const BoundingBox box = bounding_box(points);
    const double diagonal = points.empty() ? 0.0 : length(box.max - box.min);

    FeatureClassification result;
    FeatureSummary& summary = result.summary;
    FeatureGraph graph(points, triangles, table, options,
                       sharp_edges(points, triangles, triangle_refs, table, options));
    std::vector<Chain> chains;
    // Dropping a noise chain can turn a corner into a plain curve vertex and merge two chains,
    // so classify again until nothing more is dropped.
    for (int round = 0; round < 8; ++round)
    {
        graph.find_corners();
        chains = graph.chains();
        // A chain long enough is a ridge; a shorter one only when both its ends are ends of
        // ridges (a short ridge between corners of a machined part); the rest is noise.
        std::vector<char> kept(chains.size(), 0);
        std::vector<char> ridge_end(points.size(), 0);
        for (std::size_t i = 0; i < chains.size(); ++i)
        {
            const Chain& c = chains[i];
            const bool crease_only = std::all_of(
                c.edges.begin(), c.edges.end(), [&](int e) { return graph.sharp()[slot(e)] == 2; });
            const double needed = (crease_only ? 2.0 : 1.0) * options.min_ridge_length * diagonal;
            if (c.open || c.topology || c.length >= needed)
            {
                kept[i] = 1;
                const auto [a, b] = chain_ends(c, table);
                ridge_end[slot(a)] = ridge_end[slot(b)] = 1;
            }
        }
        for (bool grew = true; grew;)
        {
            grew = false;
            for (std::size_t i = 0; i < chains.size(); ++i)
            {
                if (kept[i]) continue;
                const auto [a, b] = chain_ends(chains[i], table);
                if (!ridge_end[slot(a)] || !ridge_end[slot(b)]) continue;
                kept[i] = 1;
                grew = true;
            }
        }
        bool dropped = false;
        for (std::size_t i = 0; i < chains.size(); ++i)
        {
            if (kept[i]) continue;
            for (int e : chains[i].edges) graph.sharp()[slot(e)] = 0;
            ++summary.dropped_ridge_chains;
            dropped = true;
        }
        if (!dropped) break;
    }

    const Classification smooth{Dimension::Surface, kNoModelEntity, false};
    result.edges = table.edges;
    result.vertex_class.assign(points.size(), smooth);
    result.edge_class.assign(table.edges.size(), smooth);
    int curve = 0;
    for (const Chain& c : chains)
    {
        const Classification on_curve{Dimension::Curve, curve, c.open};
        for (int e : c.edges)
        {
            result.edge_class[slot(e)] = on_curve;
            result.vertex_class[slot(table.edges[slot(e)][1])] = on_curve;
            result.vertex_class[slot(table.edges[slot(e)][0])] = on_curve;
            (c.open ? summary.boundary_edges : summary.ridge_edges) += 1;
        }
        ++curve;
    }
    int corner = 0;
    for (int v = 0; v < point_count; ++v)
        if (graph.corner()[slot(v)])
            result.vertex_class[slot(v)] = {Dimension::Corner, corner++, false};
    for (const Classification& c : result.vertex_class)
    {
        if (c.dimension == Dimension::Curve)
            ++(c.open_boundary ? summary.boundary_vertices : summary.ridge_vertices);
        else if (c.dimension == Dimension::Corner)
            ++summary.corners;
    }
    summary.curves = static_cast<std::size_t>(curve);
    return result;
}

FeatureSet feature_set(const FeatureClassification& classification)
{
    FeatureSet features;
    for (std::size_t e = 0; e < classification.edges.size(); ++e)
    {
        const Classification& c = classification.edge_class[e];
        if (c.dimension != Dimension::Curve) continue;
        const EdgeEnds& ends = classification.edges[e];
        const EdgeEnds sorted{std::min(ends[0], ends[1]), std::max(ends[0], ends[1])};
        (c.open_boundary ? features.boundary_edges : features.ridge_edges).push_back(sorted);
    }
    std::sort(features.ridge_edges.begin(), features.ridge_edges.end());
    std::sort(features.boundary_edges.begin(), features.boundary_edges.end());
    for (std::size_t v = 0; v < classification.vertex_class.size(); ++v)
        if (classification.vertex_class[v].dimension == Dimension::Corner)
            features.corners.push_back(static_cast<int>(v));
    return features;
}

FeatureSet detect_features(const std::vector<Vec3>& points, const std::vector<Triangle3>& triangles,
                           const FeatureOptions& options)
{
    return feature_set(classify_features(points, triangles, options));
}

std::vector<EdgeEnds> open_boundary_edges(const std::vector<Triangle3>& triangles)
{
    const std::vector<KeyedSide> sides = sorted_sides(triangles);
    std::vector<EdgeEnds> boundary;
    for (std::size_t i = 0; i < sides.size();)
    {
        std::size_t j = i;
        while (j < sides.size() && sides[j].key == sides[i].key) ++j;
        if (j - i == 1) boundary.push_back(sides[i].key);
        i = j;
    }
    return boundary;
}

namespace
{

int find_root(std::vector<int>& parent, int v)
{
    while (parent[slot(v)] != v)
    {
        parent[slot(v)] = parent[slot(parent[slot(v)])];
        v = parent[slot(v)];
    }
    return v;
}

}  // namespace

std::vector<int> smooth_patches(const std::vector<Triangle3>& triangles, const FeatureSet& features)
{
    std::vector<EdgeEnds> cuts = features.ridge_edges;
    cuts.insert(cuts.end(), features.boundary_edges.begin(), features.boundary_edges.end());
    std::sort(cuts.begin(), cuts.end());
    std::vector<int> parent(triangles.size());
    std::iota(parent.begin(), parent.end(), 0);
    const std::vector<KeyedSide> sides = sorted_sides(triangles);
    for (std::size_t i = 0; i < sides.size();)
    {
        std::size_t j = i;
        while (j < sides.size() && sides[j].key == sides[i].key) ++j;
        if (j - i == 2 && !std::binary_search(cuts.begin(), cuts.end(), sides[i].key))
        {
            const int ra = find_root(parent, sides[i].triangle);
            const int rb = find_root(parent, sides[i + 1].triangle);
            if (ra != rb) parent[slot(ra)] = rb;
        }
        i = j;
    }
    std::vector<int> patch_of_root(triangles.size(), -1);
    std::vector<int> patch(triangles.size());
    int patch_count = 0;
    for (std::size_t t = 0; t < triangles.size(); ++t)
    {
        int& id = patch_of_root[slot(find_root(parent, static_cast<int>(t)))];
        if (id < 0) id = patch_count++;
        patch[t] = id;
    }
    return patch;
}

std::vector<FeatureChain> feature_chains(const FeatureSet& features, int point_count)
{
    std::vector<EdgeEnds> edges = features.ridge_edges;
    edges.insert(edges.end(), features.boundary_edges.begin(), features.boundary_edges.end());
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<std::pair<int, EdgeEnds>> incidences;  // (vertex, (other vertex, edge id))
    incidences.reserve(2 * edges.size());
    for (std::size_t i = 0; i < edges.size(); ++i)
    {
        incidences.push_back({edges[i][0], {edges[i][1], static_cast<int>(i)}});
        incidences.push_back({edges[i][1], {edges[i][0], static_cast<int>(i)}});
    }
    const Rows<EdgeEnds> graph = make_rows(point_count, incidences);

    std::vector<char> breaks(slot(point_count), 0);
    for (int v = 0; v < point_count; ++v) breaks[slot(v)] = graph.size(v) != 2 && graph.size(v) > 0;
    for (int c : features.corners)
        if (c >= 0 && c < point_count) breaks[slot(c)] = 1;

    std::vector<char> used(edges.size(), 0);
    std::vector<FeatureChain> chains;
    // Follows unused edges from `start` through `first` until a break vertex or back at start.
    auto walk = [&](int start, int first_incidence) {
        FeatureChain chain;
        chain.vertices.push_back(start);
        int current = start;
        int incidence = first_incidence;
        while (true)
        {
            const auto [next, edge] = graph.row(current)[incidence];
            used[slot(edge)] = 1;
            if (next == start)
            {
                // Back where it began: a loop through one break vertex ends on it (the line is
                // not smooth there); a loop without any is closed.
                if (breaks[slot(start)])
                    chain.vertices.push_back(start);
                else
                    chain.closed = true;
                break;
            }
            chain.vertices.push_back(next);
            if (breaks[slot(next)]) break;
            current = next;
            incidence = -1;
            for (int i = 0; i < graph.size(current); ++i)
                if (!used[slot(graph.row(current)[i][1])]) incidence = i;
            if (incidence < 0) break;
        }
        chains.push_back(std::move(chain));
    };
    for (int v = 0; v < point_count; ++v)
    {
        if (!breaks[slot(v)]) continue;
        for (int i = 0; i < graph.size(v); ++i)
            if (!used[slot(graph.row(v)[i][1])]) walk(v, i);
    }
    for (int v = 0; v < point_count; ++v)  // loops without any break vertex
        for (int i = 0; i < graph.size(v); ++i)
            if (!used[slot(graph.row(v)[i][1])]) walk(v, i);
    return chains;
}

}  // namespace hdimesh::hdi
