/*MC
   ADHCRITERIONDUGDALE - "dugdale": finite-range adhesion, Maugis' cohesive zone (Maugis 1992): the surfaces attract
   with a constant tension s0 where their gap is at most the range dgamma/s0, and not at all beyond

   A point in contact (gap 0) carries whatever pressure the solve gives and leaves the contact when its tension
   exceeds s0; a point off the contact whose gap is at most the range carries the tension s0 (the cohesive zone);
   beyond the range, nothing. The work of separation is s0 times the range, dgamma. A step finds the three sets
   (contact, cohesive zone, free) consistent at its indentation or force: by minimising the energy of the law with its
   drop at the range smoothed (the default), or by the fixed point of set updates on the sharp law
   (-adh_dugdale_route fixed-point, Maugis' law as he wrote it).

   Options Database Keys:
+  -adh_criterion dugdale                       - selects this criterion
.  -adh_dugdale_stress <s0>                     - the cohesive stress s0 (required, > 0); the range is dgamma/s0
.  -adh_dugdale_route <minimize,fixed-point>    - how a step finds the zone
-  -adh_dugdale_smoothing <0.2>                 - minimize: the tension falls from s0 to 0 linearly between the gaps
                                                  range (1 - e) and range (1 + e), the work dgamma kept

   Level: intermediate

   Notes:
   Nothing is singular at the contact's edge: the answer converges with the grid once the cohesive zone spans several
   elements. For a sphere of radius R the Tabor-Maugis parameter lambda = 2 s0 (R / (pi dgamma K^2))^(1/3), K = 4 E* / 3,
   goes from DMT (lambda -> 0, pull-off 2 pi dgamma R) to JKR (lambda -> infinity, 1.5 pi dgamma R); -adh_view prints
   it for a sphere. With a work of adhesion field dgamma(x, y) the range varies, dgamma(x, y)/s0, and s0 is the same
   everywhere (a point with dgamma = 0 holds no tension).

   With the default route each state is a minimum of the total energy (the elastic energy plus the smoothed law's
   potential, the wall g >= 0 as a bound) reached from the last, as for `ADHCRITERIONEXPONENTIAL`; its cost grows
   as the zone narrows against the contact (a state's FFT pairs about as (a/zone)^0.7, Maugis' contact radius over
   his zone's width), and the smoothing makes the pull-off
   converge faster with the grid (Maugis' sphere at lambda 1: within 0.3% on 64^2 and 0.1% on 128^2, where the fixed
   point is 6% and 3% off; on a rough cell the largest tension is converged on 128^2 where the fixed point's still
   moves 1-2% a refinement at 512^2). Both controls on both boundaries; the -adh_minimize_ options apply. In the
   zone's pressure field the tension is s0 up to the gap range (1 - e) and falls to 0 at range (1 + e).

   With -adh_dugdale_route fixed-point the cohesive tractions are held in the pressure p off the contact set: the
   force, the pressure field and the gap include them, and the set's solves take their load (one compliance multiply
   more per solve). The zone is updated
   with the contact: a set update lets go the contact points whose tension exceeds s0 and moves the zone's edge to
   where the gap is the range, and the set is solved again, until nothing changes; then the points that penetrate
   join (the attach rule penetration, its default). A point that has left the zone three times in one step stays out
   of it for the rest of the step, so that the updates end: the zone's points switch all at once, and where the zone
   is narrower than an element (s0 well above Sigma) they can otherwise flip back and forth for ever; such a state
   is not quite an equilibrium of the model, and -info :adhsolver says how many points were kept out. -adh_critical_stress, -adh_cascade_apart, -adh_cascade_local and
   the certified early stop do not apply (on either route).

.seealso: `AdhSolverSetCriterionType()`, `ADHCRITERIONCRACKCLOSURE`, `ADHCRITERIONPOHRTPOPOV`
M*/
#include "solver/solverimpl.h"

/* How a step finds the zone: the energy minimisation of the law (its traction's drop at the range
   smoothed over a share of it), or the fixed point of the set updates. */
typedef enum { ADH_DUGDALE_MINIMIZE, ADH_DUGDALE_FIXED_POINT } AdhDugdaleRoute;
static const char *const AdhDugdaleRoutes[] = {"minimize", "fixed-point", "AdhDugdaleRoute", "ADH_DUGDALE_", NULL};

