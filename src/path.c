/* Indentation paths: the starting state, the legs of -adh_path, and the recorded curve. */
#include "solverimpl.h"

PetscErrorCode AdhCurveAppend_Private(AdhCurve *c, PetscReal d, PetscReal F, PetscReal A, PetscInt pts, PetscInt outer, PetscInt ksp, PetscInt mults, PetscReal sec)
{
  PetscFunctionBegin;
  if (c->n == c->cap) {
    PetscInt cap = PetscMax(64, 2 * c->cap);
    PetscCall(PetscRealloc(cap * sizeof(PetscReal), &c->d));
    PetscCall(PetscRealloc(cap * sizeof(PetscReal), &c->force));
    PetscCall(PetscRealloc(cap * sizeof(PetscReal), &c->area));
    PetscCall(PetscRealloc(cap * sizeof(PetscReal), &c->seconds));
    PetscCall(PetscRealloc(cap * sizeof(PetscInt), &c->contact_points));
    PetscCall(PetscRealloc(cap * sizeof(PetscInt), &c->outer_iterations));
    PetscCall(PetscRealloc(cap * sizeof(PetscInt), &c->ksp_iterations));
    PetscCall(PetscRealloc(cap * sizeof(PetscInt), &c->compliance_applications));
    c->cap = cap;
  }
  c->d[c->n]                       = d;
  c->force[c->n]                   = F;
  c->area[c->n]                    = A;
  c->seconds[c->n]                 = sec;
  c->contact_points[c->n]          = pts;
  c->outer_iterations[c->n]        = outer;
  c->ksp_iterations[c->n]          = ksp;
  c->compliance_applications[c->n] = mults;
  c->n++;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhCurveDestroy_Private(AdhCurve *c)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(c->d));
  PetscCall(PetscFree(c->force));
  PetscCall(PetscFree(c->area));
  PetscCall(PetscFree(c->seconds));
  PetscCall(PetscFree(c->contact_points));
  PetscCall(PetscFree(c->outer_iterations));
  PetscCall(PetscFree(c->ksp_iterations));
  PetscCall(PetscFree(c->compliance_applications));
  PetscCall(PetscMemzero(c, sizeof(*c)));
  PetscFunctionReturn(0);
}

