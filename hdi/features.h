#pragma once
// Sharp features of a triangle surface: ridges (creases), corners and open-boundary curves.
// Detected once on the input; the HDI model fits each smooth side and each feature line apart.

#include <array>
#include <vector>

#include "hdi/point_cloud.h"

namespace hdimesh::hdi
{

struct FeatureOptions
{
    /// An interior edge is sharp when the normals of its two triangles differ by more than this.
    double ridge_angle_deg = 45.0;
    /// false: no ridge is detected (`--no-ridges`); open-boundary edges are still features.
    bool detect_ridges = true;
    /// Robustness rule. Sharp edges are cut into chains at branch points, ends and turns sharper
    /// than corner_angle_deg. A chain at least this fraction of the bounding-box diagonal long is
    /// a ridge; a shorter chain is kept only when both its ends are ends of kept chains (a short
    /// ridge between two corners of a machined part), repeated until nothing changes. Everything
    /// else is scan noise (isolated creases, short zig-zags, spurs) and dropped. Non-manifold edges
    /// are kept whatever their length (they are topology).
    double min_chain_length_fraction = 0.05;
    /// A feature line that turns by more than this angle at a vertex makes the vertex a corner.
    double corner_angle_deg = 60.0;
};

/// Edges are stored as (smaller index, larger index), sorted; corners sorted.
struct FeatureSet
{
    std::vector<std::array<int, 2>> ridge_edges;     ///< sharp and non-manifold edges
    std::vector<int> corners;                        ///< vertices that never move
    std::vector<std::array<int, 2>> boundary_edges;  ///< edges with one triangle (open boundary)
};

/// Sharp edges by dihedral angle, filtered into chains long enough to matter
/// (FeatureOptions::min_chain_length_fraction); open-boundary edges; corners where three or more
/// feature lines (ridges or boundary) meet, where a feature line ends, or where it turns by more
/// than corner_angle_deg. Inconsistently oriented neighbours are compared with one normal flipped.
/// Throws InputError for a triangle index out of range.
FeatureSet detect_features(const std::vector<Vec3>& points, const std::vector<Triangle3>& triangles,
                           const FeatureOptions& options = {});

/// Edges used by exactly one triangle, as (smaller, larger), sorted.
std::vector<std::array<int, 2>> open_boundary_edges(const std::vector<Triangle3>& triangles);

/// A feature line between two corners (or branch points), or a closed loop without any.
struct FeatureChain
{
    std::vector<int> vertices;  ///< consecutive along the line; a closed loop does not repeat its first vertex
    bool closed = false;
};

/// The ridge and boundary edges of `features` cut into chains at its corners and at every vertex
/// where the number of feature edges is not two.
std::vector<FeatureChain> feature_chains(const FeatureSet& features, int point_count);

/// Smooth patches: triangles joined across edges that are neither features nor non-manifold get
/// the same id (0, 1, ...). A node on a ridge touches two or more patches: one side of each.
std::vector<int> smooth_patches(const std::vector<Triangle3>& triangles, const FeatureSet& features);

}  // namespace hdimesh::hdi
