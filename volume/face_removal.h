#pragma once
// Face removal, the 2-3 flip: the two tets sharing an interior face (x, y, z) are replaced by
// the three tets around the new edge joining their apexes p and q.
//
//            q                      before: (x, y, z, q) above and (x, z, y, p) below
//          / | \                    after:  (x, y, p, q), (y, z, p, q), (z, x, p, q)
//        x---|---z                  legal only when the segment pq crosses the triangle xyz
//          \ | /  (y behind)        (all three new tets positive)
//            p

#include "volume/tet_topology.h"

namespace hdimesh
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
/// and the worst quality rises.
FaceRemovalResult remove_face(TetMesh& mesh, OperatorContext& context, int t, int local_face,
                              const FaceRemovalOptions& options = {});

}  // namespace hdimesh
