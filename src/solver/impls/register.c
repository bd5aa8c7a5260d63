/* The solver's registered types in one place: detachment criteria, load controls and contact-set
   predictors. A new type is one file in impls/<kind>/ that fills in the kind's ops table
   (solverimpl.h), and its prototype and registration here (docs/code-map.md). Here too the
   results layer is bound to the path (AdhResultsOps): the one place the solver names it. */
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
  PetscCall(AdhCriterionDestroyList_Private());
  PetscCall(AdhControlDestroyList_Private());
  PetscCall(AdhPredictorDestroyList_Private());
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
  PetscCall(AdhCriterionRegister(ADHCRITERIONPOHRTPOPOV, AdhCriterionCreate_PohrtPopov));
  PetscCall(AdhCriterionRegister(ADHCRITERIONCRACKCLOSURE, AdhCriterionCreate_CrackClosure));
  PetscCall(AdhControlRegister(ADHCONTROLDISPLACEMENT, AdhControlCreate_Displacement));
  PetscCall(AdhControlRegister(ADHCONTROLFORCE, AdhControlCreate_Force));
  PetscCall(AdhPredictorRegister(ADHPREDICTORNONE, AdhPredictorCreate_None));
  PetscCall(AdhPredictorRegister(ADHPREDICTORPOLONSKYKEER, AdhPredictorCreate_PolonskyKeer));
  AdhResults = (AdhResultsOps){.check_writable = AdhOutputCheckWritable_Private, .open = AdhOutputOpen_Private, .resume = AdhOutputResume_Private, .write_fields = AdhOutputWriteFields_Private, .append = AdhOutputAppend_Private, .close = AdhOutputClose_Private, .checkpoint_write = AdhCheckpointWrite_Private, .checkpoint_read = AdhCheckpointRead_Private};
  PetscCall(PetscRegisterFinalize(AdhSolverFinalizePackage));
  PetscFunctionReturn(0);
}
