/*MC
   ADHCONTROLFORCE - "force": the path holds forces F, and a step finds the indentation d at which the equilibrium
   contact set carries exactly F

   F is the sum of the pressures times hx hy; for a periodic cell the mean pressure times the cell's area.

   Options Database Keys:
+  -adh_control force        - selects this control
.  -adh_pulloff_rtol <1e-3>  - the relative resolution of the pull-off force
-  -adh_max_outer <100000>   - the largest number of set updates in one step

   Level: beginner

   Notes:
   For a fixed set C the pressure is affine in d, p = d x - y with K_CC x = 1 and K_CC y = h_C, so one extra solve per
   set update gives the d of that set; then points let go and join as under displacement control, until the set is
   stable. When the set empties, no equilibrium carries F: the contact has come off. The step then bisects between
   the previous state's force and F, from the previous state, and ends on the state carrying the largest tension
   (within -adh_pulloff_rtol), marked pulled off.

   On a periodic cell the mean displacement is free (K has no mean mode), and the whole cell in contact makes K_CC
   singular. Under force control the mean pressure is known, so the solve uses K + c0 (1 1^T)/N instead, positive
   definite on every set, and takes the mean displacement c0 mean(p) back out of d.

   A step without contact starts from the first touch if F > 0; F <= 0 leaves the bodies apart. A first force below
   0 is refused by `AdhSolverSolvePath()`. -adh_cascade_apart and -adh_cascade_local are not available.

.seealso: `AdhSolverSetControlType()`, `ADHCONTROLDISPLACEMENT`, `AdhSolverStep()`, `AdhSolverIsPulledOff()`
M*/
#include "solver/solverimpl.h"

/* A copy of the contact state before a step, to go back to when the step finds no equilibrium
   (pull-off). */
typedef struct {
  char     *in_set;
  Vec       p, xunit;
  PetscReal d;
} SavedState;

typedef struct {
  PetscReal  pulloff_rtol; /* -adh_pulloff_rtol: the relative resolution of the pull-off force */
  Vec        xunit;        /* the set's response to a unit indentation, K_CC x = 1 (the solver's set_response) */
  Vec        gap_rate;     /* how fast each gap closes as the set's indentation rises */
  Mat        Kmean;        /* periodic: K + c0 (1 1^T)/N, positive definite on every set (the solver's Kcontrol) */
  PetscReal  c0;           /* its mean-mode compliance */
  PetscReal  e;            /* the indentation of the set's equations, d + c0 mean(p) */
  PetscReal  dc;           /* the step's c0 mean(p) = c0 F / (cell area): d = e - dc */
  PetscReal  Fx;           /* the force of x, sum x, for the rate at which the gaps close */
  PetscBool  unique;       /* the step's state is unique (no adhesion): x may be solved loosely */
  SavedState previous;     /* the state before the current step */
} Force;

static PetscErrorCode SetFromOptions_Force(AdhSolver s, AdhOptionItems PetscOptionsObject)
{
  Force *f = (Force *)s->cops.data;

  PetscFunctionBegin;
  PetscCall(AdhOptionsReal("-adh_pulloff_rtol", "Force control: relative resolution of the pull-off force", "ADHCONTROLFORCE", f->pulloff_rtol, &f->pulloff_rtol, NULL));
  PetscCheck(f->pulloff_rtol > 0 && f->pulloff_rtol < 1, PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_pulloff_rtol must lie in (0, 1), got %g", (double)f->pulloff_rtol);
  PetscFunctionReturn(0);
}

/* Its line of -adh_view, and its attribute in the results file. */
static PetscErrorCode View_Force(AdhSolver s, PetscViewer viewer)
{
  Force    *f = (Force *)s->cops.data;
  PetscBool isascii, ishdf5;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERHDF5, &ishdf5));
  if (isascii) PetscCall(PetscViewerASCIIPrintf(viewer, "pull-off force resolved to a relative %g%s\n", (double)f->pulloff_rtol, f->Kmean ? "; the set's equations with the mean mode K + c0 (1 1^T)/N" : ""));
  if (ishdf5) PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "pulloff_rtol", PETSC_REAL, &f->pulloff_rtol));
  PetscFunctionReturn(0);
}

/* The pull-off is found to this tolerance: a restart repeats it. */
static PetscErrorCode Shape_Force(AdhSolver s, PetscInt *n, AdhShapingOption shape[])
{
  Force *f = (Force *)s->cops.data;

  PetscFunctionBegin;
  shape[0] = (AdhShapingOption){"-adh_pulloff_rtol", PETSC_REAL, &f->pulloff_rtol};
  *n       = 1;
  PetscFunctionReturn(0);
}

