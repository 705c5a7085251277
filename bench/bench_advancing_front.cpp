// The advancing front on whole volumes (issue 15): per input the surface faces, the tets and
// points made, the AF's CPU seconds and tets per CPU-second, the volume optimizer's seconds, the
// quality (min Qe, % Qe >= 0.5, min dihedral, % edges Qt >= 0.66) before and after
// optimize_mesh, the same shape figures after it over the tets with no face on a bad input
// triangle (smallest angle under 10 degrees: such a triangle can force a bad tet; the rule of
// bench/compare_volume_peers.py) and the number of those triangles, and the peak heap bytes per
// tet during the AF (every allocation counted by the operator new below). Then a sweep on
// icospheres at h, h/2, h/4: the CPU time per tet must not grow with the size.
//
// usage: bench_advancing_front [-q] [--no-optimize] [--sweep-only] [--levels N]
//                              [--min-point-distance X]
// (-q: the tables only)

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <new>
#include <string>
#include <vector>

#include "common/stage_timer.h"
#include "coupling/mesh_from_surface.h"
#include "fixtures.h"
#include "hdi/obj_reader.h"
#include "surface/surface_io.h"
#include "volume/check/check.h"
#include "volume/check/quality_report.h"
#include "volume/fill/advancing_front.h"
#include "volume/io/tet_io.h"
#include "volume/optimize/optimize.h"
#include "volume/size/size_fields.h"

// ---- heap accounting for the peak-bytes column (bench only)
namespace
{
std::atomic<long long> g_current_bytes{0};
std::atomic<long long> g_peak_bytes{0};

void* counted_allocate(std::size_t bytes)
{
    void* block = std::malloc(bytes + 16);
    if (!block) throw std::bad_alloc();
    *static_cast<std::size_t*>(block) = bytes;
    const long long now = g_current_bytes += static_cast<long long>(bytes);
    long long peak = g_peak_bytes.load();
    while (now > peak && !g_peak_bytes.compare_exchange_weak(peak, now))
    {
    }
    return static_cast<char*>(block) + 16;
}

void counted_free(void* p)
{
    if (!p) return;
    char* block = static_cast<char*>(p) - 16;
    g_current_bytes -= static_cast<long long>(*reinterpret_cast<std::size_t*>(block));
    std::free(block);
}
}  // namespace

void* operator new(std::size_t bytes) { return counted_allocate(bytes); }
void* operator new[](std::size_t bytes) { return counted_allocate(bytes); }
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }

using namespace hdimesh;

namespace
{

struct Surface
{
    std::string name;
    std::vector<Vec3> points;
    std::vector<Triangle> faces;
    double h = 0;
};

double bbox_diagonal(const std::vector<Vec3>& points)
{
    Vec3 lo = points[0], hi = points[0];
    for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    return (hi - lo).norm();
}

double mean_edge(const std::vector<Vec3>& points, const std::vector<Triangle>& faces)
{
    double sum = 0;
    for (const Triangle& t : faces)
        for (int k = 0; k < 3; ++k) sum += (points[t[k]] - points[t[(k + 1) % 3]]).norm();
    return sum / (3.0 * faces.size());
}

Surface from_triangle_surface(const std::string& name, const hdi::TriangleSurface& s)
{
    Surface out;
    out.name = name;
    out.points = s.points;
    for (const auto& t : s.triangles) out.faces.push_back({t[0], t[1], t[2]});
    return out;
}

Surface icosphere_surface(int levels)
{
    Surface s =
        from_triangle_surface("icosphere L" + std::to_string(levels), fixtures::icosphere(levels));
    s.h = mean_edge(s.points, s.faces);
    return s;
}

/// [-1,1]^3 (each side an n x n grid) with a void: an icosphere of radius 0.5, its faces
/// turned to point into the void (outward from the domain).
Surface box_with_void(int n, int levels)
{
    fixtures::GridSurface box = fixtures::grid_cube(n);
    Surface s;
    s.name = "box + spherical void";
    for (const auto& p : box.points) s.points.push_back(2.0 * p - Vec3(1, 1, 1));
    for (const auto& t : box.triangles) s.faces.push_back({t[0], t[1], t[2]});
    const hdi::TriangleSurface ball = fixtures::icosphere(levels);
    const int offset = static_cast<int>(s.points.size());
    for (const auto& p : ball.points) s.points.push_back(0.5 * p);
    for (const auto& t : ball.triangles)
        s.faces.push_back({offset + t[0], offset + t[2], offset + t[1]});
    s.h = mean_edge(s.points, s.faces);
    return s;
}

struct Quality
{
    double min_qe = 0, percent_qe = 0, min_dihedral = 0, percent_qt = 0;
};

Quality quality_of(const TetMesh& mesh, const SizeField& field)
{
    const QualityReport r = compute_quality_report(mesh, &field);
    return {r.min_qe, r.percent_qe_ge_05, r.min_dihedral_deg, r.percent_qt_ge_066};
}

/// An input triangle with an angle under this (degrees) may force a bad tet on it.
constexpr double kBadTriangleAngle = 10.0;

double smallest_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c)
{
    double smallest = 180;
    const Vec3* corners[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k)
    {
        const Vec3 u = *corners[(k + 1) % 3] - *corners[k];
        const Vec3 w = *corners[(k + 2) % 3] - *corners[k];
        const double cosine = u.dot(w) / std::max(1e-300, u.norm() * w.norm());
        smallest = std::min(smallest, std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI);
    }
    return smallest;
}

