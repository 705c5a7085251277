#include "coupling/adapt.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include <time.h>
#include <unistd.h>

namespace hdimesh::coupling
{

namespace
{

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

double thread_cpu_seconds()
{
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Wall and CPU time of one stage, added to the report's two fields when it stops.
class StageTimer
{
public:
    StageTimer(double& wall, double& cpu)
        : wall_(wall), cpu_(cpu), wall_start_(Clock::now()), cpu_start_(thread_cpu_seconds())
    {
    }
    ~StageTimer()
    {
        wall_ += seconds_since(wall_start_);
        cpu_ += thread_cpu_seconds() - cpu_start_;
    }
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;

private:
    double& wall_;
    double& cpu_;
    Clock::time_point wall_start_;
    double cpu_start_;
};

double min_quality(const TetMesh& mesh)
{
    double worst = 1.0;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) worst = std::min(worst, mesh.quality(t));
    return worst;
}

/// Spreads the 21 low bits of x to every third bit (Morton code helper).
std::uint64_t spread_bits(std::uint64_t x)
{
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

/// Renumbers the vertices along a Morton (Z-order) curve of their positions and the tets by
/// their smallest vertex, adjacency and every id list included. Why: refinement appends
/// children and midpoints at the end of the arrays, so after a few passes the tets around a
/// vertex lie all over memory; the final optimization walks vertex balls and edge shells
/// millions of times and spends its time in cache misses. Ties keep the old order, so the
/// result is deterministic. \pre the mesh is compact (no dead tets).
void renumber_spatially(TetMesh& mesh)
{
    const int nv = mesh.num_vertices();
    const int nt = mesh.num_tet_slots();
    if (nv == 0 || nt == 0) return;
    Vec3 low = mesh.points[0], high = mesh.points[0];
    for (const Vec3& p : mesh.points)
    {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
    }
    const double extent = std::max((high - low).maxCoeff(), 1e-300);
    const double scale = static_cast<double>((1 << 21) - 1) / extent;
    std::vector<std::pair<std::uint64_t, int>> keyed(nv);
    for (int v = 0; v < nv; ++v)
    {
        const Vec3 cell = (mesh.points[v] - low) * scale;
        const std::uint64_t code = spread_bits(static_cast<std::uint64_t>(cell.x())) |
                                   spread_bits(static_cast<std::uint64_t>(cell.y())) << 1 |
                                   spread_bits(static_cast<std::uint64_t>(cell.z())) << 2;
        keyed[v] = {code, v};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<int> old2new_verts(nv);
    for (int k = 0; k < nv; ++k) old2new_verts[keyed[k].second] = k;

    auto permute_vertices = [&](auto& values) {
        auto copy = values;
        for (int v = 0; v < nv; ++v) values[old2new_verts[v]] = copy[v];
    };
    permute_vertices(mesh.points);
    permute_vertices(mesh.vertex_refs);
    permute_vertices(mesh.vertex_classes);
    for (auto& tv : mesh.tets)
        for (int& v : tv) v = old2new_verts[v];
    for (auto& tri : mesh.triangles)
        for (int& v : tri) v = old2new_verts[v];
    for (auto& e : mesh.edges)
        for (int& v : e) v = old2new_verts[v];
    for (int& v : mesh.corners) v = old2new_verts[v];
    for (int& v : mesh.required_vertices) v = old2new_verts[v];

    // tets by smallest (new) vertex id, a counting sort: stable, linear
    std::vector<int> start(nv + 1, 0);
    auto smallest = [&](int t) {
        const auto& tv = mesh.tets[t];
        return std::min(std::min(tv[0], tv[1]), std::min(tv[2], tv[3]));
    };
    for (int t = 0; t < nt; ++t) ++start[smallest(t) + 1];
    for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<int> old2new_tets(nt);
    for (int t = 0; t < nt; ++t) old2new_tets[t] = start[smallest(t)]++;

    auto permute_tets = [&](auto& values) {
        auto copy = values;
        for (int t = 0; t < nt; ++t) values[old2new_tets[t]] = copy[t];
    };
    permute_tets(mesh.tets);
    permute_tets(mesh.tet_refs);
    if (mesh.has_adjacency())
    {
        permute_tets(mesh.neighbors);
        for (auto& row : mesh.neighbors)
            for (int& n : row)
                if (n != kNoTet) n = old2new_tets[n];
    }
    for (int& t : mesh.required_tets) t = old2new_tets[t];
}

std::string format_pass_row(const AdaptPassReport& p)
{
    char row[160];
    std::snprintf(row, sizeof row, "%5d %10d %10d %10d %9d %9d %8.4f %8.3f\n", p.pass,
                  p.edges_split, p.tets, p.vertices, p.projected, p.shortened, p.min_quality,
                  p.seconds);
    return row;
}

const char* kPassHeader =
    " pass     split       tets   vertices projected shortened   min Qe     time\n";

}  // namespace

AdaptReport adapt(TetMesh& mesh, const SizeField& field, const AdaptOptions& options)
{
    AdaptReport report;
    const auto start = Clock::now();
    const double cpu_start = thread_cpu_seconds();
    if (!mesh.has_adjacency()) mesh.build_adjacency();

    std::unique_ptr<BoundaryProjector> projector;
    if (options.project)
    {
        const StageTimer timer(report.seconds_project, report.cpu_seconds_project);
        projector = std::make_unique<BoundaryProjector>(mesh, options.projection);
    }
    if (options.verbosity >= 2) std::cout << kPassHeader;

    // refinement passes, each followed by projection and local repair
    report.converged = !options.refine;
    for (int pass = 1; options.refine && pass <= options.max_passes; ++pass)
    {
        AdaptPassReport row;
        row.pass = pass;
        const auto pass_start = Clock::now();

        RefinePassResult refined;
        {
            const StageTimer timer(report.seconds_refine, report.cpu_seconds_refine);
            refined = refine_pass(mesh, field);
        }
        row.edges_split = refined.report.edges_split;
        if (row.edges_split == 0)
        {
            report.converged = true;
            break;
        }

        if (projector)
        {
            const StageTimer timer(report.seconds_project, report.cpu_seconds_project);
            const ProjectionReport moved = projector->project(mesh, refined.new_boundary_vertices);
            row.projected = moved.projected;
            row.shortened = moved.shortened;
        }
        if (options.optimize)
        {
            const StageTimer timer(report.seconds_optimize, report.cpu_seconds_optimize);
            row.min_quality = improve_bad_elements(mesh, field, options.optimizer).min_quality_after;
        }
        else
        {
            row.min_quality = min_quality(mesh);
        }

        row.tets = mesh.num_live_tets();
        row.vertices = mesh.num_vertices();
        row.seconds = seconds_since(pass_start);
        report.passes.push_back(row);
        if (options.verbosity >= 2) std::cout << format_pass_row(row) << std::flush;
        if (options.verbosity >= 1 && isatty(STDERR_FILENO))
            std::fprintf(stderr, "\radapt: pass %d, %d tets", pass, row.tets);
    }

    if (options.verbosity >= 1 && isatty(STDERR_FILENO) && !report.passes.empty())
        std::fprintf(stderr, "\radapt: final optimization...\n");

    // the final optimization, then the moves the guard had shortened
    if (options.optimize)
    {
        const StageTimer timer(report.seconds_optimize, report.cpu_seconds_optimize);
        if (mesh.num_live_tets() == mesh.num_tet_slots()) renumber_spatially(mesh);
        optimize_mesh(mesh, field, options.optimizer);
    }
    if (projector)
    {
        {
            const StageTimer timer(report.seconds_project, report.cpu_seconds_project);
            report.final_projection = projector->project_all(mesh);
        }
        if (options.optimize && report.final_projection.shortened + report.final_projection.projected > 0)
        {
            const StageTimer timer(report.seconds_optimize, report.cpu_seconds_optimize);
            improve_bad_elements(mesh, field, options.optimizer);
        }
    }
    if (!mesh.has_adjacency()) mesh.build_adjacency();
    report.seconds_total = seconds_since(start);
    report.cpu_seconds_total = thread_cpu_seconds() - cpu_start;
    return report;
}

std::string format_adapt_report(const AdaptReport& report, bool with_passes)
{
    std::ostringstream out;
    if (with_passes)
    {
        out << kPassHeader;
        for (const auto& p : report.passes) out << format_pass_row(p);
    }
    char line[256];
    const double rest = report.seconds_total - report.seconds_refine - report.seconds_project -
                        report.seconds_optimize;
    std::snprintf(line, sizeof line,
                  "time: total %.3f s = refine %.3f + project %.3f + optimize %.3f + other %.3f\n",
                  report.seconds_total, report.seconds_refine, report.seconds_project,
                  report.seconds_optimize, rest);
    out << line;
    std::snprintf(line, sizeof line,
                  "cpu:  total %.3f s = refine %.3f + project %.3f + optimize %.3f + other %.3f\n",
                  report.cpu_seconds_total, report.cpu_seconds_refine, report.cpu_seconds_project,
                  report.cpu_seconds_optimize,
                  report.cpu_seconds_total - report.cpu_seconds_refine -
                      report.cpu_seconds_project - report.cpu_seconds_optimize);
    out << line;
    out << (report.converged ? "sizes: no edge too long\n"
                             : "sizes: refinement stopped at the pass cap with edges too long\n");
    return out.str();
}

}  // namespace hdimesh::coupling
