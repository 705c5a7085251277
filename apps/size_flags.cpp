// The size-field flags of the tet tools, turned into a volume size field.
#include "size_flags.h"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "common/sol_io.h"
#include "volume/size_fields.h"
#include "volume/tet_tables.h"

namespace hdimesh::cli
{

using volume::BackgroundMeshSize;
using volume::benchmark_case;
using volume::BenchmarkSize;
using volume::ClampedSize;
using volume::ConstantSize;
using volume::grade_vertex_sizes;
using volume::sample_vertex_sizes;
using volume::SizeField;
using volume::TetMesh;
using volume::Vec3;
namespace tet = volume::tet;

namespace
{

/// The pointwise minimum of two fields (gradation only shrinks sizes).
class MinimumSize : public SizeField
{
public:
    MinimumSize(std::shared_ptr<const SizeField> a, std::shared_ptr<const SizeField> b)
        : a_(std::move(a)), b_(std::move(b))
    {
    }
    double size(const Vec3& p) const override { return std::min(a_->size(p), b_->size(p)); }

private:
    std::shared_ptr<const SizeField> a_, b_;
};

/// Mean length of the tet edges at each vertex (each edge counted once per tet: good enough
/// for a size, and O(n) without an edge table).
std::vector<double> mean_incident_edge_length(const TetMesh& mesh)
{
    std::vector<double> sum(mesh.num_vertices(), 0.0);
    std::vector<int> count(mesh.num_vertices(), 0);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        for (const auto& e : tet::kEdgeVertices)
        {
            const int a = mesh.tets[t][e[0]], b = mesh.tets[t][e[1]];
            const double length = (mesh.points[a] - mesh.points[b]).norm();
            sum[a] += length;
            sum[b] += length;
            ++count[a];
            ++count[b];
        }
    }
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (count[v] > 0) sum[v] /= count[v];
    return sum;
}

}  // namespace

void SizeFlags::add_to(CommandLine& cli, bool with_bounds)
{
    SizeOptions::add_to(cli, with_bounds);
    cli.option("--bench-field", &bench_field,
               "the paper's three-cylinder field, case A, B, C, D or E");
}

std::shared_ptr<const SizeField> SizeFlags::make(const TetMesh& input) const
{
    const int given = int(hsiz_set) + int(sol_set) + int(!bench_field.empty());
    if (given > 1) throw UsageError("give only one of --hsiz, --sol and --bench-field");
    if (hsiz_set && !(hsiz > 0)) throw UsageError("--hsiz must be positive");
    if (hmin < 0 || hmax < 0) throw UsageError("--hmin and --hmax must be positive");
    if (hmin > 0 && hmax > 0 && hmin > hmax) throw UsageError("--hmin is larger than --hmax");
    // <= 0: no gradation, as Mmg's -hgrad -1
    if (hgrad > 0 && !(hgrad > 1)) throw UsageError("--hgrad must be larger than 1 (or -1: none)");
    if (bench_field.size() > 1) throw UsageError("--bench-field expects one letter A-E");

    std::shared_ptr<const SizeField> field;
    bool at_vertices = false;  // the field is already a graded-able background over input
    std::vector<double> vertex_sizes;
    if (hsiz_set)
    {
        field = std::make_shared<ConstantSize>(hsiz);
    }
    else if (!bench_field.empty())
    {
        field = std::make_shared<BenchmarkSize>(benchmark_case(bench_field[0]));
    }
    else
    {
        if (sol_set)
            vertex_sizes = read_sol_sizes(sol, input.num_vertices());
        else
        {
            vertex_sizes = mean_incident_edge_length(input);
            for (std::size_t v = 0; v < vertex_sizes.size(); ++v)
                if (!(vertex_sizes[v] > 0))
                    throw InputError("input mesh: size at vertex " + std::to_string(v + 1) +
                                     " is not positive");
        }
        at_vertices = true;
    }

    if (hgrad > 0)
    {
        if (!at_vertices) vertex_sizes = sample_vertex_sizes(input, *field);
        grade_vertex_sizes(input, vertex_sizes, hgrad);
    }
    if (at_vertices || hgrad > 0)
    {
        auto background = std::make_shared<BackgroundMeshSize>(input, vertex_sizes);
        field =
            field
                ? std::shared_ptr<const SizeField>(std::make_shared<MinimumSize>(field, background))
                : background;
    }
    if (hmin > 0 || hmax > 0)
        field = std::make_shared<ClampedSize>(
            field, hmin, hmax > 0 ? hmax : std::numeric_limits<double>::infinity());
    return field;
}

}  // namespace hdimesh::cli
