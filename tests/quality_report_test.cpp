// The quality report on meshes whose every number is known by hand: the regular tet, the
// corner tet, the Kuhn-cube box (all tets congruent), and the jittered box for invariants.

#include "volume/check/quality_report.h"

#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>

#include "common/errors.h"
#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/io/tet_io.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

std::string read_text(const std::string& path)
{
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

TEST_CASE("regular tet: Qe 1, dihedral acos(1/3) everywhere")
{
    const TetMesh mesh = fixtures::regular_tet();
    const ConstantSize field(1.1);
    const QualityReport r = compute_quality_report(mesh, &field);
    CHECK(r.vertices == 4);
    CHECK(r.tets == 1);
    CHECK(r.edges == 6);
    CHECK(r.boundary_triangles == 4);
    CHECK(r.declared_triangles == 4);
    CHECK(r.volume == doctest::Approx(1.0 / (6.0 * std::sqrt(2.0))).epsilon(1e-14));
    CHECK(r.enclosed_volume == doctest::Approx(r.volume).epsilon(1e-14));
    CHECK(r.min_qe == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(r.mean_qe == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(r.qe_histogram[9] == 1);
    CHECK(r.percent_qe_ge_05 == 100.0);
    CHECK(r.percent_qe_lt_02 == 0.0);
    CHECK(r.min_dihedral_deg == doctest::Approx(std::acos(1.0 / 3.0) * kDegrees).epsilon(1e-12));
    CHECK(r.max_dihedral_deg == doctest::Approx(std::acos(1.0 / 3.0) * kDegrees).epsilon(1e-12));
    CHECK(r.min_boundary_triangle_qe == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(r.min_edge_length == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(r.max_edge_length == doctest::Approx(1.0).epsilon(1e-14));
    // every edge L = 1 against hth = 1.1: Qt = L/hth = 0.909, in the 0.8-1 bin
    CHECK(r.has_size);
    CHECK(r.min_qt == doctest::Approx(1.0 / 1.1).epsilon(1e-13));
    CHECK(r.mean_qt == doctest::Approx(1.0 / 1.1).epsilon(1e-13));
    CHECK(r.percent_qt_ge_066 == 100.0);
    CHECK(r.percent_too_long == 0.0);
    CHECK(r.percent_too_short == 0.0);
    CHECK(r.length_ratio_histogram[3] == 6);
}

TEST_CASE("corner tet: Qe = sqrt(3) - 1, dihedral 54.7 to 90 degrees")
{
    //   (0,0,1)
    //      |  \          three right angles at the axis edges; the slanted face meets the
    //      |   \         others at acos(1/sqrt 3) = 54.74 degrees
    //   (0,0,0)--(0,1,0)
    //     /
    //  (1,0,0)
    const QualityReport r = compute_quality_report(fixtures::single_tet(), nullptr);
    // rho = 3V / A = 0.5 / (1.5 + sqrt(3)/2), h = sqrt(2): Qe = 2 sqrt(6) rho / h = sqrt(3) - 1
    CHECK(r.min_qe == doctest::Approx(std::sqrt(3.0) - 1.0).epsilon(1e-14));
    CHECK(r.qe_histogram[7] == 1);
    CHECK(r.min_dihedral_deg ==
          doctest::Approx(std::acos(1.0 / std::sqrt(3.0)) * kDegrees).epsilon(1e-12));
    CHECK(r.max_dihedral_deg == doctest::Approx(90.0).epsilon(1e-12));
    CHECK(r.volume == doctest::Approx(1.0 / 6.0).epsilon(1e-14));
    // no field: no size statistics, and the table says so
    CHECK_FALSE(r.has_size);
    CHECK(format_quality_table(r).find("no size field") != std::string::npos);
    // the slanted face is equilateral (Qe 1), the three others right isosceles
    const double right_isosceles =
        2 * std::sqrt(3.0) * (2 * 0.5 / (2 + std::sqrt(2.0))) / std::sqrt(2.0);
    CHECK(r.min_boundary_triangle_qe == doctest::Approx(right_isosceles).epsilon(1e-14));
    CHECK(r.mean_boundary_triangle_qe ==
          doctest::Approx((3 * right_isosceles + 1) / 4).epsilon(1e-14));
}

TEST_CASE("dihedral angles of one tet, by edge")
{
    const auto angles = dihedral_angles_deg({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
    // edges e0 = 01, e1 = 02, e2 = 03 lie on the axes: right angles; e3, e4, e5 on the slanted face
    for (int e = 0; e < 3; ++e) CHECK(angles[e] == doctest::Approx(90.0));
    for (int e = 3; e < 6; ++e)
        CHECK(angles[e] == doctest::Approx(std::acos(1.0 / std::sqrt(3.0)) * kDegrees));
}

TEST_CASE("Kuhn box 2x2x2 against a constant size: every number by hand")
{
    //  48 congruent Kuhn tets (orthoschemes): Qe = 2 - sqrt(2), dihedral 45, 60 and 90 degrees.
    //  Edges of length h = 0.5: 54 axis edges (L/h 1), 36 face diagonals (1.414, Qt 0.707),
    //  8 body diagonals (1.732: too long).
    const TetMesh mesh = fixtures::box_mesh(2);
    const ConstantSize field(0.5);
    const QualityReport r = compute_quality_report(mesh, &field);
    CHECK(r.vertices == 27);
    CHECK(r.tets == 48);
    CHECK(r.boundary_triangles == 48);
    CHECK(r.edges == 98);
    CHECK(r.volume == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(r.enclosed_volume == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(r.min_qe == doctest::Approx(2.0 - std::sqrt(2.0)).epsilon(1e-13));
    CHECK(r.mean_qe == doctest::Approx(2.0 - std::sqrt(2.0)).epsilon(1e-13));
    CHECK(r.qe_histogram[5] == 48);
    CHECK(r.percent_qe_ge_05 == 100.0);
    CHECK(r.min_dihedral_deg == doctest::Approx(45.0).epsilon(1e-12));
    CHECK(r.max_dihedral_deg == doctest::Approx(90.0).epsilon(1e-12));
    CHECK(r.min_edge_length == doctest::Approx(0.5));
    CHECK(r.max_edge_length == doctest::Approx(std::sqrt(3.0) / 2));
    CHECK(r.percent_too_long == doctest::Approx(100.0 * 8 / 98));
    CHECK(r.percent_too_short == 0.0);
    CHECK(r.percent_qt_ge_066 == doctest::Approx(100.0 * 90 / 98));
    CHECK(r.min_qt == doctest::Approx(1.0 / std::sqrt(3.0)));
    CHECK(r.max_length_ratio == doctest::Approx(std::sqrt(3.0)));
    CHECK(r.min_length_ratio == doctest::Approx(1.0));
    CHECK(r.mean_length_ratio ==
          doctest::Approx((54 + 36 * std::sqrt(2.0) + 8 * std::sqrt(3.0)) / 98));
    CHECK(r.length_ratio_histogram == std::array<long, 8>{0, 0, 0, 0, 54, 36, 8, 0});

    // a field twice as large: the axis edges become too short (L/h = 0.5 < 0.66)
    const QualityReport coarse =
        compute_quality_report(mesh, std::make_unique<ConstantSize>(1.0).get());
    CHECK(coarse.percent_too_short == doctest::Approx(100.0 * 54 / 98));
    CHECK(coarse.percent_too_long == 0.0);
    CHECK(coarse.length_ratio_histogram[1] == 54);  // [0.5, 0.66)
}

TEST_CASE("jittered box: histograms account for every tet and edge, volume conserved")
{
    const TetMesh mesh = fixtures::box_mesh(5, 0.2, 21);
    const BenchmarkSize field(benchmark_case('C'));
    const QualityReport r = compute_quality_report(mesh, &field);
    CHECK(std::accumulate(r.qe_histogram.begin(), r.qe_histogram.end(), 0) == r.tets);
    CHECK(std::accumulate(r.length_ratio_histogram.begin(), r.length_ratio_histogram.end(), 0L) ==
          r.edges);
    CHECK(r.volume == doctest::Approx(1.0).epsilon(1e-13));
    CHECK(r.enclosed_volume == doctest::Approx(r.volume).epsilon(1e-13));
    CHECK(r.min_qe > 0.0);
    CHECK(r.min_qe <= r.mean_qe);
    CHECK(r.min_dihedral_deg < r.max_dihedral_deg);
    CHECK(r.min_dihedral_deg > 0.0);
    CHECK(r.max_dihedral_deg < 180.0);
    CHECK(r.percent_qt_ge_066 + r.percent_too_long + r.percent_too_short == doctest::Approx(100.0));
    CHECK(r.min_qt <= r.mean_qt);
    CHECK(r.min_length_ratio <= r.mean_length_ratio);
    CHECK(r.mean_length_ratio <= r.max_length_ratio);
    // dead tets are not counted
    TetMesh killed = mesh;
    killed.kill_tet(0);
    CHECK(compute_quality_report(killed, nullptr).tets == r.tets - 1);
}

TEST_CASE("histogram bins follow numpy's edges k * 0.1")
{
    CHECK(qe_histogram_bin(0.0) == 0);
    CHECK(qe_histogram_bin(-0.3) == 0);
    CHECK(qe_histogram_bin(0.1) == 1);
    CHECK(qe_histogram_bin(0.3) == 2);  // 0.3 < 3 * 0.1 = 0.30000000000000004
    CHECK(qe_histogram_bin(0.7) == 6);  // 0.7 < 7 * 0.1 = 0.7000000000000001
    CHECK(qe_histogram_bin(0.8) == 8);
    CHECK(qe_histogram_bin(0.99) == 9);
    CHECK(qe_histogram_bin(1.0) == 9);
    CHECK(length_ratio_histogram_bin(0.49) == 0);
    CHECK(length_ratio_histogram_bin(0.66) == 2);
    CHECK(length_ratio_histogram_bin(1.0) == 4);
    CHECK(length_ratio_histogram_bin(1.515) == 6);
    CHECK(length_ratio_histogram_bin(7.0) == 7);
}

TEST_CASE("table, JSON and SVG outputs")
{
    const TetMesh mesh = fixtures::box_mesh(2);
    const ConstantSize field(0.5);
    const QualityReport r = compute_quality_report(mesh, &field);

    const std::string table = format_quality_table(r);
    CHECK(table.find("tets") != std::string::npos);
    CHECK(table.find("48") != std::string::npos);
    CHECK(table.find("Qt >= 0.66") != std::string::npos);
    // aligned: every value starts in the same column
    std::istringstream lines(table);
    std::string line;
    std::size_t column = std::string::npos;
    while (std::getline(lines, line))
    {
        const std::size_t gap = line.find("  ");
        REQUIRE(gap != std::string::npos);
        const std::size_t value = line.find_first_not_of(' ', gap);
        if (line.rfind("  (bins)", 0) == 0) continue;
        if (column == std::string::npos) column = value;
        CHECK(value == column);
    }

    const std::string json = quality_report_json(r);
    CHECK(json.find("\"tets\": 48") != std::string::npos);
    CHECK(json.find("\"edges\": 98") != std::string::npos);
    CHECK(json.find("\"length_ratio_histogram\": [0, 0, 0, 0, 54, 36, 8, 0]") != std::string::npos);
    CHECK(json.find("\"has_size\": true") != std::string::npos);
    CHECK(json.find("inf") == std::string::npos);

    const auto directory = std::filesystem::temp_directory_path() /
                           ("quality_report_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(directory);
    const std::string svg_path = (directory / "report.svg").string();
    write_quality_svg(r, svg_path);
    const std::string svg = read_text(svg_path);
    CHECK(svg.find("<svg") != std::string::npos);
    CHECK(svg.find("</svg>") != std::string::npos);
    CHECK(svg.find(">54<") != std::string::npos);  // the count over the L/hth = 1 bar
    const std::string json_path = (directory / "report.json").string();
    write_quality_json(r, json_path);
    CHECK(read_text(json_path) == json);
    // nothing else left beside them (no temporary files)
    CHECK(std::distance(std::filesystem::directory_iterator(directory),
                        std::filesystem::directory_iterator()) == 2);
    CHECK_THROWS_AS(write_quality_svg(r, (directory / "missing" / "x.svg").string()), IoError);
    std::filesystem::remove_all(directory);
}

TEST_CASE("data/sphere480.mesh against the independent checker's numbers (case A)")
{
    // Reference: /usr/bin/python3 ../shared/tools/meshstat.py data/sphere480.mesh --case A --json
    const TetMesh mesh = read_mesh(fixtures::data_path("sphere480.mesh"));
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(violations.empty());
    const BenchmarkSize field(benchmark_case('A'));
    const QualityReport r = compute_quality_report(mesh, &field);
    CHECK(r.vertices == 156);
    CHECK(r.tets == 483);
    CHECK(r.boundary_triangles == 256);
    CHECK(r.declared_triangles == 256);
    CHECK(r.edges == 766);
    CHECK(r.volume == doctest::Approx(4.007149580083689).epsilon(1e-13));
    CHECK(r.enclosed_volume == doctest::Approx(r.volume).epsilon(1e-13));
    CHECK(r.min_qe == doctest::Approx(0.25829160425705155).epsilon(1e-12));
    CHECK(r.mean_qe == doctest::Approx(0.6375618507748647).epsilon(1e-12));
    CHECK(r.percent_qe_ge_05 == doctest::Approx(89.648033126294).epsilon(1e-12));
    CHECK(r.qe_histogram == std::array<int, 10>{0, 0, 6, 21, 23, 110, 180, 110, 29, 4});
    CHECK(r.min_qt == doctest::Approx(0.05320199414494702).epsilon(1e-12));
    CHECK(r.mean_qt == doctest::Approx(0.39412958484228894).epsilon(1e-12));
    CHECK(r.percent_qt_ge_066 == doctest::Approx(12.27154046997389).epsilon(1e-12));
    CHECK(r.percent_too_long == doctest::Approx(87.72845953002611).epsilon(1e-12));
    CHECK(r.percent_too_short == 0.0);
    CHECK(r.max_length_ratio == doctest::Approx(18.79628792250783).epsilon(1e-12));
    CHECK(r.length_ratio_histogram == std::array<long, 8>{0, 0, 0, 2, 14, 78, 141, 531});
}

TEST_CASE("tets below Qe 0.3: a sliver on a sharp ridge is forced, a flat tet inside a box is not")
{
    // a sliver alone: its boundary edges are its own small dihedral angles
    TetMesh sliver;
    for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 0.02)})
        sliver.add_vertex(p, 0, VertexClass::Interior);
    sliver.add_tet({0, 1, 2, 3}, 1);
    const QualityReport s = compute_quality_report(sliver, nullptr);
    CHECK(s.below_floor == 1);
    CHECK(s.forced_below_floor == 1);
    // the 2x2x2 Kuhn box, its centre pushed near the bottom face: flat tets between it and
    // that face, on no sharp ridge or corner (the box's are 90 degrees, pi/2 sr)
    TetMesh box = fixtures::box_mesh(2);
    for (auto& p : box.points)
        if ((p - Vec3(0.5, 0.5, 0.5)).norm() < 1e-12) p = Vec3(0.5, 0.5, 0.03);
    REQUIRE(check_mesh(box).empty());
    const QualityReport b = compute_quality_report(box, nullptr);
    CHECK(b.below_floor > 0);
    CHECK(b.forced_below_floor == 0);
    const std::string table = format_quality_table(b);
    CHECK(table.find("Qe < 0.3") != std::string::npos);
    CHECK(table.find(std::to_string(b.below_floor) +
                     " tets (0 forced by sharp input ridges or corners, or kept triangles)") !=
          std::string::npos);
    CHECK(quality_report_json(b).find("\"forced_below_floor\": 0") != std::string::npos);
}
