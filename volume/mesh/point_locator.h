#pragma once
// Point location in a tet mesh: which tet contains a point (and its barycentric weights), and,
// for points outside, the nearest point on the boundary. A uniform grid of tet centroids gives
// a start close to the point, a visibility walk across faces finishes (few steps). The locator
// keeps its own copy of the geometry, so the mesh it was built from may change or go away, and
// every query is const and touches no shared mutable state: safe from several threads.

#include <array>
#include <optional>
#include <vector>

#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// A point inside the mesh: the tet (id in the mesh the locator was built from) and the
/// weights of its four vertices (sum 1, each >= about -1e-12).
struct TetLocation
{
    int tet = -1;
    TetVertices vertices{};
    std::array<double, 4> weights{};
};

/// The nearest point found on the boundary: on triangle `vertices` with weights summing to 1.
struct BoundaryPoint
{
    Triangle vertices{};
    std::array<double, 3> weights{};
    Vec3 point = Vec3::Zero();
    double distance = 0.0;
};

class TetLocator
{
public:
    /// Throws InputError when the mesh has no live tet, a vertex id out of range or a tet of
    /// non-positive volume (the walk needs positive tets).
    explicit TetLocator(const TetMesh& mesh);

    /// The tet containing p, or nothing when p is outside the mesh.
    std::optional<TetLocation> locate(const Vec3& p) const;

    /// The closest point to p on the boundary triangles around the boundary vertex nearest p.
    /// That is the true nearest boundary point except in rare configurations (a boundary
    /// triangle that passes closer than its own vertices, next to a sharper vertex).
    BoundaryPoint nearest_boundary_point(const Vec3& p) const;

    int num_tets() const { return static_cast<int>(tets_.size()); }

private:
    struct Grid
    {
        Vec3 origin = Vec3::Zero();
        double cell = 1.0;
        std::array<int, 3> dims{1, 1, 1};
        std::vector<int> start;  // per cell, into items
        std::vector<int> items;
        std::array<int, 3> cell_of(const Vec3& p) const;
        int index(const std::array<int, 3>& c) const
        {
            return c[0] + dims[0] * (c[1] + dims[1] * c[2]);
        }
    };

    static Grid build_grid(const std::vector<Vec3>& positions, double target_per_cell);
    int start_tet(const Vec3& p) const;
    std::optional<TetLocation> walk(const Vec3& p, int from) const;
    std::optional<TetLocation> scan_near(const Vec3& p) const;
    bool contains(int t, const Vec3& p, std::array<double, 4>& weights) const;
    int nearest_boundary_vertex(const Vec3& p) const;
    static double unvisited_distance_bound(const Grid& grid, const Vec3& p,
                                           const std::array<int, 3>& c, int r);

    std::vector<Vec3> points_;
    std::vector<TetVertices> tets_;       // live tets only, renumbered
    std::vector<TetVertices> neighbors_;  // in the renumbered ids
    std::vector<int> original_tet_;       // renumbered id -> id in the source mesh
    Grid tet_grid_;                       // tet centroids
    std::vector<Vec3> cell_centroids_;    // the centroid of each of tet_grid_.items
    std::vector<Triangle> boundary_;      // outward boundary faces
    std::vector<int> boundary_vertices_;
    Grid boundary_vertex_grid_;                // items index boundary_vertices_
    std::vector<int> vertex_triangles_start_;  // boundary triangles around each boundary vertex
    std::vector<int> vertex_triangles_;        // (by position in boundary_vertices_)
};

}  // namespace hdimesh::volume
