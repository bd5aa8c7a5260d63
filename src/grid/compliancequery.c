/* What a compliance operator tells about itself: bounds on its eigenvalues and rows, the grid behind
   it, and its multiply counts (the queries of compliance.c's MatShells). */
#include "grid/gridimpl.h"

/*@
  MatAdhComplianceGetLambdaMin - Gets a lower bound on the smallest eigenvalue of a compliance K and of each submatrix K_CC

  Not Collective

  Input Parameter:
. K - a compliance or stiffness

  Output Parameter:
. lambda_min - the bound

  Notes:
  Free boundary: the smallest eigenvalue of the symmetric circulant on the zero-padded grid (zero if it is negative), of which K
  and every K_CC are principal submatrices (Cauchy interlacing). Periodic: zero, since the constant vector is in K's null space;
  `MatAdhComplianceGetSetLambdaMin()` gives a positive bound for sets smaller than the grid. Stiffness: E* pi/max(Lx, Ly), its
  smallest eigenvalue.

  K must come from `MatCreateAdhCompliance()` or `MatCreateAdhPeriodicStiffness()`; another Mat is an error, and so is a
  `MatCreateAdhMeanCompliance()` wrapper, whose bounds are not those of the compliance it wraps.

  Level: advanced

.seealso: `MatAdhComplianceGetSetLambdaMin()`, `MatCreateAdhCompliance()`, `MatAdhComplianceGetRowNormBound()`
@*/
PetscErrorCode MatAdhComplianceGetLambdaMin(Mat K, PetscReal *lambda_min)
{
  AdhComplianceCtx     *c;
  AdhMeanComplianceCtx *mean;

  PetscFunctionBegin;
  PetscValidRealPointer(lambda_min, 2);
  PetscCall(AdhComplianceGet_Private(K, "MatAdhComplianceGetLambdaMin", PETSC_FALSE, &c, &mean));
  *lambda_min = c->lambda_min;
  PetscFunctionReturn(0);
}

/*@
  MatAdhComplianceGetSetLambdaMin - Gets a lower bound on the smallest eigenvalue of K_CC for any set C of m grid points

  Not Collective

  Input Parameters:
+ K - a compliance or stiffness
- m - the number of points in the set, at most N = Nx Ny

  Output Parameter:
. lambda_min - the bound

  Notes:
  Free boundary (and stiffness): the bound of `MatAdhComplianceGetLambdaMin()`, by Cauchy interlacing. Periodic: a vector v that
  vanishes off C has a mean component of norm |sum v|/sqrt(N) <= sqrt(m/N) |v|, and K is at least lambda_meanfree (its
  smallest eigenvalue on mean-free vectors, the symbol at the largest wave number) on the rest, so
  v^T K v >= lambda_meanfree (1 - m/N) |v|^2. The bound shrinks to zero as C fills the cell, where K_CC becomes singular.

  K must come from `MatCreateAdhCompliance()` or `MatCreateAdhPeriodicStiffness()`; another Mat is an error, and so is a
  `MatCreateAdhMeanCompliance()` wrapper, whose bounds are not those of the compliance it wraps.

  Level: advanced

.seealso: `MatAdhComplianceGetLambdaMin()`, `MatCreateAdhCompliance()`, `MatCreateAdhMeanCompliance()`
@*/
PetscErrorCode MatAdhComplianceGetSetLambdaMin(Mat K, PetscInt m, PetscReal *lambda_min)
{
  AdhComplianceCtx     *c;
  AdhMeanComplianceCtx *mean;

  PetscFunctionBegin;
  PetscValidRealPointer(lambda_min, 3);
  PetscCall(AdhComplianceGet_Private(K, "MatAdhComplianceGetSetLambdaMin", PETSC_FALSE, &c, &mean));
  if (c->kind == ADH_OPERATOR_PERIODIC) *lambda_min = c->lambda_meanfree * PetscMax(0.0, 1.0 - (PetscReal)m / ((PetscReal)c->Nx * (PetscReal)c->Ny));
  else *lambda_min = c->lambda_min;
  PetscFunctionReturn(0);
}

