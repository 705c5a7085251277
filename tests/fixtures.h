#pragma once
// Tiny procedural meshes for tests. Each builds its tets positive, its adjacency, and its
// boundary triangles (outward, ref 1), so check_mesh accepts it as is.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "hdi/obj_reader.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::fixtures
{

/// The tet (0,0,0) (1,0,0) (0,1,0) (0,0,1).
TetMesh single_tet();

/// A regular tet of edge length 1 (every edge ties, every face is equilateral).
TetMesh regular_tet();

/// The unit cube cut into 6 Kuhn tets around the diagonal (0,0,0)-(1,1,1).
TetMesh kuhn_cube();

/// [0,1]^3 as n^3 Kuhn cubes; interior vertices moved by up to jitter * (1/n) with a fixed
/// seed (jitter < 0.25 keeps every tet positive).
TetMesh box_mesh(int n, double jitter = 0.0, std::uint32_t seed = 1);

/// A mesh from points and tets listed positive, with its adjacency and boundary triangles
/// (ref 1). Throws std::invalid_argument naming the first tet that is not positive.
TetMesh mesh_from_tets(const std::vector<Vec3>& points, const std::vector<TetVertices>& tets);

/// Sets mesh.triangles from the faces without a neighbour (ref 1) and classifies vertices.
void rebuild_boundary(TetMesh& mesh);

/// A fresh temporary directory, removed with its contents when the object dies.
struct ScratchDir
{
    std::filesystem::path path;
    explicit ScratchDir(const std::string& prefix);
    ~ScratchDir();
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    std::string file(const std::string& name) const { return (path / name).string(); }
};

/// Largest | |x| - 1 | over the vertices of mesh.triangles: how far the boundary is from the
/// unit sphere (the paper's benchmark domain).
double max_unit_sphere_deviation(const TetMesh& mesh);

/// The unit sphere as a triangle surface: an icosahedron subdivided `levels` times, every new
/// vertex pushed onto the sphere; triangles counter-clockwise seen from outside.
hdi::TriangleSurface icosphere(int levels);

/// Mean edge length of a triangle surface (each interior edge counted twice): its sampling h.
double mean_edge_length(const hdi::TriangleSurface& surface);

/// A triangle surface assembled from parallelogram grids; a point added again at the same place
/// (to 1e-9) is the same vertex.
struct GridSurface
{
    std::vector<hdi::Vec3> points;
    std::vector<hdi::Triangle3> triangles;

    /// Adds the point unless one is already at the same place; returns its index.
    int add(const hdi::Vec3& p);
    /// An nu x nv grid over origin + [0,1] u + [0,1] v (normal u x v), each cell cut by its
    /// diagonal from (0,0) to (1,1).
    void add_grid(const hdi::Vec3& origin, const hdi::Vec3& u, const hdi::Vec3& v, int nu, int nv);

private:
    std::map<std::array<long long, 3>, int> where_;
};

/// The unit cube's surface, each face an n x n grid, outward normals.
GridSurface grid_cube(int n);

/// Path of a file in the project's data/ folder.
std::string data_path(const std::string& name);

}  // namespace hdimesh::fixtures
