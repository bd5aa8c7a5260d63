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

/*@
  AdhLoveCoefficient - The displacement at (x, y), relative to the centre of an hx x hy element carrying a unit uniform
  pressure, of a half-space of reduced modulus E* (Love's closed form, Johnson's Contact Mechanics eq. 3.25)

  Not Collective

  Input Parameters:
+ x     - the offset along x from the element's centre
. y     - the offset along y
. hx    - the element's size along x
. hy    - the element's size along y
- Estar - the reduced modulus E*

  Level: advanced

  Notes:
  The influence coefficient of the compliance: the centre of a loaded square of side h sinks 1.1222 p h / E*.

.seealso: `MatCreateAdhCompliance()`, `AdhChi()`
@*/
PetscReal AdhLoveCoefficient(PetscReal x, PetscReal y, PetscReal hx, PetscReal hy, PetscReal Estar)
{
  const PetscReal x1 = x - 0.5 * hx, x2 = x + 0.5 * hx, y1 = y - 0.5 * hy, y2 = y + 0.5 * hy;
  const PetscReal integral = RectanglePotential(x2, y2) - RectanglePotential(x1, y2) - RectanglePotential(x2, y1) + RectanglePotential(x1, y1);
  return integral / (PETSC_PI * Estar);
}

/*@
  AdhChi - The element self-energy factor chi of an hx x hy element: U_el = sigma^2 chi / E* (Pohrt and Popov 2015, eq. 11)

  Not Collective

  Input Parameters:
+ hx - the element's size along x
- hy - the element's size along y

  Level: advanced

.seealso: `AdhChiSquare()`, `AdhCriticalStress()`
@*/
PetscReal AdhChi(PetscReal hx, PetscReal hy)
{
  const PetscReal hb = PetscSqrtReal(hx * hx + hy * hy);
  return (hx * hx * hx + hy * hy * hy - hx * hx * hb - hy * hy * hb) / (3.0 * PETSC_PI) +
         hx * hy * (hx * PetscLogReal((hb + hy) / (hb - hy)) + hy * PetscLogReal((hb + hx) / (hb - hx))) / (2.0 * PETSC_PI);
}

/*@
  AdhChiSquare - The element self-energy factor of a square element of side h, chi = 0.473201 h^3 (Pohrt and Popov 2015,
  eq. 12)

  Not Collective

  Input Parameter:
. h - the element's side

  Level: advanced

.seealso: `AdhChi()`, `AdhCriticalStress()`
@*/
PetscReal AdhChiSquare(PetscReal h)
{
  const PetscReal s2 = PetscSqrtReal(2.0);
  return h * h * h * 2.0 / (3.0 * PETSC_PI) * (1.0 - s2 + 1.5 * PetscLogReal((s2 + 1.0) / (s2 - 1.0)));
}

/*@
  AdhCriticalStress - The mesh-dependent critical tensile stress of Pohrt and Popov's criterion,
  Sigma = sqrt(hx hy E* dgamma / chi) (eq. 13)

  Not Collective

  Input Parameters:
+ hx     - the element's size along x
. hy     - the element's size along y
. Estar  - the reduced modulus E*
- dgamma - the work of adhesion

  Level: intermediate

  Notes:
  Sigma ~ h^(-1/2), like the stress at distance h from a crack tip; dgamma = 0 gives 0 (no adhesion).

.seealso: `AdhChi()`, `AdhSolverGetCriticalStress()`, `ADHCRITERIONPOHRTPOPOV`
@*/
PetscReal AdhCriticalStress(PetscReal hx, PetscReal hy, PetscReal Estar, PetscReal dgamma)
{
  return PetscSqrtReal(hx * hy * Estar * dgamma / AdhChi(hx, hy));
}
