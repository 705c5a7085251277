#pragma once
// The concrete size fields behind the SizeField interface (volume/mesh/size_field.h) and the
// Mmg-style treatments of a field given at mesh vertices: --hmin/--hmax clamping and --hgrad
// gradation.

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "common/size_field.h"
#include "volume/mesh/point_locator.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// The same size everywhere (--hsiz). Throws InputError unless h is finite and > 0.
class ConstantSize : public SizeField
{
public:
    explicit ConstantSize(double h);
    double size(const Vec3&) const override { return h_; }

private:
    double h_;
};

/// The paper's benchmark field (method.md §2): sphere of radius R at the origin, three
/// cylinders of radius r around the x, y and z axes.
struct BenchmarkFieldParams
{
    double dmin, r, dmax = 1.0 / 3, R = 1.0;
};

/// Cases 'A'..'E' of method.md §2 (dmin/R, r/R; dmax = R/3, R = 1), lower case accepted.
/// Throws InputError for any other name.
BenchmarkFieldParams benchmark_case(char name);

/// Per cylinder d = |distance to axis - r|, h_c = (1 - d/R) dmin + (d/R) dmax clamped to at
/// most dmax; h = min over the three cylinders. Exactly ../shared/tools/meshstat.py size_field().
class BenchmarkSize : public SizeField
{
public:
    /// Throws InputError unless 0 < dmin <= dmax, r >= 0 and R > 0 (all finite).
    explicit BenchmarkSize(const BenchmarkFieldParams& params);
    double size(const Vec3& p) const override;
    const BenchmarkFieldParams& params() const { return params_; }

private:
    BenchmarkFieldParams params_;
};

/// Sizes at the vertices of a tet mesh, linear inside each tet. Outside the mesh: the size at
/// the nearest boundary point (linear on that boundary triangle). Keeps its own copy of the
/// mesh, so the mesh it was built from may then be adapted freely (.sol on the input mesh).
/// Const queries are safe from several threads.
class BackgroundMeshSize : public SizeField
{
public:
    /// Throws InputError when sizes.size() != mesh.num_vertices(), a size used by a tet is not
    /// finite and > 0 (naming the vertex), or the mesh cannot be located in (see TetLocator).
    BackgroundMeshSize(const TetMesh& mesh, std::vector<double> vertex_sizes);
    double size(const Vec3& p) const override;
    const TetLocator& locator() const { return locator_; }

private:
    double locate_size(const Vec3& p) const;

    TetLocator locator_;
    std::vector<double> sizes_;
    std::uint64_t id_;  // keys this field's answers in the per-thread table of size()
};

/// Another field times a constant factor (a coarser stage of the same field). Holds a
/// reference: the field must outlive it.
class ScaledSize : public SizeField
{
public:
    ScaledSize(const SizeField& field, double factor) : field_(field), factor_(factor) {}
    double size(const Vec3& p) const override { return factor_ * field_.size(p); }
    bool anisotropic() const override { return field_.anisotropic(); }
    Metric metric(const Vec3& p) const override { return field_.metric(p) / (factor_ * factor_); }

private:
    const SizeField& field_;
    double factor_;
};

/// Another field clamped into [hmin, hmax] (--hmin, --hmax).
class ClampedSize : public SizeField
{
public:
    /// Throws InputError unless inner is set and 0 <= hmin <= hmax (hmax may be +infinity).
    ClampedSize(std::shared_ptr<const SizeField> inner, double hmin, double hmax);
    double size(const Vec3& p) const override;

private:
    std::shared_ptr<const SizeField> inner_;
    double hmin_, hmax_;
};

/// The sizes a cavity's own faces ask for, when no field is given: each input vertex's mean
/// incident edge length, blended by inverse distance, so that sizes cannot drift down as the
/// front's faces shrink (the front would then never close).
class InputSizeField final : public SizeField
{
public:
    void build(const std::vector<Vec3>& points, const std::vector<Triangle>& faces)
    {
        const int n = static_cast<int>(points.size());
        std::vector<double> sum(n, 0.0);
        std::vector<int> count(n, 0);
        for (const Triangle& t : faces)
            for (int k = 0; k < 3; ++k)
            {
                const double length = (points[t[k]] - points[t[(k + 1) % 3]]).norm();
                sum[t[k]] += length;
                sum[t[(k + 1) % 3]] += length;
                count[t[k]] += 1;
                count[t[(k + 1) % 3]] += 1;
            }
        // a large input is sampled evenly: the blend is smooth and the query stays cheap
        const int step = std::max(1, n / kMaxSamples);
        samples_.clear();
        sizes_.clear();
        for (int v = 0; v < n; v += step)
            if (count[v] > 0)
            {
                samples_.push_back(points[v]);
                sizes_.push_back(sum[v] / count[v]);
            }
    }

    double size(const Vec3& p) const override
    {
        double weighted = 0, total = 0;
        for (std::size_t k = 0; k < samples_.size(); ++k)
        {
            const double d2 = (samples_[k] - p).squaredNorm();
            const double w = 1.0 / (d2 * d2 + 1e-300);
            weighted += w * sizes_[k];
            total += w;
        }
        return weighted / total;
    }

private:
    static constexpr int kMaxSamples = 1024;
    std::vector<Vec3> samples_;
    std::vector<double> sizes_;
};

/// How many tets the field asks for: each live tet's volume over the volume of a regular tet of
/// the size at its centroid, summed. A guard against sizes far below the model's scale.
double expected_tet_count(const TetMesh& mesh, const SizeField& field);

/// The most tets a mesh may reach: their faces are numbered 4·tet + face in 32 bits.
inline constexpr double kMaxTets = 5.0e8;

/// The field sampled at every vertex of the mesh (e.g. before grade_vertex_sizes).
std::vector<double> sample_vertex_sizes(const TetMesh& mesh, const SizeField& field);

/// Mmg's --hgrad: sizes at mesh vertices corrected so that along every edge of a live tet the
/// ratio stays bounded: h_j <= h_i + (hgrad-1)*|x_i-x_j| (Borouchaki's H-correction). Sizes
/// only decrease. Solved to the exact fixed point in one Dijkstra pass (the corrected size is
/// a shortest-path distance with the input sizes as sources). Throws InputError when
/// sizes.size() != mesh.num_vertices() or hgrad is not finite and >= 1.
void grade_vertex_sizes(const TetMesh& mesh, std::vector<double>& sizes, double hgrad);

}  // namespace hdimesh::volume
