#pragma once
// "Is some triangle within `limit` of p?" answered exactly as detail::within_triangles does,
// without the closest point of a triangle whose bounding box is clearly farther than the limit.
// The tolerance checks (the refinement's near-face proofs, the witnesses of the
// tolerance-keeping changes and of the curve fit) ask it of many points against a score of
// triangles of which one or two are near: the closest points were half of their time.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "surface/local_ops_geometry.h"

namespace hdimesh::surface
{

/// The squared distance beyond which a box is clearly farther than `limit` from p: then so is
/// every point in it, whatever the rounding of a closest point (the margin, relative and
/// absolute at p's magnitude, is far above it), so skipping the exact test changes no answer.
inline double clearly_beyond_squared(const Vec3d& p, double limit)
{
    const double slack = 1e-9 * (limit + std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}));
    return (limit + slack) * (limit + slack);
}

/// Whether triangle t's bounding box is farther from p than sqrt(clearly_beyond2).
inline bool box_clearly_beyond(const Vec3d& p, const std::array<Vec3d, 3>& t, double clearly_beyond2)
{
    double box2 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
        const double below = std::min({t[0][k], t[1][k], t[2][k]}) - p[k], above = p[k] - std::max({t[0][k], t[1][k], t[2][k]});
        const double d = std::max({below, above, 0.0});
        box2 += d * d;
    }
    return box2 > clearly_beyond2;
}

/// detail::within_triangles(p, triangles, limit), the same answer.
inline bool within_triangles_boxed(const Vec3d& p, const std::vector<std::array<Vec3d, 3>>& triangles, double limit)
{
    const double clearly_beyond2 = clearly_beyond_squared(p, limit);
    for (const auto& t : triangles)
        if (!box_clearly_beyond(p, t, clearly_beyond2) && detail::distance_to_triangle(p, t) <= limit) return true;
    return false;
}

/// detail::keeps_witness(w, before, after, bound, slack), the same answer.
inline bool keeps_witness_boxed(const Vec3d& w, const std::vector<std::array<Vec3d, 3>>& before,
                                const std::vector<std::array<Vec3d, 3>>& after, double bound, double slack)
{
    if (within_triangles_boxed(w, after, bound)) return true;
    return !(detail::distance_to_triangles(w, after) > detail::distance_to_triangles(w, before) + slack);
}

}  // namespace hdimesh::surface
