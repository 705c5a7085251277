#pragma once
// The thickness of a closed solid at its surface vertices: how far a ray along the inward
// normal travels inside before it leaves through the opposite side. The coupling bounds the
// sizes on thin parts (ears, fins, fingers) by it (coupling/mesh_from_surface.cpp).

#include <vector>

#include "common/parallel.h"
#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

struct ThicknessOptions
{
    /// Hits nearer than this fraction of the bbox diagonal are the start's own sheet.
    double self_fraction = 1e-9;
    Workers* workers = nullptr;  ///< the rays cast on these threads (null: this one)
};

/// Per vertex of `mesh` (faces oriented outward, no deleted elements): the distance along the
/// inward vertex normal (area-weighted) to the first triangle, not one around the vertex,
/// through which the ray leaves the solid (its normal along the ray); infinity where none.
std::vector<double> thickness_at_vertices(const SurfaceMesh& mesh,
                                          const ThicknessOptions& options = {});

}  // namespace hdimesh::surface
