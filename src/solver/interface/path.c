/* Paths: the starting state, the legs of -adh_path (indentations, or forces under force
   control), recording the states, and the stop on a signal. The curve's columns are in curve.c,
   the monitors and the progress lines in monitor.c. */
#include <signal.h>
#include <time.h>
#include "solver/solverimpl.h"
/* Marks the local points with h - d <= 0 (touching or overlapping at indentation d). */
PetscErrorCode AdhSolverSetFromOverlap_Private(AdhSolver s, PetscReal d, PetscBool strict)
{
  const PetscScalar *ha;
  PetscInt           n, k;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(s->h, &n));
  PetscCall(VecGetArrayRead(s->h, &ha));
  for (k = 0; k < n; k++) s->in_set[k] = strict ? PetscRealPart(ha[k]) - d < 0 : PetscRealPart(ha[k]) - d <= 0;
  PetscCall(VecRestoreArrayRead(s->h, &ha));
  PetscCall(VecSet(s->p, 0.0));
  if (s->set_response) PetscCall(VecSet(s->set_response, 0.0));
  s->pulled_off = PETSC_FALSE;
  PetscCall(AdhSolverRebuildSet_Private(s));
  PetscFunctionReturn(0);
}

/* Under force control the first force must be >= 0: the adhesion-free start carries no tension,
   and the adhesive start loads from first touch, where nothing holds the bodies together yet (a
   tension there would be a pull-off of the unpressed contact, and the next states, apart, F = 0). */
