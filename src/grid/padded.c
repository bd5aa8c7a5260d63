/* The free boundary's operators on the zero-padded 2Ny x 2Nx grid itself, for a cohesive law's
   energy minimisation (src/solver/interface/minimize.c): the circulant C whose physical block is
   the free compliance K, and its inverse, the padded stiffness. C is positive definite (its
   smallest eigenvalue is about 0.58 h/E* at any size), and the smallest elastic energy of
   displacements u on the padded grid that equal u_N on the physical part is u_N^T K^-1 u_N / 2
   (the Schur complement of C^-1 is K^-1): a minimisation over the padded displacements, the
   outside ones free, is the free half-space's. Vectors live in the padded transform's slab
   layout, its local rows of the 2Ny, 2Nx entries a row: no scatter for a multiply; the moves to
   and from the grid's vectors take the physical rows' scatter of the compliance. */
#include "grid/gridimpl.h"

/* The padded rows of the vector into the transform's array (its stride), the multiplier, and back. */
static PetscErrorCode MatMult_Padded(Mat A, Vec x, Vec y)
{
  AdhComplianceCtx  *c;
  const PetscScalar *xa;
  PetscScalar       *ya;
  AdhTransform       t;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, &c));
  t = c->t;
  PetscCall(PetscLogEventBegin(ADH_ComplianceMult, A, x, y, 0));
  PetscCall(VecGetArrayRead(x, &xa));
  for (ptrdiff_t r = 0; r < t->local_n0; r++) {
    for (ptrdiff_t i = 0; i < t->n1; i++) t->data[r * t->stride + i] = PetscRealPart(xa[r * t->n1 + i]);
  }
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(AdhComplianceConvolve_Private(A, c, PETSC_FALSE));
  PetscCall(VecGetArrayWrite(y, &ya));
  for (ptrdiff_t r = 0; r < t->local_n0; r++) {
    for (ptrdiff_t i = 0; i < t->n1; i++) ya[r * t->n1 + i] = t->data[r * t->stride + i];
  }
  PetscCall(VecRestoreArrayWrite(y, &ya));
  PetscCall(PetscLogEventEnd(ADH_ComplianceMult, A, x, y, 0));
  PetscFunctionReturn(0);
}

/* The padded circulant of the free compliance K of a grid (inverse false) or its inverse, as a
   MATSHELL on the padded slab layout, sharing the grid's padded transform with K. */
PetscErrorCode AdhCreatePaddedOperator_Private(Mat K, PetscBool inverse, Mat *A)
{
  AdhComplianceCtx     *k, *c;
  AdhMeanComplianceCtx *mean;
  ptrdiff_t       nspec;

  PetscFunctionBegin;
  PetscCall(AdhComplianceGet_Private(K, "AdhCreatePaddedOperator_Private", PETSC_FALSE, &k, &mean));
  PetscCheck(k->kind == ADH_OPERATOR_FREE, k->comm, PETSC_ERR_ARG_WRONG, "The padded operators are the free compliance's");
  PetscCall(PetscNew(&c));
  *c      = *k;
  c->nmult = c->nmult_single = 0;
  c->single = PETSC_FALSE;
  c->t->refct++;
  nspec = c->t->local_n1 * c->nhalf;
  PetscCall(PetscMalloc1(PetscMax(nspec, 1), &c->multiplier));
  /* the inverse needs C positive definite: check it (about 0.58 h/E* at its smallest) */
  {
    PetscReal lmin = PETSC_MAX_REAL;
    for (ptrdiff_t k0 = 0; k0 < nspec; k0++) lmin = PetscMin(lmin, k->multiplier[k0]);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &lmin, 1, MPIU_REAL, MPIU_MIN, k->comm));
    PetscCheck(lmin > 0, k->comm, PETSC_ERR_PLIB, "The padded circulant of the free compliance is not positive definite (smallest symbol %g): the free boundary's energy minimisation needs it", (double)lmin);
  }
  /* the multiplier holds the symbol over n0 n1 (the transforms' scale): its inverse is scale^2/m */
  for (ptrdiff_t k0 = 0; k0 < nspec; k0++) {
    const PetscReal scale = 1.0 / ((PetscReal)c->t->n0 * (PetscReal)c->t->n1);
    c->multiplier[k0] = inverse ? scale * scale / k->multiplier[k0] : k->multiplier[k0];
  }
  PetscCall(MatCreateShell(c->comm, c->t->local_n0 * c->t->n1, c->t->local_n0 * c->t->n1, c->t->n0 * c->t->n1, c->t->n0 * c->t->n1, c, A));
  PetscCall(MatShellSetOperation(*A, MATOP_MULT, (void (*)(void))MatMult_Padded));
  PetscCall(MatShellSetOperation(*A, MATOP_MULT_TRANSPOSE, (void (*)(void))MatMult_Padded));
  PetscCall(MatShellSetOperation(*A, MATOP_DESTROY, (void (*)(void))AdhComplianceMatDestroy_Private));
  PetscCall(MatSetOption(*A, MAT_SPD, PETSC_TRUE));
  PetscCall(MatSetUp(*A));
  PetscFunctionReturn(0);
}

