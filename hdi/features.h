#pragma once
// Sharp features of a triangle surface, detected once on the input: ridges (chains of sharp
// edges long enough to matter, not isolated creases of scan noise), corners (where curves meet,
// end or turn sharply, and isolated spikes) and open-boundary curves. On arrays, so that the
// surface mesh and the tet mesh's boundary follow the same rules; each writes the answer into
// its own properties. The HDI model fits each smooth side and each feature line apart.

#include <array>
#include <cstddef>
#include <vector>

#include "common/classification.h"
#include "hdi/point_cloud.h"

namespace hdimesh::hdi
{

using EdgeEnds = std::array<int, 2>;

struct FeatureOptions
{
    /// false: no edge is sharp by its angle (`--no-ridges`); open boundaries, borders between
    /// refs and edges of three or more triangles are still curves.
    bool detect_ridges = true;
    double ridge_angle_deg = 45.0;  ///< an edge is sharp when its face normals differ by more
    /// Creases between this angle and ridge_angle_deg are ridges too when they form a long chain
    /// (2·min_ridge_length): a shallow crease cut by chords strays from the model. At or above
    /// ridge_angle_deg: off.
    double crease_angle_deg = 30.0;
    double corner_turn_angle_deg = 50.0;  ///< a curve vertex whose curve turns by more is a corner
    /// The same on an open boundary: the crease angle, as a flat sheet has no dihedral angle
    /// to tell its outline's turns by (a scan's zig-zag is thinned by min_corner_spacing).
    double boundary_corner_turn_angle_deg = 30.0;
    /// An inner vertex away from kept curves whose angle defect (360° minus its angle sum)
    /// exceeds this is a spike kept as an isolated corner (at or above 360: off), if its angle
    /// sum is at least cone_min_angle_sum_deg: remeshing would cut its tip off.
    double cone_defect_deg = 60.0;
    /// Only a cone wide enough for fair triangles around its tip is kept.
    double cone_min_angle_sum_deg = 150.0;
    /// A boundary corner found only by a turn is dropped when another corner (a junction, an
    /// end, a sharper turn) is closer than this (0: keep all): zig-zag at the target's scale.
    /// Ridge turns are always kept: they are the corners of machined parts.
    double min_corner_spacing = 0.0;
    /// A ridge chain is kept when at least this fraction of the bbox diagonal long (twice that for
    /// a crease-only chain), or when both its ends are ends of kept chains; the rest is noise.
    double min_ridge_length = 0.05;
};

struct FeatureSummary
{
    std::size_t ridge_edges = 0, boundary_edges = 0;
    std::size_t ridge_vertices = 0, boundary_vertices = 0, corners = 0;
    std::size_t curves = 0;
    std::size_t dropped_ridge_chains = 0;  ///< sharp chains discarded as noise
};

/// What classify_features answers. Curves are numbered 0..curves-1 in the order of their first
/// edge in `edges`; a curve runs between corners or is a closed loop.
struct FeatureClassification
{
    /// The edges classified, (from, to): the caller's list, or each edge oriented as the first
    /// triangle that uses it and numbered in that order.
    std::vector<EdgeEnds> edges;
    /// Per point: Corner (id: its rank among the corners), Curve (id: the curve; open_boundary
    /// on an open boundary) or Surface (id: kNoModelEntity).
    std::vector<Classification> vertex_class;
    /// Per edge: Curve (id, open_boundary) or Surface.
    std::vector<Classification> edge_class;
    FeatureSummary summary;
};

/// Classifies every vertex and edge of the surface (points, triangles). `edges` (may be empty):
/// the caller's own edge list, every triangle side exactly once, so that curve ids and the
/// answer per edge follow the caller's numbering. `triangle_refs` (may be empty: one ref): a
/// border between refs is kept like a ridge. An edge of three or more triangles is a curve
/// whatever its length (it is topology); two triangles that disagree on their orientation are
/// compared with one normal flipped. Throws InputError for an index out of range, or an edge
/// list or ref list that does not fit the triangles.
FeatureClassification classify_features(const std::vector<Vec3>& points,
                                        const std::vector<Triangle3>& triangles,
                                        const FeatureOptions& options = {},
                                        const std::vector<EdgeEnds>& edges = {},
                                        const std::vector<int>& triangle_refs = {});

/// Edges are stored as (smaller index, larger index), sorted; corners sorted.
struct FeatureSet
{
    std::vector<EdgeEnds> ridge_edges;  ///< inner curve edges (ridges, ref borders, non-manifold)
    std::vector<int> corners;           ///< vertices that never move
    std::vector<EdgeEnds> boundary_edges;  ///< edges with one triangle (open boundary)
};

/// The features of a classification, as the HDI model takes them.
FeatureSet feature_set(const FeatureClassification& classification);

/// feature_set(classify_features(points, triangles, options)).
FeatureSet detect_features(const std::vector<Vec3>& points, const std::vector<Triangle3>& triangles,
                           const FeatureOptions& options = {});

/// Edges used by exactly one triangle, as (smaller, larger), sorted.
std::vector<EdgeEnds> open_boundary_edges(const std::vector<Triangle3>& triangles);

/// A feature line between two corners (or branch points), or a closed loop without any.
struct FeatureChain
{
    std::vector<int>
        vertices;  ///< consecutive along the line; a closed loop does not repeat its first vertex
    bool closed = false;
};

/// The ridge and boundary edges of `features` cut into chains at its corners and at every vertex
/// where the number of feature edges is not two.
std::vector<FeatureChain> feature_chains(const FeatureSet& features, int point_count);

/// Smooth patches: triangles joined across edges that are neither features nor non-manifold get
/// the same id (0, 1, ...). A node on a ridge touches two or more patches: one side of each.
std::vector<int> smooth_patches(const std::vector<Triangle3>& triangles,
                                const FeatureSet& features);

}  // namespace hdimesh::hdi
