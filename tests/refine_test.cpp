// refine_pass / refine (volume/refine/refine.h): conformity (the checker after every pass), volume
// conservation, no edge too long at the end, vertex classes and refs carried, and the 14
// Schönhardt configurations reached on a real mesh by forcing the face rule.

#include "volume/refine/refine.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/io/tet_io.h"
#include "volume/mesh/blocks.h"
#include "volume/mesh/tet_tables.h"
#include "volume/refine/refine_patterns.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

/// h(p) = h0 * (floor + |p - center|): finer towards a random center, graded.
class RadialSize : public SizeField
{
public:
    RadialSize(Vec3 center, double h0, double floor) : center_(center), h0_(h0), floor_(floor) {}
    double size(const Vec3& p) const override { return h0_ * (floor_ + (p - center_).norm()); }

private:
    Vec3 center_;
    double h0_, floor_;
};

/// Small at the midpoints of chosen segments, large elsewhere: splits exactly those edges.
class SplitTheseEdges : public SizeField
{
public:
    void add(const Vec3& a, const Vec3& b) { midpoints_.push_back(0.5 * (a + b)); }
    double size(const Vec3& p) const override
    {
        for (const Vec3& m : midpoints_)
            if ((p - m).norm() < 1e-9) return 1e-3;
        return 1e3;
    }

private:
    std::vector<Vec3> midpoints_;
};

int popcount_mask(int mask)
{
    int n = 0;
    for (; mask; mask &= mask - 1) ++n;
    return n;
}

std::vector<Edge> unique_edges(const TetMesh& mesh)
{
    std::vector<Edge> edges;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        for (const auto& ev : tet::kEdgeVertices)
        {
            const int a = mesh.tets[t][ev[0]], b = mesh.tets[t][ev[1]];
            edges.push_back({std::min(a, b), std::max(a, b)});
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

int count_too_long(const TetMesh& mesh, const SizeField& field)
{
    int n = 0;
    for (const auto& e : unique_edges(mesh))
    {
        const Vec3& a = mesh.points[e[0]];
        const Vec3& b = mesh.points[e[1]];
        n += is_too_long((b - a).norm(), edge_target_size(field, a, b));
    }
    return n;
}

/// The checker, the classes (as classify_vertices would set them), positive volumes.
void require_valid(const TetMesh& mesh)
{
    const auto violations = check_mesh(mesh);
    CHECK_MESSAGE(violations.empty(), format_violations(violations));
    REQUIRE(mesh.has_adjacency());
    CHECK(mesh.num_live_tets() == mesh.num_tet_slots());
    TetMesh classified = mesh;
    classified.classify_vertices();
    int mismatched = 0;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        mismatched += classified.vertex_classes[v] != mesh.vertex_classes[v];
    CHECK(mismatched == 0);
}

/// Refines pass by pass, checking every intermediate mesh; returns the number of passes.
int refine_checked(TetMesh& mesh, const SizeField& field, int max_passes = 40)
{
    const double volume = mesh.total_volume();
    for (int pass = 1; pass <= max_passes; ++pass)
    {
        const int vertices_before = mesh.num_vertices();
        const RefinePassResult r = refine_pass(mesh, field);
        require_valid(mesh);
        CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-10));
        CHECK(r.report.vertices == mesh.num_vertices());
        CHECK(r.report.tets == mesh.num_tet_slots());
        CHECK(mesh.num_vertices() ==
              vertices_before + r.report.edges_split + r.report.steiner_points);
        for (int v : r.new_boundary_vertices)
            CHECK(mesh.vertex_classes[v] != VertexClass::Interior);
        for (int v : r.steiner_vertices) CHECK(mesh.vertex_classes[v] == VertexClass::Interior);
        if (r.report.edges_split == 0) return pass;
    }
    FAIL("refinement did not converge");
    return max_passes;
}

}  // namespace

