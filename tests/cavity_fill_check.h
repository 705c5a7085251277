#pragma once
// What every fill of a corpus cavity must be (tests/cavity_stages_test.cpp asserts it,
// bench/bench_cavity.cpp prints it): a tetrahedralization of exactly the cavity. Positive tets
// (exact), the enclosed volume, the input faces as the oriented boundary and every other face
// twice with opposite orientations, every cavity vertex used, Steiner points used and on no
// input face, the reported worst Qe, and the mesh checker's agreement.

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "cavity_corpus.h"
#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/fill/detail/cavity_stages.h"
#include "volume/mesh/geometry.h"
#include "volume/mesh/predicates.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::cavity_corpus
{

/// The triangle turned so that its smallest id comes first (orientation kept).
inline Triangle rotated_to_smallest(const Triangle& t)
{
    const int k = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
    return {t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
}

/// p lies in the closed triangle (a, b, c), exactly.
inline bool on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
    using volume::orient2d;
    if (volume::orient3d(a, b, c, p) != 0) return false;
    const Vec3 normal = (b - a).cross(c - a).cwiseAbs();
    int drop = 0;
    if (normal[1] > normal[drop]) drop = 1;
    if (normal[2] > normal[drop]) drop = 2;
    const int s = orient2d(a, b, c, drop);
    return s != 0 && s * orient2d(a, b, p, drop) >= 0 && s * orient2d(b, c, p, drop) >= 0 &&
           s * orient2d(c, a, p, drop) >= 0;
}

/// A vertex whose faces form more than one fan (two parts of the cavity touching at a point):
/// a valid cavity, but its boundary is not a manifold for the mesh checker.
inline bool has_pinched_vertex(const std::vector<Triangle>& faces)
{
    std::map<int, std::map<int, int>> link;  // vertex -> (next -> following) around it
    for (const auto& f : faces)
        for (int k = 0; k < 3; ++k) link[f[k]][f[(k + 1) % 3]] = f[(k + 2) % 3];
    for (const auto& [vertex, successor] : link)
    {
        int steps = 0;
        const int start = successor.begin()->first;
        int at = start;
        do
        {
            at = successor.at(at);
            ++steps;
        } while (at != start && steps <= static_cast<int>(successor.size()));
        if (steps != static_cast<int>(successor.size())) return true;
    }
    return false;
}

/// The first way `fill` fails to be a tetrahedralization of exactly `cavity` (see above), or
/// an empty string.
inline std::string fill_defect(const Cavity& cavity, const volume::CavityFill& fill)
{
    using volume::TetVertices;
    if (!fill.filled) return "not filled";
    std::vector<Vec3> all = cavity.points;
    all.insert(all.end(), fill.new_points.begin(), fill.new_points.end());
    const int num_points = static_cast<int>(all.size());

    double volume = 0, worst = std::numeric_limits<double>::max();
    std::map<Triangle, std::vector<Triangle>> faces_by_sorted;
    std::vector<bool> used(num_points, false);
    for (const auto& t : fill.tets)
    {
        for (int v : t)
        {
            if (v < 0 || v >= num_points) return "a tet names vertex " + std::to_string(v);
            used[v] = true;
        }
        if (!(volume::orient3d(all[t[0]], all[t[1]], all[t[2]], all[t[3]]) > 0))
            return "a tet is not positive";
        volume += volume::signed_volume(all[t[0]], all[t[1]], all[t[2]], all[t[3]]);
        worst = std::min(worst, volume::tet_quality(all[t[0]], all[t[1]], all[t[2]], all[t[3]]));
        for (const auto& fv : volume::tet::kFaceVertices)
        {
            const Triangle f{t[fv[0]], t[fv[1]], t[fv[2]]};
            Triangle key = f;
            std::sort(key.begin(), key.end());
            faces_by_sorted[key].push_back(rotated_to_smallest(f));
        }
    }
    const double enclosed = enclosed_volume(cavity.points, cavity.faces);
    if (std::abs(volume - enclosed) > 1e-12 * std::abs(enclosed))
        return "volume " + std::to_string(volume) + ", the cavity encloses " +
               std::to_string(enclosed);
    if (std::abs(fill.worst_quality - worst) > 1e-12 * std::max(1.0, worst))
        return "the reported worst Qe is not the tets'";

    // the boundary of the tets is the input, as an oriented set; inner faces pair up
    std::vector<Triangle> boundary, input;
    for (const auto& [key, list] : faces_by_sorted)
    {
        if (list.size() > 2) return "a face is in more than two tets";
        if (list.size() == 1)
            boundary.push_back(list[0]);
        else if (list[0] == list[1])
            return "an inner face has the same orientation in both its tets";
    }
    for (const auto& f : cavity.faces) input.push_back(rotated_to_smallest(f));
    std::sort(boundary.begin(), boundary.end());
    std::sort(input.begin(), input.end());
    if (boundary != input) return "the tets' boundary is not the cavity";

    // no cavity vertex dropped; every Steiner point used and on no input face
    for (const auto& f : cavity.faces)
        for (int v : f)
            if (!used[v]) return "cavity vertex " + std::to_string(v) + " unused";
    for (int k = 0; k < static_cast<int>(fill.new_points.size()); ++k)
    {
        const int id = static_cast<int>(cavity.points.size()) + k;
        if (!used[id]) return "Steiner point " + std::to_string(k) + " unused";
        for (const auto& f : cavity.faces)
            if (on_triangle(all[id], cavity.points[f[0]], cavity.points[f[1]], cavity.points[f[2]]))
                return "Steiner point " + std::to_string(k) + " on an input face";
    }

    // and the mesh checker agrees (it needs every point used: the cavity's own points only)
    if (has_pinched_vertex(cavity.faces)) return "";
    std::vector<int> old2new(num_points, -1);
    std::vector<Vec3> mesh_points;
    for (int v = 0; v < num_points; ++v)
        if (used[v])
        {
            old2new[v] = static_cast<int>(mesh_points.size());
            mesh_points.push_back(all[v]);
        }
    std::vector<TetVertices> mesh_tets;
    for (const auto& t : fill.tets)
        mesh_tets.push_back({old2new[t[0]], old2new[t[1]], old2new[t[2]], old2new[t[3]]});
    const auto violations = volume::check_mesh(fixtures::mesh_from_tets(mesh_points, mesh_tets));
    return violations.empty() ? "" : "checker: " + volume::format_violations(violations);
}

}  // namespace hdimesh::cavity_corpus
