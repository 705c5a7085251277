// Validation of a closed triangle surface: sorted edge records for the topology, a uniform grid
// of face boxes and the exact predicates for the geometry.
#include "volume/check/surface_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <tuple>

#include "common/errors.h"
#include "volume/mesh/predicates.h"

namespace hdimesh::volume
{

const char* to_string(SurfaceDefectKind kind)
{
    switch (kind)
    {
        case SurfaceDefectKind::VertexOutOfRange: return "vertex_out_of_range";
        case SurfaceDefectKind::DegenerateFace: return "degenerate_face";
        case SurfaceDefectKind::DuplicateFace: return "duplicate_face";
        case SurfaceDefectKind::OpenBoundary: return "open_boundary";
        case SurfaceDefectKind::NonManifoldEdge: return "non_manifold_edge";
        case SurfaceDefectKind::InconsistentOrientation: return "inconsistent_orientation";
        case SurfaceDefectKind::NonManifoldVertex: return "non_manifold_vertex";
        case SurfaceDefectKind::SelfIntersection: return "self_intersection";
    }
    return "?";
}

namespace
{

/// One face's use of an undirected edge (a < b); `forward`: the face goes a -> b.
struct EdgeUse
{
    int a, b, face;
    bool forward;
    bool operator<(const EdgeUse& o) const
    {
        return std::tie(a, b, face) < std::tie(o.a, o.b, o.face);
    }
};

/// Union-find over small index ranges, smaller root kept (deterministic).
struct DisjointSets
{
    std::vector<int> parent;
    explicit DisjointSets(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int i)
    {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    }
    void unite(int i, int j)
    {
        i = find(i);
        j = find(j);
        if (i != j) parent[std::max(i, j)] = std::min(i, j);
    }
};

bool is_zero_area(const std::vector<Vec3>& points, const Triangle& t)
{
    // collinear exactly when every coordinate-plane projection is
    for (int drop = 0; drop < 3; ++drop)
        if (orient2d(points[t[0]], points[t[1]], points[t[2]], drop) != 0) return false;
    return true;
}

/// The boundary edges chained into loops (or open chains at a pinch): an undirected walk
/// that always leaves a vertex by its unused edge of smallest id.
void add_boundary_loops(const std::vector<EdgeUse>& boundary, std::vector<SurfaceDefect>& out)
{
    const int n = static_cast<int>(boundary.size());
    // per vertex, the boundary edges at it: (vertex, edge) sorted
    std::vector<std::pair<int, int>> at;
    at.reserve(2 * n);
    for (int e = 0; e < n; ++e)
    {
        at.push_back({boundary[e].a, e});
        at.push_back({boundary[e].b, e});
    }
    std::sort(at.begin(), at.end());
    auto edges_at = [&](int v) {
        const auto lo = std::lower_bound(at.begin(), at.end(), std::make_pair(v, -1));
        auto hi = lo;
        while (hi != at.end() && hi->first == v) ++hi;
        return std::make_pair(lo, hi);
    };
    std::vector<char> used(n, 0);
    for (int start = 0; start < n; ++start)
    {
        if (used[start]) continue;
        SurfaceDefect loop{SurfaceDefectKind::OpenBoundary, {}, {}};
        // walk in the face's direction so the loop reads as the surface's boundary
        const EdgeUse& first = boundary[start];
        const int origin = first.forward ? first.a : first.b;
        int current = first.forward ? first.b : first.a;
        used[start] = 1;
        loop.vertices.push_back(origin);
        loop.faces.push_back(first.face);
        while (current != origin)
        {
            loop.vertices.push_back(current);
            int next = -1;
            const auto [lo, hi] = edges_at(current);
            for (auto it = lo; it != hi; ++it)
                if (!used[it->second])
                {
                    next = it->second;
                    break;
                }
            if (next < 0) break;  // an open chain (the walk met a pinch)
            used[next] = 1;
            loop.faces.push_back(boundary[next].face);
            current = boundary[next].a == current ? boundary[next].b : boundary[next].a;
        }
        out.push_back(std::move(loop));
    }
}

/// The faces at each vertex that make more than one fan (connected through edges at it).
void add_pinched_vertices(int num_points, const std::vector<Triangle>& triangles,
                          const std::vector<char>& skip, std::vector<SurfaceDefect>& out)
{
    std::vector<int> offsets(num_points + 1, 0);
    for (std::size_t f = 0; f < triangles.size(); ++f)
        if (!skip[f])
            for (int v : triangles[f]) ++offsets[v + 1];
    std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
    std::vector<int> faces_at(offsets.back());
    std::vector<int> fill(offsets.begin(), offsets.end() - 1);
    for (std::size_t f = 0; f < triangles.size(); ++f)
        if (!skip[f])
            for (int v : triangles[f]) faces_at[fill[v]++] = static_cast<int>(f);

    std::vector<std::pair<int, int>> others;  // (other vertex, local face)
    for (int v = 0; v < num_points; ++v)
    {
        const int begin = offsets[v], count = offsets[v + 1] - begin;
        if (count < 2) continue;
        others.clear();
        for (int i = 0; i < count; ++i)
            for (int w : triangles[faces_at[begin + i]])
                if (w != v) others.push_back({w, i});
        std::sort(others.begin(), others.end());
        DisjointSets fans(count);
        for (std::size_t k = 1; k < others.size(); ++k)
            if (others[k].first == others[k - 1].first)
                fans.unite(others[k].second, others[k - 1].second);
        int roots = 0;
        for (int i = 0; i < count; ++i) roots += fans.find(i) == i;
        if (roots > 1)
        {
            SurfaceDefect pinch{SurfaceDefectKind::NonManifoldVertex, {}, {v}};
            pinch.faces.assign(faces_at.begin() + begin, faces_at.begin() + begin + count);
            out.push_back(std::move(pinch));
        }
    }
}

struct Box
{
    Vec3 lo, hi;
};

/// Pairs of faces that meet, from a uniform grid of their boxes: each pair is tested in the
/// one cell holding the low corner of the two boxes' overlap.
void add_self_intersections(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                            const std::vector<char>& skip, int max_pairs, Workers* workers,
                            std::vector<SurfaceDefect>& out)
{
    std::vector<int> faces;
    for (std::size_t f = 0; f < triangles.size(); ++f)
        if (!skip[f]) faces.push_back(static_cast<int>(f));
    if (faces.size() < 2) return;
    std::vector<Box> boxes(triangles.size());
    Box all{Vec3::Constant(std::numeric_limits<double>::infinity()),
            Vec3::Constant(-std::numeric_limits<double>::infinity())};
    double extent_sum = 0;
    for (int f : faces)
    {
        const auto& t = triangles[f];
        Box& b = boxes[f];
        b.lo = points[t[0]].cwiseMin(points[t[1]]).cwiseMin(points[t[2]]);
        b.hi = points[t[0]].cwiseMax(points[t[1]]).cwiseMax(points[t[2]]);
        all.lo = all.lo.cwiseMin(b.lo);
        all.hi = all.hi.cwiseMax(b.hi);
        extent_sum += (b.hi - b.lo).maxCoeff();
    }
    const Vec3 span = all.hi - all.lo;
    // cells about one face wide, but never more than a few per face
    double cell = extent_sum / faces.size();
    const double max_cells = 4.0 * faces.size();
    const double span_max = span.maxCoeff();
    if (!(cell > 0)) cell = span_max > 0 ? span_max : 1.0;
    auto cells_for = [&](double c) {
        double n = 1;
        for (int k = 0; k < 3; ++k) n *= std::floor(span[k] / c) + 1;
        return n;
    };
    while (cells_for(cell) > max_cells) cell *= 1.5;
    std::array<std::int64_t, 3> dims;
    for (int k = 0; k < 3; ++k) dims[k] = static_cast<std::int64_t>(std::floor(span[k] / cell)) + 1;
    auto index = [&](double x, int k) {
        const auto i = static_cast<std::int64_t>(std::floor((x - all.lo[k]) / cell));
        return std::clamp<std::int64_t>(i, 0, dims[k] - 1);
    };
    auto key = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
        return i + dims[0] * (j + dims[1] * k);
    };

