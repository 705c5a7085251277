#pragma once
// Blocks: the tets cut into pieces that the serial engine adapts independently, on any thread,
// with the faces between pieces frozen (ParMmg's groups). The cuts depend on the mesh only,
// never on the thread count, each piece is worked in a fixed order, and the pieces merge back in
// block order: the result is the same bits for any number of threads, by construction. A
// later round moves the cuts, so the faces frozen in one round lie inside a block in the next.
// An MPI run would give each rank its blocks (docs/architecture.md).

#include <functional>
#include <vector>

#include "common/parallel.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// The ref of a block's frozen faces (faces shared with another block or an inactive tet).
inline constexpr int kFrozenFaceRef = -2147483647;

/// The refs of the faces between one rank's cells and another's (apps/petsc): kRankCutRef, or
/// kRankCutRef + r for a face that also carries the domain's ref r > 0. Required like a block's
/// frozen faces, but the refinement splits them (both sides alike: the marks and the face rule
/// are functions of the edge and the face), and a block's merge keeps them. A cut held whole
/// for a round (kHeldCutRef + r) is not split either.
inline constexpr int kRankCutRef = kFrozenFaceRef + 1;
inline constexpr int kMaxRankCutRef = 1 << 24;
inline constexpr int kHeldCutRef = kRankCutRef + kMaxRankCutRef + 1;

inline constexpr bool is_held_cut_ref(int ref)
{
    return ref >= kHeldCutRef && ref <= kHeldCutRef + kMaxRankCutRef;
}

inline constexpr bool is_rank_cut_ref(int ref)
{
    return (ref >= kRankCutRef && ref <= kRankCutRef + kMaxRankCutRef) || is_held_cut_ref(ref);
}

/// The domain's ref r a rank's cut face carries (0: none).
inline constexpr int rank_cut_domain_ref(int ref)
{
    return ref - (is_held_cut_ref(ref) ? kHeldCutRef : kRankCutRef);
}

/// A face between pieces: a block's or a rank's.
inline constexpr bool is_cut_ref(int ref) { return ref == kFrozenFaceRef || is_rank_cut_ref(ref); }

struct BlockPartition
{
    int num_blocks = 0;
    std::vector<int> block_of_tet;  ///< per tet slot; -1: dead, or kept out of every block
};

/// Blocks for a mesh of `live_tets` tets at `tets_per_block` each (at least 1).
int block_count(long long live_tets, int tets_per_block);

/// The live tets (those with active[t] when `active` is given) in `num_blocks` runs of equal
/// size along a Morton curve of their centroids; round r shifts the curve's cells by a
/// fraction of a block's width that is not a power of two, so its cuts fall elsewhere.
BlockPartition morton_blocks(const TetMesh& mesh, int num_blocks, int round,
                             const std::vector<char>* active = nullptr);

/// The live tets in `num_blocks` runs of equal size in id order: Morton blocks already when
/// the tets follow a space-filling curve (renumber_spatially).
BlockPartition contiguous_blocks(const TetMesh& mesh, int num_blocks);

/// Each block extracted as a mesh of its own, work(block mesh, block index) run on it (on
/// `workers`, blocks in any order; work must not use workers itself), and merged back. In a
/// block the faces it shares with another block or an inactive tet are required triangles of
/// ref kFrozenFaceRef and their vertices required vertices; work may change everything else, as
/// the serial engine does: split, collapse, swap, move free vertices, project new boundary
/// vertices. Vertices it does not move or remove keep their ids in the merge (required, corner,
/// feature-edge and non-interior vertices are found by their exact positions).
/// \pre mesh has its adjacency. Leaves it compact with its adjacency; returns, per vertex of
/// the merged mesh, whether it was on a cut: a face between two blocks.
std::vector<char> run_in_blocks(TetMesh& mesh, const BlockPartition& partition, Workers* workers,
                                const std::function<void(TetMesh& block, int index)>& work);

/// Per tet slot: whether it is within `rings` vertex rings of a vertex marked in `vertices`
/// (1: it has such a vertex).
std::vector<char> tets_near(const TetMesh& mesh, std::vector<char> vertices, int rings);

}  // namespace hdimesh::volume
