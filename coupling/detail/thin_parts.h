#pragma once
// Sizes on thin parts of a solid (ears, fins, fingers): bounded by the thickness there
// (surface/thickness.h), so that a few layers of tets fit across and none is flattened between
// the two sides. The bounds go to the surface remesher; the volume field is the given one,
// lowered near the bounded vertices.

#include <array>
#include <memory>
#include <vector>

#include "common/parallel.h"
#include "common/size_field.h"
#include "surface/surface_mesh.h"

namespace hdimesh::coupling::detail
{

struct ThinPartOptions
{
    /// A size at most thickness / this. Two: the tets across a part are at least two
    /// layers deep, so none has all four vertices on the boundary there.
    double thickness_per_size = 2.0;
    /// ... but never below this fraction of the size it bounds (a needle would ask for millions).
    double min_fraction = 0.125;
    Workers* workers = nullptr;  ///< thickness rays and the volume field's grid on these threads
};

struct ThinParts
{
    std::vector<double> bounds;  ///< per input vertex; infinity where none; empty: no thin part
    std::vector<Vec3> points;    ///< the bounded vertices
    std::vector<double> sizes;   ///< ... their bounds
    double reach = 0.0;          ///< farthest a bound lowers the field, graded
};

/// The bounds at the vertices of `input` (closed, outward) where the part is thinner than
/// thickness_per_size times `sizes` (the size wanted at each vertex); `grade` = hgrad - 1.
ThinParts find_thin_parts(const surface::SurfaceMesh& input, const std::vector<double>& sizes,
                          double grade, const ThinPartOptions& options = {});

/// A field lowered near thin parts: the least of the base field and, over the bounded vertices,
/// their bound grown by `grade` per unit distance. A grid of cells over the bounded vertices'
/// reach lists, per cell, the vertices that can give the least in it, so a lookup scans a few.
class ThinPartSize : public SizeField
{
public:
    ThinPartSize(std::shared_ptr<const SizeField> base, const ThinParts& thin, double grade,
                 Workers* workers = nullptr);
    double size(const Vec3& p) const override;

private:
    std::shared_ptr<const SizeField> base_;
    std::vector<Vec3> points_;
    std::vector<double> sizes_;
    double grade_;
    Vec3 lo_ = Vec3::Zero();  // the grid's corner: the bounded vertices' box less the reach
    double cell_ = 1.0;       // the cells' side
    std::array<int, 3> n_{};  // cells per axis (all 0: no bounded vertex)
    std::vector<int> start_;  // cell c's candidates: candidates_[start_[c] .. start_[c + 1])
    std::vector<int> candidates_;
    std::vector<double> lower_;  // per candidate, the least it can give in its cell (ascending)
};

}  // namespace hdimesh::coupling::detail
