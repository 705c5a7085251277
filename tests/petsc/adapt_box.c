/* A PETSc program as a user writes it: a DMPlex box from a cell list, labelled faces (the six
 * sides 1..6, the inner plane x = 0.5 as 7) and cells (x < 0.5: 1, else 2), a DMPlexMetric,
 * DMAdaptMetric with -dm_adaptor hdimesh (loaded by -dll_append), then PETSc's own checks and
 * ours: volume kept, labels on the right faces and cells, edges near the metric's sizes. It
 * prints the tets, min Qe and min Qe in the metric (the shape the adaptation works on; the
 * cells that lower it, as found, with ADAPT_BOX_WORST set).
 *   adapt_box -dll_append libhdimesh_petsc.so -dm_adaptor hdimesh [-metric iso|aniso|uniform]
 *             [-n 4] [-h 0.12] [-jitter 0] */
#include <petscdmplex.h>

#include "plex_test.h"

static const char help[] = "Adapts a DMPlex box with -dm_adaptor hdimesh and checks it.\n";

/* The metric's sizes at x: isotropic h (finer towards x = 0), or hx along x and 3 hx across. */
static void sizes_at(const PetscReal x[3], PetscReal h, PetscBool aniso, PetscReal s[3])
{
  const PetscReal hx = h * (0.6 + 0.8 * x[0]);
  s[0] = hx;
  s[1] = s[2] = aniso ? 3 * hx : hx;
}

/* n^3 cubes, 6 tets each (Kuhn's split, conforming between cubes), inward as Plex lists them;
 * rank 0 gives them all. */
static PetscErrorCode CreateBox(PetscInt n, PetscReal jitter, DM *dm)
{
  PetscMPIInt    rank;
  PetscInt       nv = (n + 1) * (n + 1) * (n + 1), nc = 6 * n * n * n;
  const PetscInt perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  PetscInt      *cells, c = 0;
  PetscReal     *xyz;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(4 * nc, &cells, 3 * nv, &xyz));
  for (PetscInt k = 0; k <= n; ++k)
    for (PetscInt j = 0; j <= n; ++j)
      for (PetscInt i = 0; i <= n; ++i) {
        const PetscInt v = i + (n + 1) * (j + (n + 1) * k);
        xyz[3 * v]         = (PetscReal)i / n;
        xyz[3 * v + 1]     = (PetscReal)j / n;
        xyz[3 * v + 2]     = (PetscReal)k / n;
        /* -jitter moves inner vertices by a fixed pseudo-random offset: an input that is no lattice */
        if (i > 0 && i < n && j > 0 && j < n && k > 0 && k < n)
          for (PetscInt d = 0; d < 3; ++d)
            if (d > 0 || 2 * i != n) xyz[3 * v + d] += jitter / n * (((v * 7919 + d * 104729) % 1000) / 500.0 - 1); /* the plane x = 0.5 stays */
      }
  for (PetscInt k = 0; k < n; ++k)
    for (PetscInt j = 0; j < n; ++j)
      for (PetscInt i = 0; i < n; ++i)
        for (PetscInt p = 0; p < 6; ++p) {
          PetscInt ijk[3] = {i, j, k};
          for (PetscInt s = 0; s < 4; ++s) {
            if (s > 0) ++ijk[perms[p][s - 1]];
            cells[4 * c + s] = ijk[0] + (n + 1) * (ijk[1] + (n + 1) * ijk[2]);
          }
          { /* Plex wants the first face to see the fourth vertex on its negative side */
            const PetscReal *a = &xyz[3 * cells[4 * c]], *b = &xyz[3 * cells[4 * c + 1]];
            const PetscReal *d = &xyz[3 * cells[4 * c + 2]], *e = &xyz[3 * cells[4 * c + 3]];
            PetscReal u[3], w[3], z[3], vol;
            for (PetscInt q = 0; q < 3; ++q) {
              u[q] = b[q] - a[q];
              w[q] = d[q] - a[q];
              z[q] = e[q] - a[q];
            }
            vol = u[0] * (w[1] * z[2] - w[2] * z[1]) - u[1] * (w[0] * z[2] - w[2] * z[0]) + u[2] * (w[0] * z[1] - w[1] * z[0]);
            if (vol > 0) {
              const PetscInt t = cells[4 * c];
              cells[4 * c]     = cells[4 * c + 1];
              cells[4 * c + 1] = t;
            }
          }
          ++c;
        }
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (rank > 0) nc = nv = 0;
  PetscCall(DMPlexCreateFromCellListPetsc(PETSC_COMM_WORLD, 3, nc, nv, 4, PETSC_TRUE, cells, 3, xyz, dm));
  PetscCall(PetscFree2(cells, xyz));
  PetscFunctionReturn(0);
}

