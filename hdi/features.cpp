#include "hdi/features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace hdimesh::hdi
{

namespace
{

constexpr double degrees = 3.14159265358979323846 / 180.0;

/// One triangle side, keyed by its sorted vertex pair; `forward` when the triangle runs
/// smaller -> larger along it (two consistently oriented neighbours disagree on it).
struct Side
{
    std::array<int, 2> edge;
    int triangle;
    bool forward;
};

std::vector<Side> sorted_sides(const std::vector<Triangle3>& triangles)
{
    std::vector<Side> sides;
    sides.reserve(3 * triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (std::size_t i = 0; i < 3; ++i) {
            const int a = triangles[t][i];
            const int b = triangles[t][(i + 1) % 3];
            if (a == b) continue;  // a degenerate triangle's collapsed side is no edge
            sides.push_back({{std::min(a, b), std::max(a, b)}, static_cast<int>(t), a < b});
        }
    std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
        return x.edge < y.edge || (x.edge == y.edge && x.triangle < y.triangle);
    });
    return sides;
}

/// Vertices joined by feature edges, as adjacency lists (neighbour, edge id).
struct FeatureGraph
{
    std::vector<int> begin;                       // CSR offsets, size point_count + 1
    std::vector<std::array<int, 2>> incidences;  // (other vertex, edge id)

    FeatureGraph(const std::vector<std::array<int, 2>>& edges, int point_count)
        : begin(static_cast<std::size_t>(point_count) + 1, 0), incidences(2 * edges.size())
    {
        for (const auto& e : edges) {
            ++begin[static_cast<std::size_t>(e[0]) + 1];
            ++begin[static_cast<std::size_t>(e[1]) + 1];
        }
        std::partial_sum(begin.begin(), begin.end(), begin.begin());
        std::vector<int> fill(begin.begin(), begin.end() - 1);
        for (std::size_t i = 0; i < edges.size(); ++i) {
            const int a = edges[i][0];
            const int b = edges[i][1];
            incidences[static_cast<std::size_t>(fill[static_cast<std::size_t>(a)]++)] = {b, static_cast<int>(i)};
            incidences[static_cast<std::size_t>(fill[static_cast<std::size_t>(b)]++)] = {a, static_cast<int>(i)};
        }
    }
    int degree(int v) const
    {
        return begin[static_cast<std::size_t>(v) + 1] - begin[static_cast<std::size_t>(v)];
    }
    const std::array<int, 2>& incidence(int v, int i) const
    {
        return incidences[static_cast<std::size_t>(begin[static_cast<std::size_t>(v)] + i)];
    }
};

int find_root(std::vector<int>& parent, int v)
{
    while (parent[static_cast<std::size_t>(v)] != v) {
        parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
        v = parent[static_cast<std::size_t>(v)];
    }
    return v;
}

/// Vertices where the lines made of `edges` branch (3+ edges), end (1) or turn by more than
/// corner_angle_deg (2), sorted.
std::vector<int> line_corners(const std::vector<std::array<int, 2>>& edges, const std::vector<Vec3>& points,
                              double corner_angle_deg)
{
    const int point_count = static_cast<int>(points.size());
    const FeatureGraph graph(edges, point_count);
    const double cos_turn = std::cos(corner_angle_deg * degrees);
    std::vector<int> corners;
    for (int v = 0; v < point_count; ++v) {
        const int degree = graph.degree(v);
        if (degree == 0) continue;
        bool corner = degree != 2;
        if (degree == 2) {
            const Vec3& p = points[static_cast<std::size_t>(v)];
            const Vec3 in = (p - points[static_cast<std::size_t>(graph.incidence(v, 0)[0])]).normalized();
            const Vec3 out = (points[static_cast<std::size_t>(graph.incidence(v, 1)[0])] - p).normalized();
            corner = in.dot(out) < cos_turn;  // the direction changes by more than the corner angle
        }
        if (corner) corners.push_back(v);
    }
    return corners;
}

/// The robustness rule. Sharp edges are cut into chains at branch points, ends and sharp turns.
/// A chain at least min_length long is a ridge; a shorter chain is kept only when both of its
/// ends are ends of kept chains (a short ridge between two corners of a machined part), repeated
/// until nothing changes. Scan noise (single creases, short zig-zags, spurs) goes.
std::vector<std::array<int, 2>> keep_ridge_chains(const std::vector<std::array<int, 2>>& sharp,
                                                  const std::vector<Vec3>& points, double min_length,
                                                  double corner_angle_deg)
{
    FeatureSet lines;
    lines.ridge_edges = sharp;
    lines.corners = line_corners(sharp, points, corner_angle_deg);
    const std::vector<FeatureChain> chains = feature_chains(lines, static_cast<int>(points.size()));
    std::vector<char> kept(chains.size(), 0);
    std::vector<int> kept_ends(points.size(), 0);  // per vertex: ends of kept chains there
    auto keep = [&](std::size_t c) {
        kept[c] = 1;
        if (!chains[c].closed) {
            ++kept_ends[static_cast<std::size_t>(chains[c].vertices.front())];
            ++kept_ends[static_cast<std::size_t>(chains[c].vertices.back())];
        }
    };
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const std::vector<int>& v = chains[c].vertices;
        double length = 0;
        for (std::size_t i = 0; i + 1 < v.size(); ++i)
            length += (points[static_cast<std::size_t>(v[i])] - points[static_cast<std::size_t>(v[i + 1])]).norm();
        if (chains[c].closed)
            length += (points[static_cast<std::size_t>(v.back())] - points[static_cast<std::size_t>(v.front())]).norm();
        if (length >= min_length) keep(c);
    }
    for (bool changed = true; changed;) {
        changed = false;
        for (std::size_t c = 0; c < chains.size(); ++c) {
            if (kept[c] || chains[c].closed) continue;
            if (kept_ends[static_cast<std::size_t>(chains[c].vertices.front())] > 0
                && kept_ends[static_cast<std::size_t>(chains[c].vertices.back())] > 0) {
                keep(c);
                changed = true;
            }
        }
    }
    std::vector<std::array<int, 2>> ridges;
    for (std::size_t c = 0; c < chains.size(); ++c) {
        if (!kept[c]) continue;
        const std::vector<int>& v = chains[c].vertices;
        const std::size_t segments = chains[c].closed ? v.size() : v.size() - 1;
        for (std::size_t i = 0; i < segments; ++i) {
            const int a = v[i], b = v[(i + 1) % v.size()];
            ridges.push_back({std::min(a, b), std::max(a, b)});
        }
    }
    std::sort(ridges.begin(), ridges.end());
    return ridges;
}

}  // namespace

