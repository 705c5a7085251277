#pragma once
// The mesh checker: every invariant of volume/mesh/tet_mesh.h verified from scratch, each broken
// one listed as a violation (never an exception), so tests can call it on every mesh they produce
// and apps can print it before writing.

#include <cstddef>
#include <string>
#include <vector>

#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// One broken invariant. `kind` is one of the names below; `element` is the index of the
/// entity named in the kind's description (-1 when global); `message` is for humans.
///
///  kind                          element    meaning
///  array_size                    -1         a per-entity array (refs, classes, neighbors) has the
///  wrong length nan_coordinate                vertex     a coordinate is NaN or infinite
///  tet_vertex_out_of_range       tet        a vertex id < 0 or >= num_vertices
///  triangle_vertex_out_of_range  triangle
///  edge_vertex_out_of_range      edge       (mesh.edges)
///  entity_index_out_of_range     -1         ridges/corners/required_* index nothing
///  non_positive_volume           tet        signed volume <= 0
///  face_shared_by_more_than_two  tet        a face (vertex set) used by 3+ live tets; element =
///  first user face_same_orientation         tet        two tets list a shared face the same way
///  (they overlap) adjacency_stale               tet        neighbors[t][f] differs from the
///  recomputed adjacency adjacency_asymmetric          tet        neighbors[t][f] = n but no face
///  of n points back to t missing_boundary_triangle     tet        a boundary face of the tets is
///  not in mesh.triangles boundary_triangle_reversed    triangle   in mesh.triangles but oriented
///  inward triangle_not_a_tet_face       triangle   in mesh.triangles but no live tet has that face
///  interior_triangle             triangle   on a face between two tets of the same ref
///  duplicate_triangle            triangle   the same vertex set listed twice in mesh.triangles
///  open_boundary_edge            triangle   a boundary edge in only one boundary triangle
///  nonmanifold_boundary_edge     triangle   a boundary edge in three or more boundary triangles
///  boundary_edge_same_direction  triangle   the two triangles at a boundary edge are not
///  consistently oriented nonmanifold_boundary_vertex   vertex     a boundary vertex whose link is
///  several cycles (pinched) volume_mismatch               -1         sum of tet volumes != volume
///  enclosed by the tets' boundary coincident_vertices           vertex     two vertices used by
///  tets at the same point (a hidden crack) unused_vertex                 vertex     no live tet
///  uses it (only with report_unused_vertices)
///
/// The boundary-manifold checks run on the boundary triangles of mesh.triangles (interface
/// triangles on faces between two tets excluded): that is the surface other modules consume.
struct MeshViolation
{
    std::string kind;
    int element;
    std::string message;
};

struct CheckOptions
{
    /// Report boundary edges in a single triangle (an open boundary). Off for open surfaces.
    bool require_closed_boundary = true;
    /// |sum of tet volumes - enclosed volume| allowed, relative to the sum.
    double volume_relative_tolerance = 1e-10;
    /// Accept triangles on faces between two tets of the same ref (internal constraint
    /// surfaces); triangles between different refs (interfaces) are always accepted.
    bool allow_interior_triangles = false;
    /// Report vertices that no live tet uses (compact() removes them). Off by default because
    /// operators leave such vertices until they compact; meshstat turns it on, as the
    /// independent checker ../shared/tools/meshstat.py counts them as non-conforming.
    bool report_unused_vertices = false;
    /// Report two vertices used by tets at exactly the same point: the tets on both sides of
    /// such a pair are not connected, an invisible crack when its faces are listed as triangles.
    bool report_coincident_vertices = true;
};

/// Lists every violation: non-positive volume, asymmetric or stale adjacency (recomputed and
/// compared; skipped while mesh.neighbors is empty), a face shared by >2 tets or by two tets
/// with the same orientation, boundary not a closed oriented 2-manifold, boundary triangles
/// not equal to the tets' boundary faces, sum of tet volumes != enclosed volume, vertex ids
/// out of range, NaN coordinates. Dead tets are ignored. O(n) apart from small sorts.
std::vector<MeshViolation> check_mesh(const TetMesh& mesh, const CheckOptions& options = {});

/// A count per kind on the first line, then up to max_lines violations, one per line.
/// "no violations" when the list is empty.
std::string format_violations(const std::vector<MeshViolation>& violations,
                              std::size_t max_lines = 20);

}  // namespace hdimesh::volume
