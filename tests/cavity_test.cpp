// The cavity filler's contract on real meshes: cut a random connected set of tets out, refill
// it, and the mesh must be as valid as before, hold the same volume, keep the cavity's outer
// faces and put Steiner points strictly inside; the same seed gives the same bytes.

#include "volume/fill/cavity.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/io/tet_io.h"
#include "volume/mesh/predicates.h"
#include "volume/mesh/tet_tables.h"
#include "volume/refine/refine.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;
using namespace hdimesh::volume;

namespace
{

/// A connected set of `count` live tets grown breadth-first from `seed` across interior faces,
/// neighbours taken in a shuffled order so that shapes vary (thin, branched, compact).
std::vector<int> random_connected_tets(const TetMesh& mesh, int seed, int count, std::mt19937& rng)
{
    std::vector<int> set{seed};
    std::vector<char> taken(mesh.tets.size(), 0);
    taken[seed] = 1;
    std::vector<int> frontier{seed};
    while (static_cast<int>(set.size()) < count && !frontier.empty())
    {
        const std::size_t pick = rng() % frontier.size();
        const int t = frontier[pick];
        std::array<int, 4> order{0, 1, 2, 3};
        std::shuffle(order.begin(), order.end(), rng);
        bool grew = false;
        for (int f : order)
        {
            const int n = mesh.neighbors[t][f];
            if (n == kNoTet || taken[n]) continue;
            taken[n] = 1;
            set.push_back(n);
            frontier.push_back(n);
            grew = true;
            break;
        }
        if (!grew) frontier.erase(frontier.begin() + static_cast<long>(pick));
    }
    return set;
}

/// The oriented outer faces of a tet set, sorted (as vertex triples rotated to start at the
/// smallest id, so orientation is part of the comparison).
std::vector<Triangle> oriented_hull(const TetMesh& mesh, const std::vector<int>& tets)
{
    std::vector<char> in(mesh.tets.size(), 0);
    for (int t : tets) in[t] = 1;
    std::vector<Triangle> hull;
    for (int t : tets)
        for (int f = 0; f < 4; ++f)
        {
            const int n = mesh.neighbors[t][f];
            if (n != kNoTet && in[n]) continue;
            const auto& lf = tet::kFaceVertices[f];
            Triangle tri{mesh.tets[t][lf[0]], mesh.tets[t][lf[1]], mesh.tets[t][lf[2]]};
            std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
            hull.push_back(tri);
        }
    std::sort(hull.begin(), hull.end());
    return hull;
}

double volume_of(const TetMesh& mesh, const std::vector<int>& tets)
{
    double v = 0;
    for (int t : tets) v += mesh.volume(t);
    return v;
}

struct Outcome
{
    bool filled = false;
    FillStage stage = FillStage::Failed;
    std::vector<TetVertices> tets;
    std::vector<Vec3> new_points;
};

/// Cuts `count` tets from `mesh` around `seed`, refills and checks every invariant.
Outcome cut_and_refill(TetMesh& mesh, const MeshConstraints& constraints, int seed, int count,
                       std::mt19937& rng, FillStatistics& stats)
{
    const std::vector<int> cut = random_connected_tets(mesh, seed, count, rng);
    const CavityFill fill = refill_tets(mesh, cut, nullptr, {}, &constraints);
    stats.add(fill);
    Outcome outcome;
    outcome.filled = fill.filled;
    if (!fill.filled)
    {
        // the cut hull is closed and the ref is one: only the budget may refuse
        MESSAGE("refused: " << fill.failure);
        return outcome;
    }
    const std::vector<Triangle> hull_before = oriented_hull(mesh, fill.removed_tets);
    const double volume_before = volume_of(mesh, fill.removed_tets);
    const int vertices_before = mesh.num_vertices();
    const std::vector<int> added = commit_cavity(mesh, fill);

    const double volume_after = volume_of(mesh, added);
    CHECK(volume_after == doctest::Approx(volume_before).epsilon(1e-9));
    CHECK(oriented_hull(mesh, added) == hull_before);
    for (int t : added)
        CHECK(orient3d(mesh.points[mesh.tets[t][0]], mesh.points[mesh.tets[t][1]],
                       mesh.points[mesh.tets[t][2]], mesh.points[mesh.tets[t][3]]) > 0);
    // Steiner points are strictly inside: interior, and on no hull face's plane
    for (int v = vertices_before; v < mesh.num_vertices(); ++v)
    {
        CHECK(mesh.vertex_classes[v] == VertexClass::Interior);
        for (const auto& f : hull_before)
            if (std::find(f.begin(), f.end(), v) == f.end())
                CHECK(orient3d(mesh.points[f[0]], mesh.points[f[1]], mesh.points[f[2]],
                               mesh.points[v]) != 0);
    }
    outcome.stage = fill.stage;
    outcome.tets = fill.tets;
    outcome.new_points = fill.new_points;
    return outcome;
}

void run_property(TetMesh mesh, int trials, int max_cut, std::uint32_t seed, const char* name)
{
    REQUIRE(check_mesh(mesh).empty());
    const MeshConstraints constraints(mesh);
    std::mt19937 rng(seed);
    FillStatistics stats;
    long filled = 0;
    for (int trial = 0; trial < trials; ++trial)
    {
        // the constraints stay valid: refills keep the boundary and add interior vertices only
        const MeshConstraints current = [&] {
            MeshConstraints c = constraints;
            c.grow(mesh.num_vertices());
            return c;
        }();
        std::vector<int> live;
        for (int t = 0; t < mesh.num_tet_slots(); ++t)
            if (!mesh.is_dead(t)) live.push_back(t);
        const int start = live[rng() % live.size()];
        const int count = 2 + static_cast<int>(rng() % static_cast<unsigned>(max_cut - 1));
        filled += cut_and_refill(mesh, current, start, count, rng, stats).filled;
    }
    const auto violations = check_mesh(mesh);
    CHECK_MESSAGE(violations.empty(), format_violations(violations));
    MESSAGE(std::string(name) << ": " << filled << "/" << trials << " filled; " << stats.format());
    CHECK(filled == trials);
}

}  // namespace

