/* The griffith attach rule (-adh_attach griffith), crack-closure's mirror on loading: the gap below
   which each open point beside the contact joins. */
#include "crackclosureimpl.h"

/* -adh_attach griffith: the gap below which each open point joins, the mirror of the detach test,
   for the p whose gap the detach test just computed (it let nothing go or, under
   -adh_cascade_apart, the points it let go keep their pressure and count as in the set here, as in
   the state solved, while they get no limit of their own). When an open point j beside
   the contact joins, the edge moves out by one element: j takes the tension of its set neighbour
   i closest to the edge's inward normal, and the crack it closes had the opening g_j, so
   G_j = -p_i g_j / 2 is the release rate of the edge one element further out. Averaged along the
   outer front as the detach test averages along the inner one, j joins when that mean is below
   its dgamma: when its gap is below g_j dgamma / mean. Where the neighbour is in compression, or
   j has no set neighbour (a new asperity's first touch), the reach limit Sigma K_00 holds. A
   point that penetrates always joins. */
PetscErrorCode AdhCrackClosureGriffithLimits_Private(AdhSolver s, CrackClosure *cc)
{
  const AdhGrid      g  = s->grid;
  const PetscReal    chi_per_area = s->eops.chi_per_area;
  const PetscReal    K00  = s->eops.self_compliance;
  const PetscBool    wrap = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  const PetscScalar *ta, **ol, **hl, **pl, **Gl;
  const char       **sl;
  PetscScalar       *Ga, *la;
  PetscReal          tu;
  PetscInt           ys, ym, gys = cc->gys, gym = cc->gym, i, j, k, a, b, nfront;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(ADH_AttachLimits, 0, 0, 0, 0));
  if (!s->attach_limit) { /* G's storage: the limits are written over it once G is no longer read */
    PetscCall(PetscObjectReference((PetscObject)cc->G));
    s->attach_limit = cc->G;
  }
  if (!cc->P.far) PetscCall(PetscMalloc1(cc->nghost * g->Nx + 1, &cc->P.far));
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  PetscCall(AdhCrackClosureFetchRows_Private(cc, s->p, &cc->P));
  PetscCall(AdhCrackClosureGetSetRows_Private(cc, &sl));
  PetscCall(AdhCrackClosureGetRows_Private(cc, &cc->O, &ol));
  PetscCall(AdhCrackClosureGetRows_Private(cc, &cc->H, &hl));
  PetscCall(AdhCrackClosureGetRows_Private(cc, &cc->P, &pl));
  PetscCall(VecGetArray(cc->G, &Ga));
  for (j = ys; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) {
      const PetscInt  k = (j - ys) * g->Nx + i, di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
      const PetscReal hj = PetscRealPart(hl[j][i]);
      PetscReal       normal[2], best = PETSC_MAX_REAL, tension = 0.0;
      PetscBool       beside = PETSC_FALSE;
      Ga[k] = NAN;
      if (cc->set_before[k] || hj >= PETSC_INFINITY) continue; /* points let go since the openings (-adh_cascade_apart) have none */
      for (PetscInt n = 0; n < 4 && !beside; n++) beside = (PetscBool)(Neighbour(g, wrap, gys, gym, i, j, di[n], dj[n], &a, &b) && sl[b][a]);
      if (!beside) continue;
      /* the outward normal (towards the open side), as for a front point */
      PetscCall(AdhCrackClosureEdgeNormal_Private(g, wrap, gys, gym, sl, i, j, normal));
      for (PetscInt n = 0; n < 4; n++) { /* the set neighbour closest to the inward normal (ties: the more tensile) */
        PetscReal along, p;
        if (!Neighbour(g, wrap, gys, gym, i, j, di[n], dj[n], &a, &b) || !sl[b][a]) continue;
        along = di[n] * normal[0] + dj[n] * normal[1];
        p     = PetscRealPart(pl[b][a]);
        if (along < best || (along == best && -p > tension)) {
          best    = along;
          tension = -p;
        }
      }
      if (tension > 0) Ga[k] = tension * PetscRealPart(ol[j][i]) / 2.0; /* ol: j's gap (it has a face) */
    }
  PetscCall(VecRestoreArray(cc->G, &Ga));
  PetscCall(AdhCrackClosureRestoreRows_Private(&cc->P, &pl));
  PetscCall(AdhCrackClosureFetchRows_Private(cc, cc->G, &cc->Gf));

  /* the mean along the outer front, against dgamma, as a limit on the gap: first into a list of
     the front's points (the walks read G's rows), then over G itself, which holds the limits */
  PetscCall(AdhCrackClosureGetRows_Private(cc, &cc->Gf, &Gl));
  PetscCall(AdhCrackClosureFrontLinks_Private(s, cc, wrap, Gl));
  cc->links_set = -1; /* the outer front's now */
  for (j = ys, nfront = 0; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) nfront += (!s->in_set[(j - ys) * g->Nx + i] && !IsNaN(PetscRealPart(Gl[j][i])));
  if (nfront > cc->capfront) {
    cc->capfront = PetscMax(nfront, 2 * cc->capfront);
    PetscCall(PetscFree(cc->front_limit));
    PetscCall(PetscMalloc1(cc->capfront, &cc->front_limit));
  }
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_FALSE, &ta, &tu));
  for (j = ys, nfront = 0; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) {
      const PetscInt  k = (j - ys) * g->Nx + i;
      const PetscReal Sigma = ADH_SIGMA_AT(ta, tu, k), dgamma = chi_per_area * Sigma * Sigma;
      PetscReal       sum, n, gap, margin;
      if (s->in_set[k] || IsNaN(PetscRealPart(Gl[j][i]))) continue;
      PetscCall(AdhCrackClosureWindowMean_Private(s, cc, wrap, Gl, i, j, NULL, ADH_WINDOW_BAND_LOW * dgamma, ADH_WINDOW_BAND_HIGH * dgamma, &sum, &n, &margin));
      gap                       = PetscRealPart(ol[j][i]); /* a front point has a face */
      cc->front_limit[nfront++] = sum > 0 ? PetscMax(0.0, gap * dgamma * n / sum) : PETSC_MAX_REAL;
    }
  PetscCall(AdhCrackClosureRestoreRows_Private(&cc->Gf, &Gl));
  PetscCall(VecGetArray(s->attach_limit, &la));
  for (k = 0, nfront = 0; k < s->nlocal; k++) {
    const PetscBool front = (PetscBool)(!s->in_set[k] && !IsNaN(PetscRealPart(la[k])));
    la[k] = front ? cc->front_limit[nfront++] : ADH_SIGMA_AT(ta, tu, k) * K00; /* else reach */
  }
  PetscCall(VecRestoreArray(s->attach_limit, &la));
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &ta));
  PetscCall(AdhCrackClosureRestoreRows_Private(&cc->H, &hl));
  PetscCall(AdhCrackClosureRestoreRows_Private(&cc->O, &ol));
  s->attach_limit_current = PETSC_TRUE;
  PetscCall(PetscLogEventEnd(ADH_AttachLimits, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