static PetscErrorCode Centroid(DM dm, PetscInt p, PetscReal x[3])
{
  PetscReal vol, normal[3];

  PetscFunctionBeginUser;
  PetscCall(DMPlexComputeCellGeometryFVM(dm, p, &vol, x, normal));
  PetscFunctionReturn(0);
}

/* The side a face lies on (1..6), 7 on the plane x = 0.5, else -1. */
static PetscInt FaceValue(const PetscReal x[3])
{
  for (PetscInt d = 0; d < 3; ++d) {
    if (PetscAbsReal(x[d]) < 1e-10) return 2 * d + 1;
    if (PetscAbsReal(x[d] - 1) < 1e-10) return 2 * d + 2;
  }
  if (PetscAbsReal(x[0] - 0.5) < 1e-10) return 7;
  return -1;
}

static PetscErrorCode Label(DM dm, DMLabel *bd, DMLabel *rg)
{
  PetscInt cStart, cEnd, fStart, fEnd;

  PetscFunctionBeginUser;
  PetscCall(DMCreateLabel(dm, "boundary"));
  PetscCall(DMGetLabel(dm, "boundary", bd));
  PetscCall(DMCreateLabel(dm, "regions"));
  PetscCall(DMGetLabel(dm, "regions", rg));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  for (PetscInt f = fStart; f < fEnd; ++f) {
    PetscReal x[3];
    PetscInt  value;
    PetscCall(Centroid(dm, f, x));
    value = FaceValue(x);
    if (value > 0) PetscCall(DMLabelSetValue(*bd, f, value));
  }
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscReal x[3];
    PetscCall(Centroid(dm, c, x));
    PetscCall(DMLabelSetValue(*rg, c, x[0] < 0.5 ? 1 : 2));
  }
  PetscFunctionReturn(0);
}

typedef struct {
  PetscReal h;
  PetscBool aniso;
} BoxSizes;

static void BoxSizesAt(const PetscReal x[3], void *ctx, PetscReal s[3])
{
  const BoxSizes *b = (const BoxSizes *)ctx;
  sizes_at(x, b->h, b->aniso, s);
}

static PetscErrorCode CreateMetric(DM dm, PetscReal h, PetscBool aniso, PetscBool uniform, Vec *metric)
{
  BoxSizes sizes = {h, aniso};

  PetscFunctionBeginUser;
  if (uniform) PetscCall(DMPlexMetricCreateUniform(dm, 0, 1 / (h * h), metric));
  else PetscCall(CreateSizeMetric(dm, BoxSizesAt, &sizes, aniso, metric));
  PetscFunctionReturn(0);
}

/* Labels where they belong, the volume kept, and the share of edges within [1/sqrt2, sqrt2] of
 * the metric's size. */

