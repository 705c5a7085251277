#pragma once
// The size fields of a volume meshed from a surface: sizes known on the surface carried into
// the volume, and the field for a kept surface. They need the surface model and the kNN index,
// so they live here rather than with the volume's fields (volume/size/size_fields.h).

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <unordered_set>
#include <vector>

#include "common/size_field.h"
#include "hdi/knn.h"
#include "surface/surface_mesh.h"
#include "surface/surface_model.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::coupling::detail
{

using surface::SurfaceMesh;
using volume::TetMesh;

/// A size known on a surface carried into the volume: the size at the closest surface point,
/// interpolated on its triangle.
class ClosestSurfaceSize : public SizeField
{
public:
    ClosestSurfaceSize(const SurfaceMesh& surface, std::vector<double> vertex_sizes)
        : model_(surface), sizes_(std::move(vertex_sizes))
    {
    }
    double size(const Vec3& p) const override
    {
        return model_.interpolate(surface::to_vec3d(p), sizes_);
    }

private:
    surface::SurfaceModel model_;
    std::vector<double> sizes_;
};

/// The field for a kept surface. No boundary edge is ever too long: refinement (which measures
/// an edge at size_at_midpoint) then splits interior edges only, and the boundary stays the
/// given triangles (an interior edge never has a boundary edge's midpoint). And beside a kept
/// edge too long for the field, the interior may be as coarse, grading down to the field away
/// from it: the tets on a long kept triangle have long edges whatever is done, and splitting
/// them only stacks slivers on it, pass after pass.
class KeptSurfaceSize : public SizeField
{
public:
    KeptSurfaceSize(std::shared_ptr<const SizeField> field, const TetMesh& mesh)
        : field_(std::move(field))
    {
        std::vector<double> longest(mesh.points.size(), 0.0);
        midpoints_.reserve(3 * mesh.triangles.size());
        for (const auto& t : mesh.triangles)
            for (int k = 0; k < 3; ++k)
            {
                const Vec3 &a = mesh.points[t[k]], &b = mesh.points[t[(k + 1) % 3]];
                size_at_midpoint(
                    [&](const Vec3& p) {
                        const Key k = key(p);
                        midpoints_.insert(k);
                        const std::size_t bit = filter_bit(k);
                        filter_[bit / 64] |= std::uint64_t{1} << (bit % 64);
                        return 0.0;
                    },
                    a, b);
                const EdgeInField edge = measure_edge(*field_, a, b);
                if (edge.too_long())
                    for (int v : {t[k], t[(k + 1) % 3]})
                        longest[v] = std::max(longest[v], edge.length);
            }
        std::vector<Vec3> ends;
        double reach = 0;  // no end lifts the size farther than its length over the grade
        for (std::size_t v = 0; v < longest.size(); ++v)
            if (longest[v] > 0)
            {
                ends.push_back(mesh.points[v]);
                end_length_.push_back(longest[v]);
                reach = std::max(reach, longest[v] / kGrade);
                reach_lo_ = reach_lo_.cwiseMin(mesh.points[v]);
                reach_hi_ = reach_hi_.cwiseMax(mesh.points[v]);
            }
        if (ends.empty()) return;
        reach_lo_ -= Vec3::Constant(reach);
        reach_hi_ += Vec3::Constant(reach);
        long_edge_ends_ = std::make_unique<hdi::KnnIndex>(ends);
    }
    double size(const Vec3& p) const override
    {
        const Key k = key(p);
        const std::size_t bit = filter_bit(k);
        if ((filter_[bit / 64] >> (bit % 64) & 1) && midpoints_.count(k) != 0)
            return std::numeric_limits<double>::max();
        const double wanted = field_->size(p);
        if (!long_edge_ends_ || (p.array() < reach_lo_.array()).any() ||
            (p.array() > reach_hi_.array()).any())
            return wanted;
        int nearest = -1;
        double squared = 0;
        if (long_edge_ends_->nearest(p, 1, &nearest, &squared) < 1) return wanted;
        return std::max(wanted, end_length_[nearest] - kGrade * std::sqrt(squared));
    }

private:
    using Key = std::array<double, 3>;
    // + 0.0 makes -0.0 into 0.0: the two compare equal, and must hash alike
    static Key key(const Vec3& p) { return {p[0] + 0.0, p[1] + 0.0, p[2] + 0.0}; }
    /// A hash, not a sorted list: the optimizer asks the size of every candidate point.
    struct KeyHash
    {
        std::size_t operator()(const Key& k) const
        {
            std::uint64_t h = 0x9e3779b97f4a7c15ull;
            for (double x : k)
            {
                std::uint64_t bits;
                std::memcpy(&bits, &x, sizeof bits);
                h = (h ^ bits) * 0x100000001b3ull;
                h ^= h >> 29;
            }
            return static_cast<std::size_t>(h);
        }
    };
    static constexpr double kGrade = 0.3;  // size lost per unit distance from a long edge's end
    // One bit per hash of the midpoints, in cache: most queried points are none, and the bit
    // says so without the set's scattered buckets.
    static constexpr std::size_t kFilterBits = std::size_t{1} << 20;
    static std::size_t filter_bit(const Key& k) { return KeyHash()(k) & (kFilterBits - 1); }
    std::shared_ptr<const SizeField> field_;
    std::unordered_set<Key, KeyHash> midpoints_;
    std::vector<std::uint64_t> filter_ = std::vector<std::uint64_t>(kFilterBits / 64, 0);
    std::unique_ptr<hdi::KnnIndex> long_edge_ends_;  // the ends of boundary edges too long
    std::vector<double> end_length_;                 // per end: its longest such edge
    Vec3 reach_lo_ = Vec3::Constant(std::numeric_limits<double>::infinity());  // where an end
    Vec3 reach_hi_ = -reach_lo_;  // may lift the size: their box, widened by the reach
};

}  // namespace hdimesh::coupling::detail
