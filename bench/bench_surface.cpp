// Surface remeshing benchmark: every surface model in data/ remeshed at the uniform size
// h = 1 % of its bounding-box diagonal (the targets of issue 6). Prints one row per model:
// time, size, min angle, % triangles with all angles ≥ 25°, % Qe ≥ 0.7, % edges Qt ≥ 0.66 (against
// h), two-sided Hausdorff distance to the input relative to the diagonal (own measurement: exact
// point-triangle distances from vertices, edge midpoints and centroids, as surfstat.py samples),
// and the topology check (Euler characteristic, boundary loops) against the input.
//
//   bench_surface [model.obj ...]     (default: the five models of issue 6 in data/)

#include <chrono>
#include <ctime>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "surface/remesh.h"
#include "surface/surface_io.h"
#include "surface/surface_quality.h"

using namespace hdimesh::surface;

namespace
{

struct Topology
{
    long euler = 0;
    int loops = 0;
};

Topology topology(const SurfaceMesh& mesh)
{
    Topology t;
    t.euler = static_cast<long>(mesh.n_vertices()) - static_cast<long>(mesh.n_edges()) + static_cast<long>(mesh.n_faces());
    std::set<int> seen;
    for (auto h : mesh.halfedges())
    {
        if (!mesh.is_boundary(h) || seen.count(h.idx())) continue;
        ++t.loops;
        auto g = h;
        do
        {
            seen.insert(g.idx());
            g = mesh.next_halfedge_handle(g);
        } while (g != h);
    }
    return t;
}

}  // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> models;
    for (int i = 1; i < argc; ++i) models.push_back(argv[i]);
    if (models.empty())
        for (const char* name : {"fandisk", "rocker-arm", "spot", "cheburashka", "stanford-bunny"})
            models.push_back(std::string(HDIMESH_DATA_DIR) + "/" + name + ".obj");

    std::printf("%-16s %7s %7s %8s %8s %8s %8s %8s %8s %10s %10s %6s\n", "model", "in tri", "out tri", "wall s", "cpu s",
                "min ang", "%ang>=25", "%Qe>=.7", "%Qt>=.66", "Hausd/diag", "ridges/cor", "topo");
    for (const std::string& path : models)
    {
        try
        {
            const SurfaceMesh input = read_surface(path);
            SurfaceMesh mesh = input;
            const double diagonal = bounding_box_diagonal(input);
            SurfaceRemeshSettings settings;
            settings.sizing.hsiz = 0.01 * diagonal;
            const auto start = std::chrono::steady_clock::now();
            const std::clock_t cpu_start = std::clock();
            const SurfaceRemeshResult result = remesh_surface(mesh, settings);
            const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const QualityReport q = measure_quality(mesh, settings.sizing.hsiz);
            const auto d = hausdorff_distance(mesh, input);
            const Topology before = topology(input), after = topology(mesh);
            const bool topology_kept = before.euler == after.euler && before.loops == after.loops;
            std::string name = path.substr(path.find_last_of('/') + 1);
            name = name.substr(0, name.find_last_of('.'));
            char features[32];
            std::snprintf(features, sizeof features, "%zu/%zu", result.features.ridge_edges, result.features.corners);
            std::printf("%-16s %7zu %7zu %8.2f %8.2f %8.2f %8.3f %8.2f %8.2f %10.3e %10s %6s\n", name.c_str(), input.n_faces(),
                        mesh.n_faces(), seconds, cpu, q.min_angle_deg, q.percent_all_angles_ge_25, q.percent_qe_ge_07,
                        q.percent_qt_ge_066, std::max(d[0], d[1]) / diagonal, features, topology_kept ? "kept" : "LOST");
        }
        catch (const std::exception& e)
        {
            std::printf("%-16s error: %s\n", path.c_str(), e.what());
        }
    }

    // The curvature-adaptive default of surfremesh (no size given): hausd = 0.002·diag, hmax = twice
    // the input's mean edge length. It must be valid, smaller than the uniform mesh, within hausd.
    std::printf("\nadaptive default (hausd = 0.002 diag, hmax = 2 x mean input edge)\n");
    std::printf("%-16s %7s %7s %8s %8s %8s %10s %10s %6s\n", "model", "in tri", "out tri", "wall s", "min ang",
                "%Qe>=.7", "Hausd/diag", "hausd/diag", "topo");
    for (const std::string& path : models)
    {
        try
        {
            const SurfaceMesh input = read_surface(path);
            SurfaceMesh mesh = input;
            const double diagonal = bounding_box_diagonal(input);
            SurfaceRemeshSettings settings;
            settings.sizing.hmax = 2.0 * mean_edge_length(input);
            const auto start = std::chrono::steady_clock::now();
            remesh_surface(mesh, settings);
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const QualityReport q = measure_quality(mesh, 0.0);
            const auto d = hausdorff_distance(mesh, input);
            const Topology before = topology(input), after = topology(mesh);
            std::string name = path.substr(path.find_last_of('/') + 1);
            name = name.substr(0, name.find_last_of('.'));
            std::printf("%-16s %7zu %7zu %8.2f %8.2f %8.2f %10.3e %10.3e %6s\n", name.c_str(), input.n_faces(), mesh.n_faces(),
                        seconds, q.min_angle_deg, q.percent_qe_ge_07, std::max(d[0], d[1]) / diagonal, 0.002,
                        before.euler == after.euler && before.loops == after.loops ? "kept" : "LOST");
        }
        catch (const std::exception& e)
        {
            std::printf("%-16s error: %s\n", path.c_str(), e.what());
        }
    }
    return 0;
}
