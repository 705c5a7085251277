#pragma once
// Edge removal (Shewchuk 2002): the m tets around an interior edge (a, b) are replaced by the
// 2(m-2) tets over a triangulation of the shell's ring, the triangulation chosen by Klincsek's
// O(m^3) dynamic program to maximize the worst new tet. m = 3 is the 3-2 flip.
//
//            b                 ring r0..r(m-1) around the edge, counter-clockwise seen from b;
//           /|\                each ring triangle (ri, rj, rk) gives the tets
//     r2 - / | \ - r1              (ri, rj, rk, b) above and (ri, rk, rj, a) below.
//         \  |  /
//     r3 -  \|/ - r0
//            a

#include "volume/mesh/tet_topology.h"

namespace hdimesh::volume
{

struct EdgeRemovalOptions
{
    int max_ring = 16;       ///< larger shells are left alone (the program is O(m^3))
    double min_gain = 1e-6;  ///< the new worst quality must beat the old one by this much
    /// false: remove_edge's program drops every partial triangulation that can no longer beat
    /// the shell's worst by min_gain (the same removals, found faster); worst_after is then
    /// exact only when the edge is removed, else -infinity. The optimizer's choice.
    bool exact_worst_after = true;
};

struct EdgeRemovalResult
{
    bool removed = false;
    double worst_before = 0;  ///< worst Qe of the shell
    double worst_after = 0;   ///< worst Qe of the best retriangulation (set even if not removed,
                              ///< unless options.exact_worst_after is false)
    int ring_size = 0;
};

/// The best worst quality a retriangulation of the shell of edge `local_edge` of tet `seed`
/// could reach, and whether the edge may be removed at all; changes nothing.
EdgeRemovalResult evaluate_edge_removal(const TetMesh& mesh, const OperatorContext& context,
                                        int seed, int local_edge,
                                        const EdgeRemovalOptions& options = {});

/// Removes the edge when it is legal (interior shell, no constrained face or edge, one tet ref,
/// every new tet positive, no new edge too long for context.field) and the worst quality rises.
EdgeRemovalResult remove_edge(TetMesh& mesh, OperatorContext& context, int seed, int local_edge,
                              const EdgeRemovalOptions& options = {});

}  // namespace hdimesh::volume