std::vector<std::array<int, 2>> open_boundary_edges(const std::vector<Triangle3>& triangles)
{
    const std::vector<Side> sides = sorted_sides(triangles);
    std::vector<std::array<int, 2>> boundary;
    for (std::size_t i = 0; i < sides.size();) {
        std::size_t j = i;
        while (j < sides.size() && sides[j].edge == sides[i].edge) ++j;
        if (j - i == 1) boundary.push_back(sides[i].edge);
        i = j;
    }
    return boundary;
}

FeatureSet detect_features(const std::vector<Vec3>& points, const std::vector<Triangle3>& triangles,
                           const FeatureOptions& options)
{
    const int point_count = static_cast<int>(points.size());
    check_triangle_indices(triangles, point_count);
    std::vector<Vec3> face_normals(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
        face_normals[t] = triangle_normal(points[static_cast<std::size_t>(triangles[t][0])],
                                          points[static_cast<std::size_t>(triangles[t][1])],
                                          points[static_cast<std::size_t>(triangles[t][2])]);

    FeatureSet features;
    std::vector<std::array<int, 2>> sharp;
    std::vector<std::array<int, 2>> non_manifold;
    const double cos_ridge = std::cos(options.ridge_angle_deg * degrees);
    const std::vector<Side> sides = sorted_sides(triangles);
    for (std::size_t i = 0; i < sides.size();) {
        std::size_t j = i;
        while (j < sides.size() && sides[j].edge == sides[i].edge) ++j;
        if (j - i == 1) {
            features.boundary_edges.push_back(sides[i].edge);
        } else if (j - i > 2) {
            non_manifold.push_back(sides[i].edge);
        } else if (options.detect_ridges) {
            const Vec3& n0 = face_normals[static_cast<std::size_t>(sides[i].triangle)];
            Vec3 n1 = face_normals[static_cast<std::size_t>(sides[i + 1].triangle)];
            if (sides[i].forward == sides[i + 1].forward) n1 = -n1;  // inconsistent orientation
            const bool both_usable = n0.squaredNorm() > 0 && n1.squaredNorm() > 0;
            if (both_usable && n0.dot(n1) < cos_ridge) sharp.push_back(sides[i].edge);
        }
        i = j;
    }

    const double diagonal = bounding_box(points).diagonal();
    features.ridge_edges = keep_ridge_chains(sharp, points, options.min_chain_length_fraction * diagonal,
                                             options.corner_angle_deg);
    features.ridge_edges.insert(features.ridge_edges.end(), non_manifold.begin(), non_manifold.end());
    std::sort(features.ridge_edges.begin(), features.ridge_edges.end());

    // Corners: where feature lines meet (3+), end (1), or turn sharply (2).
    std::vector<std::array<int, 2>> all = features.ridge_edges;
    all.insert(all.end(), features.boundary_edges.begin(), features.boundary_edges.end());
    features.corners = line_corners(all, points, options.corner_angle_deg);
    return features;
}

std::vector<int> smooth_patches(const std::vector<Triangle3>& triangles, const FeatureSet& features)
{
    std::vector<std::array<int, 2>> cuts = features.ridge_edges;
    cuts.insert(cuts.end(), features.boundary_edges.begin(), features.boundary_edges.end());
    std::sort(cuts.begin(), cuts.end());
    std::vector<int> parent(triangles.size());
    std::iota(parent.begin(), parent.end(), 0);
    const std::vector<Side> sides = sorted_sides(triangles);
    for (std::size_t i = 0; i < sides.size();) {
        std::size_t j = i;
        while (j < sides.size() && sides[j].edge == sides[i].edge) ++j;
        if (j - i == 2 && !std::binary_search(cuts.begin(), cuts.end(), sides[i].edge)) {
            const int ra = find_root(parent, sides[i].triangle);
            const int rb = find_root(parent, sides[i + 1].triangle);
            if (ra != rb) parent[static_cast<std::size_t>(ra)] = rb;
        }
        i = j;
    }
    std::vector<int> patch_of_root(triangles.size(), -1);
    std::vector<int> patch(triangles.size());
    int patch_count = 0;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        int& id = patch_of_root[static_cast<std::size_t>(find_root(parent, static_cast<int>(t)))];
        if (id < 0) id = patch_count++;
        patch[t] = id;
    }
    return patch;
}

