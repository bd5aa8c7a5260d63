/* The gap g = h - d + u of the current state, and the displacement u made from it when asked for. */
#include "solver/solverimpl.h"

/* g = (h - d) + u, u = K p, for the current state (u itself is not kept: see GetDisplacement). */
PetscErrorCode AdhSolverComputeGap_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(MatMult(s->K, s->p, s->g));
  PetscCall(AdhSolverGapFromDisplacement_Private(s, s->g));
  PetscFunctionReturn(0);
}

/* g = (h - d) + u from the displacement u (which may be g itself): the one sum every gap and
   opening is taken with, so that they agree to the last bit whichever computed them. */
PetscErrorCode AdhSolverGapFromDisplacement_Private(AdhSolver s, Vec u)
{
  const PetscScalar *ha;
  PetscScalar       *ga;

  PetscFunctionBegin;
  if (u != s->g) PetscCall(VecCopy(u, s->g));
  PetscCall(VecGetArrayRead(s->h, &ha));
  PetscCall(VecGetArray(s->g, &ga));
  for (PetscInt k = 0; k < s->nlocal; k++) ga[k] = (ha[k] - s->d) + ga[k];
  PetscCall(VecRestoreArray(s->g, &ga));
  PetscCall(VecRestoreArrayRead(s->h, &ha));
  PetscFunctionReturn(0);
}

/* The displacement u = g - h + d of the current state, made when asked for: a grid vector fewer
   for runs that never look at it. */
PetscErrorCode AdhSolverGetDisplacement_Private(AdhSolver s, Vec *u)
{
  PetscFunctionBegin;
  if (!s->u) {
    PetscCall(VecDuplicate(s->h, &s->u));
    PetscCall(PetscObjectSetName((PetscObject)s->u, "displacement"));
  }
  PetscCall(VecWAXPY(s->u, -1.0, s->h, s->g));
  PetscCall(VecShift(s->u, s->d));
  *u = s->u;
  PetscFunctionReturn(0);
}
