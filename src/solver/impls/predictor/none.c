/* Contact-set predictor none (-adh_predictor none): the set-update loop starts from the previous
   state's set. */
#include "solver/solverimpl.h"

PETSC_INTERN PetscErrorCode AdhPredictorCreate_None(AdhSolver s)
{
  PetscFunctionBegin;
  s->predict = NULL;
  PetscFunctionReturn(0);
}