/* Its state in a checkpoint: the indentation of the set's equations and the set's unit response. */
static PetscErrorCode Checkpoint_Force(AdhSolver s, PetscViewer v, PetscBool load)
{
  Force *f = (Force *)s->cops.data;

  PetscFunctionBegin;
  PetscCall(PetscObjectSetName((PetscObject)f->xunit, "xunit"));
  if (load) {
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "e", PETSC_REAL, NULL, &f->e));
    PetscCall(VecLoad(f->xunit, v));
  } else {
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "e", PETSC_REAL, &f->e));
    PetscCall(VecView(f->xunit, v));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SetUp_Force(AdhSolver s)
{
  Force *f = (Force *)s->cops.data;

  PetscFunctionBegin;
  if (!f->xunit) {
    PetscCall(VecDuplicate(s->p, &f->xunit));
    PetscCall(VecSet(f->xunit, 0.0));
    PetscCall(VecDuplicate(s->p, &f->gap_rate));
    s->set_response = f->xunit; /* the set's operations keep it zero off the set */
  }
  if (s->boundary == ADH_BOUNDARY_PERIODIC && !f->Kmean) {
    /* c0, the body's compliance of the longest wave (2/(E* q_min) on a half-space): the Fourier
       preconditioner's mean mode is its inverse, so the preconditioned operator stays well
       conditioned. */
    f->c0 = s->eops.mean_compliance;
    PetscCall(MatCreateAdhMeanCompliance(s->K, f->c0, &f->Kmean));
    s->Kcontrol        = f->Kmean;
    s->Kcontrol_lambda = f->c0;
    PetscCall(AdhSolverRebuildSet_Private(s));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Force(AdhSolver s)
{
  Force *f = (Force *)s->cops.data;

  PetscFunctionBegin;
  PetscCall(PetscFree(f->previous.in_set));
  PetscCall(VecDestroy(&f->previous.p));
  PetscCall(VecDestroy(&f->previous.xunit));
  PetscCall(VecDestroy(&f->xunit));
  PetscCall(VecDestroy(&f->gap_rate));
  PetscCall(MatDestroy(&f->Kmean));
  s->set_response = NULL;
  s->Kcontrol     = NULL;
  PetscCall(PetscFree(s->cops.data));
  PetscFunctionReturn(0);
}

/* A copy of the state before a force-controlled step, to go back to when the step finds no
   equilibrium (pull-off). */
static PetscErrorCode SaveState(AdhSolver s, Force *f, SavedState *st)
{
  PetscFunctionBegin;
  if (!st->p) {
    PetscCall(PetscMalloc1(s->nlocal + 1, &st->in_set));
    PetscCall(VecDuplicate(s->p, &st->p));
    PetscCall(VecDuplicate(s->p, &st->xunit));
  }
  PetscCall(PetscArraycpy(st->in_set, s->in_set, s->nlocal));
  PetscCall(VecCopy(s->p, st->p));
  PetscCall(VecCopy(f->xunit, st->xunit));
  st->d = s->d;
  PetscFunctionReturn(0);
}

static PetscErrorCode RestoreState(AdhSolver s, Force *f, SavedState *st)
{
  PetscFunctionBegin;
  PetscCall(PetscArraycpy(s->in_set, st->in_set, s->nlocal));
  PetscCall(VecCopy(st->p, s->p));
  PetscCall(VecCopy(st->xunit, f->xunit));
  s->d = st->d;
  PetscCall(AdhSolverRebuildSet_Private(s));
  PetscFunctionReturn(0);
}

/* The points of the first touch, h = min h, with no pressure. */
static PetscErrorCode SeedFirstTouch(AdhSolver s, Force *f)
{
  PetscReal hmin;

  PetscFunctionBegin;
  PetscCall(VecMin(s->h, NULL, &hmin));
  PetscCall(AdhSolverSetFromOverlap_Private(s, hmin, PETSC_FALSE));
  PetscCall(VecSet(f->xunit, 0.0));
  s->d = hmin;
  f->e = hmin;
  PetscFunctionReturn(0);
}

/* The equilibrium of the current set carrying F. For a fixed set the pressure is affine in the
   indentation, p = e x - y with K_CC x = 1: the solve at the current e, the unit response x, and
   the e at which p carries F. No equilibrium once the set has emptied. */
static PetscErrorCode Equilibrate_Force(AdhSolver s, PetscReal F, PetscBool *none)
{
  Force          *f = (Force *)s->cops.data;
  const PetscReal A = s->grid->hx * s->grid->hy;
  PetscScalar     Fp, Fx;
  PetscReal       de;

  PetscFunctionBegin;
  *none = (PetscBool)!s->npoints;
  if (*none) PetscFunctionReturn(0);
  PetscCall(AdhSolverSolveOnSet_Private(s, ADH_SET_SOLVE_PRESSURE, f->e, PETSC_FALSE));
  AdhSolverReturnIfStopped_Private(s);
  PetscCall(VecSum(s->p, &Fp));
  if (f->unique) {
    /* the unit response x only corrects p by de x, de = (F/A - sum p)/sum x: x needs only as
       many digits as the mismatch leaves to the solver's tolerance (at most 1e-3 relative) */
    PetscReal rtol, atol, dtol, mismatch = PetscAbsReal(F / A - PetscRealPart(Fp));
    PetscInt  maxits;

    PetscCall(KSPGetTolerances(s->ksp, &rtol, &atol, &dtol, &maxits));
    PetscCall(KSPSetTolerances(s->ksp, mismatch > 0 ? PetscMin(1e-3, PetscMax(rtol, rtol * PetscAbsReal(F / A) / mismatch)) : 1e-3, atol, dtol, maxits));
    PetscCall(AdhSolverSolveOnSet_Private(s, ADH_SET_SOLVE_UNIT_RESPONSE, 0.0, PETSC_FALSE));
    PetscCall(KSPSetTolerances(s->ksp, rtol, atol, dtol, maxits));
  } else PetscCall(AdhSolverSolveOnSet_Private(s, ADH_SET_SOLVE_UNIT_RESPONSE, 0.0, PETSC_FALSE));
  AdhSolverReturnIfStopped_Private(s);
  PetscCall(VecSum(f->xunit, &Fx));
  f->Fx = PetscRealPart(Fx);
  PetscCheck(f->Fx > 0, s->comm, PETSC_ERR_PLIB, "The unit-indentation response of the contact set carries no force");
  de = (F / A - PetscRealPart(Fp)) / f->Fx;
  f->e += de;
  PetscCall(VecAXPY(s->p, de, f->xunit)); /* x vanishes off the set */
  s->d = f->e - f->dc;
  PetscFunctionReturn(0);
}

/* With the set fixed, g = h - d + K p closes at (dd/de) - (K x)_k per unit e, and
   dd/de = 1 - c0 sum(x)/N: the points join in the order they would touch as e rises. */
static PetscErrorCode AttachRate_Force(AdhSolver s, Vec *rate, PetscReal *e)
{
  Force *f = (Force *)s->cops.data;

  PetscFunctionBegin;
  PetscCall(MatMult(s->K, f->xunit, f->gap_rate));
  PetscCall(VecScale(f->gap_rate, -1.0));
  PetscCall(VecShift(f->gap_rate, 1.0 - (f->Kmean ? f->c0 * f->Fx / (s->grid->Nx * s->grid->Ny) : 0.0)));
  *rate = f->gap_rate;
  *e    = f->e;
  PetscFunctionReturn(0);
}

/* The equilibrium set carrying F, from the current set; it may empty (no equilibrium). unique:
   there is no adhesion, so the state carrying F is the same from any set, and the order in which
   points join does not matter (the unit response may then be solved loosely). */
static PetscErrorCode Equilibrate(AdhSolver s, Force *f, PetscReal F, PetscBool unique)
{
  const PetscReal A = s->grid->hx * s->grid->hy;

  PetscFunctionBegin;
  /* d = e - c0 mean(p), and mean(p) = F / (cell area) is fixed by the target */
  f->dc     = f->Kmean ? f->c0 * F / (A * s->grid->Nx * s->grid->Ny) : 0.0;
  f->e      = s->d + f->dc;
  f->unique = unique;
  PetscCall(AdhSolverUpdateSet_Private(s, F));
  PetscFunctionReturn(0);
}

/* Whether the state after an equilibration carries the force: a set of contact points, or under a
   cohesive law any state its minimisation found (one attached through the law alone, with no
   point at the wall, carries it too). */
static PetscBool Carried(AdhSolver s)
{
  return s->crops.law ? (PetscBool)!s->law_apart : (PetscBool)(s->npoints > 0);
}

/* With no point at the wall, whether a cohesive law still holds the bodies: a gap within its
   zone (a state attached through the law alone, which the next step goes on from). */
static PetscErrorCode LawHolds(AdhSolver s, PetscBool *holds)
{
  PetscReal dgamma = s->gamma, gmin;

  PetscFunctionBegin;
  *holds = PETSC_FALSE;
  if (!s->crops.law || !s->crops.zone_gap || !s->adhesive || s->pulled_off) PetscFunctionReturn(0);
  if (s->gamma_field) PetscCall(VecMax(s->gamma_field, NULL, &dgamma));
  if (!(dgamma > 0)) PetscFunctionReturn(0);
  PetscCall(AdhSolverComputeGap_Private(s));
  PetscCall(VecMin(s->g, NULL, &gmin));
  *holds = (PetscBool)(gmin <= s->crops.zone_gap(s->crops.data, dgamma));
  PetscFunctionReturn(0);
}

/* Force control: the equilibrium set carrying F. When none does (the set empties), the contact
   has come off: bisect between the previous state's force and F from the previous state, and end
   on the state carrying the largest tension (within -adh_pulloff_rtol), marked pulled off. */
static PetscErrorCode Step_Force(AdhSolver s, PetscReal F)
{
  Force          *f = (Force *)s->cops.data;
  const PetscReal A = s->grid->hx * s->grid->hy;
  const PetscBool unique = (PetscBool)(s->pops.predict && !AdhSolverIsAdhesive_Private(s));
  PetscScalar     sum;
  PetscReal       carried, failed = F, tol;
  PetscBool       holds = PETSC_FALSE;

  PetscFunctionBegin;
  if (!s->npoints) PetscCall(LawHolds(s, &holds));
  if (!s->npoints && !holds) {
    if (F <= 0) {
      /* off the surface, and nothing pulls it back: no pressure, the undeformed gap */
      PetscCall(AdhSolverComputeGap_Private(s));
      PetscFunctionReturn(0);
    }
    PetscCall(SeedFirstTouch(s, f));
  }
  PetscCall(VecSum(s->p, &sum));
  carried = PetscRealPart(sum) * A;
  PetscCall(SaveState(s, f, &f->previous));
  /* without adhesion the state carrying F > 0 is unique: a predictor may guess its set */
  if (s->pops.predict && F > 0 && !AdhSolverIsAdhesive_Private(s)) PetscCall(s->pops.predict(s, PETSC_TRUE, F));
  AdhSolverReturnIfStopped_Private(s);
  PetscCall(Equilibrate(s, f, F, unique));
  AdhSolverReturnIfStopped_Private(s);
  if (Carried(s)) PetscFunctionReturn(0);
  PetscCall(RestoreState(s, f, &f->previous));
  /* relative to the step's forces, so that a pull-off force of 0 (no adhesion) ends too */
  tol = f->pulloff_rtol * PetscMax(PetscAbsReal(carried), PetscAbsReal(F));
  for (PetscInt k = 0; k < 60 && PetscAbsReal(failed - carried) > tol; k++) {
    const PetscReal mid = 0.5 * (carried + failed);
    /* each trial is a step of its own from the saved state */
    PetscCall(AdhSolverBeginSetUpdates_Private(s));
    PetscCall(Equilibrate(s, f, mid, PETSC_FALSE));
    AdhSolverReturnIfStopped_Private(s);
    if (Carried(s)) {
      carried = mid;
      PetscCall(SaveState(s, f, &f->previous));
    } else {
      failed = mid;
      PetscCall(RestoreState(s, f, &f->previous));
    }
  }
  PetscCall(AdhSolverComputeGap_Private(s));
  s->pulled_off = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhControlCreate_Force(AdhSolver s)
{
  Force *f;

  PetscFunctionBegin;
  PetscCall(PetscNew(&f));
  f->pulloff_rtol              = 1e-3;
  s->cops.data                 = f;
  s->cops.target               = ADH_TARGET_FORCE;
  s->cops.step                 = Step_Force;
  s->cops.equilibrate          = Equilibrate_Force;
  s->cops.attach_rate          = AttachRate_Force;
  s->cops.base.setfromoptions  = SetFromOptions_Force;
  s->cops.base.view            = View_Force;
  s->cops.base.setup           = SetUp_Force;
  s->cops.base.destroy         = Destroy_Force;
  s->cops.base.shape           = Shape_Force;
  s->cops.base.checkpoint      = Checkpoint_Force;
  PetscFunctionReturn(0);
}
