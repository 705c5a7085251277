// bench_refine: refinement alone (volume/refine/refine.h refine(), no projection, no optimization)
// on the paper's five benchmark cases A-E from data/sphere480.mesh, single-threaded.
//
//   bench_refine [--check] [CASES]     e.g. bench_refine ABCDE (default), bench_refine --check E
//
// Prints one row per case: output tets and vertices, passes, wall and CPU time (the machine may
// be shared: CPU time is the fair figure), output tets per second of each, the
// share of edges too short (Qt < 0.66, L < hth) and too long, the process's peak resident memory
// during refinement per output tet (VmHWM, reset before each case through /proc/self/clear_refs),
// and the same net of the resident memory before the case. Target (issue 3): >= 2 M tets/s and
// <= 100 bytes/tet on case E. --check also runs the mesh checker and the volume comparison.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "volume/check/check.h"
#include "volume/io/tet_io.h"
#include "volume/mesh/tet_tables.h"
#include "volume/refine/refine.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

/// A field of /proc/self/status in kB (VmHWM, VmRSS), or -1.
long status_kb(const std::string& key)
{
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.compare(0, key.size(), key) == 0 && line.size() > key.size() &&
            line[key.size()] == ':')
            return std::stol(line.substr(key.size() + 1));
    return -1;
}

/// Resets VmHWM to the current RSS (Linux >= 4.0); false if not possible.
bool reset_peak()
{
    std::ofstream out("/proc/self/clear_refs");
    out << "5";
    return static_cast<bool>(out);
}

struct EdgeShares
{
    double too_short = 0, too_long = 0;
};

EdgeShares edge_shares(const TetMesh& mesh, const SizeField& field)
{
    std::vector<std::uint64_t> keys;
    keys.reserve(static_cast<std::size_t>(mesh.num_tet_slots()) * 6);
    for (const auto& t : mesh.tets)
        for (const auto& ev : tet::kEdgeVertices)
        {
            const std::uint64_t a = std::min(t[ev[0]], t[ev[1]]), b = std::max(t[ev[0]], t[ev[1]]);
            keys.push_back(a << 32 | b);
        }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    long short_edges = 0, long_edges = 0;
    for (std::uint64_t k : keys)
    {
        const Vec3& a = mesh.points[k >> 32];
        const Vec3& b = mesh.points[k & 0xffffffffu];
        const double length = (b - a).norm(), target = edge_target_size(field, a, b);
        short_edges += is_too_short(length, target);
        long_edges += is_too_long(length, target);
    }
    return {100.0 * short_edges / keys.size(), 100.0 * long_edges / keys.size()};
}

}  // namespace

int main(int argc, char** argv)
{
    std::string cases = "ABCDE";
    bool check = false;
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "--check")
            check = true;
        else
            cases = arg;
    }
    const std::string path = std::string(HDIMESH_DATA_DIR) + "/sphere480.mesh";
    const TetMesh input = read_mesh(path);
    const double input_volume = input.total_volume();
    std::printf("bench_refine: %s (%d tets, %d vertices, volume %.6f), refine() alone, 1 thread\n",
                path.c_str(), input.num_tet_slots(), input.num_vertices(), input_volume);
    std::printf("%-4s %9s %9s %6s %8s %8s %9s %9s %8s %7s %9s %8s%s\n", "case", "tets", "vertices",
                "passes", "wall[s]", "cpu[s]", "tets/s", "tets/cpus", "short[%]", "long[%]",
                "peakB/tet", "netB/tet", check ? "  check" : "");
    for (char name : cases)
    {
        const BenchmarkSize field(benchmark_case(name));
        TetMesh mesh = input;
        const bool peak_reset = reset_peak();
        const long rss_before = status_kb("VmRSS");
        const auto start = std::chrono::steady_clock::now();
        const std::clock_t cpu_start = std::clock();
        const RefineResult result = refine(mesh, field);
        const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const long peak = status_kb("VmHWM");
        const double tets = mesh.num_tet_slots();
        const EdgeShares shares = edge_shares(mesh, field);
        std::string verdict;
        if (check)
        {
            const auto violations = check_mesh(mesh);
            const double drift = std::abs(mesh.total_volume() - input_volume) / input_volume;
            char text[96];
            std::snprintf(text, sizeof text, "  %s, volume drift %.1e",
                          violations.empty() ? "clean" : "VIOLATIONS", drift);
            verdict = text;
            if (!violations.empty()) std::printf("%s\n", format_violations(violations).c_str());
        }
        std::printf("%-4c %9d %9d %6zu %8.3f %8.3f %9.0f %9.0f %8.2f %7.3f %9.1f %8.1f%s%s\n", name,
                    mesh.num_tet_slots(), mesh.num_vertices(), result.passes.size(), seconds, cpu,
                    tets / seconds, tets / cpu, shares.too_short, shares.too_long,
                    peak * 1024.0 / tets, (peak - rss_before) * 1024.0 / tets,
                    result.converged ? "" : "  NOT CONVERGED", verdict.c_str());
        if (!peak_reset) std::printf("     (peak not reset: VmHWM covers earlier cases)\n");
        if (name == cases.back())
        {
            std::printf(
                "     passes of case %c: pass, edges split, tets, vertices, steiner, seconds\n",
                name);
            for (const auto& p : result.passes)
                std::printf("     %4d %10d %10d %10d %6d %8.3f\n", p.pass, p.edges_split, p.tets,
                            p.vertices, p.steiner_points, p.seconds);
        }
        std::fflush(stdout);
    }
    return 0;
}
