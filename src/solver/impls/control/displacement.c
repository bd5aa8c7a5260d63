/*MC
   ADHCONTROLDISPLACEMENT - "displacement", the default load control: the path holds indentations d, and a step is
   the Pohrt-Popov loop at fixed d

   The loop: solve on the contact set, let go what the criterion says, let join what the attach rule says, until the
   set stands.

   Options Database Keys:
+  -adh_control displacement - selects this control (the default)
.  -adh_max_outer <100000>   - the largest number of set updates in one step
.  -adh_cascade_rtol <0>     - the solves after a set update stop at this relative residual
.  -adh_cascade_local <F>    - local solves around the points a set update lets go
-  -adh_cascade_apart <0>    - points may join in an update that lets others go, this many grid spacings away

   Level: beginner

   Notes:
   With -adh_cascade_rtol the solves after a set update stop at that relative residual, and the set is updated on
   their pressures; once a set stands on one, it is solved to the full tolerance and tested again, so every recorded
   state is tested on an exact solve. With -adh_cascade_local the points a set update lets go are followed by local
   solves around them (cascadelocal.c) before the next solve of the whole set. -adh_cascade_local and
   -adh_cascade_apart are for this control only.

   Without adhesion a predictor may guess the set first (`AdhSolverSetPredictorType()`). A step that empties a set
   that had contact ends in pull-off. On a periodic cell d must stay below mean(h): there the cell is in full contact
   and the force is undetermined (use `ADHCONTROLFORCE`).

.seealso: `AdhSolverSetControlType()`, `ADHCONTROLFORCE`, `AdhSolverStep()`, `AdhSolverIsPulledOff()`
M*/
#include "solver/solverimpl.h"

/* The equilibrium of the current set at indentation d: one solve. */
static PetscErrorCode Equilibrate_Displacement(AdhSolver s, PetscReal d, PetscBool *none)
{
  PetscFunctionBegin;
  *none = PETSC_FALSE;
  PetscCall(AdhSolverSolveOnSet_Private(s, ADH_SET_SOLVE_PRESSURE, d, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* Displacement control: the equilibrium set at indentation d, from the current set. */
static PetscErrorCode Step_Displacement(AdhSolver s, PetscReal d)
{
  const PetscBool had_contact = s->npoints > 0;

  PetscFunctionBegin;
  PetscCall(AdhSolverCheckBelowFullContact_Private(s, d));
  s->d           = d;
  s->joined_step = 0;
  /* without adhesion the state at d is unique: a predictor may guess its set */
  if (s->pops.predict && !AdhSolverIsAdhesive_Private(s)) PetscCall(s->pops.predict(s, PETSC_FALSE, d));
  AdhSolverReturnIfStopped_Private(s);
  PetscCall(AdhSolverUpdateSet_Private(s, d));
  AdhSolverReturnIfStopped_Private(s);
  s->joined_previous = s->joined_step;
  s->pulled_off      = (PetscBool)(had_contact && !s->npoints);
  PetscFunctionReturn(0);
}

/* Its line of -adh_view: whether the intermediate solves may stop early. */
static PetscErrorCode View_Displacement(AdhSolver s, PetscViewer viewer)
{
  PetscBool isascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (isascii) PetscCall(PetscViewerASCIIPrintf(viewer, "certified early stop of intermediate solves %s\n", s->certify && s->crops.decide ? "on" : "off"));
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhControlCreate_Displacement(AdhSolver s)
{
  PetscFunctionBegin;
  s->cops.target      = ADH_TARGET_INDENTATION;
  s->cops.cascades    = PETSC_TRUE;
  s->cops.step        = Step_Displacement;
  s->cops.equilibrate = Equilibrate_Displacement;
  s->cops.base.view   = View_Displacement;
  PetscFunctionReturn(0);
}
