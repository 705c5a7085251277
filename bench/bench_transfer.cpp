// Solution transfer (volume/mesh/field_transfer.h): its accuracy and its speed. A linear field
// carried from a jittered Kuhn box onto a finer one (max error: round-off), a smooth field
// (sin 2x cos 3y + z^2) carried from boxes of n = 4, 8, 16 cubes a side onto the same fine box
// (the error falls about 4x per halving: O(h^2)), and the time per target vertex.
//
//   bench_transfer [n_target]    target: n^3 cubes of 6 tets (default 40)
//
// Times are thread CPU seconds (one thread; the machine may be shared).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "common/stage_timer.h"
#include "fixtures.h"
#include "volume/mesh/field_transfer.h"

using namespace hdimesh;
using namespace hdimesh::volume;

namespace
{

double linear(const Vec3& p) { return 0.7 + 1.3 * p.x() - 2.1 * p.y() + 0.4 * p.z(); }
double smooth(const Vec3& p) { return std::sin(2 * p.x()) * std::cos(3 * p.y()) + p.z() * p.z(); }

struct Errors
{
    double max = 0, rms = 0, seconds = 0;
};

Errors carry(const TetMesh& source, const TetMesh& target, double (*f)(const Vec3&))
{
    VertexField field;
    for (const Vec3& p : source.points) field.values.push_back(f(p));
    const double start = thread_cpu_seconds();
    const TransferReport report = transfer_fields(TransferSource(source), {field}, target);
    Errors e;
    e.seconds = thread_cpu_seconds() - start;
    for (int v = 0; v < target.num_vertices(); ++v)
    {
        const double d = report.fields[0].values[v] - f(target.points[v]);
        e.max = std::max(e.max, std::abs(d));
        e.rms += d * d;
    }
    e.rms = std::sqrt(e.rms / target.num_vertices());
    return e;
}

}  // namespace

int main(int argc, char** argv)
{
    const int n_target = argc > 1 ? std::atoi(argv[1]) : 40;
    const TetMesh target = fixtures::box_mesh(n_target, 0.2, 11);
    std::printf("target: box of %d^3 cubes, %d vertices, %d tets\n\n", n_target,
                target.num_vertices(), target.num_live_tets());
    const Errors exact = carry(fixtures::box_mesh(5, 0.2, 3), target, linear);
    std::printf("linear field from n = 5: max error %.3g\n\n", exact.max);
    std::printf("%-6s %-10s %-12s %-12s %-8s %-10s %s\n", "n", "h", "max error", "rms error",
                "ratio", "cpu s", "us/vertex");
    double previous = 0;
    for (int n : {4, 8, 16})
    {
        const Errors e = carry(fixtures::box_mesh(n, 0.2, 3), target, smooth);
        std::printf("%-6d %-10.4f %-12.4g %-12.4g %-8s %-10.3f %.2f\n", n, 1.0 / n, e.max, e.rms,
                    previous > 0 ? std::to_string(previous / e.rms).substr(0, 5).c_str() : "-",
                    e.seconds, 1e6 * e.seconds / target.num_vertices());
        previous = e.rms;
    }
    return 0;
}
