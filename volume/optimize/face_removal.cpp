#include "volume/optimize/face_removal.h"

#include <algorithm>
#include <cassert>
#include <limits>

#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace
{

/// The two tets of the face with their role names.
struct FacePair
{
    int lower = -1, upper = -1;  // lower holds the face outward, upper on the other side
    int x = -1, y = -1, z = -1;  // the face, counter-clockwise seen from upper's apex
    int p = -1, q = -1;          // apex of lower, apex of upper
};

}  // namespace

FaceRemovalResult remove_face(TetMesh& mesh, OperatorContext& context, int t, int local_face,
                              const FaceRemovalOptions& options)
{
    FaceRemovalResult result;
    // layer 1: topology
    const int other = mesh.neighbors[t][local_face];
    if (other == kNoTet) return result;
    FacePair pair;
    pair.lower = t;
    pair.upper = other;
    const auto& fv = tet::kFaceVertices[local_face];
    pair.x = mesh.tets[t][fv[0]];
    pair.y = mesh.tets[t][fv[1]];
    pair.z = mesh.tets[t][fv[2]];
    pair.p = mesh.tets[t][local_face];
    for (int v : mesh.tets[other])
        if (v != pair.x && v != pair.y && v != pair.z) pair.q = v;
    if (pair.q < 0 || pair.q == pair.p) return result;
    // layer 2: constraints
    const auto& constraints = context.constraints;
    if (constraints.is_constrained_face(mesh, t, local_face) ||
        !constraints.is_removable_tet(pair.lower) || !constraints.is_removable_tet(pair.upper))
        return result;
    // layer 3: geometry, layer 4: quality
    result.worst_before =
        std::min(context.quality(mesh, pair.lower), context.quality(mesh, pair.upper));
    const auto& pts = mesh.points;
    const std::vector<TetVertices> added = {
        {pair.x, pair.y, pair.p, pair.q},
        {pair.y, pair.z, pair.p, pair.q},
        {pair.z, pair.x, pair.p, pair.q},
    };
    double worst = 1e300;
    for (const auto& tv : added)
        worst = std::min(worst, context.shape(pts[tv[0]], pts[tv[1]], pts[tv[2]], pts[tv[3]]));
    result.worst_after = worst;
    if (worst <= 0.0 || worst <= result.worst_before + options.min_gain) return result;
    if (context.too_long(pts[pair.p], pts[pair.q])) return result;
    replace_tets(mesh, context, {pair.lower, pair.upper}, added, mesh.tet_refs[pair.lower]);
    result.removed = true;
    return result;
}

// ---------------------------------------------------------------------------------------------
// Multi-face removal

