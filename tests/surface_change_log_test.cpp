// The change log around the operators' hooks: each recording list gets the vertices every
// change touched, the caller's hooks still see every change.

#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

// (The fixtures' add_vertex, inlined here, trips GCC's -Wmaybe-uninitialized on OpenMesh's
// deliberately uninitialized VectorT, first included below: a false positive.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "surface/detail/change_log.h"
#include "surface/local_ops.h"
#include "surface_fixtures.h"
#pragma GCC diagnostic pop

using namespace hdimesh::surface;
using detail::ChangedVertices;
using detail::ChangeLog;

namespace
{

bool contains(const std::vector<VertexHandle>& vertices, VertexHandle v)
{
    return std::find(vertices.begin(), vertices.end(), v) != vertices.end();
}

}  // namespace

TEST_CASE(
    "the change log notes a split's new vertex and a collapse's kept vertex in recording lists "
    "only")
{
    //  (0,2)---(1,2)---(2,2)
    //    |    /  |    /  |      a 2×2 grid in z = 0: split the centre's edge to (2,2), then
    //    |  /    |  /    |      collapse the new vertex onto the centre
    //  (0,1)---(1,1)---(2,1)
    //    |    /  |    /  |
    //  (0,0)---(1,0)---(2,0)
    SurfaceMesh mesh = fixtures::triangulated_grid(2, [](int, int) { return 0.0; });
    fixtures::mark_all_smooth(mesh);
    int given_splits = 0, given_collapses = 0;
    SurfaceHooks given;
    given.on_split = [&](const SurfaceMesh&, VertexHandle, VertexHandle, VertexHandle) {
        ++given_splits;
    };
    given.on_collapse = [&](const SurfaceMesh&, VertexHandle, VertexHandle) { ++given_collapses; };
    ChangeLog log;
    ChangedVertices recording, idle;
    recording.recording = true;
    log.add(recording);
    log.add(idle);
    const fixtures::PlaneProjector plane;
    OperatorContext ctx(mesh, plane, log.wrap(given));

    const VertexHandle centre = fixtures::vertex_at(mesh, Vec3d(1, 1, 0));
    const VertexHandle corner = fixtures::vertex_at(mesh, Vec3d(2, 2, 0));
    const EdgeHandle diagonal = mesh.edge_handle(mesh.find_halfedge(centre, corner));
    const OpResult split = try_split(ctx, diagonal);
    REQUIRE(split.done());
    CHECK(given_splits == 1);
    CHECK(contains(recording.vertices, split.vertex));
    CHECK_FALSE(recording.edges_deleted);

    const OpResult collapse = try_collapse(ctx, mesh.find_halfedge(split.vertex, centre), 0.0);
    REQUIRE(collapse.done());
    CHECK(given_collapses == 1);
    CHECK(contains(recording.vertices, centre));  // the kept vertex: every changed face has it
    CHECK(recording.edges_deleted);               // a collapse deletes edges no vertex reaches
    CHECK(idle.vertices.empty());
    CHECK_FALSE(idle.edges_deleted);
}

TEST_CASE("the change log notes a flip's new edge ends and a move's vertex")
{
    //  (0,1)------(1.6,1.6)
    //    |        / |       one quad cut by its long diagonal (0,0)-(1.6,1.6): the quality
    //    |     /    |       flip turns it to (1,0)-(0,1); then (1.6,1.6) is moved. Each change
    //    |  /       |       is noted by the vertices every new or changed face has
    //  (0,0)------(1,0)
    SurfaceMesh mesh = fixtures::triangulated_grid(1, [](int, int) { return 0.0; });
    fixtures::mark_all_smooth(mesh);
    const VertexHandle a = fixtures::vertex_at(mesh, Vec3d(0, 0, 0)),
                       b = fixtures::vertex_at(mesh, Vec3d(1, 1, 0));
    const VertexHandle c = fixtures::vertex_at(mesh, Vec3d(1, 0, 0)),
                       d = fixtures::vertex_at(mesh, Vec3d(0, 1, 0));
    mesh.set_point(b, Vec3d(1.6, 1.6, 0.0));
    ChangeLog log;
    ChangedVertices list;
    list.recording = true;
    log.add(list);
    int given_flips = 0, given_moves = 0;
    SurfaceHooks given;
    given.on_flip = [&](const SurfaceMesh&, VertexHandle, VertexHandle, VertexHandle,
                        VertexHandle) { ++given_flips; };
    given.on_move = [&](const SurfaceMesh&, VertexHandle, const Vec3d&) { ++given_moves; };
    const fixtures::PlaneProjector plane;
    OperatorContext ctx(mesh, plane, log.wrap(given));
    REQUIRE(try_flip(ctx, mesh.edge_handle(mesh.find_halfedge(a, b)), FlipGoal::Quality).done());
    CHECK(given_flips == 1);
    CHECK(mesh.find_halfedge(c, d).is_valid());
    CHECK(list.vertices.size() == 2);
    CHECK(contains(list.vertices, c));
    CHECK(contains(list.vertices, d));
    list.vertices.clear();
    REQUIRE(commit_move(ctx, b, Vec3d(1.5, 1.5, 0.0), -1).done());
    CHECK(given_moves == 1);
    CHECK(list.vertices == std::vector<VertexHandle>{b});
    CHECK_FALSE(list.edges_deleted);
}
