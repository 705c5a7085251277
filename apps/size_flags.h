#pragma once
// The size-field flags of the tet tools (adapt, meshstat): the shared Mmg flags plus the
// paper's benchmark fields, made into a volume size field over the input mesh.

#include <memory>
#include <string>

#include "cli.h"
#include "common/size_field.h"
#include "volume/mesh/tet_mesh.h"
#include "volume/size/size_spec.h"

namespace hdimesh::cli
{

struct SizeFlags : SizeOptions
{
    std::string bench_field;  ///< --bench-field: the paper's cases A-E
    /// No size given but one asked for (Mmg's default): the input's own sizes, as with none.
    bool own_sizes = false;

    /// Registers --hsiz, --sol, --bench-field and, when with_bounds, --hmin/--hmax/--hgrad.
    void add_to(CommandLine& cli, bool with_bounds);
    bool any() const { return hsiz_set || sol_set || !bench_field.empty() || own_sizes; }
    /// The sizes as stated, checked (at most one of --hsiz, --sol, --bench-field; positive
    /// values; --hgrad -1 is none), without the .sol's values. Throws UsageError.
    volume::SizeSpec spec() const;
    /// The field they describe over `input` (the mesh the .sol belongs to). With no size flag:
    /// the input's own sizes (mean length of the edges at each vertex, linear in each tet), so
    /// --optim keeps the sizes. --hmin/--hmax clamp; --hgrad bounds the size ratio between
    /// neighbouring vertices (Mmg's H-correction) on the input mesh's vertices: for a .sol the
    /// corrected values are the field, for an analytic field the field becomes
    /// min(analytic, graded samples), so it keeps its own resolution and gradation only ever
    /// shrinks sizes. Throws InputError on conflicting or invalid flags.
    std::shared_ptr<const SizeField> make(const volume::TetMesh& input) const;
};

}  // namespace hdimesh::cli