typedef struct {
  PetscReal s0;     /* -adh_dugdale_stress: the cohesive stress */
  AdhDugdaleRoute route;     /* -adh_dugdale_route */
  PetscReal       smoothing; /* -adh_dugdale_smoothing: the drop spread over range (1 -+ smoothing) */
  char     *left;   /* how often each local point left the zone in the current step (ADH_ZONE_EXITS: it stays out) */
  PetscInt  nleft;
} Dugdale;

/* A point that has left the zone this often in one step stays out of it for the rest of the step:
   the zone's points switch all at once, and where the zone is narrower than an element they can
   flip back and forth for ever; a point that leaves and comes back once or twice is the usual
   settling of the zone's edge. */
#define ADH_ZONE_EXITS 3

/* The cohesive stress and range of local point k: s0 and dgamma/s0 where the work of adhesion is
   positive (and the stage is adhesive), none elsewhere. */
static inline void Cohesion(AdhSolver s, const Dugdale *dd, const PetscScalar *gamma, PetscInt k, PetscReal *s0, PetscReal *range)
{
  const PetscReal dgamma = gamma ? PetscRealPart(gamma[k]) : s->gamma;

  *s0    = s->adhesive && dgamma > 0 ? dd->s0 : 0.0;
  *range = *s0 > 0 ? dgamma / *s0 : 0.0;
}

/* With detach: the contact points whose tension exceeds s0 leave (into the zone), and every point
   off the contact takes the zone's tension where its gap is at most the range, none beyond; the
   number of points that changed (the set must be solved again if any did). Without: the largest
   tension over s0 on the contact. */
static PetscErrorCode Evaluate_Dugdale(AdhSolver s, PetscBool detach, PetscInt *removed, PetscReal *ratio)
{
  Dugdale           *dd = (Dugdale *)s->crops.data;
  PetscScalar       *pa, *xa = NULL;
  const PetscScalar *ga, *gamma = NULL;
  PetscReal          r     = 0.0;
  PetscInt           count = 0, kept = 0;

  PetscFunctionBegin;
  if (s->gamma_field) PetscCall(VecGetArrayRead(s->gamma_field, &gamma));
  PetscCall(VecGetArray(s->p, &pa));
  if (!detach) {
    for (PetscInt k = 0; k < s->nlocal; k++) {
      PetscReal s0, range;
      if (!s->in_set[k] || PetscRealPart(pa[k]) >= 0) continue;
      Cohesion(s, dd, gamma, k, &s0, &range);
      r = s0 > 0 ? PetscMax(r, -PetscRealPart(pa[k]) / s0) : PETSC_MAX_REAL;
    }
  } else {
    if (s->set_response) PetscCall(VecGetArray(s->set_response, &xa));
    for (PetscInt k = 0; k < s->nlocal; k++) {
      PetscReal s0, range;
      if (!s->in_set[k]) continue;
      Cohesion(s, dd, gamma, k, &s0, &range);
      if (PetscRealPart(pa[k]) < -s0) { /* it lets go, into the zone (its gap is zero) or free (no cohesion) */
        AdhSolverRemovePoint_Private(s, k, pa, xa);
        pa[k] = -s0;
        count++;
      }
    }
    if (xa) PetscCall(VecRestoreArray(s->set_response, &xa));
    /* the gap of the pressure with those points gone, and the zone's edge where it is the range */
    PetscCall(VecRestoreArray(s->p, &pa));
    PetscCall(AdhSolverComputeGap_Private(s));
    PetscCall(VecGetArray(s->p, &pa));
    PetscCall(VecGetArrayRead(s->g, &ga));
    for (PetscInt k = 0; k < s->nlocal; k++) {
      PetscReal s0, range, want;
      if (s->in_set[k]) continue;
      Cohesion(s, dd, gamma, k, &s0, &range);
      want = s0 > 0 && PetscRealPart(ga[k]) <= range && dd->left[k] < ADH_ZONE_EXITS ? -s0 : 0.0;
      if (s0 > 0 && PetscRealPart(ga[k]) <= range && want == 0.0) kept++;
      if (PetscRealPart(pa[k]) != want) {
        if (want == 0.0) dd->left[k]++; /* after ADH_ZONE_EXITS it stays out for the rest of the step: the updates end */
        pa[k] = want;
        count++;
      }
    }
    PetscCall(VecRestoreArrayRead(s->g, &ga));
  }
  PetscCall(VecRestoreArray(s->p, &pa));
  if (gamma) PetscCall(VecRestoreArrayRead(s->gamma_field, &gamma));
  if (ratio) PetscCall(MPIU_Allreduce(&r, ratio, 1, MPIU_REAL, MPIU_MAX, s->comm));
  if (detach) {
    PetscInt total[2] = {count, kept};
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, total, 2, MPIU_INT, MPI_SUM, s->comm));
    if (removed) *removed = total[0];
    s->gap_current = (PetscBool)(total[0] == 0); /* nothing changed on any rank: the attach test that follows takes this gap */
    if (!total[0] && total[1]) PetscCall(PetscInfo(s, "dugdale: %" PetscInt_FMT " points within the range kept out of the zone after %d exits in this step (the zone is not resolved)\n", total[1], ADH_ZONE_EXITS));
  } else if (removed) *removed = 0;
  PetscFunctionReturn(0);
}

