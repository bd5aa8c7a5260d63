/* What every periodic elastic body shares (impls/elastic/layer.c and the others given by a
   compliance symbol C(q)): its operators from the symbol, and the element's constants the solver
   needs (its self-compliance and self-energy) from the element's own uniform load on the cell. */
#include "solver/solverimpl.h"

/* The compliance and the stiffness of a periodic body from its symbol; the free boundary refused. */
PetscErrorCode AdhElasticPeriodicOperators_Private(AdhSolver s, AdhGrid grid, AdhBoundary boundary, AdhPeriodicSymbol symbol, void *ctx, Mat *K, Mat *S)
{
  PetscFunctionBegin;
  PetscCheck(boundary == ADH_BOUNDARY_PERIODIC, s->comm, PETSC_ERR_SUP, "-adh_elastic %s: its compliance is periodic only; give -adh_boundary periodic", s->elastic_type);
  PetscCall(MatCreateAdhPeriodicSymbolOperator(grid, symbol, ctx, PETSC_FALSE, K));
  PetscCall(MatCreateAdhPeriodicSymbolOperator(grid, symbol, ctx, PETSC_TRUE, S));
  PetscFunctionReturn(0);
}

/* sin(z)/z */
static PetscReal Sinc(PetscReal z)
{
  return PetscAbsReal(z) < 1e-8 ? 1.0 : PetscSinReal(z) / z;
}

/* The sums over the cell's wave vectors but the mean, of dC(q) S(q) / N (the element's centre) and
   dC(q) S(q)^2 / N (its average), with S the element's shape factor sinc(qx hx/2) sinc(qy hy/2)
   and dC = C - 2/(Eref q), into sums[0..1]; with whole, also those of C itself and of the
   half-space's 2/(Eref q) into sums[2..5], and those of C on the grid's own modes (no aliases: the
   discrete compliance's diagonal and its S^2-weighted twin) into sums[6..7]. Over the grid's modes and their aliases (k + a N),
   |a| <= ADH_ALIASES, and without whole only as far as 2 q depth < 80, beyond which the body's
   difference from the half-space is below exp(-80). This rank sums its rows of ky. */
#define ADH_ALIASES 8
static PetscErrorCode ElementSums(AdhSolver s, AdhPeriodicSymbol symbol, void *ctx, PetscReal Eref, PetscReal depth, PetscBool whole, PetscReal sums[8])
{
  const AdhGrid   g    = s->grid;
  const PetscReal qcut = whole ? PETSC_MAX_REAL : 40.0 / depth;
  /* the aliases reach the cut-off, at least one band around the grid's modes */
  const PetscInt ax = whole ? ADH_ALIASES : PetscMin((PetscInt)PetscCeilReal(qcut * g->Lx / (2.0 * PETSC_PI * g->Nx)) + 1, ADH_ALIASES);
  const PetscInt ay = whole ? ADH_ALIASES : PetscMin((PetscInt)PetscCeilReal(qcut * g->Ly / (2.0 * PETSC_PI * g->Ny)) + 1, ADH_ALIASES);

  PetscFunctionBegin;
  for (PetscInt k = 0; k < 8; k++) sums[k] = 0.0;
  for (PetscInt j = g->ys; j < g->ys + g->ym; j++) {
    const PetscInt ky0 = j <= g->Ny / 2 ? j : j - g->Ny;
    for (PetscInt b = -ay; b <= ay; b++) {
      const PetscReal qy = 2.0 * PETSC_PI * (ky0 + b * g->Ny) / g->Ly;
      if (PetscAbsReal(qy) > qcut) continue;
      for (PetscInt i = 0; i < g->Nx; i++) {
        const PetscInt kx0 = i <= g->Nx / 2 ? i : i - g->Nx;
        for (PetscInt a = -ax; a <= ax; a++) {
          const PetscReal qx = 2.0 * PETSC_PI * (kx0 + a * g->Nx) / g->Lx, q = PetscSqrtReal(qx * qx + qy * qy);
          PetscReal       C, Ch, S;
          if (q > qcut || q == 0.0) continue;
          C  = symbol(ctx, q);
          Ch = 2.0 / (Eref * q);
          S  = Sinc(0.5 * qx * g->hx) * Sinc(0.5 * qy * g->hy);
          sums[0] += (C - Ch) * S;
          sums[1] += (C - Ch) * S * S;
          if (whole) {
            sums[2] += C * S;
            sums[3] += C * S * S;
            sums[4] += Ch * S;
            sums[5] += Ch * S * S;
            if (!a && !b) {
              sums[6] += C;
              sums[7] += C * S * S;
            }
          }
        }
      }
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 8, MPIU_REAL, MPIU_SUM, s->comm));
  for (PetscInt k = 0; k < 8; k++) sums[k] /= (PetscReal)g->Nx * (PetscReal)g->Ny;
  PetscFunctionReturn(0);
}

