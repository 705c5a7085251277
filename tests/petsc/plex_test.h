/* What tests/petsc's programs share: the shape quality and a metric from sizes at vertices. */
#pragma once
#include <petscdmplex.h>

/* Qe = 2 sqrt(6) inradius / longest edge (1 for a regular tet), of 4 points' coordinates */
static PetscReal ShapeQuality(const PetscScalar *x)
{
    PetscReal area = 0, longest = 0, e[6][3], vol;
    const PetscInt pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    const PetscInt faces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    for (PetscInt k = 0; k < 6; ++k)
    {
        PetscReal l = 0;
        for (PetscInt d = 0; d < 3; ++d)
        {
            e[k][d] = PetscRealPart(x[3 * pairs[k][1] + d] - x[3 * pairs[k][0] + d]);
            l += e[k][d] * e[k][d];
        }
        longest = PetscMax(longest, PetscSqrtReal(l));
    }
    vol = PetscAbsReal(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                       e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                       e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
          6;
    for (PetscInt f = 0; f < 4; ++f)
    {
        PetscReal u[3], w[3], c[3];
        for (PetscInt d = 0; d < 3; ++d)
        {
            u[d] = PetscRealPart(x[3 * faces[f][1] + d] - x[3 * faces[f][0] + d]);
            w[d] = PetscRealPart(x[3 * faces[f][2] + d] - x[3 * faces[f][0] + d]);
        }
        c[0] = u[1] * w[2] - u[2] * w[1];
        c[1] = u[2] * w[0] - u[0] * w[2];
        c[2] = u[0] * w[1] - u[1] * w[0];
        area += 0.5 * PetscSqrtReal(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    return 2 * PetscSqrtReal(6.0) * (3 * vol / area) / longest;
}

/* The sizes along x, y, z at a point (one, isotropic, when they are equal). */
typedef void (*SizesAt)(const PetscReal x[3], void *ctx, PetscReal s[3]);

/* A DMPlexMetric from sizes at the vertices: isotropic (s[0]) or the diagonal tensor. */
static PetscErrorCode CreateSizeMetric(DM dm, SizesAt sizes, void *ctx, PetscBool aniso,
                                       Vec *metric)
{
    PetscInt vStart, vEnd;
    PetscSection cs, ms;
    Vec coords;
    const PetscScalar *x;
    PetscScalar *m;
    DM mdm;

    PetscFunctionBeginUser;
    PetscCall(DMPlexMetricSetIsotropic(dm, aniso ? PETSC_FALSE : PETSC_TRUE));
    PetscCall(DMPlexMetricCreate(dm, 0, metric));
    PetscCall(VecGetDM(*metric, &mdm));
    PetscCall(DMGetLocalSection(mdm, &ms));
    PetscCall(DMGetCoordinateSection(dm, &cs));
    PetscCall(DMGetCoordinatesLocal(dm, &coords));
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    PetscCall(VecGetArrayRead(coords, &x));
    PetscCall(VecGetArray(*metric, &m));
    for (PetscInt v = vStart; v < vEnd; ++v)
    {
        PetscInt xo, mo;
        PetscReal p[3], s[3];
        PetscCall(PetscSectionGetOffset(cs, v, &xo));
        PetscCall(PetscSectionGetOffset(ms, v, &mo));
        for (PetscInt d = 0; d < 3; ++d) p[d] = PetscRealPart(x[xo + d]);
        sizes(p, ctx, s);
        if (!aniso)
            m[mo] = 1 / (s[0] * s[0]);
        else
            for (PetscInt i = 0; i < 3; ++i)
                for (PetscInt j = 0; j < 3; ++j) m[mo + 3 * i + j] = i == j ? 1 / (s[i] * s[i]) : 0;
    }
    PetscCall(VecRestoreArray(*metric, &m));
    PetscCall(VecRestoreArrayRead(coords, &x));
    PetscFunctionReturn(0);
}
