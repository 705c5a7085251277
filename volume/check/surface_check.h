#pragma once
// Validation of a closed triangle surface before it is filled with tets: every defect that
// would make a tet mesher crash, hang or silently produce garbage is found and named, on plain
// points + triangles (no TetMesh, no OpenMesh), so any reader can call it.
//
//   topology   vertex ids in range, no repeated vertex in a face, no duplicated face, every
//              edge in exactly two faces (open boundaries are chained into loops), traversed
//              in opposite directions, every vertex's faces one fan (no pinch)
//   geometry   no zero-area face, no two faces meeting outside their shared vertices (exact
//              predicates, candidate pairs from a uniform grid of face boxes)
//
// Whole shells facing inward are not defects: volume/check/surface_regions.h turns them.

#include <cstdint>
#include <string>
#include <vector>

#include "common/parallel.h"
#include "volume/mesh/geometry.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// What is wrong, in the order the checks run and the message lists them.
enum class SurfaceDefectKind : std::uint8_t
{
    VertexOutOfRange = 0,     ///< a face names a vertex id that does not exist
    DegenerateFace,           ///< a repeated vertex, or three collinear points (zero area)
    DuplicateFace,            ///< the same three vertices as another face
    OpenBoundary,             ///< a loop (or chain) of edges in a single face
    NonManifoldEdge,          ///< an edge in three or more faces
    InconsistentOrientation,  ///< both faces at an edge traverse it the same way
    NonManifoldVertex,        ///< the faces at a vertex make several fans (a pinch)
    SelfIntersection,         ///< two faces meet outside their shared vertices
};
inline constexpr int kNumSurfaceDefectKinds = 8;

const char* to_string(SurfaceDefectKind kind);

/// One defect. Ids are 0-based indices into the checked arrays; messages print them 1-based,
/// as OBJ and Medit number them.
struct SurfaceDefect
{
    SurfaceDefectKind kind;
    /// The faces at fault: the face (out of range, degenerate), the copies (duplicate), the
    /// faces at the edge or vertex, the loop's faces in loop order, the two crossing faces.
    std::vector<int> faces;
    /// The vertices at fault: the bad id (out of range), the face's (degenerate, duplicate), the
    /// edge's two ends, the loop's vertices in order, the pinched vertex.
    std::vector<int> vertices;
};

struct SurfaceCheckOptions
{
    /// The exact face-pair tests (the only part that is not linear in the number of faces
    /// touching each other).
    bool check_self_intersections = true;
    /// The search stops after this many crossing pairs (one is enough to refuse).
    int max_intersections = 1000;
    Workers* workers = nullptr;  ///< the face-pair tests on these threads (null: this one)
};

/// Every defect of the surface, topology first, then geometry; empty when it bounds a volume
/// (one or more closed, consistently oriented, disjoint 2-manifold shells). Faces with a
/// repeated vertex and the later copies of a duplicate are left out of the edge, vertex and
/// intersection checks, zero-area faces out of the intersection check, so each problem is
/// reported once under its own name. Unused points are ignored. Deterministic.
std::vector<SurfaceDefect> check_closed_surface(const std::vector<Vec3>& points,
                                                const std::vector<Triangle>& triangles,
                                                const SurfaceCheckOptions& options = {});

/// One message for all the defects: "source: the surface is open: 5 boundary loops (loop 1:
/// 23 edges through vertices 10, 11, ...; ...)", one line per kind (indented under a heading
/// when there are several), at most max_listed instances named per kind. Empty when there is
/// no defect.
std::string format_surface_defects(const std::vector<SurfaceDefect>& defects,
                                   const std::string& source, int max_listed = 3);

/// check_closed_surface, then throws hdimesh::InputError with format_surface_defects' message
/// when it found anything.
void require_closed_surface(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                            const std::string& source, const SurfaceCheckOptions& options = {});

/// Renames, in the triangles, every point to the first point with exactly the same
/// coordinates (soups from STL or per-face OBJ exports repeat them); ids stay those of the
/// input, so messages name the file's vertices. Returns how many points were renamed away.
int merge_coincident_points(const std::vector<Vec3>& points, std::vector<Triangle>& triangles);

}  // namespace hdimesh::volume
