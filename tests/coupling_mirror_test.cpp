// The boundary map and the mirror: the surface of a tet mesh, changed by the surface
// operators, stays the tets' boundary (check_consistency) and the tets stay valid (check_mesh)
// after every operation.

#include <doctest/doctest.h>

#include <map>
#include <random>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "coupling/boundary_map.h"
#include "coupling/consistency.h"
#include "coupling/mirror.h"
#include "fixtures.h"
#include "surface/features.h"
#include "surface/local_ops.h"
#include "surface/surface_model.h"
#include "volume/check/boundary_repair.h"
#include "volume/check/check.h"
#include "volume/io/tet_io.h"
#include "volume/mesh/geometry.h"
#pragma GCC diagnostic pop

using namespace hdimesh;
using namespace hdimesh::coupling;
using volume::TetMesh;

namespace
{

/// The tets with the surface's edges, ridges, corners and classes written back, checked.
std::string tet_violations(const BoundaryMap& map, const TetMesh& mesh)
{
    TetMesh copy = mesh;
    write_back(map, copy);
    copy.compact();
    const auto violations = volume::check_mesh(copy);
    return violations.empty() ? std::string() : volume::format_violations(violations, 5);
}

std::string consistency(const BoundaryMap& map, const TetMesh& mesh)
{
    std::string out;
    for (const auto& line : check_consistency(map, mesh)) out += line + "\n";
    return out;
}

/// The surface of `mesh` classified by the feature detector, its classes given to the tets.
BoundaryMap classified_boundary(TetMesh& mesh)
{
    BoundaryMap map = extract_boundary(mesh);
    surface::detect_features(map.surface);
    write_back(map, mesh);
    return map;
}

/// Random surface operations (split, collapse, flip, shift, vertex removal) on the surface of
/// `mesh`, mirrored; both checks after every operation done. Returns the count done per kind.
MirrorStatistics fuzz(TetMesh& mesh, int operations, std::uint32_t seed, double max_length)
{
    BoundaryMap map = classified_boundary(mesh);
    const surface::SurfaceMesh input = map.surface;
    const surface::SurfaceModel model(input);
    MirrorStatistics stats;
    surface::OperatorContext ctx(map.surface, model, make_hooks(mesh, map, {}, &stats));
    std::mt19937 rng(seed);
    auto& s = map.surface;
    for (int i = 0; i < operations; ++i)
    {
        const int kind = static_cast<int>(rng() % 5);
        surface::OpResult result;
        if (kind == 0 || kind == 1 || kind == 2)
        {
            const auto e = s.edge_handle(static_cast<int>(rng() % s.n_edges()));
            if (s.status(e).deleted()) continue;
            if (kind == 0) result = surface::try_split(ctx, e);
            if (kind == 1)
                result = surface::try_collapse(ctx, s.halfedge_handle(e, rng() % 2), max_length);
            if (kind == 2) result = surface::try_flip(ctx, e, surface::FlipGoal::Quality);
        }
        else
        {
            const auto v = s.vertex_handle(static_cast<int>(rng() % s.n_vertices()));
            if (s.status(v).deleted()) continue;
            result = kind == 3 ? surface::shift_vertex(ctx, v) : surface::try_remove_vertex(ctx, v);
        }
        if (!result.done()) continue;
        INFO("operation ", i, " of kind ", kind);
        REQUIRE(consistency(map, mesh) == "");
        REQUIRE(tet_violations(map, mesh) == "");
    }
    return stats;
}

/// The volume of the tets of each ref, by ref.
std::map<int, double> volume_by_ref(const TetMesh& mesh)
{
    std::map<int, double> volume;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) volume[mesh.tet_refs[t]] += mesh.volume(t);
    return volume;
}

/// [0,1]^3 as 4^3 Kuhn cubes, the central 2^3 block ref 2, the rest ref 1:
///
///     +--+--+--+--+      the block's 48 interface triangles make a closed shell a layer
///     |  |  |  |  |      of cubes away from the box's faces (a ball inside a box)
///     +--+==+==+--+
///     |  |22|22|  |
///     +--+==+==+--+
///     |  |22|22|  |
///     +--+==+==+--+
///     |  |  |  |  |
///     +--+--+--+--+
TetMesh two_materials()
{
    TetMesh mesh = fixtures::box_mesh(4);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        volume::Vec3 c = volume::Vec3::Zero();
        for (int v : mesh.tets[t]) c += 0.25 * mesh.points[v];
        const bool inside = (c.array() > 0.25).all() && (c.array() < 0.75).all();
        mesh.tet_refs[t] = inside ? 2 : 1;
    }
    volume::repair_boundary(mesh, {});  // lists the interface triangles
    return mesh;
}

}  // namespace

