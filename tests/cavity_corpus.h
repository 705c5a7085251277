#pragma once
// The cavity corpus of issue 15, built in code: closed, outward-oriented triangle sets over a
// small point array, the input of the cavity stages (tests/cavity_stages_test.cpp and
// bench/bench_cavity.cpp share it). Every builder checks that its surface is closed: each
// directed edge has its reverse exactly once.

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "volume/mesh/geometry.h"
#include "volume/mesh/tet_mesh.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::cavity_corpus
{

using volume::Triangle;
using volume::Vec3;

struct Cavity
{
    std::string name;
    std::vector<Vec3> points;
    std::vector<Triangle> faces;
};

constexpr double kPi = 3.14159265358979323846;

/// Throws unless every directed edge of the faces has its reverse exactly once.
inline void require_closed(const Cavity& cavity)
{
    std::map<std::pair<int, int>, int> directed;
    for (const auto& f : cavity.faces)
        for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
    for (const auto& [edge, count] : directed)
    {
        const auto reverse = directed.find({edge.second, edge.first});
        if (count != 1 || reverse == directed.end() || reverse->second != 1)
            throw std::logic_error(cavity.name + ": not closed at edge " +
                                   std::to_string(edge.first) + "-" + std::to_string(edge.second));
    }
}

/// The volume the faces enclose (divergence theorem, about the points' mean for accuracy).
inline double enclosed_volume(const std::vector<Vec3>& points, const std::vector<Triangle>& faces)
{
    Vec3 origin = Vec3::Zero();
    for (const auto& p : points) origin += p;
    origin /= static_cast<double>(std::max<std::size_t>(points.size(), 1));
    double volume = 0;
    for (const auto& f : faces)
        volume += volume::signed_volume(origin, points[f[0]], points[f[1]], points[f[2]]);
    return volume;
}

/// Quad a b c d, counter-clockwise seen from outside, as two triangles split at a-c (or b-d).
inline void add_quad(std::vector<Triangle>& faces, int a, int b, int c, int d, bool split_ac)
{
    if (split_ac)
    {
        faces.push_back({a, b, c});
        faces.push_back({a, c, d});
    }
    else
    {
        faces.push_back({a, b, d});
        faces.push_back({b, c, d});
    }
}

/// A planar simple polygon (vertex ids, either direction) as triangles counter-clockwise about
/// `outward`: ear clipping, the ear with the smallest position first.
inline void add_polygon(std::vector<Triangle>& faces, const std::vector<Vec3>& points,
                        std::vector<int> loop, const Vec3& outward)
{
    const Vec3 u = outward.unitOrthogonal();
    const Vec3 v = outward.normalized().cross(u);
    auto cross2 = [&](int a, int b, int c) {
        const Vec3 ab = points[b] - points[a], ac = points[c] - points[a];
        return ab.dot(u) * ac.dot(v) - ab.dot(v) * ac.dot(u);
    };
    double twice_area = 0;
    for (std::size_t i = 0; i < loop.size(); ++i)
        twice_area += cross2(loop[0], loop[i], loop[(i + 1) % loop.size()]);
    if (twice_area < 0) std::reverse(loop.begin(), loop.end());
    while (loop.size() > 3)
    {
        const std::size_t n = loop.size();
        bool clipped = false;
        for (std::size_t i = 0; i < n && !clipped; ++i)
        {
            const int a = loop[(i + n - 1) % n], b = loop[i], c = loop[(i + 1) % n];
            if (cross2(a, b, c) <= 1e-12) continue;
            bool empty = true;
            for (int p : loop)
                if (p != a && p != b && p != c && cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 &&
                    cross2(c, a, p) >= 0)
                    empty = false;
            if (!empty) continue;
            faces.push_back({a, b, c});
            loop.erase(loop.begin() + static_cast<std::ptrdiff_t>(i));
            clipped = true;
        }
        if (!clipped) throw std::logic_error("add_polygon: no ear");
    }
    faces.push_back({loop[0], loop[1], loop[2]});
}

/// The outward faces of the positive tet (0,0,0) (1,0,0) (0,1,0) (0,0,1).
inline Cavity single_tet()
{
    Cavity c{"tet", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {}};
    for (const auto& fv : volume::tet::kFaceVertices) c.faces.push_back({fv[0], fv[1], fv[2]});
    require_closed(c);
    return c;
}

/*  Prisms over an n-gon: bottom ring b_i in z = 0, top ring t_i in z = height rotated by
    `twist` about the z axis; lateral quad i is b_i b_i+1 t_i+1 t_i.

          t2 ______ t1          twisted (Schönhardt for n = 3): every quad is split by the
            /\    /\            diagonal that folds inwards, so all n lateral diagonals are
           /  \  /  \           reflex and no tet of the points alone fits in a corner;
          /    \/    \          convex: the other diagonal of every quad (a polyhedron that
        b2 ---- t0 --- b1       stays fillable without a new point).
            \        /
             \  b0  /
    Caps: the n-gons fanned from b_0 and t_0.                                                   */
inline Cavity prism(int n, double twist, double height, bool reflex_diagonals)
{
    Cavity c;
    c.name = (reflex_diagonals ? "twisted prism n=" : "convex prism n=") + std::to_string(n);
    for (int i = 0; i < n; ++i)
    {
        const double angle = 2 * kPi * i / n;
        c.points.push_back({std::cos(angle), std::sin(angle), 0});
    }
    for (int i = 0; i < n; ++i)
    {
        const double angle = 2 * kPi * i / n + twist;
        c.points.push_back({std::cos(angle), std::sin(angle), height});
    }
    for (int i = 1; i + 1 < n; ++i) c.faces.push_back({0, i + 1, i});
    for (int i = 1; i + 1 < n; ++i) c.faces.push_back({n, n + i, n + i + 1});
    for (int i = 0; i < n; ++i)
    {
        const int b0 = i, b1 = (i + 1) % n, t1 = n + (i + 1) % n, t0 = n + i;
        // diagonal b0-t1 is reflex when t0 lies outside triangle b0 b1 t1
        const bool b0t1_reflex =
            volume::signed_volume6(c.points[b0], c.points[b1], c.points[t1], c.points[t0]) > 0;
        add_quad(c.faces, b0, b1, t1, t0, b0t1_reflex == reflex_diagonals);
    }
    require_closed(c);
    return c;
}

/// The Schönhardt-type prism the issue names: circumradius 1, height 1, twist pi/(2n) (30
/// degrees for n = 3), every lateral diagonal reflex.
inline Cavity twisted_prism(int n) { return prism(n, kPi / (2 * n), 1.0, true); }

/// The triangular prism (unit triangle, height 1) with its quads split so that a fan from b0
/// fills it with 3 tets.
inline Cavity convex_prism()
{
    Cavity c = prism(3, 0.0, 1.0, true);
    c.name = "convex prism";
    c.faces.clear();
    c.faces.push_back({0, 2, 1});
    c.faces.push_back({3, 4, 5});
    add_quad(c.faces, 0, 1, 4, 3, true);   // b0-t1
    add_quad(c.faces, 1, 2, 5, 4, true);   // b1-t2
    add_quad(c.faces, 2, 0, 3, 5, false);  // b0-t2
    require_closed(c);
    return c;
}

/*  Two Schönhardt prisms (twisted_prism(3)) stacked and glued along the middle triangle
    (removed): rings at z = 0, 1, 2, each turned by 30 degrees against the one below, all six
    lateral diagonals reflex. The kernel is empty.                                             */
inline Cavity glued_schonhardt_prisms()
{
    Cavity c;
    c.name = "glued Schonhardt prisms";
    const double twist = kPi / 6, height = 1.0;
    for (int ring = 0; ring < 3; ++ring)
        for (int i = 0; i < 3; ++i)
        {
            const double angle = 2 * kPi * i / 3 + ring * twist;
            c.points.push_back({std::cos(angle), std::sin(angle), ring * height});
        }
    c.faces.push_back({0, 2, 1});
    c.faces.push_back({6, 7, 8});
    for (int ring = 0; ring < 2; ++ring)
        for (int i = 0; i < 3; ++i)
        {
            const int b0 = 3 * ring + i, b1 = 3 * ring + (i + 1) % 3;
            const int t0 = b0 + 3, t1 = b1 + 3;
            const bool b0t1_reflex =
                volume::signed_volume6(c.points[b0], c.points[b1], c.points[t1], c.points[t0]) > 0;
            add_quad(c.faces, b0, b1, t1, t0, b0t1_reflex);
        }
    require_closed(c);
    return c;
}

/// The regular octahedron: the 6 points +-e_i.
inline Cavity octahedron()
{
    Cavity c{
        "octahedron", {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}, {}};
    for (int sx : {0, 1})
        for (int sy : {2, 3})
            for (int sz : {4, 5})
            {
                Triangle f{sx, sy, sz};
                if (volume::signed_volume6(Vec3::Zero(), c.points[sx], c.points[sy], c.points[sz]) <
                    0)
                    std::swap(f[1], f[2]);
                c.faces.push_back(f);
            }
    require_closed(c);
    return c;
}

/*  A box [0,a] x [0,b] x [0,c] as 12 triangles; the vertex (1,1,1) corner may be lifted by
    `lift` along z, which folds the three quads around it (nearly coplanar faces for a small
    lift). Vertex i has coordinates (i&1, i>>1&1, i>>2&1).

         6-------7
        /|      /|
       4-------5 |
       | 2-----|-3
       |/      |/
       0-------1                                                                                */
inline Cavity box(double a, double b, double c_, double lift = 0.0)
{
    Cavity c;
    c.name = "box";
    for (int i = 0; i < 8; ++i)
        c.points.push_back({(i & 1) * a, (i >> 1 & 1) * b, (i >> 2 & 1) * c_});
    c.points[7].z() += lift;
    // quads counter-clockwise from outside; split at the diagonal not through vertex 7 so
    // that the lift folds them inwards (reflex) when positive
    add_quad(c.faces, 0, 2, 3, 1, true);   // z = 0
    add_quad(c.faces, 4, 5, 7, 6, false);  // z = c: diagonal 5-6
    add_quad(c.faces, 0, 1, 5, 4, true);   // y = 0
    add_quad(c.faces, 2, 6, 7, 3, false);  // y = b: diagonal 6-3
    add_quad(c.faces, 0, 4, 6, 2, true);   // x = 0
    add_quad(c.faces, 1, 3, 7, 5, false);  // x = a: diagonal 3-5
    require_closed(c);
    return c;
}

inline Cavity cube()
{
    Cavity c = box(1, 1, 1);
    c.name = "cube";
    return c;
}

/// The unit cube with its corner 7 lifted so that the three faces around it fold by 0.1 degree
/// (reflex: a 180.1 degree dihedral seen from inside).
inline Cavity nearly_coplanar_cube()
{
    Cavity c = box(1, 1, 1, -0.0012);
    c.name = "nearly coplanar faces";
    return c;
}

/*  A thin slab: two k x k grids of points (the sheets, 1 x 1) at z = 0 and z = thickness,
    joined by walls of thickness-high quads; every tet of a fill has its 4 vertices on the
    boundary.                                                                                   */
inline Cavity thin_slab(int k, double thickness)
{
    Cavity c;
    c.name = "thin slab";
    auto id = [k](int sheet, int i, int j) { return sheet * k * k + j * k + i; };
    for (int sheet = 0; sheet < 2; ++sheet)
        for (int j = 0; j < k; ++j)
            for (int i = 0; i < k; ++i)
                c.points.push_back({i / double(k - 1), j / double(k - 1), sheet * thickness});
    for (int j = 0; j + 1 < k; ++j)
        for (int i = 0; i + 1 < k; ++i)
        {
            add_quad(c.faces, id(0, i, j), id(0, i, j + 1), id(0, i + 1, j + 1), id(0, i + 1, j),
                     true);
            add_quad(c.faces, id(1, i, j), id(1, i + 1, j), id(1, i + 1, j + 1), id(1, i, j + 1),
                     true);
        }
    // the boundary ring of a sheet, counter-clockwise seen from above
    std::vector<std::pair<int, int>> ring;
    for (int i = 0; i + 1 < k; ++i) ring.push_back({i, 0});
    for (int j = 0; j + 1 < k; ++j) ring.push_back({k - 1, j});
    for (int i = k - 1; i > 0; --i) ring.push_back({i, k - 1});
    for (int j = k - 1; j > 0; --j) ring.push_back({0, j});
    for (std::size_t r = 0; r < ring.size(); ++r)
    {
        const auto [i0, j0] = ring[r];
        const auto [i1, j1] = ring[(r + 1) % ring.size()];
        add_quad(c.faces, id(0, i0, j0), id(0, i1, j1), id(1, i1, j1), id(1, i0, j0), true);
    }
    require_closed(c);
    return c;
}

/// The boundary faces (faces in one tet only, outward) of a set of positive tets.
inline std::vector<Triangle> boundary_of(const std::vector<volume::TetVertices>& tets)
{
    std::map<std::array<int, 3>, std::vector<Triangle>> by_sorted;
    for (const auto& t : tets)
        for (const auto& fv : volume::tet::kFaceVertices)
        {
            const Triangle f{t[fv[0]], t[fv[1]], t[fv[2]]};
            std::array<int, 3> key = f;
            std::sort(key.begin(), key.end());
            by_sorted[key].push_back(f);
        }
    std::vector<Triangle> faces;
    for (const auto& [key, list] : by_sorted)
        if (list.size() == 1) faces.push_back(list[0]);
    return faces;
}

/*  An L-shaped prism, z in [0,1], three unit cubes each cut into its 6 Kuhn tets; the cavity
    is their boundary (so a fill without a new point exists). With ear_clipped_caps, the caps
    are the L hexagon ear-clipped instead and the walls one quad per side.

      (0,2)+---+(1,2)
           |   |
           |   +-------+(2,1)
           |  (1,1)    |
      (0,0)+-----------+(2,0)                                                                   */
inline Cavity l_shape(bool ear_clipped_caps = false)
{
    Cavity c;
    c.name = ear_clipped_caps ? "L-shape (ear-clipped caps)" : "L-shape";
    if (!ear_clipped_caps)
    {
        auto id = [](int i, int j, int k) { return k * 9 + j * 3 + i; };
        for (int k = 0; k < 2; ++k)
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 3; ++i) c.points.push_back({double(i), double(j), double(k)});
        std::vector<volume::TetVertices> tets;
        for (const auto& [ci, cj] : std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {0, 1}})
        {
            auto corner = [&](int bits) {
                return id(ci + (bits & 1), cj + (bits >> 1 & 1), bits >> 2 & 1);
            };
            const std::array<int, 3> axes = {1, 2, 4};
            std::array<int, 3> order = {0, 1, 2};
            do
            {
                volume::TetVertices t = {corner(0), corner(axes[order[0]]),
                                         corner(axes[order[0]] | axes[order[1]]), corner(7)};
                if (volume::signed_volume6(c.points[t[0]], c.points[t[1]], c.points[t[2]],
                                           c.points[t[3]]) < 0)
                    std::swap(t[2], t[3]);
                tets.push_back(t);
            } while (std::next_permutation(order.begin(), order.end()));
        }
        c.faces = boundary_of(tets);
        require_closed(c);
        return c;
    }
    const std::vector<std::array<double, 2>> outline = {{0, 0}, {2, 0}, {2, 1},
                                                        {1, 1}, {1, 2}, {0, 2}};
    const int n = static_cast<int>(outline.size());
    for (int level = 0; level < 2; ++level)
        for (const auto& xy : outline) c.points.push_back({xy[0], xy[1], double(level)});
    std::vector<int> bottom, top;
    for (int i = 0; i < n; ++i)
    {
        bottom.push_back(i);
        top.push_back(n + i);
    }
    add_polygon(c.faces, c.points, bottom, {0, 0, -1});
    add_polygon(c.faces, c.points, top, {0, 0, 1});
    for (int i = 0; i < n; ++i) add_quad(c.faces, i, (i + 1) % n, n + (i + 1) % n, n + i, true);
    require_closed(c);
    return c;
}

