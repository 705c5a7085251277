// generate_refine_patterns: writes volume/refine/refine_patterns_table.inc, the table of every way
// a tetrahedron can be cut when some of its edges are split at their midpoints (the paper's §3,
// ../shared/docs/method.md §3), and proves every entry while doing so.
//
//   usage: generate_refine_patterns OUTPUT.inc
//
// Configurations. A split mask (6 bits, bit e = local edge e of volume/mesh/tet_tables.h is split)
// fixes each face's pattern, except that a face with exactly two split edges (a corner triangle
// plus a quad) has two quad diagonals: one bit per face chooses (bit f of `diagonals`, see
// face_triangles below). 239 = sum over masks of 2^(faces with two split edges).
//
// Local points: 0-3 the tet's vertices, 4+e the midpoint of edge e, 10 the Steiner point (the
// parent's centroid), used only when the sub-polyhedron cannot be tetrahedralized without one
// (Schönhardt configurations).
//
// Tetrahedralization: an exhaustive depth-first search over tets spanned by the local points,
// advancing a front of oriented triangles from the prescribed face triangulation. A candidate
// tet must be positive, contain no other local point (so children meet face to face), and have
// no interior overlap with the tets already placed (separating-axis test, exact). Iterative
// deepening on the tet count returns a tetrahedralization with the fewest tets. All arithmetic is
// on integers: the reference tet is (0,0,0) (4,0,0) (0,4,0) (0,0,4), so midpoints and the
// centroid have integer coordinates. Orientation is affine invariant, so a pattern valid on this
// tet is valid on every positive tet (with exact midpoints and centroid).
//
// Proof of each entry (independent of the search): every child tet positive; the children's
// volumes sum exactly to the parent's; the oriented boundary faces of the children, after
// cancelling each interior face against its opposite, are exactly the prescribed face
// triangles; no child contains another local point; children pairwise interior-disjoint.
// The generator exits non-zero if any proof fails or the counts differ from the verified facts
// (239 configurations, 14 with a Steiner point).

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "volume/mesh/tet_tables.h"
#include "volume/refine/refine_pattern_code.h"

