#pragma once
// Triangle quality in real space (paper §5): shape Qe = 2√3·ρ/h (inradius over longest edge, 1
// for an equilateral triangle), angles, edge size quality Qt, and the two-sided Hausdorff
// distance between two surfaces. Used by the operators' quality layer and by the reports.

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "common/size_quality.h"
#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

/// triangle_qe from the lengths |b - a|, |c - b|, |a - c| and |(b - a) × (c - a)|, with its
/// arithmetic: a caller that has them already (a shift's trials share most of them) gets the
/// same bits. (An edge's length does not depend on its direction: x - y is exactly -(y - x).)
inline double triangle_qe_from(double lab, double lbc, double lca, double cross_norm)
{
    const double longest = std::max({lab, lbc, lca});
    const double perimeter = lab + lbc + lca;
    const double area = 0.5 * cross_norm;
    if (!(longest > 0.0) || !(perimeter > 0.0)) return 0.0;
    const double inradius = 2.0 * area / perimeter;
    return 2.0 * std::sqrt(3.0) * inradius / longest;
}
/// Qe of the triangle (a, b, c): 2√3 · inradius / longest edge; 0 for a degenerate one.
/// (Inline, like triangle_normal: every operator's quality layer calls them per trial triangle.)
inline double triangle_qe(const Vec3d& a, const Vec3d& b, const Vec3d& c)
{
    return triangle_qe_from((b - a).norm(), (c - b).norm(), (a - c).norm(),
                            OpenMesh::cross(b - a, c - a).norm());
}
/// Smallest interior angle of (a, b, c) in degrees (0 for a degenerate triangle).
double triangle_min_angle_deg(const Vec3d& a, const Vec3d& b, const Vec3d& c);
/// The three interior angles in degrees, at a, b, c.
std::array<double, 3> triangle_angles_deg(const Vec3d& a, const Vec3d& b, const Vec3d& c);
/// Unit normal of (a, b, c), zero for a degenerate triangle.
inline Vec3d triangle_normal(const Vec3d& a, const Vec3d& b, const Vec3d& c)
{
    Vec3d n = OpenMesh::cross(b - a, c - a);
    const double len = n.norm();
    return len > 0.0 ? n / len : Vec3d(0, 0, 0);
}
/// Qe of a face of the mesh.
double face_qe(const SurfaceMesh& mesh, FaceHandle f);
/// Edge size quality Qt = min(h/L, L/h) (common/size_quality.h), 0 for a length or size ≤ 0.
/// The surface's h is the mean of the edge's two end sizes, not the size at its midpoint.
inline double size_quality(double length, double size)
{
    if (length <= 0.0 || size <= 0.0) return 0.0;
    return hdimesh::size_quality(length, size);
}

/// The topology a remesher must keep: counts, connected components (through edges) and loops
/// of boundary edges (holes). Compare two meshes with ==.
struct SurfaceTopology
{
    long vertices = 0, edges = 0, faces = 0;
    int components = 0, boundary_loops = 0;
    long euler() const { return vertices - edges + faces; }
    bool operator==(const SurfaceTopology& o) const
    {
        return euler() == o.euler() && components == o.components &&
               boundary_loops == o.boundary_loops;
    }
    bool operator!=(const SurfaceTopology& o) const { return !(*this == o); }
};

/// \pre no deleted elements (after garbage_collection()).
SurfaceTopology measure_topology(const SurfaceMesh& mesh);

/// Everything the before/after table of surfremesh prints.
struct QualityReport
{
    std::size_t vertices = 0, faces = 0, edges = 0;
    double qe_min = 0.0, qe_mean = 0.0;
    std::array<std::size_t, 10> qe_histogram{};  // Qe in tenths
    double percent_qe_ge_07 = 0.0;
    double min_angle_deg = 0.0, max_angle_deg = 0.0;
    double percent_all_angles_ge_25 = 0.0;
    double percent_qt_ge_066 = 0.0;  // edges, against the vertex sizes (average of the ends)
    double percent_too_long = 0.0, percent_too_short = 0.0;
    double hausdorff_to_model = -1.0;    // max over output samples of distance to the reference
    double hausdorff_from_model = -1.0;  // max over reference samples of distance to the output
    double diagonal = 0.0;               // bounding-box diagonal of the measured mesh
    double hausdorff() const { return std::max(hausdorff_to_model, hausdorff_from_model); }
};

/// Quality of `mesh`; Qt against `uniform_size` if > 0, else against the vertex size property
/// (average of the two ends; Qt figures stay 0 without sizes). Hausdorff fields stay -1 (see
/// hausdorff_distance).
QualityReport measure_quality(const SurfaceMesh& mesh, double uniform_size = 0.0);

/// One-sided distances between two triangle surfaces, sampled at vertices, edge midpoints and
/// face centroids of each (the same samples as ../shared/tools/surfstat.py), exact
/// point-to-triangle distance. Returns {max dist of a's samples to b, of b's samples to a}.
std::array<double, 2> hausdorff_distance(const SurfaceMesh& a, const SurfaceMesh& b);

/// A sample of one surface and its distance to another (diagnostics of the Hausdorff distance).
struct DistanceSample
{
    Vec3d point{0, 0, 0};    // the sample (vertex, edge midpoint or centroid of the first surface)
    Vec3d closest{0, 0, 0};  // its closest point on the second surface
    double distance = 0.0;
};

/// The `count` samples of `a` (the samples of hausdorff_distance) farthest from `b`, worst first.
std::vector<DistanceSample> farthest_samples(const SurfaceMesh& a, const SurfaceMesh& b,
                                             std::size_t count);

/// A fixed-width text table comparing two reports (surfremesh prints it).
std::string format_quality_table(const QualityReport& before, const QualityReport& after);

/// Bounding-box diagonal of the mesh's vertices.
double bounding_box_diagonal(const SurfaceMesh& mesh);

}  // namespace hdimesh::surface