TEST_CASE("refine: the face rule is a pure function of the face, ties go to the smaller id")
{
    const TetMesh regular = fixtures::regular_tet();
    // on a rank's cut ties go to the lexicographically first position instead
    auto first = [&](int a, int b) {
        const Vec3 &pa = regular.points[a], &pb = regular.points[b];
        return std::lexicographical_compare(pb.data(), pb.data() + 3, pa.data(), pa.data() + 3) ? b
                                                                                                : a;
    };
    for (int c = 0; c < 4; ++c)
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b)
            {
                if (a == b || a == c || b == c) continue;
                CHECK(quad_diagonal_start(regular.points, c, a, b) ==
                      quad_diagonal_start(regular.points, c, b, a));
                CHECK(quad_diagonal_start(regular.points, c, a, b) ==
                      std::min(a, b));  // equilateral: tie
                CHECK(quad_diagonal_start_by_position(regular.points, c, a, b) == first(a, b));
                CHECK(quad_diagonal_start_by_position(regular.points, c, b, a) == first(a, b));
            }

    //      2
    //      |\          corner 0, split edges 0-1 (long) and 0-2: the diagonal from 2 to the
    //      | \         midpoint of the long edge 0-1 keeps both quad triangles fat.
    //      0----------1
    std::vector<Vec3> p = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 1, 0)};
    CHECK(quad_diagonal_start(p, 0, 1, 2) == 2);
    CHECK(quad_diagonal_start(p, 0, 2, 1) == 2);
}

TEST_CASE("refine: one tet, nothing too long: the mesh is untouched and adjacency built")
{
    TetMesh mesh = fixtures::single_tet();
    const TetMesh before = mesh;
    const ConstantSize field(10.0);
    const RefinePassResult r = refine_pass(mesh, field);
    CHECK(r.report.edges_split == 0);
    CHECK(mesh.tets == before.tets);
    CHECK(mesh.points.size() == before.points.size());
    require_valid(mesh);
}

TEST_CASE("refine: a regular tet (ties everywhere) refines conformingly to a uniform size")
{
    TetMesh mesh = fixtures::regular_tet();
    const ConstantSize field(0.2);
    const double volume = mesh.total_volume();
    refine_checked(mesh, field);
    CHECK(count_too_long(mesh, field) == 0);
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-10));
    CHECK(mesh.num_tet_slots() > 64);  // at least two full passes
}

TEST_CASE("refine: Kuhn cube and structured boxes (ties everywhere) stay conforming")
{
    for (int n : {1, 2, 3})
    {
        CAPTURE(n);
        TetMesh mesh = fixtures::box_mesh(n);
        const ConstantSize field(0.15);
        refine_checked(mesh, field);
        CHECK(count_too_long(mesh, field) == 0);
        CHECK(mesh.total_volume() == doctest::Approx(1.0).epsilon(1e-10));
    }
    // graded: splits some edges only, so every kind of face pattern meets its neighbour
    TetMesh mesh = fixtures::box_mesh(2);
    const RadialSize field(Vec3(0, 0, 0), 0.5, 0.1);
    refine_checked(mesh, field);
    CHECK(count_too_long(mesh, field) == 0);
}

