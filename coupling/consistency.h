#pragma once
// check_consistency: the surface is the tets' boundary, vertex for vertex (the coupling's
// invariant, asserted by the tests after every mirrored operation).

#include <string>
#include <vector>

#include "coupling/boundary_map.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::coupling
{

/// What differs between the surface of `map` and the boundary of `mesh`, one line each (empty:
/// consistent):
///  - each live surface vertex names a distinct tet vertex at the same position, whose class
///    is the surface's (Smooth ↔ Surface, Ridge/Boundary ↔ Ridge, Corner ↔ Corner);
///  - the live surface faces, in tet ids and orientation, are exactly the faces used by one
///    live tet, and exactly mesh.triangles, with the same refs.
/// Works on a surface with deleted elements (during a remesh); O(size of both meshes).
std::vector<std::string> check_consistency(const BoundaryMap& map, const volume::TetMesh& mesh,
                                           std::size_t max_reports = 20);

}  // namespace hdimesh::coupling