namespace
{

constexpr double kImpossible = -std::numeric_limits<double>::infinity();

/// One face sandwiched between the apexes a and b, with the state of the dynamic program.
/// Its vertices run counter-clockwise seen from b; edge k joins v[k] and v[k+1 mod 3]. When the
/// face is removed, each of its edges either bounds the polygon, giving the new tet
/// (v[k], v[k+1], a, b), or is an inner edge, when the face across it is removed too.
struct SandwichFace
{
    int lower = -1, upper = -1;  // the tets (face, a) and (face, b)
    std::array<int, 3> v{};
    int parent_edge = -1;                     // edge shared with the face it was reached from
    std::array<int, 3> child = {-1, -1, -1};  // index of the face reached across each edge
    std::array<double, 3> best{};             // best worst new quality across edge k
    std::array<bool, 3> extend{};             // ... reached by removing the child too
};

/// The apexes, the tree of sandwiched faces grown from the seed (breadth first: every child
/// after its parent), and the best choice once unwound.
struct MultiFacePlan
{
    int a = -1, b = -1, ref = 0;
    bool legal = false;
    std::vector<SandwichFace> faces;
    double worst_after = kImpossible;
    double worst_before = 0;
    std::vector<int> chosen;               // face indices, depth first from the seed
    std::vector<std::array<int, 2>> ring;  // the polygon's edges, in order around it
};

int fourth_vertex(const TetVertices& tv, int x, int y, int z)
{
    for (int v : tv)
        if (v != x && v != y && v != z) return v;
    return -1;
}

bool has_vertex(const TetVertices& tv, int v)
{
    return std::find(tv.begin(), tv.end(), v) != tv.end();
}

/// Vertices a and b are joined by an edge.
bool is_edge(const TetMesh& mesh, const OperatorContext& context, int a, int b)
{
    std::vector<int> ball;
    context.ball(mesh, a, ball);
    return std::any_of(ball.begin(), ball.end(),
                       [&](int t) { return has_vertex(mesh.tets[t], b); });
}

/// The face of tet `lower` opposite its local vertex `local_a`, as seen from the tet across it.
SandwichFace make_face(const TetMesh& mesh, int lower, int local_a)
{
    SandwichFace face;
    face.lower = lower;
    face.upper = mesh.neighbors[lower][local_a];
    const auto& fv = tet::kFaceVertices[local_a];
    for (int k = 0; k < 3; ++k) face.v[k] = mesh.tets[lower][fv[k]];
    return face;
}

/// Finds the face across edge k = (u, v) of `from` when it is sandwiched between a and b too
/// and the edge may become an inner edge of the polygon: the shell of (u, v) must be exactly
/// the four tets  from.lower -(u v a)- lower2 -(u v c)- upper2 -(u v b)- from.upper, and none
/// of what disappears with the edge (the edge, its three faces, the two tets) constrained.
bool sandwiched_neighbor(const TetMesh& mesh, const OperatorContext& context,
                         const MultiFacePlan& plan, const SandwichFace& from, int k,
                         SandwichFace& next)
{
    const int u = from.v[k], v = from.v[(k + 1) % 3], w = from.v[(k + 2) % 3];
    // topology first (cheap, and most edges fail it): the shell of (u, v) is those four tets
    const int lower_w = local_index(mesh, from.lower, w);
    const int upper_w = local_index(mesh, from.upper, w);
    if (lower_w < 0 || upper_w < 0) return false;
    const int lower2 = mesh.neighbors[from.lower][lower_w];
    const int upper2 = mesh.neighbors[from.upper][upper_w];
    if (lower2 == kNoTet || upper2 == kNoTet) return false;
    const int lower2_a = local_index(mesh, lower2, plan.a);
    if (lower2_a < 0 || mesh.neighbors[lower2][lower2_a] != upper2) return false;
    const int c = fourth_vertex(mesh.tets[lower2], u, v, plan.a);
    if (c < 0 || c == plan.b || !has_vertex(mesh.tets[upper2], c)) return false;
    // then constraints: the edge is no feature; its faces (u, v, a), (u, v, b), (u, v, c) are
    // not listed and lie between tets of one ref; the new tets may be removed
    const auto& constraints = context.constraints;
    if (constraints.is_constrained_edge(u, v) ||
        constraints.is_constrained_face(mesh, from.lower, lower_w) ||
        constraints.is_constrained_face(mesh, from.upper, upper_w) ||
        constraints.is_constrained_face(mesh, lower2, lower2_a) ||
        !constraints.is_removable_tet(lower2) || !constraints.is_removable_tet(upper2))
        return false;
    next = make_face(mesh, lower2, lower2_a);
    // the shared edge runs the other way round the neighbour
    next.parent_edge = -1;
    for (int j = 0; j < 3; ++j)
        if (next.v[j] == v && next.v[(j + 1) % 3] == u) next.parent_edge = j;
    return next.parent_edge >= 0;
}

/// Layers 1 and 2: the seed's topology and constraints, then the tree of sandwiched faces.
void grow_sandwich(const TetMesh& mesh, const OperatorContext& context, int t, int local_face,
                   const MultiFaceRemovalOptions& options, MultiFacePlan& plan)
{
    const auto& constraints = context.constraints;
    if (mesh.is_dead(t) || mesh.neighbors[t][local_face] == kNoTet) return;
    SandwichFace seed = make_face(mesh, t, local_face);
    plan.a = mesh.tets[t][local_face];
    plan.b = fourth_vertex(mesh.tets[seed.upper], seed.v[0], seed.v[1], seed.v[2]);
    if (plan.b < 0 || plan.b == plan.a) return;
    if (constraints.is_constrained_face(mesh, t, local_face) ||
        !constraints.is_removable_tet(seed.lower) || !constraints.is_removable_tet(seed.upper))
        return;
    plan.ref = mesh.tet_refs[t];
    plan.legal = true;

    plan.faces.push_back(seed);
    const int max_faces = std::max(1, options.max_faces);
    for (std::size_t i = 0; i < plan.faces.size(); ++i)
        for (int k = 0; k < 3; ++k)
        {
            if (k == plan.faces[i].parent_edge) continue;
            if (static_cast<int>(plan.faces.size()) >= max_faces) return;
            SandwichFace next;
            if (!sandwiched_neighbor(mesh, context, plan, plan.faces[i], k, next)) continue;
            // a face met twice closes a cycle around an inner vertex: the tree keeps its first
            // visit only. The vertex cannot be deleted: removing every face around it would
            // leave an uncrossed edge whose two new tets face opposite ways (one of quality
            // <= 0, so the program never picks it), and ring_is_simple guards the commit.
            const bool seen =
                std::any_of(plan.faces.begin(), plan.faces.end(),
                            [&](const SandwichFace& f) { return f.lower == next.lower; });
            if (seen) continue;
            plan.faces[i].child[k] = static_cast<int>(plan.faces.size());
            plan.faces.push_back(next);
        }
}

/// Layers 3 and 4: the program over the tree, children first. best[k] of a face is the better
/// of stopping at edge k (the new tet over it) and removing the child across it (the worst of
/// the child's own best edges); the seed's value is the worst of its three edges. Ties stop,
/// so fewer faces are removed.
void choose_faces(const TetMesh& mesh, const OperatorContext& context, MultiFacePlan& plan)
{
    const auto& p = mesh.points;
    const Vec3& pa = p[plan.a];
    const Vec3& pb = p[plan.b];
    auto subtree_value = [&](const SandwichFace& face) {
        double value = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 3; ++k)
            if (k != face.parent_edge) value = std::min(value, face.best[k]);
        return value;
    };
    for (int i = static_cast<int>(plan.faces.size()) - 1; i >= 0; --i)
    {
        SandwichFace& face = plan.faces[i];
        for (int k = 0; k < 3; ++k)
        {
            if (k == face.parent_edge) continue;
            const double stop = context.shape(p[face.v[k]], p[face.v[(k + 1) % 3]], pa, pb);
            const double through =
                face.child[k] >= 0 ? subtree_value(plan.faces[face.child[k]]) : kImpossible;
            face.extend[k] = through > stop;
            face.best[k] = std::max(stop, through);
        }
    }
    plan.worst_after = subtree_value(plan.faces[0]);

