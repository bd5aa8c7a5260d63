/* A registry of the types of one kind (the solver's criteria, load controls and predictors): the
   names and the functions that create them, found by name with one error that names the option
   and lists what is registered. One helper for every kind, so that their Register and SetType
   functions check alike. */
#include "sys/sysimpl.h"

PetscErrorCode AdhRegistryAdd_Private(AdhRegistry *reg, const char name[], PetscVoidFunction create)
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListAdd(&reg->list, name, create));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhRegistryGetNames_Private(AdhRegistry *reg, PetscInt *n, const char ***names)
{
  int m = 0, total;

  PetscFunctionBegin;
  PetscCall(PetscFunctionListGet(reg->list, names, &total));
  for (int k = 0; k < total; k++) /* PetscFunctionListGet counts a closing NULL, for PetscOptionsEList */
    if ((*names)[k] && (*names)[k][0]) (*names)[m++] = (*names)[k];
  *n = m;
  PetscFunctionReturn(0);
}

/* The names registered, as "a, b or c", for a message about an unknown type. */
static PetscErrorCode ListNames(AdhRegistry *reg, char names[], size_t len)
{
  const char **array;
  PetscInt     n;

  PetscFunctionBegin;
  names[0] = 0;
  PetscCall(AdhRegistryGetNames_Private(reg, &n, &array));
  for (PetscInt k = 0; k < n; k++) {
    PetscCall(PetscStrlcat(names, array[k], len));
    if (k < n - 1) PetscCall(PetscStrlcat(names, k < n - 2 ? ", " : " or ", len));
  }
  PetscCall(PetscFree(array));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhRegistryFind_Private(MPI_Comm comm, AdhRegistry *reg, const char name[], PetscVoidFunction *create)
{
  char names[256];

  PetscFunctionBegin;
  PetscCall(PetscFunctionListFind(reg->list, name, create));
  if (*create) PetscFunctionReturn(0);
  PetscCall(ListNames(reg, names, sizeof(names)));
  SETERRQ(comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "%s: unknown %s '%s' (%s)", reg->option, reg->what, name, names);
}

PetscErrorCode AdhRegistryDestroy_Private(AdhRegistry *reg)
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListDestroy(&reg->list));
  PetscFunctionReturn(0);
}
