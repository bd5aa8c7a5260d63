/* Load control, a registered type (-adh_control): what the path's values are and how a step
   reaches one. The types are in impls/control/, one file each, registered in impls/register.c;
   each fills in AdhControlOps (solverimpl.h) and owns its options, view and data. Their steps
   share the set-update loop (setupdate.c).

   displacement: the path holds indentations d (impls/control/displacement.c).
   force:        the path holds forces F; a step finds the d at which the equilibrium set carries
                 exactly F (impls/control/force.c). */
#include "solver/solverimpl.h"

AdhRegistry AdhControls = {"-adh_control", "load control", NULL};

/*@
  AdhControlRegister - Adds a load control type

  Not Collective

  Input Parameters:
+ name   - the type's name, as given to `AdhSolverSetControlType()` and -adh_control
- create - the function that gives a solver this control: it fills in the solver's `AdhControlOps` (its target, step and
           equilibrate, optionally attach_rate, and the ops every type may have: setfromoptions, view, setup, destroy,
           shape, checkpoint, memory; declared in the private header src/solver/solverimpl.h) and makes its data

  Calling sequence of `create`:
. s - the solver, whose previous control has been destroyed

  Level: advanced

  Notes:
  The built-in types, `ADHCONTROLDISPLACEMENT` and `ADHCONTROLFORCE`, are registered when the package is initialized,
  which this function does first. Registering a name again replaces its function.

  A new type is one file in src/solver/impls/control/ and its registration line in src/solver/impls/register.c
  (docs/developers/code-map.md); its step may run the set-update loop the built-in controls share.

.seealso: `AdhSolverSetControlType()`, `AdhSolverGetControlType()`, `AdhCriterionRegister()`, `AdhPredictorRegister()`
@*/
PetscErrorCode AdhControlRegister(const char name[], PetscErrorCode (*create)(AdhSolver))
{
  PetscFunctionBegin;
  PetscValidCharPointer(name, 1);
  PetscValidFunction(create, 2);
  PetscCall(AdhSolverInitializePackage());
  PetscCall(AdhRegistryAdd_Private(&AdhControls, name, (PetscVoidFunction)create));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverSetControlType - Sets the load control: what the path's values are and how a step reaches one

  Logically Collective

  Input Parameters:
+ s    - the solver
- type - the control's name: `ADHCONTROLDISPLACEMENT` (the default: the path holds indentations d),
         `ADHCONTROLFORCE` (the path holds forces F; each step finds the d at which the equilibrium set carries F),
         or one registered with `AdhControlRegister()`

  Options Database Key:
. -adh_control <displacement,force> - the load control

  Level: intermediate

  Notes:
  The control cannot change after `AdhSolverSetUp()`; setting the type the solver already has does nothing. An
  unknown name is an error that lists the registered ones.

  -adh_cascade_apart and -adh_cascade_local are for displacement control only, and the default of -adh_cascade_local
  follows the control and the criterion.

.seealso: `AdhSolverGetControlType()`, `AdhControlRegister()`, `ADHCONTROLDISPLACEMENT`, `ADHCONTROLFORCE`,
          `AdhSolverStep()`
@*/
PetscErrorCode AdhSolverSetControlType(AdhSolver s, AdhControlType type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidCharPointer(type, 2);
  PetscCall(AdhSolverSetType_Private(s, &AdhControls, s->control_type, &s->cops.base, sizeof(s->cops), type, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetControlType - Gets the name of the load control

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. type - the control's name, for example `ADHCONTROLDISPLACEMENT`

  Level: intermediate

  Note:
  The string is the solver's: do not free it; it holds the name until the control changes.

.seealso: `AdhSolverSetControlType()`, `AdhControlRegister()`
@*/
PetscErrorCode AdhSolverGetControlType(AdhSolver s, AdhControlType *type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(type, 2);
  *type = s->control_type;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverStep - Takes one step: the equilibrium contact set at an indentation d, or carrying a force F under force control

  Collective

  Input Parameters:
+ s      - the solver
- target - the indentation d, or the force F under `ADHCONTROLFORCE`; it must be finite

  Level: intermediate

  Notes:
  The step starts from the current set. It sets the solver up if needed (`AdhSolverSetUp()`); after a step that ended
  in pull-off (`AdhSolverIsPulledOff()`) it starts with the bodies apart, nothing in contact. The step's counts (set
  updates, KSP iterations, compliance applications, FFT pairs) are kept for `AdhSolverGetState()` and
  `AdhSolverComputeState()`, and a displacement handed out by `AdhSolverGetFields()` is brought up to date.

  Under displacement control a step that empties a set that had contact ends in pull-off. Under force control a set
  that empties means no equilibrium carries F: the contact has come off. The step then bisects between the previous
  state's force and F, from the previous state, and ends on the state carrying the largest tension (within
  -adh_pulloff_rtol), marked pulled off; the next step starts with nothing in contact. Without contact a force F <= 0
  leaves the bodies apart.

  The state is not recorded: `AdhSolverRecordState()` records it, as `AdhSolverSolvePath()` does after each step. A
  signal that stops a running `AdhSolverSolvePath()` abandons the step: it returns at once with its state half made, not
  to be recorded, and the path reports the stop.

.seealso: `AdhSolverStart()`, `AdhSolverSolvePath()`, `AdhSolverRecordState()`, `AdhSolverGetState()`,
          `AdhSolverIsPulledOff()`, `AdhSolverSetControlType()`
@*/
PetscErrorCode AdhSolverStep(AdhSolver s, PetscReal target)
{
  PetscInt mults0, mults1, ffts0, ffts1;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscCall(AdhSolverSetUp(s));
  PetscCheck(!PetscIsInfOrNanReal(target), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "The step's target (%s) is not finite", AdhSolverControlsForce_Private(s) ? "force" : "indentation");
  PetscCall(PetscLogEventBegin(ADH_Solve, 0, 0, 0, 0));
  PetscCall(AdhSolverMultCount_Private(s, &mults0, &ffts0));
  s->step_outer = 0;
  s->step_ksp   = 0;
  s->step_local_solves = 0;
  s->step_id++;
  if (s->pulled_off) {
    /* The last step ended in pull-off: the bodies are apart now. */
    PetscCall(AdhSolverClearContact_Private(s));
  }
  PetscCall(AdhSolverBeginSetUpdates_Private(s)); /* after a pull-off, of the empty set */
  PetscCall(s->cops.step(s, target));
  if (AdhSolverStopped_Private(s)) { /* stopped by a signal: the step is abandoned, its state half made */
    PetscCall(PetscLogEventEnd(ADH_Solve, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  if (s->u) { /* a displacement handed out before follows the state */
    Vec u;
    PetscCall(AdhSolverGetDisplacement_Private(s, &u));
  }
  PetscCall(AdhSolverMultCount_Private(s, &mults1, &ffts1));
  s->step_mults = mults1 - mults0;
  s->step_ffts  = ffts1 - ffts0;
  PetscCall(PetscLogEventEnd(ADH_Solve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverIsPulledOff - Tells whether the last step ended in pull-off

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. pulled_off - `PETSC_TRUE` if the last step ended in pull-off: the next step starts with the bodies apart

  Level: intermediate

  Note:
  `AdhSolverSolvePath()` ends a leg at pull-off; the state it records there has pulled_off = 1.

.seealso: `AdhSolverStep()`, `AdhSolverComputeState()`, `AdhCurveGetPullOffState()`
@*/
PetscErrorCode AdhSolverIsPulledOff(AdhSolver s, PetscBool *pulled_off)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidBoolPointer(pulled_off, 2);
  *pulled_off = s->pulled_off;
  PetscFunctionReturn(0);
}
