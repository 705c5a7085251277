#include "fixtures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

#include "volume/mesh/geometry.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::fixtures
{

namespace
{

/// Adds tet v, flipping it when it comes negative (fixtures list vertices by construction).
void add_positive_tet(TetMesh& mesh, TetVertices v)
{
    const auto& p = mesh.points;
    if (signed_volume6(p[v[0]], p[v[1]], p[v[2]], p[v[3]]) < 0) std::swap(v[2], v[3]);
    mesh.add_tet(v);
}

// The six Kuhn tets of a cube with corners numbered by bits (x = 1, y = 2, z = 4):
// each walks from corner 0 to corner 7 along one permutation of the axes.
constexpr std::array<std::array<int, 4>, 6> kKuhnTets = {{
    {0, 1, 3, 7},
    {0, 1, 5, 7},
    {0, 2, 3, 7},
    {0, 2, 6, 7},
    {0, 4, 5, 7},
    {0, 4, 6, 7},
}};

}  // namespace

TetMesh mesh_from_tets(const std::vector<Vec3>& points, const std::vector<TetVertices>& tets)
{
    TetMesh mesh;
    for (const Vec3& p : points) mesh.add_vertex(p);
    for (std::size_t i = 0; i < tets.size(); ++i)
    {
        const TetVertices& t = tets[i];
        if (!(signed_volume(points[t[0]], points[t[1]], points[t[2]], points[t[3]]) > 0))
            throw std::invalid_argument("fixture tet " + std::to_string(i) + " is not positive");
        mesh.add_tet(t);
    }
    rebuild_boundary(mesh);
    return mesh;
}

void rebuild_boundary(TetMesh& mesh)
{
    mesh.build_adjacency();
    mesh.triangles.clear();
    mesh.triangle_refs.clear();
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        for (int f = 0; f < 4; ++f)
        {
            if (mesh.neighbors[t][f] != kNoTet) continue;
            const auto& fv = tet::kFaceVertices[f];
            mesh.add_triangle({mesh.tets[t][fv[0]], mesh.tets[t][fv[1]], mesh.tets[t][fv[2]]}, 1);
        }
    }
    mesh.classify_vertices();
}

TetMesh single_tet()
{
    TetMesh mesh;
    mesh.add_vertex({0, 0, 0});
    mesh.add_vertex({1, 0, 0});
    mesh.add_vertex({0, 1, 0});
    mesh.add_vertex({0, 0, 1});
    mesh.add_tet({0, 1, 2, 3});
    rebuild_boundary(mesh);
    return mesh;
}

TetMesh regular_tet()
{
    TetMesh mesh;
    const double s = 1.0 / std::sqrt(8.0);  // (+-1,+-1,+-1) alternate corners scaled to edge 1
    mesh.add_vertex({s, s, s});
    mesh.add_vertex({s, -s, -s});
    mesh.add_vertex({-s, s, -s});
    mesh.add_vertex({-s, -s, s});
    add_positive_tet(mesh, {0, 1, 2, 3});
    rebuild_boundary(mesh);
    return mesh;
}

TetMesh kuhn_cube() { return box_mesh(1); }

TetMesh box_mesh(int n, double jitter, std::uint32_t seed)
{
    TetMesh mesh;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double h = 1.0 / n;
    auto id = [n](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
    for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i)
            {
                Vec3 p(i * h, j * h, k * h);
                const bool interior = i > 0 && i < n && j > 0 && j < n && k > 0 && k < n;
                if (interior && jitter > 0) p += jitter * h * Vec3(unit(rng), unit(rng), unit(rng));
                mesh.add_vertex(p);
            }
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
            {
                auto corner = [&](int bits) {
                    return id(i + (bits & 1), j + ((bits >> 1) & 1), k + ((bits >> 2) & 1));
                };
                for (const auto& kt : kKuhnTets)
                    add_positive_tet(mesh,
                                     {corner(kt[0]), corner(kt[1]), corner(kt[2]), corner(kt[3])});
            }
    rebuild_boundary(mesh);
    return mesh;
}

