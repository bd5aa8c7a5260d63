/* crack-closure's detach pass: the release rate of every front point, averaged along the front,
   against dgamma, with the certified decision of an iterate. Both modes share the front's release
   rates (FrontReleaseRates) and each point's windowed mean (PointWindow); the detach test
   (AdhCrackClosureDetach_Private) lets points go or gives the largest demand, the decision
   (AdhCrackClosureDecide_Private) says what the exact solution's test would do. */
#include "crackclosureimpl.h"

/* Pass 1: the gap of the current p (left in s->g), and G = -p delta / 2 of every front point in
   cc->G, fetched into cc->Gf. With decision (perr > 0) the openings are within gerr = rho perr of
   the exact solution's (rho bounds K's row norms), each front point's G within
   (|t| gerr + |delta| perr + perr gerr) / 2, and *E is the largest of these over the front. */
static PetscErrorCode FrontReleaseRates(AdhSolver s, PetscBool decision, PetscReal perr, PetscReal *E)
{
  CrackClosure      *cc = (CrackClosure *)s->crops.data;
  const AdhGrid      g  = s->grid;
  const PetscBool    wrap = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  PetscScalar       *pa, *Ga;
  const PetscScalar **ol, **hl;
  const char       **sl;
  PetscReal          gerr = 0.0;
  PetscInt           ys, ym, gys, gym, i, j, k, a, b;

  PetscFunctionBegin;
  *E = 0.0;
  PetscCheck(cc->fetch, s->comm, PETSC_ERR_ORDER, "crack-closure: evaluated before set-up");
  s->attach_limit_current = PETSC_FALSE; /* griffith's limits are kept in G's storage, written below */
  if (decision) {
    PetscReal rho;
    PetscCall(MatAdhComplianceGetRowNormBound(s->K, &rho));
    gerr = rho * perr;
  }
  if (cc->h_version != s->profile_version) { /* h changes only with the profile */
    PetscCall(AdhCrackClosureFetchRows_Private(cc, s->h, &cc->H));
    PetscCall(AdhCrackClosureEnsureFaceless_Private(s, cc));
    cc->h_version = s->profile_version;
    cc->decided   = PETSC_FALSE; /* the openings below are of this profile */
  }
  /* u = K p and g = (h - d) + u, the openings' rows, and the set's. After a certified stop p is
     the iterate the stop was decided on, whose g is at hand. */
  if (!(cc->decided && s->certified_stop && !decision)) {
    if (cc->faceless) { /* u into faceless, g from it, then g over u where there is a face */
      const PetscScalar *ha, *ga;
      PetscScalar       *fa;
      PetscCall(MatMult(s->K, s->p, cc->faceless));
      PetscCall(AdhSolverGapFromDisplacement_Private(s, cc->faceless));
      PetscCall(VecGetArrayRead(s->h, &ha));
      PetscCall(VecGetArrayRead(s->g, &ga));
      PetscCall(VecGetArray(cc->faceless, &fa));
      for (k = 0; k < s->nlocal; k++)
        if (PetscRealPart(ha[k]) < PETSC_INFINITY) fa[k] = ga[k];
      PetscCall(VecRestoreArray(cc->faceless, &fa));
      PetscCall(VecRestoreArrayRead(s->g, &ga));
      PetscCall(VecRestoreArrayRead(s->h, &ha));
    } else PetscCall(AdhSolverComputeGap_Private(s));
    PetscCall(AdhCrackClosureFetchRows_Private(cc, cc->faceless ? cc->faceless : s->g, &cc->O));
    PetscCall(AdhCrackClosureFetchSetRows_Private(s, cc));
  }
  cc->decided = decision;
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  gys = cc->gys;
  gym = cc->gym;
  if (cc->cache && cc->cache_set != s->set_version) { /* a new set: a new front */
    for (k = 0; k < s->nlocal; k++) cc->slot[k] = -1;
    cc->nentry    = 0;
    cc->nmember   = 0;
    cc->cache_set = s->set_version;
  }

  /* pass 1: G = -p delta / 2 on the front, the points of the set with an open 4-neighbour. When
     the front lets go, the edge moves by one element towards its open side: on a straight edge
     the set less its front is the set shifted by one element along the grid axis closest to the
     edge's normal. So the opening a front point gets is, by that shift, the one its neighbour
     along that axis has now: delta is the opening of the open neighbour closest to the normal
     (ties: the smaller opening). */
  PetscCall(AdhCrackClosureGetRows_Private(cc, &cc->O, &ol));
  PetscCall(AdhCrackClosureGetRows_Private(cc, &cc->H, &hl));
  PetscCall(AdhCrackClosureGetSetRows_Private(cc, &sl));
  PetscCall(VecGetArray(s->p, &pa));
  PetscCall(VecGetArray(cc->G, &Ga));
  for (j = ys; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) {
      const PetscInt  k = (j - ys) * g->Nx + i, di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
      const PetscReal hi = PetscRealPart(hl[j][i]), ti = -PetscRealPart(pa[k]);
      PetscReal       delta[4], open = PETSC_MAX_REAL, best = -PETSC_MAX_REAL, normal[2];
      PetscInt        dir[4], nopen = 0;
      Ga[k] = NAN;
      if (!s->in_set[k]) continue;
      if (cc->cache && cc->slot[k] == -2) continue; /* not on the front */
      if (cc->cache && cc->slot[k] >= 0) { /* the open neighbours closest to the normal, known */
        const FrontEntry *e = &cc->entry[cc->slot[k]];
        for (PetscInt m = 0; m < e->ncand; m++) {
          const PetscInt  bb = gys + e->cand[m] / g->Nx, aa = e->cand[m] % g->Nx;
          const PetscReal dn = Opening(PetscRealPart(hl[bb][aa]), hi, s->d, PetscRealPart(ol[bb][aa]));
          if (m == 0 || dn < open) open = dn;
        }
        Ga[k] = ti * open / 2.0;
        if (decision) *E = PetscMax(*E, (PetscAbsReal(ti) * gerr + PetscAbsReal(open) * perr + perr * gerr) / 2.0);
        continue;
      }
      for (PetscInt n = 0; n < 4; n++) { /* the open 4-neighbours and their openings */
        PetscReal hn;
        if (!Neighbour(g, wrap, gys, gym, i, j, di[n], dj[n], &a, &b)) continue; /* off the grid: AdhCrackClosureEdgeNormal_Private checks the rows */
        if (sl[b][a]) continue; /* in the set */
        hn             = PetscRealPart(hl[b][a]); /* PETSC_INFINITY (finite): no face there */
        dir[nopen]     = n;
        delta[nopen++] = Opening(hn, hi, s->d, PetscRealPart(ol[b][a]));
      }
      if (!nopen) { /* not on the front */
        if (cc->cache) cc->slot[k] = -2;
        continue;
      }
      PetscCall(AdhCrackClosureEdgeNormal_Private(g, wrap, gys, gym, sl, i, j, normal));
      for (PetscInt m = 0; m < nopen; m++) {
        const PetscReal along = di[dir[m]] * normal[0] + dj[dir[m]] * normal[1];
        if (along > best || (along == best && delta[m] < open)) {
          best = along;
          open = delta[m];
        }
      }
      if (cc->cache) { /* its entry: the open neighbours along the normal as far as the best */
        FrontEntry *e;
        if (cc->nentry == cc->capentry) {
          cc->capentry = PetscMax(256, 2 * cc->capentry);
          PetscCall(PetscRealloc(cc->capentry * sizeof(FrontEntry), &cc->entry));
        }
        cc->slot[k] = cc->nentry;
        e           = &cc->entry[cc->nentry++];
        e->ncand    = 0;
        e->n16 = e->nR = -1;
        e->w16 = e->wR = 0;
        e->kappa       = PETSC_MAX_REAL;
        for (PetscInt m = 0; m < nopen; m++)
          if (di[dir[m]] * normal[0] + dj[dir[m]] * normal[1] == best) {
            PetscCheck(Neighbour(g, wrap, gys, gym, i, j, di[dir[m]], dj[dir[m]], &a, &b), PETSC_COMM_SELF, PETSC_ERR_PLIB, "crack-closure: an open neighbour outside the fetched rows");
            e->cand[e->ncand++] = (b - gys) * g->Nx + a;
          }
      }
      Ga[k] = ti * open / 2.0;
      if (decision) *E = PetscMax(*E, (PetscAbsReal(ti) * gerr + PetscAbsReal(open) * perr + perr * gerr) / 2.0);
    }
  PetscCall(VecRestoreArray(cc->G, &Ga));
  PetscCall(AdhCrackClosureRestoreRows_Private(&cc->H, &hl));
  PetscCall(AdhCrackClosureRestoreRows_Private(&cc->O, &ol));
  PetscCall(AdhCrackClosureFetchRows_Private(cc, cc->G, &cc->Gf));
  PetscCall(VecRestoreArray(s->p, &pa));
  if (decision) PetscCall(MPIU_Allreduce(MPI_IN_PLACE, E, 1, MPIU_REAL, MPIU_MAX, s->comm));

  PetscFunctionReturn(0);
}

