#pragma once
// A tet mesh from a closed surface alone (the paper's surface-only input: "a tetrahedron mesh
// is performed and adapted thereafter"):
//
//   repair     surface/soup_repair.h     merged, dropped, oriented, pinches split, small holes
//                                          closed, tiny shells dropped; one note per repair
//   validate   volume/check/surface_check.h      what is left open or non-manifold refused, one
//                                          message naming the faces or loops (InputError);
//                                          crossings are a note, the remeshed surface decides
//   regions    volume/check/surface_regions.h    shells, voids, one tet ref per solid
//   remesh     surface/remesh_surface.h    the surfremesh pipeline to the size (skipped with
//                                          keep_surface: the given triangles are the boundary,
//                                          TetGen's -Y), then validated again
//   fill       volume/fill/cavity.h             one fill_cavity call per region (outer shell +
//   voids) adapt      coupling::adapt: too-long edges refined, new boundary points projected onto
//   the
//              model, optimized; with keep_surface, interior edges only and no projection (the
//              boundary never changes)
//
// The sizes: uniform (hsiz), curvature-adaptive on the surface (hausd), given at the input
// points (vertex_sizes, a .sol) or any volume field. A size known only on the surface is
// carried into the volume as the size at the closest surface point.

#include <memory>
#include <string>
#include <vector>

#include "common/size_field.h"
#include "coupling/adapt.h"
#include "surface/remesh_surface.h"
#include "surface/surface_io.h"
#include "surface/surface_mesh.h"
#include "volume/check/surface_check.h"
#include "volume/fill/cavity.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::coupling
{

/// The target size, Mmg's flags. At most one of hsiz, hausd, vertex_sizes and field; none: the
/// surfremesh default (curvature-adaptive, at most twice the input's mean edge), or with
/// keep_surface the input's own edge lengths.
struct SurfaceSizing
{
    double hsiz = 0;                   ///< > 0: uniform (--hsiz)
    double hausd = 0;                  ///< > 0: curvature-adaptive on the surface (--hausd)
    std::vector<double> vertex_sizes;  ///< one per input point (--sol)
    /// A size anywhere (e.g. the paper's benchmark field): sampled at the input points for the
    /// surface, used as is in the volume.
    std::shared_ptr<const SizeField> field;
    double hmin = 0, hmax = 0;  ///< bounds; 0: none
    double hgrad = 0;           ///< surface gradation; 0: the remesher's 1.3, <= 1: none
};

struct VolumeFromSurfaceOptions
{
    SurfaceSizing sizing;
    /// The given triangles are the boundary, exactly (no remeshing, no refinement or
    /// projection of the boundary afterwards).
    bool keep_surface = false;
    /// The surface remesher's other settings (features, iterations); its sizes come from
    /// `sizing`.
    surface::SurfaceRemeshSettings remesh;
    volume::SurfaceCheckOptions check;
    /// The input's repairs (surface/soup_repair.h); holes are closed at hole_size_factor
    /// local sizes of `sizing`. strict: refused as the input is, no repair.
    surface::SoupRepairOptions repair;
    volume::CavityOptions fill;
    /// After the fill: split too-long edges (interior ones only with keep_surface), project
    /// new boundary points, optimize (coupling::adapt).
    bool refine = true;
    bool optimize = true;
    /// The refinement and optimization settings (its refine / optimize flags are set from
    /// the two above).
    AdaptOptions adapt;
    std::string source;  ///< the input's name in messages ("spot.obj")
};

struct VolumeFromSurfaceReport
{
    int input_points = 0, input_triangles = 0;
    int merged_points = 0;    ///< points renamed to an earlier one at the same place
    int input_crossings = 0;  ///< pairs of input triangles that cross (the remesh is checked)
    /// One line per repair of the input and per defect left to the remesh, naming the input.
    std::vector<std::string> repairs;
    int shells = 0, regions = 0, voids = 0;
    int turned_shells = 0;  ///< shells reversed to face out of their region (input's)
    int surface_points = 0, surface_triangles = 0;  ///< the boundary filled (after remeshing)
    surface::SurfaceRemeshResult remesh;            ///< when remeshed
    int fold_rounds = 0;  ///< remeshes redone finer where the remeshed surface crossed itself
    volume::FillStatistics fills;        ///< one fill per region
    int fill_tets = 0, fill_points = 0;  ///< the fill's tets and Steiner points
    double fill_min_quality = 0;
    AdaptReport adapt;  ///< after the fill
    int tets = 0, vertices = 0;
    double min_quality = 0;
    /// Seconds per stage, wall and thread CPU.
    double seconds_check = 0, seconds_remesh = 0, seconds_fill = 0, seconds_optimize = 0,
           seconds_total = 0;
    double cpu_seconds_check = 0, cpu_seconds_remesh = 0, cpu_seconds_fill = 0,
           cpu_seconds_optimize = 0, cpu_seconds_total = 0;
    /// The volume size field the mesh was made to, for the caller's quality report.
    std::shared_ptr<const SizeField> field;
};

/// The tet mesh of the solids the soup bounds. The soup is repaired first (unless
/// options.repair.strict); throws InputError (naming options.source and the faces, loops or
/// vertices) when the repaired surface is not closed, manifold and consistently oriented, when
/// the surface filled (the remeshed one, or the input with keep_surface) has crossing or
/// degenerate faces, or when the sizing is invalid; TopologyError when the filler gives up on a
/// region. Nothing is returned partly. Output: tets with refs 1, 2, ... per region; mesh.triangles
/// the boundary (faces of voids pointing into them) with the soup's refs; with remeshing, its
/// ridges and corners as mesh.edges / ridges / corners. Compact, with adjacency, passing
/// check_mesh.
volume::TetMesh mesh_volume_from_surface(const surface::TriangleSoup& soup,
                                         const VolumeFromSurfaceOptions& options,
                                         VolumeFromSurfaceReport* report = nullptr);

/// The same from a surface mesh (its faces and face refs; no deleted elements).
volume::TetMesh mesh_volume_from_surface(const surface::SurfaceMesh& surface,
                                         const VolumeFromSurfaceOptions& options,
                                         VolumeFromSurfaceReport* report = nullptr);

/// The triangles of a mesh file without tets (Medit, Gmsh) as a soup, refs kept.
surface::TriangleSoup triangle_soup(const volume::TetMesh& mesh);

/// Stage times and counts, a few lines.
std::string format_volume_from_surface_report(const VolumeFromSurfaceReport& report);

}  // namespace hdimesh::coupling
