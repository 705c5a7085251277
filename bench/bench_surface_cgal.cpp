// CGAL comparison row of the surface remeshing benchmark (issue 6): CGAL's
// Polygon_mesh_processing::isotropic_remeshing on the same inputs, at the same target length, and
// measured by the same code (surface/surface_quality.h) as bench_surface's rows, so that the two
// tables can be read side by side (same columns, same widths).
//
// Protocol, per model:
//   - input: read_surface (our reader and its repairs), so that both remeshers start from the same
//     mesh; target edge length h = 1 % of its bounding-box diagonal;
//   - features: detect_sharp_edges at 45° into an edge_is_constrained_map (it also marks border
//     edges, so the bunny's five holes are constraints too);
//   - default: isotropic_remeshing(faces, h, mesh,
//     number_of_iterations(5).edge_is_constrained_map(map)), every other parameter at CGAL's
//     default: constrained edges are never flipped and their vertices never smoothed off them, but
//     they are split and collapsed along their polyline (protect_constraints false,
//     collapse_constraints true). This is the protocol of the peer figures quoted in issue 6: it
//     reproduces them to their last digit;
//   - --protect-constraints: the constrained edges longer than h are first split
//     (split_long_edges, as CGAL's remeshing example does for borders; protect_constraints requires
//     them no longer than 4/3·h), then the same call with protect_constraints(true): constrained
//     edges are neither split nor collapsed, so the short input edges along the features stay.
// The wall and CPU times cover only the CGAL calls (feature detection, pre-split, remeshing), like
// bench_surface times only remesh_surface (which detects its features itself); conversions between
// the two mesh types and the measurements are not timed.
//
//   bench_surface_cgal [--models a,b,...] [--protect-constraints] [--repeat N] [--write DIR]
//                      [model.obj ...]
//
// --models picks models of data/ by name; files given as arguments are added; with neither, the
// five models of issue 6. --repeat N runs CGAL N times from the input and prints the fastest run's
// times (the machine is shared; default 1, like bench_surface). --write DIR writes each CGAL output
// as DIR/<model>_cgal.obj, for a second opinion with
// ../shared/tools/surfstat.py OUT --ref IN --hsiz h.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/version.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <stdexcept>
#include <string>
#include <vector>

// OpenMesh's PropertyT<Vec3d>::push_back copies a default-constructed (deliberately uninitialized)
// VectorT: a -Wmaybe-uninitialized false positive once GCC inlines add_vertex here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "surface/surface_io.h"
#include "surface/surface_quality.h"
#pragma GCC diagnostic pop

using namespace hdimesh::surface;

