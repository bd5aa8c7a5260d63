/* The reduced modulus E* of two elastic bodies, 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2. */
#include "geometry/material.h"
#include <petsc/private/petscimpl.h> /* PetscValid* */
#include "sys/sysimpl.h"

static PetscErrorCode CheckBody(MPI_Comm comm, const char *Ename, PetscReal E, const char *nuname, PetscReal nu)
{
  PetscFunctionBegin;
  PetscCheck(E > 0 && !PetscIsInfOrNanReal(E), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: Young's modulus must be positive and finite, got %g", Ename, (double)E);
  PetscCheck(nu > -1.0 && nu <= 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: Poisson ratio must lie in (-1, 0.5], got %g", nuname, (double)nu);
  PetscFunctionReturn(0);
}

/* The solids' constants into *m (its Estar on entry kept when no option is given). */
PetscErrorCode AdhMaterialSetFromOptions_Private(MPI_Comm comm, const char prefix[], AdhMaterial *m)
{
  PetscReal E1 = 1.0, nu1 = 0.0, E2 = (PetscReal)INFINITY, nu2 = 0.0, Es = m->Estar;
  PetscBool setEs, setE1, setE2, setnu1, setnu2;

  PetscFunctionBegin;
  PetscOptionsBegin(comm, prefix, "adhbem material", "AdhSolver");
  PetscCall(AdhOptionsReal("-adh_E_star", "Reduced modulus E*", "", Es, &Es, &setEs));
  PetscCall(AdhOptionsReal("-adh_E1", "Young's modulus of body 1, the substrate or layer (instead of -adh_E_star)", "", E1, &E1, &setE1));
  PetscCall(AdhOptionsReal("-adh_nu1", "Poisson ratio of body 1", "", nu1, &nu1, &setnu1));
  PetscCall(AdhOptionsReal("-adh_E2", "Young's modulus of body 2, the indenter (default inf: rigid)", "", E2, &E2, &setE2));
  PetscCall(AdhOptionsReal("-adh_nu2", "Poisson ratio of body 2", "", nu2, &nu2, &setnu2));
  PetscOptionsEnd();
  m->solids  = PETSC_FALSE;
  m->nu1_set = PETSC_FALSE;
  if (setE1 || setE2 || setnu1 || setnu2) {
    PetscReal compliance = 0.0;
    PetscCheck(!setEs, comm, PETSC_ERR_ARG_INCOMP, "-adh_E_star cannot be combined with -adh_E1/-adh_nu1/-adh_E2/-adh_nu2");
    PetscCheck(setE1, comm, PETSC_ERR_ARG_WRONG, "-adh_E1 is required when -adh_nu1, -adh_E2 or -adh_nu2 is given");
    PetscCall(CheckBody(comm, "-adh_E1", E1, "-adh_nu1", nu1));
    compliance += (1.0 - nu1 * nu1) / E1;
    if (setE2) {
      PetscCall(CheckBody(comm, "-adh_E2", E2, "-adh_nu2", nu2));
      compliance += (1.0 - nu2 * nu2) / E2;
    } else PetscCheck(!setnu2, comm, PETSC_ERR_ARG_WRONG, "-adh_nu2 needs -adh_E2");
    Es        = 1.0 / compliance;
    m->solids = PETSC_TRUE;
    m->E1 = E1; m->nu1 = nu1; m->E2 = E2; m->nu2 = nu2;
    m->nu1_set = setnu1;
  }
  PetscCheck(Es > 0 && !PetscIsInfOrNanReal(Es), comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_E_star: the reduced modulus must be positive and finite, got %g", (double)Es);
  m->Estar = Es;
  PetscFunctionReturn(0);
}

/*@
  AdhGetReducedModulusFromOptions - Gets the reduced modulus E* of the two elastic bodies from the options database

  Collective

  Input Parameters:
+ comm   - the communicator of the options
- prefix - the options prefix, or `NULL`

  Output Parameter:
. Estar - the reduced modulus; its value on entry is kept when no option is given

  Options Database Keys:
+ -adh_E_star <Estar> - the reduced modulus E*
. -adh_E1 <E1> - Young's modulus of body 1 (instead of -adh_E_star)
. -adh_nu1 <nu1> - Poisson ratio of body 1 (default 0)
. -adh_E2 <E2> - Young's modulus of body 2 (default: rigid)
- -adh_nu2 <nu2> - Poisson ratio of body 2 (default 0)

  Notes:
  1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2. -adh_E_star cannot be combined with the others, -adh_E1 is required when any of
  -adh_nu1, -adh_E2, -adh_nu2 is given, and -adh_nu2 needs -adh_E2. The Young's moduli must be positive and finite, the Poisson
  ratios in (-1, 0.5], and E* itself, however given, positive and finite. Every error names the option.

  Level: intermediate

.seealso: `MatCreateAdhCompliance()`, `AdhSolverSetFromOptions()`
@*/
PetscErrorCode AdhGetReducedModulusFromOptions(MPI_Comm comm, const char prefix[], PetscReal *Estar)
{
  AdhMaterial m;

  PetscFunctionBegin;
  PetscValidRealPointer(Estar, 3);
  PetscCall(PetscMemzero(&m, sizeof(m)));
  m.Estar = *Estar;
  PetscCall(AdhMaterialSetFromOptions_Private(comm, prefix, &m));
  *Estar = m.Estar;
  PetscFunctionReturn(0);
}
