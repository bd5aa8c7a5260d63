/*MC
   ADHCRITERIONPOHRTPOPOV - "pohrt-popov", the paper's rule: a point of the contact set lets go when p < -Sigma

   Sigma = sqrt(hx hy E* dgamma / chi) is the tension at which the elastic energy of one isolated element pays for its
   surface energy.

   Options Database Keys:
+  -adh_criterion pohrt-popov - selects this criterion
.  -adh_critical_stress <S>   - a fixed critical stress replacing the mesh-dependent Sigma (for studies of the criterion)
-  -adh_certify <true>        - the certified early stop of intermediate solves

   Level: beginner

   Notes:
   Calibrated on one element, it lets go late on straight edges: along a grid axis as if dgamma were 1.85 times larger,
   at 45 degrees 1.34 times. With dgamma = 0 it reduces to non-adhesive contact: p < 0 lets go.

   Its certified early stop is decided by p alone: every point whose margin |p + Sigma| exceeds the error bound of the
   iterate lets go (or stays) as it would at the exact solution; cheap, it is checked at every iteration. The state's
   detach ratio is max(-p/Sigma) on the set. With this criterion the attach rule is reach by default (griffith is
   refused), and -adh_cascade_local is 0, the paper's exact cascade, by default.

.seealso: `AdhSolverSetCriterionType()`, `ADHCRITERIONCRACKCLOSURE`, `AdhSolverGetCriticalStress()`, `AdhCriticalStress()`
M*/
#include "solver/solverimpl.h"

/* With detach, every point with p < -Sigma leaves; otherwise *ratio = max(-p/Sigma) on the set. */
static PetscErrorCode Evaluate_PohrtPopov(AdhSolver s, PetscBool detach, PetscInt *removed, PetscReal *ratio)
{
  PetscScalar       *pa, *xa = NULL;
  const PetscScalar *ta;
  PetscReal          tu, r = 0.0;
  PetscInt           k, count = 0;

  PetscFunctionBegin;
  PetscCall(VecGetArray(s->p, &pa));
  if (detach && s->set_response) PetscCall(VecGetArray(s->set_response, &xa));
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_TRUE, &ta, &tu));
  for (k = 0; k < s->nlocal; k++) {
    const PetscReal p = PetscRealPart(pa[k]), Sigma = ADH_SIGMA_AT(ta, tu, k);
    if (!s->in_set[k]) continue;
    if (detach && p < -Sigma) {
      AdhSolverRemovePoint_Private(s, k, pa, xa);
      count++;
    } else if (p < 0 && Sigma > 0) r = PetscMax(r, -p / Sigma);
  }
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &ta));
  if (xa) PetscCall(VecRestoreArray(s->set_response, &xa));
  PetscCall(VecRestoreArray(s->p, &pa));
  if (removed) PetscCall(MPIU_Allreduce(&count, removed, 1, MPIU_INT, MPI_SUM, s->comm));
  if (ratio) PetscCall(MPIU_Allreduce(&r, ratio, 1, MPIU_REAL, MPIU_MAX, s->comm));
  PetscFunctionReturn(0);
}

/* Decided by p alone: every point whose margin |p + Sigma| exceeds perr lets go (or stays) as it
   would at the exact solution. Cheap: checked at every iteration. */
static PetscErrorCode Decide_PohrtPopov(AdhSolver s, Vec xC, PetscReal perr, AdhDetachDecision *decision, PetscReal *needed)
{
  const PetscScalar *xa;
  PetscInt           n, k;
  PetscReal          v[2] = {-PETSC_MAX_REAL, 0.0};

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(xC, &n));
  PetscCall(VecGetArrayRead(xC, &xa));
  for (k = 0; k < n; k++) {
    const PetscReal margin = PetscRealPart(xa[k]) + ADH_SIGMA_AT(s->threshold_local, s->threshold_uniform, k);
    v[0]                   = PetscMax(v[0], -PetscAbsReal(margin)); /* max of -|margin| = -min |margin| */
    if (margin < 0) v[1] = 1.0;
  }
  PetscCall(VecRestoreArrayRead(xC, &xa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, v, 2, MPIU_REAL, MPIU_MAX, s->comm));
  *decision = -v[0] > perr ? (v[1] > 0 ? ADH_DETACH_SOME : ADH_DETACH_NONE) : ADH_DETACH_IN_DOUBT;
  *needed   = PETSC_MAX_REAL;
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhCriterionCreate_PohrtPopov(AdhSolver s)
{
  PetscFunctionBegin;
  s->crops.attach   = ADH_ATTACH_REACH; /* the gap an element closes under its own critical tension */
  s->crops.evaluate = Evaluate_PohrtPopov;
  s->crops.decide   = Decide_PohrtPopov;
  PetscFunctionReturn(0);
}
