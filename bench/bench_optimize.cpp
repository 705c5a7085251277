// The paper's Table 3 for our refinement + optimization on data/sphere480.mesh (boundary kept
// as the input polyhedron): per case the tets, the time split (refinement, bad-element
// removal after each pass, final optimization), min Qe, % Qe >= 0.5, % Qt >= 0.66, % too long,
// the checker's verdict and a hash of the output (determinism). Times are wall clock per
// phase (s) and the process CPU time of the whole case, reading the input included; the
// speed column uses the CPU time, since the machine may be shared.
//
// usage: bench_optimize [cases, default ABC] [-v] [-o dir]   e.g. bench_optimize ABCDE -o /tmp
// (-o writes each output as dir/optimized_<case>.mesh, for meshstat.py --case <case>)

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>

#include "volume/check/check.h"
#include "volume/check/quality_report.h"
#include "volume/io/tet_io.h"
#include "volume/optimize/optimize.h"
#include "volume/refine/refine.h"
#include "volume/size/size_fields.h"

using namespace hdimesh;

namespace
{

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// FNV-1a over the coordinates and the tets: equal hashes for bitwise equal meshes.
std::uint64_t mesh_hash(const TetMesh& mesh)
{
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* data, std::size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
    };
    for (const auto& p : mesh.points) mix(p.data(), 3 * sizeof(double));
    for (const auto& t : mesh.tets) mix(t.data(), sizeof(t));
    return h;
}

struct CaseResult
{
    int tets = 0;
    double refine_seconds = 0, improve_seconds = 0, optimize_seconds = 0;
    QualityReport quality;
    std::size_t violations = 0;
    std::uint64_t hash = 0;
    int passes = 0;
    double cpu_seconds = 0;  // process CPU time of the whole case (the machine may be shared)
};

CaseResult run_case(char name, int verbosity, const std::string& output_dir)
{
    CaseResult result;
    const std::clock_t cpu_start = std::clock();
    TetMesh mesh = read_mesh(std::string(HDIMESH_DATA_DIR) + "/sphere480.mesh");
    const BenchmarkSize field(benchmark_case(name));
    OptimizeOptions options;
    options.verbosity = verbosity;
    for (int pass = 0; pass < 40; ++pass)
    {
        auto start = Clock::now();
        const RefinePassResult refined = refine_pass(mesh, field);
        result.refine_seconds += seconds_since(start);
        if (refined.report.edges_split == 0) break;
        ++result.passes;
        start = Clock::now();
        improve_bad_elements(mesh, field, options);
        result.improve_seconds += seconds_since(start);
    }
    const auto start = Clock::now();
    optimize_mesh(mesh, field, options);
    result.optimize_seconds = seconds_since(start);
    result.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    result.tets = mesh.num_live_tets();
    result.quality = compute_quality_report(mesh, &field);
    result.violations = check_mesh(mesh).size();
    result.hash = mesh_hash(mesh);
    if (!output_dir.empty())
        write_mesh(mesh, output_dir + "/optimized_" + std::string(1, name) + ".mesh");
    return result;
}

}  // namespace

int main(int argc, char** argv)
{
    std::string cases = "ABC";
    int verbosity = 0;
    std::string output_dir;
    for (int i = 1; i < argc; ++i)
    {
        if (std::strcmp(argv[i], "-v") == 0)
            verbosity = 2;
        else if (std::strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            output_dir = argv[++i];
        else
            cases = argv[i];
    }
    std::printf("%-4s %9s %6s %8s %8s %8s %8s %8s %10s %7s %9s %8s %8s %6s %16s\n", "case", "tets",
                "passes", "refine", "improve", "optim", "wall", "cpu", "tets/cpu-s", "min Qe",
                "%Qe>=0.5", "%Qt>=.66", "%long", "check", "hash");
    for (char name : cases)
    {
        const CaseResult r = run_case(name, verbosity, output_dir);
        const double total = r.refine_seconds + r.improve_seconds + r.optimize_seconds;
        std::printf(
            "%-4c %9d %6d %8.2f %8.2f %8.2f %8.2f %8.2f %10.0f %7.4f %8.2f%% %7.2f%% %7.3f%% %6s "
            "%016llx\n",
            name, r.tets, r.passes, r.refine_seconds, r.improve_seconds, r.optimize_seconds, total,
            r.cpu_seconds, r.tets / r.cpu_seconds, r.quality.min_qe, r.quality.percent_qe_ge_05,
            r.quality.percent_qt_ge_066, r.quality.percent_too_long,
            r.violations == 0 ? "clean" : "FAIL", static_cast<unsigned long long>(r.hash));
        std::fflush(stdout);
    }
    return 0;
}