/*  A needle: the triangular bipyramid over the equator a b c with |b c| = 1e-3 |a b|, apexes
    above and below; the four faces at b-c have aspect ratio about 1e3.                          */
inline Cavity needle_bipyramid()
{
    Cavity c;
    c.name = "needle faces";
    c.points = {{0, 0, 0}, {1, -0.0005, 0}, {1, 0.0005, 0}, {0.6, 0, 0.4}, {0.6, 0, -0.4}};
    // apex 3 above: a b c counter-clockwise seen from above
    c.faces = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 4, 1}, {1, 4, 2}, {2, 4, 0}};
    require_closed(c);
    return c;
}

/// The ball of an interior vertex: a regular icosahedron (12 points, 20 faces).
inline Cavity icosahedron()
{
    Cavity c;
    c.name = "vertex ball (icosahedron)";
    const double phi = (1 + std::sqrt(5.0)) / 2;
    for (double s : {-1.0, 1.0})
        for (double t : {-1.0, 1.0})
        {
            c.points.push_back({0, s, t * phi});
            c.points.push_back({s, t * phi, 0});
            c.points.push_back({t * phi, 0, s});
        }
    const int n = static_cast<int>(c.points.size());
    const double edge2 = 4.0;
    for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b)
            for (int d = b + 1; d < n; ++d)
            {
                auto close = [&](int i, int j) {
                    return std::abs((c.points[i] - c.points[j]).squaredNorm() - edge2) < 1e-9;
                };
                if (!close(a, b) || !close(b, d) || !close(a, d)) continue;
                Triangle f{a, b, d};
                if (volume::signed_volume6(Vec3::Zero(), c.points[a], c.points[b], c.points[d]) < 0)
                    std::swap(f[1], f[2]);
                c.faces.push_back(f);
            }
    require_closed(c);
    return c;
}

