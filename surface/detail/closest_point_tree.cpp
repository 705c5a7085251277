#include "surface/detail/closest_point_tree.h"

#include <algorithm>
#include <cassert>
#include <limits>

#include "surface/detail/prefetch.h"
#include "surface/detail/vector_room.h"

namespace hdimesh::surface
{

namespace
{
// Ericson's test of p's region at corner x of the triangle (a, x, y): x's vertex region, or the
// edge region of ax (then `closest` is set, true). The dots are those of ax and ay with ap
// (ax_ap, ay_ap) and with xp (ax_xp, ay_xp); `area` gets the numerator of y's barycentric
// weight (vc at x = b, vb at x = c), which the interior case needs.
bool in_corner_region(const Vec3d& a, const Vec3d& x, const Vec3d& ax, double ax_ap, double ay_ap,
                      double ax_xp, double ay_xp, double& area, Vec3d& closest)
{
    if (ax_xp >= 0.0 && ay_xp <= ax_xp)
    {
        closest = x;
        return true;
    }
    area = ax_ap * ay_xp - ax_xp * ay_ap;
    if (area <= 0.0 && ax_ap >= 0.0 && ax_xp <= 0.0)
    {
        const double t = ax_ap / (ax_ap - ax_xp);
        closest = a + t * ax;
        return true;
    }
    return false;
}
}  // namespace

Vec3d closest_point_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c)
{
    const Vec3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = OpenMesh::dot(ab, ap), d2 = OpenMesh::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    Vec3d closest;
    double vc = 0.0, vb = 0.0;
    const Vec3d bp = p - b;
    const double d3 = OpenMesh::dot(ab, bp), d4 = OpenMesh::dot(ac, bp);
    if (in_corner_region(a, b, ab, d1, d2, d3, d4, vc, closest)) return closest;
    const Vec3d cp = p - c;
    const double d5 = OpenMesh::dot(ab, cp), d6 = OpenMesh::dot(ac, cp);
    if (in_corner_region(a, c, ac, d2, d1, d6, d5, vb, closest)) return closest;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return b + w * (c - b);
    }
    const double sum = va + vb + vc;
    if (!(sum > 0.0)) return closest_point_on_segment(p, a, b);  // degenerate triangle
    const double v = vb / sum, w = vc / sum;
    return a + v * ab + w * ac;
}

Vec3d closest_point_on_segment(const Vec3d& p, const Vec3d& a, const Vec3d& b)
{
    const Vec3d ab = b - a;
    const double len2 = ab.sqrnorm();
    if (len2 <= 0.0) return a;
    const double t = std::clamp(OpenMesh::dot(p - a, ab) / len2, 0.0, 1.0);
    return a + t * ab;
}

namespace
{
constexpr int kLeafSize = 4;

// The squared distance from p to the box [lo, hi] (0 inside).
double box_distance2(const Vec3d& p, const Vec3d& lo, const Vec3d& hi)
{
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
        const double below = lo[k] - p[k], above = p[k] - hi[k];
        const double d = std::max({below, above, 0.0});
        d2 += d * d;
    }
    return d2;
}
}  // namespace

ClosestPointTree ClosestPointTree::from_triangles(std::vector<std::array<Vec3d, 3>> triangles)
{
    ClosestPointTree tree;
    tree.primitives_ = std::move(triangles);
    tree.segments_ = false;
    tree.build(false);
    return tree;
}

ClosestPointTree ClosestPointTree::lazy_from_triangles(std::vector<std::array<Vec3d, 3>> triangles)
{
    ClosestPointTree tree;
    tree.rebuild_lazy(triangles);
    return tree;
}

void ClosestPointTree::rebuild_lazy(std::vector<std::array<Vec3d, 3>>& triangles)
{
    primitives_.swap(triangles);
    segments_ = false;
    build(true);
}

ClosestPointTree ClosestPointTree::from_segments(const std::vector<std::array<Vec3d, 2>>& segments)
{
    ClosestPointTree tree;
    tree.primitives_.reserve(segments.size());
    for (const auto& s : segments) tree.primitives_.push_back({s[0], s[1], s[1]});
    tree.segments_ = true;
    tree.build(false);
    return tree;
}

