#pragma once
// The HDI model of an input surface as the smooth projection of a SurfaceModel: smooth vertices
// go onto the meshfree Hermite diffuse surface (method.md §5) instead of the input's facets.
// Feature curves stay the input's own polylines (exact ridge positions).

#include "surface/surface_mesh.h"
#include "surface/surface_model.h"

namespace hdimesh::hdi
{
class HdiSurface;
}

namespace hdimesh::surface
{

/// An HdiSurface as a Projector: smooth vertices onto the diffuse surface, ridge and boundary
/// vertices onto the 1-D fit of the nearest feature line (HdiSurface::project_to_ridge; the
/// curve id is not used, the HDI model has its own lines), corners stay. A failed fit returns
/// ok == false and the operators keep the unprojected point or refuse.
class HdiProjector final : public Projector
{
public:
    explicit HdiProjector(const hdi::HdiSurface& surface) : surface_(surface) {}
    ProjectedPoint project(const Vec3d& p, VertexClass cls, int curve) const override;

private:
    const hdi::HdiSurface& surface_;
};

struct HdiProjectionOptions
{
    int neighbours = 16;
    /// A projection farther than this fraction of the bbox diagonal from the input's facets is
    /// not trusted (a fit across a thin part): the facets are used there instead.
    double max_deviation_fraction = 0.002;
    /// ... or than this fraction of the shortest edge of the facet under it, when larger: a
    /// coarse input's chords lie that far from the smooth surface it samples (0: off).
    double max_deviation_edge_fraction = 0.0;
    /// > 0: the HDI only when most of the input's area is on facets that may stray farther
    /// than this from the smooth surface (SurfaceModel::chord_error: a coarse tessellation of a
    /// smooth shape); otherwise the facets are the finer model, and nothing is installed.
    double coarse_facet_tolerance = 0.0;
};

/// The one rule for a coarse input (surfremesh's default, the coupling's surface pass): `base`
/// with the HDI installed only where the input's facets are too coarse for `tolerance`
/// (coarse_facet_tolerance), trusted a quarter of the facet's shortest edge off it (the sagitta
/// of its chords on a surface of radius twice the edge).
HdiProjectionOptions coarse_input_options(HdiProjectionOptions base, double tolerance);

/// Builds the HDI model of `input` (classified by detect_features: its ridges, boundary curves
/// and corners are handed to the model) and installs it as `model`'s smooth projection; with
/// options.coarse_facet_tolerance, only when the facets are too coarse (nothing is built
/// otherwise). The model keeps its own copy of the input; `model` must outlive nothing else.
void attach_hdi_projection(SurfaceModel& model, const SurfaceMesh& input,
                           const HdiProjectionOptions& options = {});

/// The same with a model built already (e.g. the coupling's, from the same input), which must
/// outlive `model`; options.neighbours is the model's own.
void attach_hdi_projection(SurfaceModel& model, const hdi::HdiSurface& surface,
                           const HdiProjectionOptions& options = {});

}  // namespace hdimesh::surface
