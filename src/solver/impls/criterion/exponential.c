/*MC
   ADHCRITERIONEXPONENTIAL - "exponential": finite-range adhesion, an exponential attraction behind a hard wall: at gap
   g >= 0 the surfaces attract with the tension (dgamma/rho) exp(-g/rho), the potential -dgamma exp(-g/rho)

   The work of separation is dgamma, the largest tension dgamma/rho (at contact), and rho the range. It is the law of
   the contact-mechanics challenge (Muser et al. 2017) and of the peers' adhesion functionals. A step minimises the
   total energy, the elastic energy plus the law's potential over the gaps with the wall g >= 0 as a bound, from the
   last state: the quasi-static branch is followed, with its jumps into and out of contact where a minimum disappears.

   Options Database Keys:
+  -adh_criterion exponential        - selects this law
.  -adh_exponential_range <rho>      - the range rho (required, > 0)
.  -adh_minimize_rtol <1e-8>         - a step stops at this relative projected gradient of the energy
.  -adh_minimize_max_it <100000>     - the largest number of iterations (Newton steps) in a step
.  -adh_minimize_pc <fourier,none>   - the preconditioner of the minimisation
.  -adh_minimize_direction <newton,polak-ribiere> - inexact Newton steps by conjugate gradients on the free points,
                                       or the preconditioned gradient conjugated by Polak-Ribiere
.  -adh_minimize_trust_region <2>    - the Newton steps' trust region, in times the last step (0: none, stop at
                                       negative curvature)
-  -adh_minimize_monitor             - a line per iteration (and per Newton direction, its conjugate gradients)

   Level: intermediate

   Notes:
   The answer converges with the grid once the range spans a grid spacing or more and the cohesive zone several. For a
   sphere of radius R Tabor's parameter mu = (R dgamma^2 / (E*^2 rho^3))^(1/3) goes from DMT (mu -> 0, pull-off
   2 pi dgamma R) to JKR (mu -> infinity, 1.5 pi dgamma R); -adh_view prints it for a sphere. The cohesive zone (the
   cohesive area and force of the curve, and the zone's width) counts the points off the contact whose gap is at most
   rho ln 10, where the tension is at least a tenth of the largest. With a work of adhesion field dgamma(x, y) the
   tension follows it at a common range.

   Both boundaries: on the free boundary the minimisation runs on the zero-padded grid (the padding's displacements
   free); force control there finds the d that carries the force by minimisations at fixed d along the branch, a
   few to some tens a state. -adh_critical_stress, -adh_attach,
   -adh_cascade_apart and -adh_cascade_local do not apply: the hard wall is the bound of the minimisation.

.seealso: `AdhSolverSetCriterionType()`, `ADHCRITERIONDUGDALE`, `ADHCRITERIONCRACKCLOSURE`
M*/
#include "solver/solverimpl.h"

typedef struct {
  PetscReal rho; /* -adh_exponential_range */
} Exponential;

static void Law_Exponential(const void *data, PetscReal dgamma, PetscReal g, PetscReal *phi, PetscReal *dphi, PetscReal *ddphi)
{
  const PetscReal rho = ((const Exponential *)data)->rho, e = PetscExpReal(-g / rho);

  *phi   = -dgamma * e;
  *dphi  = dgamma / rho * e;
  *ddphi = -dgamma / (rho * rho) * e;
}

static PetscReal ZoneGap_Exponential(const void *data, PetscReal dgamma)
{
  return ((const Exponential *)data)->rho * PetscLogReal(10.0);
}

static PetscReal Peak_Exponential(const void *data, PetscReal dgamma)
{
  return dgamma / ((const Exponential *)data)->rho;
}