/// Shape figures (min Qe, % Qe >= 0.5, min dihedral; percent_qt unset) over the tets with no
/// face on a bad boundary triangle; *bad_triangles gets how many boundary triangles are bad.
Quality quality_without_bad_triangles(const TetMesh& mesh, int* bad_triangles)
{
    std::vector<std::array<int, 3>> bad;
    for (const Triangle& t : mesh.triangles)
        if (smallest_angle_deg(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]) <
            kBadTriangleAngle)
        {
            std::array<int, 3> key = {t[0], t[1], t[2]};
            std::sort(key.begin(), key.end());
            bad.push_back(key);
        }
    std::sort(bad.begin(), bad.end());
    *bad_triangles = static_cast<int>(bad.size());
    Quality q;
    q.min_qe = 1;
    q.min_dihedral = 180;
    long kept = 0, good = 0;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        const TetVertices& tv = mesh.tets[t];
        bool holds_bad = false;
        for (int f = 0; f < 4 && !holds_bad; ++f)
        {
            std::array<int, 3> key = {tv[(f + 1) % 4], tv[(f + 2) % 4], tv[(f + 3) % 4]};
            std::sort(key.begin(), key.end());
            holds_bad = std::binary_search(bad.begin(), bad.end(), key);
        }
        if (holds_bad) continue;
        const double qe = mesh.quality(t);
        q.min_qe = std::min(q.min_qe, qe);
        good += (qe >= 0.5);
        ++kept;
        const auto& p = mesh.points;
        for (double angle : dihedral_angles_deg(p[tv[0]], p[tv[1]], p[tv[2]], p[tv[3]]))
            q.min_dihedral = std::min(q.min_dihedral, angle);
    }
    q.percent_qe = kept > 0 ? 100.0 * static_cast<double>(good) / static_cast<double>(kept) : 100;
    return q;
}

struct Row
{
    std::string name;
    std::size_t faces = 0;
    long tets = 0, points = 0;
    double af_seconds = 0, optimize_seconds = 0;
    Quality before, after;
    Quality clean_after;  // after optimize_mesh, without the tets on bad input triangles
    int bad_triangles = 0;
    double bytes_per_tet = 0;
    int retreats = 0;
    std::size_t violations = 0;
    bool ok = false;
    std::string failure;
};

AdvancingFrontOptions g_options;