void ClosestPointTree::build(bool lazy)
{
    lazy_ = lazy;
    detail::resize_with_room(order_, primitives_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
    nodes_.clear();
    // Per primitive, once: its box and its centroid sums (the split keys), so a node reads
    // them from small arrays instead of the primitives (the refinement builds the output's tree
    // every round).
    // The same sums and min/max as before: the same tree.
    // (A lazy tree keeps its scratch for the splits to come, and a rebuilt one its capacity.)
    BuildScratch eager_scratch;
    BuildScratch& scratch = lazy ? scratch_ : eager_scratch;
    auto size_scratch = [&](auto& v) {
        if (lazy)
            detail::resize_with_room(v, primitives_.size());
        else
            v.resize(primitives_.size());  // (built once, dropped after the build)
    };
    size_scratch(scratch.lo);
    size_scratch(scratch.hi);
    size_scratch(scratch.centroid);
    for (std::size_t i = 0; i < primitives_.size(); ++i)
    {
        const auto& t = primitives_[i];
        Vec3d lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
        for (const Vec3d& q : t)
        {
            lo.minimize(q);
            hi.maximize(q);
        }
        scratch.lo[i] = lo;
        scratch.hi[i] = hi;
        for (int axis = 0; axis < 3; ++axis)
            scratch.centroid[i][axis] = t[0][axis] + t[1][axis] + t[2][axis];
    }
    if (lazy)
    {
        // The leaf-order arrays are filled leaf by leaf as the searches split the nodes.
        // (Swapped, not moved: a rebuilt tree's leaf-order array reuses the storage of the
        // triangles it was given before.)
        // (Not cleared: a leaf writes its entries before a search reads them, and zero-filling the
        // whole array again at every rebuild of the remesher's refinement rounds was most of what
        // a rebuild wrote.)
        given_.swap(primitives_);
        count_ = given_.size();
        if (primitives_.size() < count_) detail::resize_with_room(primitives_, count_);
        if (boxes_.size() < count_) detail::resize_with_room(boxes_, count_);
        if (given_.empty()) return;
        detail::reserve_with_room(nodes_,
                                  2 * count_ + 1);  // a binary tree over n primitives: < 2n nodes
        nodes_.push_back(Node{});
        set_node(0, 0, static_cast<int>(given_.size()), scratch_);
        return;
    }
    count_ = primitives_.size();
    if (!primitives_.empty())
    {
        nodes_.reserve(2 * primitives_.size() + 1);  // a binary tree over n primitives: < 2n nodes
        nodes_.push_back(Node{});
        set_node(0, 0, static_cast<int>(primitives_.size()), scratch);
        build_node(0, scratch);
        boxes_.resize(primitives_.size());
        for (std::size_t i = 0; i < order_.size(); ++i)
            boxes_[i] = {scratch.lo[order_[i]], scratch.hi[order_[i]]};
    }
    // The primitives in leaf order, so a leaf reads one contiguous block; position_ maps back.
    std::vector<std::array<Vec3d, 3>> in_leaf_order(primitives_.size());
    position_.resize(primitives_.size());
    for (std::size_t i = 0; i < order_.size(); ++i)
    {
        in_leaf_order[i] = primitives_[order_[i]];
        position_[order_[i]] = static_cast<int>(i);
    }
    primitives_ = std::move(in_leaf_order);
}

void ClosestPointTree::set_node(int index, int first, int count, const BuildScratch& scratch) const
{
    Vec3d lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (int i = first; i < first + count; ++i)
    {
        lo.minimize(scratch.lo[order_[i]]);
        hi.maximize(scratch.hi[order_[i]]);
    }
    Node& node = nodes_[index];
    node.lo = lo;
    node.hi = hi;
    node.first = first;
    node.count = count;
    if (lazy_ && count <= kLeafSize)
        for (int i = first; i < first + count; ++i)
        {
            primitives_[i] = given_[order_[i]];
            boxes_[i] = {scratch.lo[order_[i]], scratch.hi[order_[i]]};
        }
}

void ClosestPointTree::split_node(int index, const BuildScratch& scratch) const
{
    const int first = nodes_[index].first, count = nodes_[index].count;
    // Split at the median centroid along the widest axis.
    const Vec3d extent = nodes_[index].hi - nodes_[index].lo;
    const int axis =
        extent[0] >= extent[1] && extent[0] >= extent[2] ? 0 : (extent[1] >= extent[2] ? 1 : 2);
    const int half = count / 2;
    std::nth_element(
        order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
        [&](int a, int b) { return scratch.centroid[a][axis] < scratch.centroid[b][axis]; });
    // The two children side by side: a search reads both boxes when it opens their parent.
    const int left = static_cast<int>(nodes_.size());
    nodes_.push_back(Node{});
    nodes_.push_back(Node{});
    nodes_[index].left = left;
    nodes_[index].right = left + 1;
    set_node(left, first, half, scratch);
    set_node(left + 1, first + half, count - half, scratch);
}

void ClosestPointTree::build_node(int index, const BuildScratch& scratch) const
{
    if (nodes_[index].count <= kLeafSize) return;
    split_node(index, scratch);
    const int left = nodes_[index].left;
    build_node(left, scratch);
    build_node(left + 1, scratch);
}

Vec3d ClosestPointTree::closest_on(const std::array<Vec3d, 3>& primitive, const Vec3d& p) const
{
    const auto& t = primitive;
    return segments_ ? closest_point_on_segment(p, t[0], t[1])
                     : closest_point_on_triangle(p, t[0], t[1], t[2]);
}

ClosestPointTree::Hit ClosestPointTree::closest(const Vec3d& p) const
{
    return search(p, std::numeric_limits<double>::max());
}

ClosestPointTree::Hit ClosestPointTree::closest(const Vec3d& p, int hint) const
{
    if (hint < 0 || hint >= static_cast<int>(count_)) return closest(p);
    // Just above the hint's squared distance: the primitives closest to p all pass the bound, and
    // the first of them in traversal order wins, as without a bound. The relative margin covers
    // the rounding of box distances against point distances.
    // (A lazy tree may not have put the hint in leaf order yet: read it as given.)
    const double hint_d2 =
        (closest_on(lazy_ ? given_[hint] : primitives_[position_[hint]], p) - p).sqrnorm();
    const Hit hit = search(p, hint_d2 * (1.0 + 1e-9) + std::numeric_limits<double>::min());
    return hit.primitive >= 0 ? hit : closest(p);
}

bool ClosestPointTree::alone_within(const Vec3d& p, int primitive, double bound_d2) const
{
    if (nodes_.empty()) return true;
    auto box_d2 = [&](const Vec3d& lo, const Vec3d& hi) { return box_distance2(p, lo, hi); };
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
        const int index = stack[--top];
        if (box_d2(nodes_[index].lo, nodes_[index].hi) > bound_d2) continue;
        if (nodes_[index].left < 0 && nodes_[index].count > kLeafSize) split_node(index, scratch_);
        const Node& n = nodes_[index];
        if (n.left >= 0)
        {
            stack[top++] = n.left;
            stack[top++] = n.right;
            continue;
        }
        for (int i = n.first; i < n.first + n.count; ++i)
            if (order_[i] != primitive && !(box_d2(boxes_[i][0], boxes_[i][1]) > bound_d2) &&
                (closest_on(primitives_[i], p) - p).sqrnorm() <= bound_d2)
                return false;
    }
    return true;
}

