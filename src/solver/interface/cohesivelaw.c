/* What every smooth cohesive law (impls/criterion/exponential.c, lj93.c) shares, given as its ops:
   the refusals of the options that do not apply to a law's steps, the curve's detach ratio against
   the law's peak, and the minimisation's memory and data. A law's own file keeps its formula, its
   options, view and restart check. */
#include "solver/solverimpl.h"

/* The options a law's minimisation has no use for, refused naming them (its set-up calls this
   after its own checks). */
PetscErrorCode AdhSolverLawSetUp_Private(AdhSolver s)
{
  const char *law = s->criterion_type;

  PetscFunctionBegin;
  PetscCheck(s->sigma_fixed == 0, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_critical_stress does not apply to -adh_criterion %s, whose largest tension is its law's", law);
  PetscCheck(!s->attach_chosen, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_attach does not apply to -adh_criterion %s: the hard wall is the bound of its energy minimisation", law);
  PetscCheck(!s->cascade_apart, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_cascade_apart does not apply to -adh_criterion %s", law);
  PetscCheck(!(s->cascade_local > 0), s->comm, PETSC_ERR_ARG_INCOMP, "-adh_cascade_local does not apply to -adh_criterion %s", law);
  PetscFunctionReturn(0);
}

/* The evaluate op of a law: without detach (a law never lets points go, the minimisation does),
   the largest tension on the contact over the law's peak, at most 1 in an equilibrium. */
PetscErrorCode AdhSolverLawEvaluate_Private(AdhSolver s, PetscBool detach, PetscInt *removed, PetscReal *ratio)
{
  const PetscScalar *pa, *gamma = NULL;
  PetscReal          r = 0.0;

  PetscFunctionBegin;
  PetscCheck(!detach, s->comm, PETSC_ERR_PLIB, "A cohesive law's steps minimise the energy: no detach test");
  if (s->gamma_field) PetscCall(VecGetArrayRead(s->gamma_field, &gamma));
  PetscCall(VecGetArrayRead(s->p, &pa));
  for (PetscInt k = 0; k < s->nlocal; k++) {
    const PetscReal dgamma = s->adhesive ? (gamma ? PetscRealPart(gamma[k]) : s->gamma) : 0.0, p = PetscRealPart(pa[k]);
    if (!s->in_set[k] || p >= 0) continue;
    r = dgamma > 0 ? PetscMax(r, -p / s->crops.peak(s->crops.data, dgamma)) : PETSC_MAX_REAL;
  }
  PetscCall(VecRestoreArrayRead(s->p, &pa));
  if (gamma) PetscCall(VecRestoreArrayRead(s->gamma_field, &gamma));
  PetscCall(MPIU_Allreduce(&r, ratio, 1, MPIU_REAL, MPIU_MAX, s->comm));
  if (removed) *removed = 0;
  PetscFunctionReturn(0);
}

/* The memory op of a law: the minimisation's vectors. */
PetscErrorCode AdhSolverLawMemory_Private(AdhSolver s, PetscLogDouble *per_point, PetscLogDouble *per_rank)
{
  PetscFunctionBegin;
  *per_point = AdhSolverMinimizeMemory_Private(s);
  *per_rank  = 0.0;
  PetscFunctionReturn(0);
}

/* The destroy op of a law: the minimisation's data, then the law's own. */
PetscErrorCode AdhSolverLawDestroy_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(AdhSolverMinimizeDestroy_Private(s));
  PetscCall(PetscFree(s->crops.data));
  PetscFunctionReturn(0);
}