static PetscErrorCode CheckStartTarget(AdhSolver s, PetscReal target)
{
  PetscFunctionBegin;
  PetscCheck(s->start != ADH_START_HERTZ || !AdhSolverControlsForce_Private(s) || target >= 0, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_path: the first force is %g, but the adhesion-free start (-adh_start hertz) carries no tension; start from a compressive force or use -adh_start adhesive", (double)target);
  PetscCheck(!AdhSolverControlsForce_Private(s) || target >= 0, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_path: the first force is %g, a tension the start cannot reach: -adh_start adhesive loads from first touch, where the contact carries none; start from a compressive force (or 0) and pull in a later leg (-adh_path 0.01,%g)", (double)target, (double)target);
  PetscFunctionReturn(0);
}

/*@
  AdhSolverStart - Computes the starting state at the path's first value, and begins a new curve

  Collective

  Input Parameters:
+ s      - the solver
- target - the first value of the path: an indentation d, or a force F under `ADHCONTROLFORCE`

  Options Database Key:
. -adh_start <hertz,adhesive> - the starting state, read by `AdhSolverSetFromOptions()`

  Level: intermediate

  Notes:
  hertz (the default): the adhesion-free state at the target, from the geometric overlap (the points with h < d), or
  under force control from the first touch; its step is made without adhesion, which applies from the next step on.
  Under force control a target below 0 is refused: the adhesion-free start carries no tension.

  adhesive: loading with adhesion from first touch (d = min h, where the apex points carry no load) to the target in
  -adh_steps steps, which end early at pull-off; under force control from F = 0. Under displacement control a target
  at or before first touch (d <= min h) is one step.

  Sets the solver up if needed. The counts of `AdhSolverGetState()` are the start's, over all its steps. The state
  is not recorded: `AdhSolverRecordState()` records it, and `AdhSolverSolvePath()` calls both.

.seealso: `AdhSolverStep()`, `AdhSolverSolvePath()`, `AdhSolverRecordState()`, `AdhSolverGetCurve()`
@*/
PetscErrorCode AdhSolverStart(AdhSolver s, PetscReal target)
{
  PetscInt  outer = 0, ksp = 0, mults = 0, ffts = 0;
  PetscReal dtouch;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscCall(AdhSolverSetUp(s));
  s->curve.n       = 0;
  s->path_stopped = -1; /* a new curve: no earlier path's stop describes it */
  PetscCall(VecMin(s->h, NULL, &dtouch));
  if (s->start == ADH_START_HERTZ) {
    /* Adhesion-free contact at d0 (Sigma = 0), from the geometric overlap, or under force control
       from the first touch. */
    PetscCall(CheckStartTarget(s, target));
    PetscCall(AdhSolverSetFromOverlap_Private(s, AdhSolverControlsForce_Private(s) ? dtouch : target, (PetscBool)!AdhSolverControlsForce_Private(s)));
    s->d        = dtouch;
    s->adhesive = PETSC_FALSE;
    PetscCall(AdhSolverStep(s, target));
    s->adhesive = PETSC_TRUE; /* also after a stop by signal: the path ends there */
  } else {
    /* Load with adhesion from first touch, where the apex points carry no load, to the target in
       -adh_steps steps. */
    const PetscReal t0 = AdhSolverControlsForce_Private(s) ? 0.0 : dtouch;
    PetscCall(AdhSolverSetFromOverlap_Private(s, PetscMin(dtouch, AdhSolverControlsForce_Private(s) ? dtouch : target), PETSC_FALSE));
    s->d = dtouch;
    if (AdhSolverControlsForce_Private(s) || target > dtouch) {
      for (PetscInt k = 1; k <= s->steps; k++) {
        PetscCall(AdhSolverStep(s, t0 + (target - t0) * k / s->steps));
        AdhSolverReturnIfStopped_Private(s);
        outer += s->step_outer; ksp += s->step_ksp; mults += s->step_mults; ffts += s->step_ffts;
        if (s->pulled_off) break;
      }
      s->step_outer = outer; s->step_ksp = ksp; s->step_mults = mults; s->step_ffts = ffts;
    } else PetscCall(AdhSolverStep(s, target));
  }
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetState - Gets the current state: indentation, force, area, points in contact, and the last step's counts

  Collective

  Input Parameter:
. s - the solver

  Output Parameters:
+ d      - the indentation (or `NULL`)
. F      - the force, the sum of the pressures times the element area hx hy (or `NULL`)
. A      - the contact area, the points in contact times hx hy (or `NULL`)
. points - the number of grid points in contact (or `NULL`)
. outer  - the set updates of the last step (a cohesive law's: its Newton steps) (or `NULL`)
. ksp    - the KSP iterations of the last step (a cohesive law's: the Newton steps' CG iterations) (or `NULL`)
- mults  - the compliance applications of the last step (or `NULL`)

  Level: intermediate

  Notes:
  The last step is the last `AdhSolverStep()`, or all the steps of `AdhSolverStart()`. On a periodic cell F is the
  mean pressure times the cell's area.

  Collective whatever is asked for: it sums the pressure over the ranks.

.seealso: `AdhSolverComputeState()`, `AdhSolverGetFields()`, `AdhSolverGetContactSet()`, `AdhSolverStep()`
@*/
PetscErrorCode AdhSolverGetState(AdhSolver s, PetscReal *d, PetscReal *F, PetscReal *A, PetscInt *points, PetscInt *outer, PetscInt *ksp, PetscInt *mults)
{
  PetscScalar sum;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscCall(VecSum(s->p, &sum));
  if (d) *d = s->d;
  if (F) *F = PetscRealPart(sum) * s->grid->hx * s->grid->hy;
  if (A) *A = s->npoints * s->grid->hx * s->grid->hy;
  if (points) *points = s->npoints;
  if (outer) *outer = s->step_outer;
  if (ksp) *ksp = s->step_ksp;
  if (mults) *mults = s->step_mults;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverComputeState - Computes the current state with its statistics, as a path records it

  Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. st - the state: that of `AdhSolverGetState()`, with the statistics (contact patches, mean gap, tension, areas in
       tension and in compression, the criterion's detach ratio, small patches), the step's FFT pairs, and whether
       the step ended in pull-off

  Level: intermediate

  Notes:
  The statistics' own compliance applications (crack-closure's detach ratio needs one) are counted in the state's
  compliance_applications and fft_pairs. The seconds are left 0: `AdhSolverRecordState()` sets them. Nothing is
  added to the curve.

.seealso: `AdhSolverGetState()`, `AdhSolverRecordState()`, `AdhSolverGetCurve()`, `AdhStateValue()`
@*/
PetscErrorCode AdhSolverComputeState(AdhSolver s, AdhState *st)
{
  PetscInt mults0, ffts0, mults1, ffts1;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(st, 2);
  PetscCall(PetscMemzero(st, sizeof(*st)));
  PetscCall(AdhSolverGetState(s, &st->d, &st->force, &st->area, &st->contact_points, &st->outer_iterations, &st->ksp_iterations, &st->compliance_applications));
  /* the statistics' own multiplies (crack-closure's detach_ratio) count with the state */
  PetscCall(AdhSolverMultCount_Private(s, &mults0, &ffts0));
  PetscCall(AdhStatisticsCompute_Private(s, st));
  PetscCall(AdhSolverMultCount_Private(s, &mults1, &ffts1));
  st->compliance_applications += mults1 - mults0;
  st->pulled_off = s->pulled_off;
  st->fft_pairs  = s->step_ffts + ffts1 - ffts0;
  PetscFunctionReturn(0);
}
/*@
  AdhSolverRecordState - Records the state the last `AdhSolverStart()` or `AdhSolverStep()` reached, as a path does

  Collective

  Input Parameters:
+ s  - the solver
- t0 - when the step began, a `PetscTime()`: the state's seconds count from it

  Output Parameter:
. st - the state, as recorded

  Level: advanced

  Notes:
  The state is computed (`AdhSolverComputeState()`), its seconds set, and appended to the curve
  (`AdhSolverGetCurve()`). Nothing is written to a results file and the monitors are not called: `AdhSolverMonitor()`
  calls them.

.seealso: `AdhSolverComputeState()`, `AdhSolverMonitor()`, `AdhSolverGetCurve()`, `AdhSolverStep()`
@*/
PetscErrorCode AdhSolverRecordState(AdhSolver s, PetscLogDouble t0, AdhState *st)
{
  PetscLogDouble t1;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(st, 3);
  PetscCall(AdhSolverComputeState(s, st));
  PetscCall(PetscTime(&t1));
  st->seconds = (PetscReal)(t1 - t0);
  PetscCall(AdhCurveAppend_Private(&s->curve, st));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetPath - Gets the path: its breakpoints, and the steps of each leg between them

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameters:
+ npath - the number of breakpoints (or `NULL`)
. path  - the breakpoints: indentations, or forces under `ADHCONTROLFORCE` (or `NULL`)
- steps - the steps of each leg (or `NULL`)

  Options Database Keys:
+ -adh_path <v0,v1,...> - the breakpoints (default 0.01,0), read by `AdhSolverSetFromOptions()`
- -adh_steps <10>       - the steps per leg

  Level: intermediate

  Note:
  The array is borrowed: do not free it. It is replaced when -adh_path is read again.

.seealso: `AdhSolverSolvePath()`, `AdhSolverSetFromOptions()`
@*/
PetscErrorCode AdhSolverGetPath(AdhSolver s, PetscInt *npath, const PetscReal *path[], PetscInt *steps)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  if (npath) *npath = s->npath;
  if (path) *path = s->path;
  if (steps) *steps = s->steps;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverSetStopAtPullOff - Sets whether a pull-off ends the path or only its leg

  Logically Collective

  Input Parameters:
+ s    - the solver
- stop - `PETSC_TRUE` (the default): the path ends at the state that pulled off; `PETSC_FALSE`: only its leg does,
         and the legs after it run (a path that comes back into contact, for a second cycle)

  Options Database Key:
. -adh_stop_at_pulloff <true> - the same

  Level: intermediate

  Notes:
  After a pull-off nothing is in contact, and the legs that follow record states apart until the path comes back to
  the surface. When the path stops with legs left, `AdhSolverResolutionView()` says so and `AdhSolverGetResolution()`
  gives the state (its `stopped`).

.seealso: `AdhSolverGetStopAtPullOff()`, `AdhSolverSolvePath()`, `AdhSolverIsPulledOff()`
@*/
PetscErrorCode AdhSolverSetStopAtPullOff(AdhSolver s, PetscBool stop)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidLogicalCollectiveBool(s, stop, 2);
  s->stop_at_pulloff = stop;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetStopAtPullOff - Gets whether a pull-off ends the path or only its leg

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. stop - `PETSC_TRUE`: a pull-off ends the path (the default)

  Level: intermediate

.seealso: `AdhSolverSetStopAtPullOff()`
@*/
PetscErrorCode AdhSolverGetStopAtPullOff(AdhSolver s, PetscBool *stop)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidBoolPointer(stop, 2);
  *stop = s->stop_at_pulloff;
  PetscFunctionReturn(0);
}

/* Records the current state in the curve and the results file (its fields too), then calls the
   monitors: a monitor that fails finds the state already written. */
static PetscErrorCode Record(AdhSolver s, PetscLogDouble t0, PetscViewer viewer)
{
  AdhState st;

  PetscFunctionBegin;
  PetscCall(AdhSolverRecordState(s, t0, &st));
  if (viewer && (s->curve.n - 1) % s->fields_stride == 0) PetscCall(AdhResults.write_fields(s, viewer, s->curve.n - 1));
  if (viewer) PetscCall(AdhResults.append(s, viewer));
  PetscCall(AdhSolverMonitor(s, s->curve.n - 1, &st));
  PetscCall(AdhSolverProgress_Private(s));
  PetscFunctionReturn(0);
}

/* SIGTERM and SIGINT (what batch systems send before the kill, and what mpirun passes on to the
   ranks when it gets either, killing them a second later) stop the path: the flag is read by
   every rank together in each iteration of the solves, in each set update and after each
   recorded state, and the step in progress is abandoned. The time it came is kept to say how
   long the stop took. */
static volatile sig_atomic_t adh_signal = 0;
static struct timespec       adh_signal_time;

static void OnSignal(int sig)
{
  if (!adh_signal) clock_gettime(CLOCK_MONOTONIC, &adh_signal_time); /* async-signal-safe */
  adh_signal = sig;
}

PetscErrorCode AdhSolverStopRequested_Private(AdhSolver s, PetscBool *stop)
{
  int sig;

  PetscFunctionBegin;
  *stop = PETSC_FALSE;
  if (!s->stoppable) PetscFunctionReturn(0);
  sig = (int)adh_signal;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sig, 1, MPI_INT, MPI_MAX, s->comm));
  if (sig) {
    s->stop_signal = sig;
    *stop          = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

/* After the state at (leg, step): the checkpoint when one is due, and the stop on a signal. */
static PetscErrorCode AfterRecord(AdhSolver s, PetscInt leg, PetscInt step)
{
  PetscFunctionBegin;
  if (s->checkpoint[0] && (s->curve.n - 1) % s->checkpoint_every == 0) PetscCall(AdhResults.checkpoint_write(s, leg, step));
  AdhSolverCheckStop_Private(s);
  PetscFunctionReturn(0);
}

/* The path from its start, or after the state (leg0, step0) of a checkpoint already read. */
static PetscErrorCode SolvePathInner(AdhSolver s, PetscViewer viewer, PetscInt leg0, PetscInt step0)
{
  PetscLogDouble t0;

  PetscFunctionBegin;
  PetscCall(PetscTime(&s->path_start));
  s->progress_last = s->path_start;
  s->path_states   = 1 + (s->npath - 1) * s->steps;
  s->path_first    = s->restart[0] ? s->curve.n : 0;
  s->path_stopped  = -1;
  if (s->restart[0]) {
    /* go on after the checkpoint's state; a leg that ended in pull-off is over */
    if (leg0 == 0) leg0 = 1;
    else if (s->pulled_off) {
      leg0++;
      step0 = 0;
      if (s->stop_at_pulloff) { /* the path ended there */
        if (leg0 < s->npath) s->path_stopped = s->curve.n - 1;
        leg0 = s->npath;
      }
    }
  } else {
    PetscCall(PetscTime(&t0));
    PetscCall(AdhSolverStart(s, s->path[0]));
    AdhSolverReturnIfStopped_Private(s); /* the start abandoned: nothing to record */
    PetscCall(Record(s, t0, viewer));
    PetscCall(AfterRecord(s, 0, 0));
    AdhSolverReturnIfStopped_Private(s);
  }
  for (PetscInt leg = leg0; leg < s->npath; leg++) {
    const PetscReal a = s->path[leg - 1], b = s->path[leg];
    for (PetscInt k = leg == leg0 ? step0 + 1 : 1; k <= s->steps; k++) {
      PetscCall(PetscTime(&t0));
      PetscCall(AdhSolverStep(s, a + (b - a) * k / s->steps));
      AdhSolverReturnIfStopped_Private(s); /* the step abandoned: not recorded */
      PetscCall(Record(s, t0, viewer));
      PetscCall(AfterRecord(s, leg, k));
      AdhSolverReturnIfStopped_Private(s);
      if (s->pulled_off) break; /* the rest of this leg has nothing in contact */
    }
    if (s->pulled_off && s->stop_at_pulloff) { /* and by default the path ends there */
      if (leg + 1 < s->npath) s->path_stopped = s->curve.n - 1;
      break;
    }
  }
  PetscFunctionReturn(0);
}

/* Warns when no state of the path touches the surface. */
static PetscErrorCode CheckTouched(AdhSolver s)
{
  PetscInt  k, touched = 0;
  PetscReal dtouch, dmax = PETSC_MIN_REAL;

  PetscFunctionBegin;
  for (k = 0; k < s->curve.n; k++) {
    touched += s->curve.state[k].contact_points > 0;
    dmax = PetscMax(dmax, s->curve.state[k].d);
  }
  if (touched || !s->curve.n) PetscFunctionReturn(0);
  PetscCall(VecMin(s->h, NULL, &dtouch));
  PetscCall(PetscPrintf(s->comm, "adhbem: warning: the path never touches the surface (first touch at d = %g, the deepest state reached d = %g; -adh_path)\n", (double)dtouch, (double)dmax));
  PetscFunctionReturn(0);
}

/* A path that cannot be followed fails before any work and before a results file is opened. */
static PetscErrorCode CheckPath(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(CheckStartTarget(s, s->path[0]));
  if (s->boundary == ADH_BOUNDARY_PERIODIC && !AdhSolverControlsForce_Private(s))
    for (PetscInt k = 0; k < s->npath; k++) PetscCall(AdhSolverCheckBelowFullContact_Private(s, s->path[k]));
  PetscFunctionReturn(0);
}

/* The line that ends a path stopped by a signal: which state the results end with, where they
   are, how long the stop took, and how to go on. */
static PetscErrorCode StopMessage(AdhSolver s, char msg[], size_t len)
{
  const PetscInt  last = s->curve.n - 1;
  struct timespec now;
  double          took = -1.0;
  char            where[PETSC_MAX_PATH_LEN + 64], how[PETSC_MAX_PATH_LEN + 128], after[64];

  PetscFunctionBegin;
  clock_gettime(CLOCK_MONOTONIC, &now);
  if (adh_signal) took = (double)(now.tv_sec - adh_signal_time.tv_sec) + 1e-9 * (double)(now.tv_nsec - adh_signal_time.tv_nsec);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &took, 1, MPI_DOUBLE, MPI_MAX, s->comm));
  if (last >= 0) PetscCall(PetscSNPrintf(after, sizeof(after), "after state %" PetscInt_FMT, last));
  else PetscCall(PetscSNPrintf(after, sizeof(after), "before the first state"));
  if (!s->output[0]) PetscCall(PetscSNPrintf(where, sizeof(where), "no results file (-adh_output)"));
  else if (last >= 0) PetscCall(PetscSNPrintf(where, sizeof(where), "results up to it in %s (complete = 0)", s->output));
  else PetscCall(PetscSNPrintf(where, sizeof(where), "%s holds no state (complete = 0)", s->output));
  if (!s->checkpoint[0]) PetscCall(PetscSNPrintf(how, sizeof(how), "with -adh_checkpoint FILE a run can go on from where it stopped"));
  else if (s->checkpoint_state < 0) PetscCall(PetscSNPrintf(how, sizeof(how), "no checkpoint was written yet"));
  else if (s->checkpoint_state == last) PetscCall(PetscSNPrintf(how, sizeof(how), "go on with the same options and -adh_restart %s", s->checkpoint));
  else PetscCall(PetscSNPrintf(how, sizeof(how), "go on from state %" PetscInt_FMT " with the same options and -adh_restart %s (-adh_checkpoint_every %" PetscInt_FMT ")", s->checkpoint_state, s->checkpoint, s->checkpoint_every));
  if (took >= 0) PetscCall(PetscSNPrintf(msg, len, "stopped by signal %d %s (%.2f s after the signal); %s; %s", s->stop_signal, after, took, where, how));
  else PetscCall(PetscSNPrintf(msg, len, "stopped by signal %d %s; %s; %s", s->stop_signal, after, where, how));
  PetscFunctionReturn(0);
}

/* The path with the results file open (viewer; NULL: none): every recorded state is in it. */
static PetscErrorCode SolvePathOpen(AdhSolver s, PetscViewer *viewer, PetscInt leg0, PetscInt step0)
{
  PetscFunctionBegin;
  if (s->output[0] && s->restart[0]) PetscCall(AdhResults.resume(s, s->output, viewer));
  else if (s->output[0]) PetscCall(AdhResults.open(s, s->output, viewer));
  PetscCall(SolvePathInner(s, *viewer, leg0, step0));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverSolvePath - Follows the whole path (-adh_path), recording every state in the curve

  Collective

  Input Parameter:
. s - the solver

  Level: beginner

  Notes:
  Sets the solver up if needed and checks the path before any work and before a results file is opened: under force
  control a first force below 0 is refused, and on a periodic cell under displacement control every breakpoint must
  lie below full contact, d < mean(h). It begins a new curve, records the starting state at the first breakpoint
  (`AdhSolverStart()`, -adh_start), and follows each leg in -adh_steps steps (`AdhSolverStep()`), recording each state
  and calling the monitors after it. A leg that ends in pull-off ends there: the rest of it has nothing in contact. A
  path that never touches the surface ends with a warning.

  With -adh_output the results file is written as the path goes: every recorded state, and with -adh_fields the
  fields of every -adh_fields_stride-th state. What was computed before an error or a stop is still written, with the
  file's attribute complete = 0. With -adh_checkpoint the state is saved after every -adh_checkpoint_every-th state;
  with -adh_restart the path goes on after the checkpoint's state, in the results file of the run that wrote it (a
  leg that ended in pull-off is over).

  SIGTERM and SIGINT stop the path: every rank reads the flag together in each iteration of the solves, in each set
  update and after each recorded state, and the step in progress is abandoned. The results are closed, and the error
  `PETSC_ERR_SIG` says after which state the results end, how long the stop took, and how to go on. The signal
  handlers are installed for the path and the previous ones restored after it.

.seealso: `AdhSolverStart()`, `AdhSolverStep()`, `AdhSolverGetCurve()`, `AdhSolverGetPath()`, `AdhSolverMonitorSet()`,
          `AdhSolverSetProgress()`, `AdhSolverSetFromOptions()`
@*/
PetscErrorCode AdhSolverSolvePath(AdhSolver s)
{
  PetscViewer    viewer = NULL;
  PetscErrorCode ierr, cerr = 0;
  PetscInt       leg0 = 1, step0 = 0;
  void (*term)(int), (*intr)(int);

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscCheck(!s->writer, s->comm, PETSC_ERR_ORDER, "%s is being written state by state (AdhSolverOutputBegin(), Python's iterate_path(output=...)): end it before solving the path", s->writer_file);
  PetscCall(AdhSolverSetUp(s));
  PetscCall(CheckPath(s));
  PetscCall(AdhCurveDestroy_Private(&s->curve));
  s->checkpoint_state = -1;
  /* a checkpoint that does not fit is refused before a results file is opened */
  if (s->restart[0]) {
    PetscBool same;
    PetscCall(AdhResults.checkpoint_read(s, &leg0, &step0));
    PetscCall(PetscStrcmp(s->restart, s->checkpoint, &same));
    if (same) s->checkpoint_state = s->curve.n - 1;
  }
  if (s->checkpoint[0]) PetscCall(AdhResults.check_writable(s, "-adh_checkpoint", s->checkpoint));
  /* the handlers stay until the results are closed: mpirun's SIGTERM may follow a SIGINT */
  adh_signal     = 0;
  s->stop_signal = 0;
  term           = signal(SIGTERM, OnSignal);
  intr           = signal(SIGINT, OnSignal);
  s->stoppable   = PETSC_TRUE;
  s->on_path     = PETSC_TRUE;
  s->output_failed = PETSC_FALSE;
  ierr             = SolvePathOpen(s, &viewer, leg0, step0);
  s->on_path       = PETSC_FALSE;
  s->stoppable     = PETSC_FALSE;
  /* What was computed before an error or a stop is still written, marked incomplete; after a
     failed write the file is closed as it is (FILE.part, whole to the last state written). The
     first error is the one told: a failure of the close after it is not (after a stop, it is). */
  if (viewer) {
    const PetscBool quiet = (PetscBool)(ierr != 0);
    PetscErrorCode  aerr;
    if (quiet) PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    if (!s->output_failed) {
      cerr = PetscViewerHDF5WriteAttribute(viewer, "/", "complete", PETSC_BOOL, ierr || s->stop_signal ? &(PetscBool){PETSC_FALSE} : &(PetscBool){PETSC_TRUE});
      if (!cerr) cerr = AdhResults.close(s, s->output, &viewer);
    }
    aerr = AdhResults.abandon(&viewer); /* not closed (a write failed): HDF5 lets go of FILE.part as it is */
    if (quiet) {
      PetscCall(PetscPopErrorHandler());
      cerr = 0;
    } else if (!cerr) cerr = aerr;
  }
  if (!ierr && s->stop_signal) { /* the stop is the path's end: told once, as PETSc's signal error */
    char msg[3 * PETSC_MAX_PATH_LEN];
    if (!cerr) cerr = StopMessage(s, msg, sizeof(msg));
    signal(SIGTERM, term);
    signal(SIGINT, intr);
    PetscCall(cerr);
    SETERRQ(s->comm, PETSC_ERR_SIG, "%s", msg);
  }
  signal(SIGTERM, term);
  signal(SIGINT, intr);
  PetscCall(ierr);
  PetscCall(cerr);
  PetscCall(CheckTouched(s));
  PetscFunctionReturn(0);
}
