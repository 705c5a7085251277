// Stages 2 and 3 of the cavity cascade (volume/fill/detail/cavity_stages.h) on the corpus of
// tests/cavity_corpus.h, and the three small stages together (fill_small_cavity). Every fill
// must be a tetrahedralization of exactly the cavity: positive tets (exact), the enclosed
// volume, the input faces as the oriented boundary and every other face twice with opposite
// orientations, Steiner points strictly inside, and the same output on a second run.

#include "volume/fill/detail/cavity_stages.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "cavity_corpus.h"
#include "cavity_fill_check.h"
#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/fill/detail/kernel.h"
#include "volume/mesh/predicates.h"
#include "volume/mesh/tet_tables.h"

using namespace hdimesh;
using cavity_corpus::Cavity;
using volume::CavityFill;
using volume::CavityOptions;
using volume::FillStage;
namespace detail = volume::detail;

namespace
{

void require_valid_fill(const Cavity& cavity, const CavityFill& fill)
{
    INFO(cavity.name);
    REQUIRE(fill.filled);
    const std::string defect = cavity_corpus::fill_defect(cavity, fill);
    CHECK_MESSAGE(defect.empty(), defect);
}

bool same_fill(const CavityFill& a, const CavityFill& b)
{
    if (a.filled != b.filled || a.stage != b.stage || a.tets != b.tets ||
        a.new_points.size() != b.new_points.size() || a.worst_quality != b.worst_quality)
        return false;
    for (std::size_t k = 0; k < a.new_points.size(); ++k)
        if (a.new_points[k] != b.new_points[k]) return false;
    return true;
}

using Stage = bool (*)(const Cavity&, CavityFill&);

bool kernel_fan(const Cavity& c, CavityFill& fill)
{
    return detail::fill_by_kernel_fan(c.points, c.faces, fill);
}
bool exhaustive(const Cavity& c, CavityFill& fill)
{
    return detail::fill_exhaustive(c.points, c.faces, CavityOptions{}, fill);
}
bool small_cavity(const Cavity& c, CavityFill& fill)
{
    return detail::fill_small_cavity(c.points, c.faces, CavityOptions{}, fill);
}

/// Runs a stage twice: a valid fill, the same both times; or false both times with the fill
/// untouched.
bool run_checked(Stage stage, const Cavity& cavity, CavityFill& fill)
{
    CavityFill first, second;
    first.ref = second.ref = 7;
    const bool filled = stage(cavity, first);
    INFO(cavity.name);
    CHECK(stage(cavity, second) == filled);
    CHECK(same_fill(first, second));
    CHECK(first.ref == 7);
    if (filled)
        require_valid_fill(cavity, first);
    else
    {
        CHECK_FALSE(first.filled);
        CHECK(first.tets.empty());
        CHECK(first.new_points.empty());
    }
    fill = first;
    return filled;
}

/// The best worst cone Qe over a grid of apexes in the cavity's box: what the kernel fan's
/// search must reach.
double grid_best_cone_quality(const Cavity& cavity, int steps)
{
    Vec3 lo = cavity.points[0], hi = cavity.points[0];
    for (const auto& p : cavity.points)
    {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    double best = -1;
    for (int i = 0; i <= steps; ++i)
        for (int j = 0; j <= steps; ++j)
            for (int k = 0; k <= steps; ++k)
            {
                const Vec3 p = lo + (hi - lo).cwiseProduct(Vec3(i, j, k) / steps);
                double worst = std::numeric_limits<double>::max();
                for (const auto& f : cavity.faces)
                {
                    worst = std::min(worst, tet_quality(cavity.points[f[0]], cavity.points[f[2]],
                                                        cavity.points[f[1]], p));
                    if (worst <= best) break;
                }
                best = std::max(best, worst);
            }
    return best;
}

}  // namespace

TEST_CASE("kernel LP: the Chebyshev centre of a cube, a tet and an empty kernel")
{
    Vec3 centre;
    double radius = 0;
    const Cavity cube = cavity_corpus::cube();
    REQUIRE(detail::kernel_chebyshev_centre(cube.points, cube.faces, centre, radius));
    CHECK(radius == doctest::Approx(0.5));
    CHECK((centre - Vec3(0.5, 0.5, 0.5)).norm() < 1e-9);

    // the corner tet's inradius is 1 / (3 + sqrt 3), at (r, r, r)
    const Cavity tet = cavity_corpus::single_tet();
    REQUIRE(detail::kernel_chebyshev_centre(tet.points, tet.faces, centre, radius));
    const double r = 1.0 / (3.0 + std::sqrt(3.0));
    CHECK(radius == doctest::Approx(r));
    CHECK((centre - Vec3(r, r, r)).norm() < 1e-9);

    // a slab 0.05 thick: the ball is 0.025
    const Cavity slab = cavity_corpus::thin_slab(3, 0.05);
    REQUIRE(detail::kernel_chebyshev_centre(slab.points, slab.faces, centre, radius));
    CHECK(radius == doctest::Approx(0.025));

    const Cavity glued = cavity_corpus::glued_schonhardt_prisms();
    CHECK_FALSE(detail::kernel_chebyshev_centre(glued.points, glued.faces, centre, radius));
    const Cavity chazelle = cavity_corpus::chazelle(2);
    CHECK_FALSE(detail::kernel_chebyshev_centre(chazelle.points, chazelle.faces, centre, radius));
}

TEST_CASE("kernel fan: a cone from one new point on every star-shaped cavity of the corpus")
{
    for (const Cavity& cavity : cavity_corpus::all_cavities())
    {
        CavityFill fill;
        Vec3 centre;
        double radius = 0;
        const bool star_shaped =
            detail::kernel_chebyshev_centre(cavity.points, cavity.faces, centre, radius);
        INFO(cavity.name);
        CHECK(run_checked(kernel_fan, cavity, fill) == star_shaped);
        if (!star_shaped) continue;
        CHECK(fill.stage == FillStage::KernelFan);
        CHECK(fill.new_points.size() == 1);
        CHECK(fill.tets.size() == cavity.faces.size());
    }
}

/*  Twisted prisms, n lateral quads each split by its reflex diagonal (tests/cavity_corpus.h):
    no tetrahedralization of the 2n points alone exists. The cone from one kernel point has
    one tet per face: 2n lateral triangles + 2 (n-2) cap triangles = 4n - 4 tets.             */
TEST_CASE("kernel fan: twisted prisms n = 3..8 get 1 Steiner point and 4n-4 tets")
{
    const std::map<int, double> peer_best = {{3, 0.20}, {4, 0.40}, {6, 0.31}};
    for (int n = 3; n <= 8; ++n)
    {
        const Cavity prism = cavity_corpus::twisted_prism(n);
        INFO(prism.name);
        CavityFill vertex_fan;
        CHECK_FALSE(detail::fill_by_vertex_fan(prism.points, prism.faces, vertex_fan));
        CavityFill exhaustive_without_points;
        CavityOptions no_room;
        no_room.max_exhaustive_points = 2 * n;  // the prism's points, no Steiner candidate
        CHECK_FALSE(
            detail::fill_exhaustive(prism.points, prism.faces, no_room, exhaustive_without_points));

        CavityFill fill;
        REQUIRE(run_checked(kernel_fan, prism, fill));
        CHECK(fill.new_points.size() == 1);
        CHECK(fill.tets.size() == static_cast<std::size_t>(4 * n - 4));
        if (peer_best.count(n)) CHECK(fill.worst_quality >= peer_best.at(n));
        // the search in the kernel reaches the best apex of a fine grid
        if (n <= 6) CHECK(fill.worst_quality >= grid_best_cone_quality(prism, 40) - 1e-3);
    }
}

TEST_CASE("exhaustive: cavities that need no new point get none, with the max-min split")
{
    struct Expected
    {
        Cavity cavity;
        std::size_t tets;  // 0: not fixed
        double at_least;
    };
    const std::vector<Expected> cases = {
        {cavity_corpus::single_tet(), 1, 0.73},
        {cavity_corpus::convex_prism(), 3, 0.0},
        {cavity_corpus::octahedron(), 4, 0.0},
        // the 5-tet split: a regular tet in the middle and 4 corner tets
        {cavity_corpus::cube(), 5, 0.73},
        {cavity_corpus::nearly_coplanar_cube(), 5, 0.0},
        {cavity_corpus::l_shape(), 0, 0.0},
        {cavity_corpus::needle_bipyramid(), 2, 0.0},
        {cavity_corpus::thin_slab(3, 0.05), 0, 0.0},
        {cavity_corpus::icosahedron(), 0, 0.0},
        {cavity_corpus::edge_shell(), 0, 0.0},
    };
    for (const auto& expected : cases)
    {
        INFO(expected.cavity.name);
        CavityFill fill;
        REQUIRE(run_checked(exhaustive, expected.cavity, fill));
        CHECK(fill.stage == FillStage::Exhaustive);
        CHECK(fill.new_points.empty());
        if (expected.tets > 0) CHECK(fill.tets.size() == expected.tets);
        CHECK(fill.worst_quality >= expected.at_least);
        // max-min: never below the fans over the same points
        CavityFill fan;
        if (detail::fill_by_vertex_fan(expected.cavity.points, expected.cavity.faces, fan))
            CHECK(fill.worst_quality >= fan.worst_quality - 1e-12);
    }
}

TEST_CASE("exhaustive: Schönhardt-type cavities take the kernel point, glued ones two points")
{
    for (int n = 3; n <= 6; ++n)
    {
        const Cavity prism = cavity_corpus::twisted_prism(n);
        INFO(prism.name);
        CavityFill fill, fan;
        REQUIRE(run_checked(exhaustive, prism, fill));
        CHECK(fill.new_points.size() == 1);
        REQUIRE(detail::fill_by_kernel_fan(prism.points, prism.faces, fan));
        CHECK(fill.worst_quality >= fan.worst_quality - 1e-12);
    }

    // empty kernel: one candidate per face group that has a kernel (here each prism's)
    const Cavity glued = cavity_corpus::glued_schonhardt_prisms();
    CavityFill fill;
    REQUIRE(run_checked(exhaustive, glued, fill));
    CHECK(fill.new_points.size() == 2);
    CHECK(fill.worst_quality >= 0.2);
}

TEST_CASE("exhaustive: limits give a clean refusal, and the search finishes within its budget")
{
    const Cavity chazelle = cavity_corpus::chazelle(2);
    CavityFill fill;
    run_checked(exhaustive, chazelle, fill);  // filled or not, but valid and repeatable

    CavityOptions small_budget;
    small_budget.exhaustive_node_budget = 50;
    CavityFill budgeted;
    if (detail::fill_exhaustive(chazelle.points, chazelle.faces, small_budget, budgeted))
        require_valid_fill(chazelle, budgeted);

    CavityOptions too_few_points;
    too_few_points.max_exhaustive_points = 7;
    const Cavity cube = cavity_corpus::cube();
    CavityFill untouched;
    untouched.ref = 3;
    CHECK_FALSE(detail::fill_exhaustive(cube.points, cube.faces, too_few_points, untouched));
    CHECK_FALSE(untouched.filled);
    CHECK(untouched.ref == 3);
    CHECK(untouched.tets.empty());

    // more points than the search's bitmasks hold: refused whatever the option says
    const Cavity big = cavity_corpus::chazelle(3);
    CavityOptions generous;
    generous.max_exhaustive_points = 1000;
    CHECK_FALSE(detail::fill_exhaustive(big.points, big.faces, generous, untouched));
}

TEST_CASE("small cavity: stages 1-3 fill the corpus, cheapest stage that is good enough")
{
    for (const Cavity& cavity : cavity_corpus::all_cavities())
    {
        INFO(cavity.name);
        CavityFill fill;
        const bool filled = run_checked(small_cavity, cavity, fill);
        if (cavity.name.rfind("Chazelle", 0) != 0) CHECK(filled);
    }
    CavityFill fill;
    REQUIRE(run_checked(small_cavity, cavity_corpus::convex_prism(), fill));
    CHECK(fill.stage == FillStage::VertexFan);
    CHECK(fill.tets.size() == 3);
    CHECK(fill.new_points.empty());

    for (int n = 3; n <= 8; ++n)
    {
        REQUIRE(run_checked(small_cavity, cavity_corpus::twisted_prism(n), fill));
        CHECK(fill.new_points.size() == 1);
        CHECK(fill.tets.size() == static_cast<std::size_t>(4 * n - 4));
    }

    REQUIRE(run_checked(small_cavity, cavity_corpus::glued_schonhardt_prisms(), fill));
    CHECK(fill.stage == FillStage::Exhaustive);

    // the slab: no vertex sees the coplanar faces of its own sheet, the kernel fan is flat,
    // the exhaustive search joins the two sheets
    REQUIRE(run_checked(small_cavity, cavity_corpus::thin_slab(3, 0.05), fill));
    CHECK(fill.stage == FillStage::Exhaustive);
    CHECK(fill.new_points.empty());
}

/*  Property test: connected sets of 2-16 tets cut out of a jittered 3x3x3 Kuhn box (interior
    or touching the boundary), their boundary refilled by stages 1-3: always filled (the cut
    tets are a fill without new points), valid and repeatable.                               */
TEST_CASE("small cavity: random connected tet sets cut out of a jittered box are refilled")
{
    const TetMesh mesh = fixtures::box_mesh(3, 0.2, 5);
    std::mt19937 rng(11);
    int by_stage[volume::kNumFillStages] = {};
    for (int trial = 0; trial < 300; ++trial)
    {
        const int wanted = 2 + static_cast<int>(rng() % 15);
        std::vector<int> set = {static_cast<int>(rng() % mesh.num_tet_slots())};
        for (int guard = 0; static_cast<int>(set.size()) < wanted && guard < 200; ++guard)
        {
            const int from = set[rng() % set.size()];
            const int next = mesh.neighbors[from][rng() % 4];
            if (next >= 0 && std::find(set.begin(), set.end(), next) == set.end())
                set.push_back(next);
        }
        std::vector<TetVertices> tets;
        for (int t : set) tets.push_back(mesh.tets[t]);
        Cavity cavity{
            "cut of " + std::to_string(set.size()) + " tets, trial " + std::to_string(trial),
            mesh.points, cavity_corpus::boundary_of(tets)};
        try
        {
            cavity_corpus::require_closed(cavity);
        }
        catch (const std::logic_error&)
        {
            continue;  // tets meeting along an edge only: not a cavity fill_cavity accepts
        }
        CavityFill fill;
        INFO(cavity.name);
        REQUIRE(run_checked(small_cavity, cavity, fill));
        ++by_stage[static_cast<int>(fill.stage)];
    }
    MESSAGE("stages used: vertex fan " << by_stage[0] << ", kernel fan " << by_stage[1]
                                       << ", exhaustive " << by_stage[2]);
    CHECK(by_stage[2] > 0);
}
