/* The pieces of one step of the Pohrt-Popov algorithm, shared by the load controls (impls/control/):
   the solve on the contact set, detach (every point the detachment criterion lets go, at once:
   impls/criterion/) and attach (points off the set that penetrate, tested after a solve with no
   violators; one full multiply u = K p per attach test). */
#include "solver/solverimpl.h"

/* y = R A R^T x for an operator A on the grid in use (the window or the whole grid), R the
   restriction to n local points (their offsets in the grid's rows: the set, or a local solve's
   window, -adh_cascade_local): spread the values onto the grid, apply A, gather them back. K_CC
   uses the compliance, the preconditioner the stiffness; they share the scatter. Where the
   operators' transforms use the grid's own rows (a periodic grid), the values go straight into
   the transform: no grid vectors, no scatter. */
PetscErrorCode AdhSolverApplyRestricted_Private(AdhSolver s, Mat A, PetscInt n, const PetscInt local[], VecScatter scatter, Vec x, Vec y)
{
  PetscFunctionBegin;
  if (s->direct_set) {
    PetscCall(MatAdhComplianceMultOnSet(A, n, local, x, y));
    PetscFunctionReturn(0);
  }
  PetscCall(VecSet(s->op_in, 0.0));
  PetscCall(VecScatterBegin(scatter, x, s->op_in, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter, x, s->op_in, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(MatMult(A, s->op_in, s->op_out));
  PetscCall(VecScatterBegin(scatter, s->op_out, y, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(scatter, s->op_out, y, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

/* y = R A R^T x on the contact set. */
PetscErrorCode AdhSolverApplyOnSet_Private(AdhSolver s, Mat A, Vec x, Vec y)
{
  PetscFunctionBegin;
  PetscCall(AdhSolverApplyRestricted_Private(s, A, s->nset_local, s->set_local, s->set_scatter, x, y));
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
  s->set_version++;
  PetscCall(PetscFree(s->set_local));
  PetscCall(PetscFree(s->thrC)); /* made by the solve where the critical stress varies */
  PetscCall(PetscMalloc1(count + 1, &s->set_local));
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
  Kop = s->box ? s->box->K : s->Kmean ? s->Kmean : s->K;
  Sop = s->box ? s->box->S : s->S;
  if (Kop != s->Kop || Sop != s->Sop) {
    PetscBool kdirect = PETSC_FALSE, sdirect = PETSC_FALSE;
    PetscCall(VecDestroy(&s->op_in));
    PetscCall(VecDestroy(&s->op_out));
    /* the direct path takes the set's offsets in the grid's rows, so not on a window */
    if (!s->box) {
      PetscCall(MatAdhComplianceHasDirectLayout(Kop, &kdirect));
      PetscCall(MatAdhComplianceHasDirectLayout(Sop, &sdirect));
    }
    s->direct_set = (PetscBool)(kdirect && sdirect);
    if (!s->direct_set) PetscCall(MatCreateVecs(Kop, &s->op_in, &s->op_out));
    s->Kop = Kop;
    s->Sop = Sop;
  }
  PetscCall(ISDestroy(&s->contact_op));
  if (!s->direct_set) {
    PetscCall(AdhSolverOperatorIndices_Private(s, count, idx, opidx));
    PetscCall(ISCreateGeneral(s->comm, count, opidx, PETSC_OWN_POINTER, &s->contact_op));
  } else PetscCall(PetscFree(opidx));

  /* A lower bound on the eigenvalues of K_CC for the certified stop (zero: no certification). */
  if (Kop == s->Kmean) {
    PetscCall(MatAdhComplianceGetSetLambdaMin(s->K, 0, &s->lambda_set));
    s->lambda_set = PetscMin(s->lambda_set, s->c0);
  } else PetscCall(MatAdhComplianceGetSetLambdaMin(s->K, s->npoints, &s->lambda_set));

  PetscCall(MatDestroy(&s->Kcc));
  PetscCall(VecScatterDestroy(&s->set_scatter));
  PetscCall(VecDestroy(&s->pC));
  PetscCall(VecDestroy(&s->bC));
  /* KSP keeps work vectors of the old size; let it rebuild them for the new set. */
  if (s->ksp) PetscCall(KSPReset(s->ksp));
  if (s->npoints) {
    PetscCall(VecCreateMPI(s->comm, count, s->npoints, &s->pC));
    PetscCall(VecDuplicate(s->pC, &s->bC));
    if (!s->direct_set) PetscCall(VecScatterCreate(s->pC, NULL, s->op_in, s->contact_op, &s->set_scatter));
    PetscCall(MatCreateShell(s->comm, count, count, s->npoints, s->npoints, s, &s->Kcc));
    PetscCall(MatShellSetOperation(s->Kcc, MATOP_MULT, (void (*)(void))MatMult_Restricted));
    PetscCall(MatSetOption(s->Kcc, MAT_SPD, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

/* The critical stress on the local points: the array of a field, or (a = NULL) one value for
   all. With threshold, the allowed tension of the current stage: zero while computing a Hertz
   start. A uniform dgamma keeps no field: a grid vector fewer. */
PetscErrorCode AdhSolverGetCriticalStress_Private(AdhSolver s, PetscBool threshold, const PetscScalar **a, PetscReal *uniform)
{
  PetscFunctionBegin;
  *a       = NULL;
  *uniform = 0.0;
  if (threshold && !s->adhesive) PetscFunctionReturn(0);
  if (s->Sigma_field) PetscCall(VecGetArrayRead(s->Sigma_field, a));
  else *uniform = s->Sigma;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverRestoreCriticalStress_Private(AdhSolver s, const PetscScalar **a)
{
  PetscFunctionBegin;
  if (*a) PetscCall(VecRestoreArrayRead(s->Sigma_field, a));
  PetscFunctionReturn(0);
}

/* The gap below which an open point k joins: 0 (penetration), under reach the gap an element
   closes under its own critical tension, Sigma K_00, under griffith the limit the detach test
   left in la; false if k cannot join (it is in the set, or under reach or griffith it let go in
   this step and its limit is positive: it stays off, so the step cannot cycle; under penetration,
   or where Sigma = 0, a point that let go may come back). Under griffith it stays off only until
   the set grows larger than ever before in the step (AdhSolverAttach_Private): a contact that
   grows by many rings in one step (the jump-in at first touch) lets a point go that the next ring
   makes hold, and kept off it would stop the growth there (the JKR sphere's first touch 1.9%
   small at a_c/h 50, 2.4% at 100, against 0.5% and 0.6% when it may come back). The step still
   ends: the largest set can grow only so often. Under reach the same costs 24-37% more set
   updates on a rough cell (./run bench rough --n 256) for about 1% at first touch, and the
   paper's loop stays as it was. */
static inline PetscBool AttachLimit(AdhSolver s, PetscBool reach, PetscReal K00, const PetscScalar *ta, PetscReal tu, const PetscScalar *la, PetscInt k, PetscReal *limit)
{
  *limit = la ? PetscRealPart(la[k]) : reach ? ADH_SIGMA_AT(ta, tu, k) * K00 : 0.0;
  return (PetscBool)(!s->in_set[k] && !(reach && s->left[k] && *limit > 0));
}

/* reach, or griffith (which is reach away from the contact's edge), with adhesion */
static inline PetscBool AttachReach(AdhSolver s)
{
  return (PetscBool)((s->attach == ADH_ATTACH_REACH || s->attach == ADH_ATTACH_GRIFFITH) && s->adhesive);
}

/* griffith's limits, which the detach test just before left for the current p (NULL: not griffith) */
static PetscErrorCode GetGriffithLimits(AdhSolver s, const PetscScalar **la)
{
  PetscFunctionBegin;
  *la = NULL;
  if (s->attach != ADH_ATTACH_GRIFFITH || !AdhSolverIsAdhesive_Private(s)) PetscFunctionReturn(0);
  PetscCheck(s->attach_limit && s->attach_limit_current, s->comm, PETSC_ERR_PLIB, "-adh_attach griffith: the attach test without the limits of the current pressure");
  s->attach_limit_current = PETSC_FALSE;
  PetscCall(VecGetArrayRead(s->attach_limit, la));
  PetscFunctionReturn(0);
}

static PetscErrorCode RestoreGriffithLimits(AdhSolver s, const PetscScalar **la)
{
  PetscFunctionBegin;
  if (*la) PetscCall(VecRestoreArrayRead(s->attach_limit, la));
  PetscFunctionReturn(0);
}

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

/* Is the attach test of the exact solution already decided by the iterate x_C of a solve with
   residual rnorm? The gaps of x differ from the exact ones by K_{:,C} (x - p*), at most
   rho |x - p*|_2 <= rho ||r||_2 / lambda_min at every point (rho bounds K's row norms; the
   factor 2 as in the convergence test). Certain when every open point's gap is farther than
   that from its limit and one at least joins; then g is left as the gap of x (the attach test
   takes it). Otherwise *needed is the residual at which the points in doubt now would be
   decided, or 0 when the test is decided and lets nobody join (the solve must converge: it is
   the step's last). One compliance multiply, none when the criterion's decision at this iterate
   left its gap (crack-closure). */
static PetscErrorCode AttachDecided(AdhSolver s, Vec xC, PetscReal rnorm, PetscBool *certain, PetscReal *needed)
{
  const PetscScalar *ga, *ta;
  PetscReal          tu, rho, bound, v[2] = {PETSC_MAX_REAL, 0.0};
  PetscInt           k, counts[2] = {0, 0}; /* points in doubt, points that join */
  const PetscBool    reach = AttachReach(s);
  const PetscReal    K00   = AdhLoveCoefficient(0.0, 0.0, s->grid->hx, s->grid->hy, s->Estar);

  PetscFunctionBegin;
  /* the criterion's decision at this iterate may have left p and its gap (crack-closure) */
  if (!s->gap_current) {
    PetscCall(AdhSolverSetIterate_Private(s, xC));
    PetscCall(AdhSolverComputeGap_Private(s));
  }
  PetscCall(MatAdhComplianceGetRowNormBound(s->K, &rho));
  bound = 2.0 * rnorm * rho / s->lambda_set;
  PetscCall(VecGetArrayRead(s->g, &ga));
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_FALSE, &ta, &tu));
  for (k = 0; k < s->nlocal; k++) {
    PetscReal limit, margin;
    if (!AttachLimit(s, reach, K00, ta, tu, NULL, k, &limit)) continue;
    margin = PetscRealPart(ga[k]) - limit;
    if (PetscAbsReal(margin) <= bound) {
      counts[0]++;
      v[0] = PetscMin(v[0], PetscAbsReal(margin));
    } else if (margin < 0) counts[1]++;
  }
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &ta));
  PetscCall(VecRestoreArrayRead(s->g, &ga));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, s->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, v, 1, MPIU_REAL, MPIU_MIN, s->comm));
  *certain = (PetscBool)(!counts[0] && counts[1]);
  *needed  = counts[0] ? v[0] * s->lambda_set / (2.0 * rho) : 0.0;
  s->gap_current = *certain;
  PetscFunctionReturn(0);
}

/* KSP convergence test: the full tolerance ||r|| <= max(rtol ||b||, atol), or, for a solve whose
   only job is to decide the next update of the set, a certified early stop. Since every eigenvalue
   of K_CC is at least lambda_min (Cauchy interlacing), |p_k - p*_k| <= perr = ||r||_2 / lambda_min;
   once the criterion's decide (AdhCriterionOps) says that within that bound some points let go
   and every point's decision is the exact solution's, the solve can stop. When it says that none
   lets go, the attach test may be decided in the same way (AttachDecided). The factor 2 covers
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
      PetscCall(AttachDecided(s, x, rnorm, &certain, &needed));
      if (certain) {
        *reason             = KSP_CONVERGED_ATOL; /* marked by certified_attach */
        s->certified_attach = PETSC_TRUE;
      } else s->attach_rnorm = needed ? PetscMin(0.5 * rnorm, needed) : -1.0;
    }
  }
  PetscFunctionReturn(0);
}

/* x_C from K_CC x_C = (shift - prof)_C (prof NULL: zero), warm-started from x, which is left as it
   is off the set. With certify, the solve may stop as soon as the points to detach are certain
   (x must then be the pressure). */
PetscErrorCode AdhSolverSolveOnSet_Private(AdhSolver s, Vec x, PetscReal shift, Vec prof, PetscBool certify)
{
  KSPConvergedReason reason;
  PetscInt           its, k;
  const PetscScalar *xa, *ha = NULL, *ta = NULL;
  PetscReal          tu;
  PetscBool          field;
  PetscScalar       *xc, *bc, *xw;

  PetscFunctionBegin;
  s->certified_stop   = PETSC_FALSE;
  s->certified_attach = PETSC_FALSE;
  if (!s->npoints) PetscFunctionReturn(0);
  PetscCheck(!(s->boundary == ADH_BOUNDARY_PERIODIC && s->lambda_set <= 0), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "The whole periodic cell is in contact at d = %g: under displacement control the force is undetermined there (d must stay below the mean of the indenter profile, %g); use -adh_control force", (double)s->d, (double)s->mean_h);
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
    bc[k]         = shift - (ha ? ha[m] : 0.0);
    if (field) s->thrC[k] = ADH_SIGMA_AT(ta, tu, m);
  }
  PetscCall(VecRestoreArrayWrite(s->bC, &bc));
  PetscCall(VecRestoreArrayWrite(s->pC, &xc));
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &ta));
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
  s->certify_attach = (PetscBool)(s->certify_solve && prof == s->h && shift == s->d && x == s->p && (s->joined_step || s->joined_previous) && s->attach != ADH_ATTACH_GRIFFITH);
  s->attach_rnorm   = PETSC_MAX_REAL;
  PetscCall(KSPSetOperators(s->ksp, s->Kcc, s->Kcc));
  PetscCall(AdhSolverKSPSolve_Private(s, s->ksp, s->solve_loose, s->bC, s->pC));
  PetscCall(KSPGetConvergedReason(s->ksp, &reason));
  PetscCall(KSPGetIterationNumber(s->ksp, &its));
  s->step_ksp += its;
  if (s->stoppable && s->stop_signal) PetscFunctionReturn(PETSC_ERR_SIG); /* stopped: the step is abandoned */
  PetscCall(VecGetArray(x, &xw));
  PetscCall(VecGetArrayRead(s->pC, &xa));
  for (k = 0; k < s->nset_local; k++) xw[s->set_local[k]] = xa[k];
  PetscCall(VecRestoreArrayRead(s->pC, &xa));
  PetscCall(VecRestoreArray(x, &xw));
  PetscCheck(reason > 0, s->comm, PETSC_ERR_NOT_CONVERGED, "The KSP solve on the contact set (%" PetscInt_FMT " points) at d = %g did not converge: %s after %" PetscInt_FMT " iterations (see -adh_ksp_rtol, -adh_ksp_max_it, -adh_ksp_monitor)", s->npoints, (double)s->d, KSPConvergedReasons[reason], its);
  PetscFunctionReturn(0);
}

