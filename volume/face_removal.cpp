#include "volume/face_removal.h"

#include <algorithm>

#include "volume/tet_tables.h"

namespace hdimesh
{

namespace
{

/// The two tets of the face with their role names.
struct FacePair
{
    int lower = -1, upper = -1;  // lower holds the face outward, upper on the other side
    int x = -1, y = -1, z = -1;  // the face, counter-clockwise seen from upper's apex
    int p = -1, q = -1;          // apex of lower, apex of upper
};

}  // namespace

FaceRemovalResult remove_face(TetMesh& mesh, OperatorContext& context, int t, int local_face,
                              const FaceRemovalOptions& options)
{
    FaceRemovalResult result;
    // layer 1: topology
    const int other = mesh.neighbors[t][local_face];
    if (other == kNoTet) return result;
    FacePair pair;
    pair.lower = t;
    pair.upper = other;
    const auto& fv = tet::kFaceVertices[local_face];
    pair.x = mesh.tets[t][fv[0]];
    pair.y = mesh.tets[t][fv[1]];
    pair.z = mesh.tets[t][fv[2]];
    pair.p = mesh.tets[t][local_face];
    for (int v : mesh.tets[other])
        if (v != pair.x && v != pair.y && v != pair.z) pair.q = v;
    if (pair.q < 0 || pair.q == pair.p) return result;
    // layer 2: constraints
    const auto& constraints = context.constraints;
    if (constraints.is_constrained_face(mesh, t, local_face) ||
        !constraints.is_removable_tet(pair.lower) || !constraints.is_removable_tet(pair.upper))
        return result;
    // layer 3: geometry, layer 4: quality
    result.worst_before = std::min(mesh.quality(pair.lower), mesh.quality(pair.upper));
    const auto& pts = mesh.points;
    const std::vector<TetVertices> added = {
        {pair.x, pair.y, pair.p, pair.q},
        {pair.y, pair.z, pair.p, pair.q},
        {pair.z, pair.x, pair.p, pair.q},
    };
    double worst = 1e300;
    for (const auto& tv : added)
        worst = std::min(worst, tet_quality(pts[tv[0]], pts[tv[1]], pts[tv[2]], pts[tv[3]]));
    result.worst_after = worst;
    if (worst <= 0.0 || worst <= result.worst_before + options.min_gain) return result;
    if (context.too_long(pts[pair.p], pts[pair.q])) return result;
    replace_tets(mesh, context, {pair.lower, pair.upper}, added, mesh.tet_refs[pair.lower]);
    result.removed = true;
    return result;
}

}  // namespace hdimesh
