// The cascade's stages 1-3 on one small closed group of faces, the best fill kept.

#include <algorithm>

#include "volume/fill/detail/cavity_stages.h"
#include "volume/fill/detail/kernel.h"

namespace hdimesh::volume::detail
{

namespace
{

/// The fields a stage writes, copied so that the caller's removed_tets, ref and grown_layers
/// stay as they were.
void take_stage_fill(const CavityFill& stage_fill, CavityFill& fill)
{
    fill.filled = stage_fill.filled;
    fill.stage = stage_fill.stage;
    fill.tets = stage_fill.tets;
    fill.new_points = stage_fill.new_points;
    fill.faces = stage_fill.faces;
    fill.worst_quality = stage_fill.worst_quality;
    fill.failure.clear();
}

}  // namespace

bool fill_small_cavity(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                       const CavityOptions& options, CavityFill& fill)
{
    CavityFill best;
    // an earlier stage wins ties: fewer Steiner points for the same worst quality
    auto keep_better = [&best](const CavityFill& candidate) {
        if (!best.filled || candidate.worst_quality > best.worst_quality) best = candidate;
    };
    auto good_enough = [&] { return best.filled && best.worst_quality >= options.accept_quality; };
    if (static_cast<int>(faces.size()) <= options.max_fan_faces)
    {
        CavityFill vertex_fan;
        if (fill_by_vertex_fan(points, faces, vertex_fan)) keep_better(vertex_fan);
        if (!good_enough())
        {
            CavityFill kernel_fan;
            if (fill_by_kernel_fan(points, faces, kernel_fan)) keep_better(kernel_fan);
        }
    }
    if (!good_enough())
    {
        // with a fill in hand the search only improves it: a smaller budget, since proving
        // a many-point polyhedron's optimum would spend the whole budget on most cavities
        CavityOptions search_options = options;
        if (best.filled)
            search_options.exhaustive_node_budget =
                std::min(options.exhaustive_node_budget, options.improve_node_budget);
        CavityFill exhaustive;
        if (fill_exhaustive_above(points, faces, search_options,
                                  best.filled ? best.worst_quality : 0.0, exhaustive))
            keep_better(exhaustive);
    }
    if (!best.filled) return false;
    take_stage_fill(best, fill);
    return true;
}

}  // namespace hdimesh::volume::detail