/* The windowed mean of the release rates of the front points around front point (i, j) (local k)
   of pressure p: the weighted sum and weights (n = 0: the release-rate rule does not apply: not
   a front point in tension, or no adhesion) and the margin by which its window holds. */
static PetscErrorCode PointWindow(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl, PetscInt i, PetscInt j, PetscInt k, PetscReal p, PetscReal perr, PetscReal Sigma, PetscReal dgamma, PetscReal *sum, PetscReal *n, PetscReal *margin)
{
  PetscFunctionBegin;
  *sum = 0.0, *n = 0.0, *margin = PETSC_MAX_REAL;
  if (p < perr && Sigma > 0 && !IsNaN(PetscRealPart(Gl[j][i]))) {
    PetscCheck(!cc->cache || cc->slot[k] >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "crack-closure: a front point without its cache entry");
    PetscCall(AdhCrackClosureWindowMean_Private(s, cc, wrap, Gl, i, j, cc->cache ? &cc->entry[cc->slot[k]] : NULL, ADH_WINDOW_BAND_LOW * dgamma, ADH_WINDOW_BAND_HIGH * dgamma, sum, n, margin));
  }
  PetscFunctionReturn(0);
}

/* The detach test of the current p: every point of the set where the mean release rate of the
   front points within its window exceeds dgamma, or p < -Sigma, lets go (with detach: removed,
   *removed their number); else *ratio (if asked) is the largest demand over the set, as a stress
   ratio, max((G / dgamma)^(1/2), -p / Sigma). */
