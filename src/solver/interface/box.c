/* Convolution on the bounding box of the contact set (free boundary).

   K_CC only couples points of the set, and the free-boundary kernel is translation invariant,
   so K_CC can be applied with a compliance on any window of the plane that holds the set: its
   zero-padded transform is sized by the set's bounding box, not by the domain. During pull-off
   the set shrinks, and so does the FFT work. Window sizes come from a coarse ladder
   (2^k x {1, 5/4, 3/2, 7/4}) and their operators are cached, so FFTW plans each size once.
   The Fourier preconditioner runs on the same window. The result is the same convolution; only
   rounding differs. */
#include "solver/solverimpl.h"

/* Smallest ladder size >= n. */
static PetscInt LadderSize(PetscInt n)
{
  static const PetscInt num[] = {4, 5, 6, 7};
  for (PetscInt base = 2;; base *= 2)
    for (int k = 0; k < 4; k++)
      if (base * num[k] >= n) return base * num[k];
}

static PetscErrorCode BoxGet(AdhSolver s, PetscInt bx, PetscInt by, AdhBox **box)
{
  AdhBox     *b;
  PetscMPIInt size;

  PetscFunctionBegin;
  for (PetscInt k = 0; k < s->nboxes; k++)
    if (s->boxes[k].bx == bx && s->boxes[k].by == by) {
      *box = &s->boxes[k];
      PetscFunctionReturn(0);
    }
  if (s->nboxes == s->maxboxes) {
    s->maxboxes = PetscMax(8, 2 * s->maxboxes);
    PetscCall(PetscRealloc(s->maxboxes * sizeof(AdhBox), &s->boxes));
  }
  b = &s->boxes[s->nboxes++];
  PetscCall(PetscMemzero(b, sizeof(*b)));
  b->bx = bx;
  b->by = by;
  PetscCall(AdhGridCreate(s->comm, &b->grid));
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)b->grid, s->prefix));
  b->grid->prefix = ((PetscObject)b->grid)->prefix;
  PetscCall(AdhGridSetSizes(b->grid, bx, by, bx * s->grid->hx, by * s->grid->hy));
  /* the solver grid's FFTW options, read once by its AdhGridSetFromOptions (a window reads none) */
  b->grid->opt_planner       = s->grid->opt_planner;
  b->grid->opt_timelimit     = s->grid->opt_timelimit;
  b->grid->opt_timelimit_set = s->grid->opt_timelimit_set;
  b->grid->opt_layout        = s->grid->opt_layout;
  /* On several ranks FFTW's measuring planner cannot be time-limited (see compliance.c), and
     unlimited measuring of every window costs more than it saves. */
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  if (size > 1) b->grid->fftw_effort = 0;
  else b->grid->fftw_timelimit = s->grid->fftw_timelimit;
  PetscCall(AdhGridSetUp(b->grid));
  PetscCall(s->eops.create_operators(s, b->grid, ADH_BOUNDARY_FREE, &b->K, &b->S));
  *box = b;
  PetscFunctionReturn(0);
}

/* Chooses the operator for the current set: a cached window (origin i0, j0) or the whole grid. */
PetscErrorCode AdhSolverSelectOperator_Private(AdhSolver s)
{
  PetscInt    n, k, Nx = s->grid->Nx, Ny = s->grid->Ny, rstart, ext[4] = {PETSC_MAX_INT, PETSC_MAX_INT, PETSC_MAX_INT, PETSC_MAX_INT};
  PetscMPIInt size;

  PetscFunctionBegin;
  s->box = NULL;
  s->box_i0 = s->box_j0 = 0;
  if (s->boundary != ADH_BOUNDARY_FREE || !s->use_box || !s->npoints) PetscFunctionReturn(0);
  PetscCall(VecGetLocalSize(s->p, &n));
  PetscCall(VecGetOwnershipRange(s->p, &rstart, NULL));
  /* ext = {min i, min j, -max i, -max j}, reduced with one MIN. */
  for (k = 0; k < n; k++)
    if (s->in_set[k]) {
      const PetscInt i = (rstart + k) % Nx, j = (rstart + k) / Nx;
      ext[0] = PetscMin(ext[0], i);
      ext[1] = PetscMin(ext[1], j);
      ext[2] = PetscMin(ext[2], -i);
      ext[3] = PetscMin(ext[3], -j);
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ext, 4, MPIU_INT, MPI_MIN, s->comm));
  {
    const PetscInt bx = PetscMin(LadderSize(-ext[2] - ext[0] + 1), Nx), by = PetscMin(LadderSize(-ext[3] - ext[1] + 1), Ny);
    PetscCallMPI(MPI_Comm_size(s->comm, &size));
    if ((bx == Nx && by == Ny) || by < size) PetscFunctionReturn(0);
    PetscCall(BoxGet(s, bx, by, &s->box));
    s->box_i0 = bx == Nx ? 0 : ext[0];
    s->box_j0 = by == Ny ? 0 : ext[1];
  }
  PetscFunctionReturn(0);
}

/* Maps global grid indices of the set to the numbering of the chosen operator's grid. */
PetscErrorCode AdhSolverOperatorIndices_Private(AdhSolver s, PetscInt count, const PetscInt *grid_idx, PetscInt *op_idx)
{
  PetscFunctionBegin;
  for (PetscInt k = 0; k < count; k++) {
    if (!s->box) op_idx[k] = grid_idx[k];
    else {
      const PetscInt i = grid_idx[k] % s->grid->Nx, j = grid_idx[k] / s->grid->Nx;
      op_idx[k] = (j - s->box_j0) * s->box->bx + (i - s->box_i0);
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverDestroyBoxes_Private(AdhSolver s)
{
  PetscFunctionBegin;
  for (PetscInt k = 0; k < s->nboxes; k++) {
    PetscCall(MatDestroy(&s->boxes[k].K));
    PetscCall(MatDestroy(&s->boxes[k].S));
    PetscCall(AdhGridDestroy(&s->boxes[k].grid));
  }
  PetscCall(PetscFree(s->boxes));
  s->nboxes = s->maxboxes = 0;
  s->box    = NULL;
  PetscFunctionReturn(0);
}

/* Compliance applications so far, on the whole grid and on every window. */
/* Compliance applications so far, and all FFT pairs (the compliance's and the preconditioner's,
   on the whole grid and on every window). */
PetscErrorCode AdhSolverMultCount_Private(AdhSolver s, PetscInt *count, PetscInt *ffts)
{
  PetscInt c, f;

  PetscFunctionBegin;
  PetscCall(MatAdhComplianceGetMultCount(s->K, count));
  PetscCall(MatAdhComplianceGetMultCount(s->S, &f));
  for (PetscInt k = 0; k < s->nboxes; k++) {
    PetscCall(MatAdhComplianceGetMultCount(s->boxes[k].K, &c));
    *count += c;
    PetscCall(MatAdhComplianceGetMultCount(s->boxes[k].S, &c));
    f += c;
  }
  PetscCall(AdhSolverMinimizeMultCount_Private(s, &c));
  *ffts = *count + f + c;
  PetscFunctionReturn(0);
}
