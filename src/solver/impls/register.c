/* The solver's built-in types, registered in one place: elastic bodies, detachment criteria, load
   controls and contact-set predictors. A new type is a file (or a folder) in impls/<kind>/ whose create
   function fills in the kind's ops (solverimpl.h), and its line here (docs/developers/code-map.md). */
#include "solver/solverimpl.h"

PETSC_INTERN PetscErrorCode AdhElasticCreate_HalfSpace(AdhSolver);
PETSC_INTERN PetscErrorCode AdhElasticCreate_Layer(AdhSolver);
PETSC_INTERN PetscErrorCode AdhCriterionCreate_PohrtPopov(AdhSolver);
PETSC_INTERN PetscErrorCode AdhCriterionCreate_CrackClosure(AdhSolver);
PETSC_INTERN PetscErrorCode AdhCriterionCreate_Dugdale(AdhSolver);
PETSC_INTERN PetscErrorCode AdhCriterionCreate_Exponential(AdhSolver);
PETSC_INTERN PetscErrorCode AdhCriterionCreate_LJ93(AdhSolver);
PETSC_INTERN PetscErrorCode AdhControlCreate_Displacement(AdhSolver);
PETSC_INTERN PetscErrorCode AdhControlCreate_Force(AdhSolver);
PETSC_INTERN PetscErrorCode AdhPredictorCreate_None(AdhSolver);
PETSC_INTERN PetscErrorCode AdhPredictorCreate_PolonskyKeer(AdhSolver);

/* The built-in types, in the order -help and the error messages list them. */
PetscErrorCode AdhSolverRegisterAll_Private(void)
{
  PetscFunctionBegin;
  PetscCall(AdhElasticRegister(ADHELASTICHALFSPACE, AdhElasticCreate_HalfSpace));
  PetscCall(AdhElasticRegister(ADHELASTICLAYER, AdhElasticCreate_Layer));
  PetscCall(AdhCriterionRegister(ADHCRITERIONPOHRTPOPOV, AdhCriterionCreate_PohrtPopov));
  PetscCall(AdhCriterionRegister(ADHCRITERIONCRACKCLOSURE, AdhCriterionCreate_CrackClosure));
  PetscCall(AdhCriterionRegister(ADHCRITERIONDUGDALE, AdhCriterionCreate_Dugdale));
  PetscCall(AdhCriterionRegister(ADHCRITERIONEXPONENTIAL, AdhCriterionCreate_Exponential));
  PetscCall(AdhCriterionRegister(ADHCRITERIONLJ93, AdhCriterionCreate_LJ93));
  PetscCall(AdhControlRegister(ADHCONTROLDISPLACEMENT, AdhControlCreate_Displacement));
  PetscCall(AdhControlRegister(ADHCONTROLFORCE, AdhControlCreate_Force));
  PetscCall(AdhPredictorRegister(ADHPREDICTORNONE, AdhPredictorCreate_None));
  PetscCall(AdhPredictorRegister(ADHPREDICTORPOLONSKYKEER, AdhPredictorCreate_PolonskyKeer));
  PetscFunctionReturn(0);
}
