// Mesh I/O speed: writes and reads a ~1M-tet mesh in every format and prints a table of
// tets/s and file size, plus the container's bytes per tet with adjacency built.
//
// usage: bench_io [N]   (N^3 jittered Kuhn cubes, 6 tets each; default 56 -> 1,053,696 tets)
// Reading includes the validation every read_mesh does (index ranges, positive volumes) and
// the O(n) adjacency build, since that is what a user waits for.

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/io/tet_io.h"
#include "volume/mesh/tet_mesh.h"

using namespace hdimesh;
namespace fs = std::filesystem;

namespace
{

/// The test fixture's jittered Kuhn box, its tets split into two refs along x so refs are
/// really exercised (box_mesh lists the 6 tets of cube (i, j, k) at 6 * (i + n * (j + n * k))).
TetMesh jittered_box(int n)
{
    TetMesh mesh = fixtures::box_mesh(n, 0.2);
    for (int t = 0; t < mesh.num_tet_slots(); ++t) mesh.tet_refs[t] = 1 + (2 * ((t / 6) % n)) / n;
    return mesh;
}

double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv)
{
    const int n = argc > 1 ? std::atoi(argv[1]) : 56;
    if (n < 1) return std::fprintf(stderr, "usage: bench_io [N >= 1]\n"), 2;
    const fs::path dir =
        fs::temp_directory_path() / ("hdimesh_bench_io_" + std::to_string(::getpid()));
    fs::create_directories(dir);

    const auto build_start = std::chrono::steady_clock::now();
    const TetMesh mesh = jittered_box(n);
    const double build_seconds = seconds_since(build_start);
    const double tets = mesh.num_live_tets();
    std::printf(
        "mesh: %d^3 Kuhn cubes, %d vertices, %.0f tets, %zu boundary triangles (built in %.2f s)\n",
        n, mesh.num_vertices(), tets, mesh.triangles.size(), build_seconds);

    struct Format
    {
        const char* label;
        const char* file;
        WriteOptions options;
        bool readable;
    };
    const Format formats[] = {
        {"Medit ASCII", "box.mesh", {}, true},
        {"Medit binary v2", "box.meshb", {}, true},
        {"Gmsh 2.2 ASCII", "box22.msh", {{}, "2.2", false, {}}, true},
        {"Gmsh 2.2 binary", "box22b.msh", {{}, "2.2", true, {}}, true},
        {"Gmsh 4.1 ASCII", "box41.msh", {{}, "4.1", false, {}}, true},
        {"Gmsh 4.1 binary", "box41b.msh", {{}, "4.1", true, {}}, true},
        {"VTK .vtu (write)", "box.vtu", {}, false},
    };

    std::printf("\n%-18s %14s %14s %12s %10s\n", "format", "write tets/s", "read tets/s", "file MB",
                "bytes/tet");
    std::size_t read_memory = 0;
    for (const Format& f : formats)
    {
        const std::string path = (dir / f.file).string();
        const auto write_start = std::chrono::steady_clock::now();
        write_mesh(mesh, path, f.options);
        const double write_seconds = seconds_since(write_start);
        const double size = static_cast<double>(fs::file_size(path));
        char read_rate[32] = "-";
        if (f.readable)
        {
            const auto read_start = std::chrono::steady_clock::now();
            const TetMesh back = read_mesh(path);
            const double read_seconds = seconds_since(read_start);
            if (back.num_live_tets() != mesh.num_live_tets())
                return std::fprintf(stderr, "%s: read %d tets, wrote %.0f\n", f.file,
                                    back.num_live_tets(), tets),
                       1;
            // after the clock: the read-back mesh passes the checker like every mesh we make
            const auto violations = check_mesh(back);
            if (!violations.empty())
                return std::fprintf(stderr, "%s: read-back mesh fails the checker:\n%s", f.file,
                                    format_violations(violations).c_str()),
                       1;
            std::snprintf(read_rate, sizeof(read_rate), "%.3g", tets / read_seconds);
            read_memory = back.memory_bytes();
        }
        std::printf("%-18s %14.3g %14s %12.1f %10.1f\n", f.label, tets / write_seconds, read_rate,
                    size / 1e6, size / tets);
        fs::remove(path);
    }

    // what every read pays after parsing, for reading the table: the O(n) adjacency build
    TetMesh copy = mesh;
    const auto adjacency_start = std::chrono::steady_clock::now();
    copy.build_adjacency();
    const double adjacency_seconds = seconds_since(adjacency_start);
    std::printf("\nof each read, build_adjacency alone: %.3f s (%.3g tets/s)\n", adjacency_seconds,
                tets / adjacency_seconds);
    std::printf(
        "container with adjacency: %.1f bytes/tet as built (push_back capacity), "
        "%.1f bytes/tet as read (exact sizes)\n",
        static_cast<double>(mesh.memory_bytes()) / tets, static_cast<double>(read_memory) / tets);
    fs::remove_all(dir);
    return 0;
}
