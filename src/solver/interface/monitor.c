/* Monitors: the functions called after every recorded state, the default one (-adh_monitor: a table
   of the states with the time left), and the progress lines of a path (-adh_progress). */
#include "solver/solverimpl.h"

/*@
  AdhSolverMonitorSet - Adds a function to be called after every recorded state of a path

  Logically Collective

  Input Parameters:
+ s       - the solver
. monitor - the monitor
. ctx     - [optional] a context for it (may be `NULL`)
- destroy - [optional] a function that destroys the context (may be `NULL`)

  Calling sequence of `monitor`:
+ s    - the solver
. step - the state's row in the curve (0: the starting state)
. st   - the state just recorded
- ctx  - the context given here

  Calling sequence of `destroy`:
. ctx - the address of the context

  Options Database Key:
. -adh_monitor - sets `AdhSolverMonitorDefault()`, one line per state

  Level: intermediate

  Notes:
  The monitors are called on every rank, in the order they were set, by `AdhSolverMonitor()`: after each state
  `AdhSolverSolvePath()` records, once the state is in the curve and in the results file. One that fails on any rank
  fails on every rank. At most 8 monitors can be set.

.seealso: `AdhSolverMonitorDefault()`, `AdhSolverMonitorCancel()`, `AdhSolverMonitor()`, `AdhSolverSolvePath()`
@*/
PetscErrorCode AdhSolverMonitorSet(AdhSolver s, PetscErrorCode (*monitor)(AdhSolver, PetscInt, const AdhState *, void *), void *ctx, PetscErrorCode (*destroy)(void **))
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidFunction(monitor, 2);
  if (destroy) PetscValidFunction(destroy, 4);
  PetscCheck(s->nmonitors < ADH_MAX_MONITORS, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "Too many monitors (at most %d)", ADH_MAX_MONITORS);
  s->monitors[s->nmonitors]       = monitor;
  s->monitor_ctx[s->nmonitors]     = ctx;
  s->monitor_destroy[s->nmonitors] = destroy;
  s->nmonitors++;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverMonitorCancel - Removes every monitor, destroying their contexts

  Logically Collective

  Input Parameter:
. s - the solver

  Level: intermediate

  Note:
  Each context is destroyed with the destroy function given to `AdhSolverMonitorSet()`. The -adh_monitor setting
  stays on: a later `AdhSolverSetFromOptions()` does not set `AdhSolverMonitorDefault()` again, the progress lines
  inside long steps go on, and the path's progress lines (`AdhSolverSetProgress()`) stay off.

.seealso: `AdhSolverMonitorSet()`, `AdhSolverDestroy()`
@*/
PetscErrorCode AdhSolverMonitorCancel(AdhSolver s)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  for (PetscInt k = 0; k < s->nmonitors; k++)
    if (s->monitor_destroy[k]) PetscCall(s->monitor_destroy[k](&s->monitor_ctx[k]));
  s->nmonitors = 0;
  PetscFunctionReturn(0);
}

/* Seconds left on the path after the state just recorded, from the mean time of this run's
   states (an upper bound where a leg ends early by pull-off); -1 outside a path or before a state. */
static PetscReal SecondsLeft(AdhSolver s, PetscLogDouble now)
{
  const PetscInt done = s->curve.n - s->path_first;
  if (!s->on_path || done <= 0) return -1;
  return (PetscReal)((now - s->path_start) / done * (PetscReal)PetscMax(0, s->path_states - s->curve.n));
}

