// Blocks (volume/mesh/blocks.h): the tets cut along a Morton curve, each piece adapted alone with
// its cut faces frozen, merged back. The merge is a valid mesh with the same boundary; the
// result is the same bits for 1, 2, 3 and 8 threads; a shifted round cuts elsewhere.

#include "volume/mesh/blocks.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/optimize/optimize.h"
#include "volume/refine/refine.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;
using namespace hdimesh::volume;

namespace
{

/// A jittered box, its boundary split in two refs, a corner and a feature edge.
TetMesh test_box()
{
    TetMesh mesh = fixtures::box_mesh(6, 0.2, 7);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        const auto& tri = mesh.triangles[i];
        mesh.triangle_refs[i] = mesh.points[tri[0]].x() < 0.5 ? 1 : 2;
    }
    mesh.corners.push_back(mesh.triangles[0][0]);
    mesh.edges.push_back({mesh.triangles[0][0], mesh.triangles[0][1]});
    mesh.edge_refs.push_back(5);
    mesh.ridges.push_back(0);
    mesh.classify_vertices();
    mesh.build_adjacency();
    return mesh;
}

double boundary_area(const TetMesh& mesh)
{
    double area = 0;
    for (const auto& tri : mesh.triangles)
        area += triangle_area(mesh.points[tri[0]], mesh.points[tri[1]], mesh.points[tri[2]]);
    return area;
}

/// Refinement to a uniform size, then the final optimization, in each block.
void adapt_block(TetMesh& block, const SizeField& field)
{
    for (int pass = 0; pass < 10; ++pass)
        if (refine_pass(block, field).report.edges_split == 0) break;
    OptimizeOptions options;
    options.leave_required_vertex_balls = true;
    optimize_mesh(block, field, options);
}

}  // namespace

TEST_CASE("blocks: Morton runs of equal size, set by the mesh; a shifted round cuts elsewhere")
{
    const TetMesh mesh = test_box();
    const int n = mesh.num_live_tets();
    CHECK(block_count(n, n / 4) == 4);
    CHECK(block_count(n, 10 * n) == 1);
    CHECK(block_count(n, 0) == 1);
    const BlockPartition first = morton_blocks(mesh, 4, 0);
    const BlockPartition second = morton_blocks(mesh, 4, 1);
    std::vector<int> sizes(4, 0);
    for (int b : first.block_of_tet) ++sizes[b];
    for (int s : sizes) CHECK(std::abs(s - n / 4) <= 1);
    CHECK(first.block_of_tet != second.block_of_tet);
    std::vector<char> active(mesh.num_tet_slots(), 0);
    for (int t = 0; t < mesh.num_tet_slots(); t += 2) active[t] = 1;
    const BlockPartition some = morton_blocks(mesh, 3, 0, &active);
    for (int t = 0; t < mesh.num_tet_slots(); ++t) CHECK((some.block_of_tet[t] >= 0) == active[t]);
}

TEST_CASE("blocks: work that changes nothing merges back to the same mesh")
{
    TetMesh mesh = test_box();
    const TetMesh before = mesh;
    const std::vector<char> frozen =
        run_in_blocks(mesh, morton_blocks(mesh, 5, 0), nullptr, [](TetMesh& block, int) {
            // (a block may be pinched at an edge or vertex of its cut: those lie on frozen
            // faces, so nothing there changes)
            for (int t = 0; t < block.num_tet_slots(); ++t) CHECK(block.volume(t) > 0);
            CHECK(!block.required_vertices.empty());
        });
    CHECK(check_mesh(mesh).empty());
    CHECK(mesh.num_live_tets() == before.num_live_tets());
    CHECK(mesh.num_vertices() == before.num_vertices());
    CHECK(mesh.triangles.size() == before.triangles.size());
    CHECK(mesh.edges.size() == 1);
    CHECK(mesh.ridges.size() == 1);
    CHECK(mesh.corners.size() == 1);
    CHECK(mesh.total_volume() == doctest::Approx(before.total_volume()).epsilon(1e-12));
    CHECK(std::count(frozen.begin(), frozen.end(), 1) > 0);
    // the refs of the boundary come back, none of the frozen faces' ref
    for (int ref : mesh.triangle_refs) CHECK((ref == 1 || ref == 2));
}

TEST_CASE("blocks: refined and optimized in blocks, valid and the same bits for any thread count")
{
    const ConstantSize field(0.07);
    TetMesh reference;
    for (int threads : {1, 2, 3, 8})
    {
        TetMesh mesh = test_box();
        const double area = boundary_area(mesh);
        const double volume = mesh.total_volume();
        Workers workers(threads);
        for (int round = 0; round < 2; ++round)
            run_in_blocks(mesh, morton_blocks(mesh, 6, round), &workers,
                          [&](TetMesh& block, int) { adapt_block(block, field); });
        CHECK(check_mesh(mesh).empty());
        CHECK(boundary_area(mesh) == doctest::Approx(area).epsilon(1e-9));
        CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-9));
        CHECK(mesh.num_live_tets() > 5 * test_box().num_live_tets());
        for (int ref : mesh.triangle_refs) CHECK((ref == 1 || ref == 2));
        CHECK(mesh.corners.size() == 1);
        CHECK(mesh.ridges.size() == mesh.edges.size());
        if (threads == 1)
        {
            reference = mesh;
            continue;
        }
        REQUIRE(mesh.points.size() == reference.points.size());
        REQUIRE(mesh.tets.size() == reference.tets.size());
        CHECK(std::memcmp(mesh.points.data(), reference.points.data(),
                          mesh.points.size() * sizeof(Vec3)) == 0);
        CHECK(mesh.tets == reference.tets);
        CHECK(mesh.triangles == reference.triangles);
    }
}