/* u = K p, g = h - d + u; add every point off the set that penetrates, g < 0 (under reach,
   g < Sigma K_00). With rate (force control), the points join in the order in which they would
   touch if the set's indentation e rose from where it was with the set fixed: a gap closes at
   rate_k per unit e, so point k touches at e_k = e - (limit_k - g_k) / rate_k. At most as many
   join as a quarter of the set has points (the set grows by at most 25%), the first to touch; the next force
   balance, with them, decides about the others. Adding every point that penetrates at the e of a
   small, soft set would attach points that the load never reaches. With removed > 0
   (-adh_cascade_apart, in an update that let that many points go) the points marked in s->gone
   stay off, and the set's size after the update counts without the points let go. */
PetscErrorCode AdhSolverAttach_Private(AdhSolver s, Vec rate, PetscInt removed, PetscInt *added)
{
  const PetscScalar *ga, *ta, *ra = NULL, *la;
  PetscReal          tu;
  PetscInt           n, k, count = 0;
  const PetscBool    reach = AttachReach(s);
  const PetscReal    K00   = AdhLoveCoefficient(0.0, 0.0, s->grid->hx, s->grid->hy, s->Estar);
  PetscReal          elimit = PETSC_MAX_REAL, efirst, limit;

  PetscFunctionBegin;
  /* the detach test that came just before may have computed this very gap (crack-closure) */
  if (!s->gap_current) PetscCall(AdhSolverComputeGap_Private(s));
  s->gap_current = PETSC_FALSE;
  PetscCall(VecGetLocalSize(s->g, &n));
  PetscCall(VecGetArrayRead(s->g, &ga));
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_FALSE, &ta, &tu));
  if (rate) PetscCall(VecGetArrayRead(rate, &ra));
  PetscCall(GetGriffithLimits(s, &la));