    std::vector<std::pair<std::int64_t, int>> entries;  // (cell, face)
    for (int f : faces)
    {
        const Box& b = boxes[f];
        for (std::int64_t k = index(b.lo[2], 2); k <= index(b.hi[2], 2); ++k)
            for (std::int64_t j = index(b.lo[1], 1); j <= index(b.hi[1], 1); ++j)
                for (std::int64_t i = index(b.lo[0], 0); i <= index(b.hi[0], 0); ++i)
                    entries.push_back({key(i, j, k), f});
    }
    std::sort(entries.begin(), entries.end());

    // the cells' pair tests are independent: run on the workers, then taken in cell order
    // with the serial cut-off, so the pairs found are the same for any number of threads
    std::vector<std::size_t> starts;
    for (std::size_t begin = 0; begin < entries.size();)
    {
        starts.push_back(begin);
        std::size_t end = begin;
        while (end < entries.size() && entries[end].first == entries[begin].first) ++end;
        begin = end;
    }
    starts.push_back(entries.size());
    std::vector<std::vector<std::pair<int, int>>> found(starts.size() - 1);
    parallel_for(
        workers, found.size(),
        [&](std::size_t first, std::size_t last) {
            for (std::size_t c = first; c < last; ++c)
                for (std::size_t x = starts[c]; x < starts[c + 1]; ++x)
                    for (std::size_t y = x + 1; y < starts[c + 1]; ++y)
                    {
                        const int f = entries[x].second, g = entries[y].second;
                        const Box &bf = boxes[f], &bg = boxes[g];
                        if ((bf.lo.array() > bg.hi.array()).any() ||
                            (bg.lo.array() > bf.hi.array()).any())
                            continue;
                        const Vec3 corner = bf.lo.cwiseMax(bg.lo);
                        if (key(index(corner[0], 0), index(corner[1], 1), index(corner[2], 2)) !=
                            entries[starts[c]].first)
                            continue;
                        if (triangles_intersect(points, triangles[f], triangles[g]))
                            found[c].push_back({std::min(f, g), std::max(f, g)});
                    }
        },
        64);
    std::vector<std::pair<int, int>> crossing;
    for (const auto& pairs : found)
    {
        crossing.insert(crossing.end(), pairs.begin(), pairs.end());
        if (static_cast<int>(crossing.size()) >= max_pairs) break;
    }
    std::sort(crossing.begin(), crossing.end());
    if (static_cast<int>(crossing.size()) > max_pairs) crossing.resize(max_pairs);
    for (const auto& [f, g] : crossing)
        out.push_back({SurfaceDefectKind::SelfIntersection, {f, g}, {}});
}

}  // namespace