ClosestPointTree::Hit ClosestPointTree::search(const Vec3d& p, double bound_d2) const
{
    Hit best;
    if (nodes_.empty()) return best;
    assert(lazy_ || primitives_.size() == count_);
    double best_d2 = bound_d2;
    auto box_d2 = [&](const Vec3d& lo, const Vec3d& hi) { return box_distance2(p, lo, hi); };
    // Depth-first, nearer child first, pruned by the best distance so far. A node's box distance
    // is computed once, when its parent orders the children, and travels with it on the stack.
    struct Pending
    {
        int node;
        double d2;
    };
    Pending stack[128];
    const double tie_slack = 1e-24 * p.sqrnorm();
    int top = 0;
    stack[top++] = {0, box_d2(nodes_[0].lo, nodes_[0].hi)};
    while (top > 0)
    {
        const Pending pending = stack[--top];
        if (pending.d2 >= best_d2) continue;
        // Lazy: a node opened for the first time is split now (before n is taken: a copied tree
        // has no spare capacity, its nodes may move).
        if (nodes_[pending.node].left < 0 && nodes_[pending.node].count > kLeafSize)
            split_node(pending.node, scratch_);
        const Node& n = nodes_[pending.node];
        if (n.left < 0)
        {
            for (int i = n.first; i < n.first + n.count; ++i)
            {
                // A primitive whose box is clearly farther than the best cannot win: its closest
                // point is not computed (most of them, on the remesher's queries).
                // The margin keeps every near tie to the exact test, so the winner is unchanged:
                // relative for distances away from zero, absolute (far above the rounding of a
                // squared distance at p's magnitude) for points on the surface.
                if (box_d2(boxes_[i][0], boxes_[i][1]) > best_d2 * (1.0 + 1e-9) + tie_slack)
                    continue;
                const Vec3d q = closest_on(primitives_[i], p);
                const double d2 = (q - p).sqrnorm();
                if (d2 < best_d2)
                {
                    best_d2 = d2;
                    best.point = q;
                    best.primitive = order_[i];
                }
            }
            continue;
        }
        const double dl = box_d2(nodes_[n.left].lo, nodes_[n.left].hi),
                     dr = box_d2(nodes_[n.right].lo, nodes_[n.right].hi);
        // The farther child is pushed first (popped last); a child already beyond the best
        // distance would be skipped when popped, so it is not pushed at all.
        const Pending left{n.left, dl}, right{n.right, dr};
        const Pending& near = dl < dr ? left : right;
        const Pending& far = dl < dr ? right : left;
        if (far.d2 < best_d2) stack[top++] = far;
        if (near.d2 < best_d2)
        {
            stack[top++] = near;
            // Opened next: its children's boxes (or its primitives) are wanted soon. The trees
            // are larger than the cache.
            const Node& next = nodes_[near.node];
            if (next.left >= 0)
            {
                detail::prefetch(&nodes_[next.left]);
                detail::prefetch(&nodes_[next.left + 1]);
            }
            else
            {
                detail::prefetch(&boxes_[next.first]);
                detail::prefetch(&primitives_[next.first]);
            }
        }
    }
    if (best.primitive >= 0) best.distance = std::sqrt(best_d2);
    return best;
}

}  // namespace hdimesh::surface
