#pragma once
// The mirror: surface hooks that keep a tet mesh in step with every operator of the surface
// remesher, so that the surface stays the tets' boundary (the paper's coupling, §6).
//
//   move      the vertex's ball stays positive, its worst Qe above the floor; then it moves.
//             Else the ball is a cavity, refilled around the vertex's new place:
//   split     the edge's shell, the new vertex added:  ┐
//   collapse  the removed vertex's ball                 │ cavity = those tets; its faces are
//   flip      the edge's shell                          │ their outer faces with the changed
//   remove    the removed vertex's ball                 ┘ surface triangles swapped for the new
//                                                         ones; fill_cavity refills it
//
// A cavity that cannot be filled, or whose new surface edge is already an edge of a kept tet,
// grows by the tets in the way (a layer across its inner faces, or that edge's shell; interior
// vertices it swallows go) and is tried again, a few times.
// allow_* simulates (the fill is computed, nothing changes); on_* commits what allow_* found.
// A refusal (no fill, a new surface edge still inside the volume, a fill under the floor)
// vetoes the surface operation, and neither mesh changes. mesh.triangles and their refs follow
// every change; edges, ridges, corners and classes are written back at the end (write_back).

#include <array>
#include <string>

#include "coupling/boundary_map.h"
#include "surface/local_ops.h"
#include "volume/fill/cavity.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::coupling
{

/// The filler's options for mirrored operations: a refusal only keeps the surface as it is, so
/// the advancing front gets a budget for a local cavity, not a whole volume.
volume::CavityOptions mirror_cavity_options();

struct MirrorOptions
{
    /// New tets may be worse than the worst of the tets they replace only down to this Qe.
    double min_quality = 0.001;
    volume::CavityOptions cavity = mirror_cavity_options();
};

/// What the mirror did, by operation.
struct MirrorStatistics
{
    enum Operation
    {
        Move,
        Split,
        Collapse,
        Flip,
        Remove,
        kOperations
    };
    /// Why an operation was refused (a refused move is Inverted or UnderFloor).
    enum Refusal
    {
        NoShell,         ///< the tets hold no such edge (or its shell walk failed)
        MixedRefs,       ///< the cavity would span two tet refs
        MissedTriangle,  ///< a changed surface triangle is not a face of the cavity
        Folds,           ///< the cavity's faces repeat other than as opposite pairs
        EdgeInside,      ///< a new surface edge is already an edge of a kept tet
        NoFill,          ///< the filler found no tets for the cavity
        UnderFloor,      ///< the fill (or the moved ball) is worse than min_quality allows
        Inverted,        ///< the move inverts a tet of the ball
        kRefusals
    };
    std::array<long, kOperations> done{}, refused{};
    std::array<long, kRefusals> refusals{};
    volume::FillStatistics fills;
    std::string format() const;
};

/// Hooks that mirror the surface operators of `map.surface` into `mesh`. Both must outlive
/// the hooks; `stats` (may be null) too. \pre map came from extract_boundary(mesh) (or the
/// surface is the tets' boundary, check_consistency), and mesh has adjacency.
surface::SurfaceHooks make_hooks(volume::TetMesh& mesh, BoundaryMap& map,
                                 const MirrorOptions& options = {},
                                 MirrorStatistics* stats = nullptr);

}  // namespace hdimesh::coupling