TEST_CASE("refine: refs and classes are carried; boundary triangles split with the tets")
{
    TetMesh mesh = fixtures::box_mesh(2);
    // two tet refs (left/right half), triangle refs by side, a ridge along one cube edge
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        Vec3 c = Vec3::Zero();
        for (int v : mesh.tets[t]) c += 0.25 * mesh.points[v];
        mesh.tet_refs[t] = c.x() < 0.5 ? 7 : 8;
    }
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        Vec3 c = Vec3::Zero();
        for (int v : mesh.triangles[i]) c += mesh.points[v] / 3.0;
        mesh.triangle_refs[i] = c.z() < 1e-9 ? 5 : 1;
    }
    for (int v = 0; v < mesh.num_vertices(); ++v)
    {
        const Vec3& p = mesh.points[v];
        if (p.y() < 1e-9 && p.z() < 1e-9 && p.x() > 1e-9)  // segments of the x axis
            for (int w = 0; w < mesh.num_vertices(); ++w)
                if (mesh.points[w].y() < 1e-9 && mesh.points[w].z() < 1e-9 &&
                    std::abs(mesh.points[w].x() - (p.x() - 0.5)) < 1e-9)
                {
                    mesh.edges.push_back({w, v});
                    mesh.edge_refs.push_back(3);
                    mesh.ridges.push_back(static_cast<int>(mesh.edges.size()) - 1);
                }
    }
    REQUIRE(mesh.edges.size() == 2u);
    // one triangle of the top face required, away from the ridge and the bottom
    for (std::size_t i = 0; i < mesh.triangles.size() && mesh.required_triangles.empty(); ++i)
        if (std::all_of(mesh.triangles[i].begin(), mesh.triangles[i].end(),
                        [&](int v) { return mesh.points[v].z() == 1.0; }))
            mesh.required_triangles = {static_cast<int>(i)};
    REQUIRE(mesh.required_triangles.size() == 1u);
    const Triangle required = mesh.triangles[mesh.required_triangles[0]];
    mesh.classify_vertices();
    const double left = [&] {
        double v = 0;
        for (int t = 0; t < mesh.num_tet_slots(); ++t)
            if (mesh.tet_refs[t] == 7) v += mesh.volume(t);
        return v;
    }();

    const ConstantSize field(0.2);
    refine_checked(mesh, field);
    double left_after = 0;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (mesh.tet_refs[t] == 7) left_after += mesh.volume(t);
    CHECK(left_after == doctest::Approx(left).epsilon(1e-12));

    // the ridge: split into pieces of length <= 0.2*1.515, all Ridge-class inside, ref 3
    CHECK(mesh.edges.size() == mesh.ridges.size());
    double ridge_length = 0;
    for (std::size_t i = 0; i < mesh.edges.size(); ++i)
    {
        const auto& e = mesh.edges[i];
        ridge_length += (mesh.points[e[1]] - mesh.points[e[0]]).norm();
        CHECK(mesh.edge_refs[i] == 3);
        for (int v : e)
        {
            CHECK(mesh.points[v].y() == 0.0);
            CHECK(mesh.points[v].z() == 0.0);
        }
    }
    CHECK(ridge_length == doctest::Approx(1.0));
    CHECK(mesh.edges.size() >= 4u);
    // triangle refs: bottom area stays ref 5
    double bottom = 0;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        const auto& t = mesh.triangles[i];
        if (mesh.triangle_refs[i] == 5)
        {
            bottom += triangle_area(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
            for (int v : t) CHECK(mesh.points[v].z() == 0.0);
        }
    }
    CHECK(bottom == doctest::Approx(1.0));
    // the required triangle is never split: the same one, still required
    REQUIRE(mesh.required_triangles.size() == 1u);
    CHECK(mesh.triangles[mesh.required_triangles[0]] == required);
}

TEST_CASE("refine: required triangles and edges are never split, bit for bit")
{
    //   z=0 face of the box: its 8 triangles required, and one vertical edge of the box a
    //   required feature edge; a size 0.15 splits everything else
    TetMesh mesh = fixtures::box_mesh(2);
    std::vector<std::array<Vec3, 3>> kept;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        const auto& t = mesh.triangles[i];
        if (mesh.points[t[0]].z() == 0.0 && mesh.points[t[1]].z() == 0.0 &&
            mesh.points[t[2]].z() == 0.0)
        {
            mesh.required_triangles.push_back(static_cast<int>(i));
            kept.push_back({mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]});
        }
    }
    REQUIRE(kept.size() == 8u);
    int low = -1, high = -1;  // (1,1,0)-(1,1,0.5)
    for (int v = 0; v < mesh.num_vertices(); ++v)
    {
        if (mesh.points[v] == Vec3(1, 1, 0)) low = v;
        if (mesh.points[v] == Vec3(1, 1, 0.5)) high = v;
    }
    REQUIRE(low >= 0);
    REQUIRE(high >= 0);
    mesh.edges.push_back({low, high});
    mesh.edge_refs.push_back(2);
    mesh.required_edges = {0};
    mesh.classify_vertices();

    const ConstantSize field(0.15);
    refine_checked(mesh, field);
    REQUIRE(mesh.required_triangles.size() == 8u);
    for (std::size_t k = 0; k < kept.size(); ++k)
    {
        const auto& t = mesh.triangles[mesh.required_triangles[k]];
        for (int c = 0; c < 3; ++c) CHECK(mesh.points[t[c]] == kept[k][c]);
    }
    REQUIRE(mesh.required_edges.size() == 1u);
    CHECK(mesh.edges[mesh.required_edges[0]] == Edge{low, high});
    // everything else was refined
    CHECK(mesh.num_live_tets() > 48 * 20);
}

