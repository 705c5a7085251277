#pragma once
// Keeps the boundary vertices of a tet mesh on the HDI model of the input boundary (paper §4):
// the model is built once from the input's boundary triangles; after every refinement pass
// the new boundary vertices are projected onto it, never inverting a tet.

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "hdi/features.h"
#include "hdi/hdi_surface.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::coupling
{

struct ProjectionOptions
{
    hdi::HdiOptions model;         ///< the meshfree model's neighbours, weights, tolerances
    hdi::FeatureOptions features;  ///< feature detection on the input boundary (as the surface's)
    /// A move that would push a tet's quality below this is shortened (halved until valid).
    double min_quality_after_move = 1e-3;
    int max_halvings = 6;
    /// A target farther than this fraction of the vertex's shortest edge is a fit gone wrong
    /// (neighbours from another sheet): the vertex stays, counted as failed. A new vertex at
    /// the midpoint of an edge 2s long is s/(2R) s from a surface of radius R it samples: this
    /// allows radii down to twice the edge.
    double max_move_fraction = 0.25;
};

struct ProjectionReport
{
    int projected = 0;  ///< vertices moved all the way onto the model
    int shortened = 0;  ///< vertices moved only part of the way (an incident tet would invert)
    int failed = 0;     ///< the model gave no projection (status Failed), or a far one
    double max_remaining_distance = 0;  ///< of the shortened vertices, from the model
};

/// The input boundary's meshfree model, and the guarded projection of tet-mesh vertices onto it.
class BoundaryProjector
{
public:
    /// Builds the model from mesh.triangles (all boundary and interface triangles), with the
    /// mesh's ridges and corners as features plus those hdi::classify_features finds.
    BoundaryProjector(const volume::TetMesh& mesh, const ProjectionOptions& options = {});
    ~BoundaryProjector();

    /// Moves each listed Surface/Ridge vertex onto the model (Ridge vertices onto the ridge
    /// fit; Corner and Interior vertices are left alone). Vertex balls are walked over the
    /// adjacency (built here if missing); positions change, topology does not.
    ProjectionReport project(volume::TetMesh& mesh, const std::vector<int>& vertices) const;

    /// Projects every Surface/Ridge vertex of the mesh (finishes earlier shortened moves).
    ProjectionReport project_all(volume::TetMesh& mesh) const;

    const hdi::HdiSurface& model() const { return *model_; }

    /// Where a Surface vertex goes instead of the HDI model (empty optional: nowhere): the
    /// model a surface pass placed the others on, once it has run (its facets where they are
    /// finer than the HDI fit), so that later splits land on the same geometry. Its feet are
    /// taken however far (max_move_fraction guards the fit only); the tets still shorten them.
    using SurfaceTarget = std::function<std::optional<volume::Vec3>(const volume::Vec3&)>;
    void set_surface_target(SurfaceTarget target) { surface_target_ = std::move(target); }

private:
    ProjectionOptions options_;
    std::unique_ptr<hdi::HdiSurface> model_;
    SurfaceTarget surface_target_;
};

}  // namespace hdimesh::coupling
