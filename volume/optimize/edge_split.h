#pragma once
// Split of an interior edge by a new free vertex, placed by smoothing's moves: the repair of
// a bad tet whose four vertices are all fixed (boundary, ridge, corner or required), which no
// smoothing can reach and which swaps may have no better shape for. Typical case: a tet with
// two boundary faces over a crease, whose one interior edge c-d no operator touched.
//
//            c                  each tet (a, b, r_i, r_i+1) of the shell of edge a-b becomes
//           /|\                 (a, m, r_i, r_i+1) and (m, b, r_i, r_i+1); m starts at the
//     r1 - / m \ - r0           midpoint and moves to where the worst new tet is best
//         \  |  /
//            d       (here a-b is c-d)
//
// Legal only for an interior edge (closed shell) that is not a listed feature edge, whose
// shell has one tet ref, no constrained face and no required tet; the boundary never changes.
// Simulated before the commit: every new tet positive, the worst new tet better than the
// shell's old worst by options.min_gain, no new dihedral angle below min(the shell's smallest,
// options.min_dihedral_deg), and no edge of m made too long or too short by its move away from the
// midpoint (smooth_vertex's rule, the midpoint as the start).

#include "volume/mesh/tet_topology.h"
#include "volume/optimize/smooth.h"

namespace hdimesh::volume
{

struct EdgeSplitOptions
{
    int max_ring = 16;       ///< larger shells are left alone
    double min_gain = 1e-3;  ///< the new worst must beat the shell's old worst by this much
    /// a new dihedral angle may go below the shell's smallest only down to this (degrees)
    double min_dihedral_deg = 20;
    SmoothOptions placement;  ///< how the new vertex is placed
};

struct EdgeSplitResult
{
    bool split = false;
    int new_vertex = -1;
    double worst_before = 0;  ///< worst Qe of the best candidate edge's shell
    double worst_after = 0;   ///< worst Qe of its new tets (when they could be formed)
};

/// Splits, of the interior edges of live tet t, the one whose split gives the best worst new
/// tet, when that beats its shell's worst (see above).
EdgeSplitResult split_interior_edge(TetMesh& mesh, OperatorContext& context, int t,
                                    const EdgeSplitOptions& options = {});

}  // namespace hdimesh::volume
