/*MC
   ADHELASTICHALFSPACE - "halfspace", the default elastic body: an elastic half-space of reduced modulus E*

   Options Database Keys:
+  -adh_elastic halfspace - selects this body (the default)
.  -adh_E_star <1>        - the reduced modulus E*, or
-  -adh_E1, -adh_nu1, -adh_E2, -adh_nu2 - each solid's Young's modulus and Poisson ratio, 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2

   Level: beginner

   Notes:
   Both boundaries: on the free boundary (an isolated contact) the compliance holds Love's influence coefficients of the
   uniformly loaded rectangular element (`AdhLoveCoefficient()`), on a periodic cell the spectral symbol 2/(E*|q|). The
   element's self-compliance is Love's at its centre, its self-energy Pohrt and Popov's chi (`AdhChi()`), and the critical stress
   theirs (`AdhCriticalStress()`). Only E* matters: the two solids' Poisson ratios enter through it alone.

.seealso: `AdhSolverSetElasticType()`, `ADHELASTICLAYER`, `MatCreateAdhCompliance()`
M*/
#include "solver/solverimpl.h"

static PetscErrorCode CreateOperators_HalfSpace(AdhSolver s, AdhGrid grid, AdhBoundary boundary, Mat *K, Mat *S)
{
  PetscFunctionBegin;
  PetscCall(MatCreateAdhCompliance(grid, s->Estar, boundary, K));
  PetscCall(MatCreateAdhPeriodicStiffness(grid, s->Estar, S));
  PetscFunctionReturn(0);
}

/* 2/(q C(q)) = E* at every wave number */
static PetscReal Modulus_HalfSpace(AdhSolver s, PetscReal q)
{
  (void)q;
  return s->Estar;
}

static PetscReal CriticalStress_HalfSpace(AdhSolver s, PetscReal dgamma)
{
  return AdhCriticalStress(s->grid->hx, s->grid->hy, s->Estar, dgamma);
}

/* The element's constants from the half-space's closed forms. */
static PetscErrorCode SetUp_HalfSpace(AdhSolver s)
{
  const AdhGrid g = s->grid;

  PetscFunctionBegin;
  s->eops.self_compliance = AdhLoveCoefficient(0.0, 0.0, g->hx, g->hy, s->Estar);
  s->eops.chi_per_area    = AdhChi(g->hx, g->hy) / (g->hx * g->hy * s->Estar); /* dgamma = chi Sigma^2 / (hx hy E*) */
  s->eops.stress_per_work = g->hx * g->hy * s->Estar / AdhChi(g->hx, g->hy);
  /* 2/(E* q_min), the compliance of the longest wave: the Fourier preconditioner's mean mode is its
     inverse, so the preconditioned operator stays well conditioned */
  s->eops.mean_compliance = 2.0 / (s->Estar * 2.0 * PETSC_PI / PetscMax(g->Lx, g->Ly));
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhElasticCreate_HalfSpace(AdhSolver s)
{
  PetscFunctionBegin;
  s->eops.halfspace        = PETSC_TRUE;
  s->eops.create_operators = CreateOperators_HalfSpace;
  s->eops.modulus          = Modulus_HalfSpace;
  s->eops.critical_stress  = CriticalStress_HalfSpace;
  s->eops.base.setup       = SetUp_HalfSpace;
  PetscFunctionReturn(0);
}