#define LIMIT(k) (AttachLimit(s, reach, K00, ta, tu, la, k, &limit) ? limit : PETSC_MIN_REAL)
#define CANDIDATE(k) (PetscRealPart(ga[k]) < LIMIT(k))
#define TOUCH(k) (PetscRealPart(ra[k]) > 0 ? s->e - (LIMIT(k) - PetscRealPart(ga[k])) / PetscRealPart(ra[k]) : PETSC_MIN_REAL)
  if (rate) {
    /* the touching depth below which at most max(npoints/4, 1) candidates lie, by bisection */
    PetscInt  total = 0, allowed = PetscMax(s->npoints / 4, 1);
    PetscReal lo = PETSC_MAX_REAL, hi = s->e;
    for (k = 0; k < n; k++)
      if (CANDIDATE(k)) {
        lo = PetscMin(lo, TOUCH(k));
        total++;
      }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &total, 1, MPIU_INT, MPI_SUM, s->comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &lo, 1, MPIU_REAL, MPIU_MIN, s->comm));
    efirst = lo;
    if (total > allowed && lo > PETSC_MIN_REAL) {
      for (PetscInt it = 0; it < 60; it++) {
        const PetscReal mid = 0.5 * (lo + hi);
        PetscInt        below = 0;
        for (k = 0; k < n; k++)
          if (CANDIDATE(k) && TOUCH(k) <= mid) below++;
        PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &below, 1, MPIU_INT, MPI_SUM, s->comm));
        if (below > allowed) hi = mid;
        else lo = mid;
      }
      /* at least the first point to touch; points that touch together (symmetric profiles) join
         together, whatever the rounding, so the set does not depend on the number of ranks */
      elimit = lo + 1e-8 * (s->e - efirst);
    }
  }
  for (k = 0; k < n; k++)
    if (CANDIDATE(k) && (!rate || TOUCH(k) <= elimit) && !(removed && s->gone[k])) {
      s->in_set[k] = 1;
      count++;
    }
