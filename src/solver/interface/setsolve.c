/* The solve on the contact set: K_CC p_C = (d - h)_C with KSP, its certified convergence test, and
   the single-precision loose solves. */
#include "solver/solverimpl.h"

/* The solve's iterate xC into p on the set (p off the set stays): the state the certified checks
   look at. Its gap is no longer current. */
PetscErrorCode AdhSolverSetIterate_Private(AdhSolver s, Vec xC)
{
  const PetscScalar *xa;
  PetscScalar       *pa;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(xC, &xa));
  PetscCall(VecGetArray(s->p, &pa));
  for (PetscInt k = 0; k < s->nset_local; k++) pa[s->set_local[k]] = xa[k];
  PetscCall(VecRestoreArray(s->p, &pa));
  PetscCall(VecRestoreArrayRead(xC, &xa));
  s->gap_current = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* KSP convergence test: the full tolerance ||r|| <= max(rtol ||b||, atol), or, for a solve whose
   only job is to decide the next update of the set, a certified early stop. Since every eigenvalue
   of K_CC is at least lambda_min (Cauchy interlacing), |p_k - p*_k| <= perr = ||r||_2 / lambda_min;
   once the criterion's decide (AdhCriterionOps) says that within that bound some points let go
   and every point's decision is the exact solution's, the solve can stop. When it says that none
   lets go, the attach test may be decided in the same way (AdhSolverAttachDecided_Private). The factor 2 covers
   the difference between CG's recursive residual and the true one. Either way the set changes,
   so the last solve of a step always runs to the full tolerance. */
PETSC_INTERN PetscErrorCode AdhConvergedCertified_Private(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason *reason, void *ctx)
{
  AdhSolver          s = (AdhSolver)ctx;
  PetscReal          rtol, atol, dtol;
  PetscInt           maxits;

  PetscFunctionBegin;
  *reason = KSP_CONVERGED_ITERATING;
  {
    /* a signal stops the path within an iteration: the solve ends here, marked by stop_signal */
    PetscBool stop;
    PetscCall(AdhSolverStopRequested_Private(s, &stop));
    if (stop) {
      *reason = KSP_DIVERGED_NULL;
      PetscFunctionReturn(0);
    }
  }
  PetscCall(KSPGetTolerances(ksp, &rtol, &atol, &dtol, &maxits));
  if (PetscIsInfOrNanReal(rnorm)) {
    *reason = KSP_DIVERGED_NANORINF;
    PetscFunctionReturn(0);
  }
  if (rnorm <= PetscMax(rtol * s->bnorm, atol) || (s->solve_loose && rnorm <= s->cascade_rtol * s->bnorm)) {
    *reason = KSP_CONVERGED_RTOL;
    PetscFunctionReturn(0);
  }
  if (s->certify_solve && it > 0) {
    Vec               x;
    const PetscReal   perr       = 2.0 * rnorm / s->lambda_set;
    const PetscBool   attach_due = (PetscBool)(s->certify_attach && rnorm <= s->attach_rnorm);
    AdhDetachDecision decision   = ADH_DETACH_IN_DOUBT;

    PetscCall(KSPBuildSolution(ksp, NULL, &x));
    /* decided at this iterate: when the bound has come down far enough, and, once the exact
       solution is known to let nothing go, again before an attach check (the step's detach test
       runs on the iterate the solve stops at, which must let nothing go either) */
    if ((!s->detach_none && perr <= s->detach_perr) || (s->detach_none && attach_due)) {
      PetscReal needed;
      PetscCall(s->crops.decide(s, x, perr, &decision, &needed));
      if (decision == ADH_DETACH_IN_DOUBT) s->detach_perr = needed;
      else if (decision == ADH_DETACH_NONE && needed == 0) s->detach_none = PETSC_TRUE;
    }
    if (decision == ADH_DETACH_SOME) {
      *reason           = KSP_CONVERGED_ATOL; /* marked by certified_stop */
      s->certified_stop = PETSC_TRUE;
    } else if (decision == ADH_DETACH_NONE && attach_due) {
      PetscBool certain;
      PetscReal needed;
      PetscCall(AdhSolverAttachDecided_Private(s, x, rnorm, &certain, &needed));
      if (certain) {
        *reason             = KSP_CONVERGED_ATOL; /* marked by certified_attach */
        s->certified_attach = PETSC_TRUE;
      } else s->attach_rnorm = needed ? PetscMin(0.5 * rnorm, needed) : -1.0;
    }
  }
  PetscFunctionReturn(0);
}

