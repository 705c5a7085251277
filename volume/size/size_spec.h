#pragma once
// A size field as a user states it: Mmg's options (--hsiz, --sol, --hmin, --hmax, --hgrad),
// the paper's benchmark cases, or sizes given at the input's vertices (a .sol, or a numpy
// array). The command-line tools and the Python module make their field here, so both read
// the same options the same way.

#include <memory>
#include <vector>

#include "common/size_field.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

struct SizeSpec
{
    double hsiz = 0;                   ///< > 0: constant size
    std::vector<double> vertex_sizes;  ///< non-empty: one size per input vertex
    /// non-empty: one metric per input vertex, 6 values in Medit's order (m11 m12 m22 m13 m23
    /// m33): the field is anisotropic
    std::vector<double> vertex_metrics;
    char benchmark = 0;         ///< 'A'..'E': the paper's three-cylinder field
    double hmin = 0, hmax = 0;  ///< bounds; 0: none
    double hgrad = 0;           ///< > 1: size ratio bound between neighbours; 0: none

    bool any() const
    {
        return hsiz > 0 || !vertex_sizes.empty() || !vertex_metrics.empty() || benchmark != 0;
    }
};

/// The field `spec` describes over `input` (the mesh the vertex sizes belong to). With no size
/// given: the input's own sizes (mean length of the edges at each vertex, linear in each tet),
/// so an optimize-only run keeps them. hmin/hmax clamp; hgrad bounds the size ratio between
/// neighbouring vertices (Mmg's H-correction) on the input's vertices: for vertex sizes the
/// corrected values are the field, for an analytic field the field becomes
/// min(analytic, graded samples), so it keeps its own resolution and gradation only ever
/// shrinks sizes. Vertex metrics are interpolated log-Euclidean (volume/size/metric_fields.h),
/// graded by hgrad as Mmg grades metrics and bounded by hmin/hmax in every direction.
/// Throws InputError on conflicting or invalid values (naming the option).
std::shared_ptr<const SizeField> make_size_field(const SizeSpec& spec, const TetMesh& input);

}  // namespace hdimesh::volume