PetscErrorCode AdhCrackClosureDetach_Private(AdhSolver s, PetscBool detach, PetscInt *removed, PetscReal *ratio)
{
  CrackClosure      *cc = (CrackClosure *)s->crops.data;
  const AdhGrid      g  = s->grid;
  const PetscReal    chi_per_area = s->eops.chi_per_area; /* dgamma = chi_per_area Sigma^2 (the body's) */
  const PetscBool    wrap = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  PetscScalar       *pa, *xa = NULL;
  const PetscScalar *ta, **Gl;
  PetscReal          tu, r = 0.0, E;
  PetscInt           ys, ym, i, j, count = 0;

  PetscFunctionBegin;
  PetscCall(FrontReleaseRates(s, PETSC_FALSE, 0.0, &E));
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  if (detach && s->set_response) PetscCall(VecGetArray(s->set_response, &xa));
  PetscCall(VecGetArray(s->p, &pa));
  PetscCall(AdhCrackClosureGetRows_Private(cc, &cc->Gf, &Gl));
  PetscCall(AdhCrackClosureEnsureInnerLinks_Private(s, cc, wrap, Gl)); /* the set's front decides them: once a set */
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_TRUE, &ta, &tu));
  for (j = ys; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) {
      const PetscInt  k = (j - ys) * g->Nx + i;
      const PetscReal p = PetscRealPart(pa[k]), Sigma = ADH_SIGMA_AT(ta, tu, k), dgamma = chi_per_area * Sigma * Sigma;
      PetscReal       sum, n, margin, load;
      PetscBool       lets_go;
      if (!s->in_set[k]) continue;
      PetscCall(PointWindow(s, cc, wrap, Gl, i, j, k, p, 0.0, Sigma, dgamma, &sum, &n, &margin));
      /* both rules as stress ratios: (G / dgamma)^(1/2) and -p / Sigma */
      load    = p < 0 && Sigma > 0 ? -p / Sigma : 0.0;
      lets_go = (PetscBool)(p < -Sigma);
      if (n && sum > 0) {
        load    = PetscMax(load, PetscSqrtReal(sum / n / dgamma));
        lets_go = (PetscBool)(lets_go || sum / n > dgamma);
      }
      if (detach && lets_go) {
        AdhSolverRemovePoint_Private(s, k, pa, xa);
        count++;
      } else r = PetscMax(r, load);
    }
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &ta));
  PetscCall(AdhCrackClosureRestoreRows_Private(&cc->Gf, &Gl));
  if (xa) PetscCall(VecRestoreArray(s->set_response, &xa));
  PetscCall(VecRestoreArray(s->p, &pa));
  if (removed) {
    PetscCall(MPIU_Allreduce(&count, removed, 1, MPIU_INT, MPI_SUM, s->comm));
    /* p unchanged (-adh_cascade_apart: the points let go keep theirs until the attach test): it
       takes this gap, and griffith's limits of this p */
    s->gap_current = (PetscBool)(*removed == 0 || s->apart_pending);
    if ((!*removed || s->apart_pending) && s->attach == ADH_ATTACH_GRIFFITH && AdhSolverIsAdhesive_Private(s)) PetscCall(AdhCrackClosureGriffithLimits_Private(s, cc));
  }
  if (ratio) PetscCall(MPIU_Allreduce(&r, ratio, 1, MPIU_REAL, MPIU_MAX, s->comm));
  PetscFunctionReturn(0);
}