static PetscErrorCode CheckAdapted(DM dm, PetscReal h, PetscBool aniso, PetscBool uniform)
{
  PetscInt  cStart, cEnd, fStart, fEnd, eStart, eEnd, bad = 0, in_range = 0, seen[8] = {0}, counts[3];
  PetscReal volume = 0, min_qe = 1, min_metric_qe = 1, digest = 0;
  DMLabel   bd, rg, outer;
  DM        cdm;
  Vec       coords;
  PetscSection cs;
  PetscMPIInt  size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(DMPlexCheck(dm));
  PetscCall(DMGetLabel(dm, "boundary", &bd));
  PetscCall(DMGetLabel(dm, "regions", &rg));
  PetscCheck(bd && rg, PETSC_COMM_SELF, PETSC_ERR_PLIB, "labels lost");
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 1, &eStart, &eEnd));
  PetscCall(DMLabelCreate(PETSC_COMM_SELF, "outer", &outer));
  PetscCall(DMPlexMarkBoundaryFaces(dm, 1, outer));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(DMGetLocalSection(cdm, &cs));
  for (PetscInt c = cStart; c < cEnd; ++c) {
    PetscReal    x[3], vol, normal[3];
    PetscInt     value, nx = 0;
    PetscScalar *cx = NULL;
    PetscCall(DMPlexVecGetClosure(cdm, cs, coords, c, &nx, &cx));
    { /* the shape in the metric: the cell scaled by the sizes at its centroid */
      PetscScalar y[12];
      PetscReal   g[3] = {0, 0, 0}, s[3];
      for (PetscInt k = 0; k < 12; ++k) g[k % 3] += PetscRealPart(cx[k]) / 4;
      sizes_at(g, h, aniso, s);
      if (uniform) s[0] = s[1] = s[2] = h;
      for (PetscInt k = 0; k < 12; ++k) y[k] = cx[k] / s[k % 3];
      const PetscReal q = ShapeQuality(y);
      if (q < min_metric_qe && getenv("ADAPT_BOX_WORST")) {
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "worse: %g at", (double)q));
        for (PetscInt k = 0; k < 12; ++k) PetscCall(PetscPrintf(PETSC_COMM_SELF, " %g%s", (double)PetscRealPart(cx[k]), k % 3 == 2 && k < 11 ? " |" : ""));
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "\n"));
      }
      min_metric_qe = PetscMin(min_metric_qe, q);
    }
    min_qe = PetscMin(min_qe, ShapeQuality(cx));
    PetscCall(DMPlexVecRestoreClosure(cdm, cs, coords, c, &nx, &cx));
    PetscCall(DMPlexComputeCellGeometryFVM(dm, c, &vol, x, normal));
    volume += vol;
    digest += x[0] + 2 * x[1] + 3 * x[2];
    PetscCall(DMLabelGetValue(rg, c, &value));
    if (value != (x[0] < 0.5 ? 1 : 2)) ++bad;
  }
  PetscCheck(bad == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%" PetscInt_FMT " cells in the wrong region", bad);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &volume, 1, MPIU_REAL, MPI_SUM, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &digest, 1, MPIU_REAL, MPI_SUM, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &min_qe, 1, MPIU_REAL, MPI_MIN, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &min_metric_qe, 1, MPIU_REAL, MPI_MIN, PETSC_COMM_WORLD));
  PetscCheck(PetscAbsReal(volume - 1) < 1e-10, PETSC_COMM_SELF, PETSC_ERR_PLIB, "volume %g, not 1", (double)volume);
  for (PetscInt f = fStart; f < fEnd; ++f) {
    PetscReal x[3];
    PetscInt  value, on_boundary, expect;
    PetscCall(Centroid(dm, f, x));
    PetscCall(DMLabelGetValue(bd, f, &value));
    PetscCall(DMLabelGetValue(outer, f, &on_boundary));
    expect = FaceValue(x);
    /* on several ranks 3.18 marks a face on a rank's cut as boundary too */
    if (value != expect || (on_boundary == 1 && expect < 0 && size == 1)) {
      if (bad < 5) PetscCall(PetscPrintf(PETSC_COMM_SELF, "face at (%g %g %g): value %d, expected %d, marked boundary %d\n", (double)x[0], (double)x[1], (double)x[2], (int)value, (int)expect, (int)on_boundary));
      ++bad;
    }
    if (value > 0) seen[value] = 1;
  }
  PetscCheck(bad == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%" PetscInt_FMT " faces labelled wrongly", bad);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, seen, 8, MPIU_INT, MPI_MAX, PETSC_COMM_WORLD));
  for (PetscInt v = 1; v <= 7; ++v) PetscCheck(seen[v], PETSC_COMM_SELF, PETSC_ERR_PLIB, "no face keeps value %" PetscInt_FMT, v);
  for (PetscInt e = eStart; e < eEnd; ++e) {
    PetscReal x[3], len = 0, s[3], lm = 0, a[3], b[3];
    PetscInt *closure = NULL, n, k = 0;
    PetscCall(Centroid(dm, e, x));
    PetscCall(DMPlexGetTransitiveClosure(dm, e, PETSC_TRUE, &n, &closure));
    { /* the edge's two vertices: its closure's last two points */
      Vec                coords;
      PetscSection       cs;
      const PetscScalar *xyz;
      PetscInt           off;
      PetscCall(DMGetCoordinatesLocal(dm, &coords));
      PetscCall(DMGetCoordinateSection(dm, &cs));
      PetscCall(VecGetArrayRead(coords, &xyz));
      PetscCall(PetscSectionGetOffset(cs, closure[2], &off));
      for (k = 0; k < 3; ++k) a[k] = PetscRealPart(xyz[off + k]);
      PetscCall(PetscSectionGetOffset(cs, closure[4], &off));
      for (k = 0; k < 3; ++k) b[k] = PetscRealPart(xyz[off + k]);
      PetscCall(VecRestoreArrayRead(coords, &xyz));
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, e, PETSC_TRUE, &n, &closure));
    sizes_at(x, h, aniso, s);
    if (uniform) s[0] = s[1] = s[2] = h;
    for (k = 0; k < 3; ++k) {
      len += (b[k] - a[k]) * (b[k] - a[k]);
      lm += (b[k] - a[k]) * (b[k] - a[k]) / (s[k] * s[k]);
    }
    lm = PetscSqrtReal(lm);
    if (lm >= 1 / PetscSqrtReal(2.0) && lm <= PetscSqrtReal(2.0)) ++in_range;
  }
  PetscCall(DMLabelDestroy(&outer));
  counts[0] = cEnd - cStart;
  counts[1] = in_range;
  counts[2] = eEnd - eStart; /* edges on a cut are counted on each rank */
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, counts, 3, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "adapted: %" PetscInt_FMT " tets, min Qe %.6f, in the metric %.6f, %.1f %% of %" PetscInt_FMT " edges in [1/sqrt2, sqrt2], digest %.17g\n", counts[0], (double)min_qe, (double)min_metric_qe, 100.0 * counts[1] / counts[2], counts[2], (double)digest));
  { /* PETSc's -dm_plex_metric_no_insert reaches the adaptor: no vertex added or removed */
    PetscBool no_insert = PETSC_FALSE;
    PetscInt  vStart, vEnd, nv;
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-dm_plex_metric_no_insert", &no_insert, NULL));
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    nv = vEnd - vStart;
    if (no_insert) {
      PetscCheck(size == 1, PETSC_COMM_SELF, PETSC_ERR_SUP, "checked on one rank");
      PetscCheck(nv == 125, PETSC_COMM_SELF, PETSC_ERR_PLIB, "no_insert: %" PetscInt_FMT " vertices, not the input's 125", nv);
      PetscFunctionReturn(0);
    }
  }
  PetscCheck(counts[1] >= 0.75 * counts[2], PETSC_COMM_SELF, PETSC_ERR_PLIB, "too few edges in range");
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  DM          dm, adapted;
  DMLabel     bd, rg;
  Vec         metric;
  PetscInt    n = 4;
  PetscReal   h = 0.12, jitter = 0;
  char        kind[16] = "iso";
  PetscBool   aniso, uniform;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &n, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-h", &h, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-metric", kind, sizeof kind, NULL));
  PetscCall(PetscStrcmp(kind, "aniso", &aniso));
  PetscCall(PetscStrcmp(kind, "uniform", &uniform));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-jitter", &jitter, NULL));
  PetscCall(CreateBox(n, jitter, &dm));
  PetscCall(DMPlexCheck(dm));
  PetscCall(Label(dm, &bd, &rg));
  { /* on several ranks, PETSc's partitioner shares the box out (labels go with it) */
    DM dist = NULL;
    PetscCall(DMPlexDistribute(dm, 0, NULL, &dist));
    if (dist) {
      PetscCall(DMDestroy(&dm));
      dm = dist;
      PetscCall(DMGetLabel(dm, "boundary", &bd));
      PetscCall(DMGetLabel(dm, "regions", &rg));
    }
  }
  PetscCall(CreateMetric(dm, h, aniso, uniform, &metric));
  PetscCall(DMAdaptMetric(dm, metric, bd, rg, &adapted));
  PetscCall(CheckAdapted(adapted, h, aniso, uniform));
  PetscCall(VecDestroy(&metric));
  PetscCall(DMDestroy(&adapted));
  PetscCall(DMDestroy(&dm));
  PetscCall(PetscFinalize());
  return 0;
}
