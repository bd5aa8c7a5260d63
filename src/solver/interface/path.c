/* Paths: the starting state, the legs of -adh_path (indentations, or forces under force
   control), and the recorded curve. */
#include <signal.h>
#include <time.h>
#include "solver/solverimpl.h"

#define COLUMN(name, integer) {#name, offsetof(AdhState, name), integer}
const AdhCurveColumn AdhCurveColumns[] = {
  COLUMN(d, PETSC_FALSE),
  COLUMN(force, PETSC_FALSE),
  COLUMN(area, PETSC_FALSE),
  COLUMN(contact_points, PETSC_TRUE),
  COLUMN(outer_iterations, PETSC_TRUE),
  COLUMN(ksp_iterations, PETSC_TRUE),
  COLUMN(seconds, PETSC_FALSE),
  COLUMN(compliance_applications, PETSC_TRUE),
  COLUMN(fft_pairs, PETSC_TRUE),
  COLUMN(patches, PETSC_TRUE),
  COLUMN(mean_gap, PETSC_FALSE),
  COLUMN(max_tension_ratio, PETSC_FALSE),
  COLUMN(area_tension, PETSC_FALSE),
  COLUMN(area_compression, PETSC_FALSE),
  COLUMN(pulled_off, PETSC_TRUE),
  COLUMN(detach_ratio, PETSC_FALSE),
  COLUMN(smallest_tensile_patch, PETSC_TRUE),
  COLUMN(small_patch_tension, PETSC_FALSE),
};
const PetscInt AdhCurveNumColumns = sizeof(AdhCurveColumns) / sizeof(AdhCurveColumns[0]);

/*@
  AdhStateValue - Gives one column of a recorded state as a real number

  Not Collective

  Input Parameters:
+ st     - the state
- column - the column's index in `AdhCurveColumns`, from 0 to `AdhCurveNumColumns` - 1

  Level: intermediate

  Notes:
  Returns the value; a count (an integer column) is converted to `PetscReal`. `AdhCurveColumns` gives each column's
  name, its place in `AdhState` and whether it is a count, in the order of the CSV file. The index is not checked.

.seealso: `AdhSolverGetCurve()`, `AdhSolverRecordState()`, `AdhSolverComputeState()`
@*/
PetscReal AdhStateValue(const AdhState *st, PetscInt column)
{
  const char *field = (const char *)st + AdhCurveColumns[column].offset;
  return AdhCurveColumns[column].integer ? (PetscReal) * (const PetscInt *)field : *(const PetscReal *)field;
}

void AdhStateSetValue(AdhState *st, PetscInt column, PetscReal value)
{
  char *field = (char *)st + AdhCurveColumns[column].offset;
  if (AdhCurveColumns[column].integer) *(PetscInt *)field = (PetscInt)value;
  else *(PetscReal *)field = value;
}