TEST_CASE("refine: forced face rules reach all 14 Schönhardt configurations on a real tet")
{
    // star: the three edges at one vertex split; 8 ways to choose the three quad diagonals,
    // exactly 2 twist (each midpoint the end of one diagonal) and need the Steiner point.
    // four-cycle: edges 01 12 23 30 split (02, 13 not) etc.; 16 choices, exactly 2 twist.
    //
    //  star at vertex 0: edges 0-1, 0-2, 0-3 split at a, b, c.
    //            3
    //           /|\         cutting the corner tet (0 a b c) leaves the prism
    //          c | \        a b c / 1 2 3 whose three quad sides (a b 2 1),
    //         /  |  \       (b c 3 2), (c a 1 3) each get one diagonal; when
    //        0---b---2      each of a, b, c ends exactly one diagonal they
    //         \  |  /       twist: the prism is a Schönhardt polyhedron and
    //          a | /        needs the Steiner point.
    //           \|/
    //            1
    int steiner_runs = 0, runs = 0;
    for (int mask = 1; mask < 64; ++mask)
    {
        const int quads = faces_with_two_split_edges(mask);
        int nquads = 0;
        for (int f = 0; f < 4; ++f) nquads += (quads >> f) & 1;
        if (nquads < 3) continue;  // Schönhardt needs every face around the prism twisted
        for (int choice = 0; choice < (1 << nquads); ++choice)
        {
            TetMesh mesh = fixtures::regular_tet();
            const double volume = mesh.total_volume();
            SplitTheseEdges field;
            for (int e = 0; e < 6; ++e)
                if ((mask >> e) & 1)
                    field.add(mesh.points[tet::kEdgeVertices[e][0]],
                              mesh.points[tet::kEdgeVertices[e][1]]);
            // the rule: face k (in order of its smallest-id corner key) takes bit k of choice
            std::map<std::array<int, 3>, int> face_bit;
            const QuadDiagonalRule rule = [&](int corner, int a, int b) {
                const std::array<int, 3> key = {corner, a, b};
                auto it = face_bit.find(key);
                if (it == face_bit.end())
                    it = face_bit.emplace(key, static_cast<int>(face_bit.size())).first;
                return ((choice >> it->second) & 1) ? b : a;
            };
            const RefinePassResult r = refine_pass(mesh, field, rule);
            CAPTURE(mask);
            CAPTURE(choice);
            CHECK(r.report.edges_split == popcount_mask(mask));
            require_valid(mesh);
            CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-12));
            ++runs;
            if (r.report.steiner_points > 0)
            {
                ++steiner_runs;
                CHECK(r.report.steiner_points == 1);
                REQUIRE(r.steiner_vertices.size() == 1u);
                const int s = r.steiner_vertices[0];
                CHECK(mesh.vertex_classes[s] == VertexClass::Interior);
                CHECK(mesh.num_tet_slots() >= 9);
                CHECK(mesh.num_tet_slots() <= 12);
            }
        }
    }
    CHECK(runs > 0);
    CHECK(steiner_runs == 14);
}

TEST_CASE("refine: property test, jittered boxes with random graded fields, many seeds")
{
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (std::uint32_t seed = 1; seed <= 24; ++seed)
    {
        CAPTURE(seed);
        TetMesh mesh = fixtures::box_mesh(3, 0.2, seed);
        const Vec3 center(unit(rng), unit(rng), unit(rng));
        const RadialSize field(center, 0.3 + 0.4 * unit(rng), 0.15 + 0.2 * unit(rng));
        const double volume = mesh.total_volume();
        refine_checked(mesh, field);
        CHECK(count_too_long(mesh, field) == 0);
        CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-10));
    }
}

