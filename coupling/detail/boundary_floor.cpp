// Boundary vertices of tets under the floor slid along the model (see boundary_floor.h).
#include "coupling/detail/boundary_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "volume/mesh/geometry.h"
#include "volume/mesh/tet_tables.h"
#include "volume/mesh/tet_topology.h"

namespace hdimesh::coupling::detail
{
namespace
{

using volume::TetMesh;
using volume::Vec3;
using volume::VertexClass;

constexpr double kPi = 3.14159265358979323846;

/// A vertex's tets and, among their faces through it, those on the boundary or an interface.
struct Ball
{
    int vertex = -1;
    std::vector<int> tets;
    std::vector<std::pair<int, int>> faces;  // (tet, local face)
    std::vector<Vec3> normals;               // the faces' unit normals before the move
};

Vec3 face_normal(const TetMesh& mesh, int t, int f)
{
    const auto& fv = volume::tet::kFaceVertices[f];
    const auto& tv = mesh.tets[t];
    const Vec3 &a = mesh.points[tv[fv[0]]], &b = mesh.points[tv[fv[1]]],
               &c = mesh.points[tv[fv[2]]];
    const Vec3 n = (b - a).cross(c - a);
    const double length = n.norm();
    return length > 0 ? Vec3(n / length) : Vec3::Zero();
}

Ball gather_ball(const TetMesh& mesh, int seed, int v)
{
    Ball ball;
    ball.vertex = v;
    volume::vertex_ball(mesh, seed, v, ball.tets);
    for (int t : ball.tets)
        for (int f = 0; f < 4; ++f)
        {
            if (mesh.tets[t][f] == v) continue;  // the face opposite v does not move
            const int across = mesh.neighbors[t][f];
            if (across != volume::kNoTet && mesh.tet_refs[across] == mesh.tet_refs[t]) continue;
            ball.faces.push_back({t, f});
            ball.normals.push_back(face_normal(mesh, t, f));
        }
    return ball;
}

/// The ball's worst Qe and its tet (inverted tets count negative).
std::pair<double, int> worst_of(const TetMesh& mesh, const Ball& ball)
{
    std::pair<double, int> worst{std::numeric_limits<double>::infinity(), -1};
    for (int t : ball.tets) worst = std::min(worst, {mesh.quality(t), t});
    return worst;
}

/// Whether no boundary face of the ball turned more than the limit from where it was.
bool faces_kept(const TetMesh& mesh, const Ball& ball, double min_cosine)
{
    for (std::size_t i = 0; i < ball.faces.size(); ++i)
    {
        const Vec3 n = face_normal(mesh, ball.faces[i].first, ball.faces[i].second);
        if (n.dot(ball.normals[i]) < min_cosine) return false;
    }
    return true;
}

/// The gradient of tet t's Qe in its vertex v's position (central differences).
Vec3 quality_gradient(TetMesh& mesh, int t, int v, double step)
{
    const Vec3 at = mesh.points[v];
    Vec3 g;
    for (int axis = 0; axis < 3; ++axis)
    {
        mesh.points[v][axis] = at[axis] + step;
        const double plus = mesh.quality(t);
        mesh.points[v][axis] = at[axis] - step;
        const double minus = mesh.quality(t);
        mesh.points[v][axis] = at[axis];
        g[axis] = (plus - minus) / (2 * step);
    }
    return g;
}

double mean_edge_at(const TetMesh& mesh, const Ball& ball)
{
    double sum = 0;
    int count = 0;
    for (int t : ball.tets)
        for (int u : mesh.tets[t])
            if (u != ball.vertex)
            {
                sum += (mesh.points[u] - mesh.points[ball.vertex]).norm();
                ++count;
            }
    return count ? sum / count : 0.0;
}

/// Ascent of the ball's worst Qe along the model: the worst tet's gradient in the tangent
/// plane (along the ridge), halved steps until a projected trial raises the worst. The moves
/// kept.
int raise_vertex(TetMesh& mesh, const BoundaryModel& model, Ball& ball,
                 const BoundaryFloorOptions& options)
{
    const int v = ball.vertex;
    const VertexClass cls = mesh.vertex_classes[v];
    const double min_cosine = std::cos(options.max_turn_deg * kPi / 180.0);
    const double length = mean_edge_at(mesh, ball);
    if (!(length > 0)) return 0;
    int moves = 0;
    for (int step = 0; step < options.steps_per_vertex; ++step)
    {
        const auto [worst, tet] = worst_of(mesh, ball);
        if (worst >= options.floor || tet < 0) break;
        const BoundaryFoot here = model.project(mesh.points[v], cls);
        if (here.target.status == hdi::ProjectionStatus::Failed) break;
        Vec3 g = quality_gradient(mesh, tet, v, 1e-6 * length);
        g = cls == VertexClass::Ridge ? Vec3(g.dot(here.target.tangent) * here.target.tangent)
                                      : Vec3(g - g.dot(here.target.normal) * here.target.normal);
        if (!(g.norm() > 0)) break;
        const Vec3 direction = g.normalized();
        const Vec3 from = mesh.points[v];
        bool moved = false;
        for (double alpha : {0.25, 0.125, 0.0625, 0.03125})
        {
            const BoundaryFoot foot = model.project(from + alpha * length * direction, cls);
            if (foot.target.status == hdi::ProjectionStatus::Failed) continue;
            mesh.points[v] = foot.target.point;
            if (worst_of(mesh, ball).first >= worst + options.min_gain &&
                faces_kept(mesh, ball, min_cosine))
            {
                moved = true;
                break;
            }
            mesh.points[v] = from;
        }
        if (!moved) break;
        ++moves;
    }
    return moves;
}

}  // namespace

BoundaryFloorReport raise_boundary_floor(TetMesh& mesh, const BoundaryModel& model,
                                         const BoundaryFloorOptions& options)
{
    BoundaryFloorReport report;
    // the movable boundary vertices of the tets under the floor, each with a tet of its ball
    std::vector<char> locked = held_vertices(mesh);  // required, or on a required entity
    for (int i : mesh.required_edges)
        for (int v : mesh.edges[i]) locked[v] = 1;
    std::vector<std::pair<int, int>> vertices;  // (vertex, seed tet)
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t) || !(mesh.quality(t) < options.floor)) continue;
        ++report.below;
        for (int v : mesh.tets[t])
            if (!locked[v] && (mesh.vertex_classes[v] == VertexClass::Surface ||
                               mesh.vertex_classes[v] == VertexClass::Ridge))
                vertices.push_back({v, t});
    }
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end(),
                               [](const auto& a, const auto& b) { return a.first == b.first; }),
                   vertices.end());
    for (const auto& [v, seed] : vertices)
    {
        Ball ball = gather_ball(mesh, seed, v);
        report.moves += raise_vertex(mesh, model, ball, options);
    }
    return report;
}

}  // namespace hdimesh::coupling::detail
