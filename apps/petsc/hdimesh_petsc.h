/* hdimesh as a PETSc DMPlex adaptor: `-dm_adaptor hdimesh` in DMAdaptMetric().
 *
 * Load it with `-dll_append /path/libhdimesh_petsc.so` (PETSc then calls
 * PetscDLLibraryRegister_hdimesh_petsc), or link it and call HdimeshPetscRegister() after
 * PetscInitialize(). Either registers "hdimesh" once. */
#ifndef HDIMESH_PETSC_H
#define HDIMESH_PETSC_H

#include <petscdmplex.h>

/* Registers the adaptor with DMGenerateRegister (once per PetscInitialize). */
PETSC_EXTERN PetscErrorCode HdimeshPetscRegister(void);

/* The adapt callback: dm adapted to the DMPlexMetric metric (the local vector, isotropic or
 * full dim x dim per vertex); bdLabel's face values and rgLabel's cell values are kept (NULL:
 * "_boundary_" marks every boundary face 1, "_regions_" holds the cells' values). */
PETSC_EXTERN PetscErrorCode DMAdaptMetric_Hdimesh_Plex(DM dm, Vec metric, DMLabel bdLabel,
                                                       DMLabel rgLabel, DM* dmNew);

#endif