Row run(const Surface& s, bool optimize, bool quiet)
{
    Row row;
    row.name = s.name;
    row.faces = s.faces.size();
    const ConstantSize field(s.h);
    std::vector<TetVertices> tets;
    std::vector<Vec3> new_points;
    FrontReport report;
    const long long base_bytes = g_current_bytes.load();
    g_peak_bytes = base_bytes;
    const double cpu_start = thread_cpu_seconds();
    row.ok =
        advance_front(s.points, s.faces, &field, g_options, tets, new_points, row.failure, &report);
    row.af_seconds = thread_cpu_seconds() - cpu_start;
    row.bytes_per_tet = static_cast<double>(g_peak_bytes.load() - base_bytes) /
                        std::max<std::size_t>(1, tets.size());
    row.retreats = report.retreat_rounds;
    if (!row.ok)
    {
        if (!quiet) std::printf("  %s: %s\n", s.name.c_str(), row.failure.c_str());
        return row;
    }
    TetMesh mesh;
    for (const Vec3& p : s.points) mesh.add_vertex(p);
    for (const Vec3& p : new_points) mesh.add_vertex(p);
    for (const TetVertices& t : tets) mesh.add_tet(t, 1);
    for (const Triangle& f : s.faces) mesh.add_triangle(f, 1);
    mesh.compact();  // input points no face uses
    mesh.classify_vertices();
    mesh.build_adjacency();
    row.tets = mesh.num_live_tets();
    row.points = mesh.num_vertices();
    row.violations = check_mesh(mesh).size();
    if (row.violations && !quiet)
        std::printf("  %s: %s\n", s.name.c_str(), format_violations(check_mesh(mesh), 5).c_str());
    row.before = quality_of(mesh, field);
    if (optimize)
    {
        const double start = thread_cpu_seconds();
        optimize_mesh(mesh, field);
        row.optimize_seconds = thread_cpu_seconds() - start;
        row.after = quality_of(mesh, field);
        row.clean_after = quality_without_bad_triangles(mesh, &row.bad_triangles);
        if (!check_mesh(mesh).empty()) row.violations += 1000000;
    }
    return row;
}

void print_header()
{
    std::printf(
        "%-22s %7s %8s %7s %7s %8s %6s | %6s %5s %5s %5s | %6s %5s %5s %5s | %6s %5s %5s %5s | %6s "
        "%3s %s\n",
        "input", "faces", "tets", "points", "AF s", "tets/s", "opt s", "minQe", "%0.5", "dih",
        "%Qt", "minQe", "%0.5", "dih", "%Qt", "minQe", "%0.5", "dih", "bad", "B/tet", "rtr",
        "check");
    std::printf("%-22s %7s %8s %7s %7s %8s %6s | %-23s | %-23s | %-23s |\n", "", "", "", "", "", "",
                "", "   after AF", "   after optimize_mesh", " w/o bad-triangle tets");
}

void print_row(const Row& r)
{
    if (!r.ok)
    {
        std::printf("%-22s %7zu  FAILED: %s\n", r.name.c_str(), r.faces, r.failure.c_str());
        return;
    }
    std::printf(
        "%-22s %7zu %8ld %7ld %7.3f %8.0f %6.2f | %6.3f %5.1f %5.1f %5.1f | %6.3f %5.1f %5.1f "
        "%5.1f | %6.3f %5.1f %5.1f %5d | %6.0f %3d %s\n",
        r.name.c_str(), r.faces, r.tets, r.points, r.af_seconds,
        r.tets / std::max(1e-9, r.af_seconds), r.optimize_seconds, r.before.min_qe,
        r.before.percent_qe, r.before.min_dihedral, r.before.percent_qt, r.after.min_qe,
        r.after.percent_qe, r.after.min_dihedral, r.after.percent_qt, r.clean_after.min_qe,
        r.clean_after.percent_qe, r.clean_after.min_dihedral, r.bad_triangles, r.bytes_per_tet,
        r.retreats, r.violations == 0 ? "clean" : "VIOLATIONS");
    std::fflush(stdout);
}

}  // namespace