/* The load of the tractions a cohesive criterion holds off the set, on the set's points: w = K q
   with q the pressure off the set (K the operator of the set's equations on the whole grid); NULL
   when there is none. One compliance multiply. */
static PetscErrorCode OffSetLoad(AdhSolver s, const PetscScalar **wa)
{
  PetscScalar *qa;
  PetscReal    qmax;

  PetscFunctionBegin;
  *wa = NULL;
  if (!s->off_load) {
    PetscCall(VecDuplicate(s->p, &s->off_load));
    PetscCall(VecDuplicate(s->p, &s->off_work));
  }
  PetscCall(VecCopy(s->p, s->off_work));
  PetscCall(VecGetArray(s->off_work, &qa));
  for (PetscInt k = 0; k < s->nset_local; k++) qa[s->set_local[k]] = 0.0;
  PetscCall(VecRestoreArray(s->off_work, &qa));
  PetscCall(VecNorm(s->off_work, NORM_INFINITY, &qmax));
  if (qmax == 0.0) PetscFunctionReturn(0);
  PetscCall(MatMult(s->Kcontrol ? s->Kcontrol : s->K, s->off_work, s->off_load));
  PetscCall(VecGetArrayRead(s->off_load, wa));
  PetscFunctionReturn(0);
}

/* x_C from K_CC x_C = (shift - prof)_C, warm-started from x, which is left as it is off the set:
   the pressure (x = p, prof = h, shift = d) or the unit response (x = s->set_response, no
   profile, shift = 1). With certify (the pressure at the path's indentation, displacement
   control's), the solve may stop as soon as the points to detach, and those to join, are
   certain. The pressure's solve of a cohesive criterion also takes the load of the tractions off
   the set: K_CC p_C = (d - h)_C - (K p_off)_C. */
