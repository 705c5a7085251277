#pragma once
// Face removal: the 2-3 flip, and multi-face removal (Shewchuk 2002), its generalization and
// the inverse of edge removal.
//
// 2-3 flip: the two tets sharing an interior face (x, y, z) are replaced by the three tets
// around the new edge joining their apexes p and q.
//
//            q                      before: (x, y, z, q) above and (x, z, y, p) below
//          / | \                    after:  (x, y, p, q), (y, z, p, q), (z, x, p, q)
//        x---|---z                  legal only when the segment pq crosses the triangle xyz
//          \ | /  (y behind)        (all three new tets positive)
//            p
//
// Multi-face removal: faces f1..fk "sandwiched" between two vertices a and b (each fi has the
// tet (fi, a) on one side and (fi, b) on the other) that form a triangulated polygon of
// m = k + 2 vertices, all on its boundary, around the segment ab. The 2k tets are replaced by
// the m tets (u, v, a, b), one per polygon edge (u, v); the polygon's inner edges and faces
// disappear, ab appears. k = 1 is the 2-3 flip, k = 2 the 4-4 flip.
//
//        r3 ------- r2          seen from b (above the page), a below:
//        / \   f2  / \          sandwiched faces f1 f2 f3 around the seed f2 through which
//       / f1 \   / f3 \         ab passes; removing f1..f3 (6 tets) gives the 5 tets
//     r4 ------ r0 ---- r1      (ri, ri+1, a, b) over the pentagon's edges.
//
// Which of the sandwiched faces to remove is a choice: the new tets' quality depends only on
// the polygon's boundary edges, so a dynamic program over the tree of sandwiched faces grown
// from the seed finds, in time linear in their number, the connected subset (containing the
// seed) whose new tets have the best worst quality.

#include "volume/mesh/tet_topology.h"

namespace hdimesh::volume
{

struct FaceRemovalOptions
{
    double min_gain = 1e-6;  ///< the new worst quality must beat the old one by this much
};

struct FaceRemovalResult
{
    bool removed = false;
    double worst_before = 0;  ///< worst Qe of the two tets
    double worst_after = 0;   ///< worst Qe of the three new tets (when they could be formed)
};

/// Flips face `local_face` of tet t (2-3) when the face is interior and unconstrained, both tets
/// share one ref, the new edge is not too long for context.field, all new tets are positive
/// and the worst quality rises. The optimizer uses remove_multi_face, which makes every flip
/// this one makes and more; this plain 2-3 flip is the reference its k = 1 case is tested
/// against. It does not check that the new edge is absent (positive new tets imply it).
FaceRemovalResult remove_face(TetMesh& mesh, OperatorContext& context, int t, int local_face,
                              const FaceRemovalOptions& options = {});

struct MultiFaceRemovalOptions
{
    int max_faces = 16;      ///< sandwiched faces explored from the seed at most
    double min_gain = 1e-6;  ///< the new worst quality must beat the old one by this much
};

/// The best removal found from a seed face. The figures describe the best choice of faces
/// even when it was not committed (no gain, an inverted new tet, a too-long new edge).
struct MultiFaceRemovalResult
{
    bool legal = false;       ///< topology and constraints allow removing the seed face
                              ///< (ab not an edge yet: tested only for a removal that
                              ///< passes geometry and quality)
    bool removed = false;     ///< the mesh was changed
    double worst_before = 0;  ///< worst Qe of the 2k tets of the best choice
    double worst_after = 0;   ///< worst Qe of its k + 2 new tets (<= 0: some would be inverted)
    int sandwich_size = 0;    ///< faces found sandwiched between a and b (capped by max_faces)
    int faces_removed = 0;    ///< k of the best choice
    int tets_removed = 0;     ///< 2k
    int tets_created = 0;     ///< k + 2
};

/// The best multi-face removal seeded at face `local_face` of tet t (a is the vertex of t
/// opposite the face, b the apex of the tet across it), and whether it is legal; changes
/// nothing. Legal: the seed face interior, unconstrained, between two tets of one ref, a != b
/// and ab not an edge yet (looked for last, only when the removal would raise the worst
/// quality: the new tets around an existing edge cannot all be positive, and the test walks
/// the ball of a); faces are added to the sandwich only across inner edges that are
/// not feature edges, whose faces (u, v, a), (u, v, b) and (u, v, c) are not constrained and
/// whose four tets share the seed's ref and may be removed.
MultiFaceRemovalResult evaluate_multi_face_removal(const TetMesh& mesh,
                                                   const OperatorContext& context, int t,
                                                   int local_face,
                                                   const MultiFaceRemovalOptions& options = {});

/// Commits the best removal when it is legal, every new tet is positive, the new edge ab is
/// not too long for context.field, and the worst quality rises by options.min_gain.
/// The new tets take the slots of the removed ones first (see replace_tets).
MultiFaceRemovalResult remove_multi_face(TetMesh& mesh, OperatorContext& context, int t,
                                         int local_face,
                                         const MultiFaceRemovalOptions& options = {});

}  // namespace hdimesh::volume
