#pragma once
// The stages of the cavity cascade (volume/fill/cavity.h), each on its own: a closed, outward set
// of faces over `points` in, a fill out. Every stage writes tets with the ids of CavityFill
// (new points after points.size()) and sets worst_quality; a stage that finds no valid fill
// returns false and leaves `fill` as it was. Validity is exact (volume/mesh/predicates.h).

#include <vector>

#include "volume/fill/fill_common.h"

namespace hdimesh::volume::detail
{

/// Stage 1: the cone from the cavity vertex that sees every face not incident to it, the one
/// with the best worst Qe (ties: smaller id).
bool fill_by_vertex_fan(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                        CavityFill& fill);

/// Stage 2: the cone from one new point in the kernel (the intersection of the faces' inner
/// half-spaces): the Chebyshev centre from a 3-variable LP, then moved inside the kernel to
/// raise the worst Qe.
bool fill_by_kernel_fan(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                        CavityFill& fill);

/// Stage 3: branch and bound over the tetrahedralizations of the cavity's points (plus the
/// kernel point when the kernel is not empty), at most options.max_exhaustive_points points and
/// options.exhaustive_node_budget nodes. Returns the max-min-Qe fill found.
bool fill_exhaustive(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                     const CavityOptions& options, CavityFill& fill);

/// The cascade's stages 1-3 on a small closed group, best fill kept (advance_front's leftovers
/// use it): returns false when none fills it.
bool fill_small_cavity(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                       const CavityOptions& options, CavityFill& fill);

}  // namespace hdimesh::volume::detail