std::vector<SurfaceDefect> check_closed_surface(const std::vector<Vec3>& points,
                                                const std::vector<Triangle>& triangles,
                                                const SurfaceCheckOptions& options)
{
    std::vector<SurfaceDefect> defects;
    const int num_points = static_cast<int>(points.size());
    const int num_faces = static_cast<int>(triangles.size());
    for (int f = 0; f < num_faces; ++f)
        for (int v : triangles[f])
            if (v < 0 || v >= num_points)
                defects.push_back({SurfaceDefectKind::VertexOutOfRange, {f}, {v}});
    if (!defects.empty()) return defects;  // nothing else can be looked at safely

    // faces left out of the later checks: a repeated vertex, a later copy of a face
    std::vector<char> skip(num_faces, 0);
    std::vector<char> flat(num_faces, 0);
    for (int f = 0; f < num_faces; ++f)
    {
        const auto& t = triangles[f];
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            skip[f] = 1;
        else if (is_zero_area(points, t))
            flat[f] = 1;
        if (skip[f] || flat[f])
            defects.push_back({SurfaceDefectKind::DegenerateFace, {f}, {t[0], t[1], t[2]}});
    }

    std::vector<std::pair<Triangle, int>> sorted_faces;
    sorted_faces.reserve(num_faces);
    for (int f = 0; f < num_faces; ++f)
    {
        if (skip[f]) continue;
        Triangle key = triangles[f];
        std::sort(key.begin(), key.end());
        sorted_faces.push_back({key, f});
    }
    std::sort(sorted_faces.begin(), sorted_faces.end());
    for (std::size_t begin = 0; begin < sorted_faces.size();)
    {
        std::size_t end = begin + 1;
        while (end < sorted_faces.size() && sorted_faces[end].first == sorted_faces[begin].first)
            ++end;
        if (end - begin > 1)
        {
            SurfaceDefect copies{SurfaceDefectKind::DuplicateFace, {}, {}};
            const Triangle& t = triangles[sorted_faces[begin].second];
            copies.vertices = {t[0], t[1], t[2]};
            for (std::size_t k = begin; k < end; ++k)
            {
                copies.faces.push_back(sorted_faces[k].second);
                if (k > begin) skip[sorted_faces[k].second] = 1;
            }
            defects.push_back(std::move(copies));
        }
        begin = end;
    }

    std::vector<EdgeUse> uses;
    uses.reserve(3 * static_cast<std::size_t>(num_faces));
    for (int f = 0; f < num_faces; ++f)
    {
        if (skip[f]) continue;
        for (int k = 0; k < 3; ++k)
        {
            const int a = triangles[f][k], b = triangles[f][(k + 1) % 3];
            uses.push_back({std::min(a, b), std::max(a, b), f, a < b});
        }
    }
    std::sort(uses.begin(), uses.end());
    std::vector<EdgeUse> boundary;
    for (std::size_t begin = 0; begin < uses.size();)
    {
        std::size_t end = begin + 1;
        while (end < uses.size() && uses[end].a == uses[begin].a && uses[end].b == uses[begin].b)
            ++end;
        const EdgeUse& e = uses[begin];
        if (end - begin == 1)
            boundary.push_back(e);
        else if (end - begin > 2 || uses[begin].forward == uses[begin + 1].forward)
        {
            SurfaceDefect bad{end - begin > 2 ? SurfaceDefectKind::NonManifoldEdge
                                              : SurfaceDefectKind::InconsistentOrientation,
                              {},
                              {e.a, e.b}};
            for (std::size_t k = begin; k < end; ++k) bad.faces.push_back(uses[k].face);
            defects.push_back(std::move(bad));
        }
        begin = end;
    }
    add_boundary_loops(boundary, defects);
    add_pinched_vertices(num_points, triangles, skip, defects);

    if (options.check_self_intersections)
    {
        std::vector<char> not_tested = skip;
        for (int f = 0; f < num_faces; ++f) not_tested[f] |= flat[f];
        add_self_intersections(points, triangles, not_tested,
                               std::max(1, options.max_intersections), options.workers, defects);
    }
    std::stable_sort(
        defects.begin(), defects.end(),
        [](const SurfaceDefect& x, const SurfaceDefect& y) { return x.kind < y.kind; });
    return defects;
}

