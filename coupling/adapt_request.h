#pragma once
// The front door: one call that takes what a user hands adapt (a tet mesh, or a closed surface
// to fill) and a request stated as Mmg's options, checks that a size is given, mends a tet
// input, adapts or fills, and checks the result. The command-line tool and the Python module
// both call it, so the two read the same request the same way.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/messages.h"
#include "common/size_field.h"
#include "coupling/adapt.h"
#include "coupling/mesh_from_surface.h"
#include "surface/surface_io.h"
#include "volume/mesh/field_transfer.h"
#include "volume/mesh/tet_mesh.h"
#include "volume/size/size_spec.h"

namespace hdimesh::coupling
{

/// A tet mesh, or a surface whose volume is to be filled (is_surface).
struct AdaptInput
{
    volume::TetMesh mesh;           ///< the tets (unused for a surface)
    surface::TriangleSoup surface;  ///< the surface's triangles
    bool is_surface = false;
};

/// A surface-only format by extension: OBJ, OFF, STL or PLY (any case).
bool is_surface_format(const std::string& path);

/// A surface format (is_surface_format) or a mesh file with triangles and no tets is a
/// surface; any other mesh file is a tet mesh. Throws InputError/IoError naming path.
AdaptInput read_adapt_input(const std::string& path);

/// A mesh with tets as a tet input; with triangles only, as a surface.
AdaptInput adapt_input_from_mesh(volume::TetMesh mesh);

/// What the user asked for, in Mmg's terms.
struct AdaptRequest
{
    /// The sizes as stated (hsiz, sizes at the input's vertices, a benchmark case; hmin, hmax,
    /// hgrad > 1 or 0 for none).
    volume::SizeSpec size;
    std::string sol;  ///< non-empty: a .sol/.solb with the sizes at the input's vertices
    /// A distance bound, hmin, hmax or hgrad was given: with no size, a tet input keeps its own
    /// sizes within them (Mmg grades the boundary's curvature sizes inward instead).
    bool bounds_given = false;
    /// A surface input's gradation as given (0: the remesher's default, <= 1: none).
    double surface_hgrad = 0;
    double hausd = 0;  ///< > 0: the boundary's distance bound to the input
    AdaptSwitches switches;
    bool keep_surface = false;  ///< a surface input's triangles are the boundary, exactly
    /// Input defects refused, not mended: a tet input's triangles, a surface input's merges,
    /// drops, pinches, holes and shells (surface/soup_repair.h).
    bool strict = false;
    int max_passes = 40;  ///< refinement passes at most
    /// Threads the run uses (0: the cores present); the output is the same for any count.
    int threads = 0;
    /// The decomposition's grain (AdaptOptions::tets_per_block); the output depends on it.
    int tets_per_block = AdaptOptions{}.tets_per_block;
    int verbosity = 1;  ///< 0 silent, 1 a summary, 2 a table per pass
    /// Where the report lines (Report), the input's repairs (Trace) and progress go.
    MessageSink messages;
    std::function<void(const std::string& stage, int tets)> progress;  ///< may throw to stop
    bool check = false;           ///< report the checker's verdict on the input and output
    std::string source = "mesh";  ///< the input's name in messages
    /// Fields at the input's vertices (a tet input) carried onto the output
    /// (volume::transfer_fields: P1 in the input tet of each output vertex's own region).
    std::vector<volume::VertexField> fields;
    /// The domain's boundary when the mesh is a piece of it (AdaptOptions::geometry).
    std::shared_ptr<const volume::TetMesh> geometry;
};

struct AdaptResult
{
    volume::TetMesh mesh;  ///< valid (check_mesh clean)
    /// The field it was adapted to (the surface's sizes carried into the volume for a surface)
    std::shared_ptr<const SizeField> field;
    std::vector<std::string> repairs;  ///< what mending the input changed, one line each
    /// The request's fields at the output's vertices (transfer.fields) and how they were found.
    volume::TransferReport transfer;
    double adapt_seconds = 0;     ///< wall time of the adaptation proper
    double transfer_seconds = 0;  ///< wall time of the fields' transfer (the locator included)
};

/// Adapts a tet input to the request, or fills a surface input's volume. Throws InputError
/// when no size is given or a value is invalid, and Error when the result is not valid.
AdaptResult run_adapt(AdaptInput input, const AdaptRequest& request);

}  // namespace hdimesh::coupling