/* The multiplies a padded operator has done. */
PetscErrorCode AdhPaddedGetMultCount_Private(Mat A, PetscInt *count)
{
  AdhComplianceCtx *c;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, &c));
  *count = c->nmult;
  PetscFunctionReturn(0);
}

/* Which local entries of a padded vector are the grid's points (1) and which the padding (0). */
PetscErrorCode AdhPaddedGetPhysicalMask_Private(Mat A, char mask[])
{
  AdhComplianceCtx *c;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, &c));
  for (ptrdiff_t r = 0; r < c->t->local_n0; r++)
    for (ptrdiff_t i = 0; i < c->t->n1; i++) mask[r * c->t->n1 + i] = (char)(r < c->t->phys_rows && i < c->Nx);
  PetscFunctionReturn(0);
}

/* A grid vector x into the physical entries of the padded vector y (its padding left as it is),
   or (reverse) the physical entries of y into x. */
PetscErrorCode AdhPaddedMove_Private(Mat A, Vec x, Vec y, PetscBool reverse)
{
  AdhComplianceCtx  *c;
  AdhTransform t;
  PetscScalar *xa, *ya;
  Vec          phys;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, &c));
  t    = c->t;
  phys = t->toFFT ? t->xfft : x;
  if (t->toFFT && !reverse) {
    PetscCall(VecScatterBegin(t->toFFT, x, t->xfft, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(t->toFFT, x, t->xfft, INSERT_VALUES, SCATTER_FORWARD));
  }
  /* the source read-only (a grid vector's state stays), the destination written */
  if (reverse) {
    PetscCall(VecGetArray(phys, &xa));
    PetscCall(VecGetArrayRead(y, (const PetscScalar **)&ya));
  } else {
    PetscCall(VecGetArrayRead(phys, (const PetscScalar **)&xa));
    PetscCall(VecGetArray(y, &ya));
  }
  for (ptrdiff_t r = 0; r < t->phys_rows; r++)
    for (ptrdiff_t i = 0; i < c->Nx; i++) {
      if (reverse) xa[r * c->Nx + i] = ya[r * t->n1 + i];
      else ya[r * t->n1 + i] = xa[r * c->Nx + i];
    }
  if (reverse) {
    PetscCall(VecRestoreArrayRead(y, (const PetscScalar **)&ya));
    PetscCall(VecRestoreArray(phys, &xa));
  } else {
    PetscCall(VecRestoreArray(y, &ya));
    PetscCall(VecRestoreArrayRead(phys, (const PetscScalar **)&xa));
  }
  if (t->toFFT && reverse) {
    PetscCall(VecScatterBegin(t->toFFT, t->xfft, x, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecScatterEnd(t->toFFT, t->xfft, x, INSERT_VALUES, SCATTER_REVERSE));
  }
  PetscFunctionReturn(0);
}