#undef LIMIT
#undef CANDIDATE
#undef TOUCH
  if (rate) PetscCall(VecRestoreArrayRead(rate, &ra));
  PetscCall(RestoreGriffithLimits(s, &la));
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &ta));
  PetscCall(VecRestoreArrayRead(s->g, &ga));
  PetscCall(MPIU_Allreduce(&count, added, 1, MPIU_INT, MPI_SUM, s->comm));
  if (s->attach == ADH_ATTACH_GRIFFITH && s->npoints - removed + *added > s->step_largest) { /* the points that let go may come back (AttachLimit) */
    s->step_largest = s->npoints - removed + *added;
    PetscCall(PetscArrayzero(s->left, s->nlocal));
  }
  PetscFunctionReturn(0);
}

/* Nothing in contact: an empty set, no pressure. */
PetscErrorCode AdhSolverClearContact_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(PetscArrayzero(s->in_set, s->nlocal));
  PetscCall(VecSet(s->p, 0.0));
  if (s->xunit) PetscCall(VecSet(s->xunit, 0.0));
  s->pulled_off = PETSC_FALSE;
  PetscCall(AdhSolverRebuildSet_Private(s));
  PetscFunctionReturn(0);
}

/* g = (h - d) + u, u = K p, for the current state (u itself is not kept: see GetDisplacement). */
PetscErrorCode AdhSolverComputeGap_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(MatMult(s->K, s->p, s->g));
  PetscCall(AdhSolverGapFromDisplacement_Private(s, s->g));
  PetscFunctionReturn(0);
}