/* The law of the minimisation: the tension s0 up to the gap range (1 - e), falling linearly to 0
   at range (1 + e) (the work of separation stays s0 range = dgamma), none beyond. */
static void Law_Dugdale(const void *data, PetscReal dgamma, PetscReal g, PetscReal *phi, PetscReal *dphi, PetscReal *ddphi)
{
  const Dugdale  *dd = (const Dugdale *)data;
  const PetscReal range = dgamma / dd->s0, a = range * (1.0 - dd->smoothing), b = range * (1.0 + dd->smoothing);

  if (g <= a) {
    *phi   = -dgamma + dd->s0 * g;
    *dphi  = dd->s0;
    *ddphi = 0.0;
  } else if (g < b) {
    *phi   = -0.5 * dd->s0 * (b - g) * (b - g) / (b - a);
    *dphi  = dd->s0 * (b - g) / (b - a);
    *ddphi = -dd->s0 / (b - a);
  } else *phi = *dphi = *ddphi = 0.0;
}

static PetscReal ZoneGap_Dugdale(const void *data, PetscReal dgamma)
{
  return dgamma / ((const Dugdale *)data)->s0;
}

static PetscReal Peak_Dugdale(const void *data, PetscReal dgamma)
{
  return ((const Dugdale *)data)->s0;
}

/* A step begins: no point has left the zone yet. */
static PetscErrorCode Begin_Dugdale(AdhSolver s)
{
  Dugdale *dd = (Dugdale *)s->crops.data;

  PetscFunctionBegin;
  if (dd->nleft != s->nlocal) {
    PetscCall(PetscFree(dd->left));
    PetscCall(PetscMalloc1(s->nlocal + 1, &dd->left));
    dd->nleft = s->nlocal;
  }
  PetscCall(PetscArrayzero(dd->left, s->nlocal));
  PetscFunctionReturn(0);
}

/* The route decides the kind of step: a law minimises, none updates sets. */
static PetscErrorCode SetRoute(AdhSolver s)
{
  const Dugdale *dd = (const Dugdale *)s->crops.data;

  PetscFunctionBegin;
  s->crops.law      = dd->route == ADH_DUGDALE_MINIMIZE ? Law_Dugdale : NULL;
  s->crops.zone_gap = dd->route == ADH_DUGDALE_MINIMIZE ? ZoneGap_Dugdale : NULL;
  s->crops.peak     = dd->route == ADH_DUGDALE_MINIMIZE ? Peak_Dugdale : NULL;
  PetscFunctionReturn(0);
}

