#pragma once
// The HDI model's private machinery, shared by its build (hdi/detail/hdi_build.cpp), its local
// fits (hdi/detail/hdi_fit.cpp) and the projections (hdi/hdi_surface.cpp): the built model,
// the per-thread query buffers, the neighbour search and the quadratic Monge patch.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "hdi/hdi_surface.h"
#include "hdi/knn.h"

namespace hdimesh::hdi
{

struct HdiSurface::Model
{
    Model() : knn(std::vector<Vec3>{}), line_knn(std::vector<Vec3>{}) {}

    HdiOptions options;
    std::vector<Vec3> points;
    std::vector<Triangle3> triangles;
    FeatureSet features;               // as given, plus open boundaries and completed corners
    std::vector<FeatureChain> chains;  // feature lines cut at corners
    std::vector<char> corner;          // per point
    double scale = 0;
    KnnIndex knn;  // over every point

    // Smooth sides: a node has one (patch, normal) per smooth patch it touches.
    std::vector<int> triangle_patch;
    std::vector<Vec3> face_normal;
    std::vector<int> side_begin;  // CSR over points
    std::vector<int> side_patch;
    std::vector<Vec3> side_normal;
    // The hot data of each node in one cache line: its position and its first side, so that
    // sorting out the admissible neighbours of a query reads one record per candidate.
    struct NodeRecord
    {
        Vec3 point;
        Vec3 normal;  // of the first side
        int patch;    // of the first side
        int sides;    // 0: no triangle touches the node; > 1: a ridge node, see side_begin...
    };
    std::vector<NodeRecord> node_record;
    std::vector<int> incident_begin;  // CSR over points: triangles around each point
    std::vector<int> incident_triangles;
    bool several_patches = false;

    // Feature lines: a kd-tree over their nodes, and per node the segments (chain, j) touching it,
    // segment j of a chain joining its vertices j and j + 1 (mod size when closed).
    std::vector<int> line_node;  // point index of each line node
    KnnIndex line_knn;
    std::vector<int> segment_begin;  // CSR over line nodes
    std::vector<std::array<int, 2>> segments;
};

namespace detail
{

using Model = HdiSurface::Model;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

inline constexpr double relative_rank_threshold = 1e-10;

/// Per-thread buffers of one query; they only grow, so a query allocates nothing once warm.
struct Scratch
{
    std::vector<int> candidate;  // the kd-tree's answer: nearest input nodes of the search point
    std::vector<double> candidate_d2;
    // The admissible candidates (on the query's side, normal agreeing), nearest to the current
    // point first; a fit uses the first n. Positions and normals are copied so the fit reads
    // contiguous memory.
    std::vector<int> node;
    std::vector<double> node_d2;
    std::vector<Vec3> node_point;
    std::vector<Vec3> node_normal;
};

/// This thread's query buffers.
Scratch& thread_scratch();

inline std::size_t at(int i) { return static_cast<std::size_t>(i); }

inline int side_count(const Model& m, int v)
{
    return m.side_begin[at(v) + 1] - m.side_begin[at(v)];
}

inline int segment_count(const FeatureChain& chain)
{
    const int n = static_cast<int>(chain.vertices.size());
    return chain.closed ? n : n - 1;
}

/// Finds the input nodes of one fit at x: the n nearest admissible ones, exactly. A search is
/// reused while it provably still contains them (x moved by less than half the gap between the
/// n-th admissible distance and the farthest candidate at the search point).
class NeighbourSearch
{
public:
    NeighbourSearch(const Model& m, Scratch& s) : m_(m), s_(s) {}

    /// Decides the side instead of the first gather(): a given smooth patch and reference normal.
    void fix_side(int patch, const Vec3& reference_normal)
    {
        side_fixed_ = true;
        patch_ = patch;
        reference_normal_ = reference_normal;
    }

    /// Returns n' = min(n, admissible nodes found): the fit's nodes are the first n' of s.node...
    /// The first call fixes the side.
    int gather(const Vec3& x);

private:
    const Model& m_;
    Scratch& s_;
    bool searched_ = false;
    bool side_fixed_ = false;
    bool complete_ = false;  // the last search returned every node
    int patch_ = -1;
    Vec3 reference_normal_ = Vec3::Zero();
    Vec3 search_point_ = Vec3::Zero();
    double nth_distance_ = 0;
    double farthest_distance_ = 0;
};

/// A quadratic Monge patch z = <1, u, v, u², uv, v²>·a over the diffuse plane, in coordinates
/// scaled by the window radius (so the normal equations are well conditioned at any model size).
struct MongePatch
{
    Vec3 origin, e1, e2, n;
    double rho = 0;
    Vector6d a = Vector6d::Zero();
    bool linear = false;
};

/// Fits the patch to the first `count` nodes of s (hermite: with the nodes' slope rows); false
/// when the window or the weights vanish.
bool fit_monge_patch(const Model& m, const Scratch& s, int count, MongePatch& patch,
                     bool hermite = true);

/// Moves x onto the patch along its plane normal; fills point, normal and curvatures.
void evaluate_monge_patch(const MongePatch& patch, const Vec3& x, Projection& result);

/// The model of the given input (checked: InputError names what is wrong).
std::shared_ptr<Model> build_model(std::vector<Vec3> points, const std::vector<Vec3>* given_normals,
                                   std::vector<Triangle3> triangles, const FeatureSet& features,
                                   const HdiOptions& options);

}  // namespace detail
}  // namespace hdimesh::hdi