TEST_CASE("refine: the sphere with random fields and the paper's case A")
{
    const TetMesh sphere = read_mesh(fixtures::data_path("sphere480.mesh"));
    const double volume = sphere.total_volume();
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> coord(-0.8, 0.8);
    for (int trial = 0; trial < 3; ++trial)
    {
        CAPTURE(trial);
        TetMesh mesh = sphere;
        const RadialSize field(Vec3(coord(rng), coord(rng), coord(rng)), 0.4, 0.3);
        refine_checked(mesh, field);
        CHECK(count_too_long(mesh, field) == 0);
        CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-10));
    }

    TetMesh mesh = sphere;
    const BenchmarkSize field(benchmark_case('A'));
    const RefineResult r = refine(mesh, field);
    CHECK(r.converged);
    require_valid(mesh);
    CHECK(count_too_long(mesh, field) == 0);
    CHECK(mesh.total_volume() == doctest::Approx(volume).epsilon(1e-10));
    CHECK(mesh.total_volume() == doctest::Approx(4.00715).epsilon(1e-5));
    int split = 0;
    for (const auto& pass : r.passes) split += pass.edges_split;
    CHECK(mesh.num_vertices() ==
          sphere.num_vertices() + split + static_cast<int>(r.steiner_vertices.size()));
    for (int v : r.new_boundary_vertices) CHECK(mesh.vertex_classes[v] == VertexClass::Surface);
}

TEST_CASE("refine: a tet flat in doubles defers its edges to a later pass instead of failing")
{
    //        c
    //       / \      d lies on the plane of abc up to round-off: the tet is positive, but
    //      /.d.\     its children from rounded midpoints need not be. Such tets (the front
    //     a-----b    leaves slivers in flat pockets) must not stop the pass.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int deferred = 0, tried = 0;
    for (int trial = 0; trial < 4000 && deferred == 0; ++trial)
    {
        const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
        const double wa = u(rng), wb = u(rng) * (1 - wa);
        const Vec3 d = wa * a + wb * b + (1 - wa - wb) * c;
        TetMesh mesh;
        mesh.points = {a, b, c, d};
        mesh.tets = {{0, 1, 2, 3}};
        if (!(mesh.volume(0) > 0)) mesh.tets[0] = {0, 2, 1, 3};
        if (!(mesh.volume(0) > 0)) continue;
        mesh.tet_refs = {1};
        mesh.vertex_refs.assign(4, 0);
        mesh.vertex_classes.assign(4, VertexClass::Interior);
        ++tried;
        const ConstantSize field(1e-3);  // every edge too long
        RefinePassResult result;
        CHECK_NOTHROW(result = refine_pass(mesh, field));
        deferred += result.report.deferred_edges;
        if (result.report.deferred_edges > 0)
        {
            // nothing split that the stuck tet holds: it is still there, whole
            CHECK(result.report.edges_split == 0);
            CHECK(mesh.num_live_tets() == 1);
        }
        else
            CHECK(mesh.num_live_tets() > 1);
    }
    CHECK(tried > 0);
    CHECK(deferred > 0);  // the search met the case
}