static PetscErrorCode SetFromOptions_Dugdale(AdhSolver s, AdhOptionItems PetscOptionsObject)
{
  Dugdale *dd = (Dugdale *)s->crops.data;

  PetscFunctionBegin;
  PetscCall(AdhOptionsReal("-adh_dugdale_stress", "dugdale: the cohesive stress s0, the tension the surfaces hold while their gap is at most the range dgamma/s0 (required with -adh_criterion dugdale)", "ADHCRITERIONDUGDALE", dd->s0, &dd->s0, NULL));
  PetscCheck(dd->s0 == 0 || (dd->s0 > 0 && !PetscIsInfOrNanReal(dd->s0)), PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_dugdale_stress must be > 0 and finite, got %g", (double)dd->s0);
  PetscCall(PetscOptionsEnum("-adh_dugdale_route", "dugdale: how a step finds the zone: minimise the energy of the law (its drop at the range smoothed, -adh_dugdale_smoothing; the default) or the fixed point of set updates (Maugis' sharp law; slow once the zone is a few elements wide)", "ADHCRITERIONDUGDALE", AdhDugdaleRoutes, (PetscEnum)dd->route, (PetscEnum *)&dd->route, NULL));
  PetscCall(AdhOptionsReal("-adh_dugdale_smoothing", "dugdale, minimize route: the tension falls from s0 to 0 linearly between the gaps range (1 - e) and range (1 + e), the work dgamma kept", "ADHCRITERIONDUGDALE", dd->smoothing, &dd->smoothing, NULL));
  PetscCheck(dd->smoothing > 0 && dd->smoothing < 1, PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_dugdale_smoothing must lie in (0, 1), got %g", (double)dd->smoothing);
  PetscCall(SetRoute(s));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetUp_Dugdale(AdhSolver s)
{
  Dugdale *dd = (Dugdale *)s->crops.data;

  PetscFunctionBegin;
  PetscCheck(dd->s0 > 0, s->comm, PETSC_ERR_USER_INPUT, "-adh_criterion dugdale needs the cohesive stress: give -adh_dugdale_stress S (> 0; the range is dgamma/S)");
  PetscCheck(s->sigma_fixed == 0, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_critical_stress does not apply to -adh_criterion dugdale, whose cohesive stress is -adh_dugdale_stress");
  PetscCall(Begin_Dugdale(s));
  /* their marks zero the pressure off the set, and the local solves leave out the zone's load */
  PetscCheck(!s->cascade_apart, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_cascade_apart does not apply to -adh_criterion dugdale");
  PetscCheck(!(s->cascade_local > 0), s->comm, PETSC_ERR_ARG_INCOMP, "-adh_cascade_local does not apply to -adh_criterion dugdale");
  PetscCheck(s->attach == ADH_ATTACH_PENETRATION, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_attach %s does not apply to -adh_criterion dugdale: a point joins the contact when it penetrates (-adh_attach penetration)", AdhAttaches[s->attach]);
  PetscFunctionReturn(0);
}

/* Tabor-Maugis' lambda of a sphere of radius R: 2 s0 (R / (pi dgamma K^2))^(1/3), K = 4 E* / 3. */
static PetscReal Lambda(AdhSolver s, PetscReal s0)
{
  const PetscReal R = s->indenter.radius, K = 4.0 * AdhSolverSummitModulus_Private(s, R, s->gamma) / 3.0;
  return 2.0 * s0 * PetscCbrtReal(R / (PETSC_PI * s->gamma * K * K));
}

/* The resolution report's Tabor-Maugis parameter of a summit of radius R. */
static PetscReal Tabor_Dugdale(AdhSolver s, PetscReal R, PetscReal dgamma)
{
  const PetscReal K = 4.0 * AdhSolverSummitModulus_Private(s, R, dgamma) / 3.0;
  return 2.0 * ((Dugdale *)s->crops.data)->s0 * PetscCbrtReal(R / (PETSC_PI * dgamma * K * K));
}

/* The range of its attraction: the gap h0 = dgamma / s0 at which the stress s0 ends. */
static PetscReal Range_Dugdale(AdhSolver s, PetscReal dgamma)
{
  return dgamma / ((Dugdale *)s->crops.data)->s0;
}

/* Its line of -adh_view, and its attributes in the results file. */
static PetscErrorCode View_Dugdale(AdhSolver s, PetscViewer viewer)
{
  Dugdale  *dd    = (Dugdale *)s->crops.data;
  PetscReal range = dd->s0 > 0 ? s->gamma / dd->s0 : 0.0;
  PetscBool isascii, ishdf5, sphere = (PetscBool)(s->indenter.type == ADH_INDENTER_SPHERE && s->gamma > 0 && dd->s0 > 0);

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERHDF5, &ishdf5));
  if (isascii) {
    if (s->gamma_field) PetscCall(PetscViewerASCIIPrintf(viewer, "cohesive stress s0 = %g; the range dgamma(x,y)/s0 follows the field\n", (double)dd->s0));
    else PetscCall(PetscViewerASCIIPrintf(viewer, "cohesive stress s0 = %g, range dgamma/s0 = %g (%g grid spacings)\n", (double)dd->s0, (double)range, (double)(s->grid->hx > 0 ? range / PetscMin(s->grid->hx, s->grid->hy) : 0)));
    if (sphere && !s->gamma_field) PetscCall(PetscViewerASCIIPrintf(viewer, "Tabor-Maugis lambda of the sphere %g (JKR: large, DMT: small)\n", (double)Lambda(s, dd->s0)));
    if (dd->route == ADH_DUGDALE_MINIMIZE) {
      PetscCall(PetscViewerASCIIPrintf(viewer, "the tension falls from s0 to 0 between the gaps range (1 -+ %g)\n", (double)dd->smoothing));
      PetscCall(AdhSolverMinimizeView_Private(s, viewer));
    } else PetscCall(PetscViewerASCIIPrintf(viewer, "steps: the fixed point of set updates (-adh_dugdale_route fixed-point)\n"));
  }
  if (ishdf5) {
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "dugdale_stress", PETSC_REAL, &dd->s0));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "dugdale_route", PETSC_STRING, AdhDugdaleRoutes[dd->route]));
    if (dd->route == ADH_DUGDALE_MINIMIZE) {
      PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "dugdale_smoothing", PETSC_REAL, &dd->smoothing));
      PetscCall(AdhSolverMinimizeView_Private(s, viewer)); /* minimize_rtol, minimize_direction */
    }
    if (!s->gamma_field) PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "dugdale_range", PETSC_REAL, &range));
    if (sphere && !s->gamma_field) {
      PetscReal lambda = Lambda(s, dd->s0);
      PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "tabor_lambda", PETSC_REAL, &lambda));
    }
  }
  PetscFunctionReturn(0);
}

