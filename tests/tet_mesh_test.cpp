#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/mesh/reorder.h"
#include "volume/mesh/tet_tables.h"

using namespace hdimesh;

TEST_CASE("local numbering: face edges join the face's vertices, edge faces contain the edge")
{
    for (int f = 0; f < 4; ++f)
        for (int k = 0; k < 3; ++k)
        {
            const int a = tet::kFaceVertices[f][k], b = tet::kFaceVertices[f][(k + 1) % 3];
            CHECK(tet::kFaceEdges[f][k] == tet::kEdgeOfVertices[a][b]);
            CHECK(a != f);
        }
    for (int e = 0; e < 6; ++e)
        for (int f : tet::kEdgeFaces[e])
        {
            // face f is opposite vertex f, so it contains e iff e does not touch vertex f
            CHECK(tet::kEdgeVertices[e][0] != f);
            CHECK(tet::kEdgeVertices[e][1] != f);
        }
}

TEST_CASE("local numbering: faces are outward for a positive tet")
{
    const TetMesh m = fixtures::single_tet();
    const Vec3 centroid = 0.25 * (m.points[0] + m.points[1] + m.points[2] + m.points[3]);
    for (int f = 0; f < 4; ++f)
    {
        const auto& fv = tet::kFaceVertices[f];
        // the centroid is behind every outward face
        CHECK(signed_volume6(m.points[fv[0]], m.points[fv[1]], m.points[fv[2]], centroid) < 0);
    }
}

TEST_CASE("quality: a regular tet scores 1 and a flat one 0")
{
    const TetMesh m = fixtures::regular_tet();
    CHECK(m.quality(0) == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(tet_quality({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}) == doctest::Approx(0.0));
    CHECK(triangle_quality({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}) ==
          doctest::Approx(1.0).epsilon(1e-12));
}

//   A Kuhn cube: 6 tets around the diagonal 0-7, each interior face shared by two tets.
TEST_CASE("adjacency of a Kuhn box is symmetric and matches shared faces")
{
    TetMesh m = fixtures::box_mesh(3, 0.2, 7);
    CHECK(m.build_adjacency() == 0);
    int boundary_faces = 0;
    for (int t = 0; t < m.num_tet_slots(); ++t)
    {
        CHECK(m.volume(t) > 0);
        for (int f = 0; f < 4; ++f)
        {
            const int n = m.neighbors[t][f];
            if (n == kNoTet)
            {
                ++boundary_faces;
                continue;
            }
            int back = 0;
            for (int g = 0; g < 4; ++g) back += (m.neighbors[n][g] == t);
            CHECK(back == 1);
        }
    }
    CHECK(boundary_faces == 6 * 2 * 9);
    CHECK(m.total_volume() == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE("compact drops dead tets and unused vertices and returns its maps")
{
    TetMesh m = fixtures::box_mesh(2);
    const int n_before = m.num_tet_slots();
    const double volume_before = m.total_volume();
    const double killed_volume = m.volume(0) + m.volume(5);
    m.kill_tet(0);
    m.kill_tet(5);
    m.triangles.clear();  // so the only users of a vertex are tets
    m.triangle_refs.clear();
    const CompactionMaps maps = m.compact();
    CHECK(m.num_tet_slots() == n_before - 2);
    CHECK(maps.old2new_tets[0] == -1);
    CHECK(maps.old2new_tets[5] == -1);
    CHECK(maps.old2new_tets[1] == 0);
    CHECK(m.total_volume() == doctest::Approx(volume_before - killed_volume));
    // adjacency survived renumbering: still symmetric
    for (int t = 0; t < m.num_tet_slots(); ++t)
        for (int f = 0; f < 4; ++f)
            if (m.neighbors[t][f] != kNoTet)
            {
                const auto& nb = m.neighbors[m.neighbors[t][f]];
                CHECK(std::count(nb.begin(), nb.end(), t) == 1);
            }
}

TEST_CASE("spatial renumbering is a permutation that keeps the mesh, its adjacency and boundary")
{
    // A jittered 4x4x4 Kuhn box: box_mesh numbers vertices row by row, so the Morton order
    // moves most of them; every tet, triangle and link must follow its vertices.
    const TetMesh before = fixtures::box_mesh(4, 0.2, 7);
    TetMesh m = before;
    const CompactionMaps maps = renumber_spatially(m);
    REQUIRE(maps.old2new_verts.size() == before.points.size());
    REQUIRE(maps.old2new_tets.size() == before.tets.size());
    std::vector<int> seen_verts(before.points.size(), 0), seen_tets(before.tets.size(), 0);
    for (int v : maps.old2new_verts) ++seen_verts[static_cast<std::size_t>(v)];
    for (int t : maps.old2new_tets) ++seen_tets[static_cast<std::size_t>(t)];
    CHECK(std::count(seen_verts.begin(), seen_verts.end(), 1) ==
          static_cast<long>(seen_verts.size()));
    CHECK(std::count(seen_tets.begin(), seen_tets.end(), 1) == static_cast<long>(seen_tets.size()));
    for (int v = 0; v < before.num_vertices(); ++v)
    {
        CHECK(m.points[maps.old2new_verts[v]] == before.points[v]);
        CHECK(m.vertex_classes[maps.old2new_verts[v]] == before.vertex_classes[v]);
    }
    for (int t = 0; t < before.num_tet_slots(); ++t)
    {
        const int nt = maps.old2new_tets[t];
        for (int k = 0; k < 4; ++k)
        {
            CHECK(m.tets[nt][k] == maps.old2new_verts[before.tets[t][k]]);
            const int old_neighbor = before.neighbors[t][k];
            CHECK(m.neighbors[nt][k] ==
                  (old_neighbor == kNoTet ? kNoTet : maps.old2new_tets[old_neighbor]));
        }
        CHECK(m.volume(nt) == before.volume(t));
    }
    for (std::size_t i = 0; i < before.triangles.size(); ++i)
        for (int k = 0; k < 3; ++k)
            CHECK(m.triangles[i][k] == maps.old2new_verts[before.triangles[i][k]]);
    CHECK(check_mesh(m).empty());
    // tets are sorted by their smallest vertex
    auto smallest = [&](int t) { return *std::min_element(m.tets[t].begin(), m.tets[t].end()); };
    for (int t = 1; t < m.num_tet_slots(); ++t) CHECK(smallest(t - 1) <= smallest(t));
}
