#pragma once
// The adaptor's private pieces: a DMPlex's tets, labels, metric and options as hdimesh takes
// them, shared by the one-rank path (hdimesh_petsc.cpp) and the ranks' (distributed.cpp).

#include <petscdmplex.h>
#include <petscsf.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "coupling/adapt_request.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh_petsc
{

/// A label's values as refs 1..k in increasing order; ref 0 is "no value".
struct LabelRefs
{
    std::vector<PetscInt> values;

    int ref(PetscInt value) const
    {
        const auto it = std::lower_bound(values.begin(), values.end(), value);
        return it != values.end() && *it == value ? static_cast<int>(it - values.begin()) + 1 : 0;
    }
    /// The value of ref r; false for ref 0 or a ref the adaptation made up.
    bool value(int r, PetscInt& out) const
    {
        if (r < 1 || r > static_cast<int>(values.size())) return false;
        out = values[r - 1];
        return true;
    }
};

/// The values label gives points [pStart, pEnd), sorted and without the default (-1).
PetscErrorCode label_refs(DMLabel label, PetscInt pStart, PetscInt pEnd, LabelRefs& refs);

/// The vertex points in the closure of point p, in closure order.
PetscErrorCode closure_vertices(DM dm, PetscInt p, PetscInt vStart, PetscInt vEnd,
                                std::vector<PetscInt>& out);

double signed_volume(const hdimesh::volume::TetMesh& m, const std::array<int, 4>& t);

/// What the adaptor reads off the DM: the tets and their faces, with the labels as refs.
struct PlexInput
{
    hdimesh::volume::TetMesh mesh;
    LabelRefs face_refs, cell_refs;
};

/// dm's tets (positive), its coordinates, every boundary face and every face bdLabel marks as
/// triangles (refs from bdLabel; 0 for an unmarked boundary face) and rgLabel's cell refs.
PetscErrorCode read_plex(DM dm, DMLabel bdLabel, DMLabel rgLabel, PlexInput& in);

/// The metric Vec (local, DMPlexMetricCreate's) as sizes (isotropic) or Medit-order tensors
/// at the DM's nv local vertices, checked.
PetscErrorCode read_metric(DM dm, Vec metric, int nv, hdimesh::volume::SizeSpec& size);

/// PETSc's metric options that have a meaning here, as Mmg's switches; the report to PETSc's
/// output when verbose.
PetscErrorCode read_options(DM dm, hdimesh::coupling::AdaptRequest& request);

/// The checks a file read makes, then run_adapt: the error's text, empty when it ran.
std::string run_request(hdimesh::volume::TetMesh mesh,
                        const hdimesh::coupling::AdaptRequest& request,
                        hdimesh::coupling::AdaptResult& result);

/// The labels rebuilt on dm (the mesh's vertex v is dm's point[v]): triangles' refs as face
/// values, tets' refs as cell values (tet c is dm's cell c), under their names.
PetscErrorCode attach_labels(DM dm, const hdimesh::volume::TetMesh& mesh,
                             const std::vector<PetscInt>& point, const LabelRefs& face_refs,
                             const LabelRefs& cell_refs, const char* bd_name, const char* rg_name);

/// The adapted mesh as a new DM on comm's one rank, the labels rebuilt under their names.
PetscErrorCode write_plex(MPI_Comm comm, hdimesh::volume::TetMesh& mesh, const PlexInput& in,
                          const char* bd_name, const char* rg_name, DM* dmNew);

/// The ranks' scheme (ParMmg's): each rank adapts its cells with the faces it shares frozen,
/// the cells move to a new decomposition whose cuts lie elsewhere, num_iterations times; the
/// last rounds' cells make the new DM.
PetscErrorCode adapt_distributed(DM dm, Vec metric, DMLabel bdLabel, DMLabel rgLabel,
                                 const char* bd_name, const char* rg_name, DM* dmNew);

}  // namespace hdimesh_petsc