/* What it adds to the memory model: the tractions off the set and their load (two grid vectors,
   made at the first solve with a zone) and a byte a point for the zone's exits. */
static PetscErrorCode Memory_Dugdale(AdhSolver s, PetscLogDouble *per_point, PetscLogDouble *per_rank)
{
  PetscFunctionBegin;
  *per_point = 2.0 * sizeof(PetscScalar) + 1.0;
  if (((Dugdale *)s->crops.data)->route == ADH_DUGDALE_MINIMIZE) *per_point = AdhSolverMinimizeMemory_Private(s);
  *per_rank  = 0.0;
  PetscFunctionReturn(0);
}

/* The cohesive stress shapes the answer: a restart repeats it. */
static PetscErrorCode Shape_Dugdale(AdhSolver s, PetscInt *n, AdhShapingOption shape[])
{
  Dugdale *dd = (Dugdale *)s->crops.data;

  PetscFunctionBegin;
  shape[0] = (AdhShapingOption){"-adh_dugdale_stress", PETSC_REAL, &dd->s0};
  shape[1] = (AdhShapingOption){"-adh_dugdale_route", PETSC_STRING, AdhDugdaleRoutes[dd->route], AdhDugdaleRoutes[ADH_DUGDALE_FIXED_POINT]}; /* older checkpoints: the fixed point */
  *n       = 2;
  if (dd->route == ADH_DUGDALE_MINIMIZE) {
    shape[2] = (AdhShapingOption){"-adh_dugdale_smoothing", PETSC_REAL, &dd->smoothing};
    shape[3] = (AdhShapingOption){"-adh_minimize_rtol", PETSC_REAL, &s->minimize_rtol};
    *n       = 4;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Dugdale(AdhSolver s)
{
  Dugdale *dd = (Dugdale *)s->crops.data;

  PetscFunctionBegin;
  PetscCall(PetscFree(dd->left));
  PetscCall(AdhSolverMinimizeDestroy_Private(s));
  PetscCall(PetscFree(s->crops.data));
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhCriterionCreate_Dugdale(AdhSolver s)
{
  Dugdale *dd;

  PetscFunctionBegin;
  PetscCall(PetscNew(&dd));
  dd->route                    = ADH_DUGDALE_MINIMIZE; /* more accurate at the same cost: docs/theory/minimisation.md */
  dd->smoothing                = 0.2;
  s->crops.data                = dd;
  s->crops.attach              = ADH_ATTACH_PENETRATION;
  s->crops.cohesive            = PETSC_TRUE;
  s->crops.evaluate            = Evaluate_Dugdale;
  s->crops.begin               = Begin_Dugdale;
  s->crops.tabor               = Tabor_Dugdale;
  s->crops.tabor_name          = "Maugis' lambda";
  s->crops.range               = Range_Dugdale;
  s->crops.base.setfromoptions = SetFromOptions_Dugdale;
  s->crops.base.view           = View_Dugdale;
  s->crops.base.setup          = SetUp_Dugdale;
  s->crops.base.shape          = Shape_Dugdale;
  s->crops.base.memory         = Memory_Dugdale;
  s->crops.base.destroy        = Destroy_Dugdale;
  PetscCall(SetRoute(s)); /* the default route's ops from the start, as the view and the checkpoint's shape say */
  PetscFunctionReturn(0);
}
