#pragma once
// The last stage of a coupled adapt: boundary vertices of tets still under the quality floor
// slide on the boundary's model to where their ball's worst tet is better. The volume
// optimizer keeps the boundary fixed, so a tet whose poor shape comes from its boundary face
// (a thin part, a face leaning over its neighbour) is otherwise left as it is.

#include "coupling/boundary_model.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::coupling::detail
{

struct BoundaryFloorOptions
{
    double floor = 0.3;          ///< tets under this Qe have their boundary vertices moved
    int steps_per_vertex = 6;    ///< ascent steps per vertex and sweep
    double min_gain = 1e-3;      ///< a move must raise the ball's worst Qe by this
    double max_turn_deg = 20.0;  ///< no boundary face of the ball turns more (the shape kept)
};

struct BoundaryFloorReport
{
    int below = 0;  ///< tets under the floor before the sweep
    int moves = 0;  ///< boundary vertex moves kept
};

/// One sweep: moves the Surface and Ridge vertices of tets under options.floor along the model
/// (Ridge vertices along their ridge fit; corners stay) while their ball's worst Qe rises.
/// Positions change, topology does not. \pre mesh has adjacency.
BoundaryFloorReport raise_boundary_floor(volume::TetMesh& mesh, const BoundaryModel& model,
                                         const BoundaryFloorOptions& options = {});

}  // namespace hdimesh::coupling::detail