/*@
  MatAdhComplianceGetGridSize - Gets the size of the grid behind a compliance

  Not Collective

  Input Parameter:
. K - a compliance or stiffness

  Output Parameters:
+ Nx - the number of points per row (or `NULL`)
- Ny - the number of rows (or `NULL`)

  Notes:
  K must come from `MatCreateAdhCompliance()`, `MatCreateAdhPeriodicStiffness()` or `MatCreateAdhMeanCompliance()` (then
  the answer is the wrapped compliance's); another Mat is an error.

  Level: advanced

.seealso: `MatCreateAdhCompliance()`, `AdhGridSetSizes()`
@*/
PetscErrorCode MatAdhComplianceGetGridSize(Mat K, PetscInt *Nx, PetscInt *Ny)
{
  AdhComplianceCtx     *c;
  AdhMeanComplianceCtx *mean;

  PetscFunctionBegin;
  PetscCall(AdhComplianceGet_Private(K, "MatAdhComplianceGetGridSize", PETSC_TRUE, &c, &mean));
  if (Nx) *Nx = c->Nx;
  if (Ny) *Ny = c->Ny;
  PetscFunctionReturn(0);
}

/*@
  MatAdhComplianceGetRowNormBound - Gets an upper bound on the 2-norm of every row of a compliance, max_k |K e_k|

  Not Collective

  Input Parameter:
. K - a compliance or stiffness

  Output Parameter:
. rho - the bound

  Notes:
  A change dp of the pressure changes every displacement by at most rho |dp|_2. rho is the 2-norm of a row of the circulant
  behind the multiplier (all its rows have the same norm), from the spectrum by Parseval, without a multiply; every row of K, and
  every part of one, is part of such a row (free boundary: the zero-padded circulant holds every offset of the grid).

  K must come from `MatCreateAdhCompliance()` or `MatCreateAdhPeriodicStiffness()`; another Mat is an error, and so is a
  `MatCreateAdhMeanCompliance()` wrapper, whose bounds are not those of the compliance it wraps.

  Level: advanced

.seealso: `MatAdhComplianceGetLambdaMin()`, `MatCreateAdhCompliance()`
@*/
PetscErrorCode MatAdhComplianceGetRowNormBound(Mat K, PetscReal *rho)
{
  AdhComplianceCtx     *c;
  AdhMeanComplianceCtx *mean;

  PetscFunctionBegin;
  PetscValidRealPointer(rho, 2);
  PetscCall(AdhComplianceGet_Private(K, "MatAdhComplianceGetRowNormBound", PETSC_FALSE, &c, &mean));
  *rho = c->rownorm;
  PetscFunctionReturn(0);
}

/*@
  MatAdhComplianceGetMultCount - Gets the number of multiplies (FFT pairs) an operator has applied so far

  Not Collective

  Input Parameter:
. K - a compliance or stiffness

  Output Parameter:
. count - the number of multiplies

  Notes:
  It counts `MatMult()`, `MatMultTranspose()` and `MatAdhComplianceMultOnSet()`, in double and in single precision, since the
  operator was created.

  K must come from `MatCreateAdhCompliance()`, `MatCreateAdhPeriodicStiffness()` or `MatCreateAdhMeanCompliance()` (then
  the answer is the wrapped compliance's); another Mat is an error.

  Level: intermediate

.seealso: `MatAdhComplianceGetSingleMultCount()`, `MatCreateAdhCompliance()`
@*/
PetscErrorCode MatAdhComplianceGetMultCount(Mat K, PetscInt *count)
{
  AdhComplianceCtx     *c;
  AdhMeanComplianceCtx *mean;

  PetscFunctionBegin;
  PetscValidIntPointer(count, 2);
  PetscCall(AdhComplianceGet_Private(K, "MatAdhComplianceGetMultCount", PETSC_TRUE, &c, &mean));
  *count = c->nmult;
  PetscFunctionReturn(0);
}

/*@
  MatAdhComplianceGetSingleMultCount - Gets how many of an operator's multiplies ran in single precision

  Not Collective

  Input Parameter:
. K - a compliance or stiffness

  Output Parameter:
. count - the number of multiplies in single precision (`MatAdhComplianceSetSinglePrecision()`)

  Notes:
  They are counted in `MatAdhComplianceGetMultCount()` too.

  K must come from `MatCreateAdhCompliance()`, `MatCreateAdhPeriodicStiffness()` or `MatCreateAdhMeanCompliance()` (then
  the answer is the wrapped compliance's); another Mat is an error.

  Level: advanced

.seealso: `MatAdhComplianceGetMultCount()`, `MatAdhComplianceSetSinglePrecision()`
@*/
PetscErrorCode MatAdhComplianceGetSingleMultCount(Mat K, PetscInt *count)
{
  AdhComplianceCtx     *c;
  AdhMeanComplianceCtx *mean;

  PetscFunctionBegin;
  PetscValidIntPointer(count, 2);
  PetscCall(AdhComplianceGet_Private(K, "MatAdhComplianceGetSingleMultCount", PETSC_TRUE, &c, &mean));
  *count = c->nmult_single;
  PetscFunctionReturn(0);
}
