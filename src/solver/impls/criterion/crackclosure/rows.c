/* crack-closure's view of the grid beyond its rank: the rows of grid vectors (and of the contact
   set) within the averaging window's reach, fetched from the ranks that own them. */
#include "crackclosureimpl.h"

/* The rows this rank looks at of grid vector v: the other ranks' rows fetched into f's buffer;
   v itself must not change while they are in use. */
PetscErrorCode AdhCrackClosureFetchRows_Private(CrackClosure *cc, Vec v, FetchedRows *f)
{
  const PetscScalar *va;

  PetscFunctionBegin;
  f->v = v;
  PetscCall(VecGetArrayRead(v, &va));
  PetscCall(PetscSFBcastBegin(cc->fetch, cc->row_scalars, va, f->far, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(cc->fetch, cc->row_scalars, va, f->far, MPI_REPLACE));
  PetscCall(VecRestoreArrayRead(v, &va));
  PetscFunctionReturn(0);
}

/* The contact set (s->in_set) as the openings were computed: a copy of the rank's own points and
   the other ranks' rows this rank looks at. It stays as it was when the detach test goes on to
   griffith's limits after letting points go (-adh_cascade_apart): those points keep their pressure
   for the limits, as in the state just solved. */
PetscErrorCode AdhCrackClosureFetchSetRows_Private(AdhSolver s, CrackClosure *cc)
{
  PetscFunctionBegin;
  PetscCall(PetscArraycpy(cc->set_before, s->in_set, s->nlocal));
  PetscCall(PetscSFBcastBegin(cc->fetch, cc->row_flags, cc->set_before, cc->far_set, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(cc->fetch, cc->row_flags, cc->set_before, cc->far_set, MPI_REPLACE));
  PetscFunctionReturn(0);
}

/* Those rows: rows[b][i] nonzero when (i, b) was in the set, as AdhCrackClosureGetRows_Private gives a vector's. */
PetscErrorCode AdhCrackClosureGetSetRows_Private(CrackClosure *cc, const char ***rows)
{
  PetscFunctionBegin;
  for (PetscInt r = 0; r < cc->gym; r++) cc->set_store[r] = cc->rowmap[r] >= 0 ? cc->set_before + cc->rowmap[r] * cc->nx : cc->far_set + (-1 - cc->rowmap[r]) * cc->nx;
  *rows = (const char **)(cc->set_store - cc->gys);
  PetscFunctionReturn(0);
}

/* Whether the profile has points without a face (h = PETSC_INFINITY): then the openings' rows
   need u there, kept in faceless (a grid vector only such a profile pays for). */
PetscErrorCode AdhCrackClosureEnsureFaceless_Private(AdhSolver s, CrackClosure *cc)
{
  const PetscScalar *ha;
  PetscBool          any = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(s->h, &ha));
  for (PetscInt k = 0; k < s->nlocal && !any; k++) any = (PetscBool)(PetscRealPart(ha[k]) >= PETSC_INFINITY);
  PetscCall(VecRestoreArrayRead(s->h, &ha));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &any, 1, MPIU_BOOL, MPI_LOR, s->comm));
  if (any && !cc->faceless) PetscCall(VecDuplicate(s->h, &cc->faceless));
  if (!any) PetscCall(VecDestroy(&cc->faceless));
  PetscFunctionReturn(0);
}

/* The fetched rows of f: rows[b] is row b of the grid (gys <= b < gys + gym), as DMDA gives them. */
PetscErrorCode AdhCrackClosureGetRows_Private(CrackClosure *cc, FetchedRows *f, const PetscScalar ***rows)
{
  const PetscInt nx = cc->nx;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(f->v, &f->own));
  for (PetscInt r = 0; r < cc->gym; r++) f->store[r] = cc->rowmap[r] >= 0 ? (PetscScalar *)f->own + cc->rowmap[r] * nx : f->far + (-1 - cc->rowmap[r]) * nx;
  *rows = (const PetscScalar **)(f->store - cc->gys);
  PetscFunctionReturn(0);
}

PetscErrorCode AdhCrackClosureRestoreRows_Private(FetchedRows *f, const PetscScalar ***rows)
{
  PetscFunctionBegin;
  PetscCall(VecRestoreArrayRead(f->v, &f->own));
  *rows = NULL;
  PetscFunctionReturn(0);
}
