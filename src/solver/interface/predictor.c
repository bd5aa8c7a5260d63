/* Contact-set predictor, a registered type (-adh_predictor; impls/predictor/, registered in
   impls/register.c, each owning its options, view and data): a fast first guess of the contact set
   and pressure of a step without adhesion, at a force or an indentation (the load controls),
   handed to the set-update loop, which then certifies it as it certifies any set. The answer is
   the loop's: without adhesion the contact problem (p >= 0 on the set, g >= 0 off it, at d or
   carrying F) has one solution, and the loop started from a good guess only has fewer sets to
   go through.

   none:          the loop starts from the previous state's set (impls/predictor/none.c).
   polonsky-keer: Polonsky & Keer's conjugate gradient (impls/predictor/polonskykeer.c). */
#include "solver/solverimpl.h"

AdhRegistry AdhPredictors = {"-adh_predictor", "contact-set predictor", NULL};

/*@
  AdhPredictorRegister - Adds a contact-set predictor type

  Not Collective

  Input Parameters:
+ name   - the type's name, as given to `AdhSolverSetPredictorType()` and -adh_predictor
- create - the function that gives a solver this predictor: it fills in the solver's `AdhPredictorOps` (predict,
           `NULL` for none, and the ops every type may have; see the private header src/solver/solverimpl.h) and makes
           its data

  Calling sequence of `create`:
. s - the solver, whose previous predictor has been destroyed

  Level: advanced

  Notes:
  The built-in types, `ADHPREDICTORPOLONSKYKEER` and `ADHPREDICTORNONE`, are registered when the package is
  initialized, which this function does first. Registering a name again replaces its function.

.seealso: `AdhSolverSetPredictorType()`, `AdhSolverGetPredictorType()`, `AdhControlRegister()`, `AdhCriterionRegister()`
@*/
PetscErrorCode AdhPredictorRegister(const char name[], PetscErrorCode (*create)(AdhSolver))
{
  PetscFunctionBegin;
  PetscValidCharPointer(name, 1);
  PetscValidFunction(create, 2);
  PetscCall(AdhSolverInitializePackage());
  PetscCall(AdhRegistryAdd_Private(&AdhPredictors, name, (PetscVoidFunction)create));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverSetPredictorType - Sets the contact-set predictor: a fast first guess of a step's contact set without adhesion

  Logically Collective

  Input Parameters:
+ s    - the solver
- type - the predictor's name: `ADHPREDICTORPOLONSKYKEER` (Polonsky & Keer's constrained conjugate gradient),
         `ADHPREDICTORNONE`, or one registered with `AdhPredictorRegister()`

  Options Database Key:
. -adh_predictor <polonsky-keer,none> - the predictor

  Level: intermediate

  Notes:
  The guess (a contact set and pressure) is handed to the set-update loop, which then certifies it as it certifies
  any set: the predictor changes the cost, not the answer. Without adhesion the contact problem at d or carrying F
  has one solution, and the loop started from a good guess only has fewer sets to go through. It is used under either
  control, only for steps without adhesion (no dgamma nor -adh_critical_stress, or the step of a Hertz start), and
  under force control only for F > 0.

  The default is polonsky-keer on a periodic cell and none on a free boundary, where the loop's bounding-box windows
  cost less than the predictor's transforms of the whole grid: `AdhSolverSetUp()` chooses none there unless a type
  was set, by this function or -adh_predictor. Unlike the control and the criterion, the predictor may change after
  set-up. An unknown name is an error that lists the registered ones.

.seealso: `AdhSolverGetPredictorType()`, `AdhPredictorRegister()`, `ADHPREDICTORPOLONSKYKEER`, `ADHPREDICTORNONE`
@*/
PetscErrorCode AdhSolverSetPredictorType(AdhSolver s, AdhPredictorType type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidCharPointer(type, 2);
  PetscCall(AdhSolverSetType_Private(s, &AdhPredictors, s->predictor_type, &s->pops.base, sizeof(s->pops), type, PETSC_FALSE));
  s->predictor_chosen = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetPredictorType - Gets the name of the contact-set predictor

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. type - the predictor's name, for example `ADHPREDICTORNONE`

  Level: intermediate

  Note:
  The string is the solver's: do not free it. Before `AdhSolverSetUp()` it may still be the provisional default
  polonsky-keer, which set-up replaces by none on a free boundary.

.seealso: `AdhSolverSetPredictorType()`, `AdhPredictorRegister()`
@*/
PetscErrorCode AdhSolverGetPredictorType(AdhSolver s, AdhPredictorType *type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(type, 2);
  *type = s->predictor_type;
  PetscFunctionReturn(0);
}
