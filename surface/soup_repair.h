#pragma once
// The one repair pass over a triangle soup, before any mesh is built from it: the surface
// readers (build_surface), adapt's surface input (coupling::mesh_volume_from_surface) and
// Python all call it. In order:
//
//   merge     points with identical coordinates become one
//   collapse  a flat triangle of three distinct points: its middle point joins the nearer end
//   drop      degenerate triangles (a repeated point, zero area) and duplicated ones (copies
//             cancel by orientation: a back-to-back pair is a zero-volume wall, dropped whole)
//   orient    each component consistently, by a walk over shared edges
//   split     pinched vertices: one copy per fan of triangles, each moved a little into its
//             own fan so the copies do not coincide
//   close     holes whose loop spans at most hole_size_factor local sizes (triangulated by a
//             minimum-area search; the remesh then refines the patch onto the HDI model)
//   outward   closed components enclose a positive volume
//   drop      tiny closed shells (below tiny_shell_volume of the total) inside no other shell
//
// Each repair adds one note naming what and where; with `strict` the first defect a repair
// would mend is an InputError instead. What stays ambiguous (a non-manifold edge, a
// non-orientable component) is an InputError naming the element.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "surface/surface_mesh.h"
#include "surface/triangle_soup.h"

namespace hdimesh::surface
{

struct SoupRepairOptions
{
    /// Refuse, naming the element, instead of mending (merging identical points and turning a
    /// closed component outward are not defects).
    bool strict = false;
    /// Close holes (a volume needs a closed surface; a surface remesher keeps open boundaries).
    bool close_holes = false;
    /// A hole's loop spans at most this many local sizes (its largest point distance) ...
    double hole_size_factor = 10.0;
    /// ... and its patch at most this fraction of its component's area (an open sheet's
    /// outline is no hole).
    double max_hole_area_fraction = 0.25;
    /// The target size at a point (close_holes needs it).
    std::function<double(const Vec3d&)> local_size;
    /// Closed shells below this fraction of the total enclosed volume, inside no other shell,
    /// are dropped (0: none).
    double tiny_shell_volume = 1e-6;
};

struct SoupRepairReport
{
    std::size_t merged_vertices = 0;
    std::size_t degenerate_faces = 0;
    std::size_t duplicate_faces = 0;
    std::size_t unused_vertices = 0;
    std::size_t reoriented_faces = 0;
    std::size_t components = 0;
    std::size_t split_vertices = 0;  ///< copies added at pinched vertices
    std::size_t closed_holes = 0;
    std::size_t turned_shells = 0;  ///< closed components turned outward
    std::size_t dropped_shells = 0;
    /// Per output point, the input point it comes from (copies of a pinch name the same one).
    std::vector<int> source_point;
    /// One line per repair, naming the input ("spot.obj: closed a hole of 3 edges at ...").
    std::vector<std::string> notes;
};

/// Repairs `soup` in place as described above; the result uses every point it lists. Throws
/// InputError naming `source` and the element when a defect is ambiguous (or, with strict,
/// at the first defect), or when no triangle is left.
void repair_soup(TriangleSoup& soup, const std::string& source, const SoupRepairOptions& options,
                 SoupRepairReport* report = nullptr);

}  // namespace hdimesh::surface
