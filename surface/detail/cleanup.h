#pragma once
// The stages that shape the output after the first refinement: the polish, the reference-size
// collapses, the worst-triangle cleanup, the angle repair, the needle slides and the curve fits.
// Those after the polish may be asked to keep the tolerance (ToleranceKeeper).

#include <cstddef>
#include <vector>

#include "surface/detail/change_log.h"
#include "surface/detail/keep_tolerance.h"

namespace hdimesh::surface::detail
{

class Cleanup : private ToleranceStage
{
public:
    Cleanup(RemeshRun& run, ToleranceKeeper& keeper, ChangeLog& log,
            const ToleranceOptions& tolerance, const CleanupOptions& options);

    /// Edges too short for the reference size collapsed (plain collapses, right after the loop).
    void collapse_short_for_reference();
    /// Quality flips and smart shifts where a triangle misses the polish's quality.
    void polish(const PolishOptions& options);
    /// The worst triangles: flips, collapses, removals, smart shifts, in rounds.
    void cleanup_worst_triangles(Keep keep = Keep::Nothing);
    /// Edges short for the reference size collapsed where the tolerance is kept.
    std::size_t collapse_short_keeping_tolerance();
    /// Curve vertices slid to where their chords follow the input curve best.
    std::size_t fit_curves();
    /// Needles with a curve vertex: the vertex slid along its curve.
    void slide_curve_vertices_of_needles();
    /// Small angles repaired by changes that keep the tolerance.
    std::size_t repair_small_angles();
    /// The vertices of triangles under `quality` relocated (relocate_vertex), then such
    /// triangles flipped or their shortest edge collapsed, each keeping what `keep` asks;
    /// rounds until nothing changes. The number of changes.
    std::size_t raise_poor_triangles(double quality, Keep keep);

private:
    std::vector<char> vertices_of_poor_triangles(double quality) const;
    std::vector<FaceHandle> faces_under_cleanup_angle();
    static std::vector<int> face_indices(const std::vector<FaceHandle>& faces);
    bool face_angle_below(FaceHandle f, double degrees) const;
    bool improve_face(FaceHandle f, const ShiftOptions& smart, Keep keep);
    bool try_slide(VertexHandle v);

    const CleanupOptions& options_;
    // Once the first small-angle scan ran (faces_under_cleanup_angle, recording from then on):
    // the faces it found last time, and the vertices changed since.
    ChangedVertices angle_changes_;
    const double cleanup_angle_margin_cos_;  // face_angle_below
    std::vector<FaceHandle> faces_under_angle_;
};

}  // namespace hdimesh::surface::detail
