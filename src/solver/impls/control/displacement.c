/*MC
   ADHCONTROLDISPLACEMENT - "displacement", the default load control: the path holds indentations d, and a step is
   the Pohrt-Popov loop at fixed d

   The loop: solve on the contact set, let go what the criterion says, let join what the attach rule says, until the
   set stands.

   Options Database Keys:
+  -adh_control displacement - selects this control (the default)
.  -adh_max_outer <100000>   - the largest number of set updates in one step
.  -adh_cascade_rtol <0>     - the solves after a set update stop at this relative residual
.  -adh_cascade_local <F>    - local solves around the points a set update lets go
-  -adh_cascade_apart <0>    - points may join in an update that lets others go, this many grid spacings away

   Level: beginner

   Notes:
   With -adh_cascade_rtol the solves after a set update stop at that relative residual, and the set is updated on
   their pressures; once a set stands on one, it is solved to the full tolerance and tested again, so every recorded
   state is tested on an exact solve. With -adh_cascade_local the points a set update lets go are followed by local
   solves around them (cascadelocal.c) before the next solve of the whole set. -adh_cascade_local and
   -adh_cascade_apart are for this control only.

   Without adhesion a predictor may guess the set first (`AdhSolverSetPredictorType()`). A step that empties a set
   that had contact ends in pull-off. On a periodic cell d must stay below mean(h): there the cell is in full contact
   and the force is undetermined (use `ADHCONTROLFORCE`).

.seealso: `AdhSolverSetControlType()`, `ADHCONTROLFORCE`, `AdhSolverStep()`, `AdhSolverIsPulledOff()`
M*/
#include "solver/solverimpl.h"

/* Displacement control: the equilibrium set at indentation d, from the current set. */
static PetscErrorCode Step_Displacement(AdhSolver s, PetscReal d)
{
  PetscInt        outer, removed, added, widened;
  const PetscBool had_contact = s->npoints > 0;
  PetscBool       loose; /* -adh_cascade_rtol: the next solve may stop early */

  PetscFunctionBegin;
  PetscCall(AdhSolverCheckBelowFullContact_Private(s, d));
  s->d           = d;
  s->joined_step = 0;
  /* without adhesion the state at d is unique: a predictor may guess its set */
  if (s->predict && !AdhSolverIsAdhesive_Private(s)) PetscCall(s->predict(s, PETSC_FALSE, d));
  loose = (PetscBool)(s->cascade_rtol > 0);
  for (outer = 1;; outer++) {
    PetscCheck(outer <= s->max_outer, s->comm, PETSC_ERR_NOT_CONVERGED, "No stable contact set at d = %g after %" PetscInt_FMT " set updates (-adh_max_outer)", (double)d, s->max_outer);
    AdhSolverCheckStop_Private(s);
    PetscCall(AdhSolverMonitorProgress_Private(s, outer));
    s->solve_loose = loose;
    PetscCall(AdhSolverSolveOnSet_Private(s, s->p, d, s->h, PETSC_TRUE));
    s->solve_loose = PETSC_FALSE;
    PetscCall(PetscLogEventBegin(ADH_SetUpdate, 0, 0, 0, 0));
    /* -adh_cascade_apart: the points let go are marked and keep their pressure for this update's
       attach test; not after a certified stop, whose iterate decides only the detachments */
    if (s->cascade_apart && !s->certified_stop) PetscCall(AdhSolverBeginCascadeApart_Private(s));
    /* -adh_cascade_local: the points let go are marked, for the local solves around them */
    if (s->cascade_local && !s->local_whole) {
      PetscCall(PetscArrayzero(s->gone, s->nlocal));
      s->local_pending = PETSC_TRUE;
    }
    PetscCall(AdhSolverDetach_Private(s, &removed));
    s->local_pending = PETSC_FALSE;
    if (!removed) s->apart_pending = PETSC_FALSE; /* nothing marked */
    if (!removed && loose) { /* the set stands on a loose solve: solve to the full tolerance and test again */
      loose = PETSC_FALSE;
      PetscCall(PetscLogEventEnd(ADH_SetUpdate, 0, 0, 0, 0));
      continue;
    }
    PetscCheck(removed || !s->certified_stop, s->comm, PETSC_ERR_PLIB, "Certified early stop without a point to detach");
    added   = 0;
    widened = 0; /* how far the marks of the points let go have been widened */
    if (!removed) PetscCall(AdhSolverAttach_Private(s, NULL, 0, &added));
    else if (s->apart_pending) { /* -adh_cascade_apart: join away from the points let go */
      PetscCall(AdhSolverMarkNearGone_Private(s, s->cascade_apart));
      widened = s->cascade_apart;
      PetscCall(AdhSolverAttach_Private(s, NULL, removed, &added));
      PetscCall(AdhSolverEndCascadeApart_Private(s));
    }
    s->joined_step += added;
    PetscCheck(!s->certified_attach || (!removed && added), s->comm, PETSC_ERR_PLIB, "Certified early stop for an attach test that changed nothing");
    if (removed || added) {
      PetscCall(AdhSolverRebuildSet_Private(s));
      loose = (PetscBool)(s->cascade_rtol > 0);
    }
    PetscCall(PetscLogEventEnd(ADH_SetUpdate, 0, 0, 0, 0));
    PetscCall(PetscInfo(NULL, "d = %g, update %" PetscInt_FMT ": %" PetscInt_FMT " KSP iterations so far%s, %" PetscInt_FMT " points let go, %" PetscInt_FMT " joined, %" PetscInt_FMT " in the set\n", (double)d, outer, s->step_ksp, s->certified_stop ? " (certified stop)" : s->certified_attach ? " (certified attach)" : "", removed, added, s->npoints));
    if (removed && s->cascade_local) PetscCall(AdhSolverCascadeLocal_Private(s, widened)); /* cascadelocal.c */
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
