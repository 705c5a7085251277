#pragma once
// Collapse of a too-short edge (derefinement, paper §5): the free vertex `from` moves onto its
// neighbour `to`; the tets of the edge disappear and the rest of from's ball is re-attached
// to `to`.
//
//      x-------y               x-------y
//      | \   / |               |\     /|
//      |  from |     ==>       | \   / |      from's ball minus the edge's shell,
//      | /   \ |               |  \ /  |      with from replaced by to
//      z------to               z---to--
//
// Legal only when `from` is interior and free (boundary, ridge, corner, required vertices
// never move, so no boundary triangle changes), from's ball has one ref, every new tet is
// positive with quality >= min(old worst of the ball, options.min_quality), and no new edge
// is too long for context.field.

#include <optional>

#include "volume/mesh/tet_topology.h"

namespace hdimesh::volume
{

struct CollapseOptions
{
    double min_quality = 0.3;  ///< new tets may go below the ball's old worst only down to this
    /// When `to` is free as well and merging onto `to` is refused, try placing the merged
    /// vertex at the edge's midpoint, then at the centre of the vertices it will see (to's
    /// other tets must then pass the same quality floor and no edge of to become too long).
    bool allow_midpoint = true;
    /// `from` may also be a surface vertex (MeshConstraints::is_surface_vertex) whose boundary
    /// faces lie in one plane with one ref, collapsed along a boundary edge in that plane: the
    /// boundary keeps its shape and mesh.triangles follow (a metric's coarsening of a flat
    /// boundary, which no surface pass remeshes).
    bool on_flat_boundary = false;
};

struct CollapseResult
{
    bool collapsed = false;
    /// Worst Qe of from's ball when the test needed it (a new tet below options.min_quality),
    /// else -1: computing it for every attempt would cost more than the attempt.
    double worst_before = -1;
    double worst_after = 0;  ///< worst Qe of the new tets (when they could be formed)
};

/// The unit outward normal of boundary vertex v's star when its boundary faces (the open faces
/// of its ball through it) are listed, share one ref and lie in one plane, and no listed
/// interior face passes through v; with `neighbour`, it must be a vertex of those faces.
std::optional<Vec3> flat_boundary_normal(const TetMesh& mesh, const OperatorContext& context, int v,
                                         int* neighbour = nullptr);

/// Collapses edge (from, to) onto `to` (or, see the options, both onto the midpoint, the
/// vertex kept being `to`) when legal. `from` must be used by a live tet.
CollapseResult collapse_edge(TetMesh& mesh, OperatorContext& context, int from, int to,
                             const CollapseOptions& options = {});

}  // namespace hdimesh::volume
