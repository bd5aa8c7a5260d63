/* Detachment criterion, a registered type (-adh_criterion): which points of the contact set let
   go after a solve. The types are in impls/criterion/, one file each, listed in solverregis.c;
   each fills in AdhCriterionOps (solverimpl.h). Both reduce to non-adhesive contact (p < 0 lets
   go) when dgamma = 0.

   pohrt-popov:   the paper's rule, p < -Sigma (impls/criterion/pohrtpopov.c).
   crack-closure: the contact edge's energy release rate by virtual crack closure, averaged along
                  the edge, against dgamma (impls/criterion/crackclosure.c). */
#include "solver/solverimpl.h"

static PetscFunctionList AdhCriterionList = NULL;

PetscErrorCode AdhCriterionRegister(const char name[], PetscErrorCode (*create)(AdhSolver))
{
  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  PetscCall(PetscFunctionListAdd(&AdhCriterionList, name, create));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhCriterionDestroyList_Private(void)
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListDestroy(&AdhCriterionList));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhCriterionGetList_Private(PetscFunctionList *list)
{
  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  *list = AdhCriterionList;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverSetCriterionType(AdhSolver s, AdhCriterionType type)
{
  PetscErrorCode (*create)(AdhSolver);
  PetscBool same;

  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  PetscCall(PetscStrcmp(s->criterion_type, type, &same));
  if (same) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListFind(AdhCriterionList, type, &create));
  if (!create) {
    char names[256];
    PetscCall(AdhFunctionListNames_Private(AdhCriterionList, names, sizeof(names)));
    SETERRQ(s->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "-adh_criterion: unknown detachment criterion '%s' (%s)", type, names);
  }
  PetscCheck(!s->setup, s->comm, PETSC_ERR_ORDER, "-adh_criterion: the detachment criterion cannot change after set-up");
  if (s->crops.destroy) PetscCall(s->crops.destroy(s));
  PetscCall(PetscMemzero(&s->crops, sizeof(s->crops)));
  PetscCall(create(s));
  PetscCall(PetscStrncpy(s->criterion_type, type, sizeof(s->criterion_type)));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetCriterionType(AdhSolver s, AdhCriterionType *type)
{
  PetscFunctionBegin;
  *type = s->criterion_type;
  PetscFunctionReturn(0);
}

/* Remove every point of the set that the criterion lets go. */
PetscErrorCode AdhSolverDetach_Private(AdhSolver s, PetscInt *removed)
{
  PetscFunctionBegin;
  s->gap_current          = PETSC_FALSE;
  s->attach_limit_current = PETSC_FALSE;
  PetscCall(PetscLogEventBegin(ADH_DetachTest, 0, 0, 0, 0));
  PetscCall(s->crops.evaluate(s, PETSC_TRUE, removed, NULL));
  PetscCall(PetscLogEventEnd(ADH_DetachTest, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* How close the current state is to letting go: the criterion's largest demand over its limit on
   the set (1: a point is about to let go). */
PetscErrorCode AdhSolverDetachRatio_Private(AdhSolver s, PetscReal *ratio)
{
  PetscFunctionBegin;
  PetscCall(s->crops.evaluate(s, PETSC_FALSE, NULL, ratio));
  PetscFunctionReturn(0);
}