std::vector<FeatureChain> feature_chains(const FeatureSet& features, int point_count)
{
    std::vector<std::array<int, 2>> edges = features.ridge_edges;
    edges.insert(edges.end(), features.boundary_edges.begin(), features.boundary_edges.end());
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    const FeatureGraph graph(edges, point_count);

    std::vector<char> breaks(static_cast<std::size_t>(point_count), 0);
    for (int v = 0; v < point_count; ++v) breaks[static_cast<std::size_t>(v)] = graph.degree(v) != 2 && graph.degree(v) > 0;
    for (int c : features.corners)
        if (c >= 0 && c < point_count) breaks[static_cast<std::size_t>(c)] = 1;

    std::vector<char> used(edges.size(), 0);
    std::vector<FeatureChain> chains;
    // Follows unused edges from `start` through `first` until a break vertex or back at start.
    auto walk = [&](int start, int first_incidence) {
        FeatureChain chain;
        chain.vertices.push_back(start);
        int current = start;
        int incidence = first_incidence;
        while (true) {
            const auto [next, edge] = graph.incidence(current, incidence);
            used[static_cast<std::size_t>(edge)] = 1;
            if (next == start) {
                // Back where it began: a loop through one break vertex ends on it (the line is
                // not smooth there); a loop without any is closed.
                if (breaks[static_cast<std::size_t>(start)]) chain.vertices.push_back(start);
                else chain.closed = true;
                break;
            }
            chain.vertices.push_back(next);
            if (breaks[static_cast<std::size_t>(next)]) break;
            current = next;
            incidence = -1;
            for (int i = 0; i < graph.degree(current); ++i)
                if (!used[static_cast<std::size_t>(graph.incidence(current, i)[1])]) incidence = i;
            if (incidence < 0) break;
        }
        chains.push_back(std::move(chain));
    };
    for (int v = 0; v < point_count; ++v) {
        if (!breaks[static_cast<std::size_t>(v)]) continue;
        for (int i = 0; i < graph.degree(v); ++i)
            if (!used[static_cast<std::size_t>(graph.incidence(v, i)[1])]) walk(v, i);
    }
    for (int v = 0; v < point_count; ++v)  // loops without any break vertex
        for (int i = 0; i < graph.degree(v); ++i)
            if (!used[static_cast<std::size_t>(graph.incidence(v, i)[1])]) walk(v, i);
    return chains;
}

}  // namespace hdimesh::hdi
