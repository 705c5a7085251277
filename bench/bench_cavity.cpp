// The cavity cascade's small stages on the corpus of tests/cavity_corpus.h: per case and per
// stage (vertex fan, kernel fan, exhaustive search, and stages 1-3 together as
// fill_small_cavity runs them) whether it fills, the tets, the Steiner points, the worst Qe,
// cavities per CPU-second (each fill repeated for a while) and the median CPU time of one
// call, and whether the fill is exactly the cavity (tests/cavity_fill_check.h, the mesh
// checker included). Then the two figures the issue targets: fan stages on cavities of up to
// 50 faces, and the exhaustive search's median.
//
// usage: bench_cavity [name filter] [-q]   (-q: shorter timing, rougher figures)

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cavity_corpus.h"
#include "cavity_fill_check.h"
#include "volume/fill/detail/cavity_stages.h"

using namespace hdimesh;
using cavity_corpus::Cavity;
using volume::CavityFill;
using volume::CavityOptions;

namespace
{

double cpu_seconds()
{
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

struct Stage
{
    const char* name;
    bool (*run)(const Cavity&, CavityFill&);
};

bool vertex_fan(const Cavity& c, CavityFill& f)
{
    return volume::detail::fill_by_vertex_fan(c.points, c.faces, f);
}
bool kernel_fan(const Cavity& c, CavityFill& f)
{
    return volume::detail::fill_by_kernel_fan(c.points, c.faces, f);
}
bool exhaustive(const Cavity& c, CavityFill& f)
{
    return volume::detail::fill_exhaustive(c.points, c.faces, CavityOptions{}, f);
}
bool small_cavity(const Cavity& c, CavityFill& f)
{
    return volume::detail::fill_small_cavity(c.points, c.faces, CavityOptions{}, f);
}

struct Timing
{
    double per_second = 0;
    double median_us = 0;
};

/// Calls per CPU-second over batches lasting `seconds` in all, and the median of single calls.
Timing time_stage(const Stage& stage, const Cavity& cavity, double seconds)
{
    Timing timing;
    long calls = 0;
    const double start = cpu_seconds();
    double elapsed = 0;
    for (long batch = 1; elapsed < seconds; batch = std::min(batch * 2, 1L << 16))
    {
        for (long i = 0; i < batch; ++i)
        {
            CavityFill fill;
            stage.run(cavity, fill);
        }
        calls += batch;
        elapsed = cpu_seconds() - start;
    }
    timing.per_second = calls / elapsed;
    const long singles = std::clamp<long>(calls, 5, 201);
    std::vector<double> times;
    for (long i = 0; i < singles; ++i)
    {
        CavityFill fill;
        const double t0 = cpu_seconds();
        stage.run(cavity, fill);
        times.push_back(cpu_seconds() - t0);
    }
    std::nth_element(times.begin(), times.begin() + singles / 2, times.end());
    timing.median_us = 1e6 * times[singles / 2];
    return timing;
}

}  // namespace

int main(int argc, char** argv)
{
    std::string filter;
    double seconds = 0.3;
    for (int i = 1; i < argc; ++i)
    {
        if (std::strcmp(argv[i], "-q") == 0)
            seconds = 0.05;
        else
            filter = argv[i];
    }
    const std::vector<Stage> stages = {{"vertex fan", vertex_fan},
                                       {"kernel fan", kernel_fan},
                                       {"exhaustive", exhaustive},
                                       {"stages 1-3", small_cavity}};
    std::printf("%-28s %5s %5s  %-10s %6s %5s %7s %8s %12s %10s  %s\n", "case", "faces", "pts",
                "stage", "filled", "tets", "steiner", "worst Qe", "cavities/s", "median us",
                "check");
    int defects = 0;
    double fan_calls_time = 0;  // sum over (case, fan stage) of 1 / rate, cases <= 50 faces
    int fan_runs = 0;
    std::vector<double> exhaustive_medians;
    for (const Cavity& cavity : cavity_corpus::all_cavities())
    {
        if (!filter.empty() && cavity.name.find(filter) == std::string::npos) continue;
        std::vector<int> vertices;
        for (const auto& f : cavity.faces) vertices.insert(vertices.end(), f.begin(), f.end());
        std::sort(vertices.begin(), vertices.end());
        vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
        for (const Stage& stage : stages)
        {
            CavityFill fill;
            const bool filled = stage.run(cavity, fill);
            const Timing timing = time_stage(stage, cavity, seconds);
            const std::string defect = filled ? cavity_corpus::fill_defect(cavity, fill) : "";
            defects += !defect.empty();
            std::printf("%-28s %5zu %5zu  %-10s %6s %5zu %7zu %8.4f %12.0f %10.2f  %s\n",
                        cavity.name.c_str(), cavity.faces.size(), vertices.size(), stage.name,
                        filled ? "yes" : "no", fill.tets.size(), fill.new_points.size(),
                        filled ? fill.worst_quality : 0.0, timing.per_second, timing.median_us,
                        !filled          ? "-"
                        : defect.empty() ? "clean"
                                         : defect.c_str());
            const bool fan_stage = &stage == &stages[0] || &stage == &stages[1];
            if (fan_stage && filled && cavity.faces.size() <= 50)
            {
                fan_calls_time += 1.0 / timing.per_second;
                ++fan_runs;
            }
            if (&stage == &stages[2]) exhaustive_medians.push_back(timing.median_us);
        }
    }
    if (fan_runs > 0)
        std::printf(
            "\nfan stages (vertex, kernel) that fill, cavities <= 50 faces: %.0f cavities/s"
            " (%d case-stage pairs, equal weights)\n",
            fan_runs / fan_calls_time, fan_runs);
    if (!exhaustive_medians.empty())
    {
        std::sort(exhaustive_medians.begin(), exhaustive_medians.end());
        std::printf(
            "exhaustive search: median over the cases of the median call %.1f us,"
            " slowest case %.1f us\n",
            exhaustive_medians[exhaustive_medians.size() / 2], exhaustive_medians.back());
    }
    std::printf("fills with a defect (check column): %d\n", defects);
    return defects == 0 ? 0 : 1;
}
