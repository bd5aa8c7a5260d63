/* The solver's built-in types, registered in one place: detachment criteria, load controls and
   contact-set predictors. A new type is a file (or a folder) in impls/<kind>/ whose create
   function fills in the kind's ops (solverimpl.h), and its line here (docs/code-map.md). Here too
   the results layer is bound to the path (AdhResultsOps): the one place the solver names it. */
#include "results/resultsimpl.h"

PETSC_INTERN PetscErrorCode AdhCriterionCreate_PohrtPopov(AdhSolver);
PETSC_INTERN PetscErrorCode AdhCriterionCreate_CrackClosure(AdhSolver);
PETSC_INTERN PetscErrorCode AdhControlCreate_Displacement(AdhSolver);
PETSC_INTERN PetscErrorCode AdhControlCreate_Force(AdhSolver);
PETSC_INTERN PetscErrorCode AdhPredictorCreate_None(AdhSolver);
PETSC_INTERN PetscErrorCode AdhPredictorCreate_PolonskyKeer(AdhSolver);

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

/* The built-in types, in the order -help and the error messages list them. */
PetscErrorCode AdhSolverRegisterAll_Private(void)
{
  PetscFunctionBegin;
  PetscCall(AdhCriterionRegister(ADHCRITERIONPOHRTPOPOV, AdhCriterionCreate_PohrtPopov));
  PetscCall(AdhCriterionRegister(ADHCRITERIONCRACKCLOSURE, AdhCriterionCreate_CrackClosure));
  PetscCall(AdhControlRegister(ADHCONTROLDISPLACEMENT, AdhControlCreate_Displacement));
  PetscCall(AdhControlRegister(ADHCONTROLFORCE, AdhControlCreate_Force));
  PetscCall(AdhPredictorRegister(ADHPREDICTORNONE, AdhPredictorCreate_None));
  PetscCall(AdhPredictorRegister(ADHPREDICTORPOLONSKYKEER, AdhPredictorCreate_PolonskyKeer));
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
  AdhResults = (AdhResultsOps){.check_writable = AdhOutputCheckWritable_Private, .open = AdhOutputOpen_Private, .resume = AdhOutputResume_Private, .write_fields = AdhOutputWriteFields_Private, .append = AdhOutputAppend_Private, .close = AdhOutputClose_Private, .checkpoint_write = AdhCheckpointWrite_Private, .checkpoint_read = AdhCheckpointRead_Private};
  PetscCall(PetscRegisterFinalize(AdhSolverFinalizePackage));
  PetscFunctionReturn(0);
}
