#pragma once
// The target edge length of the surface remesher: uniform (--hsiz), given at the input
// vertices (--sol, read by common/sol_io.h), or curvature-adaptive from a geometric tolerance
// (--hausd, Mmg semantics: a triangle of side h on a surface of curvature k strays about h²k/6 from
// it; with a margin for the curvature estimate, h = √(3·hausd/k)), bounded by hmin/hmax and graded
// by hgrad.

#include <string>
#include <vector>

#include "surface/surface_mesh.h"
#include "surface/surface_model.h"

namespace hdimesh::surface
{

struct SizingOptions
{
    double hsiz = 0.0;   // > 0: uniform size
    double hausd = 0.0;  // > 0 (and hsiz = 0): curvature-adaptive size
    double hmin = 0.0;   // ≤ 0: none
    double hmax = 0.0;   // ≤ 0: none
    double hgrad =
        1.3;  // ≤ 1: no gradation; neighbouring sizes differ by at most (hgrad−1)·distance
};

/// A size at every point of the model: a constant, or per-input-vertex sizes interpolated on the
/// closest input triangle.
class SizeMap
{
public:
    static SizeMap uniform(double size);
    static SizeMap per_input_vertex(const SurfaceModel& model, std::vector<double> sizes);
    /// `face_hint`: an input face near p (SurfaceModel::project_near): the same size, found faster.
    double at(const Vec3d& p, int face_hint = -1) const;
    bool is_uniform() const { return model_ == nullptr; }
    double uniform_size() const { return uniform_; }
    const std::vector<double>& vertex_sizes() const { return sizes_; }

private:
    double uniform_ = 0.0;
    const SurfaceModel* model_ = nullptr;
    std::vector<double> sizes_;
};

/// Sizes at the input vertices from the curvature (smooth vertices: the model's quadric fit;
/// curve vertices: the curve's turning angle per length), then bounded and graded.
std::vector<double> curvature_sizes(const SurfaceMesh& input, const SurfaceModel& model,
                                    const SizingOptions& options);

/// Bounds sizes to [hmin, hmax] and limits their growth along input edges to hgrad.
void bound_and_grade(const SurfaceMesh& input, std::vector<double>& sizes,
                     const SizingOptions& options);

/// Mean edge length of a mesh (the default size when none is given).
double mean_edge_length(const SurfaceMesh& mesh);

}  // namespace hdimesh::surface