/* The decision of the exact solution p*, within perr of the current p at every point: nothing is
   removed. Every windowed mean is within E of p*'s (FrontReleaseRates), and a point's decision is
   made when its margins exceed these bounds: |p + Sigma| > perr, |p| > perr where the front rule
   may apply, |mean - dgamma| > E. In doubt, *needed is the bound at which the decisions in doubt
   now would be made. */
PetscErrorCode AdhCrackClosureDecide_Private(AdhSolver s, PetscReal perr, AdhDetachDecision *decision, PetscReal *needed)
{
  CrackClosure      *cc = (CrackClosure *)s->crops.data;
  const AdhGrid      g  = s->grid;
  const PetscReal    chi_per_area = s->eops.chi_per_area;
  const PetscBool    wrap = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  const PetscScalar *pa, *ta, **Gl;
  PetscReal          tu, E, ratio_in_doubt = PETSC_MAX_REAL;
  PetscInt           ys, ym, i, j, counts[2] = {0, 0}; /* those that let go, those in doubt */

  PetscFunctionBegin;
  PetscCall(FrontReleaseRates(s, PETSC_TRUE, perr, &E));
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  PetscCall(VecGetArrayRead(s->p, &pa));
  PetscCall(AdhCrackClosureGetRows_Private(cc, &cc->Gf, &Gl));
  PetscCall(AdhCrackClosureEnsureInnerLinks_Private(s, cc, wrap, Gl));
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_TRUE, &ta, &tu));
  for (j = ys; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) {
      const PetscInt  k = (j - ys) * g->Nx + i;
      const PetscReal p = PetscRealPart(pa[k]), Sigma = ADH_SIGMA_AT(ta, tu, k), dgamma = chi_per_area * Sigma * Sigma;
      PetscReal       sum, n, margin;
      if (!s->in_set[k]) continue;
      PetscCall(PointWindow(s, cc, wrap, Gl, i, j, k, p, perr, Sigma, dgamma, &sum, &n, &margin));
      {
        /* each rule's decision for p*: made (true or false), or in doubt with the factor by which
           the bounds must shrink to make it */
        const PetscBool front = (PetscBool)(n > 0), sigma_go = (PetscBool)(p + perr < -Sigma), sigma_stay = (PetscBool)(p - perr >= -Sigma);
        const PetscBool applies = (PetscBool)(front && p + perr < 0), not_applies = (PetscBool)(!front || p - perr >= 0);
        const PetscReal mean = front ? sum / n : 0.0;
        const PetscBool window = (PetscBool)(!front || margin > E); /* p*'s window is this one */
        const PetscBool above = (PetscBool)(front && window && mean - E > dgamma), below = (PetscBool)(!front || (window && mean + E <= dgamma));
        if (sigma_go || (applies && above)) counts[0]++;
        else if (!(sigma_stay && (not_applies || below))) {
          counts[1]++;
          if (!sigma_go && !sigma_stay) ratio_in_doubt = PetscMin(ratio_in_doubt, PetscAbsReal(p + Sigma) / perr);
          if (!applies && !not_applies) ratio_in_doubt = PetscMin(ratio_in_doubt, PetscAbsReal(p) / perr);
          if (!above && !below) ratio_in_doubt = PetscMin(ratio_in_doubt, PetscMin(PetscAbsReal(mean - dgamma), margin) / E);
        }
      }
    }
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &ta));
  PetscCall(AdhCrackClosureRestoreRows_Private(&cc->Gf, &Gl));
  PetscCall(VecRestoreArrayRead(s->p, &pa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, s->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ratio_in_doubt, 1, MPIU_REAL, MPIU_MIN, s->comm));
  *decision = counts[1] ? ADH_DETACH_IN_DOUBT : counts[0] ? ADH_DETACH_SOME : ADH_DETACH_NONE;
  *needed   = counts[1] ? PetscMin(0.5, ratio_in_doubt) * perr : 0.0;
  PetscFunctionReturn(0);
}
