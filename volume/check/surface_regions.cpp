// Shells, nesting and regions of a closed surface: connected components through shared edges,
// containment by winding numbers with exactly signed solid angles.
#include "volume/check/surface_regions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include "volume/mesh/predicates.h"

namespace hdimesh::volume
{

namespace
{

/// Union-find, smaller root kept.
int find_root(std::vector<int>& parent, int i)
{
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

/// Union-find parents of the faces, the faces sharing an edge joined (find_root gives a face's
/// component).
std::vector<int> join_faces_by_edges(const std::vector<Triangle>& triangles)
{
    const int num_faces = static_cast<int>(triangles.size());
    std::vector<int> parent(num_faces);
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<std::array<int, 3>> edges;  // (a, b, face), a < b
    edges.reserve(3 * static_cast<std::size_t>(num_faces));
    for (int f = 0; f < num_faces; ++f)
        for (int k = 0; k < 3; ++k)
        {
            const int a = triangles[f][k], b = triangles[f][(k + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), f});
        }
    std::sort(edges.begin(), edges.end());
    for (std::size_t k = 1; k < edges.size(); ++k)
        if (edges[k][0] == edges[k - 1][0] && edges[k][1] == edges[k - 1][1])
        {
            const int x = find_root(parent, edges[k][2]), y = find_root(parent, edges[k - 1][2]);
            if (x != y) parent[std::max(x, y)] = std::min(x, y);
        }
    return parent;
}

std::array<double, 3> coordinates(const Vec3& p) { return {p[0], p[1], p[2]}; }

}  // namespace

int winding_number(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                   const std::vector<int>& faces, const Vec3& p)
{
    double solid_angle = 0;
    for (int f : faces)
    {
        const Vec3& A = points[triangles[f][0]];
        const Vec3& B = points[triangles[f][1]];
        const Vec3& C = points[triangles[f][2]];
        // the sign is what decides a point close to a face's plane: take it exactly
        const int side = orient3d(p, A, B, C);
        if (side == 0) continue;  // p in the face's plane, off the face: no solid angle
        const Vec3 a = A - p, b = B - p, c = C - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double det =
            std::max(std::abs(a.dot(b.cross(c))), std::numeric_limits<double>::denorm_min());
        const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        solid_angle += 2.0 * std::atan2(side * det, denominator);
    }
    return static_cast<int>(std::lround(solid_angle / (4.0 * M_PI)));
}

std::vector<Triangle> SurfaceRegions::region_faces(int r) const
{
    std::vector<Triangle> faces;
    auto add_shell = [&](int s) {
        for (int f : shells[s].faces) faces.push_back(triangles[f]);
    };
    add_shell(regions[r].outer_shell);
    for (int s : regions[r].void_shells) add_shell(s);
    return faces;
}

SurfaceRegions find_surface_regions(const std::vector<Vec3>& points,
                                    const std::vector<Triangle>& triangles)
{
    const int num_faces = static_cast<int>(triangles.size());
    std::vector<int> parent = join_faces_by_edges(triangles);

    // shells by root, then in geometric order
    std::vector<int> shell_of_root(num_faces, -1);
    std::vector<SurfaceShell> shells;
    for (int f = 0; f < num_faces; ++f)
    {
        const int root = find_root(parent, f);
        if (shell_of_root[root] < 0)
        {
            shell_of_root[root] = static_cast<int>(shells.size());
            shells.emplace_back();
        }
        shells[shell_of_root[root]].faces.push_back(f);
    }
    auto lowest_point = [&](const SurfaceShell& shell) {
        std::array<double, 3> lowest = coordinates(points[triangles[shell.faces[0]][0]]);
        for (int f : shell.faces)
            for (int v : triangles[f]) lowest = std::min(lowest, coordinates(points[v]));
        return lowest;
    };
    std::vector<std::pair<std::array<double, 3>, int>> order;
    for (std::size_t s = 0; s < shells.size(); ++s)
        order.push_back({lowest_point(shells[s]), static_cast<int>(s)});
    std::sort(order.begin(), order.end());
    SurfaceRegions result;
    for (const auto& entry : order) result.shells.push_back(std::move(shells[entry.second]));
    const int num_shells = static_cast<int>(result.shells.size());

    std::vector<Vec3> lo(num_shells), hi(num_shells);
    for (int s = 0; s < num_shells; ++s)
    {
        SurfaceShell& shell = result.shells[s];
        lo[s] = hi[s] = points[triangles[shell.faces[0]][0]];
        for (int f : shell.faces)
            for (int v : triangles[f])
            {
                lo[s] = lo[s].cwiseMin(points[v]);
                hi[s] = hi[s].cwiseMax(points[v]);
            }
        // relative to the box centre, so the sum does not cancel far from the origin
        const Vec3 centre = 0.5 * (lo[s] + hi[s]);
        double volume6 = 0;
        for (int f : shell.faces)
        {
            const auto& t = triangles[f];
            volume6 +=
                (points[t[0]] - centre).dot((points[t[1]] - centre).cross(points[t[2]] - centre));
        }
        shell.volume = volume6 / 6.0;
    }

    // containment: a shell inside another has its box inside the other's, and any of its
    // points is inside (the shells are disjoint)
    std::vector<std::vector<int>> containers(num_shells);
    for (int s = 0; s < num_shells; ++s)
    {
        const Vec3& probe = points[triangles[result.shells[s].faces[0]][0]];
        for (int c = 0; c < num_shells; ++c)
        {
            if (c == s) continue;
            if ((lo[s].array() < lo[c].array()).any() || (hi[s].array() > hi[c].array()).any())
                continue;
            if (winding_number(points, triangles, result.shells[c].faces, probe) != 0)
                containers[s].push_back(c);
        }
        result.shells[s].depth = static_cast<int>(containers[s].size());
    }
    for (int s = 0; s < num_shells; ++s)
        for (int c : containers[s])  // the innermost container is the deepest
            if (result.shells[s].parent < 0 ||
                result.shells[c].depth > result.shells[result.shells[s].parent].depth)
                result.shells[s].parent = c;

    // a container comes before what it contains in the geometric order (its lowest point is
    // on its boundary, below every point inside it)
    result.triangles = triangles;
    for (int s = 0; s < num_shells; ++s)
    {
        SurfaceShell& shell = result.shells[s];
        if (shell.depth % 2 == 0)
        {
            shell.region = static_cast<int>(result.regions.size());
            SurfaceRegion region;
            region.ref = shell.region + 1;
            region.outer_shell = s;
            result.regions.push_back(region);
        }
        else
        {
            shell.region = result.shells[shell.parent].region;
            result.regions[shell.region].void_shells.push_back(s);
        }
        const bool outward_wanted = shell.depth % 2 == 0;
        if ((shell.volume > 0) != outward_wanted)
        {
            shell.turned = true;
            ++result.turned_shells;
            for (int f : shell.faces) std::swap(result.triangles[f][1], result.triangles[f][2]);
        }
    }
    return result;
}

}  // namespace hdimesh::volume
