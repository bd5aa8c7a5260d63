/* One indentation step of the Pohrt-Popov algorithm (DESIGN.md section 4):
     solve K_CC p_C = (d - h)_C with CG, detach every point with p < -Sigma, and once none is
     left attach every point off the set that penetrates (g < 0); repeat until C is stable.
   Detaching all violators at once is the paper's rule. Attach is tested only after a solve with
   no violators, which costs one full multiply u = K p per attach test. */
#include "solverimpl.h"

/* y = R A R^T x for an operator A on the grid in use (the window or the whole grid): spread the
   set values onto it, apply A, gather them back. K_CC uses the compliance, the preconditioner
   the stiffness; they share the scatter. */
PetscErrorCode AdhSolverApplyOnSet_Private(AdhSolver s, Mat A, Vec x, Vec y)
{
  PetscFunctionBegin;
  PetscCall(VecSet(s->op_in, 0.0));
  PetscCall(VecScatterBegin(s->set_scatter, x, s->op_in, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(s->set_scatter, x, s->op_in, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(MatMult(A, s->op_in, s->op_out));
  PetscCall(VecScatterBegin(s->set_scatter, s->op_out, y, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(s->set_scatter, s->op_out, y, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

static PetscErrorCode MatMult_Restricted(Mat Kcc, Vec x, Vec y)
{
  AdhSolver s;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(Kcc, &s));
  PetscCall(AdhSolverApplyOnSet_Private(s, s->Kop, x, y));
  PetscFunctionReturn(0);
}

/* The IS of the set (global indices of the local points in it), K restricted to it (on the
   bounding-box window when there is one), and the scatter between the two. */
PetscErrorCode AdhSolverRebuildSet_Private(AdhSolver s)
{
  PetscInt nlocal, rstart, count = 0, k, *idx, *opidx;
  Mat      Kop, Sop;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(s->p, &nlocal));
  PetscCall(VecGetOwnershipRange(s->p, &rstart, NULL));
  for (k = 0; k < nlocal; k++) count += s->in_set[k] ? 1 : 0;
  PetscCall(PetscMalloc1(count, &idx));
  PetscCall(PetscMalloc1(count, &opidx));
  PetscCall(PetscFree(s->set_local));
  PetscCall(PetscFree(s->thrC));
  PetscCall(PetscMalloc1(count + 1, &s->set_local));
  PetscCall(PetscMalloc1(count + 1, &s->thrC));
  for (k = 0, count = 0; k < nlocal; k++)
    if (s->in_set[k]) {
      s->set_local[count] = k;
      idx[count++]        = rstart + k;
    }
  s->nset_local = count;
  PetscCall(ISDestroy(&s->contact));
  PetscCall(ISCreateGeneral(s->comm, count, idx, PETSC_OWN_POINTER, &s->contact));
  PetscCall(PetscObjectSetName((PetscObject)s->contact, "contact_set"));
  PetscCall(ISGetSize(s->contact, &s->npoints));

  PetscCall(AdhSolverSelectOperator_Private(s));
  PetscCall(AdhSolverOperatorIndices_Private(s, count, idx, opidx));
  PetscCall(ISDestroy(&s->contact_op));
  PetscCall(ISCreateGeneral(s->comm, count, opidx, PETSC_OWN_POINTER, &s->contact_op));
  Kop = s->box ? s->box->K : s->K;
  Sop = s->box ? s->box->S : s->S;
  if (Kop != s->Kop) {
    PetscCall(VecDestroy(&s->op_in));
    PetscCall(VecDestroy(&s->op_out));
    PetscCall(MatCreateVecs(Kop, &s->op_in, &s->op_out));
    s->Kop = Kop;
    s->Sop = Sop;
  }

  PetscCall(MatDestroy(&s->Kcc));
  PetscCall(VecScatterDestroy(&s->set_scatter));
  PetscCall(VecDestroy(&s->pC));
  PetscCall(VecDestroy(&s->bC));
  /* KSP keeps work vectors of the old size; let it rebuild them for the new set. */
  if (s->ksp) PetscCall(KSPReset(s->ksp));
  if (s->npoints) {
    PetscCall(VecCreateMPI(s->comm, count, s->npoints, &s->pC));
    PetscCall(VecDuplicate(s->pC, &s->bC));
    PetscCall(VecScatterCreate(s->pC, NULL, s->op_in, s->contact_op, &s->set_scatter));
    PetscCall(MatCreateShell(s->comm, count, count, s->npoints, s->npoints, s, &s->Kcc));
    PetscCall(MatShellSetOperation(s->Kcc, MATOP_MULT, (void (*)(void))MatMult_Restricted));
    PetscCall(MatSetOption(s->Kcc, MAT_SPD, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

/* The allowed tension: Sigma while adhesive, zero while computing a Hertz start. */
static Vec Threshold(AdhSolver s)
{
  return s->adhesive ? s->Sigma_field : s->zero;
}

/* KSP convergence test: the full tolerance ||r|| <= max(rtol ||b||, atol), or, for a solve whose
   only job is to find the points to detach, a certified early stop. Since every eigenvalue of K_CC
   is at least lambda_min (Cauchy interlacing), |p_k - p*_k| <= ||r||_2 / lambda_min; once every
   point's margin |p_k + Sigma_k| exceeds that bound and some point violates, the set of points to
   detach is the exact solution's and the solve can stop. The factor 2 covers the difference
   between CG's recursive residual and the true one. */
PETSC_INTERN PetscErrorCode AdhConvergedCertified_Private(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason *reason, void *ctx)
{
  AdhSolver          s = (AdhSolver)ctx;
  PetscReal          rtol, atol, dtol;
  PetscInt           maxits;

  PetscFunctionBegin;
  *reason = KSP_CONVERGED_ITERATING;
  PetscCall(KSPGetTolerances(ksp, &rtol, &atol, &dtol, &maxits));
  if (PetscIsInfOrNanReal(rnorm)) {
    *reason = KSP_DIVERGED_NANORINF;
    PetscFunctionReturn(0);
  }
  if (rnorm <= PetscMax(rtol * s->bnorm, atol)) {
    *reason = KSP_CONVERGED_RTOL;
    PetscFunctionReturn(0);
  }
  if (s->certify && it > 0) {
    Vec                x;
    const PetscScalar *xa;
    PetscInt           n, k;
    PetscReal          bound = 2.0 * rnorm / s->lambda_min, v[2] = {-PETSC_MAX_REAL, 0.0};

    PetscCall(KSPBuildSolution(ksp, NULL, &x));
    PetscCall(VecGetLocalSize(x, &n));
    PetscCall(VecGetArrayRead(x, &xa));
    for (k = 0; k < n; k++) {
      const PetscReal margin = PetscRealPart(xa[k]) + PetscRealPart(s->threshold_local[k]);
      v[0]                   = PetscMax(v[0], -PetscAbsReal(margin)); /* max of -|margin| = -min |margin| */
      if (margin < 0) v[1] = 1.0;
    }
    PetscCall(VecRestoreArrayRead(x, &xa));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, v, 2, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)ksp)));
    if (-v[0] > bound && v[1] > 0) {
      *reason           = KSP_CONVERGED_ATOL; /* marked by certified_stop */
      s->certified_stop = PETSC_TRUE;
    }
  }
  PetscFunctionReturn(0);
}

/* p_C from K_CC p_C = (d - h)_C, warm-started from the current p; p = 0 off the set. */
static PetscErrorCode SolveOnSet(AdhSolver s)
{
  KSPConvergedReason reason;
  PetscInt           its, k;
  const PetscScalar *pa, *ha, *ta;
  PetscScalar       *pc, *bc;
  PetscScalar       *pw;

  PetscFunctionBegin;
  s->certified_stop = PETSC_FALSE;
  if (!s->npoints) PetscFunctionReturn(0);
  /* The set's points are local to each rank, so restriction is a local gather. */
  PetscCall(VecGetArrayRead(s->p, &pa));
  PetscCall(VecGetArrayRead(s->h, &ha));
  PetscCall(VecGetArrayRead(Threshold(s), &ta));
  PetscCall(VecGetArrayWrite(s->pC, &pc));
  PetscCall(VecGetArrayWrite(s->bC, &bc));
  for (k = 0; k < s->nset_local; k++) {
    const PetscInt m = s->set_local[k];
    pc[k]         = pa[m];
    bc[k]         = s->d - ha[m];
    s->thrC[k]    = ta[m];
  }
  PetscCall(VecRestoreArrayWrite(s->bC, &bc));
  PetscCall(VecRestoreArrayWrite(s->pC, &pc));
  PetscCall(VecRestoreArrayRead(Threshold(s), &ta));
  PetscCall(VecRestoreArrayRead(s->h, &ha));
  PetscCall(VecRestoreArrayRead(s->p, &pa));
  PetscCall(VecNorm(s->bC, NORM_2, &s->bnorm));
  s->threshold_local = s->thrC;
  PetscCall(KSPSetOperators(s->ksp, s->Kcc, s->Kcc));
  PetscCall(KSPSolve(s->ksp, s->bC, s->pC));
  PetscCall(KSPGetConvergedReason(s->ksp, &reason));
  PetscCall(KSPGetIterationNumber(s->ksp, &its));
  s->step_ksp += its;
  PetscCall(VecGetArray(s->p, &pw));
  PetscCall(VecGetArrayRead(s->pC, &pa));
  for (k = 0; k < s->nset_local; k++) pw[s->set_local[k]] = pa[k];
  PetscCall(VecRestoreArrayRead(s->pC, &pa));
  PetscCall(VecRestoreArray(s->p, &pw));
  PetscCheck(reason > 0, s->comm, PETSC_ERR_NOT_CONVERGED, "The KSP solve on the contact set (%" PetscInt_FMT " points) at d = %g did not converge: %s after %" PetscInt_FMT " iterations (see -adh_ksp_rtol, -adh_ksp_max_it, -adh_ksp_monitor)", s->npoints, (double)s->d, KSPConvergedReasons[reason], its);
  PetscFunctionReturn(0);
}

/* Remove every point of the set whose tension exceeds its critical stress, p < -Sigma. */
static PetscErrorCode Detach(AdhSolver s, PetscInt *removed)
{
  PetscScalar       *pa;
  const PetscScalar *ta;
  PetscInt           n, k, count = 0;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(s->p, &n));
  PetscCall(VecGetArray(s->p, &pa));
  PetscCall(VecGetArrayRead(Threshold(s), &ta));
  for (k = 0; k < n; k++)
    if (s->in_set[k] && PetscRealPart(pa[k]) < -PetscRealPart(ta[k])) {
      s->in_set[k] = 0;
      s->left[k]   = 1;
      pa[k]        = 0.0;
      count++;
    }
  PetscCall(VecRestoreArrayRead(Threshold(s), &ta));
  PetscCall(VecRestoreArray(s->p, &pa));
  PetscCall(MPIU_Allreduce(&count, removed, 1, MPIU_INT, MPI_SUM, s->comm));
  PetscFunctionReturn(0);
}

/* u = K p, g = h - d + u; add every point off the set that penetrates, g < 0. */
static PetscErrorCode Attach(AdhSolver s, PetscInt *added)
{
  const PetscScalar *ga, *ta;
  PetscInt           n, k, count = 0;
  const PetscBool    reach = s->attach == ADH_ATTACH_REACH && s->adhesive;
  /* reach: the gap an element closes under its own critical tension, Sigma K_00. */
  const PetscReal    K00 = AdhLoveCoefficient(0.0, 0.0, s->grid->hx, s->grid->hy, s->Estar);

  PetscFunctionBegin;
  PetscCall(MatMult(s->K, s->p, s->u));
  PetscCall(VecWAXPY(s->g, 1.0, s->h, s->u));
  PetscCall(VecShift(s->g, -s->d));
  PetscCall(VecGetLocalSize(s->g, &n));
  PetscCall(VecGetArrayRead(s->g, &ga));
  PetscCall(VecGetArrayRead(s->Sigma_field, &ta));
  for (k = 0; k < n; k++) {
    const PetscReal limit = reach ? PetscRealPart(ta[k]) * K00 : 0.0;
    /* Under reach, a point that let go in this step stays off, so the step cannot cycle. */
    if (!s->in_set[k] && PetscRealPart(ga[k]) < limit && !(reach && s->left[k])) {
      s->in_set[k] = 1;
      count++;
    }
  }
  PetscCall(VecRestoreArrayRead(s->Sigma_field, &ta));
  PetscCall(VecRestoreArrayRead(s->g, &ga));
  PetscCall(MPIU_Allreduce(&count, added, 1, MPIU_INT, MPI_SUM, s->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverStep(AdhSolver s, PetscReal d)
{
  PetscInt outer, removed, added, mults0, mults1;

  PetscFunctionBegin;
  PetscCall(AdhSolverSetUp(s));
  PetscCall(PetscLogEventBegin(ADH_Solve, 0, 0, 0, 0));
  PetscCall(AdhSolverMultCount_Private(s, &mults0));
  s->d          = d;
  PetscCall(PetscArrayzero(s->left, s->nlocal));
  s->step_outer = 0;
  s->step_ksp   = 0;
  for (outer = 1;; outer++) {
    PetscCheck(outer <= s->max_outer, s->comm, PETSC_ERR_NOT_CONVERGED, "No stable contact set at d = %g after %" PetscInt_FMT " set updates (-adh_max_outer)", (double)d, s->max_outer);
    PetscCall(SolveOnSet(s));
    PetscCall(PetscLogEventBegin(ADH_SetUpdate, 0, 0, 0, 0));
    PetscCall(Detach(s, &removed));
    PetscCheck(removed || !s->certified_stop, s->comm, PETSC_ERR_PLIB, "Certified early stop without a point to detach");
    added = 0;
    if (!removed) PetscCall(Attach(s, &added));
    if (removed || added) PetscCall(AdhSolverRebuildSet_Private(s));
    PetscCall(PetscLogEventEnd(ADH_SetUpdate, 0, 0, 0, 0));
    if (!removed && !added) break;
  }
  s->step_outer = outer;
  PetscCall(AdhSolverMultCount_Private(s, &mults1));
  s->step_mults = mults1 - mults0;
  PetscCall(PetscLogEventEnd(ADH_Solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
