// Thickness at surface vertices by ray casting inward, over a bounding-volume tree of the
// triangles (built once per call).
#include "surface/thickness.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace hdimesh::surface
{

namespace
{

using Box = Eigen::AlignedBox3d;

struct Node
{
    Box box;
    int first = 0, count = 0;  // a leaf: triangles order[first, first + count)
    int left = -1, right = -1;
};

constexpr int kLeafSize = 4;

struct Tree
{
    std::vector<std::array<Vec3, 3>> corners;
    std::vector<Vec3> normals;  // unnormalized, outward
    std::vector<int> order;
    std::vector<Node> nodes;

    int build(int first, int count)
    {
        Node node;
        node.first = first;
        node.count = count;
        for (int i = first; i < first + count; ++i)
            for (const Vec3& p : corners[order[i]]) node.box.extend(p);
        const int index = static_cast<int>(nodes.size());
        nodes.push_back(node);
        if (count <= kLeafSize) return index;
        Box centres;
        for (int i = first; i < first + count; ++i)
            centres.extend((corners[order[i]][0] + corners[order[i]][1] + corners[order[i]][2]) /
                           3.0);
        int axis = 0;
        centres.sizes().maxCoeff(&axis);
        const int half = count / 2;
        std::nth_element(order.begin() + first, order.begin() + first + half,
                         order.begin() + first + count, [&](int a, int b) {
                             return corners[a][0][axis] + corners[a][1][axis] +
                                        corners[a][2][axis] <
                                    corners[b][0][axis] + corners[b][1][axis] + corners[b][2][axis];
                         });
        const int left = build(first, half);
        const int right = build(first + half, count - half);
        nodes[index].left = left;
        nodes[index].right = right;
        nodes[index].count = 0;
        return index;
    }
};

// Entry distance of the ray into the box, or infinity when it misses it before `limit`.
double enter(const Box& box, const Vec3& origin, const Vec3& inverse, double limit)
{
    double lo = 0.0, hi = limit;
    for (int k = 0; k < 3; ++k)
    {
        double a = (box.min()[k] - origin[k]) * inverse[k];
        double b = (box.max()[k] - origin[k]) * inverse[k];
        if (a > b) std::swap(a, b);
        if (std::isnan(a) || std::isnan(b)) continue;  // parallel, origin on the slab's plane
        lo = std::max(lo, a);
        hi = std::min(hi, b);
        if (lo > hi) return std::numeric_limits<double>::infinity();
    }
    return lo;
}

// Möller–Trumbore: the ray parameter of the hit, or infinity.
double hit(const std::array<Vec3, 3>& t, const Vec3& origin, const Vec3& direction)
{
    const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
    const Vec3 p = direction.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) return std::numeric_limits<double>::infinity();
    const double inv = 1.0 / det;
    const Vec3 s = origin - t[0];
    const double u = s.dot(p) * inv;
    if (u < 0.0 || u > 1.0) return std::numeric_limits<double>::infinity();
    const Vec3 q = s.cross(e1);
    const double v = direction.dot(q) * inv;
    if (v < 0.0 || u + v > 1.0) return std::numeric_limits<double>::infinity();
    return e2.dot(q) * inv;
}

}  // namespace

std::vector<double> thickness_at_vertices(const SurfaceMesh& mesh, const ThicknessOptions& options)
{
    const double infinity = std::numeric_limits<double>::infinity();
    std::vector<double> thickness(mesh.n_vertices(), infinity);
    if (mesh.n_faces() == 0) return thickness;
    Tree tree;
    std::vector<Vec3> normals(mesh.n_vertices(), Vec3::Zero());
    std::vector<std::array<int, 3>> face_vertices;
    Box all;
    const bool has_status = mesh.has_face_status();
    for (auto f : mesh.faces())
    {
        if (has_status && mesh.status(f).deleted()) continue;
        std::array<Vec3, 3> c;
        std::array<int, 3> ids;
        int k = 0;
        for (auto v : mesh.fv_range(f))
        {
            ids[k] = v.idx();
            c[k++] = to_point(mesh.point(v));
        }
        const Vec3 n = (c[1] - c[0]).cross(c[2] - c[0]);  // twice the area: area-weighted
        for (int v : ids) normals[v] += n;
        for (const Vec3& p : c) all.extend(p);
        tree.corners.push_back(c);
        tree.normals.push_back(n);
        face_vertices.push_back(ids);
    }
    tree.order.resize(tree.corners.size());
    std::iota(tree.order.begin(), tree.order.end(), 0);
    tree.nodes.reserve(2 * tree.corners.size());
    tree.build(0, static_cast<int>(tree.corners.size()));
    const double self = options.self_fraction * all.diagonal().norm();

    // each vertex's ray is its own: the same answers on any number of threads
    parallel_for(options.workers, mesh.n_vertices(), [&](std::size_t first, std::size_t last) {
        std::vector<int> stack;
        for (std::size_t i = first; i < last; ++i)
        {
            const int v = static_cast<int>(i);
            if (!(normals[v].norm() > 0)) continue;  // deleted, or on no face
            const Vec3 origin = to_point(mesh.point(VertexHandle(v)));
            const Vec3 direction = -normals[v].normalized();
            const Vec3 inverse = direction.cwiseInverse();
            double best = infinity;
            stack.assign(1, 0);
            while (!stack.empty())
            {
                const Node& node = tree.nodes[stack.back()];
                stack.pop_back();
                if (!(enter(node.box, origin, inverse, best) < best)) continue;
                if (node.count == 0)
                {
                    stack.push_back(node.left);
                    stack.push_back(node.right);
                    continue;
                }
                for (int i = node.first; i < node.first + node.count; ++i)
                {
                    const int f = tree.order[i];
                    const auto& ids = face_vertices[f];
                    if (ids[0] == v || ids[1] == v || ids[2] == v) continue;
                    // leaving the solid: the face's outward normal along the ray
                    if (!(tree.normals[f].dot(direction) > 0)) continue;
                    const double t = hit(tree.corners[f], origin, direction);
                    if (t > self && t < best) best = t;
                }
            }
            thickness[v] = best;
        }
    });
    return thickness;
}

}  // namespace hdimesh::surface
