/* The spectral multipliers of the operators: the free compliance (Love's coefficients, wrapped on
   the zero-padded grid), the periodic compliance 2/(E*|q|) or a body's C(|q|), the periodic
   stiffness E*|q|/2 or 1/C(|q|), and
   the diagonal and row norms of the circulant behind them. */
#include "grid/gridimpl.h"

/* Real kernel in the local FFTW slab: free = Love coefficients at wrapped offsets (even in both
   directions, so its spectrum is real); transformed once to give the multiplier. */
PetscErrorCode AdhComplianceFreeMultiplier_Private(AdhComplianceCtx *c)
{
  fftw_complex *spec = (fftw_complex *)c->t->data;
  ptrdiff_t     r, i, k, ncomplex = c->t->local_n1 * c->t->n0;
  PetscReal     scale = 1.0 / ((PetscReal)c->t->n0 * (PetscReal)c->t->n1), lmin = PETSC_MAX_REAL;

  PetscFunctionBegin;
  PetscCall(PetscArrayzero(c->t->data, c->t->local_n0 * c->t->stride));
  for (r = 0; r < c->t->local_n0; r++) {
    ptrdiff_t row = c->t->local_0_start + r, dj = row <= c->Ny ? row : row - c->t->n0;
    for (i = 0; i < c->t->n1; i++) {
      ptrdiff_t di = i <= c->Nx ? i : i - c->t->n1;
      c->t->data[r * c->t->stride + i] = AdhLoveCoefficient(di * c->hx, dj * c->hy, c->hx, c->hy, c->Estar);
    }
  }
  fftw_execute(c->t->forward);
  for (k = 0; k < ncomplex; k++) {
    const ptrdiff_t k0 = c->t->serial ? k / c->t->local_n1 : k % c->t->n0, a = c->t->serial ? k % c->t->local_n1 : k / c->t->n0;
    if (k0 <= c->t->n0 / 2) c->multiplier[AdhMultiplierIndex(c, a, k0)] = spec[k][0] * scale;
    lmin = PetscMin(lmin, spec[k][0]);
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &lmin, 1, MPIU_REAL, MPIU_MIN, c->comm));
  /* K is a principal submatrix of this symmetric circulant, and so is every K_CC: by Cauchy
     interlacing the smallest circulant eigenvalue bounds theirs from below. */
  c->lambda_min      = PetscMax(lmin, 0.0);
  c->lambda_meanfree = c->lambda_min;
  PetscFunctionReturn(0);
}

/* periodic: u_q = 2/(E* |q|) p_q with q = 2 pi (kx/Lx, ky/Ly), or a body's symbol C(|q|); the
   mean (q = 0) is left to d. */
PetscErrorCode AdhCompliancePeriodicMultiplier_Private(AdhComplianceCtx *c)
{
  ptrdiff_t a, k0;
  PetscReal scale = 1.0 / ((PetscReal)c->t->n0 * (PetscReal)c->t->n1), lmin = PETSC_MAX_REAL;

  PetscFunctionBegin;
  for (a = 0; a < c->t->local_n1; a++) {
    const ptrdiff_t kx = c->t->local_1_start + a; /* 0 .. n1/2: r2c keeps half the x modes */
    for (k0 = 0; k0 <= c->t->n0 / 2; k0++) {
      const ptrdiff_t ky = k0;
      const PetscReal qx = 2.0 * PETSC_PI * kx / c->Lx, qy = 2.0 * PETSC_PI * ky / c->Ly;
      const PetscReal q  = PetscSqrtReal(qx * qx + qy * qy);
      const PetscReal C  = (kx == 0 && ky == 0) ? 0.0 : c->symbol ? c->symbol(c->symbol_ctx, q) : 2.0 / (c->Estar * q);
      c->multiplier[AdhMultiplierIndex(c, a, k0)] = C * scale;
      if (kx || ky) lmin = (C > 0 && !PetscIsInfOrNanReal(C)) ? PetscMin(lmin, C) : -1.0; /* a bad symbol: told by every rank below */
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &lmin, 1, MPIU_REAL, MPIU_MIN, c->comm));
  PetscCheck(lmin > 0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "The body's compliance symbol is not positive and finite at every wave number of the cell");
  /* The constant vector is in K's null space, so no positive bound holds for K itself; on
     mean-free vectors the smallest eigenvalue is the symbol at the largest wave number. */
  c->lambda_min      = 0.0;
  c->lambda_meanfree = lmin;
  PetscFunctionReturn(0);
}