namespace
{

std::string one_based(int id) { return std::to_string(static_cast<long long>(id) + 1); }

/// "10, 11, 12, ..." with at most `limit` ids.
std::string id_list(const std::vector<int>& ids, std::size_t limit, const char* separator = ", ")
{
    std::string text;
    for (std::size_t i = 0; i < ids.size() && i < limit; ++i)
        text += (i ? separator : "") + one_based(ids[i]);
    if (ids.size() > limit) text += std::string(separator) + "...";
    return text;
}

std::string plural(std::size_t n, const std::string& singular, const std::string& plural_form)
{
    return std::to_string(n) + " " + (n == 1 ? singular : plural_form);
}

std::string describe(const SurfaceDefect& d)
{
    switch (d.kind)
    {
        case SurfaceDefectKind::VertexOutOfRange:
            return "triangle " + one_based(d.faces[0]) + " names vertex " +
                   one_based(d.vertices[0]);
        case SurfaceDefectKind::DegenerateFace:
            return "triangle " + one_based(d.faces[0]) + " (vertices " +
                   id_list(d.vertices, 3, " ") + ")";
        case SurfaceDefectKind::DuplicateFace:
            return "triangles " + id_list(d.faces, 4) + " (vertices " +
                   id_list(d.vertices, 3, " ") + ")";
        case SurfaceDefectKind::OpenBoundary:
            return plural(d.faces.size(), "edge", "edges") + " through vertices " +
                   id_list(d.vertices, 8);
        case SurfaceDefectKind::NonManifoldEdge:
        case SurfaceDefectKind::InconsistentOrientation:
            return "edge " + one_based(d.vertices[0]) + "-" + one_based(d.vertices[1]) +
                   " in triangles " + id_list(d.faces, 6);
        case SurfaceDefectKind::NonManifoldVertex:
            return "vertex " + one_based(d.vertices[0]) + " (triangles " + id_list(d.faces, 8) +
                   ")";
        case SurfaceDefectKind::SelfIntersection:
            return "triangles " + one_based(d.faces[0]) + " and " + one_based(d.faces[1]);
    }
    return "?";
}

std::string headline(SurfaceDefectKind kind, std::size_t n)
{
    switch (kind)
    {
        case SurfaceDefectKind::VertexOutOfRange:
            return "a triangle names a vertex that does not exist: " +
                   plural(n, "bad id", "bad ids");
        case SurfaceDefectKind::DegenerateFace:
            return plural(n, "degenerate (zero-area) triangle", "degenerate (zero-area) triangles");
        case SurfaceDefectKind::DuplicateFace:
            return plural(n, "duplicated triangle", "duplicated triangles") +
                   " (the same three vertices)";
        case SurfaceDefectKind::OpenBoundary:
            return "the surface is open: " + plural(n, "boundary loop", "boundary loops");
        case SurfaceDefectKind::NonManifoldEdge:
            return plural(n, "non-manifold edge", "non-manifold edges") +
                   " (in three or more triangles)";
        case SurfaceDefectKind::InconsistentOrientation:
            return "inconsistent orientation: " + plural(n, "edge is", "edges are") +
                   " traversed the same way by both triangles";
        case SurfaceDefectKind::NonManifoldVertex:
            return plural(n, "pinched (non-manifold) vertex", "pinched (non-manifold) vertices") +
                   " where separate fans of triangles meet";
        case SurfaceDefectKind::SelfIntersection:
            return "the surface intersects itself: " +
                   plural(n, "pair of triangles meets", "pairs of triangles meet");
    }
    return "?";
}

}  // namespace