namespace
{

/// The tets of `mesh` on one side of the plane x = 0.5 (by centroid) as a mesh of their own,
/// the left side's vertices numbered in reverse (the sides number them apart), the faces it shares
/// with the other side listed as a rank's cut (required triangles of kRankCutRef), the others
/// as boundary (ref 1).
TetMesh side_of_cut(const TetMesh& mesh, bool left)
{
    auto on_side = [&](int t) {
        Vec3 c = Vec3::Zero();
        for (int v : mesh.tets[t]) c += 0.25 * mesh.points[v];
        return (c[0] < 0.5) == left;
    };
    const int nv = mesh.num_vertices();
    auto id = [&](int v) { return left ? nv - 1 - v : v; };
    std::vector<Vec3> points(nv);
    for (int v = 0; v < nv; ++v) points[id(v)] = mesh.points[v];
    std::vector<TetVertices> tets;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (on_side(t))
        {
            TetVertices tv = mesh.tets[t];
            for (int& v : tv) v = id(v);
            tets.push_back(tv);
        }
    TetMesh side = fixtures::mesh_from_tets(points, tets);
    std::set<std::array<int, 3>> cut;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        for (int f = 0; f < 4; ++f)
        {
            const int n = mesh.neighbors[t][f];
            if (!on_side(t) || n == kNoTet || on_side(n)) continue;
            std::array<int, 3> key;
            for (int k = 0; k < 3; ++k) key[k] = id(mesh.tets[t][tet::kFaceVertices[f][k]]);
            std::sort(key.begin(), key.end());
            cut.insert(key);
        }
    for (std::size_t i = 0; i < side.triangles.size(); ++i)
    {
        std::array<int, 3> key = side.triangles[i];
        std::sort(key.begin(), key.end());
        if (!cut.count(key)) continue;
        side.triangle_refs[i] = kRankCutRef;
        side.required_triangles.push_back(static_cast<int>(i));
    }
    return side;
}

/// The cut's triangles as sorted position triples.
std::set<std::array<std::array<double, 3>, 3>> cut_triangles(const TetMesh& mesh)
{
    std::set<std::array<std::array<double, 3>, 3>> out;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        if (!is_rank_cut_ref(mesh.triangle_refs[i])) continue;
        std::array<std::array<double, 3>, 3> key;
        for (int k = 0; k < 3; ++k)
        {
            const Vec3& p = mesh.points[mesh.triangles[i][k]];
            key[k] = {p[0], p[1], p[2]};
        }
        std::sort(key.begin(), key.end());
        out.insert(key);
    }
    return out;
}

}  // namespace

TEST_CASE("refine: the two sides of a rank's cut, numbered apart, split it alike")
{
    for (double jitter : {0.0, 0.2})
    {
        CAPTURE(jitter);
        TetMesh box = fixtures::box_mesh(4, jitter);
        box.build_adjacency();
        TetMesh left = side_of_cut(box, true), right = side_of_cut(box, false);
        const std::size_t before = cut_triangles(left).size();
        REQUIRE(before > 0);
        REQUIRE(cut_triangles(right).size() == before);
        const RadialSize field(Vec3(0.5, 0.3, 0.2), 0.2, 0.2);
        REQUIRE(refine(left, field).converged);
        REQUIRE(refine(right, field).converged);
        const auto split = cut_triangles(left);
        CHECK(split.size() > 4 * before);  // refined, not kept as given
        CHECK(split == cut_triangles(right));
        CHECK(left.required_triangles.size() == split.size());
        require_valid(left);
        require_valid(right);
    }
}

TEST_CASE("refine: a cut edge at the threshold, measured a few ulps apart by the sides, is kept")
{
    // the box's edges along the axes are 0.25 long: at h = 0.66 * 0.25 they sit on the
    // threshold, and each side's field rounds the other way
    class Rounded : public SizeField
    {
    public:
        explicit Rounded(double factor) : factor_(factor) {}
        double size(const Vec3&) const override { return 0.66 * 0.25 * factor_; }

    private:
        double factor_;
    };
    TetMesh box = fixtures::box_mesh(4);
    box.build_adjacency();
    TetMesh left = side_of_cut(box, true), right = side_of_cut(box, false);
    refine(left, Rounded(1 - 4e-16));
    refine(right, Rounded(1 + 4e-16));
    CHECK(cut_triangles(left) == cut_triangles(right));
    require_valid(left);
    require_valid(right);
}

TEST_CASE("refine: a rank's cut held whole for a round is not split")
{
    TetMesh box = fixtures::box_mesh(4, 0.2);
    box.build_adjacency();
    TetMesh left = side_of_cut(box, true);
    for (int i : left.required_triangles) left.triangle_refs[i] = kHeldCutRef + 3;
    const auto before = cut_triangles(left);
    const RadialSize field(Vec3(0.5, 0.3, 0.2), 0.2, 0.2);
    refine(left, field);
    CHECK(left.num_live_tets() > 4 * box.num_live_tets() / 2);
    CHECK(cut_triangles(left) == before);
    for (int i : left.required_triangles) CHECK(rank_cut_domain_ref(left.triangle_refs[i]) == 3);
    require_valid(left);
}
