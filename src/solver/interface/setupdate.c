/* The set-update loop of a step, shared by the load controls: from the current set, the
   equilibrium at the target (the control's equilibrate), the points that let go (the criterion),
   the points that join (the attach rule), until the set stands. The Pohrt-Popov loop, with the
   routes of -adh_cascade_rtol, -adh_cascade_apart and -adh_cascade_local around it. */
#include "solver/solverimpl.h"

PetscErrorCode AdhSolverUpdateSet_Private(AdhSolver s, PetscReal target)
{
  const char *what  = s->cops.target == ADH_TARGET_FORCE ? "the force" : "d =";
  PetscBool   loose = (PetscBool)(s->cascade_rtol > 0); /* -adh_cascade_rtol: the next solve may stop early */

  PetscFunctionBegin;
  if (s->crops.law) { /* a cohesive law: the energy's minimum, no set updates */
    PetscBool none;
    PetscCall(AdhSolverMinimize_Private(s, target, &none));
    PetscFunctionReturn(0);
  }
  for (PetscInt outer = 1;; outer++) {
    PetscInt  removed, added, widened;
    PetscBool none;

    PetscCheck(outer <= s->max_outer, s->comm, PETSC_ERR_NOT_CONVERGED, "No stable contact set at %s %g after %" PetscInt_FMT " set updates (-adh_max_outer)", what, (double)target, s->max_outer);
    AdhSolverCheckStop_Private(s);
    PetscCall(AdhSolverMonitorProgress_Private(s, outer));
    s->solve_loose = loose;
    PetscCall(s->cops.equilibrate(s, target, &none));
    s->solve_loose = PETSC_FALSE;
    AdhSolverReturnIfStopped_Private(s);
    if (none) break; /* the set has emptied: no equilibrium carries the target */
    s->step_outer++;
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
    if (!removed) {
      Vec       rate = NULL;
      PetscReal e    = 0.0;
      if (s->cops.attach_rate) PetscCall(s->cops.attach_rate(s, &rate, &e));
      PetscCall(AdhSolverAttach_Private(s, rate, e, 0, &added));
    } else if (s->apart_pending) { /* -adh_cascade_apart: join away from the points let go */
      PetscCall(AdhSolverMarkNearGone_Private(s, s->cascade_apart));
      widened = s->cascade_apart;
      PetscCall(AdhSolverAttach_Private(s, NULL, 0.0, removed, &added));
      PetscCall(AdhSolverEndCascadeApart_Private(s));
    }
    s->joined_step += added;
    PetscCheck(!s->certified_attach || (!removed && added), s->comm, PETSC_ERR_PLIB, "Certified early stop for an attach test that changed nothing");
    if (removed || added) {
      PetscCall(AdhSolverRebuildSet_Private(s));
      loose = (PetscBool)(s->cascade_rtol > 0);
    }
    PetscCall(PetscLogEventEnd(ADH_SetUpdate, 0, 0, 0, 0));
    PetscCall(PetscInfo(s, "%s %g, update %" PetscInt_FMT ": %" PetscInt_FMT " KSP iterations so far%s, %" PetscInt_FMT " points let go, %" PetscInt_FMT " joined, %" PetscInt_FMT " in the set\n", what, (double)target, outer, s->step_ksp, s->certified_stop ? " (certified stop)" : s->certified_attach ? " (certified attach)" : "", removed, added, s->npoints));
    if (removed && s->cascade_local) PetscCall(AdhSolverCascadeLocal_Private(s, widened)); /* cascadelocal.c */
    AdhSolverReturnIfStopped_Private(s);
    if (!removed && !added) break;
  }
  PetscFunctionReturn(0);
}