/*@
  AdhSolverMonitorDefault - The default monitor: one line per recorded state, with a header before the first

  Collective

  Input Parameters:
+ s    - the solver
. step - the state's row in the curve
. st   - the state
- ctx  - unused

  Options Database Key:
. -adh_monitor - sets this monitor, read by `AdhSolverSetFromOptions()`

  Level: intermediate

  Notes:
  The line gives the state's row, d, the force, the area, the points in contact, the patches, the set updates, the
  KSP iterations, the compliance applications, the seconds, and the seconds left on the path: estimated from the mean
  time of this run's states, an upper bound where a leg ends early by pull-off, "-" outside a path. A header of two
  lines, the columns' names and units, comes before state 0 and before the first state of a path or of a restart; a
  state that ends a leg by pull-off adds the line "contact lost at d = ...: the leg ends". It prints with
  `PetscPrintf()` on the solver's communicator.

  Give it to `AdhSolverMonitorSet()` with a `NULL` context.

.seealso: `AdhSolverMonitorSet()`, `AdhSolverSetProgress()`, `AdhSolverMonitor()`
@*/
PetscErrorCode AdhSolverMonitorDefault(AdhSolver s, PetscInt step, const AdhState *st, void *ctx)
{
  PetscLogDouble now;
  PetscReal      left;
  char           text[32] = "-";

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(st, 3);
  PetscCall(PetscTime(&now));
  left = SecondsLeft(s, now);
  if (left >= 0) PetscCall(PetscSNPrintf(text, sizeof(text), left < 10 ? "%.1f" : "%.0f", (double)left));
  /* the header with the first state of a path or of a restart, and of a step-by-step run */
  if (step == 0 || step == s->path_first) {
    PetscCall(PetscPrintf(s->comm, "%5s %13s %13s %13s %8s %7s %6s %7s %7s %9s %7s\n", "state", "d", "force", "area", "points", "patches", "outer", "ksp", "K-mults", "seconds", "left"));
    PetscCall(PetscPrintf(s->comm, "%5s %13s %13s %13s %8s %7s %6s %7s %7s %9s %7s\n", "", "[length]", "[force]", "[length^2]", "", "", "", "", "", "[s]", "[s]"));
  }
  PetscCall(PetscPrintf(s->comm, "%5" PetscInt_FMT " %13.6e %13.6e %13.6e %8" PetscInt_FMT " %7" PetscInt_FMT " %6" PetscInt_FMT " %7" PetscInt_FMT " %7" PetscInt_FMT " %9.3f %7s\n", step, (double)st->d, (double)st->force, (double)st->area, st->contact_points, st->patches, st->outer_iterations, st->ksp_iterations, st->compliance_applications, (double)st->seconds, text));
  if (st->pulled_off) PetscCall(PetscPrintf(s->comm, "contact lost at d = %g: the leg ends\n", (double)st->d));
  PetscFunctionReturn(0);
}

/* -adh_progress: a line after the first `progress` seconds of a path, then every tenth of the
   time so far (or `progress`, if longer), unless -adh_monitor prints one a state. */
PetscErrorCode AdhSolverProgress_Private(AdhSolver s)
{
  PetscLogDouble now, so_far;
  PetscReal      left;
  const AdhState *st = &s->curve.state[s->curve.n - 1];

  PetscFunctionBegin;
  if (!(s->progress > 0) || s->monitor || !s->on_path) PetscFunctionReturn(0);
  PetscCall(PetscTime(&now));
  so_far = now - s->path_start;
  if (now - s->progress_last < PetscMax(s->progress, 0.1 * so_far)) PetscFunctionReturn(0);
  s->progress_last = now;
  left             = SecondsLeft(s, now);
  PetscCall(PetscPrintf(s->comm, "adhbem: state %" PetscInt_FMT " of at most %" PetscInt_FMT " (d = %g, force %g, %" PetscInt_FMT " points in contact): %.0f s so far, about %.0f s left\n", s->curve.n - 1, s->path_states - 1, (double)st->d, (double)st->force, st->contact_points, (double)so_far, (double)left));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverMonitor - Calls the monitors with a recorded state

  Collective

  Input Parameters:
+ s    - the solver
. step - the state's row in the curve
- st   - the state

  Level: advanced

  Notes:
  `AdhSolverSolvePath()` calls it after each state it records. Call it after `AdhSolverRecordState()` to monitor the
  states of your own `AdhSolverStart()` and `AdhSolverStep()` calls.

  A monitor that fails on any rank fails on every rank: after each monitor its error code is reduced over the
  communicator, and a failure is the error `PETSC_ERR_USER`, naming the monitor and the state.

.seealso: `AdhSolverMonitorSet()`, `AdhSolverRecordState()`, `AdhSolverMonitorDefault()`
@*/
PetscErrorCode AdhSolverMonitor(AdhSolver s, PetscInt step, const AdhState *st)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(st, 3);
  for (PetscInt k = 0; k < s->nmonitors; k++) {
    /* a monitor that fails on one rank stops every rank, not just that one */
    int err = (int)s->monitors[k](s, step, st, s->monitor_ctx[k]);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &err, 1, MPI_INT, MPI_MAX, s->comm));
    PetscCheck(!err, s->comm, PETSC_ERR_USER, "Monitor %" PetscInt_FMT " failed at state %" PetscInt_FMT " (error %d)", k, step, err);
  }
  PetscFunctionReturn(0);
}