namespace
{

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using CgalEdge = boost::graph_traits<CgalMesh>::edge_descriptor;

struct Options
{
    std::vector<std::string> models;  // paths
    bool protect_constraints = false;
    int repeat = 1;         // CGAL runs per model; the fastest is reported
    std::string write_dir;  // empty: do not write outputs
};

struct CgalRunResult
{
    double wall_seconds = 0.0, cpu_seconds = 0.0;
    std::size_t sharp_edges = 0;   // detected at 45°, border edges excluded
    std::size_t border_edges = 0;  // of the input
};

CgalMesh to_cgal(const SurfaceMesh& mesh)
{
    CgalMesh out;
    std::vector<CgalMesh::Vertex_index> old2new_vertex(mesh.n_vertices());
    for (auto v : mesh.vertices())
    {
        const Vec3d& p = mesh.point(v);
        old2new_vertex[v.idx()] = out.add_vertex(Kernel::Point_3(p[0], p[1], p[2]));
    }
    for (auto f : mesh.faces())
    {
        auto fv = mesh.cfv_iter(f);
        const auto a = old2new_vertex[fv->idx()];
        const auto b = old2new_vertex[(++fv)->idx()];
        const auto c = old2new_vertex[(++fv)->idx()];
        if (out.add_face(a, b, c) == CgalMesh::null_face())
            throw std::runtime_error("face " + std::to_string(f.idx()) +
                                     " cannot be added to a CGAL Surface_mesh");
    }
    return out;
}

/// Back to our mesh type for the measurements. No repair: a face OpenMesh refuses (non-manifold
/// output) is counted in `rejected_faces`, not silently fixed.
SurfaceMesh from_cgal(const CgalMesh& mesh, std::size_t& rejected_faces)
{
    SurfaceMesh out;
    // Indices of a Surface_mesh may have holes (removed elements not yet garbage-collected).
    std::size_t index_bound = 0;
    for (auto v : mesh.vertices()) index_bound = std::max<std::size_t>(index_bound, v.idx() + 1);
    std::vector<VertexHandle> old2new_vertex(index_bound);
    for (auto v : mesh.vertices())
    {
        const auto& p = mesh.point(v);
        old2new_vertex[v.idx()] = out.add_vertex(Vec3d(p.x(), p.y(), p.z()));
    }
    rejected_faces = 0;
    for (auto f : mesh.faces())
    {
        std::vector<VertexHandle> corners;
        for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
            corners.push_back(old2new_vertex[v.idx()]);
        if (corners.size() != 3 || !out.add_face(corners).is_valid()) ++rejected_faces;
    }
    return out;
}

/// The CGAL protocol described at the top of the file, on `mesh` in place; only this is timed.
CgalRunResult remesh_with_cgal(CgalMesh& mesh, double target_length, bool protect_constraints)
{
    CgalRunResult result;
    auto constrained = mesh.add_property_map<CgalEdge, bool>("e:is_constrained", false).first;

    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    PMP::detect_sharp_edges(mesh, 45.0, constrained);
    if (protect_constraints)
    {
        std::vector<CgalEdge> constrained_edges;
        for (auto e : mesh.edges())
            if (constrained[e]) constrained_edges.push_back(e);
        PMP::split_long_edges(constrained_edges, target_length, mesh,
                              PMP::parameters::edge_is_constrained_map(constrained));
        PMP::isotropic_remeshing(mesh.faces(), target_length, mesh,
                                 PMP::parameters::number_of_iterations(5)
                                     .protect_constraints(true)
                                     .edge_is_constrained_map(constrained));
    }
    else
    {
        PMP::isotropic_remeshing(
            mesh.faces(), target_length, mesh,
            PMP::parameters::number_of_iterations(5).edge_is_constrained_map(constrained));
    }
    result.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    result.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

/// Sharp (non-border) and border edges of the input, as detect_sharp_edges sees them at 45°: the
/// amount of the input CGAL keeps fixed, printed beside the row to explain its worst angles.
void count_constraints(const CgalMesh& input, CgalRunResult& result)
{
    CgalMesh copy = input;
    auto sharp = copy.add_property_map<CgalEdge, bool>("e:sharp", false).first;
    PMP::detect_sharp_edges(copy, 45.0, sharp);
    for (auto e : copy.edges())
    {
        if (copy.is_border(e))
            ++result.border_edges;
        else if (sharp[e])
            ++result.sharp_edges;
    }
}

std::string model_name(const std::string& path)
{
    std::string name = path.substr(path.find_last_of('/') + 1);
    return name.substr(0, name.find_last_of('.'));
}

void print_usage()
{
    std::fprintf(
        stderr,
        "usage: bench_surface_cgal [--models a,b,...] [--protect-constraints] [--repeat N] "
        "[--write DIR]\n"
        "                          [model.obj ...]\n"
        "  --models               models of %s by name (default: the five of issue 6)\n"
        "  --protect-constraints  pre-split constrained edges to h, then never split or\n"
        "                         collapse them\n"
        "                         (default: split and collapsed along their polyline)\n"
        "  --repeat N             run CGAL N times per model, report the fastest (default 1)\n"
        "  --write DIR            write each output as DIR/<model>_cgal.obj\n",
        HDIMESH_DATA_DIR);
}

/// Throws std::invalid_argument on a malformed command line.
Options parse_options(int argc, char** argv)
{
    Options options;
    auto value_of = [&](int& i) -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(std::string(argv[i]) + " needs a value");
        return argv[++i];
    };
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "--models")
        {
            const std::string list = value_of(i);
            std::size_t begin = 0;
            while (begin <= list.size())
            {
                const std::size_t end = std::min(list.find(',', begin), list.size());
                const std::string name = list.substr(begin, end - begin);
                if (name.empty())
                    throw std::invalid_argument("empty model name in --models " + list);
                options.models.push_back(std::string(HDIMESH_DATA_DIR) + "/" + name + ".obj");
                begin = end + 1;
            }
        }
        else if (arg == "--protect-constraints")
            options.protect_constraints = true;
        else if (arg == "--write")
            options.write_dir = value_of(i);
        else if (arg == "--repeat")
        {
            const std::string count = value_of(i);
            std::size_t parsed = 0;
            try
            {
                options.repeat = std::stoi(count, &parsed);
            }
            catch (const std::exception&)
            {
                parsed = 0;
            }
            if (parsed != count.size() || options.repeat < 1)
                throw std::invalid_argument("--repeat needs a positive integer, not " + count);
        }
        else if (arg == "-h" || arg == "--help")
        {
            print_usage();
            std::exit(0);
        }
        else if (arg.size() > 1 && arg[0] == '-')
            throw std::invalid_argument("unknown option " + arg);
        else
            options.models.push_back(arg);
    }
    if (options.models.empty())
        for (const char* name : {"fandisk", "rocker-arm", "spot", "cheburashka", "stanford-bunny"})
            options.models.push_back(std::string(HDIMESH_DATA_DIR) + "/" + name + ".obj");
    return options;
}

}  // namespace

