/* The solver's package: its initialisation, which registers the built-in types (impls/register.c)
   and binds the results layer to the path (AdhResultsOps): the one place the solver names the
   layer above it, the way PETSc's XXXInitializePackage reaches its implementations. */
#include "results/resultsimpl.h"

PETSC_INTERN PetscErrorCode AdhSolverRegisterAll_Private(void); /* impls/register.c */

AdhResultsOps    AdhResults;
static PetscBool AdhSolverPackageInitialized = PETSC_FALSE;

static PetscErrorCode AdhSolverFinalizePackage(void)
{
  PetscFunctionBegin;
  PetscCall(AdhRegistryDestroy_Private(&AdhCriteria));
  PetscCall(AdhRegistryDestroy_Private(&AdhControls));
  PetscCall(AdhRegistryDestroy_Private(&AdhPredictors));
  AdhSolverPackageInitialized = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Registers the built-in types once (the way KSPInitializePackage does); called by
   AdhSolverCreate() and by every Register and SetType function. */
PetscErrorCode AdhSolverInitializePackage(void)
{
  PetscFunctionBegin;
  if (AdhSolverPackageInitialized) PetscFunctionReturn(0);
  AdhSolverPackageInitialized = PETSC_TRUE;
  PetscCall(AdhInitializePackage());
  PetscCall(AdhSolverRegisterAll_Private());
  {
    /* a failed write is told in one line that names the file (results/diskspace.c): HDF5's own
       print of its error stack stays behind -adh_traceback, as PETSc's traceback does */
    PetscBool traceback = PETSC_FALSE;
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-adh_traceback", &traceback, NULL));
    if (!traceback) ADH_H5(H5Eset_auto2(H5E_DEFAULT, NULL, NULL));
  }
  AdhResults = (AdhResultsOps){.check_writable = AdhOutputCheckWritable_Private, .open = AdhOutputOpen_Private, .resume = AdhOutputResume_Private, .write_fields = AdhOutputWriteFields_Private, .append = AdhOutputAppend_Private, .close = AdhOutputClose_Private, .abandon = AdhOutputAbandon_Private, .checkpoint_write = AdhCheckpointWrite_Private, .checkpoint_read = AdhCheckpointRead_Private};
  PetscCall(PetscRegisterFinalize(AdhSolverFinalizePackage));
  PetscFunctionReturn(0);
}
