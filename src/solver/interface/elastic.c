/* Elastic body, a registered type (-adh_elastic): what deforms under the contact's pressure. The
   types are in impls/elastic/, a file each, registered in impls/register.c; each fills in
   AdhElasticOps (solverimpl.h): the compliance and the stiffness on a grid, and the elastic
   constants the solver needs (an element's self-compliance and self-energy, the mean mode's
   compliance, the modulus of the estimates), and owns its options, view and data.

   halfspace: an elastic half-space, free or periodic (impls/elastic/halfspace.c).
   layer:     an elastic layer of finite thickness on a rigid base, bonded or slipping, periodic
              (impls/elastic/layer.c). */
#include "solver/solverimpl.h"

AdhRegistry AdhElastics = {"-adh_elastic", "elastic body", NULL};

/*@
  AdhElasticRegister - Adds an elastic body type

  Not Collective

  Input Parameters:
+ name   - the type's name, as given to `AdhSolverSetElasticType()` and -adh_elastic
- create - the function that gives a solver this body: it fills in the solver's `AdhElasticOps` (create_operators, modulus,
           the flags periodic_only and halfspace, and the ops every type may have: setfromoptions, view, setup, destroy,
           shape, checkpoint, memory; declared in the private header src/solver/solverimpl.h) and makes its data

  Calling sequence of `create`:
. s - the solver, whose previous body has been destroyed

  Level: advanced

  Notes:
  The built-in types, `ADHELASTICHALFSPACE` and `ADHELASTICLAYER`, are registered when the package is initialized, which this
  function does first. Registering a name again replaces its function.

  A new body is one file in src/solver/impls/elastic/ and its registration line in src/solver/impls/register.c
  (docs/developers/code-map.md). Its setup runs first of the solver's set-up and sets the constants of `AdhElasticOps`: the
  element's self-compliance, its self-energy (Pohrt and Popov's chi, here chi_per_area), the critical stress, and the mean
  mode's compliance. A periodic body gets its operators from its compliance symbol with
  `MatCreateAdhPeriodicSymbolOperator()`.

.seealso: `AdhSolverSetElasticType()`, `AdhSolverGetElasticType()`, `AdhCriterionRegister()`
@*/
PetscErrorCode AdhElasticRegister(const char name[], PetscErrorCode (*create)(AdhSolver))
{
  PetscFunctionBegin;
  PetscValidCharPointer(name, 1);
  PetscValidFunction(create, 2);
  PetscCall(AdhSolverInitializePackage());
  PetscCall(AdhRegistryAdd_Private(&AdhElastics, name, (PetscVoidFunction)create));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverSetElasticType - Sets the elastic body: what deforms under the contact's pressure

  Logically Collective

  Input Parameters:
+ s    - the solver
- type - the body's name: `ADHELASTICHALFSPACE` (the default: an elastic half-space of reduced modulus E*, on a free or
         periodic boundary), `ADHELASTICLAYER` (a layer of thickness -adh_layer_thickness on a rigid base, bonded or
         slipping, on a periodic cell), or one registered with `AdhElasticRegister()`

  Options Database Key:
. -adh_elastic <halfspace,layer> - the elastic body

  Level: intermediate

  Notes:
  The body cannot change after `AdhSolverSetUp()`; setting the type the solver already has does nothing. An unknown name is
  an error that lists the registered ones. The boundary (-adh_boundary) stays a choice of its own; a body that has no
  free-boundary compliance (a layer) refuses the free boundary at set-up.

.seealso: `AdhSolverGetElasticType()`, `AdhElasticRegister()`, `ADHELASTICHALFSPACE`, `ADHELASTICLAYER`
@*/
PetscErrorCode AdhSolverSetElasticType(AdhSolver s, AdhElasticType type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidCharPointer(type, 2);
  PetscCall(AdhSolverSetType_Private(s, &AdhElastics, s->elastic_type, &s->eops.base, sizeof(s->eops), type, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetElasticType - Gets the name of the elastic body

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. type - the body's name, for example `ADHELASTICHALFSPACE`

  Level: intermediate

  Note:
  The string is the solver's: do not free it; it holds the name until the body changes.

.seealso: `AdhSolverSetElasticType()`, `AdhElasticRegister()`
@*/
PetscErrorCode AdhSolverGetElasticType(AdhSolver s, AdhElasticType *type)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(type, 2);
  *type = s->elastic_type;
  PetscFunctionReturn(0);
}

void AdhSolverGetTypeOps_Private(AdhSolver s, AdhTypeOps *ops[ADH_NUM_KINDS], AdhRegistry *regs[ADH_NUM_KINDS], const char *names[ADH_NUM_KINDS])
{
  AdhTypeOps  *o[ADH_NUM_KINDS] = {&s->eops.base, &s->crops.base, &s->cops.base, &s->pops.base};
  AdhRegistry *r[ADH_NUM_KINDS] = {&AdhElastics, &AdhCriteria, &AdhControls, &AdhPredictors};
  const char  *n[ADH_NUM_KINDS] = {s->elastic_type, s->criterion_type, s->control_type, s->predictor_type};

  for (PetscInt k = 0; k < ADH_NUM_KINDS; k++) {
    if (ops) ops[k] = o[k];
    if (regs) regs[k] = r[k];
    if (names) names[k] = n[k];
  }
}

/* The excess of a modulus E over the body's at the wave number 1/a of the JKR radius a it gives. */
static PetscReal SummitExcess(AdhSolver s, PetscReal R, PetscReal dgamma, PetscReal E)
{
  const PetscReal a = PetscCbrtReal(9.0 * PETSC_PI * dgamma * R * R / (8.0 * E));
  return E - s->eops.modulus(s, 1.0 / a);
}

/* A JKR contact's radius a = (9 pi dgamma R^2 / (8 E))^(1/3) with E the body's modulus at the wave
   number 1/a (the half-space's E* needs no search). The excess grows with E (a stiffer guess, a
   smaller contact, a modulus nearer the half-space's): bisected in log E between a bracket
   widened by factors of 2 (a fixed point cycles where the modulus goes as a^-3, on a thin
   incompressible layer), to 1e-6. */
PetscReal AdhSolverSummitModulus_Private(AdhSolver s, PetscReal R, PetscReal dgamma)
{
  PetscReal lo = s->Estar, hi = s->Estar;

  if (s->eops.halfspace || !(R > 0) || !(dgamma > 0)) return s->Estar;
  for (PetscInt k = 0; k < 200 && SummitExcess(s, R, dgamma, lo) > 0; k++) lo *= 0.5;
  for (PetscInt k = 0; k < 200 && SummitExcess(s, R, dgamma, hi) < 0; k++) hi *= 2.0;
  for (PetscInt it = 0; it < 100 && hi > lo * (1.0 + 1e-6); it++) {
    const PetscReal mid = PetscSqrtReal(lo * hi);
    if (SummitExcess(s, R, dgamma, mid) < 0) lo = mid;
    else hi = mid;
  }
  return PetscSqrtReal(lo * hi);
}
