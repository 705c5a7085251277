#include "coupling/adapt.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>

#include "common/errors.h"
#include "common/size_quality.h"
#include "common/stage_timer.h"
#include "coupling/boundary_map.h"
#include "surface/features.h"
#include "surface/hdi_projection.h"
#include "surface/surface_model.h"
#include "surface/surface_quality.h"
#include "volume/mesh/reorder.h"
#include "volume/size/size_fields.h"

namespace hdimesh::coupling
{

using namespace volume;

namespace
{

// Surface passes at most, another while the volume's splits changed more than this fraction of
// the triangles the last one left (a few too long edges are no reason to remesh it all again).
constexpr int kSurfaceRounds = 3;
constexpr double kSurfaceRepeatFraction = 0.01;
constexpr int kStallPasses = 3;          // refinement stops when the splits have not decreased
constexpr double kStallFraction = 1e-3;  // over this many passes and are this few per tet

double min_quality(const TetMesh& mesh)
{
    double worst = 1.0;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t)) worst = std::min(worst, mesh.quality(t));
    return worst;
}

std::string format_pass_row(const AdaptPassReport& p)
{
    char row[160];
    std::snprintf(row, sizeof row, "%5d %10d %10d %10d %9d %9d %8.4f %8.3f\n", p.pass,
                  p.edges_split, p.tets, p.vertices, p.projected, p.shortened, p.min_quality,
                  p.seconds);
    return row;
}

/// The surface pass's settings: the field's size, a constant when it is one at every boundary
/// vertex (the uniform sizing, with its curvature cap); the distance bound when --hausd gives one.
surface::SurfaceRemeshSettings surface_settings(const surface::SurfaceMesh& boundary,
                                                const SizeField& field, const AdaptOptions& options)
{
    surface::SurfaceRemeshSettings settings = options.surface_settings;
    auto size = [&field](const surface::Vec3d& p) { return field.size(Vec3(p[0], p[1], p[2])); };
    double lo = std::numeric_limits<double>::max(), hi = 0.0;
    for (auto v : boundary.vertices())
    {
        const double h = size(boundary.point(v));
        lo = std::min(lo, h);
        hi = std::max(hi, h);
    }
    settings.input_sizes.clear();
    settings.sizing.hsiz = 0.0;
    settings.size_function = nullptr;
    if (lo == hi)
        settings.sizing.hsiz = lo;
    else
        settings.size_function = size;  // field outlives the pass
    if (options.hausd > 0.0) settings.sizing.hausd = options.hausd;
    settings.keep_classification = true;  // classified once, before the model is built
    return settings;
}

const char* kPassHeader =
    " pass     split       tets   vertices projected shortened   min Qe     time\n";

}  // namespace

void apply_switches(const AdaptSwitches& switches, AdaptOptions& options)
{
    const bool insert = !switches.noinsert && !switches.optim;
    options.refine = insert;
    options.optimize = !switches.no_optimize;
    options.project = !switches.no_projection;
    // the surface pass splits and collapses
    options.surface = !switches.nosurf && insert;
    options.optimizer.swap = !switches.noswap;
    options.optimizer.move = !switches.nomove;
    options.surface_settings.swap = !switches.noswap;  // Mmg's switches hold on both meshes
    options.surface_settings.move = !switches.nomove;
    options.optimizer.split = insert;
    options.optimizer.collapse = insert;  // a collapse removes a vertex
    for (hdi::FeatureOptions* features :
         {&options.surface_settings.features, &options.projection.features})
    {
        features->detect_ridges = !switches.no_ridges;
        features->ridge_angle_deg = switches.ridge_angle;
    }
}

