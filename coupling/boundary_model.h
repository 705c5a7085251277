#pragma once
// The input boundary's geometry, built once and shared by the projector and the surface pass:
// the HDI model of the boundary triangles, and for the surface pass the model of the classified
// input surface (its facets, the HDI installed where they are too coarse for the tolerance).
// Once a surface pass has placed the boundary on the latter, smooth points go there too, so the
// refinement's later splits land on the geometry the surface pass used.

#include <memory>
#include <optional>

#include "hdi/features.h"
#include "hdi/hdi_surface.h"
#include "surface/hdi_projection.h"
#include "surface/surface_model.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::coupling
{

/// Where a boundary point goes.
struct BoundaryFoot
{
    hdi::Projection target;
    /// On the surface pass's model, taken however far (the HDI fit's feet are guarded instead).
    bool exact = false;
};

class BoundaryModel
{
public:
    /// The HDI model of mesh.triangles (all boundary and interface triangles), with the mesh's
    /// ridges and corners as features plus those hdi::classify_features finds with `features`.
    BoundaryModel(const volume::TetMesh& mesh, const hdi::FeatureOptions& features,
                  const hdi::HdiOptions& options = {});
    ~BoundaryModel();
    BoundaryModel(const BoundaryModel&) = delete;  // the surface model points into this one
    BoundaryModel& operator=(const BoundaryModel&) = delete;

    const hdi::HdiSurface& hdi() const { return *hdi_; }

    /// Builds the surface pass's model on `input` (classified by detect_features; it must
    /// outlive this), its smooth projection this HDI model where the input's facets stray
    /// farther than `tolerance` from the smooth surface.
    const surface::SurfaceModel& build_surface_model(const surface::SurfaceMesh& input,
                                                     const surface::HdiProjectionOptions& options,
                                                     double tolerance);
    /// From now on smooth points go onto the surface pass's model (after a surface pass).
    void place_on_surface_model() { on_surface_model_ = surface_.has_value(); }

    /// The foot of p, a boundary point of class `cls` (Surface or Ridge): a Surface point on
    /// the surface pass's model once place_on_surface_model() was called, else on the HDI
    /// model (a Ridge point on its ridge fit).
    BoundaryFoot project(const volume::Vec3& p, volume::VertexClass cls) const;

private:
    std::unique_ptr<hdi::HdiSurface> hdi_;
    std::optional<surface::SurfaceModel> surface_;
    bool on_surface_model_ = false;
};

}  // namespace hdimesh::coupling