/// The shell of an interior edge: the bipyramid over a hexagon (apexes at +-1 on the axis).
inline Cavity edge_shell()
{
    Cavity c;
    c.name = "edge shell (6 tets)";
    for (int i = 0; i < 6; ++i)
    {
        const double angle = 2 * kPi * i / 6;
        c.points.push_back({std::cos(angle), std::sin(angle), 0});
    }
    c.points.push_back({0, 0, 1});
    c.points.push_back({0, 0, -1});
    for (int i = 0; i < 6; ++i)
    {
        c.faces.push_back({i, (i + 1) % 6, 6});
        c.faces.push_back({(i + 1) % 6, i, 7});
    }
    require_closed(c);
    return c;
}

/*  A Chazelle-type polyhedron: the box [0,L]^2 x [0,H] (L = n+1) with n V-grooves cut into
    its top along x and n into its bottom along y; the grooves' edges come within 2 delta of
    each other at mid-height, so the region between them is a thin twisted gap that needs many
    Steiner points, and the kernel is empty.

       top, seen along x:   __  ____  __        bottom, seen along y: the same, upside down
                              \/    \/
                                                                                                */
inline Cavity chazelle(int n, double delta = 0.05)
{
    Cavity c;
    c.name = "Chazelle n=" + std::to_string(n);
    const double length = n + 1, height = 2.0, half_width = 0.3;
    auto add = [&](double x, double y, double z) {
        c.points.push_back({x, y, z});
        return static_cast<int>(c.points.size()) - 1;
    };
    // a groove profile across the box: (coordinate, height) pairs from 0 to length
    auto profile = [&](double tip) {
        std::vector<std::pair<double, double>> chain = {{0.0, -1.0}};
        for (int k = 1; k <= n; ++k)
        {
            chain.push_back({k - half_width, -1.0});
            chain.push_back({double(k), tip});
            chain.push_back({k + half_width, -1.0});
        }
        chain.push_back({length, -1.0});
        return chain;
    };
    const auto top_profile = profile(height / 2 + delta);
    const auto bottom_profile = profile(height / 2 - delta);
    std::array<std::vector<int>, 2> top, bottom;  // [x = 0 / L] along y, [y = 0 / L] along x
    for (int side = 0; side < 2; ++side)
        for (const auto& [y, z] : top_profile)
            top[side].push_back(add(side * length, y, z < 0 ? height : z));
    for (int side = 0; side < 2; ++side)
        for (const auto& [x, z] : bottom_profile)
            bottom[side].push_back(add(x, side * length, z < 0 ? 0.0 : z));
    const int m = static_cast<int>(top_profile.size());
    // top quads counter-clockwise seen from above, bottom ones seen from below
    for (int j = 0; j + 1 < m; ++j)
    {
        add_quad(c.faces, top[0][j], top[1][j], top[1][j + 1], top[0][j + 1], true);
        add_quad(c.faces, bottom[0][j], bottom[1][j], bottom[1][j + 1], bottom[0][j + 1], true);
    }
    auto wall = [&](std::vector<int> loop, const Vec3& outward) {
        add_polygon(c.faces, c.points, std::move(loop), outward);
    };
    std::vector<int> loop;
    loop = top[0];
    loop.push_back(bottom[1][0]);
    loop.push_back(bottom[0][0]);
    wall(loop, {-1, 0, 0});
    loop = top[1];
    loop.push_back(bottom[1][m - 1]);
    loop.push_back(bottom[0][m - 1]);
    wall(loop, {1, 0, 0});
    loop = bottom[0];
    loop.push_back(top[1][0]);
    loop.push_back(top[0][0]);
    wall(loop, {0, -1, 0});
    loop = bottom[1];
    loop.push_back(top[1][m - 1]);
    loop.push_back(top[0][m - 1]);
    wall(loop, {0, 1, 0});
    require_closed(c);
    return c;
}

/// The corpus, in a fixed order.
inline std::vector<Cavity> all_cavities()
{
    std::vector<Cavity> corpus = {single_tet(), convex_prism(), octahedron(), cube()};
    for (int n = 3; n <= 8; ++n) corpus.push_back(twisted_prism(n));
    corpus.push_back(glued_schonhardt_prisms());
    corpus.push_back(l_shape());
    corpus.push_back(l_shape(true));
    corpus.push_back(nearly_coplanar_cube());
    corpus.push_back(needle_bipyramid());
    corpus.push_back(thin_slab(3, 0.05));
    corpus.push_back(icosahedron());
    corpus.push_back(edge_shell());
    corpus.push_back(chazelle(2));
    return corpus;
}

}  // namespace hdimesh::cavity_corpus
