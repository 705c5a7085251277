#pragma once
// The kernel of a closed, outward set of faces (the points that see every face from inside) and
// the cone from one of its points: shared by the kernel fan (stage 2) and the exhaustive search,
// which offers the same point as an optional Steiner point.

#include <vector>

#include "volume/fill/fill_common.h"

namespace hdimesh::volume::detail
{

/// The positive tet on outward face `face` with apex `apex` on its inner side.
inline TetVertices cone_tet(const Triangle& face, int apex)
{
    return {face[0], face[2], face[1], apex};
}

/// Chebyshev centre of the kernel: the point farthest from every face plane on the inner side
/// (a 3-variable LP), and that distance; the faces need not be closed (the search is kept in
/// their bounding box). Returns false when the kernel has no interior, or is thinner than
/// round-off can resolve at the faces' size.
bool kernel_chebyshev_centre(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                             Vec3& centre, double& radius);

/// The kernel point whose cone has the best worst Qe, found from the Chebyshev centre by a
/// search that never leaves the kernel; every cone tet is checked positive exactly. Any set of
/// faces (a part of a cavity too). Returns false when the kernel is empty (or no checked point
/// exists).
bool best_kernel_point(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                       Vec3& point, double& worst_quality);

/// The exhaustive search with a known lower bound: only fills whose worst Qe is above
/// `quality_floor` are looked for (fill_small_cavity passes the best fill of the earlier
/// stages). Otherwise as fill_exhaustive.
bool fill_exhaustive_above(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                           const CavityOptions& options, double quality_floor, CavityFill& fill);

}  // namespace hdimesh::volume::detail
