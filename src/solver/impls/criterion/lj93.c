/*MC
   ADHCRITERIONLJ93 - "lj93": finite-range adhesion, a Lennard-Jones 9-3 law cut at its minimum by the hard wall: two
   half-spaces of atoms a distance z = z0 + g apart (g >= 0 the gap) have the potential
   (dgamma/2) ((z0/z)^9 - 3 (z0/z)^3) per area, -dgamma at contact

   The attraction (9 dgamma / (2 z0)) ((z0/z)^4 - (z0/z)^10) is zero at contact, peaks at
   (0.4)^(2/3) 0.6 * 4.5 dgamma/z0 = 1.466 dgamma/z0 at g = 0.165 z0 and falls off as g^-4: the smooth law of
   Lennard-Jones-type finite-range studies (Muller, Yushchenko and Derjaguin 1980; Greenwood 1997; the Adhesion
   package's Lj93 behind a hard wall). The work of separation is dgamma. A step minimises the total energy, as with
   `ADHCRITERIONEXPONENTIAL`, from the last state.

   Options Database Keys:
+  -adh_criterion lj93          - selects this law
.  -adh_lj93_distance <z0>      - the equilibrium distance z0 (required, > 0), the law's length
-  -adh_minimize_rtol, -adh_minimize_max_it, -adh_minimize_pc, -adh_minimize_direction, -adh_minimize_trust_region - the minimisation, as for
                                 `ADHCRITERIONEXPONENTIAL`

   Level: intermediate

   Notes:
   For a sphere of radius R Tabor's parameter mu = (R dgamma^2 / (E*^2 z0^3))^(1/3) (Tabor's own, with the equilibrium
   distance) goes from DMT (mu -> 0, pull-off 2 pi dgamma R) to JKR (mu -> infinity, 1.5 pi dgamma R). The range that
   the stickiness criteria take is dgamma over the peak tension, z0/1.466. The cohesive zone counts the points off the
   contact whose gap is within the tail where the tension is at least a tenth of its peak (g <= 1.35 z0).

   The boundaries, controls and options that do not apply are those of `ADHCRITERIONEXPONENTIAL`.

.seealso: `AdhSolverSetCriterionType()`, `ADHCRITERIONEXPONENTIAL`, `ADHCRITERIONDUGDALE`
M*/
#include "solver/solverimpl.h"

typedef struct {
  PetscReal z0;   /* -adh_lj93_distance */
  PetscReal zone; /* the zone's gap over z0: beyond the peak, where the tension falls to a tenth of it */
} LJ93;

/* The attraction's shape x^4 - x^10 in x = z0/z, and its peak (at x^6 = 2/5). */
static PetscReal Shape(PetscReal x)
{
  const PetscReal x4 = x * x * x * x;
  return x4 * (1.0 - x4 * x * x);
}
#define ADH_LJ93_XPEAK 0.858374218932557 /* (2/5)^(1/6) */

static void Law_LJ93(const void *data, PetscReal dgamma, PetscReal g, PetscReal *phi, PetscReal *dphi, PetscReal *ddphi)
{
  const PetscReal z0 = ((const LJ93 *)data)->z0, x = z0 / (z0 + g), x3 = x * x * x, x4 = x3 * x, x5 = x4 * x, x9 = x4 * x5;

  *phi   = 0.5 * dgamma * (x9 - 3.0 * x3);
  *dphi  = 4.5 * dgamma / z0 * (x4 - x9 * x);
  *ddphi = 4.5 * dgamma / (z0 * z0) * (-4.0 * x5 + 10.0 * x9 * x * x);
}

static PetscReal Peak_LJ93(const void *data, PetscReal dgamma)
{
  return 4.5 * dgamma / ((const LJ93 *)data)->z0 * Shape(ADH_LJ93_XPEAK);
}

static PetscReal ZoneGap_LJ93(const void *data, PetscReal dgamma)
{
  (void)dgamma;
  return ((const LJ93 *)data)->zone * ((const LJ93 *)data)->z0;
}

