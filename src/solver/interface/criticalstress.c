#include "solver/solverimpl.h"

/* The critical stress on the local points: the array of a field, or (a = NULL) one value for
   all. With threshold, the allowed tension of the current stage: zero while computing a Hertz
   start. A uniform dgamma keeps no field: a grid vector fewer. */
PetscErrorCode AdhSolverGetCriticalStress_Private(AdhSolver s, PetscBool threshold, const PetscScalar **a, PetscReal *uniform)
{
  PetscFunctionBegin;
  *a       = NULL;
  *uniform = 0.0;
  if (threshold && !s->adhesive) PetscFunctionReturn(0);
  if (s->Sigma_field) PetscCall(VecGetArrayRead(s->Sigma_field, a));
  else *uniform = s->Sigma;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverRestoreCriticalStress_Private(AdhSolver s, const PetscScalar **a)
{
  PetscFunctionBegin;
  if (*a) PetscCall(VecRestoreArrayRead(s->Sigma_field, a));
  PetscFunctionReturn(0);
}