PetscErrorCode AdhCurveAppend_Private(AdhCurve *c, const AdhState *st)
{
  PetscFunctionBegin;
  if (c->n == c->cap) {
    c->cap = PetscMax(64, 2 * c->cap);
    PetscCall(PetscRealloc(c->cap * sizeof(AdhState), &c->state));
  }
  c->state[c->n++] = *st;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhCurveDestroy_Private(AdhCurve *c)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(c->state));
  PetscCall(PetscMemzero(c, sizeof(*c)));
  PetscFunctionReturn(0);
}

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
  if (s->xunit) PetscCall(VecSet(s->xunit, 0.0));
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
  PetscCheck(s->start != ADH_START_HERTZ || !s->force_control || target >= 0, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_path: the first force is %g, but the adhesion-free start (-adh_start hertz) carries no tension; start from a compressive force or use -adh_start adhesive", (double)target);
  PetscCheck(!s->force_control || target >= 0, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_path: the first force is %g, a tension the start cannot reach: -adh_start adhesive loads from first touch, where the contact carries none; start from a compressive force (or 0) and pull in a later leg (-adh_path 0.01,%g)", (double)target, (double)target);
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
  s->curve.n = 0;
  PetscCall(VecMin(s->h, NULL, &dtouch));
  if (s->start == ADH_START_HERTZ) {
    /* Adhesion-free contact at d0 (Sigma = 0), from the geometric overlap, or under force control
       from the first touch. */
    PetscCall(CheckStartTarget(s, target));
    PetscCall(AdhSolverSetFromOverlap_Private(s, s->force_control ? dtouch : target, (PetscBool)!s->force_control));
    s->d        = dtouch;
    s->adhesive = PETSC_FALSE;
    PetscCall(AdhSolverStep(s, target));
    s->adhesive = PETSC_TRUE;
  } else {
    /* Load with adhesion from first touch, where the apex points carry no load, to the target in
       -adh_steps steps. */
    const PetscReal t0 = s->force_control ? 0.0 : dtouch;
    PetscCall(AdhSolverSetFromOverlap_Private(s, PetscMin(dtouch, s->force_control ? dtouch : target), PETSC_FALSE));
    s->d = dtouch;
    if (s->force_control || target > dtouch) {
      for (PetscInt k = 1; k <= s->steps; k++) {
        PetscCall(AdhSolverStep(s, t0 + (target - t0) * k / s->steps));
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
. outer  - the set updates of the last step (or `NULL`)
. ksp    - the KSP iterations of the last step (or `NULL`)
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
static PetscErrorCode Progress(AdhSolver s)
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
  for (PetscInt k = 0; k < s->nmonitors; k++) {
    /* a monitor that fails on one rank stops every rank, not just that one */
    int err = (int)s->monitors[k](s, step, st, s->monitor_ctx[k]);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &err, 1, MPI_INT, MPI_MAX, s->comm));
    PetscCheck(!err, s->comm, PETSC_ERR_USER, "Monitor %" PetscInt_FMT " failed at state %" PetscInt_FMT " (error %d)", k, step, err);
  }
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
  PetscCall(Progress(s));
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
  if (s->restart[0]) {
    /* go on after the checkpoint's state; a leg that ended in pull-off is over */
    if (leg0 == 0) leg0 = 1;
    else if (s->pulled_off) {
      leg0++;
      step0 = 0;
    }
  } else {
    PetscCall(PetscTime(&t0));
    PetscCall(AdhSolverStart(s, s->path[0]));
    PetscCall(Record(s, t0, viewer));
    PetscCall(AfterRecord(s, 0, 0));
  }
  for (PetscInt leg = leg0; leg < s->npath; leg++) {
    const PetscReal a = s->path[leg - 1], b = s->path[leg];
    for (PetscInt k = leg == leg0 ? step0 + 1 : 1; k <= s->steps; k++) {
      PetscCall(PetscTime(&t0));
      PetscCall(AdhSolverStep(s, a + (b - a) * k / s->steps));
      PetscCall(Record(s, t0, viewer));
      PetscCall(AfterRecord(s, leg, k));
      if (s->pulled_off) break; /* the rest of this leg has nothing in contact */
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
  if (s->boundary == ADH_BOUNDARY_PERIODIC && !s->force_control)
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
  ierr           = SolvePathOpen(s, &viewer, leg0, step0);
  s->on_path     = PETSC_FALSE;
  s->stoppable   = PETSC_FALSE;
  /* What was computed before an error or a stop is still written, marked incomplete. */
  if (viewer) {
    cerr = PetscViewerHDF5WriteAttribute(viewer, "/", "complete", PETSC_BOOL, ierr ? &(PetscBool){PETSC_FALSE} : &(PetscBool){PETSC_TRUE});
    if (!cerr) cerr = AdhResults.close(s, s->output, &viewer);
  }
  if (ierr == PETSC_ERR_SIG && s->stop_signal) {
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
