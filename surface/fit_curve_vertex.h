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

struct CurveFitOptions
{
    /// Distance both ways that counts as near (the refinement's tolerance): only the excess over
    /// it is minimized.
    double tolerance = 0.0;
    /// No triangle of the star gets an angle under this (a star that had one already: under its worst).
    double min_angle_deg = 30.0;
    /// The star's edges stay within [min_length, max_length] (≤ 0: no bound); an edge out of the
    /// band before may not get farther out.
    double min_length = 0.0, max_length = 0.0;
    /// > 0: an edge already under min_length may get shorter, down to this, when no edge of the
    /// star newly leaves the band (the size quality counts the edges out of it).
    double floor_length = 0.0;
    /// Model points around the star (the input's vertices and edge midpoints): the distances
    /// in->out. Those on v's curve between its curve neighbours are also the candidate positions.
    std::vector<Vec3d> witnesses;
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
