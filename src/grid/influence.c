/* Closed-form integrals over one uniformly loaded rectangular element. */
#include "adhbem.h"

/* Antiderivative of 1/sqrt(x^2+y^2) in x and y, up to terms in x alone or y alone, which cancel
   in the corner sum below. Written with asinh so it is odd in each argument and has no 0*log(0). */
static PetscReal RectanglePotential(PetscReal x, PetscReal y)
{
  PetscReal v = 0.0;
  if (x != 0.0) v += x * PetscAsinhReal(y / PetscAbsReal(x));
  if (y != 0.0) v += y * PetscAsinhReal(x / PetscAbsReal(y));
  return v;
}

PetscReal AdhLoveCoefficient(PetscReal x, PetscReal y, PetscReal hx, PetscReal hy, PetscReal Estar)
{
  const PetscReal x1 = x - 0.5 * hx, x2 = x + 0.5 * hx, y1 = y - 0.5 * hy, y2 = y + 0.5 * hy;
  const PetscReal integral = RectanglePotential(x2, y2) - RectanglePotential(x1, y2) - RectanglePotential(x2, y1) + RectanglePotential(x1, y1);
  return integral / (PETSC_PI * Estar);
}

PetscReal AdhChi(PetscReal hx, PetscReal hy)
{
  const PetscReal hb = PetscSqrtReal(hx * hx + hy * hy);
  return (hx * hx * hx + hy * hy * hy - hx * hx * hb - hy * hy * hb) / (3.0 * PETSC_PI) +
         hx * hy * (hx * PetscLogReal((hb + hy) / (hb - hy)) + hy * PetscLogReal((hb + hx) / (hb - hx))) / (2.0 * PETSC_PI);
}

PetscReal AdhChiSquare(PetscReal h)
{
  const PetscReal s2 = PetscSqrtReal(2.0);
  return h * h * h * 2.0 / (3.0 * PETSC_PI) * (1.0 - s2 + 1.5 * PetscLogReal((s2 + 1.0) / (s2 - 1.0)));
}

PetscReal AdhCriticalStress(PetscReal hx, PetscReal hy, PetscReal Estar, PetscReal dgamma)
{
  return PetscSqrtReal(hx * hy * Estar * dgamma / AdhChi(hx, hy));
}
