/* The pieces of one step of the Pohrt-Popov algorithm, shared by the load controls (impls/control/):
   the contact set and K restricted to it (contactset.c), the solve on it (setsolve.c), detach
   (every point the detachment criterion lets go, at once: impls/criterion/), attach (attach.c:
   points off the set that penetrate, tested after a solve with no violators; one full multiply
   u = K p per attach test), the gap (gap.c); here, what a step reports and checks on its way. */
#include "solver/solverimpl.h"

/* Progress inside a long step, with -adh_monitor: at most every few seconds. */
PetscErrorCode AdhSolverMonitorProgress_Private(AdhSolver s, PetscInt outer)
{
  PetscLogDouble now;

  PetscFunctionBegin;
  if (!s->monitor) PetscFunctionReturn(0);
  PetscCall(PetscTime(&now));
  if (outer == 1) s->progress_time = now;
  else if (now - s->progress_time >= s->monitor_interval) {
    s->progress_time = now;
    PetscCall(PetscPrintf(s->comm, "      ... d = %.6e: %" PetscInt_FMT " set updates, %" PetscInt_FMT " points in the set, %" PetscInt_FMT " KSP iterations so far\n", (double)s->d, outer - 1, s->npoints, s->step_ksp));
  }
  PetscFunctionReturn(0);
}

/* Under displacement control a periodic cell must stay above full contact, d < mean(h). */
PetscErrorCode AdhSolverCheckBelowFullContact_Private(AdhSolver s, PetscReal d)
{
  PetscFunctionBegin;
  PetscCheck(!(s->boundary == ADH_BOUNDARY_PERIODIC && d >= s->mean_h), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_path: d = %g presses the periodic cell into full contact (the gap's mean is max(0, mean(h) - d), and mean(h) = %g): under displacement control the force is undetermined there; use -adh_control force", (double)d, (double)s->mean_h);
  PetscFunctionReturn(0);
}
