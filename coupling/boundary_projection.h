#pragma once
// Keeps the boundary vertices of a tet mesh on the model of the input boundary (paper §4,
// coupling/boundary_model.h): after every refinement pass the new boundary vertices are
// projected onto it, never inverting a tet.

#include <vector>

#include "common/parallel.h"
#include "coupling/boundary_model.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::coupling
{

struct ProjectionOptions
{
    hdi::HdiOptions model;  ///< the meshfree model's neighbours, weights, tolerances
    /// A move that would push a tet's quality below this is shortened (halved until valid).
    double min_quality_after_move = 1e-3;
    int max_halvings = 6;
    /// A target farther than this fraction of the vertex's shortest edge is a fit gone wrong
    /// (neighbours from another sheet): the vertex stays, counted as failed. A new vertex at
    /// the midpoint of an edge 2s long is s/(2R) s from a surface of radius R it samples: this
    /// allows radii down to twice the edge.
    double max_move_fraction = 0.25;
    /// The model's queries run on these threads (null: one); the moves are made in the list's
    /// order on the calling thread, so the result does not depend on them.
    Workers* workers = nullptr;
    /// A surface vertex whose boundary faces lie in one plane stays: a flat boundary has no
    /// curvature for the model to add (in a metric, its stretched triangles make poor fits).
    bool keep_flat = false;
};

struct ProjectionReport
{
    int projected = 0;  ///< vertices moved all the way onto the model
    int shortened = 0;  ///< vertices moved only part of the way (an incident tet would invert)
    int failed = 0;     ///< the model gave no projection (status Failed), or a far one
    double max_remaining_distance = 0;  ///< of the shortened vertices, from the model
};

/// The guarded projection of tet-mesh vertices onto the boundary's model.
class BoundaryProjector
{
public:
    /// `model` must outlive the projector.
    BoundaryProjector(const BoundaryModel& model, const ProjectionOptions& options = {})
        : options_(options), model_(model)
    {
    }

    /// Moves each listed Surface/Ridge vertex onto the model (Ridge vertices onto the ridge
    /// fit; Corner and Interior vertices, required ones and those of required triangles are
    /// left alone). Vertex balls are walked over the
    /// adjacency (built here if missing); positions change, topology does not.
    ProjectionReport project(volume::TetMesh& mesh, const std::vector<int>& vertices) const;

    /// Projects every Surface/Ridge vertex of the mesh (finishes earlier shortened moves).
    ProjectionReport project_all(volume::TetMesh& mesh) const;

private:
    ProjectionOptions options_;
    const BoundaryModel& model_;
};

}  // namespace hdimesh::coupling
