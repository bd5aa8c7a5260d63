/* Detachment criterion, a registered type (-adh_criterion): which points of the contact set let
   go after a solve. The types are in impls/criterion/, a file or a folder each, registered in
   impls/register.c; each fills in AdhCriterionOps (solverimpl.h) and owns its options, view and
   data. Both reduce to non-adhesive contact (p < 0 lets go) when dgamma = 0.

   pohrt-popov:   the paper's rule, p < -Sigma (impls/criterion/pohrtpopov.c).
   crack-closure: the contact edge's energy release rate by virtual crack closure, averaged along
                  the edge, against dgamma (impls/criterion/crackclosure/).
   dugdale:       finite range, Maugis' cohesive zone (impls/criterion/dugdale.c). */
#include "solver/solverimpl.h"

AdhRegistry AdhCriteria = {"-adh_criterion", "detachment criterion", NULL};

/*@
  AdhCriterionRegister - Adds a detachment criterion type

  Not Collective

  Input Parameters:
+ name   - the type's name, as given to `AdhSolverSetCriterionType()` and -adh_criterion
- create - the function that gives a solver this criterion: it fills in the solver's `AdhCriterionOps` (evaluate;
           optionally decide, and the ops every type may have: setfromoptions, view, setup, destroy, shape,
           checkpoint, memory; declared in the private header src/solver/solverimpl.h) and makes its data

  Calling sequence of `create`:
. s - the solver, whose previous criterion has been destroyed

  Level: advanced

  Notes:
  The built-in types, `ADHCRITERIONCRACKCLOSURE`, `ADHCRITERIONPOHRTPOPOV` and `ADHCRITERIONDUGDALE`, are registered when the package is
  initialized, which this function does first. Registering a name again replaces its function.

  A new type is one file (or folder) in src/solver/impls/criterion/ and its registration line in
  src/solver/impls/register.c, with no edit of the solver's interface; docs/developers/code-map.md works one through. Its options
  are read by its setfromoptions in a -help group of its own, its lines of `AdhSolverView()` and its attributes in the
  results file come from its view.

.seealso: `AdhSolverSetCriterionType()`, `AdhSolverGetCriterionType()`, `AdhControlRegister()`, `AdhPredictorRegister()`
@*/
PetscErrorCode AdhCriterionRegister(const char name[], PetscErrorCode (*create)(AdhSolver))
{
  PetscFunctionBegin;
  PetscValidCharPointer(name, 1);
  PetscValidFunction(create, 2);
  PetscCall(AdhSolverInitializePackage());
  PetscCall(AdhRegistryAdd_Private(&AdhCriteria, name, (PetscVoidFunction)create));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverSetCriterionType - Sets the detachment criterion: when a point of the contact set lets go

  Logically Collective

  Input Parameters:
+ s    - the solver
- type - the criterion's name: `ADHCRITERIONCRACKCLOSURE` (the default: the contact edge's energy release rate by
         virtual crack closure, G > dgamma, which does not depend on the edge's direction on the grid),
         `ADHCRITERIONPOHRTPOPOV` (the paper's p < -Sigma), `ADHCRITERIONDUGDALE` (finite range: Maugis' cohesive zone),
         or one registered with `AdhCriterionRegister()`

  Options Database Key:
. -adh_criterion <crack-closure,pohrt-popov,dugdale> - the criterion

  Level: intermediate

  Notes:
  The criterion cannot change after `AdhSolverSetUp()`; setting the type the solver already has does nothing. An
  unknown name is an error that lists the registered ones.

  The criterion chooses defaults at set-up: the attach rule griffith (crack-closure's mirror) with crack-closure, reach
  with pohrt-popov and penetration with dugdale (griffith is refused with any criterion but crack-closure), and
  -adh_cascade_local inf (the whole grid) with crack-closure under displacement control, 0 otherwise.

.seealso: `AdhSolverGetCriterionType()`, `AdhCriterionRegister()`, `ADHCRITERIONCRACKCLOSURE`, `ADHCRITERIONPOHRTPOPOV`,
          `ADHCRITERIONDUGDALE`
@*/
PetscErrorCode AdhSolverSetCriterionType(AdhSolver s, AdhCriterionType type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidCharPointer(type, 2);
  PetscCall(AdhSolverSetType_Private(s, &AdhCriteria, s->criterion_type, &s->crops.base, sizeof(s->crops), type, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetCriterionType - Gets the name of the detachment criterion

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. type - the criterion's name, for example `ADHCRITERIONCRACKCLOSURE`

  Level: intermediate

  Note:
  The string is the solver's: do not free it; it holds the name until the criterion changes.

.seealso: `AdhSolverSetCriterionType()`, `AdhCriterionRegister()`
@*/
PetscErrorCode AdhSolverGetCriterionType(AdhSolver s, AdhCriterionType *type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(type, 2);
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