static PetscErrorCode SetFromOptions_LJ93(AdhSolver s, AdhOptionItems PetscOptionsObject)
{
  LJ93 *lj = (LJ93 *)s->crops.data;

  PetscFunctionBegin;
  PetscCall(AdhOptionsReal("-adh_lj93_distance", "lj93: the equilibrium distance z0 of the 9-3 law (dgamma/2)((z0/z)^9 - 3 (z0/z)^3), z = z0 + gap (required with -adh_criterion lj93)", "ADHCRITERIONLJ93", lj->z0, &lj->z0, NULL));
  PetscCheck(lj->z0 == 0 || (lj->z0 > 0 && !PetscIsInfOrNanReal(lj->z0)), PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_lj93_distance must be > 0 and finite, got %g", (double)lj->z0);
  PetscFunctionReturn(0);
}

static PetscErrorCode SetUp_LJ93(AdhSolver s)
{
  LJ93     *lj = (LJ93 *)s->crops.data;
  PetscReal lo = 0.0, hi = ADH_LJ93_XPEAK, tenth = 0.1 * Shape(ADH_LJ93_XPEAK);

  PetscFunctionBegin;
  PetscCheck(lj->z0 > 0, s->comm, PETSC_ERR_USER_INPUT, "-adh_criterion lj93 needs the equilibrium distance: give -adh_lj93_distance Z0 (> 0)");
  PetscCheck(lj->z0 < PetscMax(s->grid->Lx, s->grid->Ly), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_lj93_distance %g is not below the cell's side %g: the law's range must be short against the geometry", (double)lj->z0, (double)PetscMax(s->grid->Lx, s->grid->Ly));
  PetscCall(AdhSolverLawSetUp_Private(s));
  /* the tail's x where the tension is a tenth of the peak, by bisection (the shape rises on [0, peak]) */
  for (PetscInt it = 0; it < 60; it++) {
    const PetscReal mid = 0.5 * (lo + hi);
    if (Shape(mid) < tenth) lo = mid;
    else hi = mid;
  }
  lj->zone = 2.0 / (lo + hi) - 1.0;
  PetscFunctionReturn(0);
}

/* Tabor's parameter of a summit or sphere of radius R, with the equilibrium distance. */
static PetscReal Tabor_LJ93(AdhSolver s, PetscReal R, PetscReal dgamma)
{
  const PetscReal z0 = ((LJ93 *)s->crops.data)->z0;
  const PetscReal E = AdhSolverSummitModulus_Private(s, R, dgamma);
  return PetscCbrtReal(R * dgamma * dgamma / (E * E * z0 * z0 * z0));
}

/* The range of its attraction for the stickiness criteria: dgamma over the peak tension, as for
   the other laws (the exponential's rho, Dugdale's dgamma/s0). */
static PetscReal Range_LJ93(AdhSolver s, PetscReal dgamma)
{
  return dgamma / Peak_LJ93(s->crops.data, dgamma);
}

static PetscErrorCode View_LJ93(AdhSolver s, PetscViewer viewer)
{
  LJ93     *lj = (LJ93 *)s->crops.data;
  PetscBool isascii, ishdf5, sphere = (PetscBool)(s->indenter.type == ADH_INDENTER_SPHERE && s->gamma > 0 && lj->z0 > 0 && !s->gamma_field);

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERHDF5, &ishdf5));
  if (isascii) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "Lennard-Jones 9-3: equilibrium distance z0 = %g (%g grid spacings), largest tension %g at gap %g\n", (double)lj->z0, (double)(s->grid->hx > 0 ? lj->z0 / PetscMin(s->grid->hx, s->grid->hy) : 0), (double)(lj->z0 > 0 ? Peak_LJ93(lj, s->gamma) : 0), (double)(lj->z0 * (1.0 / ADH_LJ93_XPEAK - 1.0))));
    if (sphere) PetscCall(PetscViewerASCIIPrintf(viewer, "Tabor's mu of the sphere %g (JKR: large, DMT: small)\n", (double)Tabor_LJ93(s, s->indenter.radius, s->gamma)));
    PetscCall(AdhSolverMinimizeView_Private(s, viewer));
  }
  if (ishdf5) {
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "lj93_distance", PETSC_REAL, &lj->z0));
    PetscCall(AdhSolverMinimizeView_Private(s, viewer)); /* minimize_rtol, minimize_direction */
    if (sphere) {
      PetscReal mu = Tabor_LJ93(s, s->indenter.radius, s->gamma);
      PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "tabor_mu", PETSC_REAL, &mu));
    }
  }
  PetscFunctionReturn(0);
}

/* The distance and the minimisation's tolerance shape the answer: a restart repeats them. */
static PetscErrorCode Shape_LJ93(AdhSolver s, PetscInt *n, AdhShapingOption shape[])
{
  LJ93 *lj = (LJ93 *)s->crops.data;

  PetscFunctionBegin;
  shape[0] = (AdhShapingOption){"-adh_lj93_distance", PETSC_REAL, &lj->z0};
  shape[1] = (AdhShapingOption){"-adh_minimize_rtol", PETSC_REAL, &s->minimize_rtol};
  *n       = 2;
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhCriterionCreate_LJ93(AdhSolver s)
{
  LJ93 *lj;

  PetscFunctionBegin;
  PetscCall(PetscNew(&lj));
  s->crops.data                = lj;
  s->crops.attach              = ADH_ATTACH_PENETRATION;
  s->crops.cohesive            = PETSC_TRUE;
  s->crops.evaluate            = AdhSolverLawEvaluate_Private;
  s->crops.law                 = Law_LJ93;
  s->crops.zone_gap            = ZoneGap_LJ93;
  s->crops.peak                = Peak_LJ93;
  s->crops.stiffens            = PETSC_TRUE; /* phi'' > 0 for g < 0.165 z0 */
  s->crops.tabor               = Tabor_LJ93;
  s->crops.tabor_name          = "Tabor's mu";
  s->crops.range               = Range_LJ93;
  s->crops.base.setfromoptions = SetFromOptions_LJ93;
  s->crops.base.view           = View_LJ93;
  s->crops.base.setup          = SetUp_LJ93;
  s->crops.base.shape          = Shape_LJ93;
  s->crops.base.memory         = AdhSolverLawMemory_Private;
  s->crops.base.destroy        = AdhSolverLawDestroy_Private;
  PetscFunctionReturn(0);
}
