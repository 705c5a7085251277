/* The adaptor on a mesh a user has: a Gmsh file read by PETSc (its physical groups become the
 * "Face Sets" and "Cell Sets" labels), distributed with overlap 0 on several ranks, an
 * isotropic or uniform DMPlexMetric, DMAdaptMetric with -dm_adaptor hdimesh, then PETSc's own
 * checks and ours: every region's volume kept (to `-volume_tolerance`, relative: a curved
 * boundary lands on its model), every face on the domain's boundary still labelled, the
 * interior labelled faces (interfaces) still there. Prints the tets, min Qe and min Qe in the
 * metric as tests/petsc/adapt_box.c does, so tests/petsc/ranks_compare.sh compares ranks.
 *   adapt_file -dll_append libhdimesh_petsc.so -dm_adaptor hdimesh -file F.msh
 *              [-metric iso|uniform] [-h 0.2] [-volume_tolerance 0.02] */
#include <petscdmplex.h>
#include <petscsf.h>

#include "plex_test.h"

static const char help[] = "Adapts a DMPlex read from a Gmsh file with -dm_adaptor hdimesh.\n";

#define MAX_REGIONS 16

/* The size at x: isotropic, finer towards x = -1 (the files' boxes span [-1, 1]), or uniform. */
static PetscReal SizeAt(const PetscReal x[3], PetscReal h, PetscBool uniform)
{
  return uniform ? h : h * (0.6 + 0.4 * (x[0] + 1));
}

/* Per region value (index = value, < MAX_REGIONS): the volume of its cells, over all ranks. */
static PetscErrorCode RegionVolumes(DM dm, PetscReal volumes[MAX_REGIONS])
{
  DMLabel  cells;
  PetscInt cStart, cEnd;

  PetscFunctionBeginUser;
  for (PetscInt r = 0; r < MAX_REGIONS; ++r) volumes[r] = 0;
  PetscCall(DMGetLabel(dm, "Cell Sets", &cells));
  PetscCheck(cells, PETSC_COMM_SELF, PETSC_ERR_PLIB, "no Cell Sets label");
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscReal vol, x[3], n[3];
    PetscInt  value;
    PetscCall(DMLabelGetValue(cells, c, &value));
    PetscCheck(value >= 0 && value < MAX_REGIONS, PETSC_COMM_SELF, PETSC_ERR_PLIB, "cell %" PetscInt_FMT ": region %" PetscInt_FMT, c, value);
    PetscCall(DMPlexComputeCellGeometryFVM(dm, c, &vol, x, n));
    volumes[value] += vol;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, volumes, MAX_REGIONS, MPIU_REAL, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  PetscFunctionReturn(0);
}

/* Faces on the domain's boundary without a Face Sets value, and interior faces with one. */
static PetscErrorCode CountFaces(DM dm, PetscInt *unlabelled_boundary, PetscInt *labelled_inside)
{
  DMLabel            faces;
  PetscSF            sf;
  PetscInt           pStart, pEnd, fStart, fEnd, nleaves, counts[2] = {0, 0};
  const PetscInt    *leaves, *degree;
  PetscBool         *shared;

  PetscFunctionBeginUser;
  PetscCall(DMGetLabel(dm, "Face Sets", &faces));
  PetscCheck(faces, PETSC_COMM_SELF, PETSC_ERR_PLIB, "no Face Sets label");
  /* a face on a rank's cut has one cell on each rank: shared in the point SF, not boundary */
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(PetscCalloc1(pEnd - pStart, &shared));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &leaves, NULL));
  for (PetscInt i = 0; i < nleaves && nleaves > 0; ++i) shared[(leaves ? leaves[i] : i) - pStart] = PETSC_TRUE;
  if (nleaves >= 0) {
    PetscCall(PetscSFComputeDegreeBegin(sf, &degree));
    PetscCall(PetscSFComputeDegreeEnd(sf, &degree));
    for (PetscInt p = pStart; p < pEnd; ++p)
      if (degree[p - pStart] > 0) shared[p - pStart] = PETSC_TRUE;
  }
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  for (PetscInt f = fStart; f < fEnd; ++f) {
    PetscInt value, support;
    PetscCall(DMLabelGetValue(faces, f, &value));
    PetscCall(DMPlexGetSupportSize(dm, f, &support));
    if (support == 1 && !shared[f - pStart] && value < 0) ++counts[0];
    if (support == 2 && value >= 0) ++counts[1];
  }
  PetscCall(PetscFree(shared));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  *unlabelled_boundary = counts[0];
  *labelled_inside     = counts[1];
  PetscFunctionReturn(0);
}

static void FileSizesAt(const PetscReal x[3], void *ctx, PetscReal s[3])
{
  s[0] = s[1] = s[2] = SizeAt(x, *(const PetscReal *)ctx, PETSC_FALSE);
}