std::string format_surface_defects(const std::vector<SurfaceDefect>& defects,
                                   const std::string& source, int max_listed)
{
    if (defects.empty()) return {};
    std::vector<std::string> lines;
    for (int kind = 0; kind < kNumSurfaceDefectKinds; ++kind)
    {
        std::vector<const SurfaceDefect*> of_kind;
        for (const auto& d : defects)
            if (static_cast<int>(d.kind) == kind) of_kind.push_back(&d);
        if (of_kind.empty()) continue;
        const bool loops = static_cast<SurfaceDefectKind>(kind) == SurfaceDefectKind::OpenBoundary;
        std::string line = headline(static_cast<SurfaceDefectKind>(kind), of_kind.size()) + " (";
        for (std::size_t i = 0; i < of_kind.size() && static_cast<int>(i) < max_listed; ++i)
            line += (i ? "; " : "") + (loops ? "loop " + std::to_string(i + 1) + ": " : "") +
                    describe(*of_kind[i]);
        if (static_cast<int>(of_kind.size()) > max_listed) line += "; ...";
        lines.push_back(line + ")");
    }
    const std::string prefix = source.empty() ? "" : source + ": ";
    if (lines.size() == 1) return prefix + lines[0];
    std::string message = prefix + "the surface cannot bound a volume:";
    for (const auto& line : lines) message += "\n  " + line;
    return message;
}

void require_closed_surface(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                            const std::string& source, const SurfaceCheckOptions& options)
{
    const auto defects = check_closed_surface(points, triangles, options);
    if (!defects.empty()) throw InputError(format_surface_defects(defects, source));
}

int merge_coincident_points(const std::vector<Vec3>& points, std::vector<Triangle>& triangles)
{
    std::vector<int> order(points.size());
    std::iota(order.begin(), order.end(), 0);
    auto coordinates = [&](int i) {
        return std::array<double, 3>{points[i][0], points[i][1], points[i][2]};
    };
    std::sort(order.begin(), order.end(), [&](int i, int j) {
        return std::make_pair(coordinates(i), i) < std::make_pair(coordinates(j), j);
    });
    std::vector<int> first(points.size());
    int renamed_points = 0;
    for (std::size_t k = 0; k < order.size(); ++k)
    {
        const bool same = k > 0 && coordinates(order[k]) == coordinates(order[k - 1]);
        first[order[k]] = same ? first[order[k - 1]] : order[k];
    }
    std::vector<char> renamed(points.size(), 0);
    for (auto& t : triangles)
        for (int& v : t)
            if (v >= 0 && v < static_cast<int>(points.size()) && first[v] != v)
            {
                if (!renamed[v]) ++renamed_points;
                renamed[v] = 1;
                v = first[v];
            }
    return renamed_points;
}

}  // namespace hdimesh::volume
