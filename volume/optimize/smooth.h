#pragma once
// Vertex smoothing of free (interior) vertices, two moves tried in turn:
//  1. George's nodal shifting: every tet of the ball proposes the point that would make it
//     regular over its opposite face; the proposals are averaged with weights 1/Qe^2 (the bad
//     tets pull hardest) and the vertex steps toward that point (full, half, quarter step);
//  2. a max-min optimization-based move (Freitag's): the steepest common ascent of the tets
//     near the worst quality, with a backtracking line search on the ball's true minimum.
// A move is kept only when the ball's worst quality rises and no edge of the vertex becomes
// too long or too short for context.field (a candidate point that would make one is first
// pulled radially back into the size band), and the ball's smallest dihedral angle does not
// fall below min(its old value, options.min_dihedral_deg).
//
// A third move serves the sizes, not the shapes: equalize_edge_sizes pulls a vertex so that
// its edges approach their target lengths (each neighbour x proposes the point at distance
// hth from x toward the vertex), kept when the worst Qt of its edges rises and the ball's
// worst shape stays above a floor.

#include <array>
#include <vector>

#include "volume/mesh/tet_topology.h"

namespace hdimesh::volume
{

struct SmoothOptions
{
    bool nodal_shifting = true;
    bool optimization_based = true;
    int max_ascent_steps = 3;     ///< iterations of the max-min move
    double active_band = 0.02;    ///< tets within this Qe of the worst steer the max-min move too
    bool size_projection = true;  ///< a point the sizes refuse is pulled back into their band
    double good_enough = 1.0;     ///< skip the max-min move once the ball's worst reaches this
    double min_gain = 1e-6;       ///< the ball's worst quality must rise by this much
    /// the ball's smallest dihedral angle may fall below its old value only down to this (deg)
    double min_dihedral_deg = 20;
    /// a surface vertex whose boundary is flat (flat_boundary_normal) moves within its plane
    bool in_flat_boundary = false;
};

struct SmoothResult
{
    bool moved = false;
    double worst_before = 0;  ///< worst Qe of the vertex's ball
    double worst_after = 0;
};

struct SizeSmoothOptions
{
    double min_quality = 0.3;  ///< the ball's worst Qe may drop, but not below min(old, this)
    double min_gain = 1e-4;    ///< the worst Qt of the vertex's edges must rise by this much
};

struct PointPlacement
{
    Vec3 point;                 ///< the start when no move beat it
    double worst_at_start = 0;  ///< worst Qe of the tets over `faces` with the vertex at the start
    double worst = 0;           ///< and at `point`
};

/// smooth_vertex's moves for a vertex the mesh does not have yet (an operator simulating an
/// insertion): it would see the triangles `faces`, each with (f0, f1, f2, p) positive on its
/// side, and have an edge to each of their corners. Changes nothing.
PointPlacement place_vertex(const OperatorContext& context,
                            const std::vector<std::array<Vec3, 3>>& faces, const Vec3& start,
                            const SmoothOptions& options = {});

/// Moves free vertex v toward the lengths its edges should have (see above).
SmoothResult equalize_edge_sizes(TetMesh& mesh, OperatorContext& context, int v,
                                 const SizeSmoothOptions& options = {});

/// Smooths vertex v (which must be used by a live tet). Boundary, ridge, corner and required
/// vertices are never moved (the result says moved = false).
SmoothResult smooth_vertex(TetMesh& mesh, OperatorContext& context, int v,
                           const SmoothOptions& options = {});

}  // namespace hdimesh::volume
