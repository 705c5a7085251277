#pragma once
// The cavity filler (issue 15): tets for any closed, outward-oriented set of triangles over a
// mesh's points, a hole left by a surface operation or a whole surface with several shells.
// Cheapest stage first:
//
//   1. fan from a cavity vertex          that sees every face not incident to it
//   2. fan from a kernel point           Chebyshev centre of the face half-spaces (a 3-D LP),
//                                        then smoothed inside the kernel (Schönhardt cavities)
//   3. exhaustive search                 small polyhedron reconnection (<= 32 points): the
//                                        max-min quality tetrahedralization, or a proof of none
//   4. advancing front with retreat      larger cavities and whole volumes (advancing_front.h)
//   5. grow the cavity                   by one layer of interior tets, then again from 1
//   6. give up                           nothing changed; the caller refuses its operation
//
// fill_cavity and refill_tets only compute: the mesh is not touched until commit_cavity.
// Steiner points are strictly inside the cavity, never on its faces. Every decision of
// topology uses the exact predicates of volume/mesh/predicates.h; ties go to the smaller vertex id,
// so the output is a function of the input alone.

#include <array>
#include <string>
#include <vector>

#include "common/size_field.h"
#include "volume/fill/fill_common.h"
#include "volume/mesh/tet_mesh.h"
#include "volume/mesh/tet_topology.h"

namespace hdimesh::volume
{

/// Fills the region bounded by `faces` (closed, each edge in exactly two faces with opposite
/// directions, outward-oriented; vertex ids into mesh.points). The mesh supplies points only.
/// field: sizes for interior points (nullptr: from the face sizes). Never throws on a cavity
/// that cannot be filled: filled = false with `failure` set.
CavityFill fill_cavity(const TetMesh& mesh, const std::vector<Triangle>& faces,
                       const SizeField* field, const CavityOptions& options = {});

/// Fills the hole left by removing the live tets `tets` (connected, one ref; needs adjacency),
/// growing it by whole layers of interior tets (never across mesh.triangles, a tet ref change
/// or the boundary) when stages 1-4 fail.
/// constraints: what may not be crossed when growing (nullptr: built from the mesh, O(mesh)).
CavityFill refill_tets(const TetMesh& mesh, const std::vector<int>& tets, const SizeField* field,
                       const CavityOptions& options = {},
                       const MeshConstraints* constraints = nullptr);

/// Puts a fill into the mesh in one step: adds new_points (Interior, ref 0), kills
/// removed_tets, adds the new tets with fill.ref into the freed slots first. Keeps the
/// adjacency when the mesh has it and is not empty (the new tets are linked to each other and
/// to the tets across fill.faces); into an empty mesh (a whole volume) the caller then runs
/// build_adjacency. mesh.triangles, refs and the classes of existing vertices are unchanged:
/// the faces are the cavity's boundary, kept exactly. Returns the new tet ids. O(n log n) in
/// the fill's size.
/// \pre fill.filled and mesh.num_vertices() == fill.first_new_vertex.
std::vector<int> commit_cavity(TetMesh& mesh, const CavityFill& fill);

/// Counts of fills by stage, for reports and benchmarks.
struct FillStatistics
{
    std::array<long, kNumFillStages> by_stage{};
    long grown = 0;  ///< fills that needed stage 5
    void add(const CavityFill& fill);
    std::string format() const;
};

}  // namespace hdimesh::volume
