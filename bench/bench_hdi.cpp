// HDI model benchmark: projections per second (single thread) for smooth points on
// stanford-bunny (35k nodes) and on the unit sphere of data/sphere480.mesh (156 nodes), the
// accuracy reached there, and the convergence table on icospheres (observed order of the max
// projection error). Run from a Release build: bench_hdi [repeats]

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "fixtures.h"
#include "hdi/features.h"
#include "hdi/hdi_surface.h"
#include "hdi/obj_reader.h"

using namespace hdimesh::hdi;
using hdimesh::fixtures::icosphere;
using hdimesh::fixtures::mean_edge_length;
using Clock = std::chrono::steady_clock;

namespace
{

double seconds_since(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The Vertices and Triangles of a Medit .mesh file (ASCII), triangles turned outward from the
/// origin (the file's boundary orientation is not needed for a star-shaped sphere).
TriangleSurface read_medit_boundary(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
    {
        std::fprintf(stderr, "cannot open %s\n", path.c_str());
        std::exit(1);
    }
    TriangleSurface s;
    std::string word;
    while (in >> word)
    {
        if (word == "Vertices")
        {
            int count = 0;
            in >> count;
            for (int i = 0; i < count; ++i)
            {
                Vec3 p;
                int ref = 0;
                in >> p.x() >> p.y() >> p.z() >> ref;
                s.points.push_back(p);
            }
        }
        else if (word == "Triangles")
        {
            int count = 0;
            in >> count;
            for (int i = 0; i < count; ++i)
            {
                int a = 0, b = 0, c = 0, ref = 0;
                in >> a >> b >> c >> ref;
                s.triangles.push_back({a - 1, b - 1, c - 1});
            }
        }
    }
    for (Triangle3& t : s.triangles)
    {
        const Vec3& a = s.points[static_cast<std::size_t>(t[0])];
        const Vec3 n = (s.points[static_cast<std::size_t>(t[1])] - a)
                           .cross(s.points[static_cast<std::size_t>(t[2])] - a);
        if (n.dot(a) < 0) std::swap(t[1], t[2]);
    }
    return s;
}

/// Smooth query points as adapt and the remesher make them: random points of random input
/// triangles (edge midpoints are among them), lifted off the facet by up to +-10 % of h.
std::vector<Vec3> query_points(const TriangleSurface& s, int count, std::uint32_t seed)
{
    const double h = mean_edge_length(s);
    std::mt19937 random(seed);
    std::uniform_int_distribution<std::size_t> pick(0, s.triangles.size() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Vec3> queries;
    queries.reserve(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k)
    {
        const Triangle3& t = s.triangles[pick(random)];
        const Vec3& a = s.points[static_cast<std::size_t>(t[0])];
        const Vec3& b = s.points[static_cast<std::size_t>(t[1])];
        const Vec3& c = s.points[static_cast<std::size_t>(t[2])];
        double u = unit(random), v = unit(random);
        if (u + v > 1) u = 1 - u, v = 1 - v;
        queries.push_back((1 - u - v) * a + u * b + v * c +
                          (unit(random) - 0.5) * 0.2 * h * triangle_normal(a, b, c));
    }
    return queries;
}

struct Timing
{
    double per_second = 0;      // wall clock
    double per_cpu_second = 0;  // process CPU time: the figure that holds on a shared machine
    int statuses[4] = {0, 0, 0, 0};
};

Timing time_projections(const HdiSurface& model, const std::vector<Vec3>& queries, int repeats,
                        std::vector<Projection>* out)
{
    Timing timing;
    double best = 1e300, best_cpu = 1e300;
    Vec3 checksum = Vec3::Zero();
    for (int r = 0; r < repeats; ++r)
    {
        const Clock::time_point start = Clock::now();
        const std::clock_t cpu_start = std::clock();
        for (const Vec3& q : queries) checksum += model.project(q).point;
        best_cpu =
            std::min(best_cpu, static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
        best = std::min(best, seconds_since(start));
    }
    timing.per_second = static_cast<double>(queries.size()) / best;
    timing.per_cpu_second = static_cast<double>(queries.size()) / best_cpu;
    for (const Vec3& q : queries)
    {
        const Projection p = model.project(q);
        ++timing.statuses[static_cast<int>(p.status)];
        if (out) out->push_back(p);
    }
    if (!std::isfinite(checksum.sum())) std::printf("(non-finite checksum)\n");
    return timing;
}

void print_statuses(const Timing& t)
{
    std::printf("  statuses: Ok %d, LinearFallback %d, NotConverged %d, Failed %d\n", t.statuses[0],
                t.statuses[1], t.statuses[2], t.statuses[3]);
}

}  // namespace

int main(int argc, char** argv)
{
    const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
    const HdiOptions options;
    std::printf(
        "HDI projection benchmark (single thread, best of %d; n = %d, interpolating weights)\n\n",
        repeats, options.neighbours);

    // --- stanford-bunny -----------------------------------------------------------------------
    {
        const TriangleSurface bunny =
            read_obj(std::string(HDIMESH_DATA_DIR) + "/stanford-bunny.obj");
        Clock::time_point start = Clock::now();
        const FeatureSet features = detect_features(bunny.points, bunny.triangles);
        const double detect_seconds = seconds_since(start);
        start = Clock::now();
        const HdiSurface model(bunny.points, bunny.triangles, features, options);
        const double build_seconds = seconds_since(start);
        const std::vector<Vec3> queries = query_points(bunny, 200000, 1);
        const Timing t = time_projections(model, queries, repeats, nullptr);
        std::printf(
            "| model          | nodes  | feature detection | model build | projections/s (wall) | "
            "projections/CPU-s |\n");
        std::printf(
            "|----------------|--------|-------------------|-------------|----------------------|--"
            "-----------------|\n");
        std::printf("| stanford-bunny | %6zu | %15.3f s | %9.3f s | %20.0f | %17.0f |\n",
                    bunny.points.size(), detect_seconds, build_seconds, t.per_second,
                    t.per_cpu_second);
        print_statuses(t);
        std::printf("  features kept: %zu ridge edges, %zu boundary edges, %zu corners\n",
                    model.features().ridge_edges.size(), model.features().boundary_edges.size(),
                    model.features().corners.size());
    }

    // --- the sphere of data/sphere480.mesh ----------------------------------------------------
    {
        const TriangleSurface sphere =
            read_medit_boundary(std::string(HDIMESH_DATA_DIR) + "/sphere480.mesh");
        const Clock::time_point start = Clock::now();
        const HdiSurface model(sphere.points, sphere.triangles, FeatureSet{}, options);
        const double build_seconds = seconds_since(start);
        const std::vector<Vec3> queries = query_points(sphere, 200000, 2);
        std::vector<Projection> projected;
        const Timing t = time_projections(model, queries, repeats, &projected);
        double worst = 0;
        for (const Projection& p : projected)
            worst = std::max(worst, std::abs(p.point.norm() - 1.0));
        double worst_midpoint = 0;
        for (const Triangle3& tri : sphere.triangles)
            for (std::size_t i = 0; i < 3; ++i)
            {
                const Vec3 mid = 0.5 * (sphere.points[static_cast<std::size_t>(tri[i])] +
                                        sphere.points[static_cast<std::size_t>(tri[(i + 1) % 3])]);
                worst_midpoint =
                    std::max(worst_midpoint, std::abs(model.project(mid).point.norm() - 1.0));
            }
        std::printf(
            "\n| model            | nodes | model build | projections/s (wall) | projections/CPU-s "
            "| max |r-1| random points | max |r-1| edge midpoints |\n");
        std::printf(
            "|------------------|-------|-------------|----------------------|-------------------|-"
            "-----------------------|------------------------|\n");
        std::printf("| sphere480 (unit) | %5zu | %9.4f s | %20.0f | %17.0f | %22.2e | %22.2e |\n",
                    sphere.points.size(), build_seconds, t.per_second, t.per_cpu_second, worst,
                    worst_midpoint);
        print_statuses(t);
    }

    // --- convergence on icospheres ------------------------------------------------------------
    std::printf(
        "\n| icosphere level | nodes | h (mean edge) | max |r-1| | order | projections/CPU-s |\n");
    std::printf(
        "|-----------------|-------|---------------|-----------|-------|-------------------|\n");
    double previous_error = 0, previous_h = 0;
    for (int level = 1; level <= 5; ++level)
    {
        const TriangleSurface sphere = icosphere(level);
        const HdiSurface model(sphere.points, sphere.triangles, FeatureSet{}, options);
        const double h = mean_edge_length(sphere);
        const std::vector<Vec3> queries =
            query_points(sphere, 50000, 10u + static_cast<std::uint32_t>(level));
        std::vector<Projection> projected;
        const Timing t = time_projections(model, queries, 1, &projected);
        double worst = 0;
        for (const Projection& p : projected)
            worst = std::max(worst, std::abs(p.point.norm() - 1.0));
        char order[32] = "    -";
        if (previous_error > 0)
            std::snprintf(order, sizeof order, "%5.2f",
                          std::log(previous_error / worst) / std::log(previous_h / h));
        std::printf("| %15d | %5zu | %13.4f | %9.2e | %s | %17.0f |\n", level, sphere.points.size(),
                    h, worst, order, t.per_cpu_second);
        previous_error = worst;
        previous_h = h;
    }
    return 0;
}
