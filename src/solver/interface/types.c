/* What the solver does alike for the types of its four kinds (elastic body, criterion, control, predictor):
   set a type, read a type's options in a -help group of its own, and read the options of the
   registered types it does not have. The kinds' registries are in elastic.c, criterion.c,
   control.c and predictor.c, the built-in types' registration in impls/register.c. */
#include "solver/solverimpl.h"

PetscErrorCode AdhSolverSetType_Private(AdhSolver s, AdhRegistry *reg, char current[64], AdhTypeOps *ops, size_t size, const char type[], PetscBool fixed)
{
  PetscErrorCode (*create)(AdhSolver) = NULL;
  PetscBool same;

  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  PetscCall(PetscStrcmp(current, type, &same));
  if (same) PetscFunctionReturn(0);
  PetscCall(AdhRegistryFind_Private(s->comm, reg, type, (PetscVoidFunction *)&create));
  PetscCheck(!fixed || !s->setup, s->comm, PETSC_ERR_ORDER, "%s: the %s cannot change after set-up", reg->option, reg->what);
  if (ops->destroy) PetscCall(ops->destroy(s));
  PetscCall(PetscMemzero(ops, size)); /* the kind's ops: the AdhTypeOps first, then the kind's own and its data */
  current[0] = 0;                      /* no type, should its create fail */
  PetscCall(create(s));
  PetscCall(PetscStrncpy(current, type, 64));
  if (s->setup && ops->setup) PetscCall(ops->setup(s));
  PetscFunctionReturn(0);
}

/* The group's title: the kind, the type, and the option that chooses it. */
static PetscErrorCode GroupTitle(AdhRegistry *reg, const char type[], char title[], size_t len)
{
  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(title, len, "adhbem %s %s (%s %s)", reg->what, type, reg->option, type));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverTypeSetFromOptions_Private(AdhSolver s, AdhRegistry *reg, const char type[], AdhTypeOps *ops)
{
  char title[256];

  PetscFunctionBegin;
  if (!ops->setfromoptions) PetscFunctionReturn(0);
  PetscCall(GroupTitle(reg, type, title, sizeof(title)));
  PetscOptionsBegin(s->comm, s->prefix, title, "AdhSolver");
  PetscCall(ops->setfromoptions(s, PetscOptionsObject));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/* A scratch solver on the same communicator and prefix takes each registered type in turn and
   reads its options: under -help they are printed in their groups (a group is printed once per
   prefix, so those of the solver's own types are not repeated), and PETSc marks them used, so
   that the check of misspelled options at set-up passes them. A value out of range is refused as
   it would be for the type in use. */
PetscErrorCode AdhSolverReadTypesOptions_Private(AdhSolver s)
{
  AdhSolver scratch;

  PetscFunctionBegin;
  PetscCall(AdhSolverCreate(s->comm, &scratch));
  PetscCall(AdhSolverSetOptionsPrefix(scratch, s->prefix));
  /* the kinds' setters, in the order of AdhSolverGetTypeOps_Private */
  PetscErrorCode (*const set[ADH_NUM_KINDS])(AdhSolver, const char[]) = {AdhSolverSetElasticType, AdhSolverSetCriterionType, AdhSolverSetControlType, AdhSolverSetPredictorType};
  for (PetscInt k = 0; k < ADH_NUM_KINDS; k++) {
    AdhRegistry *regs[ADH_NUM_KINDS];
    AdhTypeOps  *ops[ADH_NUM_KINDS];
    const char **names;
    PetscInt     n;

    AdhSolverGetTypeOps_Private(scratch, ops, regs, NULL);
    PetscCall(AdhRegistryGetNames_Private(regs[k], &n, &names));
    for (PetscInt t = 0; t < n; t++) {
      PetscCall(set[k](scratch, names[t]));
      PetscCall(AdhSolverTypeSetFromOptions_Private(scratch, regs[k], names[t], ops[k]));
    }
    PetscCall(PetscFree(names));
  }
  PetscCall(AdhSolverDestroy(&scratch));
  PetscFunctionReturn(0);
}