/* The diagonal and the 2-norm of one row of the circulant behind the multiplier (translation
   invariance makes them one number each), from the half spectrum (modes kx and n1-kx, ky and
   n0-ky share a value): the diagonal is the mean of the symbol, the row norm by Parseval. Every
   row of K, and every part of one, is a part of such a row (free: the padded circulant holds
   every offset of the grid). No grid vector, no multiply. */
PetscErrorCode AdhComplianceRowStatistics_Private(AdhComplianceCtx *c)
{
  ptrdiff_t a, k0;
  PetscReal sum[2] = {0.0, 0.0};

  PetscFunctionBegin;
  for (a = 0; a < c->t->local_n1; a++) {
    const ptrdiff_t kx = c->t->local_1_start + a;
    const PetscReal wx = (kx == 0 || 2 * kx == c->t->n1) ? 1.0 : 2.0;
    for (k0 = 0; k0 <= c->t->n0 / 2; k0++) {
      const PetscReal wy = (k0 == 0 || 2 * k0 == c->t->n0) ? 1.0 : 2.0, m = c->multiplier[AdhMultiplierIndex(c, a, k0)];
      sum[0] += wx * wy * m;
      sum[1] += wx * wy * m * m;
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, 2, MPIU_REAL, MPIU_SUM, c->comm));
  c->diagonal = sum[0];
  c->rownorm  = PetscSqrtReal(sum[1] * (PetscReal)c->t->n0 * (PetscReal)c->t->n1);
  PetscFunctionReturn(0);
}

/* Stiffness E*|q|/2, the inverse of the periodic compliance symbol (or 1/C(|q|) of a body's
   symbol); the mean mode gets the value of the lowest nonzero wave number so the operator is
   positive definite. */
PetscErrorCode AdhComplianceStiffnessMultiplier_Private(AdhComplianceCtx *c)
{
  ptrdiff_t a, k0;
  PetscReal scale = 1.0 / ((PetscReal)c->t->n0 * (PetscReal)c->t->n1), qmin = 2.0 * PETSC_PI / PetscMax(c->Lx, c->Ly), lmin = PETSC_MAX_REAL;

  PetscFunctionBegin;
  for (a = 0; a < c->t->local_n1; a++) {
    const ptrdiff_t kx = c->t->local_1_start + a;
    for (k0 = 0; k0 <= c->t->n0 / 2; k0++) {
      const ptrdiff_t ky = k0;
      const PetscReal qx = 2.0 * PETSC_PI * kx / c->Lx, qy = 2.0 * PETSC_PI * ky / c->Ly;
      const PetscReal q  = (kx == 0 && ky == 0) ? qmin : PetscSqrtReal(qx * qx + qy * qy);
      if (c->symbol) {
        const PetscReal C = c->symbol(c->symbol_ctx, q), S = 1.0 / C;
        c->multiplier[AdhMultiplierIndex(c, a, k0)] = S * scale;
        lmin = (C > 0 && !PetscIsInfOrNanReal(C)) ? PetscMin(lmin, S) : -1.0;
      } else c->multiplier[AdhMultiplierIndex(c, a, k0)] = 0.5 * c->Estar * q * scale;
    }
  }
  /* a half-space's smallest is at qmin; a body's symbol need not fall with q everywhere */
  if (c->symbol) PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &lmin, 1, MPIU_REAL, MPIU_MIN, c->comm));
  PetscCheck(!c->symbol || lmin > 0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "The body's compliance symbol is not positive and finite at every wave number of the cell");
  c->lambda_min = c->symbol ? lmin : 0.5 * c->Estar * qmin;
  PetscFunctionReturn(0);
}
