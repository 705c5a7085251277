#include "volume/mesh/point_locator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "common/errors.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace
{

/// Barycentric weights may dip this far below zero for a point on a face or an edge, so that
/// rounding never leaves a point between two tets.
constexpr double kWeightTolerance = 1e-12;

/// The walk from a start a few cells away takes a handful of steps; this bound only stops a
/// pathological cycle, after which the local scan takes over.
constexpr int kMaxWalkSteps = 10000;

/// Closest point to p on triangle abc (Ericson, Real-Time Collision Detection, 5.1.5), with
/// the weights of a, b, c.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                               std::array<double, 3>& w)
{
    // the answer at vertex k, or at x + v * along on the edge from vertex i to vertex j
    auto at_vertex = [&w](const Vec3& x, int k) {
        w = {0, 0, 0};
        w[k] = 1;
        return x;
    };
    auto on_edge = [&w](const Vec3& x, const Vec3& along, double v, int i, int j) -> Vec3 {
        w = {0, 0, 0};
        w[i] = 1 - v;
        w[j] = v;
        return x + v * along;
    };
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return at_vertex(a, 0);
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return at_vertex(b, 1);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return on_edge(a, ab, d1 / (d1 - d3), 0, 1);
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return at_vertex(c, 2);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return on_edge(a, ac, d2 / (d2 - d6), 0, 2);
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return on_edge(b, c - b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), 1, 2);
    const double denominator = 1.0 / (va + vb + vc);
    const double v = vb * denominator, u = vc * denominator;
    w = {1 - v - u, v, u};
    return a + v * ab + u * ac;
}

/// Visits the cells at Chebyshev distance exactly r from c (the shell of a cube), clipped.
template <class Visit>
void for_each_cell_in_ring(const std::array<int, 3>& c, int r, const std::array<int, 3>& dims,
                           Visit&& visit)
{
    for (int k = std::max(0, c[2] - r); k <= std::min(dims[2] - 1, c[2] + r); ++k)
        for (int j = std::max(0, c[1] - r); j <= std::min(dims[1] - 1, c[1] + r); ++j)
        {
            const bool shell_kj = std::abs(k - c[2]) == r || std::abs(j - c[1]) == r;
            if (shell_kj)
            {
                for (int i = std::max(0, c[0] - r); i <= std::min(dims[0] - 1, c[0] + r); ++i)
                    visit(i, j, k);
            }
            else
            {
                if (c[0] - r >= 0) visit(c[0] - r, j, k);
                if (r > 0 && c[0] + r < dims[0]) visit(c[0] + r, j, k);
            }
        }
}

}  // namespace

/// A lower bound on the distance from p to any cell farther than ring r from c (p's clamped
/// cell): such a cell lies beyond the ring on some axis i, so it is at least the gap to that
/// slab along i away, plus, on the other axes, p's distance to the grid's box (which matters
/// for points far outside; a plain r * cell bound would make those scan the whole grid).
double TetLocator::unvisited_distance_bound(const Grid& grid, const Vec3& p,
                                            const std::array<int, 3>& c, int r)
{
    std::array<double, 3> outside_box{};
    for (int i = 0; i < 3; ++i)
    {
        const double low = grid.origin[i], high = grid.origin[i] + grid.dims[i] * grid.cell;
        outside_box[i] = std::max({0.0, low - p[i], p[i] - high});
    }
    double bound = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i)
    {
        double gap = std::numeric_limits<double>::infinity();
        if (c[i] - r - 1 >= 0)
            gap = std::min(gap, std::max(0.0, p[i] - (grid.origin[i] + (c[i] - r) * grid.cell)));
        if (c[i] + r + 1 < grid.dims[i])
            gap = std::min(gap, std::max(0.0, grid.origin[i] + (c[i] + r + 1) * grid.cell - p[i]));
        if (!std::isfinite(gap)) continue;  // no cells beyond the ring on this axis
        double squared = gap * gap;
        for (int j = 0; j < 3; ++j)
            if (j != i) squared += outside_box[j] * outside_box[j];
        bound = std::min(bound, std::sqrt(squared));
    }
    return bound;
}

std::array<int, 3> TetLocator::Grid::cell_of(const Vec3& p) const
{
    std::array<int, 3> c{0, 0, 0};
    for (int i = 0; i < 3; ++i)
    {
        const double x = (p[i] - origin[i]) / cell;
        if (!(x > 0)) continue;  // also NaN
        c[i] = x >= dims[i] ? dims[i] - 1 : static_cast<int>(x);
    }
    return c;
}

