#pragma once
// Feature detection on a surface mesh: the rules of hdi/features.h (ridges, corners, open
// boundary curves) applied to the mesh's own arrays, their answer written into the vertex class
// and the curve ids of vertices and edges (surface/surface_mesh.h).

#include "hdi/features.h"
#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

using FeatureOptions = hdi::FeatureOptions;
using FeatureSummary = hdi::FeatureSummary;

/// Classifies every vertex and edge of `mesh` (no deleted elements). Curves are numbered
/// 0..curves-1 in the order of the mesh's edges; a curve runs between corners or is a closed
/// loop; face refs that differ across an edge make it a curve.
FeatureSummary detect_features(SurfaceMesh& mesh, const FeatureOptions& options = {});

}  // namespace hdimesh::surface