TEST_CASE("the boundary of a tet mesh maps onto a surface and back, vertex for vertex")
{
    //   a 2×2×2 cube of Kuhn tets: 8 boundary squares a side, 48 boundary triangles, one
    //   interior vertex (the centre) left off the surface
    TetMesh mesh = fixtures::box_mesh(2);
    const std::size_t listed = mesh.triangles.size();
    CHECK(coupled_surface_refusal(mesh) == "");
    BoundaryMap map = classified_boundary(mesh);
    CHECK(map.surface.n_faces() == listed);
    CHECK(map.surface.n_vertices() == 26);
    CHECK(consistency(map, mesh) == "");
    CHECK(tet_violations(map, mesh) == "");
    const auto back = map.tet_to_surface(mesh.num_vertices());
    CHECK(!back[13].is_valid());  // the centre (1,1,1)
    CHECK(mesh.corners.size() == 8);
}

TEST_CASE("an interface that meets the boundary is refused; a closed one inside is taken")
{
    TetMesh mesh = fixtures::box_mesh(2);
    mesh.tet_refs[0] = 7;  // a corner tet: its interface faces meet the box's
    CHECK(coupled_surface_refusal(mesh) ==
          "interfaces between tet refs that meet the boundary or each other");
    TetMesh inner = two_materials();
    CHECK(coupled_surface_refusal(inner) == "");
    BoundaryMap map = extract_boundary(inner);
    CHECK(map.surface.n_faces() == 6 * 16 * 2 + 6 * 4 * 2);  // the box's faces, the block's
    CHECK(consistency(map, inner) == "");
}

TEST_CASE("two tets touching at one vertex pinch the boundary: the coupled pass refuses them")
{
    //        2   5
    //       /|\ /|\        tets (0,1,2,3) and (3,4,5,6) share vertex 3 only: its boundary
    //      0-+-3-+-6       faces make two fans there, which no manifold surface holds
    //       \|/ \|/
    //        1   4
    // (vertices 2 and 5 lifted to z = 1, so both tets have volume; listed positive)
    const std::vector<volume::Vec3> points = {{0, 0, 0},  {1, -1, 0}, {1, 1, 1}, {2, 0, 0},
                                              {3, -1, 0}, {3, 1, 1},  {4, 0, 0}};
    TetMesh mesh = fixtures::mesh_from_tets(points, {{1, 0, 2, 3}, {4, 3, 5, 6}});
    const std::string refusal = coupled_surface_refusal(mesh);
    CHECK(refusal.find("vertex 4") != std::string::npos);  // named 1-based
}

TEST_CASE("a split, a collapse and a flip on a cube face are mirrored into the tets")
{
    //   face z = 0 of the 2×2×2 cube, seen from below (outward):
    //
    //   (0,2)--(1,2)--(2,2)        split the centre's diagonal, collapse the new vertex back
    //     | \    | \    |          onto the centre, flip a diagonal of the face: after each,
    //     |   \  |   \  |          the surface is the tets' boundary and the tets are valid
    //   (0,1)--(1,1)--(2,1)
    //     | \    | \    |
    //     |   \  |   \  |
    //   (0,0)--(1,0)--(2,0)
    TetMesh mesh = fixtures::box_mesh(2);
    const double volume = mesh.total_volume();
    BoundaryMap map = classified_boundary(mesh);
    const surface::SurfaceMesh input = map.surface;
    const surface::SurfaceModel model(input);
    MirrorStatistics stats;
    surface::OperatorContext ctx(map.surface, model, make_hooks(mesh, map, {}, &stats));
    auto& s = map.surface;
    surface::VertexHandle centre;
    for (auto v : s.vertices())
        if ((s.point(v) - surface::Vec3d(0.5, 0.5, 0)).norm() < 1e-12) centre = v;
    REQUIRE(centre.is_valid());
    surface::EdgeHandle diagonal;
    for (auto h : s.voh_range(centre))
    {
        const auto p = s.point(s.to_vertex_handle(h));
        if (std::abs(p[2]) < 1e-12 && std::abs(p[0] - 0.5) > 0.1 && std::abs(p[1] - 0.5) > 0.1)
            diagonal = s.edge_handle(h);
    }
    REQUIRE(diagonal.is_valid());

    const auto split = surface::try_split(ctx, diagonal);
    REQUIRE(split.done());
    CHECK(consistency(map, mesh) == "");
    CHECK(tet_violations(map, mesh) == "");
    CHECK(mesh.total_volume() == doctest::Approx(volume));

    const auto back = s.find_halfedge(split.vertex, centre);
    REQUIRE(back.is_valid());
    REQUIRE(surface::try_collapse(ctx, back, 1.0).done());
    CHECK(consistency(map, mesh) == "");
    CHECK(tet_violations(map, mesh) == "");
    CHECK(mesh.total_volume() == doctest::Approx(volume));
    CHECK(stats.done[MirrorStatistics::Split] == 1);
    CHECK(stats.done[MirrorStatistics::Collapse] == 1);
}

