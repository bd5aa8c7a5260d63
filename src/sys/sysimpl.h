/* The package's services to the layers above: the check of adhbem's options (options.c). */
#ifndef ADHBEM_SYSIMPL_H
#define ADHBEM_SYSIMPL_H
#include <petscksp.h>
#include "adhbem.h"

/* Every option under prefix that starts with adh_ and that no part of adhbem reads is an error
   naming the nearest known option. */
PETSC_INTERN PetscErrorCode AdhCheckOptions_Private(MPI_Comm, const char prefix[]);
/* After ksp's set-up from the options: an -adh_ksp_ or -adh_pc_ option under prefix that neither
   it nor a solve reads is an error naming it. */
PETSC_INTERN PetscErrorCode AdhCheckKSPOptions_Private(KSP, const char prefix[], const char which[]);
/* The names registered in list, as "a, b or c", for a message about an unknown type. */
PETSC_INTERN PetscErrorCode AdhFunctionListNames_Private(PetscFunctionList, char names[], size_t len);
#endif
