/* The contact set as the solver holds it: its IS and local offsets, K restricted to it (a MatShell
   applying R K R^T on the grid in use), and the empty set. */
#include "solver/solverimpl.h"

/* y = R A R^T x for an operator A on the grid in use (the window or the whole grid), R the
   restriction to n local points (their offsets in the grid's rows: the set, or a local solve's
   window, -adh_cascade_local): spread the values onto the grid, apply A, gather them back. K_CC
   uses the compliance, the preconditioner the stiffness; they share the scatter. Where the
   operators' transforms use the grid's own rows (a periodic grid), the values go straight into
   the transform: no grid vectors, no scatter. */
PetscErrorCode AdhSolverApplyRestricted_Private(AdhSolver s, Mat A, PetscInt n, const PetscInt local[], VecScatter scatter, Vec x, Vec y)
{
  PetscFunctionBegin;
  if (s->direct_set) {
    PetscCall(MatAdhComplianceMultOnSet(A, n, local, x, y));
    PetscFunctionReturn(0);
  }
  PetscCall(VecSet(s->op_in, 0.0));
  PetscCall(VecScatterBegin(scatter, x, s->op_in, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter, x, s->op_in, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(MatMult(A, s->op_in, s->op_out));
  PetscCall(VecScatterBegin(scatter, s->op_out, y, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(scatter, s->op_out, y, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

/* y = R A R^T x on the contact set. */
PetscErrorCode AdhSolverApplyOnSet_Private(AdhSolver s, Mat A, Vec x, Vec y)
{
  PetscFunctionBegin;
  PetscCall(AdhSolverApplyRestricted_Private(s, A, s->nset_local, s->set_local, s->set_scatter, x, y));
  PetscFunctionReturn(0);
}

static PetscErrorCode MatMult_Restricted(Mat Kcc, Vec x, Vec y)
{
  AdhSolver s;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(Kcc, &s));
  PetscCall(AdhSolverApplyOnSet_Private(s, s->Kop, x, y));
  PetscFunctionReturn(0);
}

/* The IS of the set (global indices of the local points in it), K restricted to it (on the
   bounding-box window when there is one), and the scatter between the two. */
PetscErrorCode AdhSolverRebuildSet_Private(AdhSolver s)
{
  PetscInt nlocal, rstart, count = 0, k, *idx, *opidx;
  Mat      Kop, Sop;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(s->p, &nlocal));
  PetscCall(VecGetOwnershipRange(s->p, &rstart, NULL));
  for (k = 0; k < nlocal; k++) count += s->in_set[k] ? 1 : 0;
  PetscCall(PetscMalloc1(count, &idx));
  PetscCall(PetscMalloc1(count, &opidx));
  s->set_version++;
  PetscCall(PetscFree(s->set_local));
  PetscCall(PetscFree(s->thrC)); /* made by the solve where the critical stress varies */
  PetscCall(PetscMalloc1(count + 1, &s->set_local));
  for (k = 0, count = 0; k < nlocal; k++)
    if (s->in_set[k]) {
      s->set_local[count] = k;
      idx[count++]        = rstart + k;
    }
  s->nset_local = count;
  PetscCall(ISDestroy(&s->contact));
  PetscCall(ISCreateGeneral(s->comm, count, idx, PETSC_OWN_POINTER, &s->contact));
  PetscCall(PetscObjectSetName((PetscObject)s->contact, "contact_set"));
  PetscCall(ISGetSize(s->contact, &s->npoints));

  PetscCall(AdhSolverSelectOperator_Private(s));
  Kop = s->box ? s->box->K : s->Kcontrol ? s->Kcontrol : s->K;
  Sop = s->box ? s->box->S : s->S;
  if (Kop != s->Kop || Sop != s->Sop) {
    PetscBool kdirect = PETSC_FALSE, sdirect = PETSC_FALSE;
    PetscCall(VecDestroy(&s->op_in));
    PetscCall(VecDestroy(&s->op_out));
    /* the direct path takes the set's offsets in the grid's rows, so not on a window */
    if (!s->box) {
      PetscCall(MatAdhComplianceHasDirectLayout(Kop, &kdirect));
      PetscCall(MatAdhComplianceHasDirectLayout(Sop, &sdirect));
    }
    s->direct_set = (PetscBool)(kdirect && sdirect);
    if (!s->direct_set) PetscCall(MatCreateVecs(Kop, &s->op_in, &s->op_out));
    s->Kop = Kop;
    s->Sop = Sop;
  }
  PetscCall(ISDestroy(&s->contact_op));
  if (!s->direct_set) {
    PetscCall(AdhSolverOperatorIndices_Private(s, count, idx, opidx));
    PetscCall(ISCreateGeneral(s->comm, count, opidx, PETSC_OWN_POINTER, &s->contact_op));
  } else PetscCall(PetscFree(opidx));

  /* A lower bound on the eigenvalues of K_CC for the certified stop (zero: no certification). */
  if (Kop == s->Kcontrol) {
    PetscCall(MatAdhComplianceGetSetLambdaMin(s->K, 0, &s->lambda_set));
    s->lambda_set = PetscMin(s->lambda_set, s->Kcontrol_lambda);
  } else PetscCall(MatAdhComplianceGetSetLambdaMin(s->K, s->npoints, &s->lambda_set));

  PetscCall(MatDestroy(&s->Kcc));
  PetscCall(VecScatterDestroy(&s->set_scatter));
  PetscCall(VecDestroy(&s->pC));
  PetscCall(VecDestroy(&s->bC));
  /* KSP keeps work vectors of the old size; let it rebuild them for the new set. */
  if (s->ksp) PetscCall(KSPReset(s->ksp));
  if (s->npoints) {
    PetscCall(VecCreateMPI(s->comm, count, s->npoints, &s->pC));
    PetscCall(VecDuplicate(s->pC, &s->bC));
    if (!s->direct_set) PetscCall(VecScatterCreate(s->pC, NULL, s->op_in, s->contact_op, &s->set_scatter));
    PetscCall(MatCreateShell(s->comm, count, count, s->npoints, s->npoints, s, &s->Kcc));
    PetscCall(MatShellSetOperation(s->Kcc, MATOP_MULT, (void (*)(void))MatMult_Restricted));
    PetscCall(MatSetOption(s->Kcc, MAT_SPD, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

/* Nothing in contact: an empty set, no pressure. */
PetscErrorCode AdhSolverClearContact_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(PetscArrayzero(s->in_set, s->nlocal));
  PetscCall(VecSet(s->p, 0.0));
  if (s->set_response) PetscCall(VecSet(s->set_response, 0.0));
  s->pulled_off = PETSC_FALSE;
  PetscCall(AdhSolverRebuildSet_Private(s));
  PetscFunctionReturn(0);
}