TetLocator::Grid TetLocator::build_grid(const std::vector<Vec3>& positions, double target_per_cell)
{
    Grid grid;
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
    for (const Vec3& p : positions)
    {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
    }
    if (positions.empty()) low = high = Vec3::Zero();
    const double diagonal = std::max((high - low).norm(), 1e-300);
    // flat point sets (a planar boundary) still get a 3D cell size
    const Vec3 extent = (high - low).cwiseMax(Vec3::Constant(1e-3 * diagonal));
    const double cells_wanted =
        std::clamp(positions.size() / target_per_cell, 1.0, double(1 << 24));
    grid.cell = std::cbrt(extent.prod() / cells_wanted);
    grid.origin = low;
    for (int i = 0; i < 3; ++i)
        grid.dims[i] = std::clamp(static_cast<int>(std::ceil(extent[i] / grid.cell)), 1, 1 << 10);
    const int num_cells = grid.dims[0] * grid.dims[1] * grid.dims[2];

    grid.start.assign(num_cells + 1, 0);
    std::vector<int> cell_of_item(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i)
    {
        cell_of_item[i] = grid.index(grid.cell_of(positions[i]));
        ++grid.start[cell_of_item[i] + 1];
    }
    for (int c = 0; c < num_cells; ++c) grid.start[c + 1] += grid.start[c];
    grid.items.resize(positions.size());
    std::vector<int> fill(grid.start.begin(), grid.start.end() - 1);
    for (std::size_t i = 0; i < positions.size(); ++i)
        grid.items[fill[cell_of_item[i]]++] = static_cast<int>(i);
    return grid;
}

TetLocator::TetLocator(const TetMesh& mesh)
{
    const int nv = mesh.num_vertices();
    points_ = mesh.points;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        const auto& tv = mesh.tets[t];
        for (int v : tv)
            if (v < 0 || v >= nv)
                throw InputError("background mesh: tet " + std::to_string(t) + " has vertex id " +
                                 std::to_string(v) + " outside [0, " + std::to_string(nv) + ")");
        if (!(mesh.volume(t) > 0.0))
            throw InputError("background mesh: tet " + std::to_string(t) +
                             " has a non-positive volume; point location needs positive tets");
        tets_.push_back(tv);
        original_tet_.push_back(t);
    }
    if (tets_.empty()) throw InputError("background mesh: no tetrahedra");

    {
        TetMesh live;
        live.points = std::move(points_);
        live.tets = tets_;
        live.tet_refs.assign(tets_.size(), 0);
        live.build_adjacency();
        neighbors_ = std::move(live.neighbors);
        points_ = std::move(live.points);
    }

    std::vector<Vec3> centroids(tets_.size());
    for (std::size_t t = 0; t < tets_.size(); ++t)
    {
        const auto& v = tets_[t];
        centroids[t] = 0.25 * (points_[v[0]] + points_[v[1]] + points_[v[2]] + points_[v[3]]);
    }
    tet_grid_ = build_grid(centroids, 2.0);
    // the centroids in cell order: a query scans its cell's without visiting the tets
    cell_centroids_.resize(tet_grid_.items.size());
    for (std::size_t n = 0; n < tet_grid_.items.size(); ++n)
        cell_centroids_[n] = centroids[tet_grid_.items[n]];

    // boundary faces, their vertices (compact numbering) and the faces around each vertex
    std::vector<int> position(nv, -1);
    for (std::size_t t = 0; t < tets_.size(); ++t)
        for (int f = 0; f < 4; ++f)
        {
            if (neighbors_[t][f] != kNoTet) continue;
            const auto& fv = tet::kFaceVertices[f];
            const Triangle tri = {tets_[t][fv[0]], tets_[t][fv[1]], tets_[t][fv[2]]};
            boundary_.push_back(tri);
            for (int v : tri)
                if (position[v] < 0)
                {
                    position[v] = static_cast<int>(boundary_vertices_.size());
                    boundary_vertices_.push_back(v);
                }
        }
    const int nb = static_cast<int>(boundary_vertices_.size());
    vertex_triangles_start_.assign(nb + 1, 0);
    for (const auto& tri : boundary_)
        for (int v : tri) ++vertex_triangles_start_[position[v] + 1];
    for (int i = 0; i < nb; ++i) vertex_triangles_start_[i + 1] += vertex_triangles_start_[i];
    vertex_triangles_.resize(vertex_triangles_start_[nb]);
    std::vector<int> fill(vertex_triangles_start_.begin(), vertex_triangles_start_.end() - 1);
    for (std::size_t i = 0; i < boundary_.size(); ++i)
        for (int v : boundary_[i]) vertex_triangles_[fill[position[v]]++] = static_cast<int>(i);

    std::vector<Vec3> boundary_points(nb);
    for (int i = 0; i < nb; ++i) boundary_points[i] = points_[boundary_vertices_[i]];
    boundary_vertex_grid_ = build_grid(boundary_points, 2.0);
}

bool TetLocator::contains(int t, const Vec3& p, std::array<double, 4>& weights) const
{
    const auto& v = tets_[t];
    const Vec3 &a = points_[v[0]], &b = points_[v[1]], &c = points_[v[2]], &d = points_[v[3]];
    const double six_volume = signed_volume6(a, b, c, d);
    weights = {signed_volume6(p, b, c, d) / six_volume, signed_volume6(a, p, c, d) / six_volume,
               signed_volume6(a, b, p, d) / six_volume, signed_volume6(a, b, c, p) / six_volume};
    return *std::min_element(weights.begin(), weights.end()) >= -kWeightTolerance;
}

