#pragma once
// The boundary triangles other meshers write, made to this container's invariants
// (volume/mesh/tet_mesh.h): TetGen's -g lists every face of every tet, interior ones included, with
// the boundary turned inward; a tets-only file has no triangles at all. Each fix-up is counted,
// so the apps can say what they changed; `--strict` runs the checker on the file as it is.

#include <string>
#include <vector>

#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

struct BoundaryRepair
{
    int dropped_interior = 0;    ///< triangles on a face between two tets of the same ref
    int dropped_duplicates = 0;  ///< a vertex set listed again (the first one is kept)
    int turned_outward = 0;      ///< boundary triangles listed pointing into their tet
    int added_boundary = 0;      ///< boundary faces with no triangle: the tet's ref
    int added_interface = 0;     ///< faces between two tet refs with no triangle: the smaller ref

    bool any() const
    {
        return dropped_interior + dropped_duplicates + turned_outward + added_boundary +
                   added_interface >
               0;
    }
    /// One line per fix-up made, e.g. "dropped 17526 interior triangles (between two tets of
    /// the same ref)".
    std::vector<std::string> lines() const;
};

struct BoundaryRepairOptions
{
    /// Also list the faces between two tet refs (Mmg does); a converter keeps the file's.
    bool add_interfaces = true;
};

/// Makes mesh.triangles the tets' boundary and interfaces, each face once and the boundary
/// outward, refs as Mmg gives them: a new boundary triangle takes its tet's ref, a new
/// interface triangle the smaller of the two. Required triangles are never dropped (the checker
/// then names them); triangle_refs and required_triangles follow the renumbering. Triangles that
/// are no face of a tet are left for the checker. Vertex classes are recomputed when anything
/// changed. Tets with out-of-range ids are ignored (the checker names them).
BoundaryRepair repair_boundary(TetMesh& mesh, const BoundaryRepairOptions& options = {});

/// The curves where three or more regions meet (an edge of three or more triangles: the outer
/// boundary of two tet refs and their interface, say) listed as ridges, and the points where
/// three or more such curves meet as corners, so that a split on them stays on the curve.
struct RegionCurves
{
    int ridges = 0;   ///< edges added to mesh.ridges
    int corners = 0;  ///< vertices added to mesh.corners
};
RegionCurves mark_region_curves(TetMesh& mesh);

/// A tet mesh as read, made ready for adapt: its boundary mended (unless strict), the curves
/// where regions meet marked, then checked. Returns a line per change made; throws InputError
/// naming `source` and the violations when the mesh is not valid.
std::vector<std::string> prepare_tet_input(TetMesh& mesh, const std::string& source, bool strict);

}  // namespace hdimesh::volume