/* g = (h - d) + u from the displacement u (which may be g itself): the one sum every gap and
   opening is taken with, so that they agree to the last bit whichever computed them. */
PetscErrorCode AdhSolverGapFromDisplacement_Private(AdhSolver s, Vec u)
{
  const PetscScalar *ha;
  PetscScalar       *ga;

  PetscFunctionBegin;
  if (u != s->g) PetscCall(VecCopy(u, s->g));
  PetscCall(VecGetArrayRead(s->h, &ha));
  PetscCall(VecGetArray(s->g, &ga));
  for (PetscInt k = 0; k < s->nlocal; k++) ga[k] = (ha[k] - s->d) + ga[k];
  PetscCall(VecRestoreArray(s->g, &ga));
  PetscCall(VecRestoreArrayRead(s->h, &ha));
  PetscFunctionReturn(0);
}

/* The displacement u = g - h + d of the current state, made when asked for: a grid vector fewer
   for runs that never look at it. */
PetscErrorCode AdhSolverGetDisplacement_Private(AdhSolver s, Vec *u)
{
  PetscFunctionBegin;
  if (!s->u) {
    PetscCall(VecDuplicate(s->h, &s->u));
    PetscCall(PetscObjectSetName((PetscObject)s->u, "displacement"));
  }
  PetscCall(VecWAXPY(s->u, -1.0, s->h, s->g));
  PetscCall(VecShift(s->u, s->d));
  *u = s->u;
  PetscFunctionReturn(0);
}

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
