/* The package's services to the layers above: the check of adhbem's options (options.c), the
   registries of types (registry.c) and the versions (version.c). */
#ifndef ADHBEM_SYSIMPL_H
#define ADHBEM_SYSIMPL_H
#include <petscksp.h>
#include "adhbem.h"
#include "sys/petsccompat.h"

/* Every option under prefix that starts with adh_ and that no part of adhbem reads is an error
   naming the nearest known option. */
PETSC_INTERN PetscErrorCode AdhCheckOptions_Private(MPI_Comm, const char prefix[]);
/* After ksp's set-up from the options: an -adh_ksp_ or -adh_pc_ option under prefix that neither
   it nor a solve reads is an error naming it. */
PETSC_INTERN PetscErrorCode AdhCheckKSPOptions_Private(KSP, const char prefix[], const char which[]);

/* The value given to a numeric option (optionvalues.c) is a number of its kind: an integer within
   PetscInt, or a real (inf allowed, NaN not), each item of a comma-separated list; else an error
   naming the option. Called before PETSc reads the option, by the readers below: */
typedef enum {
  ADH_NUMBER_INT,
  ADH_NUMBER_REAL
} AdhNumberKind;
PETSC_INTERN PetscErrorCode AdhOptionsCheckNumber_Private(MPI_Comm, PetscOptions, const char prefix[], const char name[], AdhNumberKind);
/* adhbem's reads of numeric options inside an options block: the value checked, then read. */
static inline PetscErrorCode AdhOptionsReal_Private(AdhOptionItems PetscOptionsObject, const char opt[], const char text[], const char man[], PetscReal current, PetscReal *value, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(AdhOptionsCheckNumber_Private(PetscOptionsObject->comm, PetscOptionsObject->options, PetscOptionsObject->prefix, opt, ADH_NUMBER_REAL));
  PetscCall(AdhPETScOptionsReal(opt, text, man, current, value, set));
  PetscFunctionReturn(0);
}
static inline PetscErrorCode AdhOptionsInt_Private(AdhOptionItems PetscOptionsObject, const char opt[], const char text[], const char man[], PetscInt current, PetscInt *value, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(AdhOptionsCheckNumber_Private(PetscOptionsObject->comm, PetscOptionsObject->options, PetscOptionsObject->prefix, opt, ADH_NUMBER_INT));
  PetscCall(PetscOptionsInt(opt, text, man, current, value, set));
  PetscFunctionReturn(0);
}
static inline PetscErrorCode AdhOptionsRealArray_Private(AdhOptionItems PetscOptionsObject, const char opt[], const char text[], const char man[], PetscReal value[], PetscInt *n, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(AdhOptionsCheckNumber_Private(PetscOptionsObject->comm, PetscOptionsObject->options, PetscOptionsObject->prefix, opt, ADH_NUMBER_REAL));
  PetscCall(PetscOptionsRealArray(opt, text, man, value, n, set));
  PetscFunctionReturn(0);
}
static inline PetscErrorCode AdhOptionsIntArray_Private(AdhOptionItems PetscOptionsObject, const char opt[], const char text[], const char man[], PetscInt value[], PetscInt *n, PetscBool *set)
{
  PetscFunctionBegin;
  PetscCall(AdhOptionsCheckNumber_Private(PetscOptionsObject->comm, PetscOptionsObject->options, PetscOptionsObject->prefix, opt, ADH_NUMBER_INT));
  PetscCall(PetscOptionsIntArray(opt, text, man, value, n, set));
  PetscFunctionReturn(0);
}
#define AdhOptionsReal(opt, text, man, current, value, set)      AdhOptionsReal_Private(PetscOptionsObject, opt, text, man, current, value, set)
#define AdhOptionsInt(opt, text, man, current, value, set)       AdhOptionsInt_Private(PetscOptionsObject, opt, text, man, current, value, set)
#define AdhOptionsRealArray(opt, text, man, value, n, set)       AdhOptionsRealArray_Private(PetscOptionsObject, opt, text, man, value, n, set)
#define AdhOptionsIntArray(opt, text, man, value, n, set)        AdhOptionsIntArray_Private(PetscOptionsObject, opt, text, man, value, n, set)

/* The types of one kind, by name (registry.c): option is the option that chooses one
   ("-adh_criterion"), what says what they are ("detachment criterion"). */
typedef struct {
  const char       *option;
  const char       *what;
  PetscFunctionList list;
} AdhRegistry;
PETSC_INTERN PetscErrorCode AdhRegistryAdd_Private(AdhRegistry *, const char name[], PetscVoidFunction create);
/* The create function of name; an unknown name is an error naming the option and the registered names. */
PETSC_INTERN PetscErrorCode AdhRegistryFind_Private(MPI_Comm, AdhRegistry *, const char name[], PetscVoidFunction *create);
/* The registered names, in registration order; free the array (not the names) with PetscFree(). */
PETSC_INTERN PetscErrorCode AdhRegistryGetNames_Private(AdhRegistry *, PetscInt *n, const char ***names);
PETSC_INTERN PetscErrorCode AdhRegistryDestroy_Private(AdhRegistry *);

/* The version (version.c): PETSc's as the process runs it ("3.18.5"), and the check, when the
   package initialises, that it is the major.minor and the index size adhbem was
   built against. */
PETSC_INTERN PetscErrorCode AdhGetPETScVersion_Private(char version[], size_t len);
PETSC_INTERN PetscErrorCode AdhCheckPETSc_Private(void);
#endif
