/* Load control, a registered type (-adh_control): what the path's values are and how a step
   reaches one. The types are in impls/control/, one file each, listed in solverregis.c; each
   fills in AdhControlOps (solverimpl.h).

   displacement: the path holds indentations d (impls/control/displacement.c).
   force:        the path holds forces F; a step finds the d at which the equilibrium set carries
                 exactly F (impls/control/force.c). */
#include "solver/solverimpl.h"

static PetscFunctionList AdhControlList = NULL;

PetscErrorCode AdhControlRegister(const char name[], PetscErrorCode (*create)(AdhSolver))
{
  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  PetscCall(PetscFunctionListAdd(&AdhControlList, name, create));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhControlDestroyList_Private(void)
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListDestroy(&AdhControlList));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhControlGetList_Private(PetscFunctionList *list)
{
  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  *list = AdhControlList;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverSetControlType(AdhSolver s, AdhControlType type)
{
  PetscErrorCode (*create)(AdhSolver);
  PetscBool same;

  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  PetscCall(PetscStrcmp(s->control_type, type, &same));
  if (same) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListFind(AdhControlList, type, &create));
  if (!create) {
    char names[256];
    PetscCall(AdhFunctionListNames_Private(AdhControlList, names, sizeof(names)));
    SETERRQ(s->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "-adh_control: unknown load control '%s' (%s)", type, names);
  }
  PetscCheck(!s->setup, s->comm, PETSC_ERR_ORDER, "-adh_control: the load control cannot change after set-up");
  if (s->cops.destroy) PetscCall(s->cops.destroy(s));
  PetscCall(PetscMemzero(&s->cops, sizeof(s->cops)));
  PetscCall(create(s));
  PetscCall(PetscStrncpy(s->control_type, type, sizeof(s->control_type)));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetControlType(AdhSolver s, AdhControlType *type)
{
  PetscFunctionBegin;
  *type = s->control_type;
  PetscFunctionReturn(0);
}

/* One step to the target (d, or F under force control), with its counts. */
PetscErrorCode AdhSolverStep(AdhSolver s, PetscReal target)
{
  PetscInt       mults0, mults1, ffts0, ffts1;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(AdhSolverSetUp(s));
  PetscCheck(!PetscIsInfOrNanReal(target), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "The step's target (%s) is not finite", s->force_control ? "force" : "indentation");
  PetscCall(PetscLogEventBegin(ADH_Solve, 0, 0, 0, 0));
  PetscCall(AdhSolverMultCount_Private(s, &mults0, &ffts0));
  s->step_outer = 0;
  s->step_ksp   = 0;
  s->step_local_solves = 0;
  if (s->pulled_off) {
    /* The last step ended in pull-off: the bodies are apart now. */
    PetscCall(AdhSolverClearContact_Private(s));
  }
  PetscCall(AdhSolverBeginSetUpdates_Private(s)); /* after a pull-off, of the empty set */
  ierr = s->cops.step(s, target);
  if (ierr == PETSC_ERR_SIG && s->stoppable && s->stop_signal) { /* stopped by a signal: the step is abandoned */
    PetscCall(PetscLogEventEnd(ADH_Solve, 0, 0, 0, 0));
    PetscFunctionReturn(ierr);
  }
  PetscCall(ierr);
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

PetscErrorCode AdhSolverIsPulledOff(AdhSolver s, PetscBool *pulled_off)
{
  PetscFunctionBegin;
  *pulled_off = s->pulled_off;
  PetscFunctionReturn(0);
}