    // unwind depth first; each face lists its edges from the one after its parent edge, so
    // the polygon's edges come out in order around it
    plan.chosen.clear();
    plan.ring.clear();
    struct Visit
    {
        int face, step;
    };
    std::vector<Visit> stack = {{0, 0}};
    plan.chosen.push_back(0);
    while (!stack.empty())
    {
        Visit& top = stack.back();
        const SandwichFace& face = plan.faces[top.face];
        const int edges = face.parent_edge < 0 ? 3 : 2;
        if (top.step == edges)
        {
            stack.pop_back();
            continue;
        }
        const int k = (face.parent_edge + 1 + top.step) % 3;
        ++top.step;
        if (face.extend[k])
        {
            plan.chosen.push_back(face.child[k]);
            stack.push_back({face.child[k], 0});  // `top` is not used after this
        }
        else
        {
            plan.ring.push_back({face.v[k], face.v[(k + 1) % 3]});
        }
    }
    plan.worst_before = std::numeric_limits<double>::infinity();
    for (int i : plan.chosen)
        plan.worst_before = std::min({plan.worst_before, context.quality(mesh, plan.faces[i].lower),
                                      context.quality(mesh, plan.faces[i].upper)});
}

MultiFacePlan plan_multi_face_removal(const TetMesh& mesh, const OperatorContext& context, int t,
                                      int local_face, const MultiFaceRemovalOptions& options)
{
    MultiFacePlan plan;
    grow_sandwich(mesh, context, t, local_face, options, plan);
    if (!plan.legal) return plan;
    choose_faces(mesh, context, plan);
    // ab must be a new edge. Tested last, and only for a removal that would otherwise be
    // committed, because it walks the ball of a (three quarters of the operator's time when
    // tested first). It is a guard against round-off: if ab were an edge, the segment would
    // lie in the mesh's skeleton, not inside the removed tets, so the new tets around it could
    // not all be positive (on an adapted sphere: 399 seeds with ab an edge, none positive).
    if (plan.worst_after > 0.0 && plan.worst_after > plan.worst_before + options.min_gain &&
        !context.too_long(mesh.points[plan.a], mesh.points[plan.b]) &&
        is_edge(mesh, context, plan.a, plan.b))
        plan.legal = false;
    return plan;
}