/* Marks the local points with h - d <= 0 (touching or overlapping at indentation d). */
static PetscErrorCode SetFromOverlap(AdhSolver s, PetscReal d, PetscBool strict)
{
  const PetscScalar *ha;
  PetscInt           n, k;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(s->h, &n));
  PetscCall(VecGetArrayRead(s->h, &ha));
  for (k = 0; k < n; k++) s->in_set[k] = strict ? PetscRealPart(ha[k]) - d < 0 : PetscRealPart(ha[k]) - d <= 0;
  PetscCall(VecRestoreArrayRead(s->h, &ha));
  PetscCall(VecSet(s->p, 0.0));
  PetscCall(AdhSolverRebuildSet_Private(s));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverStart(AdhSolver s, PetscReal d0)
{
  PetscInt outer = 0, ksp = 0, mults = 0;

  PetscFunctionBegin;
  PetscCall(AdhSolverSetUp(s));
  if (s->start == ADH_START_HERTZ) {
    /* Adhesion-free contact at d0 (Sigma = 0), from the geometric overlap. */
    PetscCall(SetFromOverlap(s, d0, PETSC_TRUE));
    s->adhesive = PETSC_FALSE;
    PetscCall(AdhSolverStep(s, d0));
    s->adhesive = PETSC_TRUE;
  } else {
    /* Load with adhesion from first touch, where the apex points carry no load, to d0. */
    PetscReal dtouch;
    PetscCall(VecMin(s->h, NULL, &dtouch));
    if (d0 > dtouch) {
      PetscCall(SetFromOverlap(s, dtouch, PETSC_FALSE));
      for (PetscInt k = 1; k <= s->steps; k++) {
        PetscCall(AdhSolverStep(s, dtouch + (d0 - dtouch) * k / s->steps));
        outer += s->step_outer; ksp += s->step_ksp; mults += s->step_mults;
      }
      s->step_outer = outer; s->step_ksp = ksp; s->step_mults = mults;
    } else {
      PetscCall(SetFromOverlap(s, d0, PETSC_FALSE));
      PetscCall(AdhSolverStep(s, d0));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetState(AdhSolver s, PetscReal *d, PetscReal *F, PetscReal *A, PetscInt *points, PetscInt *outer, PetscInt *ksp, PetscInt *mults)
{
  PetscScalar sum;

  PetscFunctionBegin;
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

/* Appends the current state to the curve, prints it with -adh_monitor, writes its fields. */
static PetscErrorCode Record(AdhSolver s, PetscLogDouble t0, PetscViewer viewer)
{
  PetscReal      F, A;
  PetscLogDouble t1;

  PetscFunctionBegin;
  PetscCall(PetscTime(&t1));
  PetscCall(AdhSolverGetState(s, NULL, &F, &A, NULL, NULL, NULL, NULL));
  PetscCall(AdhCurveAppend_Private(&s->curve, s->d, F, A, s->npoints, s->step_outer, s->step_ksp, s->step_mults, (PetscReal)(t1 - t0)));
  if (s->monitor) {
    if (s->curve.n == 1) PetscCall(PetscPrintf(s->comm, "%5s %13s %13s %13s %8s %6s %7s %7s %9s\n", "step", "d", "force", "area", "points", "outer", "ksp", "K-mults", "seconds"));
    PetscCall(PetscPrintf(s->comm, "%5" PetscInt_FMT " %13.6e %13.6e %13.6e %8" PetscInt_FMT " %6" PetscInt_FMT " %7" PetscInt_FMT " %7" PetscInt_FMT " %9.3f\n", s->curve.n - 1, (double)s->d, (double)F, (double)A, s->npoints, s->step_outer, s->step_ksp, s->step_mults, (double)(t1 - t0)));
  }
  if (viewer && s->fields) PetscCall(AdhOutputWriteFields_Private(s, viewer, s->curve.n - 1));
  PetscFunctionReturn(0);
}

static PetscErrorCode SolvePathInner(AdhSolver s, PetscViewer viewer)
{
  PetscLogDouble t0;

  PetscFunctionBegin;
  PetscCall(PetscTime(&t0));
  PetscCall(AdhSolverStart(s, s->path[0]));
  PetscCall(Record(s, t0, viewer));
  for (PetscInt leg = 1; leg < s->npath; leg++) {
    const PetscReal a = s->path[leg - 1], b = s->path[leg];
    for (PetscInt k = 1; k <= s->steps; k++) {
      const PetscBool had_contact = s->npoints > 0;
      PetscCall(PetscTime(&t0));
      PetscCall(AdhSolverStep(s, a + (b - a) * k / s->steps));
      PetscCall(Record(s, t0, viewer));
      if (had_contact && !s->npoints && b < a) {
        /* Pull-off: the rest of this unloading leg has nothing in contact. */
        if (s->monitor) PetscCall(PetscPrintf(s->comm, "pull-off at d = %g: the contact set is empty, leg %" PetscInt_FMT " ends\n", (double)s->d, leg));
        break;
      }
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverSolvePath(AdhSolver s)
{
  PetscViewer    viewer = NULL;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(AdhSolverSetUp(s));
  PetscCall(AdhCurveDestroy_Private(&s->curve));
  if (s->output[0]) PetscCall(AdhOutputOpen_Private(s, s->output, &viewer));
  ierr = SolvePathInner(s, viewer);
  /* What was computed before an error is still written, marked incomplete. */
  if (viewer) {
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "complete", PETSC_BOOL, ierr ? &(PetscBool){PETSC_FALSE} : &(PetscBool){PETSC_TRUE}));
    PetscCall(AdhOutputClose_Private(s, s->output, &viewer));
  }
  PetscCall(ierr);
  PetscFunctionReturn(0);
}
