/* Contact-set predictor, a registered type (-adh_predictor; impls/predictor/, listed in
   solverregis.c): a fast first guess of the contact set
   and pressure of a step without adhesion, at a force or an indentation (the load controls),
   handed to the set-update loop, which then certifies it as it certifies any set. The answer is
   the loop's: without adhesion the contact problem (p >= 0 on the set, g >= 0 off it, at d or
   carrying F) has one solution, and the loop started from a good guess only has fewer sets to
   go through.

   none:          the loop starts from the previous state's set (impls/predictor/none.c).
   polonsky-keer: Polonsky & Keer's conjugate gradient (impls/predictor/polonskykeer.c). */
#include "solver/solverimpl.h"

static PetscFunctionList AdhPredictorList = NULL;

PetscErrorCode AdhPredictorRegister(const char name[], PetscErrorCode (*create)(AdhSolver))
{
  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  PetscCall(PetscFunctionListAdd(&AdhPredictorList, name, create));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhPredictorDestroyList_Private(void)
{
  PetscFunctionBegin;
  PetscCall(PetscFunctionListDestroy(&AdhPredictorList));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhPredictorGetList_Private(PetscFunctionList *list)
{
  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  *list = AdhPredictorList;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverSetPredictorType(AdhSolver s, AdhPredictorType type)
{
  PetscErrorCode (*create)(AdhSolver);

  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  PetscCall(PetscFunctionListFind(AdhPredictorList, type, &create));
  if (!create) {
    char names[256];
    PetscCall(AdhFunctionListNames_Private(AdhPredictorList, names, sizeof(names)));
    SETERRQ(s->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "-adh_predictor: unknown contact-set predictor '%s' (%s)", type, names);
  }
  PetscCall(create(s));
  PetscCall(PetscStrncpy(s->predictor_type, type, sizeof(s->predictor_type)));
  s->predictor_chosen = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetPredictorType(AdhSolver s, AdhPredictorType *type)
{
  PetscFunctionBegin;
  *type = s->predictor_type;
  PetscFunctionReturn(0);
}
