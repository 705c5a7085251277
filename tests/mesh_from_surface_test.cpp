// A tet mesh from a closed surface alone: small surfaces built in code, meshed with and without
// remeshing. Every produced mesh passes check_mesh (positive tets, the tets' boundary equal to
// mesh.triangles, the volume equal to the enclosed one); the boundary is kept exactly with
// keep_surface; nested shells leave a void, disjoint shells get refs 1 and 2; bad input is
// refused before anything is made.

#include "coupling/mesh_from_surface.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "common/errors.h"
#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/check/quality_report.h"
#include "volume/io/tet_io.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;
using namespace hdimesh::volume;
using coupling::mesh_volume_from_surface;
using coupling::VolumeFromSurfaceOptions;
using coupling::VolumeFromSurfaceReport;

namespace
{

/// A soup of icospheres, each outward unless `inward`.
struct Spheres
{
    surface::TriangleSoup soup;

    Spheres& add(const Vec3& centre, double radius, int levels = 2, bool inward = false)
    {
        const hdi::TriangleSurface s = fixtures::icosphere(levels);
        const int base = static_cast<int>(soup.points.size());
        for (const auto& p : s.points)
        {
            const Vec3 q = centre + radius * p;
            soup.points.emplace_back(q[0], q[1], q[2]);
        }
        for (auto t : s.triangles)
        {
            if (inward) std::swap(t[1], t[2]);
            soup.triangles.push_back({base + t[0], base + t[1], base + t[2]});
            soup.refs.push_back(7);
        }
        return *this;
    }
};

void require_valid(const TetMesh& mesh)
{
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    REQUIRE(violations.empty());
}

/// Boundary triangles as coordinate triples starting at their smallest corner (orientation
/// kept), sorted: equal exactly when two boundaries are the same oriented triangles.
using CoordinateTriangle = std::array<std::array<double, 3>, 3>;
std::vector<CoordinateTriangle> oriented_triangles(const std::vector<std::array<double, 3>>& pts,
                                                   const std::vector<std::array<int, 3>>& tris)
{
    std::vector<CoordinateTriangle> out;
    for (const auto& t : tris)
    {
        CoordinateTriangle c = {pts[t[0]], pts[t[1]], pts[t[2]]};
        std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
        out.push_back(c);
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<CoordinateTriangle> oriented_triangles(const TetMesh& mesh)
{
    std::vector<std::array<double, 3>> pts;
    for (const auto& p : mesh.points) pts.push_back({p[0], p[1], p[2]});
    return oriented_triangles(pts, {mesh.triangles.begin(), mesh.triangles.end()});
}

std::vector<CoordinateTriangle> oriented_triangles(const surface::TriangleSoup& soup)
{
    std::vector<std::array<double, 3>> pts;
    for (const auto& p : soup.points) pts.push_back({p[0], p[1], p[2]});
    return oriented_triangles(pts, soup.triangles);
}

Vec3 centroid(const TetMesh& mesh, int t)
{
    Vec3 c = Vec3::Zero();
    for (int v : mesh.tets[t]) c += mesh.points[v];
    return c / 4;
}

VolumeFromSurfaceOptions uniform(double h, bool keep_surface)
{
    VolumeFromSurfaceOptions options;
    options.sizing.hsiz = h;
    options.keep_surface = keep_surface;
    options.adapt.verbosity = 0;
    options.source = "test";
    return options;
}

/// The boundary of a union of cells of the grid xs x ys x zs (two outward triangles per
/// exposed cell face): boxes glued face to face, e.g. a block with a thin fin.
surface::TriangleSoup cell_union(const std::vector<double>& xs, const std::vector<double>& ys,
                                 const std::vector<double>& zs,
                                 const std::function<bool(int, int, int)>& full)
{
    const std::array<const std::vector<double>*, 3> axes = {&xs, &ys, &zs};
    const int nx = static_cast<int>(xs.size()), ny = static_cast<int>(ys.size());
    surface::TriangleSoup soup;
    for (double z : zs)
        for (double y : ys)
            for (double x : xs) soup.points.emplace_back(x, y, z);
    auto node = [&](std::array<int, 3> n) { return n[0] + nx * (n[1] + ny * n[2]); };
    auto is_full = [&](std::array<int, 3> c) {
        for (int a = 0; a < 3; ++a)
            if (c[a] < 0 || c[a] + 1 >= static_cast<int>(axes[a]->size())) return false;
        return full(c[0], c[1], c[2]);
    };
    for (int k = 0; k + 1 < static_cast<int>(zs.size()); ++k)
        for (int j = 0; j + 1 < ny; ++j)
            for (int i = 0; i + 1 < nx; ++i)
            {
                if (!full(i, j, k)) continue;
                for (int a = 0; a < 3; ++a)
                    for (int side : {0, 1})
                    {
                        std::array<int, 3> next = {i, j, k};
                        next[a] += side ? 1 : -1;
                        if (is_full(next)) continue;
                        const int b = (a + 1) % 3, c = (a + 2) % 3;
                        std::array<int, 4> quad;
                        const int corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                        for (int q = 0; q < 4; ++q)
                        {
                            std::array<int, 3> n = {i, j, k};
                            n[a] += side;
                            n[b] += corners[q][0];
                            n[c] += corners[q][1];
                            quad[q] = node(n);
                        }
                        if (!side) std::swap(quad[1], quad[3]);  // e_b x e_c is +a
                        soup.triangles.push_back({quad[0], quad[1], quad[2]});
                        soup.triangles.push_back({quad[0], quad[2], quad[3]});
                        soup.refs.push_back(1);
                        soup.refs.push_back(1);
                    }
            }
    return soup;
}

}  // namespace

TEST_CASE("a sphere's surface becomes a valid tet mesh at the size asked")
{
    // the unit icosphere (320 triangles, edges about 0.3) remeshed to 0.25 and filled
    const Spheres input = Spheres().add(Vec3::Zero(), 1.0, 2);
    const double h = 0.25;
    VolumeFromSurfaceReport report;
    const TetMesh mesh = mesh_volume_from_surface(input.soup, uniform(h, false), &report);
    require_valid(mesh);
    CHECK(report.regions == 1);
    CHECK(report.voids == 0);
    CHECK(report.fills.by_stage[static_cast<int>(FillStage::Failed)] == 0);
    for (int t = 0; t < mesh.num_tet_slots(); ++t) CHECK(mesh.tet_refs[t] == 1);
    // the boundary is on the input polyhedron, which is within 1.3 % of the unit sphere
    CHECK(fixtures::max_unit_sphere_deviation(mesh) < 0.02);
    const ConstantSize field(h);
    const QualityReport quality = compute_quality_report(mesh, &field);
    CHECK(quality.min_qe > 0.1);
    CHECK(quality.percent_too_long < 5.0);
    CHECK(quality.volume == doctest::Approx(quality.enclosed_volume).epsilon(1e-9));
    CHECK(quality.volume == doctest::Approx(4.0 / 3.0 * 3.14159265).epsilon(0.05));
}

TEST_CASE("keep_surface: the given triangles are the boundary, exactly and in orientation")
{
    const Spheres input = Spheres().add(Vec3(0.5, -1, 2), 1.0, 2);
    VolumeFromSurfaceReport report;
    const TetMesh mesh = mesh_volume_from_surface(input.soup, uniform(0.3, true), &report);
    require_valid(mesh);
    CHECK(report.surface_triangles == static_cast<int>(input.soup.triangles.size()));
    CHECK(oriented_triangles(mesh) == oriented_triangles(input.soup));
    CHECK(std::all_of(mesh.triangle_refs.begin(), mesh.triangle_refs.end(),
                      [](int r) { return r == 7; }));
    // Steiner points only inside: every other vertex is one of the input's
    int surface_vertices = 0;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        surface_vertices += mesh.vertex_classes[v] != VertexClass::Interior;
    CHECK(surface_vertices == static_cast<int>(input.soup.points.size()));
}

TEST_CASE("keep_surface on an inward shell: turned, filled, the same triangles reversed")
{
    const Spheres input = Spheres().add(Vec3::Zero(), 1.0, 1, true);
    VolumeFromSurfaceReport report;
    const TetMesh mesh = mesh_volume_from_surface(input.soup, uniform(0.5, true), &report);
    require_valid(mesh);
    REQUIRE(report.repairs.size() == 1);
    CHECK(report.repairs[0] == "test: repaired: turned 1 closed shell(s) outward");
    surface::TriangleSoup reversed = input.soup;
    for (auto& t : reversed.triangles) std::swap(t[1], t[2]);
    CHECK(oriented_triangles(mesh) == oriented_triangles(reversed));
}

TEST_CASE("nested shells make a void: no tet inside the inner shell")
{
    //   +-----------------+
    //   |  r = 2 (ref 1)   |   both spheres given outward, as solids
    //   |    ( r = 1 )     |
    //   +-----------------+
    const Spheres input = Spheres().add(Vec3::Zero(), 1.0, 2).add(Vec3::Zero(), 2.0, 2);
    for (const bool keep : {true, false})
    {
        CAPTURE(keep);
        VolumeFromSurfaceReport report;
        const TetMesh mesh = mesh_volume_from_surface(input.soup, uniform(0.4, keep), &report);
        require_valid(mesh);
        CHECK(report.regions == 1);
        CHECK(report.voids == 1);
        double volume = 0;
        for (int t = 0; t < mesh.num_tet_slots(); ++t)
        {
            CHECK(mesh.tet_refs[t] == 1);
            // the inner polyhedron holds the ball of its inradius (> 0.9)
            CHECK(centroid(mesh, t).norm() > 0.9);
            volume += mesh.volume(t);
        }
        const double shell = 4.0 / 3.0 * 3.14159265 * (8 - 1);
        CHECK(volume == doctest::Approx(shell).epsilon(0.05));
    }
}

TEST_CASE("disjoint shells are separate regions with refs 1 and 2")
{
    // listed right one first: refs follow the geometric order (lowest point first)
    const Spheres input = Spheres().add(Vec3(4, 0, 0), 1.0, 1).add(Vec3::Zero(), 1.0, 1);
    for (const bool keep : {true, false})
    {
        CAPTURE(keep);
        VolumeFromSurfaceReport report;
        const TetMesh mesh = mesh_volume_from_surface(input.soup, uniform(0.4, keep), &report);
        require_valid(mesh);
        CHECK(report.regions == 2);
        std::array<int, 3> per_ref{};
        for (int t = 0; t < mesh.num_tet_slots(); ++t)
        {
            const int ref = mesh.tet_refs[t];
            REQUIRE((ref == 1 || ref == 2));
            ++per_ref[ref];
            CHECK((centroid(mesh, t)[0] < 2) == (ref == 1));
        }
        CHECK(per_ref[1] > 0);
        CHECK(per_ref[2] > 0);
    }
}

TEST_CASE("sizes known on the surface only (hausd, sizes at the input points) reach the volume")
{
    const Spheres input = Spheres().add(Vec3::Zero(), 1.0, 2);
    {
        // on the unit sphere (curvature 1) hausd 0.02 asks for edges near sqrt(3 * 0.02) = 0.245
        VolumeFromSurfaceOptions options = uniform(0, false);
        options.sizing.hausd = 0.02;
        VolumeFromSurfaceReport report;
        const TetMesh mesh = mesh_volume_from_surface(input.soup, options, &report);
        require_valid(mesh);
        REQUIRE(report.field);
        for (const Vec3& p : {Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(0, 0, 0.99)})
        {
            CAPTURE(p);
            CHECK(report.field->size(p) > 0.1);
            CHECK(report.field->size(p) < 0.5);
        }
    }
    {
        // 0.4 at the input points with z > 0, 0.2 below: the lower half gets the finer tets
        VolumeFromSurfaceOptions options = uniform(0, false);
        for (const auto& p : input.soup.points)
            options.sizing.vertex_sizes.push_back(p[2] > 0 ? 0.4 : 0.2);
        VolumeFromSurfaceReport report;
        const TetMesh mesh = mesh_volume_from_surface(input.soup, options, &report);
        require_valid(mesh);
        CHECK(report.field->size(Vec3(0, 0, 0.9)) == doctest::Approx(0.4));
        CHECK(report.field->size(Vec3(0, 0, -0.9)) == doctest::Approx(0.2));
        int upper = 0, lower = 0;
        for (int t = 0; t < mesh.num_tet_slots(); ++t)
            (centroid(mesh, t)[2] > 0 ? upper : lower) += 1;
        CHECK(lower > 2 * upper);
    }
}

TEST_CASE("the same input gives the same mesh")
{
    const Spheres input = Spheres().add(Vec3::Zero(), 1.0, 2);
    const TetMesh a = mesh_volume_from_surface(input.soup, uniform(0.3, false));
    const TetMesh b = mesh_volume_from_surface(input.soup, uniform(0.3, false));
    CHECK(a.points == b.points);
    CHECK(a.tets == b.tets);
    CHECK(a.triangles == b.triangles);
}

TEST_CASE("bad surfaces and sizes are refused before anything is made")
{
    auto refusal = [](const surface::TriangleSoup& soup, const VolumeFromSurfaceOptions& o) {
        try
        {
            mesh_volume_from_surface(soup, o);
        }
        catch (const InputError& e)
        {
            return std::string(e.what());
        }
        return std::string();
    };
    Spheres open = Spheres().add(Vec3::Zero(), 1.0, 1);
    open.soup.triangles.pop_back();
    open.soup.refs.pop_back();
    VolumeFromSurfaceOptions strict = uniform(0.3, false);
    strict.repair.strict = true;
    CHECK(refusal(open.soup, strict).find("test: the surface is open: 1 boundary loop") == 0);
    // without --strict that hole is closed; half a sphere is no hole (its patch would be half
    // of what is left)
    Spheres half = Spheres().add(Vec3::Zero(), 1.0, 2);
    surface::TriangleSoup bowl = half.soup;
    bowl.triangles.clear();
    bowl.refs.clear();
    for (const auto& t : half.soup.triangles)
        if (bowl.points[t[0]][2] + bowl.points[t[1]][2] + bowl.points[t[2]][2] < 0)
        {
            bowl.triangles.push_back(t);
            bowl.refs.push_back(7);
        }
    CHECK(refusal(bowl, uniform(0.3, false)).find("test: the surface is open: 1 boundary loop") ==
          0);

    Spheres overlapping = Spheres().add(Vec3::Zero(), 1.0, 1).add(Vec3(0.5, 0, 0), 1.0, 1);
    CHECK(refusal(overlapping.soup, uniform(0.3, true)).find("intersects itself") !=
          std::string::npos);

    const Spheres fine = Spheres().add(Vec3::Zero(), 1.0, 1);
    VolumeFromSurfaceOptions two_sizes = uniform(0.3, false);
    two_sizes.sizing.hausd = 0.01;
    CHECK(refusal(fine.soup, two_sizes).find("at most one") != std::string::npos);
    VolumeFromSurfaceOptions sol = uniform(0, false);
    sol.sizing.hsiz = 0;
    sol.sizing.vertex_sizes.assign(5, 0.1);
    CHECK(refusal(fine.soup, sol).find("5 sizes for 42 points") != std::string::npos);
    CHECK(refusal(surface::TriangleSoup{}, uniform(0.3, false)) == "test: no triangles");
}

TEST_CASE("a mesh file's triangles without tets are read as a soup, refs kept")
{
    TetMesh mesh;
    for (const auto& p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)})
        mesh.add_vertex(p);
    mesh.add_triangle({1, 2, 3}, 4);
    mesh.add_triangle({0, 3, 2}, 4);
    mesh.add_triangle({0, 1, 3}, 5);
    mesh.add_triangle({0, 2, 1}, 5);
    const surface::TriangleSoup soup = coupling::triangle_soup(mesh);
    CHECK(soup.points.size() == 4);
    CHECK(soup.triangles.size() == 4);
    CHECK(soup.refs == std::vector<int>{4, 4, 5, 5});
    CHECK(soup.triangles[1] == std::array<int, 3>{0, 3, 2});
}