/* The element's constants of a periodic body whose symbol differs from the half-space's of modulus
   Eref within `depth` of the surface (a layer's or coating's thickness): the half-space's (Love's
   self-compliance, Pohrt and Popov's chi, as the half-space body has them on a periodic cell too)
   plus what the body adds under the element's own uniform pressure, U_el = sigma^2 A (chi/(A Eref)
   + sum/2). That is exact to the half-space's own offset between Love's free-space value and the
   periodic cell's mean-free one (a few per cent of Love's on 32^2, 0.2% on 512^2), which would
   dominate a body's value far below the half-space's, and, the sums being truncated, would even
   turn it negative for a layer much thinner than an element. So under a grid spacing h
   (*approximate) the constants are the body's own sums plus that offset (in the same truncation)
   weighted by depth/h: equal to the formula above at depth = h, the layer's own value as depth
   goes to 0, continuous between; and at least the discrete compliance's own diagonal (and its
   S^2-weighted twin), positive, where the truncated sums fall below it (an incompressible layer
   far thinner than an element, whose element rests on the base: its own value nearly vanishes).
   The mean mode's compliance is the symbol's at the longest wave. */
PetscErrorCode AdhElasticPeriodicConstants_Private(AdhSolver s, AdhPeriodicSymbol symbol, void *ctx, PetscReal Eref, PetscReal depth, PetscBool *approximate)
{
  const AdhGrid   g = s->grid;
  const PetscReal h = PetscMin(g->hx, g->hy), love = AdhLoveCoefficient(0.0, 0.0, g->hx, g->hy, Eref), chi = AdhChi(g->hx, g->hy) / (g->hx * g->hy * Eref);
  PetscReal       sums[8];

  PetscFunctionBegin;
  *approximate = (PetscBool)(depth < h);
  PetscCall(ElementSums(s, symbol, ctx, Eref, depth, *approximate, sums));
  if (*approximate) {
    const PetscReal w = depth / h;
    s->eops.self_compliance = PetscMax(sums[2] + w * (love - sums[4]), sums[6]);
    s->eops.chi_per_area    = PetscMax(0.5 * sums[3] + w * (chi - 0.5 * sums[5]), 0.5 * sums[7]);
  } else {
    s->eops.self_compliance = love + sums[0];
    s->eops.chi_per_area    = chi + 0.5 * sums[1];
  }
  PetscCheck(s->eops.self_compliance > 0 && s->eops.chi_per_area > 0, s->comm, PETSC_ERR_PLIB, "-adh_elastic %s: the element's self-compliance %g or self-energy %g is not positive", s->elastic_type, (double)s->eops.self_compliance, (double)s->eops.chi_per_area);
  s->eops.stress_per_work = 1.0 / s->eops.chi_per_area;
  s->eops.mean_compliance = symbol(ctx, 2.0 * PETSC_PI / PetscMax(g->Lx, g->Ly));
  PetscFunctionReturn(0);
}

/* Sigma = (stress_per_work dgamma)^(1/2), from the constants a body's setup set */
PetscReal AdhElasticCriticalStress_Private(AdhSolver s, PetscReal dgamma)
{
  return PetscSqrtReal(s->eops.stress_per_work * dgamma);
}
