/*MC
   ADHPREDICTORPOLONSKYKEER - "polonsky-keer": Polonsky & Keer's conjugate gradient (Wear 1999) guesses the contact set
   of a step without adhesion, which the set-update loop then certifies

   It works with the force constraint (preconditioned with the body's stiffness (E*|q|/2 on a half-space), -adh_predictor_fourier) or at
   fixed d.

   Options Database Keys:
+  -adh_predictor polonsky-keer    - selects it (the default on a periodic cell)
.  -adh_predictor_rtol <1e-8>      - stop when an iteration changes the pressure by less than this of its 1-norm
.  -adh_predictor_max_it <10000>   - or after this many iterations
-  -adh_predictor_fourier <true>   - under force control, precondition with the body's stiffness (E*|q|/2 on a half-space)

   Level: intermediate

   Notes:
   After -adh_predictor_max_it iterations the loop goes on from where it got. Should it lose the whole set, the loop
   starts from nothing in contact and still ends in the same state: the predictor changes the cost, not the answer.

.seealso: `AdhSolverSetPredictorType()`, `ADHPREDICTORNONE`
M*/
#include "solver/solverimpl.h"

/* The pressure p >= 0 with the gap g = K p + h - d >= 0 closed where p > 0, on the whole grid,
   carrying F (force: d is the gap's mean on the set, and s->d is set to it) or at d; the contact
   set is p > 0. s->p is the start (the previous state's pressure) and the result.

   The displacement u = K p follows p along the search direction (u -= tau K t) at no cost. Where
   an iteration also moves points off or onto the set, u misses that change; u is computed anew
   (one more compliance application) once the changes missed amount to more than 1e-7 of the
   pressure's 1-norm, and always before the iteration may stop. The loops over the grid are
   fused, and the force constraint's rescaling of p and u is applied in the next pass over them:
   at 1024^2 the passes over memory cost as much as the transforms. */
typedef struct {
  PetscReal rtol;    /* -adh_predictor_rtol: stop when an iteration changes p by less than this of its 1-norm */
  PetscInt  max_it;  /* -adh_predictor_max_it */
  PetscBool fourier; /* -adh_predictor_fourier: under force control, precondition with the body's stiffness (E*|q|/2 on a half-space) */
  PetscInt  its;     /* iterations so far, over all steps */
} PolonskyKeerData;

/* The predictor's work vectors, at every way out of it. */
static PetscErrorCode DestroyWork(Vec *u, Vec *g, Vec *t, Vec *r, Vec *z)
{
  PetscFunctionBegin;
  PetscCall(VecDestroy(u));
  PetscCall(VecDestroy(g));
  PetscCall(VecDestroy(t));
  PetscCall(VecDestroy(r));
  PetscCall(VecDestroy(z));
  PetscFunctionReturn(0);
}