AdaptReport adapt(TetMesh& mesh, const SizeField& field, const AdaptOptions& options)
{
    AdaptReport report;
    const Stopwatch clock;
    if (!mesh.has_adjacency()) mesh.build_adjacency();
    if (options.refine || options.surface)
    {
        // A size far below the model's scale would run until memory is gone.
        const double expected = expected_tet_count(mesh, field);
        if (!(expected <= kMaxTets))
        {
            char text[200];
            std::snprintf(text, sizeof text,
                          "the size field asks for about %.3g tets, more than the %.3g a mesh "
                          "can hold: the size is far below the model's scale",
                          expected, kMaxTets);
            throw InputError(text);
        }
    }

    // One classification of the input boundary, given to both meshes before either model is
    // built from it.
    std::optional<BoundaryMap> input;  // its surface is the model's; its tet ids go stale
    surface::SurfaceRemeshSettings settings;
    if (options.surface && options.project)  // no projection: the polyhedron is kept
    {
        const StageTimer timer(report.seconds_surface, report.cpu_seconds_surface);
        report.surface_refusal = coupled_surface_refusal(mesh);
        if (report.surface_refusal.empty() && mesh.num_live_tets() > 0)
        {
            input = extract_boundary(mesh);
            settings = surface_settings(input->surface, field, options);
            surface::detect_features(input->surface, surface::feature_options(settings));
            write_back(*input, mesh);
        }
    }

    std::unique_ptr<BoundaryProjector> projector;
    if (options.project)
    {
        const StageTimer timer(report.seconds_project, report.cpu_seconds_project);
        projector = std::make_unique<BoundaryProjector>(mesh, options.projection);
    }

    if (options.verbosity >= 2) std::cout << kPassHeader;

    // Refinement passes, each followed by projection and local repair, until no edge is too
    // long (or they stall, or reach the cap).
    auto refine_to_field = [&](const SizeField& target) {
        report.converged = !options.refine;
        report.stalled = false;
        const int first = static_cast<int>(report.passes.size()) + 1;
        for (int pass = first; options.refine && pass < first + options.max_passes; ++pass)
        {
            AdaptPassReport row;
            row.pass = pass;
            const Stopwatch pass_clock;

            RefinePassResult refined;
            {
                const StageTimer timer(report.seconds_refine, report.cpu_seconds_refine);
                refined = refine_pass(mesh, target);
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
                const ProjectionReport moved =
                    projector->project(mesh, refined.new_boundary_vertices);
                row.projected = moved.projected;
                row.shortened = moved.shortened;
            }
            if (options.optimize)
            {
                const StageTimer timer(report.seconds_optimize, report.cpu_seconds_optimize);
                row.min_quality =
                    improve_bad_elements(mesh, target, options.optimizer).min_quality_after;
            }
            else
            {
                row.min_quality = min_quality(mesh);
            }

            row.tets = mesh.num_live_tets();
            row.vertices = mesh.num_vertices();
            row.seconds = pass_clock.wall_seconds();
            report.passes.push_back(row);
            if (options.verbosity >= 2) std::cout << format_pass_row(row) << std::flush;
            if (options.progress) options.progress("pass " + std::to_string(pass), row.tets);
            if (options.verbosity >= 1 && isatty(STDERR_FILENO))
                std::fprintf(stderr, "\radapt: pass %d, %d tets", pass, row.tets);
            // A few splits a pass that no longer decrease: the long edges left are where a split
            // does not shorten them (beside a kept triangle longer than the size); more passes only
            // stack slivers there.
            // (this call's passes only: the second call follows a surface pass, not these)
            const int n = static_cast<int>(report.passes.size());
            if (n - first + 1 > kStallPasses &&
                row.edges_split <= kStallFraction * static_cast<double>(mesh.num_live_tets()) &&
                row.edges_split >= report.passes[n - 1 - kStallPasses].edges_split)
            {
                report.stalled = true;
                break;
            }
        }
    };
    refine_to_field(field);

    if (options.verbosity >= 1 && isatty(STDERR_FILENO) && !report.passes.empty())
        std::fprintf(stderr, "\radapt: surface and final optimization...\n");

    // The surface pass on the input's model, once the tets are at the field's size near the
    // boundary: the tets follow every change (the mirror).
    std::optional<surface::SurfaceModel> surface_model;  // the surface pass's, kept for the
                                                         // splits after it
    std::unique_ptr<BackgroundMeshSize> graded;
    const SizeField* volume_field = &field;
    // One surface pass: the boundary remeshed with the tets mirrored, then the volume's sizes
    // graded from what the surface reached. Its triangle count.
    auto surface_pass = [&] {
        const StageTimer timer(report.seconds_surface, report.cpu_seconds_surface);
        mesh.compact();
        if (!mesh.has_adjacency()) mesh.build_adjacency();
        BoundaryMap boundary = extract_boundary(mesh);
        if (!surface_model)
        {
            report.surface_triangles_before = static_cast<int>(input->surface.n_faces());
            settings.model_surface = &input->surface;
            // One model on both sides: smooth vertices go onto the projection's HDI surface
            // where the input's facets are too coarse for the tolerance, trusted as far from
            // their chords as those are from the smooth surface; elsewhere the facets are the
            // finer model.
            surface_model.emplace(input->surface);
            surface::attach_hdi_projection(
                *surface_model, projector->model(),
                surface::coarse_input_options(
                    settings.hdi_projection,
                    surface::distance_tolerance(settings,
                                                surface::bounding_box_diagonal(input->surface))));
            settings.model = &*surface_model;
        }
        const surface::SurfaceHooks hooks =
            make_hooks(mesh, boundary, options.mirror, &report.mirror);
        surface::remesh_surface(boundary.surface, settings, hooks);
        // The splits the refinement still makes on the boundary land on the same model.
        projector->set_surface_target([&model = *surface_model](const Vec3& p) {
            const surface::ProjectedPoint q = model.project(
                surface::Vec3d(p[0], p[1], p[2]), surface::VertexClass::Smooth, surface::kNoCurve);
            return q.ok ? std::optional<Vec3>(Vec3(q.point[0], q.point[1], q.point[2]))
                        : std::nullopt;
        });
        write_back(boundary, mesh);
        // The sizes the surface reached (the field's, or finer where the tolerance asked),
        // by tet vertex across the compaction.
        std::vector<double> surface_size(mesh.num_vertices(), 0.0);
        const surface::SurfaceProperties props(boundary.surface);
        for (auto v : boundary.surface.vertices())
            surface_size[boundary.tet_vertex_of(v)] =
                boundary.surface.property(props.vertex_size, v);
        const CompactionMaps maps = mesh.compact();
        report.surface_remeshed = true;
        // The volume grades from the boundary's sizes to the field's (Mmg's hgrad) where the
        // tolerance made them finer than the field's band, so the tets between that boundary
        // and a coarse interior keep their shape.
        std::vector<double> sizes = sample_vertex_sizes(mesh, field);
        bool finer = false;
        for (std::size_t old = 0; old < maps.old2new_verts.size(); ++old)
        {
            const int v = maps.old2new_verts[old];
            // (within the field's band the tets keep the field: its edges are not too short)
            if (v < 0 || !(surface_size[old] > 0.0) ||
                !(surface_size[old] < kSizeQualityThreshold * sizes[v]))
                continue;
            sizes[v] = surface_size[old];
            finer = true;
        }
        volume_field = &field;
        graded.reset();
        if (finer)
        {
            grade_vertex_sizes(mesh, sizes, std::max(1.0, settings.sizing.hgrad));
            graded = std::make_unique<BackgroundMeshSize>(mesh, std::move(sizes));
            volume_field = graded.get();
        }
        return static_cast<int>(mesh.triangles.size());
    };
    // The surface pass, then the volume's splits to the graded field, until the volume leaves
    // the boundary (nearly) as the surface pass made it: its splits of the edges the pass left
    // too long change it, the optimization after does not.
    for (int round = 0; input && round < kSurfaceRounds; ++round)
    {
        if (options.progress) options.progress("surface", mesh.num_live_tets());
        const int remeshed = surface_pass();
        ++report.surface_passes;
        // The surface's bands and the refills may leave a few edges too long on either side.
        refine_to_field(*volume_field);
        report.surface_triangles_after = static_cast<int>(mesh.triangles.size());
        if (report.surface_triangles_after - remeshed <= kSurfaceRepeatFraction * remeshed) break;
    }

    // the final optimization, then the moves the guard had shortened
    if (options.optimize)
    {
        if (options.progress) options.progress("optimize", mesh.num_live_tets());
        const StageTimer timer(report.seconds_optimize, report.cpu_seconds_optimize);
        mesh.compact();  // renumbering needs a compact mesh; the passes leave it so, this makes
                         // sure
        renumber_spatially(mesh);
        optimize_mesh(mesh, *volume_field, options.optimizer);
    }
    // After a surface pass the boundary lies on the model already; else the refinement's
    // shortened moves are left to finish.
    if (projector && !report.surface_remeshed)
    {
        {
            const StageTimer timer(report.seconds_project, report.cpu_seconds_project);
            report.final_projection = projector->project_all(mesh);
        }
        if (options.optimize &&
            report.final_projection.shortened + report.final_projection.projected > 0)
        {
            const StageTimer timer(report.seconds_optimize, report.cpu_seconds_optimize);
            // the moved boundary vertices reshape tets the final optimization had lifted above
            // its target: bring them back there, not only above the passes' "bad" threshold
            OptimizeOptions repair = options.optimizer;
            repair.bad_quality = std::max(repair.bad_quality, repair.target_quality);
            improve_bad_elements(mesh, *volume_field, repair);
        }
    }
    if (!mesh.has_adjacency()) mesh.build_adjacency();
    report.seconds_total = clock.wall_seconds();
    report.cpu_seconds_total = clock.cpu_seconds();
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
    if (report.surface_remeshed)
    {
        std::snprintf(line, sizeof line, "surface: %d triangles -> %d, on the input's model%s\n",
                      report.surface_triangles_before, report.surface_triangles_after,
                      report.surface_passes > 1
                          ? (", " + std::to_string(report.surface_passes) + " passes").c_str()
                          : "");
        out << line << report.mirror.format();
    }
    else if (!report.surface_refusal.empty())
    {
        out << "surface: kept (" << report.surface_refusal << ")\n";
    }
    const double rest = report.seconds_total - report.seconds_surface - report.seconds_refine -
                        report.seconds_project - report.seconds_optimize;
    std::snprintf(line, sizeof line,
                  "time: total %.3f s = surface %.3f + refine %.3f + project %.3f + optimize %.3f "
                  "+ other %.3f\n",
                  report.seconds_total, report.seconds_surface, report.seconds_refine,
                  report.seconds_project, report.seconds_optimize, rest);
    out << line;
    std::snprintf(line, sizeof line,
                  "cpu:  total %.3f s = surface %.3f + refine %.3f + project %.3f + optimize %.3f "
                  "+ other %.3f\n",
                  report.cpu_seconds_total, report.cpu_seconds_surface, report.cpu_seconds_refine,
                  report.cpu_seconds_project, report.cpu_seconds_optimize,
                  report.cpu_seconds_total - report.cpu_seconds_surface -
                      report.cpu_seconds_refine - report.cpu_seconds_project -
                      report.cpu_seconds_optimize);
    out << line;
    out << (report.converged ? "sizes: no edge too long\n"
            : report.stalled
                ? "sizes: refinement stopped with a few edges too long that splitting does not "
                  "shorten\n"
                : "sizes: refinement stopped at the pass cap with edges too long\n");
    return out.str();
}

}  // namespace hdimesh::coupling