/// The polygon passes through each of its vertices once. Positive new tets already imply it
/// (the tets around ab turn once around it); checked anyway as the commit's last guard.
bool ring_is_simple(const std::vector<std::array<int, 2>>& ring)
{
    std::vector<int> vertices;
    vertices.reserve(ring.size());
    for (const auto& edge : ring) vertices.push_back(edge[0]);
    std::sort(vertices.begin(), vertices.end());
    return std::adjacent_find(vertices.begin(), vertices.end()) == vertices.end();
}

MultiFaceRemovalResult summarize(const MultiFacePlan& plan)
{
    MultiFaceRemovalResult result;
    result.legal = plan.legal;
    if (!plan.legal) return result;
    result.worst_before = plan.worst_before;
    result.worst_after = plan.worst_after;
    result.sandwich_size = static_cast<int>(plan.faces.size());
    result.faces_removed = static_cast<int>(plan.chosen.size());
    result.tets_removed = 2 * result.faces_removed;
    result.tets_created = static_cast<int>(plan.ring.size());
    return result;
}

}  // namespace

MultiFaceRemovalResult evaluate_multi_face_removal(const TetMesh& mesh,
                                                   const OperatorContext& context, int t,
                                                   int local_face,
                                                   const MultiFaceRemovalOptions& options)
{
    return summarize(plan_multi_face_removal(mesh, context, t, local_face, options));
}

MultiFaceRemovalResult remove_multi_face(TetMesh& mesh, OperatorContext& context, int t,
                                         int local_face, const MultiFaceRemovalOptions& options)
{
    const MultiFacePlan plan = plan_multi_face_removal(mesh, context, t, local_face, options);
    MultiFaceRemovalResult result = summarize(plan);
    if (!plan.legal || plan.worst_after <= 0.0 ||
        plan.worst_after <= plan.worst_before + options.min_gain)
        return result;
    const auto& pts = mesh.points;
    if (context.too_long(pts[plan.a], pts[plan.b])) return result;
    assert(plan.ring.size() == plan.chosen.size() + 2);
    if (!ring_is_simple(plan.ring)) return result;

    std::vector<int> removed;
    removed.reserve(2 * plan.chosen.size());
    for (int i : plan.chosen)
    {
        removed.push_back(plan.faces[i].lower);
        removed.push_back(plan.faces[i].upper);
    }
    std::vector<TetVertices> added;
    added.reserve(plan.ring.size());
    for (const auto& [u, v] : plan.ring) added.push_back({u, v, plan.a, plan.b});
    replace_tets(mesh, context, removed, added, plan.ref);
    result.removed = true;
    return result;
}

}  // namespace hdimesh::volume
