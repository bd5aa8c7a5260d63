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

static PetscErrorCode SetUp_Force(AdhSolver s)
{
  PetscFunctionBegin;
  if (!s->xunit) {
    PetscCall(VecDuplicate(s->p, &s->xunit));
    PetscCall(VecSet(s->xunit, 0.0));
    PetscCall(VecDuplicate(s->p, &s->gap_rate));
  }
  if (s->boundary == ADH_BOUNDARY_PERIODIC && !s->Kmean) {
    /* c0 = 2/(E* q_min), the compliance of the longest wave: the Fourier preconditioner's mean
       mode is its inverse, so the preconditioned operator stays well conditioned. */
    s->c0 = 2.0 / (s->Estar * 2.0 * PETSC_PI / PetscMax(s->grid->Lx, s->grid->Ly));
    PetscCall(MatCreateAdhMeanCompliance(s->K, s->c0, &s->Kmean));
    PetscCall(AdhSolverRebuildSet_Private(s));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Force(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(s->previous.in_set));
  PetscCall(VecDestroy(&s->previous.p));
  PetscCall(VecDestroy(&s->previous.xunit));
  PetscCall(VecDestroy(&s->xunit));
  PetscCall(VecDestroy(&s->gap_rate));
  PetscCall(MatDestroy(&s->Kmean));
  s->c0 = 0.0;
  PetscFunctionReturn(0);
}

/* A copy of the state before a force-controlled step, to go back to when the step finds no
   equilibrium (pull-off). */
static PetscErrorCode SaveState(AdhSolver s, AdhSavedState *st)
{
  PetscFunctionBegin;
  if (!st->p) {
    PetscCall(PetscMalloc1(s->nlocal + 1, &st->in_set));
    PetscCall(VecDuplicate(s->p, &st->p));
    PetscCall(VecDuplicate(s->p, &st->xunit));
  }
  PetscCall(PetscArraycpy(st->in_set, s->in_set, s->nlocal));
  PetscCall(VecCopy(s->p, st->p));
  PetscCall(VecCopy(s->xunit, st->xunit));
  st->d = s->d;
  PetscFunctionReturn(0);
}

static PetscErrorCode RestoreState(AdhSolver s, AdhSavedState *st)
{
  PetscFunctionBegin;
  PetscCall(PetscArraycpy(s->in_set, st->in_set, s->nlocal));
  PetscCall(VecCopy(st->p, s->p));
  PetscCall(VecCopy(st->xunit, s->xunit));
  s->d = st->d;
  PetscCall(AdhSolverRebuildSet_Private(s));
  PetscFunctionReturn(0);
}

/* The points of the first touch, h = min h, with no pressure. */
static PetscErrorCode SeedFirstTouch(AdhSolver s)
{
  PetscReal hmin;

  PetscFunctionBegin;
  PetscCall(VecMin(s->h, NULL, &hmin));
  PetscCall(AdhSolverSetFromOverlap_Private(s, hmin, PETSC_FALSE));
  PetscCall(VecSet(s->xunit, 0.0));
  s->d = hmin;
  s->e = hmin;
  PetscFunctionReturn(0);
}

/* The equilibrium set carrying F, from the current set; it may empty (no equilibrium). unique:
   there is no adhesion, so the state carrying F is the same from any set, and the order in which
   points join does not matter (the unit response may then be solved loosely). */
static PetscErrorCode Equilibrate(AdhSolver s, PetscReal F, PetscBool unique)
{
  const PetscReal A  = s->grid->hx * s->grid->hy;
  /* d = e - c0 mean(p), and mean(p) = F / (cell area) is fixed by the target */
  const PetscReal dc = s->Kmean ? s->c0 * F / (A * s->grid->Nx * s->grid->Ny) : 0.0;
  PetscInt        outer, removed, added;
  PetscBool       loose = (PetscBool)(s->cascade_rtol > 0); /* -adh_cascade_rtol: the next solves may stop early */

  PetscFunctionBegin;
  s->e = s->d + dc;
  for (outer = 1; s->npoints; outer++) {
    PetscScalar Fp, Fx;
    PetscReal   de;

    PetscCheck(outer <= s->max_outer, s->comm, PETSC_ERR_NOT_CONVERGED, "No stable contact set for the force %g after %" PetscInt_FMT " set updates (-adh_max_outer)", (double)F, s->max_outer);
    AdhSolverCheckStop_Private(s);
    PetscCall(AdhSolverMonitorProgress_Private(s, outer));
    s->solve_loose = loose;
    PetscCall(AdhSolverSolveOnSet_Private(s, s->p, s->e, s->h, PETSC_FALSE));
    PetscCall(VecSum(s->p, &Fp));
    if (unique) {
      /* the unit response x only corrects p by de x, de = (F/A - sum p)/sum x: x needs only as
         many digits as the mismatch leaves to the solver's tolerance (at most 1e-3 relative) */
      PetscReal rtol, atol, dtol, mismatch = PetscAbsReal(F / A - PetscRealPart(Fp));
      PetscInt  maxits;

      PetscCall(KSPGetTolerances(s->ksp, &rtol, &atol, &dtol, &maxits));
      PetscCall(KSPSetTolerances(s->ksp, mismatch > 0 ? PetscMin(1e-3, PetscMax(rtol, rtol * PetscAbsReal(F / A) / mismatch)) : 1e-3, atol, dtol, maxits));
      PetscCall(AdhSolverSolveOnSet_Private(s, s->xunit, 1.0, NULL, PETSC_FALSE));
      PetscCall(KSPSetTolerances(s->ksp, rtol, atol, dtol, maxits));
    } else PetscCall(AdhSolverSolveOnSet_Private(s, s->xunit, 1.0, NULL, PETSC_FALSE));
    s->solve_loose = PETSC_FALSE;
    PetscCall(VecSum(s->xunit, &Fx));
    PetscCheck(PetscRealPart(Fx) > 0, s->comm, PETSC_ERR_PLIB, "The unit-indentation response of the contact set carries no force");
    de = (F / A - PetscRealPart(Fp)) / PetscRealPart(Fx);
    s->e += de;
    PetscCall(VecAXPY(s->p, de, s->xunit)); /* x vanishes off the set */
    s->d = s->e - dc;
    PetscCall(PetscLogEventBegin(ADH_SetUpdate, 0, 0, 0, 0));
    PetscCall(AdhSolverDetach_Private(s, &removed));
    if (!removed && loose) { /* the set stands on loose solves: solve to the full tolerance and test again */
      loose = PETSC_FALSE;
      PetscCall(PetscLogEventEnd(ADH_SetUpdate, 0, 0, 0, 0));
      s->step_outer++;
      continue;
    }
    added = 0;
    if (!removed) {
      /* with the set fixed, g = h - d + K p closes at (dd/de) - (K x)_k per unit e, and
         dd/de = 1 - c0 sum(x)/N */
      PetscCall(MatMult(s->K, s->xunit, s->gap_rate));
      PetscCall(VecScale(s->gap_rate, -1.0));
      PetscCall(VecShift(s->gap_rate, 1.0 - (s->Kmean ? s->c0 * PetscRealPart(Fx) / (s->grid->Nx * s->grid->Ny) : 0.0)));
      PetscCall(AdhSolverAttach_Private(s, s->gap_rate, 0, &added));
    }
    if (removed || added) {
      PetscCall(AdhSolverRebuildSet_Private(s));
      loose = (PetscBool)(s->cascade_rtol > 0);
    }
    PetscCall(PetscLogEventEnd(ADH_SetUpdate, 0, 0, 0, 0));
    s->step_outer++;
    if (!removed && !added) break;
  }
  PetscFunctionReturn(0);
}

/* Force control: the equilibrium set carrying F. When none does (the set empties), the contact
   has come off: bisect between the previous state's force and F from the previous state, and end
   on the state carrying the largest tension (within -adh_pulloff_rtol), marked pulled off. */
static PetscErrorCode Step_Force(AdhSolver s, PetscReal F)
{
  const PetscReal A = s->grid->hx * s->grid->hy;
  PetscScalar     sum;
  PetscReal       carried, failed = F, tol;

  PetscFunctionBegin;
  if (!s->npoints) {
    if (F <= 0) {
      /* off the surface, and nothing pulls it back: no pressure, the undeformed gap */
      PetscCall(AdhSolverComputeGap_Private(s));
      PetscFunctionReturn(0);
    }
    PetscCall(SeedFirstTouch(s));
  }
  PetscCall(VecSum(s->p, &sum));
  carried = PetscRealPart(sum) * A;
  PetscCall(SaveState(s, &s->previous));
  /* without adhesion the state carrying F > 0 is unique: a predictor may guess its set */
  if (s->predict && F > 0 && !AdhSolverIsAdhesive_Private(s)) PetscCall(s->predict(s, PETSC_TRUE, F));
  PetscCall(Equilibrate(s, F, (PetscBool)(s->predict && !AdhSolverIsAdhesive_Private(s))));
  if (s->npoints) PetscFunctionReturn(0);
  PetscCall(RestoreState(s, &s->previous));
  /* relative to the step's forces, so that a pull-off force of 0 (no adhesion) ends too */
  tol = s->pulloff_rtol * PetscMax(PetscAbsReal(carried), PetscAbsReal(F));
  for (PetscInt k = 0; k < 60 && PetscAbsReal(failed - carried) > tol; k++) {
    const PetscReal mid = 0.5 * (carried + failed);
    /* each trial is a step of its own from the saved state */
    PetscCall(AdhSolverBeginSetUpdates_Private(s));
    PetscCall(Equilibrate(s, mid, PETSC_FALSE));
    if (s->npoints) {
      carried = mid;
      PetscCall(SaveState(s, &s->previous));
    } else {
      failed = mid;
      PetscCall(RestoreState(s, &s->previous));
    }
  }
  PetscCall(AdhSolverComputeGap_Private(s));
  s->pulled_off = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhControlCreate_Force(AdhSolver s)
{
  PetscFunctionBegin;
  s->cops.setup     = SetUp_Force;
  s->cops.step      = Step_Force;
  s->cops.destroy   = Destroy_Force;
  s->force_control  = PETSC_TRUE;
  PetscFunctionReturn(0);
}
