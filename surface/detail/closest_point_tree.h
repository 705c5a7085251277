#pragma once
// A bounding-volume tree over triangles or segments answering "closest point" queries exactly.
// The surface model uses it to keep vertices on the input surface and ridge vertices on their
// input ridge line; the quality report uses it for Hausdorff distances.

#include <array>
#include <vector>

#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

/// Closest point on the triangle (a, b, c) to p (Ericson, Real-Time Collision Detection 5.1.5).
Vec3d closest_point_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c);
/// Closest point on the segment [a, b] to p.
Vec3d closest_point_on_segment(const Vec3d& p, const Vec3d& a, const Vec3d& b);

class ClosestPointTree
{
public:
    struct Hit
    {
        Vec3d point{0, 0, 0};
        double distance = -1.0;  // < 0: the tree is empty
        int primitive = -1;      // index in the order primitives were given
    };

    ClosestPointTree() = default;
    /// Triangles (three points each).
    static ClosestPointTree from_triangles(std::vector<std::array<Vec3d, 3>> triangles);
    /// Segments (two points each).
    static ClosestPointTree from_segments(const std::vector<std::array<Vec3d, 2>>& segments);
    /// The tree of from_triangles, built lazily: a node is split when a search first opens it,
    /// so a tree asked a few hundred queries costs a fraction of a full build (the top levels
    /// still partition the whole set). The same answers as from_triangles, ties included (the
    /// same splits, in the same order within each node). A search then modifies the tree: not
    /// for concurrent queries.
    static ClosestPointTree lazy_from_triangles(std::vector<std::array<Vec3d, 3>> triangles);
    /// This tree made lazy_from_triangles(triangles) in place, in the memory it already has;
    /// `triangles` gets back the storage of its earlier triangles (content unspecified), for a
    /// caller that refills it for the next rebuild. (The remesher's refinement builds a tree of
    /// the output every round: fresh arrays each time were a fifth of the refinement's time,
    /// most of it the page faults of memory first touched.)
    void rebuild_lazy(std::vector<std::array<Vec3d, 3>>& triangles);

    Hit closest(const Vec3d& p) const;
    /// The same hit as closest(p), found faster when `hint` (a primitive index, e.g. the one a
    /// nearby point hit) is near p: its distance bounds the search from the start, so most nodes
    /// are pruned without being opened. Ties resolve exactly as in closest(p) (the bound is set
    /// just above the hint's distance, never at it), so the answer does not depend on the hint;
    /// an out-of-range hint is ignored.
    Hit closest(const Vec3d& p, int hint) const;
    /// Whether no primitive but `primitive` (an index as given) has its closest point within
    /// sqrt(bound_d2) of p. (The remesher's refinement asks it of a far point's closest face with
    /// a bound just above its distance: while that face and those around it do not change, the
    /// face stays the closest, whatever tree the output makes.)
    bool alone_within(const Vec3d& p, int primitive, double bound_d2) const;
    bool empty() const { return count_ == 0; }
    std::size_t size() const { return count_; }

private:
    struct Node
    {
        Vec3d lo, hi;
        int first = 0, count = 0;  // leaf: primitives [first, first+count) of order_
        int left = -1, right = -1;
    };
    struct BuildScratch
    {
        std::vector<Vec3d> lo, hi, centroid;  // per primitive (as given): box, sum of its points
    };
    void build(bool lazy);
    // Node `index` gets its range of order_ and the box of its primitives (a lazy leaf: its
    // primitives in leaf order too).
    void set_node(int index, int first, int count, const BuildScratch& scratch) const;
    // Node `index` (more than a leaf's primitives) split at the median centroid along the widest
    // axis of its box into two new nodes; and, eagerly built, those too, recursively.
    void split_node(int index, const BuildScratch& scratch) const;
    void build_node(int index, const BuildScratch& scratch) const;
    Vec3d closest_on(const std::array<Vec3d, 3>& primitive,
                     const Vec3d& p) const;  // a segment: points 0, 1
    // The nearest primitive among those closer than sqrt(bound_d2) (primitive -1 if none).
    Hit search(const Vec3d& p, double bound_d2) const;

    // Mutable: a lazy tree's search splits the nodes it opens first (an eager tree's never
    // changes after the build).
    std::size_t count_ = 0;  // primitives
    // In leaf order once built. Lazy: only the first count_ entries are the tree's, each written
    // when its leaf is opened (the rest, and unopened leaves, hold an earlier build's: never
    // read; primitives_.size() is not the count).
    mutable std::vector<std::array<Vec3d, 3>> primitives_;
    mutable std::vector<std::array<Vec3d, 2>> boxes_;  // per primitive in leaf order: lo, hi
    bool segments_ = false;
    mutable std::vector<int> order_;  // leaf-order position -> index as given
    std::vector<int> position_;       // index as given -> leaf-order position (eager)
    mutable std::vector<Node> nodes_;
    bool lazy_ = false;
    std::vector<std::array<Vec3d, 3>> given_;  // lazy: the primitives as given
    BuildScratch scratch_;                     // lazy: kept for the splits to come
};

}  // namespace hdimesh::surface