PetscErrorCode AdhSolverSolveOnSet_Private(AdhSolver s, AdhSetSolve what, PetscReal d, PetscBool certify)
{
  const PetscBool    pressure = (PetscBool)(what == ADH_SET_SOLVE_PRESSURE);
  const Vec          x = pressure ? s->p : s->set_response, prof = pressure ? s->h : NULL;
  const PetscReal    shift = pressure ? d : 1.0;
  KSPConvergedReason reason;
  PetscInt           its, k;
  const PetscScalar *xa, *ha = NULL, *ta = NULL, *wa = NULL;
  PetscReal          tu;
  PetscBool          field;
  PetscScalar       *xc, *bc, *xw;

  PetscFunctionBegin;
  s->certified_stop   = PETSC_FALSE;
  s->certified_attach = PETSC_FALSE;
  if (!s->npoints) PetscFunctionReturn(0);
  PetscCheck(!(s->boundary == ADH_BOUNDARY_PERIODIC && s->lambda_set <= 0), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "The whole periodic cell is in contact at d = %g: under displacement control the force is undetermined there (d must stay below the mean of the indenter profile, %g); use -adh_control force", (double)s->d, (double)s->mean_h);
  PetscCheck(x, s->comm, PETSC_ERR_PLIB, "A unit-response solve without the control's response vector");
  if (s->crops.cohesive && pressure) PetscCall(OffSetLoad(s, &wa));
  /* The set's points are local to each rank, so restriction is a local gather. */
  PetscCall(VecGetArrayRead(x, &xa));
  if (prof) PetscCall(VecGetArrayRead(prof, &ha));
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_TRUE, &ta, &tu));
  /* the allowed tension on the set: one value, or (a field) an array of the set's size, 8 B a
     point of the set that a uniform dgamma does without (field: before the restore clears ta) */
  field = (PetscBool)(ta != NULL);
  if (field && !s->thrC) PetscCall(PetscMalloc1(s->nset_local + 1, &s->thrC));
  PetscCall(VecGetArrayWrite(s->pC, &xc));
  PetscCall(VecGetArrayWrite(s->bC, &bc));
  for (k = 0; k < s->nset_local; k++) {
    const PetscInt m = s->set_local[k];
    xc[k]         = xa[m];
    bc[k]         = shift - (ha ? ha[m] : 0.0) - (wa ? wa[m] : 0.0);
    if (field) s->thrC[k] = ADH_SIGMA_AT(ta, tu, m);
  }
  PetscCall(VecRestoreArrayWrite(s->bC, &bc));
  PetscCall(VecRestoreArrayWrite(s->pC, &xc));
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &ta));
  if (wa) PetscCall(VecRestoreArrayRead(s->off_load, &wa));
  if (prof) PetscCall(VecRestoreArrayRead(prof, &ha));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecNorm(s->bC, NORM_2, &s->bnorm));
  s->threshold_local   = field ? s->thrC : NULL;
  s->threshold_uniform = tu;
  s->certify_solve   = (PetscBool)(certify && s->certify && s->crops.decide && s->lambda_set > 0);
  s->detach_perr     = PETSC_MAX_REAL;
  s->detach_none     = PETSC_FALSE;
  /* the attach test of displacement control (the gap of h at s->d), where points have been
     joining lately: elsewhere (unloading) its checks would cost a multiply each for nothing; not
     griffith, whose limits come from the detach test of the converged pressure */
  s->certify_attach = (PetscBool)(s->certify_solve && pressure && d == s->d && (s->joined_step || s->joined_previous) && s->attach != ADH_ATTACH_GRIFFITH);
  s->attach_rnorm   = PETSC_MAX_REAL;
  PetscCall(KSPSetOperators(s->ksp, s->Kcc, s->Kcc));
  PetscCall(AdhSolverKSPSolve_Private(s, s->ksp, s->solve_loose, s->bC, s->pC));
  PetscCall(KSPGetConvergedReason(s->ksp, &reason));
  PetscCall(KSPGetIterationNumber(s->ksp, &its));
  s->step_ksp += its;
  AdhSolverReturnIfStopped_Private(s); /* stopped: the step is abandoned */
  PetscCall(VecGetArray(x, &xw));
  PetscCall(VecGetArrayRead(s->pC, &xa));
  for (k = 0; k < s->nset_local; k++) xw[s->set_local[k]] = xa[k];
  PetscCall(VecRestoreArrayRead(s->pC, &xa));
  PetscCall(VecRestoreArray(x, &xw));
  PetscCheck(reason > 0, s->comm, PETSC_ERR_NOT_CONVERGED, "The KSP solve on the contact set (%" PetscInt_FMT " points) at d = %g did not converge: %s after %" PetscInt_FMT " iterations (see -adh_ksp_rtol, -adh_ksp_max_it, -adh_ksp_monitor)", s->npoints, (double)s->d, KSPConvergedReasons[reason], its);
  PetscFunctionReturn(0);
}

/* KSPSolve; a loose solve (-adh_cascade_rtol's, or a local solve of -adh_cascade_local) with
   -adh_cascade_single applies its operators in single precision (a periodic cell, whose set goes
   straight into the transforms): its rounding, about 1e-7, lies far below its tolerance. Back to
   double whatever the solve returns: no later solve may inherit it. */
PetscErrorCode AdhSolverKSPSolve_Private(AdhSolver s, KSP ksp, PetscBool loose, Vec b, Vec x)
{
  const PetscBool single = (PetscBool)(loose && s->cascade_single && s->direct_set && s->boundary == ADH_BOUNDARY_PERIODIC);
  PetscErrorCode  ierr;

  PetscFunctionBegin;
  if (single) {
    PetscCall(MatAdhComplianceSetSinglePrecision(s->Kop, PETSC_TRUE));
    PetscCall(MatAdhComplianceSetSinglePrecision(s->Sop, PETSC_TRUE));
  }
  ierr = KSPSolve(ksp, b, x);
  if (single) {
    PetscCall(MatAdhComplianceSetSinglePrecision(s->Kop, PETSC_FALSE));
    PetscCall(MatAdhComplianceSetSinglePrecision(s->Sop, PETSC_FALSE));
  }
  PetscCall(ierr);
  PetscFunctionReturn(0);
}