TEST_CASE("refilling random cavities of sphere480 keeps the mesh valid")
{
    TetMesh mesh = read_mesh(std::string(HDIMESH_DATA_DIR) + "/sphere480.mesh");
    mesh.build_adjacency();
    run_property(mesh, 400, 40, 7, "sphere480, 2-40 tets");
    run_property(mesh, 40, 300, 11, "sphere480, 2-300 tets");
}

TEST_CASE("refilling random cavities of a jittered box keeps the mesh valid")
{
    TetMesh mesh = fixtures::box_mesh(5, 0.2, 3);
    run_property(mesh, 300, 60, 5, "box 5^3 jittered, 2-60 tets");
}

TEST_CASE("refilling random cavities of a refined mesh keeps the mesh valid")
{
    TetMesh mesh = read_mesh(std::string(HDIMESH_DATA_DIR) + "/sphere480.mesh");
    ConstantSize field(0.12);
    refine_pass(mesh, field);
    refine_pass(mesh, field);
    mesh.build_adjacency();
    run_property(mesh, 200, 500, 13, "sphere480 refined twice, 2-500 tets");
}

TEST_CASE("a refill is byte-identical on a rerun")
{
    auto run = [] {
        TetMesh mesh = read_mesh(std::string(HDIMESH_DATA_DIR) + "/sphere480.mesh");
        mesh.build_adjacency();
        const MeshConstraints constraints(mesh);
        std::mt19937 rng(99);
        FillStatistics stats;
        std::vector<Outcome> outcomes;
        for (int k = 0; k < 30; ++k)
            outcomes.push_back(cut_and_refill(mesh, constraints, 17 * k + 3, 25, rng, stats));
        return std::make_pair(outcomes, mesh.points);
    };
    const auto first = run();
    const auto second = run();
    REQUIRE(first.first.size() == second.first.size());
    for (std::size_t k = 0; k < first.first.size(); ++k)
    {
        CHECK(first.first[k].tets == second.first[k].tets);
        REQUIRE(first.first[k].new_points.size() == second.first[k].new_points.size());
        for (std::size_t p = 0; p < first.first[k].new_points.size(); ++p)
            CHECK(std::memcmp(first.first[k].new_points[p].data(),
                              second.first[k].new_points[p].data(), sizeof(double) * 3) == 0);
    }
    REQUIRE(first.second.size() == second.second.size());
    for (std::size_t p = 0; p < first.second.size(); ++p)
        CHECK(std::memcmp(first.second[p].data(), second.second[p].data(), sizeof(double) * 3) ==
              0);
}

TEST_CASE("a cavity with tets of two refs is refused and the mesh is untouched")
{
    // two tets sharing face (1,2,3), refs 1 and 2:
    //        3
    //       /|\      tet A = (0,1,2,3) ref 1, tet B = (4,2,1,3) ref 2
    //   0 -1-+-2- 4
    TetMesh mesh = fixtures::mesh_from_tets(
        {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)},
        {{0, 1, 2, 3}, {4, 2, 1, 3}});
    mesh.tet_refs[1] = 2;
    const CavityFill fill = refill_tets(mesh, {0, 1}, nullptr);
    CHECK_FALSE(fill.filled);
    CHECK(fill.failure.find("refs") != std::string::npos);
}

TEST_CASE("an interior vertex's ball is refilled without it")
{
    // the ball of the centre vertex of a jittered 3^3 box: every tet around it goes, the cavity
    // is star-shaped from the removed vertex, and a fan or kernel point closes it
    TetMesh mesh = fixtures::box_mesh(2, 0.1, 9);
    int centre = -1;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (mesh.vertex_classes[v] == VertexClass::Interior) centre = v;
    REQUIRE(centre >= 0);
    std::vector<int> ball;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (std::find(mesh.tets[t].begin(), mesh.tets[t].end(), centre) != mesh.tets[t].end())
            ball.push_back(t);
    const double volume = mesh.total_volume();
    const CavityFill fill = refill_tets(mesh, ball, nullptr);
    REQUIRE(fill.filled);
    commit_cavity(mesh, fill);
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
    const auto violations = check_mesh(mesh);
    CHECK_MESSAGE(violations.empty(), format_violations(violations));
}