int main(int argc, char** argv)
{
    Options options;
    try
    {
        options = parse_options(argc, argv);
    }
    catch (const std::invalid_argument& e)
    {
        std::fprintf(stderr, "bench_surface_cgal: %s\n", e.what());
        print_usage();
        return 2;
    }

    std::printf(
        "CGAL %s isotropic_remeshing: h = 0.01 diag, 5 iterations, sharp edges at 45 deg and "
        "border edges %s\n",
        CGAL_VERSION_STR,
        options.protect_constraints ? "protected (pre-split to h, then protect_constraints)"
                                    : "constrained (split/collapse along them allowed)");
    std::printf("%-16s %7s %7s %8s %8s %8s %8s %8s %8s %10s %10s %6s\n", "model", "in tri",
                "out tri", "wall s", "cpu s", "min ang", "%ang>=25", "%Qe>=.7", "%Qt>=.66",
                "Hausd/diag", "sharp/bord", "topo");
    int failures = 0;
    for (const std::string& path : options.models)
    {
        const std::string name = model_name(path);
        try
        {
            const SurfaceMesh input = read_surface(path);
            const double diagonal = bounding_box_diagonal(input);
            const double target_length = 0.01 * diagonal;

            const CgalMesh cgal_input = to_cgal(input);
            CgalRunResult run;
            count_constraints(cgal_input, run);
            CgalMesh cgal_mesh;
            for (int r = 0; r < options.repeat; ++r)
            {
                // Each run starts from the input; CGAL is deterministic: every run gives the same
                // mesh.
                cgal_mesh = cgal_input;
                const CgalRunResult timed =
                    remesh_with_cgal(cgal_mesh, target_length, options.protect_constraints);
                if (r == 0 || timed.wall_seconds < run.wall_seconds)
                {
                    run.wall_seconds = timed.wall_seconds;
                    run.cpu_seconds = timed.cpu_seconds;
                }
            }

            std::size_t rejected_faces = 0;
            const SurfaceMesh output = from_cgal(cgal_mesh, rejected_faces);
            const QualityReport q = measure_quality(output, target_length);
            const auto d = hausdorff_distance(output, input);
            const bool topology_kept =
                rejected_faces == 0 && measure_topology(input) == measure_topology(output);
            char constraints[32];
            std::snprintf(constraints, sizeof constraints, "%zu/%zu", run.sharp_edges,
                          run.border_edges);
            std::printf("%-16s %7zu %7zu %8.2f %8.2f %8.2f %8.3f %8.2f %8.2f %10.3e %10s %6s\n",
                        name.c_str(), input.n_faces(), output.n_faces(), run.wall_seconds,
                        run.cpu_seconds, q.min_angle_deg, q.percent_all_angles_ge_25,
                        q.percent_qe_ge_07, q.percent_qt_ge_066, std::max(d[0], d[1]) / diagonal,
                        constraints, topology_kept ? "kept" : "LOST");
            if (rejected_faces > 0)
                std::printf("%-16s   %zu output faces non-manifold in OpenMesh (not measured)\n",
                            "", rejected_faces);
            if (!options.write_dir.empty())
                write_surface(output, options.write_dir + "/" + name + "_cgal.obj");
        }
        catch (const std::exception& e)
        {
            ++failures;
            std::printf("%-16s error: %s\n", name.c_str(), e.what());
        }
    }
    return failures == 0 ? 0 : 1;
}
