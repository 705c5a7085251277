#pragma once
// A ridge or boundary vertex moved along its curve to where its two chords follow the input
// polyline best: the worst distance both ways (input points to the output, the output's samples
// to the input) around it is smallest. The cure for a scan's zig-zag open boundary, where chords
// between points of the polyline cut the zigs: no split helps there (each new chord cuts the
// next zig), but output vertices on the zig extremes do.

#include <vector>

#include "surface/local_ops.h"

namespace hdimesh::surface
{

/// The tolerance: only the excess over it is minimized. The witnesses (the input's vertices and
/// edge midpoints around the star) give the distances in->out; those on v's curve between its
/// curve neighbours are also the candidate positions.
struct CurveFitOptions : WitnessedMoveOptions
{
    int samples = 8;  // besides the witnesses: trial points toward each curve neighbour
};

/// Moves ridge or boundary vertex v along its curve (candidates: the witnesses on its curve
/// between its curve neighbours, and points toward them) to the position with the smallest
/// worst excess over the tolerance of the witnesses' distances to the output's 2-ring of v and
/// of the star's edge midpoints and centroids to the model (ties: the smallest sum of excesses).
/// Done only when that improves, no triangle of the star folds, turns too far or loses its
/// angles, and the star's edges keep the length band.
OpResult fit_curve_vertex(OperatorContext& ctx, VertexHandle v, const CurveFitOptions& options);

}  // namespace hdimesh::surface
