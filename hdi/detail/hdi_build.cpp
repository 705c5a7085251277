// The HDI model's build: the input checked, the features normalized, the smooth patches and
// the per-side node normals, the incidences and the feature lines' search structures.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "common/errors.h"
#include "hdi/detail/hdi_model.h"

namespace hdimesh::hdi::detail
{
namespace
{

void fill_node_records(Model& m)
{
    m.node_record.resize(m.points.size());
    for (std::size_t v = 0; v < m.points.size(); ++v)
    {
        Model::NodeRecord& record = m.node_record[v];
        record.point = m.points[v];
        record.sides = m.side_begin[v + 1] - m.side_begin[v];
        record.patch = record.sides > 0 ? m.side_patch[at(m.side_begin[v])] : -1;
        record.normal = record.sides > 0 ? m.side_normal[at(m.side_begin[v])] : Vec3::Zero();
    }
}

/// Face-averaged node normals are only first-order accurate on irregular meshes, and the Hermite
/// rows pass their error on to the patch (its order of accuracy drops, docs/tuning.md). A quadratic
/// fit of the node's admissible neighbours' positions alone, evaluated at the node, gives its
/// normal to second order; that becomes the side's normal.
void refine_side_normals(Model& m)
{
    Scratch& scratch = thread_scratch();
    std::vector<Vec3> refined = m.side_normal;
    for (int v = 0; v < static_cast<int>(m.points.size()); ++v)
        for (int side = m.side_begin[at(v)]; side < m.side_begin[at(v) + 1]; ++side)
        {
            NeighbourSearch search(m, scratch);
            search.fix_side(m.side_patch[at(side)], m.side_normal[at(side)]);
            const Vec3& x = m.points[at(v)];
            const int count = search.gather(x);
            MongePatch patch;
            if (count < 6 || !fit_monge_patch(m, scratch, count, patch, false) || patch.linear)
                continue;
            Projection at_node;
            evaluate_monge_patch(patch, x, at_node);
            if (at_node.normal.dot(m.side_normal[at(side)]) > 0.5)
                refined[at(side)] = at_node.normal;
        }
    m.side_normal = std::move(refined);
}

/// The input checked: the options in range, one normal per point, the triangles' and the
/// features' vertices among the points.
void check_model_input(const std::vector<Vec3>& points, const std::vector<Vec3>* given_normals,
                       const std::vector<Triangle3>& triangles, const FeatureSet& features,
                       const HdiOptions& options)
{
    const int n = static_cast<int>(points.size());
    if (options.neighbours < 3 || options.neighbours > 256)
        throw InputError("hdi: HdiOptions::neighbours must be in [3, 256]");
    if (!(options.window_factor >= 1.0))
        throw InputError("hdi: HdiOptions::window_factor must be at least 1");
    if (options.max_iterations < 1)
        throw InputError("hdi: HdiOptions::max_iterations must be at least 1");
    if (!(options.tolerance > 0)) throw InputError("hdi: HdiOptions::tolerance must be positive");
    if (options.ridge_neighbours < 2 || options.ridge_neighbours > 64)
        throw InputError("hdi: HdiOptions::ridge_neighbours must be in [2, 64]");
    if (given_normals && given_normals->size() != points.size())
        throw InputError("hdi: " + std::to_string(given_normals->size()) + " normals given for " +
                         std::to_string(points.size()) + " points");
    check_triangle_indices(triangles, n);
    auto check_vertex = [n](int v, const char* what) {
        if (v < 0 || v >= n)
            throw InputError(std::string("hdi: feature ") + what + " names vertex " +
                             std::to_string(v) + " but there are " + std::to_string(n) + " points");
    };
    for (const auto& e : features.ridge_edges)
    {
        check_vertex(e[0], "ridge edge");
        check_vertex(e[1], "ridge edge");
    }
    for (const auto& e : features.boundary_edges)
    {
        check_vertex(e[0], "boundary edge");
        check_vertex(e[1], "boundary edge");
    }
    for (int c : features.corners) check_vertex(c, "corner");
}

/// Features, normalized: sorted (min, max) edges, open boundaries added, corners completed.
void normalize_features(Model& m, const FeatureSet& features, int n)
{
    auto normalized = [](std::vector<std::array<int, 2>> edges) {
        for (auto& e : edges)
            if (e[0] > e[1]) std::swap(e[0], e[1]);
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        return edges;
    };
    m.features.ridge_edges = normalized(features.ridge_edges);
    std::vector<std::array<int, 2>> boundary = features.boundary_edges;
    const std::vector<std::array<int, 2>> open = open_boundary_edges(m.triangles);
    boundary.insert(boundary.end(), open.begin(), open.end());
    m.features.boundary_edges = normalized(boundary);
    std::vector<int> degree(at(n), 0);
    {
        std::vector<std::array<int, 2>> all = m.features.ridge_edges;
        all.insert(all.end(), m.features.boundary_edges.begin(), m.features.boundary_edges.end());
        for (const auto& e : normalized(all))
        {
            ++degree[at(e[0])];
            ++degree[at(e[1])];
        }
    }
    m.features.corners = features.corners;
    for (int v = 0; v < n; ++v)
        if (degree[at(v)] > 0 && degree[at(v)] != 2) m.features.corners.push_back(v);
    std::sort(m.features.corners.begin(), m.features.corners.end());
    m.features.corners.erase(std::unique(m.features.corners.begin(), m.features.corners.end()),
                             m.features.corners.end());
    m.corner.assign(at(n), 0);
    for (int c : m.features.corners) m.corner[at(c)] = 1;
    m.chains = feature_chains(m.features, n);
}

/// One triangle's weighted normal at one of its vertices, on its smooth patch.
struct Contribution
{
    int vertex, patch;
    Vec3 normal;
};

/// Each triangle's normal at its vertices, weighted by area or angle (a pure point cloud: the
/// given normals), sorted by vertex and patch.
std::vector<Contribution> normal_contributions(const Model& m,
                                               const std::vector<Vec3>* given_normals,
                                               const HdiOptions& options, int n)
{
    const std::size_t triangle_count = m.triangles.size();
    std::vector<Contribution> contributions;
    contributions.reserve(3 * triangle_count);
    for (std::size_t t = 0; t < triangle_count; ++t)
    {
        const Triangle3& tri = m.triangles[t];
        const Vec3& fn = m.face_normal[t];
        if (fn.squaredNorm() == 0) continue;
        for (std::size_t c = 0; c < 3; ++c)
        {
            const Vec3& p = m.points[at(tri[c])];
            const Vec3& q = m.points[at(tri[(c + 1) % 3])];
            const Vec3& r = m.points[at(tri[(c + 2) % 3])];
            double weight;
            if (options.normal_weighting == NormalWeighting::Area)
            {
                weight = 0.5 * (q - p).cross(r - p).norm();
            }
            else
            {
                const Vec3 u = q - p, v = r - p;
                weight = std::atan2(u.cross(v).norm(), u.dot(v));
            }
            contributions.push_back({tri[c], m.triangle_patch[t], weight * fn});
        }
    }
    if (m.triangles.empty() && given_normals)  // a pure point cloud: one patch
        for (int v = 0; v < n; ++v) contributions.push_back({v, 0, (*given_normals)[at(v)]});
    std::sort(contributions.begin(), contributions.end(),
              [](const Contribution& a, const Contribution& b) {
                  return a.vertex < b.vertex || (a.vertex == b.vertex && a.patch < b.patch);
              });
    return contributions;
}

/// Smooth patches and the per-side node normals.
void build_sides(Model& m, const std::vector<Vec3>* given_normals, const HdiOptions& options, int n)
{
    const std::size_t triangle_count = m.triangles.size();
    m.triangle_patch = smooth_patches(m.triangles, m.features);
    m.face_normal.resize(triangle_count);
    for (std::size_t t = 0; t < triangle_count; ++t)
    {
        const Triangle3& tri = m.triangles[t];
        m.face_normal[t] =
            triangle_normal(m.points[at(tri[0])], m.points[at(tri[1])], m.points[at(tri[2])]);
    }
    const std::vector<Contribution> contributions =
        normal_contributions(m, given_normals, options, n);
    m.side_begin.assign(at(n) + 1, 0);
    for (std::size_t i = 0; i < contributions.size();)
    {
        std::size_t j = i;
        Vec3 sum = Vec3::Zero();
        while (j < contributions.size() && contributions[j].vertex == contributions[i].vertex &&
               contributions[j].patch == contributions[i].patch)
            sum += contributions[j++].normal;
        if (sum.squaredNorm() > 0)
        {
            m.side_patch.push_back(contributions[i].patch);
            m.side_normal.push_back(sum.normalized());
            ++m.side_begin[at(contributions[i].vertex) + 1];
        }
        i = j;
    }
    std::partial_sum(m.side_begin.begin(), m.side_begin.end(), m.side_begin.begin());
    if (given_normals && !m.triangles.empty())  // the given normal wins where it is unambiguous
        for (int v = 0; v < n; ++v)
            if (side_count(m, v) == 1 && (*given_normals)[at(v)].squaredNorm() > 0)
                m.side_normal[at(m.side_begin[at(v)])] = (*given_normals)[at(v)].normalized();
    const int patch_count =
        m.triangle_patch.empty()
            ? 1
            : *std::max_element(m.triangle_patch.begin(), m.triangle_patch.end()) + 1;
    m.several_patches = patch_count > 1;
}

/// The triangles around each point (CSR).
void build_incidence(Model& m, int n)
{
    const std::size_t triangle_count = m.triangles.size();
    m.incident_begin.assign(at(n) + 1, 0);
    for (const Triangle3& tri : m.triangles)
        for (int v : tri) ++m.incident_begin[at(v) + 1];
    std::partial_sum(m.incident_begin.begin(), m.incident_begin.end(), m.incident_begin.begin());
    m.incident_triangles.resize(at(m.incident_begin.back()));
    {
        std::vector<int> fill(m.incident_begin.begin(), m.incident_begin.end() - 1);
        for (std::size_t t = 0; t < triangle_count; ++t)
            for (int v : m.triangles[t])
                m.incident_triangles[at(fill[at(v)]++)] = static_cast<int>(t);
    }
}

/// Feature lines: a kd-tree over their nodes, and per node the segments touching it.
void build_feature_lines(Model& m, int n)
{
    std::vector<int> line_index(at(n), -1);
    std::vector<std::vector<std::array<int, 2>>> node_segments;
    for (std::size_t c = 0; c < m.chains.size(); ++c)
    {
        const FeatureChain& chain = m.chains[c];
        for (int v : chain.vertices)
            if (line_index[at(v)] < 0)
            {
                line_index[at(v)] = static_cast<int>(m.line_node.size());
                m.line_node.push_back(v);
                node_segments.emplace_back();
            }
        const int segments = segment_count(chain);
        for (int j = 0; j < segments; ++j)
        {
            const int a = chain.vertices[at(j)];
            const int b = chain.vertices[(at(j) + 1) % chain.vertices.size()];
            node_segments[at(line_index[at(a)])].push_back({static_cast<int>(c), j});
            node_segments[at(line_index[at(b)])].push_back({static_cast<int>(c), j});
        }
    }
    m.segment_begin.assign(m.line_node.size() + 1, 0);
    for (std::size_t i = 0; i < node_segments.size(); ++i)
    {
        m.segment_begin[i + 1] = m.segment_begin[i] + static_cast<int>(node_segments[i].size());
        m.segments.insert(m.segments.end(), node_segments[i].begin(), node_segments[i].end());
    }
    std::vector<Vec3> line_points;
    line_points.reserve(m.line_node.size());
    for (int v : m.line_node) line_points.push_back(m.points[at(v)]);
    m.line_knn = KnnIndex(line_points);
}

}  // namespace

std::shared_ptr<Model> build_model(std::vector<Vec3> points, const std::vector<Vec3>* given_normals,
                                   std::vector<Triangle3> triangles, const FeatureSet& features,
                                   const HdiOptions& options)
{
    const int n = static_cast<int>(points.size());
    check_model_input(points, given_normals, triangles, features, options);

    auto m = std::make_shared<Model>();
    m->options = options;
    m->points = std::move(points);
    m->triangles = std::move(triangles);
    m->scale = bounding_box(m->points).diagonal();
    normalize_features(*m, features, n);
    build_sides(*m, given_normals, options, n);
    build_incidence(*m, n);

    m->knn = KnnIndex(m->points);
    fill_node_records(*m);
    if (options.refine_normals && !given_normals)
    {
        refine_side_normals(*m);
        fill_node_records(*m);
    }
    build_feature_lines(*m, n);
    return m;
}

}  // namespace hdimesh::hdi::detail