TEST_CASE("sphere480's boundary, kept, filled and optimized: the same triangles, a valid volume")
{
    // the 256 boundary triangles of data/sphere480.mesh, the tets dropped
    const TetMesh source = read_mesh(fixtures::data_path("sphere480.mesh"));
    const surface::TriangleSoup soup = coupling::triangle_soup(source);
    VolumeFromSurfaceReport report;
    const TetMesh mesh = mesh_volume_from_surface(soup, uniform(0.3, true), &report);
    require_valid(mesh);
    CHECK(report.fills.by_stage[static_cast<int>(FillStage::Failed)] == 0);
    auto sorted_triangles = [](const std::vector<Triangle>& triangles,
                               const std::vector<Vec3>& points) {
        std::vector<std::array<double, 9>> out;
        for (const Triangle& t : triangles)
        {
            std::array<int, 3> r{0, 1, 2};  // rotate to the smallest point first
            auto less = [&](int a, int b) {
                return std::lexicographical_compare(points[t[a]].data(), points[t[a]].data() + 3,
                                                    points[t[b]].data(), points[t[b]].data() + 3);
            };
            const int first = less(0, 1) ? (less(0, 2) ? 0 : 2) : (less(1, 2) ? 1 : 2);
            for (int k = 0; k < 3; ++k) r[k] = (first + k) % 3;
            std::array<double, 9> key{};
            for (int k = 0; k < 3; ++k)
                for (int c = 0; c < 3; ++c) key[3 * k + c] = points[t[r[k]]][c];
            out.push_back(key);
        }
        std::sort(out.begin(), out.end());
        return out;
    };
    // the boundary is the input's triangles, in position and orientation
    CHECK(sorted_triangles(mesh.triangles, mesh.points) ==
          sorted_triangles(source.triangles, source.points));
    const QualityReport quality = compute_quality_report(mesh, nullptr);
    CHECK(quality.volume == doctest::Approx(source.total_volume()).epsilon(1e-9));
    CHECK(quality.min_qe > 0.3);
}

