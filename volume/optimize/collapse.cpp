#include "volume/optimize/collapse.h"

#include <algorithm>
#include <limits>
#include <optional>

#include "volume/optimize/vertex_marks.h"

namespace hdimesh::volume
{

namespace
{

/// from's ball split by role: the shell of the edge (dies) and the rest (re-attached to `to`).
struct CollapseConfiguration
{
    int from = -1, to = -1;
    std::vector<int> ball;
    std::vector<int> shell;           // tets containing both from and to
    std::vector<TetVertices> moved;   // the other tets, with from replaced by to
    std::vector<int> new_neighbours;  // vertices joined to `to` by the collapse
    int ref = 0;                      // the ball's one tet ref
};

/// Layer 2 of collapse_edge: from's ball split into config (false: no edge (from, to), more than
/// one ref, or a tet that may not be removed).
bool collect_collapse_configuration(const TetMesh& mesh, OperatorContext& context, int from, int to,
                                    CollapseConfiguration& config)
{
    config.from = from;
    config.to = to;
    context.ball(mesh, from, config.ball);
    const int ref = mesh.tet_refs[config.ball.front()];
    config.ref = ref;
    for (int t : config.ball)
    {
        if (mesh.tet_refs[t] != ref || !context.constraints.is_removable_tet(t)) return false;
        const auto& tv = mesh.tets[t];
        if (local_index(mesh, t, to) >= 0)
        {
            config.shell.push_back(t);
            continue;
        }
        TetVertices moved = tv;
        for (int& v : moved)
            if (v == from) v = to;
        config.moved.push_back(moved);
    }
    if (config.shell.empty() || config.moved.empty()) return false;  // (from, to) no edge
    // new neighbours: the vertices of the moved tets that no shell tet has, in increasing order
    VertexMarks& marks = vertex_marks();
    marks.next_round(mesh.num_vertices());
    for (int t : config.shell)
        for (int v : mesh.tets[t]) marks.mark(v);
    for (const auto& tv : config.moved)
        for (int v : tv)
            if (marks.mark(v)) config.new_neighbours.push_back(v);
    std::sort(config.new_neighbours.begin(), config.new_neighbours.end());
    return true;
}

}  // namespace

std::optional<Vec3> flat_boundary_normal(const TetMesh& mesh, const OperatorContext& context, int v,
                                         int* neighbour)
{
    std::vector<int> ball;
    context.ball(mesh, v, ball);
    Vec3 normal = Vec3::Zero();
    int ref = 0;
    bool first = true, neighbour_on_boundary = neighbour == nullptr;
    for (int t : ball)
        for (int f = 0; f < 4; ++f)
        {
            const auto& fv = tet::kFaceVertices[f];
            const auto& tv = mesh.tets[t];
            if (tv[f] == v) continue;  // the face opposite v
            if (mesh.neighbors[t][f] != kNoTet)
            {
                if (context.constraints.is_constrained_face(mesh, t, f)) return std::nullopt;
                continue;
            }
            const int listed =
                context.constraints.listed_triangle({tv[fv[0]], tv[fv[1]], tv[fv[2]]});
            if (listed < 0) return std::nullopt;
            const int face_ref = static_cast<std::size_t>(listed) < mesh.triangle_refs.size()
                                     ? mesh.triangle_refs[listed]
                                     : 0;
            const Vec3 n = (mesh.points[tv[fv[1]]] - mesh.points[tv[fv[0]]])
                               .cross(mesh.points[tv[fv[2]]] - mesh.points[tv[fv[0]]]);
            if (first)
            {
                normal = n;
                ref = face_ref;
                first = false;
            }
            // one plane, one side: the normals parallel to round-off
            if (face_ref != ref || n.dot(normal) <= 0.0 ||
                n.cross(normal).norm() > 1e-12 * n.norm() * normal.norm())
                return std::nullopt;
            if (neighbour)
                for (int k : fv)
                    neighbour_on_boundary = neighbour_on_boundary || tv[k] == *neighbour;
        }
    if (first || !neighbour_on_boundary || !(normal.norm() > 0.0)) return std::nullopt;
    return Vec3(normal.normalized());
}

namespace
{

/// Layer 1 for a boundary `from`: a flat boundary star with `to` on it, the edge in its plane.
bool in_boundary_plane(const TetMesh& mesh, const OperatorContext& context, int from, int to)
{
    const std::optional<Vec3> normal = flat_boundary_normal(mesh, context, from, &to);
    if (!normal) return false;
    const Vec3 e = mesh.points[to] - mesh.points[from];
    return std::abs(e.dot(*normal)) <= 1e-12 * e.norm();
}

}  // namespace

CollapseResult collapse_edge(TetMesh& mesh, OperatorContext& context, int from, int to,
                             const CollapseOptions& options)
{
    CollapseResult result;
    // layer 1: classes — a free interior vertex moves onto another vertex, or (when asked) a
    // vertex of a flat boundary moves within it
    if (from == to || context.vertex_tet[from] < 0) return result;
    const bool on_boundary = !context.constraints.is_free_vertex(from);
    if (on_boundary && !(options.on_flat_boundary && context.constraints.is_surface_vertex(from) &&
                         in_boundary_plane(mesh, context, from, to)))
        return result;

    // layer 2: topology — the edge exists, one ref, nothing required
    CollapseConfiguration config;
    if (!collect_collapse_configuration(mesh, context, from, to, config)) return result;

    // layers 3 and 4 for each place the merged vertex may take: `to` itself, then (when `to`
    // is free too) the edge's midpoint, which halves how much the new edges grow
    // the ball's old worst only matters when a new tet falls below options.min_quality, so
    // it is computed on demand (most collapses never need it)
    double ball_worst = -1;  // not computed yet
    auto old_worst = [&] {
        if (ball_worst < 0) ball_worst = std::max(0.0, context.worst_quality(mesh, config.ball));
        return ball_worst;
    };
    std::vector<int> to_ball, to_neighbours;
    const bool may_move_to =
        options.allow_midpoint && !on_boundary && context.constraints.is_free_vertex(to);
    const Vec3 to_position = mesh.points[to];
    // the places other than `to` itself, and to's ball they need, are built only if `to` fails
    std::vector<Vec3> places = {to_position};
    auto add_moving_places = [&] {
        context.ball(mesh, to, to_ball);
        VertexMarks& marks = vertex_marks();
        marks.next_round(mesh.num_vertices());
        marks.mark(to);
        marks.mark(from);
        for (int t : to_ball)
            for (int v : mesh.tets[t])
                if (marks.mark(v)) to_neighbours.push_back(v);
        std::sort(to_neighbours.begin(), to_neighbours.end());
        places.push_back(0.5 * (mesh.points[from] + to_position));
        // the centre of every vertex the merged one will see: balances the new lengths
        Vec3 centre = Vec3::Zero();
        int count = 0;
        for (const auto* list : {&to_neighbours, &config.new_neighbours})
            for (int v : *list)
            {
                centre += mesh.points[v];
                ++count;
            }
        if (count > 0) places.push_back(centre / count);
    };
    bool found = false;
    std::vector<int> reshaped_by_move;  // tets of `to` outside the shell, when `to` moves
    Vec3 chosen = to_position;
    std::size_t refused = static_cast<std::size_t>(-1);  // index of the last refusing new tet
    for (std::size_t attempt = 0; !found; ++attempt)
    {
        if (attempt == 1 && may_move_to) add_moving_places();
        if (attempt >= places.size()) break;
        const Vec3 place = places[attempt];
        const auto& p = mesh.points;
        auto point_of = [&](int v) -> const Vec3& { return v == to ? place : p[v]; };
        auto quality_of = [&](const TetVertices& tv) {
            return context.shape(point_of(tv[0]), point_of(tv[1]), point_of(tv[2]),
                                 point_of(tv[3]));
        };
        std::vector<int> reshaped;  // tets of `to` outside the shell, when `to` moves
        if (attempt > 0)
            for (int t : to_ball)
                if (local_index(mesh, t, from) < 0) reshaped.push_back(t);
        // the floor: min(old worst of every tet involved, options.min_quality)
        double floor = options.min_quality;
        bool floor_exact = false;
        auto below_floor = [&](double q) {
            if (q <= 0.0) return true;
            if (q >= floor) return false;
            if (!floor_exact)
            {
                floor = std::min(floor, old_worst());
                if (attempt > 0) floor = std::min(floor, context.worst_quality(mesh, reshaped));
                floor_exact = true;
            }
            return q < floor;
        };
        // the new tets: the moved ones, then the reshaped ones; the one that refused the
        // previous place is tested first, as it usually refuses this one too (the verdict
        // does not depend on the order: any tet below the exact floor refuses)
        const std::size_t num_new = config.moved.size() + reshaped.size();
        auto new_tet = [&](std::size_t k) -> const TetVertices& {
            return k < config.moved.size() ? config.moved[k]
                                           : mesh.tets[reshaped[k - config.moved.size()]];
        };
        double worst = std::numeric_limits<double>::infinity();
        bool rejected = false;
        const std::size_t first = refused < num_new ? refused : 0;
        for (std::size_t i = 0; i < num_new && !rejected; ++i)
        {
            const std::size_t k = (first + i) % num_new;
            worst = std::min(worst, quality_of(new_tet(k)));
            if ((rejected = below_floor(worst))) refused = k;
        }
        result.worst_after = worst;
        if (rejected) continue;
        bool sizes_ok = true;
        for (int v : config.new_neighbours) sizes_ok = sizes_ok && !context.too_long(place, p[v]);
        if (attempt > 0)
            for (int v : to_neighbours)
                sizes_ok = sizes_ok &&
                           !(context.too_long(place, p[v]) && !context.too_long(to_position, p[v]));
        if (!sizes_ok) continue;
        found = true;
        chosen = place;
        if (attempt > 0) reshaped_by_move = reshaped;
    }
    result.worst_before = ball_worst;
    if (!found) return result;

    mesh.points[to] = chosen;
    context.tets_changed(reshaped_by_move);  // their cached qualities are stale now
    replace_tets(mesh, context, config.ball, config.moved, config.ref);
    if (on_boundary) context.constraints.collapse_listed_faces(mesh, from, to);
    context.vertex_tet[from] = -1;
    result.collapsed = true;
    return result;
}

}  // namespace hdimesh::volume