ScratchDir::ScratchDir(const std::string& prefix)
{
    path = std::filesystem::temp_directory_path() /
           (prefix + "_" + std::to_string(std::random_device{}()));
    std::filesystem::create_directories(path);
}

ScratchDir::~ScratchDir()
{
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
}

double max_unit_sphere_deviation(const TetMesh& mesh)
{
    double worst = 0;
    for (const auto& tri : mesh.triangles)
        for (int v : tri) worst = std::max(worst, std::abs(mesh.points[v].norm() - 1.0));
    return worst;
}

std::string data_path(const std::string& name)
{
    return std::string(HDIMESH_DATA_DIR) + "/" + name;
}

hdi::TriangleSurface icosphere(int levels)
{
    using hdi::Vec3;
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;  // the golden ratio: icosahedron corners
    hdi::TriangleSurface s;
    for (const Vec3& p : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                          Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                          Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
        s.points.push_back(p.normalized());
    s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                   {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                   {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                   {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int level = 0; level < levels; ++level)
    {
        std::map<std::pair<int, int>, int> midpoint;  // edge -> its new vertex, made once
        auto middle = [&](int a, int b) {
            const std::pair<int, int> key(std::min(a, b), std::max(a, b));
            const auto it = midpoint.find(key);
            if (it != midpoint.end()) return it->second;
            s.points.push_back((s.points[a] + s.points[b]).normalized());
            return midpoint[key] = static_cast<int>(s.points.size()) - 1;
        };
        std::vector<hdi::Triangle3> finer;
        for (const hdi::Triangle3& tri : s.triangles)
        {
            const int ab = middle(tri[0], tri[1]), bc = middle(tri[1], tri[2]);
            const int ca = middle(tri[2], tri[0]);
            finer.push_back({tri[0], ab, ca});
            finer.push_back({tri[1], bc, ab});
            finer.push_back({tri[2], ca, bc});
            finer.push_back({ab, bc, ca});
        }
        s.triangles = finer;
    }
    return s;
}

double mean_edge_length(const hdi::TriangleSurface& surface)
{
    double sum = 0;
    for (const hdi::Triangle3& t : surface.triangles)
        for (std::size_t i = 0; i < 3; ++i)
            sum += (surface.points[t[i]] - surface.points[t[(i + 1) % 3]]).norm();
    return sum / (3.0 * static_cast<double>(surface.triangles.size()));
}

int GridSurface::add(const hdi::Vec3& p)
{
    const std::array<long long, 3> key{std::llround(p.x() * 1e9), std::llround(p.y() * 1e9),
                                       std::llround(p.z() * 1e9)};
    const auto it = where_.find(key);
    if (it != where_.end()) return it->second;
    points.push_back(p);
    return where_[key] = static_cast<int>(points.size()) - 1;
}

void GridSurface::add_grid(const hdi::Vec3& origin, const hdi::Vec3& u, const hdi::Vec3& v, int nu,
                           int nv)
{
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j)
        {
            auto at = [&](int a, int b) {
                return add(origin + (double(a) / nu) * u + (double(b) / nv) * v);
            };
            const int p00 = at(i, j), p10 = at(i + 1, j), p11 = at(i + 1, j + 1),
                      p01 = at(i, j + 1);
            triangles.push_back({p00, p10, p11});
            triangles.push_back({p00, p11, p01});
        }
}

GridSurface grid_cube(int n)
{
    GridSurface s;
    const hdi::Vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1), o(0, 0, 0);
    s.add_grid(o, y, x, n, n);      // z = 0, normal -z
    s.add_grid(o + z, x, y, n, n);  // z = 1, normal +z
    s.add_grid(o, x, z, n, n);      // y = 0, normal -y
    s.add_grid(o + y, z, x, n, n);  // y = 1, normal +y
    s.add_grid(o, z, y, n, n);      // x = 0, normal -x
    s.add_grid(o + x, y, z, n, n);  // x = 1, normal +x
    return s;
}

}  // namespace hdimesh::fixtures
