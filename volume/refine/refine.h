#pragma once
// Refinement by edge bisection (the paper's §3, ../shared/docs/method.md §3): every too-long
// edge is split at its midpoint and every tet is rebuilt from the table of all 239 split
// configurations (volume/refine/refine_patterns.h). Conformity comes from the face rule below being
// a pure function of a face, so the two tets sharing a face, and the boundary triangle on it,
// triangulate it alike.
//
// The face rule. A face (or boundary triangle) with two split edges meeting at corner c, other
// vertices a, b (global ids, a < b), is a corner triangle (c, m_ca, m_cb) plus a quad with two
// diagonals: a–m_cb or b–m_ca. We take the one whose worse quad triangle has the higher triangle
// Qe (volume/mesh/geometry.h triangle_quality, computed in the fixed order given by the ids); when
// the two worse qualities differ by at most 1e-12 relative (a tie: regular or structured meshes),
// the diagonal starting at the smaller global id (a). A tie therefore never creates a Schönhardt
// configuration (the ids are totally ordered, the diagonals cannot twist). A face whose three
// vertices lie on a rank's cut (blocks.h kRankCutRef), which the rank beyond numbers apart, takes
// a before b in the lexicographic order of their positions instead: both ranks split it alike.

#include <functional>
#include <vector>

#include "common/parallel.h"
#include "common/size_field.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

struct RefineOptions
{
    int max_passes = 40;
};

struct RefinePassReport
{
    int pass = 0;
    int edges_split = 0;
    int tets = 0;            ///< after the pass
    int vertices = 0;        ///< after the pass
    int steiner_points = 0;  ///< interior points added (Schönhardt configurations, fallbacks)
    double seconds = 0;
    /// Tets whose table pattern would have had a non-positive child in the real geometry (a
    /// moved midpoint, round-off on a nearly flat parent) and were instead coned from an
    /// interior point that sees every boundary triangle of the sub-polyhedron.
    int fallback_tets = 0;
    /// Marked edges left for a later pass: a tet through them, flat in doubles, had no positive
    /// split (nor a coned one).
    int deferred_edges = 0;
};

struct RefinePassResult
{
    RefinePassReport report;
    std::vector<int> new_boundary_vertices;  ///< midpoints of boundary edges (Surface or Ridge
                                             ///< class), to be projected onto the surface model
    std::vector<int> steiner_vertices;  ///< interior points added for Schönhardt configurations,
                                        ///< for the optimizer
};

/// One pass: marks every too-long edge (measure_edge(field, a, b).too_long()), interior
/// and boundary; never an edge of a required triangle (but a cut between ranks, blocks.h
/// kRankCutRef) or a required edge, and at their vertices
/// the size is at least the mean length of those edges), adds one midpoint per
/// marked edge, rebuilds each tet from the table (children keep the parent's ref), splits
/// mesh.triangles with the same face rule (children keep the ref), splits feature edges
/// (mesh.edges) in two keeping refs and updates ridges and the required_* lists (children of a
/// required tet are required).
///
/// New vertices: the midpoint of a ridge edge is Ridge (ref: the edge's), of an edge of
/// mesh.triangles Surface (ref: a triangle's), else Interior (ref: the endpoints' common ref,
/// else 0); a Steiner point is Interior (ref: the parent's vertices' common ref, else 0).
/// Existing vertices keep their ids.
///
/// Every child's volume is checked before anything is committed; a pattern with a non-positive
/// child falls back to a cone from the parent's centroid, then from the average of the
/// sub-polyhedron's points (one new interior vertex, reported as a Steiner point). If no
/// fallback is positive (the parent is flat in doubles) its split edges wait for a later pass
/// (deferred_edges) and the pass is simulated again; after 16 such rounds the mesh is left
/// unchanged and hdimesh::InputError is thrown.
///
/// The pass starts from a freshly built adjacency (callers need not maintain it) and links the
/// children from the pattern table and the parents' adjacency (no global rebuild): child 0 of a
/// refined tet takes its parent's slot, the other children are appended; unrefined tets keep
/// their slots. On return the mesh is compact (no dead tets) with valid adjacency. A pass that
/// splits no edge changes nothing but that.
RefinePassResult refine_pass(TetMesh& mesh, const SizeField& field);

/// What a caller vouches for about the mesh it hands to refine_pass.
struct RefinePassOptions
{
    /// mesh.neighbors is the adjacency of mesh.tets as they are (the previous pass left it and
    /// every change since kept it, as the optimizer does): not rebuilt.
    bool adjacency_valid = false;
    /// Edges with both ends below this vertex id were measured by the previous pass against
    /// the same field, and nothing since made an edge too long (the optimizer's operators and
    /// the projection never do; that pass deferred no edge): they are not measured again.
    int first_candidate_vertex = 0;
    /// Measures the edges on these threads (null: one); the result does not depend on them.
    Workers* workers = nullptr;
};

/// refine_pass, told what holds already.
RefinePassResult refine_pass(TetMesh& mesh, const SizeField& field,
                             const RefinePassOptions& options);

/// A face rule: for a face with split edges corner–a and corner–b (global ids), the id (a or b)
/// its quad diagonal starts from. Any pure function of (corner, {a, b}) keeps the mesh
/// conforming; tests use this to force Schönhardt configurations.
using QuadDiagonalRule = std::function<int(int corner, int a, int b)>;

/// refine_pass with another face rule (tets and boundary triangles).
RefinePassResult refine_pass(TetMesh& mesh, const SizeField& field, const QuadDiagonalRule& rule);

struct RefineResult
{
    std::vector<RefinePassReport> passes;
    bool converged = false;  ///< the last pass found no edge too long
    std::vector<int> new_boundary_vertices;
    std::vector<int> steiner_vertices;
};

/// Repeats refine_pass until no edge is too long or max_passes passes have run. Between its own
/// passes nothing moves, so a pass only measures edges with an endpoint created by the previous
/// pass (an older edge was already found short enough) and reuses the adjacency it built.
RefineResult refine(TetMesh& mesh, const SizeField& field, const RefineOptions& options = {});

/// The face rule above: for a face with split edges c–a and c–b (global ids), the global id (a
/// or b) the quad diagonal starts from (it ends at the midpoint of the other split edge).
/// Symmetric in a and b.
int quad_diagonal_start(const std::vector<Vec3>& points, int corner, int a, int b);

/// The face rule on a rank's cut: ties go to the lexicographically first position, so the
/// result does not depend on the numbering. Symmetric in a and b.
int quad_diagonal_start_by_position(const std::vector<Vec3>& points, int corner, int a, int b);

}  // namespace hdimesh::volume
