/* Load control displacement (-adh_control displacement, the default): the path holds
   indentations d; a step is the Pohrt-Popov loop at fixed d: solve on the set, let go what the
   criterion says, let join what the attach rule says, until the set stands. */
#include "solver/solverimpl.h"

/* Displacement control: the equilibrium set at indentation d, from the current set. */
static PetscErrorCode Step_Displacement(AdhSolver s, PetscReal d)
{
  PetscInt        outer, removed, added;
  const PetscBool had_contact = s->npoints > 0;

  PetscFunctionBegin;
  PetscCall(AdhSolverCheckBelowFullContact_Private(s, d));
  s->d           = d;
  s->joined_step = 0;
  /* without adhesion the state at d is unique: a predictor may guess its set */
  if (s->predict && !AdhSolverIsAdhesive_Private(s)) PetscCall(s->predict(s, PETSC_FALSE, d));
  for (outer = 1;; outer++) {
    PetscCheck(outer <= s->max_outer, s->comm, PETSC_ERR_NOT_CONVERGED, "No stable contact set at d = %g after %" PetscInt_FMT " set updates (-adh_max_outer)", (double)d, s->max_outer);
    AdhSolverCheckStop_Private(s);
    PetscCall(AdhSolverMonitorProgress_Private(s, outer));
    PetscCall(AdhSolverSolveOnSet_Private(s, s->p, d, s->h, PETSC_TRUE));
    PetscCall(PetscLogEventBegin(ADH_SetUpdate, 0, 0, 0, 0));
    PetscCall(AdhSolverDetach_Private(s, &removed));
    PetscCheck(removed || !s->certified_stop, s->comm, PETSC_ERR_PLIB, "Certified early stop without a point to detach");
    added = 0;
    if (!removed) PetscCall(AdhSolverAttach_Private(s, NULL, &added));
    s->joined_step += added;
    PetscCheck(!s->certified_attach || (!removed && added), s->comm, PETSC_ERR_PLIB, "Certified early stop for an attach test that changed nothing");
    if (removed || added) PetscCall(AdhSolverRebuildSet_Private(s));
    PetscCall(PetscLogEventEnd(ADH_SetUpdate, 0, 0, 0, 0));
    PetscCall(PetscInfo(NULL, "d = %g, update %" PetscInt_FMT ": %" PetscInt_FMT " KSP iterations so far%s, %" PetscInt_FMT " points let go, %" PetscInt_FMT " joined, %" PetscInt_FMT " in the set\n", (double)d, outer, s->step_ksp, s->certified_stop ? " (certified stop)" : s->certified_attach ? " (certified attach)" : "", removed, added, s->npoints));
    if (!removed && !added) break;
  }
  s->step_outer      = outer;
  s->joined_previous = s->joined_step;
  s->pulled_off      = (PetscBool)(had_contact && !s->npoints);
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhControlCreate_Displacement(AdhSolver s)
{
  PetscFunctionBegin;
  s->cops.step        = Step_Displacement;
  s->force_control    = PETSC_FALSE;
  PetscFunctionReturn(0);
}