TEST_CASE("keep_surface with triangles far longer than the size: the interior grades from them")
{
    //  +-------------------------------+   a 12 x 1 x 1 box of 12 triangles, kept, filled at
    //  |                               |   h = 0.25: a tet on a 12-long triangle has a long
    //  +-------------------------------+   edge whatever is done; splitting made slivers
    surface::TriangleSoup soup;
    for (int i = 0; i < 8; ++i)
        soup.points.push_back({(i & 1) ? 12.0 : 0.0, (i & 2) ? 1.0 : 0.0, (i & 4) ? 1.0 : 0.0});
    const std::array<std::array<int, 4>, 6> quads{
        {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
    for (const auto& q : quads)
    {
        soup.triangles.push_back({q[0], q[1], q[2]});
        soup.triangles.push_back({q[0], q[2], q[3]});
    }
    VolumeFromSurfaceReport report;
    const TetMesh mesh = mesh_volume_from_surface(soup, uniform(0.25, true), &report);
    require_valid(mesh);
    CHECK(mesh.triangles.size() == 12);
    CHECK(mesh.total_volume() == doctest::Approx(12.0).epsilon(1e-9));
    // before: 8 passes and 170k tets at min Qe 0.0006, still refining
    CHECK(report.adapt.converged);
    CHECK(mesh.num_live_tets() < 200);
    CHECK(report.min_quality > 0.05);
}

TEST_CASE("thin parts get sizes their thickness allows: a fin and a finger at half the size")
{
    // a unit block with a fin (0.05 thick) on +x and a square finger (0.05 across) on -x, at
    // h = 0.1: the sizes there are bounded, the block keeps h (flat sides: 0.477 unbounded)
    const std::vector<double> xs = {-0.6, -0.3, 0, 0.5, 1, 1.3, 1.6};
    const std::vector<double> ys = {0, 0.3, 0.475, 0.525, 0.7, 1};
    const std::vector<double> zs = {0, 0.475, 0.525, 1};
    const surface::TriangleSoup soup = cell_union(xs, ys, zs, [](int i, int j, int k) {
        if (i == 2 || i == 3) return true;              // the block
        if (i >= 4) return k == 1 && j >= 1 && j <= 3;  // the fin
        return k == 1 && j == 2;                        // the finger
    });
    VolumeFromSurfaceReport report;
    const TetMesh mesh = mesh_volume_from_surface(soup, uniform(0.1, false), &report);
    require_valid(mesh);
    const QualityReport quality = compute_quality_report(mesh, report.field.get());
    MESSAGE("fin and finger: min Qe " << quality.min_qe << ", " << quality.below_floor
                                      << " below 0.3, " << quality.tets << " tets");
    CHECK(quality.min_qe > 0.3);
    // the field is h away from the thin parts, finer on them
    CHECK(report.field->size(Vec3(0.5, 0.5, 0.5)) == doctest::Approx(0.1));
    CHECK(report.field->size(Vec3(1.45, 0.5, 0.5)) < 0.05);
    CHECK(report.field->size(Vec3(-0.45, 0.5, 0.5)) < 0.05);
}

TEST_CASE("thin parts: a flat ellipsoid 0.16 thick at h = 0.1 keeps its tets above Qe 0.33")
{
    // Without the thickness bound the rim's tets reach 0.313 (0.366 with it).
    Spheres input = Spheres().add(Vec3::Zero(), 1.0, 4);
    for (auto& p : input.soup.points) p[2] *= 0.08;
    VolumeFromSurfaceReport report;
    const TetMesh mesh = mesh_volume_from_surface(input.soup, uniform(0.1, false), &report);
    require_valid(mesh);
    const QualityReport quality = compute_quality_report(mesh, report.field.get());
    MESSAGE("flat ellipsoid: min Qe " << quality.min_qe << ", " << quality.tets << " tets");
    CHECK(quality.min_qe > 0.33);
    CHECK(report.field->size(Vec3(0.0, 0.0, 0.0)) == doctest::Approx(0.1));
    CHECK(report.field->size(Vec3(0.9, 0.0, 0.0)) < 0.06);  // the rim, 0.07 thick
}

TEST_CASE("a capsule thinner than the size (radius h/2) is filled, no tet under the floor")
{
    // its boundary faces lean over the few tets across it: only boundary slides lift the
    // worst of them (0.226 without) above 0.3
    constexpr double pi = 3.14159265358979323846, radius = 0.1, half = 5.0;
    constexpr int around = 16, cap = 6, along = 40;
    std::vector<std::array<double, 2>> profile = {{-half - radius, 0}};  // (z, r), poles r = 0
    for (int i = 1; i < cap; ++i)
        profile.push_back(
            {-half - radius * std::cos(pi / 2 * i / cap), radius * std::sin(pi / 2 * i / cap)});
    for (int i = 0; i <= along; ++i) profile.push_back({-half + 2 * half * i / along, radius});
    for (int i = cap - 1; i > 0; --i)
        profile.push_back(
            {half + radius * std::cos(pi / 2 * i / cap), radius * std::sin(pi / 2 * i / cap)});
    profile.push_back({half + radius, 0});
    surface::TriangleSoup soup;
    std::vector<std::vector<int>> rows;
    for (const auto& [z, r] : profile)
    {
        rows.emplace_back();
        for (int j = 0; j < (r > 0 ? around : 1); ++j)
        {
            rows.back().push_back(static_cast<int>(soup.points.size()));
            soup.points.emplace_back(r * std::cos(2 * pi * j / around),
                                     r * std::sin(2 * pi * j / around), z);
        }
    }
    for (std::size_t i = 0; i + 1 < rows.size(); ++i)
        for (int j = 0; j < around; ++j)
        {
            const auto& a = rows[i];
            const auto& b = rows[i + 1];
            const int j1 = (j + 1) % around;
            if (a.size() == 1)
                soup.triangles.push_back({a[0], b[j1], b[j]});
            else if (b.size() == 1)
                soup.triangles.push_back({a[j], a[j1], b[0]});
            else
            {
                soup.triangles.push_back({a[j], a[j1], b[j1]});
                soup.triangles.push_back({a[j], b[j1], b[j]});
            }
        }
    soup.refs.assign(soup.triangles.size(), 1);
    VolumeFromSurfaceReport report;
    const TetMesh mesh = mesh_volume_from_surface(soup, uniform(2 * radius, false), &report);
    require_valid(mesh);
    const QualityReport quality = compute_quality_report(mesh, report.field.get());
    MESSAGE("capsule: min Qe " << quality.min_qe << ", " << quality.below_floor << " below 0.3 ("
                               << quality.forced_below_floor << " forced), " << quality.tets
                               << " tets");
    CHECK(quality.below_floor == quality.forced_below_floor);
}
