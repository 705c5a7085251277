#pragma once
// Memory order of a tet mesh. Refinement appends children and midpoints at the end of the
// arrays, so after a few passes the tets around a vertex lie all over memory; the final
// optimization walks vertex balls and edge shells millions of times and would spend its time
// in cache misses. Renumbering along a space-filling curve puts neighbours next to each other.

#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// Renumbers the vertices along a Morton (Z-order) curve of their positions and the tets by
/// their smallest vertex (a stable counting sort), adjacency and every id list included, and
/// returns the maps. Ties keep the old order, so the result is deterministic.
/// \pre the mesh is compact (no dead tets).
CompactionMaps renumber_spatially(TetMesh& mesh);

}  // namespace hdimesh::volume
