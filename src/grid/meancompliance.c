/* The periodic compliance with a finite compliance c0 on the mean mode, K + c0 (1 1^T)/N (force
   control on a periodic cell): a MatShell around the compliance. */
#include "grid/gridimpl.h"

PetscErrorCode MatMult_AdhMeanCompliance_Private(Mat A, Vec x, Vec y)
{
  AdhMeanComplianceCtx *m;
  PetscScalar     sum;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, &m));
  PetscCall(VecSum(x, &sum));
  PetscCall(MatMult(m->K, x, y));
  PetscCall(VecShift(y, m->c0 * sum / m->N));
  PetscFunctionReturn(0);
}

static PetscErrorCode MatDestroy_MeanCompliance(Mat A)
{
  AdhMeanComplianceCtx *m;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, &m));
  PetscCall(MatDestroy(&m->K));
  PetscCall(PetscFree(m));
  PetscFunctionReturn(0);
}

/*@
  MatCreateAdhMeanCompliance - Creates K + c0 (1 1^T)/N, a periodic compliance whose mean mode has the compliance c0

  Collective

  Input Parameters:
+ K  - a periodic compliance from `MatCreateAdhCompliance()`
- c0 - the compliance of the mean mode, > 0

  Output Parameter:
. A - the operator, a `MATSHELL`

  Notes:
  With c0 > 0 every K_CC is positive definite, the whole cell included; the eigenvalues of A are K's on mean-free vectors and
  c0. Under force control the mean pressure is given, so the mean displacement can be carried by any c0 and subtracted
  afterwards.

  A keeps a reference to K, released when A is destroyed, has K's layout, provides `MatMult()` only, and is marked SPD.
  `MatAdhComplianceHasDirectLayout()`, `MatAdhComplianceSetSinglePrecision()` and `MatAdhComplianceMultOnSet()` accept it (they
  act on K, the last adding the mean term); the other MatAdhComplianceGet functions need K itself. c0 must be positive and
  finite (`PETSC_ERR_ARG_OUTOFRANGE`); the kind of K is not checked.

  Level: advanced

.seealso: `MatCreateAdhCompliance()`, `MatAdhComplianceMultOnSet()`, `MatAdhComplianceGetSetLambdaMin()`
@*/
PetscErrorCode MatCreateAdhMeanCompliance(Mat K, PetscReal c0, Mat *A)
{
  AdhMeanComplianceCtx *m;
  PetscInt              nloc, N;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(K, MAT_CLASSID, 1);
  PetscValidLogicalCollectiveReal(K, c0, 2);
  PetscValidPointer(A, 3);
  PetscCheck(c0 > 0 && !PetscIsInfOrNanReal(c0), PetscObjectComm((PetscObject)K), PETSC_ERR_ARG_OUTOFRANGE, "MatCreateAdhMeanCompliance: the mean mode's compliance c0 must be positive and finite, got %g", (double)c0);
  PetscCall(PetscNew(&m));
  PetscCall(PetscObjectReference((PetscObject)K));
  m->K  = K;
  m->c0 = c0;
  PetscCall(MatGetLocalSize(K, &nloc, NULL));
  PetscCall(MatGetSize(K, &N, NULL));
  m->N = (PetscReal)N;
  PetscCall(MatCreateShell(PetscObjectComm((PetscObject)K), nloc, nloc, N, N, m, A));
  PetscCall(MatShellSetOperation(*A, MATOP_MULT, (void (*)(void))MatMult_AdhMeanCompliance_Private));
  PetscCall(MatShellSetOperation(*A, MATOP_DESTROY, (void (*)(void))MatDestroy_MeanCompliance));
  PetscCall(MatSetOption(*A, MAT_SPD, PETSC_TRUE));
  PetscCall(MatSetUp(*A));
  PetscFunctionReturn(0);
}