static PetscErrorCode CreateMetric(DM dm, PetscReal h, PetscBool uniform, Vec *metric)
{
  PetscFunctionBeginUser;
  if (uniform) PetscCall(DMPlexMetricCreateUniform(dm, 0, 1 / (h * h), metric));
  else PetscCall(CreateSizeMetric(dm, FileSizesAt, &h, PETSC_FALSE, metric));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  DM          dm, adapted;
  DMLabel     bd, rg;
  Vec         metric;
  PetscReal   h = 0.2, tolerance = 0.02, before[MAX_REGIONS], after[MAX_REGIONS], min_qe = 1, min_metric_qe = 1;
  PetscInt    cStart, cEnd, counts[2], unlabelled, inside_before, inside_after, tets;
  PetscMPIInt size;
  char        file[PETSC_MAX_PATH_LEN] = "", kind[16] = "iso";
  PetscBool   uniform, found;
  DM          cdm;
  Vec         coords;
  PetscSection cs;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-file", file, sizeof file, &found));
  PetscCheck(found, PETSC_COMM_WORLD, PETSC_ERR_USER, "give -file F.msh");
  PetscCall(PetscOptionsGetString(NULL, NULL, "-metric", kind, sizeof kind, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-h", &h, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-volume_tolerance", &tolerance, NULL));
  PetscCall(PetscStrcmp(kind, "uniform", &uniform));
  PetscCall(DMPlexCreateFromFile(PETSC_COMM_WORLD, file, "adapt_file", PETSC_TRUE, &dm));
  if (size > 1) {
    DM distributed = NULL;
    PetscCall(DMPlexDistribute(dm, 0, NULL, &distributed));
    if (distributed) {
      PetscCall(DMDestroy(&dm));
      dm = distributed;
    }
  }
  PetscCall(DMGetLabel(dm, "Face Sets", &bd));
  PetscCall(DMGetLabel(dm, "Cell Sets", &rg));
  PetscCheck(bd && rg, PETSC_COMM_WORLD, PETSC_ERR_USER, "%s: no physical surfaces and volumes", file);
  PetscCall(RegionVolumes(dm, before));
  PetscCall(CountFaces(dm, &unlabelled, &inside_before));
  PetscCall(CreateMetric(dm, h, uniform, &metric));
  PetscCall(DMAdaptMetric(dm, metric, bd, rg, &adapted));

  PetscCall(DMPlexCheck(adapted));
  PetscCall(RegionVolumes(adapted, after));
  for (PetscInt r = 0; r < MAX_REGIONS; ++r) {
    PetscCheck((before[r] > 0) == (after[r] > 0), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "region %" PetscInt_FMT " lost or made up", r);
    PetscCheck(PetscAbsReal(after[r] - before[r]) <= tolerance * before[r], PETSC_COMM_WORLD, PETSC_ERR_PLIB, "region %" PetscInt_FMT ": volume %g, was %g", r, (double)after[r], (double)before[r]);
  }
  PetscCall(CountFaces(adapted, &unlabelled, &inside_after));
  PetscCheck(unlabelled == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%" PetscInt_FMT " boundary faces lost their label", unlabelled);
  PetscCheck((inside_before > 0) == (inside_after > 0), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "labelled interior faces: %" PetscInt_FMT ", were %" PetscInt_FMT, inside_after, inside_before);

  PetscCall(DMGetCoordinateDM(adapted, &cdm));
  PetscCall(DMGetCoordinatesLocal(adapted, &coords));
  PetscCall(DMGetLocalSection(cdm, &cs));
  PetscCall(DMPlexGetHeightStratum(adapted, 0, &cStart, &cEnd));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscInt     nx = 0;
    PetscScalar *cx = NULL, y[12];
    PetscReal    g[3] = {0, 0, 0}, s;
    PetscCall(DMPlexVecGetClosure(cdm, cs, coords, c, &nx, &cx));
    for (PetscInt k = 0; k < 12; ++k) g[k % 3] += PetscRealPart(cx[k]) / 4;
    s = SizeAt(g, h, uniform);
    for (PetscInt k = 0; k < 12; ++k) y[k] = cx[k] / s;
    min_qe        = PetscMin(min_qe, ShapeQuality(cx));
    min_metric_qe = PetscMin(min_metric_qe, ShapeQuality(y));
    PetscCall(DMPlexVecRestoreClosure(cdm, cs, coords, c, &nx, &cx));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &min_qe, 1, MPIU_REAL, MPI_MIN, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &min_metric_qe, 1, MPIU_REAL, MPI_MIN, PETSC_COMM_WORLD));
  tets = cEnd - cStart;
  PetscCallMPI(MPI_Allreduce(&tets, &counts[0], 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  counts[1] = inside_after;
  {
    PetscReal total_before = 0, total_after = 0;
    for (PetscInt r = 0; r < MAX_REGIONS; ++r) {
      total_before += before[r];
      total_after += after[r];
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "adapted: %" PetscInt_FMT " tets, min Qe %.6f, in the metric %.6f, volume %.6f (was %.6f), %" PetscInt_FMT " interface faces\n", counts[0], (double)min_qe, (double)min_metric_qe, (double)total_after, (double)total_before, counts[1]));
  }
  PetscCall(VecDestroy(&metric));
  PetscCall(DMDestroy(&adapted));
  PetscCall(DMDestroy(&dm));
  PetscCall(PetscFinalize());
  return 0;
}