int TetLocator::start_tet(const Vec3& p) const
{
    const auto c = tet_grid_.cell_of(p);
    const int max_ring = std::max({tet_grid_.dims[0], tet_grid_.dims[1], tet_grid_.dims[2]});
    for (int r = 0; r <= max_ring; ++r)
    {
        int best = -1;
        double best_distance = std::numeric_limits<double>::infinity();
        for_each_cell_in_ring(c, r, tet_grid_.dims, [&](int i, int j, int k) {
            const int cell = tet_grid_.index({i, j, k});
            for (int n = tet_grid_.start[cell]; n < tet_grid_.start[cell + 1]; ++n)
            {
                const double distance = (cell_centroids_[n] - p).squaredNorm();
                if (distance < best_distance)
                {
                    best_distance = distance;
                    best = tet_grid_.items[n];
                }
            }
        });
        if (best >= 0) return best;
    }
    return 0;
}

std::optional<TetLocation> TetLocator::walk(const Vec3& p, int from) const
{
    int t = from;
    std::array<double, 4> weights;
    // a cheap deterministic "random" face order per step breaks the cycles a fixed order can
    // fall into on non-Delaunay meshes (remembering stochastic walk), without shared state
    std::uint32_t state = 0x9e3779b9u;
    for (int step = 0; step < kMaxWalkSteps; ++step)
    {
        if (contains(t, p, weights)) return TetLocation{original_tet_[t], tets_[t], weights};
        state = state * 1664525u + 1013904223u;
        const int offset = static_cast<int>(state >> 30);
        int next = kNoTet;
        for (int k = 0; k < 4 && next == kNoTet; ++k)
        {
            const int f = (offset + k) & 3;
            if (weights[f] < -kWeightTolerance) next = neighbors_[t][f];
        }
        if (next == kNoTet) return std::nullopt;  // p lies beyond boundary faces only
        t = next;
    }
    return std::nullopt;
}

std::optional<TetLocation> TetLocator::scan_near(const Vec3& p) const
{
    // only for points inside the grid's box: a far point is plainly outside
    const Vec3 offset = p - tet_grid_.origin;
    for (int i = 0; i < 3; ++i)
        if (!(offset[i] >= -tet_grid_.cell &&
              offset[i] <= (tet_grid_.dims[i] + 1) * tet_grid_.cell))
            return std::nullopt;
    const auto c = tet_grid_.cell_of(p);
    std::array<double, 4> weights;
    std::optional<TetLocation> found;
    for (int r = 0; r <= 1 && !found; ++r)
        for_each_cell_in_ring(c, r, tet_grid_.dims, [&](int i, int j, int k) {
            if (found) return;
            const int cell = tet_grid_.index({i, j, k});
            for (int n = tet_grid_.start[cell]; n < tet_grid_.start[cell + 1]; ++n)
            {
                const int t = tet_grid_.items[n];
                if (contains(t, p, weights))
                {
                    found = TetLocation{original_tet_[t], tets_[t], weights};
                    return;
                }
            }
        });
    return found;
}

std::optional<TetLocation> TetLocator::locate(const Vec3& p) const
{
    if (!p.allFinite()) return std::nullopt;
    if (auto found = walk(p, start_tet(p))) return found;
    // the straight walk can leave a non-convex domain and miss a point that is inside
    return scan_near(p);
}

int TetLocator::nearest_boundary_vertex(const Vec3& p) const
{
    const Grid& grid = boundary_vertex_grid_;
    const auto c = grid.cell_of(p);
    const int max_ring = std::max({grid.dims[0], grid.dims[1], grid.dims[2]});
    int best = 0;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int r = 0; r <= max_ring; ++r)
    {
        for_each_cell_in_ring(c, r, grid.dims, [&](int i, int j, int k) {
            const int cell = grid.index({i, j, k});
            for (int n = grid.start[cell]; n < grid.start[cell + 1]; ++n)
            {
                const int item = grid.items[n];
                const double distance = (points_[boundary_vertices_[item]] - p).norm();
                if (distance < best_distance)
                {
                    best_distance = distance;
                    best = item;
                }
            }
        });
        if (best_distance <= unvisited_distance_bound(grid, p, c, r)) break;
    }
    return best;
}

BoundaryPoint TetLocator::nearest_boundary_point(const Vec3& p) const
{
    const int vertex = nearest_boundary_vertex(p);
    BoundaryPoint best;
    best.distance = std::numeric_limits<double>::infinity();
    for (int n = vertex_triangles_start_[vertex]; n < vertex_triangles_start_[vertex + 1]; ++n)
    {
        const Triangle& tri = boundary_[vertex_triangles_[n]];
        std::array<double, 3> weights;
        const Vec3 q = closest_point_on_triangle(p, points_[tri[0]], points_[tri[1]],
                                                 points_[tri[2]], weights);
        const double distance = (q - p).norm();
        if (distance < best.distance) best = {tri, weights, q, distance};
    }
    return best;
}

}  // namespace hdimesh::volume