static PetscErrorCode SetFromOptions_Exponential(AdhSolver s, AdhOptionItems PetscOptionsObject)
{
  Exponential *ex = (Exponential *)s->crops.data;

  PetscFunctionBegin;
  PetscCall(AdhOptionsReal("-adh_exponential_range", "exponential: the range rho of the attraction (dgamma/rho) exp(-g/rho) at gap g (required with -adh_criterion exponential)", "ADHCRITERIONEXPONENTIAL", ex->rho, &ex->rho, NULL));
  PetscCheck(ex->rho == 0 || (ex->rho > 0 && !PetscIsInfOrNanReal(ex->rho)), PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_exponential_range must be > 0 and finite, got %g", (double)ex->rho);
  PetscFunctionReturn(0);
}

static PetscErrorCode SetUp_Exponential(AdhSolver s)
{
  Exponential *ex = (Exponential *)s->crops.data;

  PetscFunctionBegin;
  PetscCheck(ex->rho > 0, s->comm, PETSC_ERR_USER_INPUT, "-adh_criterion exponential needs the range: give -adh_exponential_range RHO (> 0)");
  PetscCheck(ex->rho < PetscMax(s->grid->Lx, s->grid->Ly), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_exponential_range %g is not below the cell's side %g: the law's range must be short against the geometry", (double)ex->rho, (double)PetscMax(s->grid->Lx, s->grid->Ly));
  PetscCall(AdhSolverLawSetUp_Private(s));
  PetscFunctionReturn(0);
}

/* Tabor's parameter of a sphere of radius R: (R dgamma^2 / (E*^2 rho^3))^(1/3). */
static PetscReal Tabor(AdhSolver s, PetscReal rho)
{
  const PetscReal E = AdhSolverSummitModulus_Private(s, s->indenter.radius, s->gamma);
  return PetscCbrtReal(s->indenter.radius * s->gamma * s->gamma / (E * E * rho * rho * rho));
}

/* The resolution report's Tabor parameter of a summit of radius R. */
static PetscReal Tabor_Exponential(AdhSolver s, PetscReal R, PetscReal dgamma)
{
  const PetscReal rho = ((Exponential *)s->crops.data)->rho;
  const PetscReal E   = AdhSolverSummitModulus_Private(s, R, dgamma);
  return PetscCbrtReal(R * dgamma * dgamma / (E * E * rho * rho * rho));
}

/* The range of its attraction: rho, whatever dgamma. */
static PetscReal Range_Exponential(AdhSolver s, PetscReal dgamma)
{
  (void)dgamma;
  return ((Exponential *)s->crops.data)->rho;
}

/* Its lines of -adh_view, and its attributes in the results file. */
static PetscErrorCode View_Exponential(AdhSolver s, PetscViewer viewer)
{
  Exponential *ex = (Exponential *)s->crops.data;
  PetscBool    isascii, ishdf5, sphere = (PetscBool)(s->indenter.type == ADH_INDENTER_SPHERE && s->gamma > 0 && ex->rho > 0 && !s->gamma_field);

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERHDF5, &ishdf5));
  if (isascii) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "range rho = %g (%g grid spacings), largest tension dgamma/rho = %g\n", (double)ex->rho, (double)(s->grid->hx > 0 ? ex->rho / PetscMin(s->grid->hx, s->grid->hy) : 0), (double)(ex->rho > 0 ? s->gamma / ex->rho : 0)));
    if (sphere) PetscCall(PetscViewerASCIIPrintf(viewer, "Tabor's mu of the sphere %g (JKR: large, DMT: small)\n", (double)Tabor(s, ex->rho)));
    PetscCall(AdhSolverMinimizeView_Private(s, viewer));
  }
  if (ishdf5) {
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "exponential_range", PETSC_REAL, &ex->rho));
    PetscCall(AdhSolverMinimizeView_Private(s, viewer)); /* minimize_rtol, minimize_direction */
    if (sphere) {
      PetscReal mu = Tabor(s, ex->rho);
      PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "tabor_mu", PETSC_REAL, &mu));
    }
  }
  PetscFunctionReturn(0);
}

/* The range and the minimisation's tolerance shape the answer: a restart repeats them. */
static PetscErrorCode Shape_Exponential(AdhSolver s, PetscInt *n, AdhShapingOption shape[])
{
  Exponential *ex = (Exponential *)s->crops.data;

  PetscFunctionBegin;
  shape[0] = (AdhShapingOption){"-adh_exponential_range", PETSC_REAL, &ex->rho};
  shape[1] = (AdhShapingOption){"-adh_minimize_rtol", PETSC_REAL, &s->minimize_rtol};
  *n       = 2;
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhCriterionCreate_Exponential(AdhSolver s)
{
  Exponential *ex;

  PetscFunctionBegin;
  PetscCall(PetscNew(&ex));
  s->crops.data                = ex;
  s->crops.attach              = ADH_ATTACH_PENETRATION;
  s->crops.cohesive            = PETSC_TRUE;
  s->crops.evaluate            = AdhSolverLawEvaluate_Private;
  s->crops.law                 = Law_Exponential;
  s->crops.zone_gap            = ZoneGap_Exponential;
  s->crops.peak                = Peak_Exponential;
  s->crops.tabor               = Tabor_Exponential;
  s->crops.tabor_name          = "Tabor's mu";
  s->crops.range               = Range_Exponential;
  s->crops.base.setfromoptions = SetFromOptions_Exponential;
  s->crops.base.view           = View_Exponential;
  s->crops.base.setup          = SetUp_Exponential;
  s->crops.base.shape          = Shape_Exponential;
  s->crops.base.memory         = AdhSolverLawMemory_Private;
  s->crops.base.destroy        = AdhSolverLawDestroy_Private;
  PetscFunctionReturn(0);
}
