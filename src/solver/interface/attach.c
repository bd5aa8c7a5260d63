/* Attach: the points off the set that join it after a solve with no violators (penetration,
   reach, or griffith's limits), and whether an iterate has already decided the test. */
#include "solver/solverimpl.h"

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

/* Is the attach test of the exact solution already decided by the iterate x_C of a solve with
   residual rnorm? The gaps of x differ from the exact ones by K_{:,C} (x - p*), at most
   rho |x - p*|_2 <= rho ||r||_2 / lambda_min at every point (rho bounds K's row norms; the
   factor 2 as in the convergence test). Certain when every open point's gap is farther than
   that from its limit and one at least joins; then g is left as the gap of x (the attach test
   takes it). Otherwise *needed is the residual at which the points in doubt now would be
   decided, or 0 when the test is decided and lets nobody join (the solve must converge: it is
   the step's last). One compliance multiply, none when the criterion's decision at this iterate
   left its gap (crack-closure). */
PetscErrorCode AdhSolverAttachDecided_Private(AdhSolver s, Vec xC, PetscReal rnorm, PetscBool *certain, PetscReal *needed)
{
  const PetscScalar *ga, *ta;
  PetscReal          tu, rho, bound, v[2] = {PETSC_MAX_REAL, 0.0};
  PetscInt           k, counts[2] = {0, 0}; /* points in doubt, points that join */
  const PetscBool    reach = AttachReach(s);
  const PetscReal    K00   = s->eops.self_compliance;

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

/* u = K p, g = h - d + u; add every point off the set that penetrates, g < 0 (under reach,
   g < Sigma K_00). With rate (force control), the points join in the order in which they would
   touch if the set's indentation e rose from where it is (e) with the set fixed: a gap closes at
   rate_k per unit e, so point k touches at e_k = e - (limit_k - g_k) / rate_k. At most as many
   join as a quarter of the set has points (the set grows by at most 25%), the first to touch; the next force
   balance, with them, decides about the others. Adding every point that penetrates at the e of a
   small, soft set would attach points that the load never reaches. With removed > 0
   (-adh_cascade_apart, in an update that let that many points go) the points marked in s->gone
   stay off, and the set's size after the update counts without the points let go. */
PetscErrorCode AdhSolverAttach_Private(AdhSolver s, Vec rate, PetscReal e, PetscInt removed, PetscInt *added)
{
  const PetscScalar *ga, *ta, *ra = NULL, *la;
  PetscReal          tu;
  PetscInt           n, k, count = 0;
  const PetscBool    reach = AttachReach(s);
  const PetscReal    K00   = s->eops.self_compliance;
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
#define TOUCH(k) (PetscRealPart(ra[k]) > 0 ? e - (LIMIT(k) - PetscRealPart(ga[k])) / PetscRealPart(ra[k]) : PETSC_MIN_REAL)
  if (rate) {
    /* the touching depth below which at most max(npoints/4, 1) candidates lie, by bisection */
    PetscInt  total = 0, allowed = PetscMax(s->npoints / 4, 1);
    PetscReal lo = PETSC_MAX_REAL, hi = e;
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
      elimit = lo + 1e-8 * (e - efirst);
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
