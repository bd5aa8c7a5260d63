/*MC
   ADHPREDICTORNONE - "none": no contact-set predictor; the set-update loop starts from the previous state's set

   Options Database Key:
.  -adh_predictor none - selects it

   Level: intermediate

   Note:
   The default on a free boundary, where the loop's bounding-box windows cost less than a predictor's transforms of
   the whole grid. The answer is the same as with `ADHPREDICTORPOLONSKYKEER`.

.seealso: `AdhSolverSetPredictorType()`, `ADHPREDICTORPOLONSKYKEER`
M*/
#include "solver/solverimpl.h"

PETSC_INTERN PetscErrorCode AdhPredictorCreate_None(AdhSolver s)
{
  PetscFunctionBegin;
  s->pops.predict = NULL; /* the set-update loop starts from the previous state's set */
  PetscFunctionReturn(0);
}