TEST_CASE("random surface operations on the sphere480 boundary keep both meshes consistent")
{
    TetMesh mesh = volume::read_mesh(fixtures::data_path("sphere480.mesh"));
    mesh.build_adjacency();
    const MirrorStatistics stats = fuzz(mesh, 1500, 11, 0.5);
    MESSAGE(stats.format());
    for (int k = 0; k < MirrorStatistics::kOperations; ++k)
        if (k != MirrorStatistics::Remove) CHECK(stats.done[k] > 0);
}

TEST_CASE("random surface operations on a box keep its ridges, corners and both meshes")
{
    TetMesh mesh = fixtures::box_mesh(4, 0.2, 3);
    const double volume = mesh.total_volume();
    const MirrorStatistics stats = fuzz(mesh, 1500, 5, 0.4);
    MESSAGE(stats.format());
    CHECK(stats.done[MirrorStatistics::Split] > 0);
    CHECK(stats.done[MirrorStatistics::Collapse] > 0);
    // faces stay planar and corners fixed: the volume is the cube's
    CHECK(mesh.total_volume() == doctest::Approx(volume));
}

TEST_CASE("random surface operations on a box holding a block of another material")
{
    // every operation on the block's faces is one cavity a side, each refilled with its ref
    TetMesh mesh = two_materials();
    mesh.build_adjacency();
    const std::map<int, double> before = volume_by_ref(mesh);
    const MirrorStatistics stats = fuzz(mesh, 3000, 7, 0.3);
    MESSAGE(stats.format());
    CHECK(stats.done[MirrorStatistics::Split] > 0);
    CHECK(stats.done[MirrorStatistics::Collapse] > 0);
    CHECK(stats.done[MirrorStatistics::Flip] > 0);
    CHECK(stats.refusals[MirrorStatistics::MixedRefs] == 0);
    // the block's faces stay planar and its corners fixed: each material keeps its volume
    const std::map<int, double> after = volume_by_ref(mesh);
    REQUIRE(after.size() == 2);
    CHECK(after.at(1) == doctest::Approx(before.at(1)));
    CHECK(after.at(2) == doctest::Approx(before.at(2)));
}

TEST_CASE("a boundary move its tets cannot follow refills its ball around the new place")
{
    //   the 2×2×2 cube, its centre i lowered to just under the face z = 0:
    //
    //     (0,0,0) ──────── c ──────── (1,0,0)     c = (0.5, 0.5, 0) slides along -x in the
    //                      · i                    face; some tet (c, i, ...) turns inside out
    //                                             long before the face's triangles do
    //
    //   the mirror then takes c's ball out and refills it with c at the new place
    TetMesh mesh = fixtures::box_mesh(2);
    mesh.points[13] = volume::Vec3(0.5, 0.5, 0.05);
    REQUIRE(volume::check_mesh(mesh).empty());
    const double volume = mesh.total_volume();
    BoundaryMap map = classified_boundary(mesh);
    MirrorStatistics stats;
    const surface::SurfaceHooks hooks = make_hooks(mesh, map, {}, &stats);
    auto& s = map.surface;
    surface::VertexHandle c;
    for (auto v : s.vertices())
        if ((s.point(v) - surface::Vec3d(0.5, 0.5, 0)).norm() < 1e-12) c = v;
    REQUIRE(c.is_valid());
    const int tc = map.tet_vertex_of(c);

    const surface::Vec3d to(0.2, 0.5, 0);
    bool inverts = false;  // the ball alone could not follow
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        std::array<volume::Vec3, 4> x;
        for (int k = 0; k < 4; ++k)
            x[k] = mesh.tets[t][k] == tc ? volume::Vec3(to[0], to[1], to[2])
                                         : mesh.points[mesh.tets[t][k]];
        if (volume::signed_volume6(x[0], x[1], x[2], x[3]) <= 0.0) inverts = true;
    }
    REQUIRE(inverts);

    REQUIRE(hooks.allow_move(s, c, to));
    const surface::Vec3d from = s.point(c);
    s.set_point(c, to);
    hooks.on_move(s, c, from);
    CHECK(stats.done[MirrorStatistics::Move] == 1);
    CHECK(consistency(map, mesh) == "");
    CHECK(tet_violations(map, mesh) == "");
    CHECK(mesh.points[tc][0] == doctest::Approx(0.2));
    CHECK(mesh.total_volume() == doctest::Approx(volume));  // the face stays planar
}