/// A real surface at h, h/2, h/4: remeshed (surfremesh's pipeline), then filled by the front;
/// the fill's CPU time per tet must not grow with the size either.
void surface_sweep(const char* name)
{
    const std::string path = std::string(HDIMESH_DATA_DIR) + "/" + name + ".obj";
    const surface::TriangleSoup soup = surface::read_triangle_soup(path);
    std::vector<Vec3> points;
    for (const auto& p : soup.points) points.emplace_back(p[0], p[1], p[2]);
    const double diagonal = bbox_diagonal(points);
    std::printf(
        "\nsweep: %s remeshed at h, h/2, h/4 (h = 2 %% of the bbox diagonal), then the AF\n", name);
    std::printf("%-14s %8s %9s %8s %9s %10s\n", "h", "faces", "tets", "AF s", "tets/s", "us/tet");
    for (double fraction : {0.02, 0.01, 0.005})
    {
        coupling::VolumeFromSurfaceOptions options;
        options.sizing.hsiz = fraction * diagonal;
        options.refine = options.optimize = false;
        options.source = name;
        coupling::VolumeFromSurfaceReport report;
        char label[32];
        std::snprintf(label, sizeof label, "%.5f", options.sizing.hsiz);
        try
        {
            coupling::mesh_volume_from_surface(soup, options, &report);
        }
        catch (const std::exception& e)
        {
            std::printf("%-14s FAILED: %s\n", label, e.what());
            continue;
        }
        const double seconds = report.cpu_seconds_fill;
        std::printf("%-14s %8d %9d %8.3f %9.0f %10.2f\n", label, report.surface_triangles,
                    report.fill_tets, seconds, report.fill_tets / std::max(1e-9, seconds),
                    1e6 * seconds / std::max(1, report.fill_tets));
        std::fflush(stdout);
    }
}

int main(int argc, char** argv)
{
    bool optimize = true, quiet = false, sweep_only = false, surface_sweep_on = true;
    int sweep_levels = 3;
    for (int i = 1; i < argc; ++i)
    {
        if (!std::strcmp(argv[i], "--no-optimize"))
            optimize = false;
        else if (!std::strcmp(argv[i], "-q"))
            quiet = true;
        else if (!std::strcmp(argv[i], "--sweep-only"))
            sweep_only = true;
        else if (!std::strcmp(argv[i], "--no-surface-sweep"))  // the spot sweep takes minutes
            surface_sweep_on = false;
        else if (!std::strcmp(argv[i], "--levels") && i + 1 < argc)
            sweep_levels = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--min-point-distance") && i + 1 < argc)
            g_options.min_point_distance = std::atof(argv[++i]);
    }

    if (!sweep_only)
    {
        std::vector<Surface> inputs;
        {
            const TetMesh sphere = read_mesh(std::string(HDIMESH_DATA_DIR) + "/sphere480.mesh");
            Surface s;
            s.name = "sphere480 boundary";
            s.points = sphere.points;
            s.faces = sphere.triangles;
            s.h = mean_edge(s.points, s.faces);
            inputs.push_back(s);
        }
        inputs.push_back(icosphere_surface(4));
        inputs.push_back(box_with_void(12, 2));
        for (const char* name : {"fandisk", "spot", "rocker-arm", "cheburashka", "stanford-bunny"})
        {
            const std::string path = std::string(HDIMESH_DATA_DIR) + "/" + name + ".obj";
            Surface s = from_triangle_surface(name, hdi::read_obj(path));
            s.h = 0.02 * bbox_diagonal(s.points);
            inputs.push_back(s);
        }
        std::printf(
            "whole volumes (h: sphere480 / icosphere / box: the mean surface edge; OBJs: 2 %% "
            "of the bbox diagonal)\n");
        print_header();
        for (const Surface& s : inputs) print_row(run(s, optimize, quiet));
    }

    std::printf("\nsweep: icospheres at h, h/2, h/4 (h = mean surface edge), AF only\n");
    std::printf("%-14s %8s %9s %8s %9s %10s %7s\n", "input", "faces", "tets", "AF s", "tets/s",
                "us/tet", "B/tet");
    for (int level = 3; level < 3 + sweep_levels; ++level)
    {
        const Row r = run(icosphere_surface(level), false, quiet);
        if (!r.ok)
        {
            std::printf("%-14s FAILED: %s\n", r.name.c_str(), r.failure.c_str());
            continue;
        }
        std::printf("%-14s %8zu %9ld %8.3f %9.0f %10.2f %7.0f\n", r.name.c_str(), r.faces, r.tets,
                    r.af_seconds, r.tets / std::max(1e-9, r.af_seconds),
                    1e6 * r.af_seconds / std::max(1L, r.tets), r.bytes_per_tet);
        std::fflush(stdout);
    }
    if (surface_sweep_on) surface_sweep("spot");
    return 0;
}
