// The size-field flags of the tet tools, turned into a volume size field.
#include "size_flags.h"

#include "common/sol_io.h"
#include "volume/io/tet_io.h"
#include "volume/size/size_spec.h"

namespace hdimesh::cli
{

void SizeFlags::add_to(CommandLine& cli, bool with_bounds)
{
    SizeOptions::add_to(cli, with_bounds);
    cli.option("--bench-field", &bench_field,
               "the paper's three-cylinder field, case A, B, C, D or E");
}

volume::SizeSpec SizeFlags::spec() const
{
    const int given = int(hsiz_set) + int(sol_set) + int(!bench_field.empty());
    if (given > 1) throw UsageError("give only one of --hsiz, --sol and --bench-field");
    if (hsiz_set && !(hsiz > 0)) throw UsageError("--hsiz must be positive");
    // <= 0: no gradation, as Mmg's -hgrad -1
    if (hgrad > 0 && !(hgrad > 1)) throw UsageError("--hgrad must be larger than 1 (or -1: none)");
    if (bench_field.size() > 1) throw UsageError("--bench-field expects one letter A-E");
    volume::SizeSpec spec;
    spec.hsiz = hsiz_set ? hsiz : 0.0;
    spec.benchmark = bench_field.empty() ? 0 : bench_field[0];
    spec.hmin = hmin;
    spec.hmax = hmax;
    spec.hgrad = hgrad > 0 ? hgrad : 0.0;
    return spec;
}

std::shared_ptr<const SizeField> SizeFlags::make(const volume::TetMesh& input) const
{
    volume::SizeSpec sizes = spec();
    if (sol_set)
    {
        SolSizing sizing = volume::read_vertex_sizing(sol, input);
        sizes.vertex_sizes = std::move(sizing.sizes);
        sizes.vertex_metrics = std::move(sizing.metrics);
    }
    return volume::make_size_field(sizes, input);
}

}  // namespace hdimesh::cli