static PetscErrorCode PolonskyKeer(AdhSolver s, PetscBool force, PetscReal target)
{
  PolonskyKeerData  *pk = (PolonskyKeerData *)s->pops.data;
  const PetscReal    F = force ? target : 0.0, d = force ? 0.0 : target;
  const PetscReal    A = s->grid->hx * s->grid->hy, N = (PetscReal)s->grid->Nx * s->grid->Ny;
  Vec                p = s->p, u, g, t, r, z = NULL;
  const PetscScalar *ha, *ra;
  PetscScalar       *pa, *ua, *ga, *ta, sum;
  PetscBool          have_u = PETSC_FALSE; /* u = K p already */
  PetscReal          Gold = 1.0, delta = 0.0, gbar = 0.0, change = PETSC_MAX_REAL, nc = 0.0, missed = 0.0, scale = 1.0;
  PetscInt           it, n, k, updates = 0;
  PetscBool          stop = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(ADH_Predict, 0, 0, 0, 0));
  PetscCall(VecDuplicate(p, &u));
  PetscCall(VecDuplicate(p, &g));
  PetscCall(VecDuplicate(p, &t));
  PetscCall(VecDuplicate(p, &r));
  /* at fixed d on a periodic cell the preconditioned direction can be nearly uniform over a large
     set, which K hardly feels (it has no mean mode): the step then empties the set (seen at
     1024^2). With the force constraint that mode is projected out. */
  if (pk->fourier && force) PetscCall(VecDuplicate(p, &z));
  PetscCall(VecGetLocalSize(p, &n));
  /* start from the previous pressure (scaled to F), or from a uniform one (force), or from the
     overlap w = max(0, d - h) scaled to the least energy along it, c = w.(d - h) / w.K w
     (indentation; on a periodic cell a pressure too large would push the open surface into
     overlap everywhere, K p having no mean) */
  PetscCall(VecSum(p, &sum));
  if (force && PetscRealPart(sum) > 0) PetscCall(VecScale(p, F / (A * PetscRealPart(sum))));
  else if (force) PetscCall(VecSet(p, F / (A * N)));
  else if (!(PetscRealPart(sum) > 0)) {
    PetscCall(VecGetArray(p, &pa));
    PetscCall(VecGetArrayRead(s->h, &ha));
    for (k = 0; k < n; k++) pa[k] = PetscMax(0.0, d - PetscRealPart(ha[k]));
    PetscCall(VecRestoreArrayRead(s->h, &ha));
    PetscCall(VecRestoreArray(p, &pa));
    PetscCall(VecSum(p, &sum));
    if (PetscRealPart(sum) > 0) {
      PetscScalar wb, wKw;
      PetscCall(MatMult(s->K, p, u));
      PetscCall(VecDot(p, u, &wKw));
      PetscCall(VecDot(p, p, &wb)); /* w.(d - h) = w.w where w > 0 */
      PetscCall(VecScale(p, PetscRealPart(wb) / PetscRealPart(wKw)));
      PetscCall(VecScale(u, PetscRealPart(wb) / PetscRealPart(wKw)));
      have_u = PETSC_TRUE;
    }
    if (!(PetscRealPart(sum) > 0)) { /* nothing touches at d */
      PetscCall(DestroyWork(&u, &g, &t, &r, &z));
      PetscCall(PetscLogEventEnd(ADH_Predict, 0, 0, 0, 0));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(VecSet(t, 0.0));
  if (!have_u) PetscCall(MatMult(s->K, p, u));
  for (it = 0; it < pk->max_it; it++) {
    PetscReal loc[4], glob[4], G, beta, tau;

    PetscCall(AdhSolverStopRequested_Private(s, &stop));
    if (stop) break;

    if (missed > 1e-7 || (change <= pk->rtol && missed > 0)) {
      PetscCall(VecScale(p, scale));
      scale = 1.0;
      PetscCall(MatMult(s->K, p, u));
      missed = 0.0;
      updates++;
    } else if (change <= pk->rtol) break;
    /* rescale; the set p > 0, and the gap's mean there (the indentation d) */
    PetscCall(VecGetArray(p, &pa));
    PetscCall(VecGetArray(u, &ua));
    PetscCall(VecGetArray(g, &ga));
    PetscCall(VecGetArrayRead(s->h, &ha));
    loc[0] = loc[1] = 0.0;
    for (k = 0; k < n; k++) {
      pa[k] *= scale;
      ua[k] *= scale;
      ga[k] = ua[k] + ha[k];
      if (PetscRealPart(pa[k]) > 0) {
        loc[0] += 1;
        loc[1] += PetscRealPart(ga[k]);
      }
    }
    PetscCall(VecRestoreArrayRead(s->h, &ha));
    PetscCall(VecRestoreArray(u, &ua));
    scale = 1.0;
    PetscCall(MPIU_Allreduce(loc, glob, 2, MPIU_REAL, MPIU_SUM, s->comm));
    nc   = glob[0];
    gbar = force ? glob[1] / nc : d;
    loc[0] = 0.0;
    for (k = 0; k < n; k++) {
      ga[k] -= gbar;
      if (!z && PetscRealPart(pa[k]) > 0) loc[0] += PetscRealPart(ga[k] * ga[k]);
    }
    if (z) {
      /* preconditioned: z = P S P g with S the body's stiffness (E*|q|/2 on a half-space) on the grid (the inverse of the
         compliance's symbol) and P the projection onto the set's pressures of zero sum */
      PetscScalar *za;
      PetscReal    zloc[2], zglob[2], zbar;

      PetscCall(VecGetArray(r, &ta));
      for (k = 0; k < n; k++) ta[k] = PetscRealPart(pa[k]) > 0 ? ga[k] : 0.0;
      PetscCall(VecRestoreArray(r, &ta));
      PetscCall(MatMult(s->S, r, z));
      PetscCall(VecGetArray(z, &za));
      zloc[0] = 0.0;
      for (k = 0; k < n; k++)
        if (PetscRealPart(pa[k]) > 0) zloc[0] += PetscRealPart(za[k]);
      PetscCall(MPIU_Allreduce(zloc, zglob, 1, MPIU_REAL, MPIU_SUM, s->comm));
      zbar = force ? zglob[0] / nc : 0.0;
      for (k = 0; k < n; k++) {
        za[k] = PetscRealPart(pa[k]) > 0 ? za[k] - zbar : 0.0;
        loc[0] += PetscRealPart(ga[k] * za[k]);
      }
      PetscCall(VecRestoreArray(z, &za));
    }
    PetscCall(MPIU_Allreduce(loc, &G, 1, MPIU_REAL, MPIU_SUM, s->comm));
    if (G == 0) { /* the gap is closed exactly on the set */
      PetscCall(VecRestoreArray(g, &ga));
      PetscCall(VecRestoreArray(p, &pa));
      break;
    }
    /* conjugate direction on the set, restarted (delta = 0) after points joined */
    beta = delta * G / Gold;
    Gold = G;
    PetscCall(VecGetArray(t, &ta));
    if (z) {
      const PetscScalar *za;
      PetscCall(VecGetArrayRead(z, &za));
      for (k = 0; k < n; k++) ta[k] = PetscRealPart(pa[k]) > 0 ? za[k] + beta * ta[k] : 0.0;
      PetscCall(VecRestoreArrayRead(z, &za));
    } else
      for (k = 0; k < n; k++) ta[k] = PetscRealPart(pa[k]) > 0 ? ga[k] + beta * ta[k] : 0.0;
    PetscCall(VecRestoreArray(t, &ta));
    PetscCall(VecRestoreArray(g, &ga));
    PetscCall(VecRestoreArray(p, &pa));
    /* the step length from the direction's gap change, again relative to its mean on the set */
    PetscCall(MatMult(s->K, t, r));
    PetscCall(VecGetArrayRead(r, &ra));
    PetscCall(VecGetArray(p, &pa));
    PetscCall(VecGetArray(g, &ga));
    PetscCall(VecGetArray(t, &ta));
    loc[0] = loc[1] = loc[2] = loc[3] = 0.0;
    for (k = 0; k < n; k++)
      if (PetscRealPart(pa[k]) > 0) {
        loc[0] += PetscRealPart(ra[k]);
        loc[1] += PetscRealPart(ta[k]);
        loc[2] += PetscRealPart(ga[k] * ta[k]);
        loc[3] += PetscRealPart(ra[k] * ta[k]);
      }
    PetscCall(MPIU_Allreduce(loc, glob, 4, MPIU_REAL, MPIU_SUM, s->comm));
    {
      const PetscReal den = glob[3] - (force ? glob[0] / nc * glob[1] : 0.0);
      if (!(den > 0)) { /* the direction changes nothing any more: converged to rounding */
        PetscCall(VecRestoreArray(t, &ta));
        PetscCall(VecRestoreArray(g, &ga));
        PetscCall(VecRestoreArray(p, &pa));
        PetscCall(VecRestoreArrayRead(r, &ra));
        break;
      }
      tau = glob[2] / den;
    }
    /* p - tau t (u with it); points with p < 0 leave, points off the set where the surfaces
       overlap join */
    PetscCall(VecGetArray(u, &ua));
    loc[0] = loc[1] = loc[2] = loc[3] = 0.0;
    for (k = 0; k < n; k++) {
      const PetscReal old = PetscRealPart(pa[k]), step = old - tau * PetscRealPart(ta[k]);
      PetscReal       v = step;

      if (v < 0) v = 0.0;
      else if (old == 0.0 && PetscRealPart(ga[k]) < 0) {
        v = -PetscRealPart(ga[k]) * tau;
        loc[2] += 1;
      }
      loc[0] += PetscAbsReal(v - old);
      loc[1] += PetscAbsReal(v - step);
      loc[3] += v;
      pa[k] = v;
      ua[k] -= tau * ra[k];
    }
    PetscCall(VecRestoreArray(u, &ua));
    PetscCall(VecRestoreArray(t, &ta));
    PetscCall(VecRestoreArray(g, &ga));
    PetscCall(VecRestoreArray(p, &pa));
    PetscCall(VecRestoreArrayRead(r, &ra));
    PetscCall(MPIU_Allreduce(loc, glob, 4, MPIU_REAL, MPIU_SUM, s->comm));
    /* the force constraint, applied in the next pass */
    if (!(glob[3] > 0)) break; /* no contact: under displacement control, nothing touches */
    scale  = force ? F / (A * glob[3]) : 1.0;
    delta  = glob[2] > 0 ? 0.0 : 1.0;
    change = glob[0] / glob[3];
    missed = missed + glob[1] / glob[3];
  }
  if (stop) { /* a signal stops the path: the step is abandoned */
    PetscCall(DestroyWork(&u, &g, &t, &r, &z));
    PetscCall(PetscLogEventEnd(ADH_Predict, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  PetscCall(VecScale(p, scale));
  PetscCall(PetscInfo(s, "polonsky-keer: %" PetscInt_FMT " iterations, %" PetscInt_FMT " displacement updates, last change %g of the pressure's 1-norm, %g points in contact\n", it, updates, (double)change, (double)nc));
  if (force) s->d = gbar;
  pk->its += it;
  /* the set is where the pressure is positive; the unit response vanishes off it, as p does */
  {
    PetscScalar *xa = NULL;
    if (s->set_response) PetscCall(VecGetArray(s->set_response, &xa));
    PetscCall(VecGetArray(p, &pa));
    for (k = 0; k < n; k++) {
      s->in_set[k] = PetscRealPart(pa[k]) > 0;
      if (xa && !s->in_set[k]) xa[k] = 0.0;
    }
    PetscCall(VecRestoreArray(p, &pa));
    if (xa) PetscCall(VecRestoreArray(s->set_response, &xa));
  }
  PetscCall(AdhSolverRebuildSet_Private(s));
  PetscCall(DestroyWork(&u, &g, &t, &r, &z));
  PetscCall(PetscLogEventEnd(ADH_Predict, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetFromOptions_PolonskyKeer(AdhSolver s, AdhOptionItems PetscOptionsObject)
{
  PolonskyKeerData *pk = (PolonskyKeerData *)s->pops.data;

  PetscFunctionBegin;
  PetscCall(AdhOptionsReal("-adh_predictor_rtol", "polonsky-keer: stop when an iteration changes the pressure by less than this fraction of its 1-norm", "ADHPREDICTORPOLONSKYKEER", pk->rtol, &pk->rtol, NULL));
  PetscCall(PetscOptionsBool("-adh_predictor_fourier", "polonsky-keer under force control: precondition with the inverse of the compliance's symbol, as the set solves do", "ADHPREDICTORPOLONSKYKEER", pk->fourier, &pk->fourier, NULL));
  PetscCall(AdhOptionsInt("-adh_predictor_max_it", "polonsky-keer: at most this many iterations per step", "ADHPREDICTORPOLONSKYKEER", pk->max_it, &pk->max_it, NULL));
  PetscCheck(pk->rtol > 0 && pk->rtol < 1, PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_predictor_rtol must lie in (0, 1), got %g", (double)pk->rtol);
  PetscCheck(pk->max_it >= 1, PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_predictor_max_it must be at least 1, got %" PetscInt_FMT, pk->max_it);
  PetscFunctionReturn(0);
}

static PetscErrorCode View_PolonskyKeer(AdhSolver s, PetscViewer viewer)
{
  PolonskyKeerData *pk = (PolonskyKeerData *)s->pops.data;
  PetscBool         isascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (isascii) PetscCall(PetscViewerASCIIPrintf(viewer, "stops at a change of %g of the pressure's 1-norm or after %" PetscInt_FMT " iterations%s; %" PetscInt_FMT " iterations so far\n", (double)pk->rtol, pk->max_it, pk->fourier ? ", preconditioned under force control" : "", pk->its));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_PolonskyKeer(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(s->pops.data));
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhPredictorCreate_PolonskyKeer(AdhSolver s)
{
  PolonskyKeerData *pk;

  PetscFunctionBegin;
  PetscCall(PetscNew(&pk));
  pk->rtol                    = 1e-8;
  pk->max_it                  = 10000;
  pk->fourier                 = PETSC_TRUE;
  s->pops.data                = pk;
  s->pops.predict             = PolonskyKeer;
  s->pops.base.setfromoptions = SetFromOptions_PolonskyKeer;
  s->pops.base.view           = View_PolonskyKeer;
  s->pops.base.destroy        = Destroy_PolonskyKeer;
  PetscFunctionReturn(0);
}
