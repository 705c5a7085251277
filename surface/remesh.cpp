#include "surface/remesh.h"

#include <algorithm>
#include <cstdio>
#include <memory>

#include "surface/hdi_projection.h"
#include "surface/local_ops_geometry.h"
#include "surface/surface_errors.h"
#include "surface/surface_model.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface
{
namespace
{

constexpr double kTooLong = 4.0 / 3.0;
constexpr double kTooShort = 4.0 / 5.0;

class Remesher
{
public:
    Remesher(SurfaceMesh& mesh, const RemeshOptions& options, const Projector& model, const SurfaceHooks& hooks)
        : mesh_(mesh), options_(options), ctx_(mesh, model, hooks, options.limits)
    {
        ctx_.limits.max_model_distance = options.max_model_distance;
    }

    RemeshReport run()
    {
        update_sizes();
        for (int it = 0; it < options_.iterations; ++it)
        {
            split_long_edges();
            collapse_short_edges();
            flip_edges(FlipGoal::Valence);
            shift_vertices(false);
            ++report_.iterations;
            if (options_.verbosity > 0)
                std::fprintf(stderr, "remesh: iteration %d: %zu vertices, %zu splits, %zu collapses, %zu flips, %zu shifts\n",
                             it + 1, count_vertices(), report_.splits, report_.collapses, report_.flips, report_.shifts);
        }
        // Shape polish: quality flips and smart shifts only raise the worst Qe of what they touch.
        for (int pass = 0; pass < options_.polish_passes; ++pass)
        {
            flip_edges(FlipGoal::Quality);
            shift_vertices(true);
        }
        cleanup_worst_triangles();
        mesh_.garbage_collection();
        return report_;
    }

private:
    std::size_t count_vertices() const
    {
        std::size_t n = 0;
        for (auto v : mesh_.vertices())
            if (!mesh_.status(v).deleted()) ++n;
        return n;
    }

    void set_size(VertexHandle v) { mesh_.property(ctx_.props.vertex_size, v) = options_.size(mesh_.point(v)); }

    void update_sizes()
    {
        for (auto v : mesh_.vertices()) set_size(v);
    }

    double edge_size(EdgeHandle e) const
    {
        const auto h = mesh_.halfedge_handle(e, 0);
        return 0.5 * (mesh_.property(ctx_.props.vertex_size, mesh_.from_vertex_handle(h)) +
                      mesh_.property(ctx_.props.vertex_size, mesh_.to_vertex_handle(h)));
    }

    std::vector<EdgeHandle> live_edges() const
    {
        std::vector<EdgeHandle> edges;
        edges.reserve(mesh_.n_edges());
        for (auto e : mesh_.edges())
            if (!mesh_.status(e).deleted()) edges.push_back(e);
        return edges;
    }

    void split_long_edges()
    {
        for (int pass = 0; pass < 10; ++pass)
        {
            std::vector<std::pair<double, EdgeHandle>> candidates;
            for (auto e : live_edges())
            {
                const double ratio = mesh_.calc_edge_length(e) / edge_size(e);
                if (ratio > kTooLong) candidates.emplace_back(ratio, e);
            }
            if (candidates.empty()) return;
            std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
            std::size_t done = 0;
            for (const auto& [ratio, e] : candidates)
            {
                if (mesh_.status(e).deleted() || mesh_.calc_edge_length(e) <= kTooLong * edge_size(e)) continue;
                const OpResult r = try_split(ctx_, e);
                if (!r.done()) continue;
                set_size(r.vertex);
                ++done;
            }
            report_.splits += done;
            if (done == 0) return;
        }
    }

    // Smooth vertices go first; a curve vertex only along its curve (try_collapse checks).
    int removal_rank(VertexHandle v) const
    {
        switch (ctx_.vertex_class(v))
        {
        case VertexClass::Smooth: return 0;
        case VertexClass::Ridge:
        case VertexClass::Boundary: return 1;
        case VertexClass::Corner: return 2;
        }
        return 2;
    }

    void collapse_short_edges()
    {
        for (int pass = 0; pass < 5; ++pass)
        {
            std::size_t done = 0;
            for (auto e : live_edges())
            {
                if (mesh_.status(e).deleted()) continue;
                const double h = edge_size(e);
                if (mesh_.calc_edge_length(e) >= kTooShort * h) continue;
                HalfedgeHandle hs[2] = {mesh_.halfedge_handle(e, 0), mesh_.halfedge_handle(e, 1)};
                if (removal_rank(mesh_.from_vertex_handle(hs[1])) < removal_rank(mesh_.from_vertex_handle(hs[0])))
                    std::swap(hs[0], hs[1]);
                for (const HalfedgeHandle hh : hs)
                {
                    const OpResult r = try_collapse(ctx_, hh, kTooLong * h);
                    if (r.done())
                    {
                        ++done;
                        break;
                    }
                }
            }
            report_.collapses += done;
            if (done == 0) return;
        }
    }

    std::size_t flip_edges(FlipGoal goal)
    {
        std::size_t done = 0;
        for (auto e : live_edges())
            if (!mesh_.status(e).deleted() && try_flip(ctx_, e, goal).done()) ++done;
        report_.flips += done;
        return done;
    }

    void shift_vertices(bool smart)
    {
        ShiftOptions shift;
        shift.smart = smart;
        for (auto v : mesh_.vertices())
        {
            if (mesh_.status(v).deleted()) continue;
            if (shift_vertex(ctx_, v, shift).done())
            {
                set_size(v);
                ++report_.shifts;
            }
        }
    }

    double face_min_angle(FaceHandle f) const
    {
        const auto p = detail::face_points(mesh_, f);
        return triangle_min_angle_deg(p[0], p[1], p[2]);
    }

    // The worst triangles: try, in order, a quality flip of each edge, a collapse of the
    // shortest edge that raises the worst Qe around, removal of a vertex, a smart shift of each
    // vertex; repeat while something changes.
    void cleanup_worst_triangles()
    {
        ShiftOptions smart;
        smart.smart = true;
        for (int round = 0; round < options_.cleanup_rounds; ++round)
        {
            std::vector<FaceHandle> bad;
            for (auto f : mesh_.faces())
                if (!mesh_.status(f).deleted() && face_min_angle(f) < options_.cleanup_angle_deg) bad.push_back(f);
            if (bad.empty()) break;
            std::size_t changed = 0;
            for (const FaceHandle f : bad)
            {
                if (mesh_.status(f).deleted() || face_min_angle(f) >= options_.cleanup_angle_deg) continue;
                if (improve_face(f, smart)) ++changed;
            }
            if (options_.verbosity > 0)
                std::fprintf(stderr, "remesh: cleanup round %d: %zu bad triangles, %zu improved\n", round + 1, bad.size(), changed);
            if (changed == 0) break;
            // Let the neighbourhood settle after the topological changes.
            for (const FaceHandle f : bad)
            {
                if (mesh_.status(f).deleted()) continue;
                for (auto v : mesh_.fv_range(f))
                    if (shift_vertex(ctx_, v, smart).done()) ++report_.shifts;
            }
        }
    }

    bool improve_face(FaceHandle f, const ShiftOptions& smart)
    {
        std::vector<EdgeHandle> edges;
        for (auto e : mesh_.fe_range(f)) edges.push_back(e);
        std::sort(edges.begin(), edges.end(), [&](EdgeHandle a, EdgeHandle b) {
            return mesh_.calc_edge_length(a) > mesh_.calc_edge_length(b);
        });
        // The longest edge is opposite the largest angle: flipping it is the usual cure.
        for (const EdgeHandle e : edges)
            if (try_flip(ctx_, e, FlipGoal::Quality).done())
            {
                ++report_.flips;
                return true;
            }
        // The shortest edge of a needle: collapse it if the neighbourhood gets better.
        const EdgeHandle shortest = edges.back();
        const double h = edge_size(shortest);
        for (int i = 0; i < 2; ++i)
            if (try_collapse(ctx_, mesh_.halfedge_handle(shortest, i), kTooLong * h, true).done())
            {
                ++report_.collapses;
                return true;
            }
        std::vector<VertexHandle> vertices;
        for (auto v : mesh_.fv_range(f)) vertices.push_back(v);
        for (const VertexHandle v : vertices)
            if (try_remove_vertex(ctx_, v).done())
            {
                ++report_.removals;
                return true;
            }
        bool moved = false;
        for (const VertexHandle v : vertices)
            if (!mesh_.status(v).deleted() && shift_vertex(ctx_, v, smart).done())
            {
                ++report_.shifts;
                moved = true;
            }
        return moved;
    }

    SurfaceMesh& mesh_;
    const RemeshOptions& options_;
    OperatorContext ctx_;
    RemeshReport report_;
};

}  // namespace

RemeshReport remesh(SurfaceMesh& mesh, const RemeshOptions& options, const Projector& model, const SurfaceHooks& hooks)
{
    if (!options.size) throw SurfaceInputError("remesh: no size function given");
    Remesher remesher(mesh, options, model, hooks);
    return remesher.run();
}

RemeshReport remesh(SurfaceMesh& mesh, const RemeshOptions& options, const hdi::HdiSurface& model,
                    const SurfaceHooks& hooks)
{
    const HdiProjector projector(model);
    return remesh(mesh, options, projector, hooks);
}

SurfaceRemeshResult remesh_surface(SurfaceMesh& mesh, const SurfaceRemeshSettings& settings)
{
    SurfaceRemeshResult result;
    result.diagonal = bounding_box_diagonal(mesh);
    FeatureOptions features = settings.features;
    if (features.min_corner_spacing <= 0.0)
    {
        const double h = settings.sizing.hsiz > 0.0 ? settings.sizing.hsiz
                         : settings.sizing.hmin > 0.0 ? settings.sizing.hmin
                                                      : 0.0;
        features.min_corner_spacing = 0.5 * h;
    }
    result.features = detect_features(mesh, features);
    SurfaceModel model(mesh);
    if (settings.use_hdi) attach_hdi_projection(model, mesh);

    SizeMap sizes = SizeMap::uniform(settings.sizing.hsiz);
    if (settings.sizing.hsiz > 0.0 && settings.uniform_hausd_fraction > 0.0)
    {
        // A uniform size, but no coarser than the curvature allows for the tolerance: a fillet
        // narrower than h would otherwise be cut by chords (the Hausdorff target).
        SizingOptions capped = settings.sizing;
        capped.hmax = settings.sizing.hsiz;
        if (!(capped.hausd > 0.0)) capped.hausd = settings.uniform_hausd_fraction * result.diagonal;
        std::vector<double> local = curvature_sizes(mesh, model, capped);
        // Never below the floor (edges shorter than 0.66·hsiz fail the size criterion); on ridges
        // down to half of it: a curved ridge must stay within its tolerance. Open boundaries of scans zig-zag,
        // so their turning is no curvature to follow.
        SurfaceProperties props(mesh);
        for (auto v : mesh.vertices())
        {
            const bool ridge = mesh.property(props.vertex_class, v) == VertexClass::Ridge;
            const double floor = (ridge ? 0.5 : 1.0) * settings.uniform_size_floor * settings.sizing.hsiz;
            local[v.idx()] = std::max(local[v.idx()], floor);
        }
        const bool all_uniform = std::all_of(local.begin(), local.end(),
                                             [&](double s) { return s >= settings.sizing.hsiz; });
        if (!all_uniform) sizes = SizeMap::per_input_vertex(model, std::move(local));
    }
    if (!settings.input_sizes.empty())
    {
        if (settings.input_sizes.size() != mesh.n_vertices())
            throw SurfaceInputError("remesh_surface: " + std::to_string(settings.input_sizes.size()) +
                                    " sizes for " + std::to_string(mesh.n_vertices()) + " vertices");
        std::vector<double> graded = settings.input_sizes;
        bound_and_grade(mesh, graded, settings.sizing);
        sizes = SizeMap::per_input_vertex(model, std::move(graded));
        result.adaptive = true;
    }
    else if (!(settings.sizing.hsiz > 0.0))
    {
        sizes = SizeMap::per_input_vertex(model, curvature_sizes(mesh, model, settings.sizing));
        result.adaptive = true;
    }
    result.uniform_size = settings.sizing.hsiz > 0.0 ? settings.sizing.hsiz : sizes.uniform_size();

    RemeshOptions options;
    options.size = [&sizes](const Vec3d& p) { return sizes.at(p); };
    options.iterations = settings.iterations;
    options.verbosity = settings.verbosity;
    if (settings.max_model_distance >= 0.0) options.max_model_distance = settings.max_model_distance;
    else if (settings.sizing.hausd > 0.0) options.max_model_distance = settings.sizing.hausd;
    else options.max_model_distance = 0.002 * result.diagonal;
    result.report = remesh(mesh, options, model, {});
    return result;
}

}  // namespace hdimesh::surface
