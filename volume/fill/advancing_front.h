#pragma once
// The advancing-front mesher (issue 15, stage 4 of volume/fill/cavity.h): fills a closed,
// outward-oriented set of triangles with tets whose size follows a size field, placing interior
// points as it goes. Used for cavities too large for the exhaustive search and for whole
// volumes from a surface.
//
//   front     flat arrays + a hash from the sorted triple, so a new face that matches a front
//             face closes both exactly; components kept apart
//   order     most-failed faces last, then the oldest, then the smallest
//   candidate nearby front vertices and the ideal point at the height the field asks for
//   tests     exact intersection tests against the local front (a bucket grid)
//   stuck     priority drops, radius widens, quality floor relaxes; when every face is stuck,
//             retreat (remove the tets at the open faces) and retry, capped
//   leftover  small groups go back to the fan / kernel / exhaustive stages

#include <string>
#include <vector>

#include "common/size_field.h"
#include "volume/fill/fill_common.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

struct FrontReport
{
    long tets = 0;
    long new_points = 0;
    int retreat_rounds = 0;
    int leftover_groups = 0;  ///< groups closed by stages 1-3
    double seconds = 0;
};

/// Fills the region bounded by `faces` (vertex ids into `points`; closed and outward, several
/// shells allowed: nested ones bound voids). Appends the new points after points.size() into
/// new_points and the tets (ids as in CavityFill) into tets. Returns false, with `failure` set
/// and tets/new_points unchanged, when it cannot close the front within its budgets.
/// field: target sizes (nullptr: the local face size).
bool advance_front(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                   const SizeField* field, const AdvancingFrontOptions& options,
                   std::vector<TetVertices>& tets, std::vector<Vec3>& new_points,
                   std::string& failure, FrontReport* report = nullptr);

}  // namespace hdimesh::volume
