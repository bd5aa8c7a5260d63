/* What differs between the PETSc releases adhbem builds with (3.18 to the current one), in one
   place. Each entry names the release that changed and what it changed. */
#ifndef ADHBEM_PETSCCOMPAT_H
#define ADHBEM_PETSCCOMPAT_H
#include <math.h>
#include <petscksp.h>

/* The context of an options block, as a type's SetFromOptions op receives it: a struct that ops
   took by pointer up to 3.22; from 3.23 PetscOptionItems is itself the pointer. */
#if PETSC_VERSION_LT(3, 23, 0)
typedef PetscOptionItems *AdhOptionItems;
#else
typedef PetscOptionItems AdhOptionItems;
#endif

/* A real option: PetscOptionsReal bounds its current and new value by PETSC_MAX_REAL in current
   releases (a default of inf, as -adh_E2's rigid body, is an error there); adhbem checks each
   option's range itself, after the read, where the meaning is. The bounds are the true infinities
   (PETSC_INFINITY is a finite number). */
#if defined(PetscOptionsRangeReal)
  #define AdhPETScOptionsReal(opt, text, man, current, value, set) PetscOptionsRangeReal(opt, text, man, current, value, set, -(PetscReal)HUGE_VAL, (PetscReal)HUGE_VAL)
#else
  #define AdhPETScOptionsReal(opt, text, man, current, value, set) PetscOptionsReal(opt, text, man, current, value, set)
#endif
/* KSPConvergedDefaultDestroy takes the context up to 3.22 and its address from 3.23 (a
   PetscCtxDestroyFn); C converts the one to the other without a word, and the wrong one crashes. */
static inline PetscErrorCode AdhKSPConvergedDefaultDestroy(void **ctx)
{
#if PETSC_VERSION_LT(3, 23, 0)
  PetscErrorCode ierr = KSPConvergedDefaultDestroy(*ctx);
  *ctx                = NULL;
  return ierr;
#else
  return KSPConvergedDefaultDestroy(ctx);
#endif
}
#endif