namespace
{

using hdimesh::volume::face_split_count;
using hdimesh::volume::tet::kEdgeOfVertices;
using hdimesh::volume::tet::kEdgeVertices;
using hdimesh::volume::tet::kFaceEdges;
using hdimesh::volume::tet::kFaceVertices;

using IPoint = std::array<std::int64_t, 3>;
using LocalTet = std::array<int, 4>;
using LocalTriangle = std::array<int, 3>;

constexpr int kSteinerPoint = 10;
constexpr int kNumLocalPoints = 11;
constexpr std::int64_t kParentVolume6 = 64;  // det of the reference tet below

int midpoint_of(int edge) { return 4 + edge; }

std::array<IPoint, kNumLocalPoints> reference_points()
{
    std::array<IPoint, kNumLocalPoints> p{};
    p[0] = {0, 0, 0};
    p[1] = {4, 0, 0};
    p[2] = {0, 4, 0};
    p[3] = {0, 0, 4};
    for (int e = 0; e < 6; ++e)
        for (int k = 0; k < 3; ++k)
            p[midpoint_of(e)][k] = (p[kEdgeVertices[e][0]][k] + p[kEdgeVertices[e][1]][k]) / 2;
    for (int k = 0; k < 3; ++k) p[kSteinerPoint][k] = (p[0][k] + p[1][k] + p[2][k] + p[3][k]) / 4;
    return p;
}

const std::array<IPoint, kNumLocalPoints> kPoints = reference_points();

IPoint sub(const IPoint& a, const IPoint& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
IPoint cross(const IPoint& a, const IPoint& b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
std::int64_t dot(const IPoint& a, const IPoint& b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// Six times the signed volume, exact.
std::int64_t orient(int a, int b, int c, int d)
{
    return dot(sub(kPoints[b], kPoints[a]),
               cross(sub(kPoints[c], kPoints[a]), sub(kPoints[d], kPoints[a])));
}
std::int64_t orient(const LocalTet& t) { return orient(t[0], t[1], t[2], t[3]); }

/// True when local point p lies in the closed tet t and is not one of its vertices.
bool contains_other_point(const LocalTet& t, int p)
{
    if (std::find(t.begin(), t.end(), p) != t.end()) return false;
    return orient(p, t[1], t[2], t[3]) >= 0 && orient(t[0], p, t[2], t[3]) >= 0 &&
           orient(t[0], t[1], p, t[3]) >= 0 && orient(t[0], t[1], t[2], p) >= 0;
}

/// Exact separating-axis test for two positive tets: true when their interiors intersect.
bool interiors_overlap(const LocalTet& s, const LocalTet& t)
{
    std::vector<IPoint> axes;
    for (const LocalTet* tet : {&s, &t})
    {
        for (const auto& fv : kFaceVertices)
        {
            const IPoint& a = kPoints[(*tet)[fv[0]]];
            axes.push_back(cross(sub(kPoints[(*tet)[fv[1]]], a), sub(kPoints[(*tet)[fv[2]]], a)));
        }
    }
    for (const auto& es : kEdgeVertices)
        for (const auto& et : kEdgeVertices)
            axes.push_back(cross(sub(kPoints[s[es[1]]], kPoints[s[es[0]]]),
                                 sub(kPoints[t[et[1]]], kPoints[t[et[0]]])));
    for (const IPoint& axis : axes)
    {
        if (axis[0] == 0 && axis[1] == 0 && axis[2] == 0) continue;
        std::int64_t smin = INT64_MAX, smax = INT64_MIN, tmin = INT64_MAX, tmax = INT64_MIN;
        for (int k = 0; k < 4; ++k)
        {
            const std::int64_t ps = dot(axis, kPoints[s[k]]), pt = dot(axis, kPoints[t[k]]);
            smin = std::min(smin, ps), smax = std::max(smax, ps);
            tmin = std::min(tmin, pt), tmax = std::max(tmax, pt);
        }
        if (smax <= tmin || tmax <= smin) return false;  // touching is not overlapping
    }
    return true;
}

/// Rotation of an oriented triangle that starts at its smallest point (orientation kept).
LocalTriangle canonical(LocalTriangle t)
{
    while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
    return t;
}
LocalTriangle reversed(const LocalTriangle& t) { return canonical({t[0], t[2], t[1]}); }

/// The prescribed triangulation of face f (outward, local points). For a face with two split
/// edges meeting at corner c, with the other two vertices a < b (local ids): diagonal bit 0 joins
/// a to the midpoint of edge cb, bit 1 joins b to the midpoint of edge ca.
std::vector<LocalTriangle> face_triangles(int mask, int diagonals, int f)
{
    const auto& v = kFaceVertices[f];
    const auto& e = kFaceEdges[f];  // e[k] joins v[k] and v[k+1]
    std::vector<LocalTriangle> out;
    const int n = face_split_count(mask, f);
    if (n == 0)
        out.push_back({v[0], v[1], v[2]});
    else if (n == 1)
    {
        for (int k = 0; k < 3; ++k)
        {
            if (!((mask >> e[k]) & 1)) continue;
            const int m = midpoint_of(e[k]), o = v[(k + 2) % 3];
            out.push_back({v[k], m, o});
            out.push_back({m, v[(k + 1) % 3], o});
        }
    }
    else if (n == 3)
    {
        for (int k = 0; k < 3; ++k)
            out.push_back({v[k], midpoint_of(e[k]), midpoint_of(e[(k + 2) % 3])});
        out.push_back({midpoint_of(e[0]), midpoint_of(e[1]), midpoint_of(e[2])});
    }
    else
    {
        // corner v[k]: its two face edges e[k-1] (v[k-1] v[k]) and e[k] (v[k] v[k+1]) are split
        int k = 0;
        while (!(((mask >> e[k]) & 1) && ((mask >> e[(k + 2) % 3]) & 1))) ++k;
        const int c = v[k], a = v[(k + 1) % 3], b = v[(k + 2) % 3];  // counter-clockwise c, a, b
        const int mca = midpoint_of(e[k]), mcb = midpoint_of(e[(k + 2) % 3]);
        out.push_back({c, mca, mcb});
        const bool from_higher = (diagonals >> f) & 1;
        const int diagonal_vertex = from_higher ? std::max(a, b) : std::min(a, b);
        if (diagonal_vertex == a)
        {
            out.push_back({mca, a, mcb});
            out.push_back({a, b, mcb});
        }
        else
        {
            out.push_back({mca, a, b});
            out.push_back({mca, b, mcb});
        }
    }
    for (auto& t : out) t = canonical(t);
    return out;
}

struct Configuration
{
    int mask = 0;
    int diagonals = 0;
    std::vector<LocalTriangle> boundary;  // all faces' triangles, outward, canonical
    std::vector<int> points;              // local points available (vertices + split midpoints)
};

// --- the search ------------------------------------------------------------------------------

class Tetrahedralizer
{
public:
    Tetrahedralizer(const Configuration& config, bool with_steiner) : config_(config)
    {
        points_ = config.points;
        if (with_steiner) points_.push_back(kSteinerPoint);
    }

    /// The fewest-tets tetrahedralization, or empty when none exists.
    std::vector<LocalTet> solve()
    {
        max_tets_ = 64;  // every lattice tet has orient >= 1, the parent 64: a hard bound
        if (!search(config_.boundary)) return {};
        const std::size_t found = placed_best_.size();
        for (std::size_t limit = 1; limit < found; ++limit)
        {
            max_tets_ = static_cast<int>(limit);
            placed_.clear();
            if (search(config_.boundary)) return placed_best_;
        }
        return placed_best_;
    }

private:
    bool point_free(const LocalTet& t) const
    {
        for (int p : points_)
            if (contains_other_point(t, p)) return false;
        return true;
    }

    /// The front after placing tet t (whose face 3 closes front[i]); false if t would glue to the
    /// front from outside.
    bool advance(const std::vector<LocalTriangle>& front, const LocalTet& t,
                 std::vector<LocalTriangle>& next) const
    {
        next = front;
        for (int f = 0; f < 4; ++f)
        {
            const auto& fv = kFaceVertices[f];
            const LocalTriangle face = canonical({t[fv[0]], t[fv[1]], t[fv[2]]});
            auto same = std::find(next.begin(), next.end(), face);
            if (same != next.end())
            {
                next.erase(same);
                continue;
            }
            const LocalTriangle inward = reversed(face);
            if (std::find(next.begin(), next.end(), inward) != next.end()) return false;
            next.push_back(inward);
        }
        return true;
    }

    std::vector<LocalTet> candidates(const LocalTriangle& tri) const
    {
        std::vector<LocalTet> out;
        for (int p : points_)
        {
            if (p == tri[0] || p == tri[1] || p == tri[2]) continue;
            const LocalTet t = {tri[0], tri[2], tri[1], p};  // face 3 of t is tri, outward
            if (orient(t) <= 0 || !point_free(t)) continue;
            bool overlap = false;
            for (const auto& q : placed_)
                if (interiors_overlap(t, q))
                {
                    overlap = true;
                    break;
                }
            if (!overlap) out.push_back(t);
        }
        return out;
    }

    bool search(const std::vector<LocalTriangle>& front)
    {
        if (front.empty())
        {
            placed_best_ = placed_;
            return true;
        }
        const int placed = static_cast<int>(placed_.size());
        if (placed + (static_cast<int>(front.size()) + 3) / 4 > max_tets_) return false;
        // the most constrained front triangle first
        std::vector<LocalTet> best;
        bool have = false;
        for (const auto& tri : front)
        {
            auto c = candidates(tri);
            if (!have || c.size() < best.size())
            {
                best = std::move(c);
                have = true;
                if (best.empty()) return false;
            }
        }
        std::vector<LocalTriangle> next;
        for (const auto& t : best)
        {
            if (!advance(front, t, next)) continue;
            placed_.push_back(t);
            if (search(next)) return true;
            placed_.pop_back();
        }
        return false;
    }

    const Configuration& config_;
    std::vector<int> points_;
    std::vector<LocalTet> placed_, placed_best_;
    int max_tets_ = 64;
};

// --- the proof -------------------------------------------------------------------------------

/// Returns an empty string when the tets are a valid tetrahedralization of the configuration.
std::string prove(const Configuration& config, const std::vector<LocalTet>& tets, bool steiner)
{
    std::vector<int> points = config.points;
    if (steiner) points.push_back(kSteinerPoint);
    std::int64_t volume = 0;
    std::map<LocalTriangle, int> chain;  // oriented triangle -> multiplicity
    for (const auto& t : tets)
    {
        if (orient(t) <= 0) return "a child tet is not positive";
        volume += orient(t);
        for (int p : points)
            if (contains_other_point(t, p)) return "a child contains another local point";
        for (int f = 0; f < 4; ++f)
        {
            const auto& fv = kFaceVertices[f];
            const LocalTriangle face = canonical({t[fv[0]], t[fv[1]], t[fv[2]]});
            const LocalTriangle back = reversed(face);
            auto it = chain.find(back);
            if (it != chain.end())
            {
                if (--it->second == 0) chain.erase(it);
            }
            else
                ++chain[face];
        }
    }
    if (volume != kParentVolume6) return "children volumes do not sum to the parent's";
    std::map<LocalTriangle, int> expected;
    for (const auto& tri : config.boundary) ++expected[tri];
    if (chain != expected)
        return "the children's boundary is not the prescribed face triangulation";
    for (std::size_t i = 0; i < tets.size(); ++i)
        for (std::size_t j = i + 1; j < tets.size(); ++j)
            if (interiors_overlap(tets[i], tets[j])) return "two children overlap";
    return {};
}

/// The rule of method.md: a configuration has no tetrahedralization iff it has quads and every
/// midpoint on a quad is the end of exactly one diagonal.
bool schonhardt_by_rule(int mask, int diagonals)
{
    std::array<int, 10> diagonal_ends{};
    std::array<bool, 10> on_quad{};
    bool any_quad = false;
    for (int f = 0; f < 4; ++f)
    {
        if (face_split_count(mask, f) != 2) continue;
        any_quad = true;
        for (const auto& tri : face_triangles(mask, diagonals, f))
            for (int p : tri)
                if (p >= 4) on_quad[p] = true;
        // the diagonal is the one edge vertex->midpoint shared by the two quad triangles
        const auto tris = face_triangles(mask, diagonals, f);
        for (int p : tris[1])
            if (p >= 4 && std::find(tris[2].begin(), tris[2].end(), p) != tris[2].end())
                ++diagonal_ends[p];
    }
    if (!any_quad) return false;
    for (int p = 4; p < 10; ++p)
        if (on_quad[p] && diagonal_ends[p] != 1) return false;
    return true;
}

/// The lexicographically smallest even permutation of t (same orientation), for a readable table.
LocalTet smallest_even_permutation(const LocalTet& t)
{
    LocalTet best = t;
    std::array<int, 4> order = {0, 1, 2, 3};
    do
    {
        int inversions = 0;
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) inversions += order[i] > order[j];
        if (inversions % 2) continue;
        const LocalTet candidate = {t[order[0]], t[order[1]], t[order[2]], t[order[3]]};
        best = std::min(best, candidate);
    } while (std::next_permutation(order.begin(), order.end()));
    return best;
}

struct Entry
{
    int mask, diagonals, code;
    bool steiner;
    std::vector<LocalTet> tets;
    std::vector<LocalTriangle> boundary;
};

/// One table row of local tets or triangles: "    {a, b, c, d}, {..},", no line end.
template <std::size_t N>
void write_row(std::ostringstream& out, const std::vector<std::array<int, N>>& items)
{
    out << "    ";
    for (std::size_t i = 0; i < items.size(); ++i)
    {
        out << (i ? " " : "") << "{";
        for (std::size_t k = 0; k < N; ++k) out << (k ? ", " : "") << items[i][k];
        out << "},";
    }
}

std::string format_table(const std::vector<Entry>& entries)
{
    std::ostringstream out;
    int num_tets = 0, num_triangles = 0;
    for (const auto& e : entries)
    {
        num_tets += static_cast<int>(e.tets.size());
        num_triangles += static_cast<int>(e.boundary.size());
    }
    out << "// GENERATED by volume/tools/generate_refine_patterns.cpp -- do not edit.\n"
           "// Regenerate: generate_refine_patterns volume/refine/refine_patterns_table.inc\n"
           "// (tests/cmake/refine.cmake checks this file is exactly what the generator writes).\n"
           "//\n"
           "// Every configuration of a tet with split edges, each proven by the generator on the\n"
           "// reference tet in exact integer arithmetic: children positive, volumes summing to "
           "the\n"
           "// parent's, boundary equal to the prescribed face triangulations.\n"
           "// Local points: 0-3 vertices, 4+e midpoint of edge e, 10 Steiner point (centroid).\n"
           "// Included by volume/refine/refine_patterns.cpp only.\n\n";
    out << "constexpr int kTableNumPatterns = " << entries.size() << ";\n";
    out << "constexpr int kTableNumTets = " << num_tets << ";\n";
    out << "constexpr int kTableNumTriangles = " << num_triangles << ";\n\n";
    out << "// mask, diagonals, paper code, steiner, first tet, tet count, first triangle, "
           "triangle count\n";
    out << "constexpr PatternRecord kTablePatterns[kTableNumPatterns] = {\n";
    int first_tet = 0, first_triangle = 0;
    for (const auto& e : entries)
    {
        out << "    {" << e.mask << ", " << e.diagonals << ", " << e.code << ", "
            << (e.steiner ? 1 : 0) << ", " << first_tet << ", " << e.tets.size() << ", "
            << first_triangle << ", " << e.boundary.size() << "},\n";
        first_tet += static_cast<int>(e.tets.size());
        first_triangle += static_cast<int>(e.boundary.size());
    }
    out << "};\n\n";
    out << "constexpr std::uint8_t kTableTets[kTableNumTets][4] = {\n";
    for (const auto& e : entries)
    {
        write_row(out, e.tets);
        out << "  // mask " << e.mask << " diagonals " << e.diagonals << "\n";
    }
    out << "};\n\n";
    out << "constexpr std::uint8_t kTableTriangles[kTableNumTriangles][3] = {\n";
    for (const auto& e : entries)
    {
        write_row(out, e.boundary);
        out << "\n";
    }
    out << "};\n";
    return out.str();
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 2)
    {
        std::cerr << "usage: generate_refine_patterns OUTPUT.inc\n";
        return 2;
    }
    std::vector<Entry> entries;
    int steiner_star = 0, steiner_cycle = 0;
    for (int mask = 0; mask < 64; ++mask)  // mask 0: nothing split, the tet itself
    {
        int free_faces = 0;  // faces with two split edges
        for (int f = 0; f < 4; ++f) free_faces |= (face_split_count(mask, f) == 2) << f;
        for (int diagonals = 0; diagonals < 16; ++diagonals)
        {
            if (diagonals & ~free_faces) continue;
            Configuration config;
            config.mask = mask;
            config.diagonals = diagonals;
            for (int v = 0; v < 4; ++v) config.points.push_back(v);
            for (int e = 0; e < 6; ++e)
                if ((mask >> e) & 1) config.points.push_back(midpoint_of(e));
            for (int f = 0; f < 4; ++f)
                for (const auto& t : face_triangles(mask, diagonals, f))
                    config.boundary.push_back(t);

            const int code = hdimesh::volume::paper_pattern_code(mask, diagonals);
            Entry entry{mask, diagonals, code, false, {}, config.boundary};
            entry.tets = Tetrahedralizer(config, false).solve();
            if (entry.tets.empty())
            {
                entry.steiner = true;
                entry.tets = Tetrahedralizer(config, true).solve();
                int split = 0;
                for (int e = 0; e < 6; ++e) split += (mask >> e) & 1;
                (split == 3 ? steiner_star : steiner_cycle) += 1;
            }
            if (entry.tets.empty())
            {
                std::cerr << "mask " << mask << " diagonals " << diagonals
                          << ": no tetrahedralization even with the centroid\n";
                return 1;
            }
            if (entry.steiner != schonhardt_by_rule(mask, diagonals))
            {
                std::cerr << "mask " << mask << " diagonals " << diagonals
                          << ": search and the Schönhardt rule disagree\n";
                return 1;
            }
            const std::string failure = prove(config, entry.tets, entry.steiner);
            if (!failure.empty())
            {
                std::cerr << "mask " << mask << " diagonals " << diagonals << ": " << failure
                          << "\n";
                return 1;
            }
            for (auto& t : entry.tets) t = smallest_even_permutation(t);
            std::sort(entry.tets.begin(), entry.tets.end());
            entries.push_back(std::move(entry));
        }
    }
    const int configurations = static_cast<int>(entries.size());
    if (configurations != 239 || steiner_star != 8 || steiner_cycle != 6)
    {
        std::cerr << "counts differ from the verified facts: " << configurations
                  << " configurations, " << steiner_star << " star and " << steiner_cycle
                  << " four-cycle Steiner configurations\n";
        return 1;
    }
    std::vector<int> codes;
    for (const auto& e : entries) codes.push_back(e.code);
    std::sort(codes.begin(), codes.end());
    if (std::adjacent_find(codes.begin(), codes.end()) != codes.end())
    {
        std::cerr << "the paper's code is not unique per configuration\n";
        return 1;
    }

    const std::string text = format_table(entries);
    const std::string path = argv[1];
    const std::string temporary = path + ".tmp";
    {
        std::ofstream file(temporary, std::ios::binary);
        file << text;
        if (!file)
        {
            std::cerr << "cannot write " << temporary << "\n";
            return 1;
        }
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0)
    {
        std::cerr << "cannot rename " << temporary << " to " << path << "\n";
        return 1;
    }
    std::cout << "wrote " << path << ": " << configurations << " configurations, "
              << steiner_star + steiner_cycle << " with a Steiner point\n";
    return 0;
}
