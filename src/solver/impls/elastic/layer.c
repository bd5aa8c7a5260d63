/*MC
   ADHELASTICLAYER - "layer": an elastic layer of thickness T on a rigid base, bonded to it or free to slip, pressed by
   a rigid or elastic half-space indenter, on a periodic cell

   Options Database Keys:
+  -adh_elastic layer                  - selects this body
.  -adh_layer_thickness <T>            - the layer's thickness (required, > 0)
.  -adh_layer_base <bonded,slip>       - the layer bonded to the base (the default) or slipping on it without friction
.  -adh_E1 <E1>, -adh_nu1 <nu1>        - the layer's Young's modulus and Poisson ratio (both required; nu1 from 0 to 0.5)
-  -adh_E2 <E2>, -adh_nu2 <nu2>        - the indenter's (default: rigid)

   Level: intermediate

   Notes:
   A pressure wave of wave number q on the layer's free surface (no shear) moves it by C(q) times the pressure:
.vb
   C(q) = 2 (1 - nu1^2) / (E1 q) f(qT) + 2 (1 - nu2^2) / (E2 q)
   bonded: f(t) = (k sinh 2t - 2t) / (k cosh 2t + 2t^2 + (1 + k^2)/2),  k = 3 - 4 nu1
   slip:   f(t) = (cosh 2t - 1) / (sinh 2t + 2t)
.ve
   f -> 1 for a thick layer (qT >> 1: the half-space). A thin bonded layer stiffens without bound as it becomes
   incompressible: C -> T (1 + nu1)(1 - 2 nu1)/(E1 (1 - nu1)), the oedometer's, for nu1 < 0.5, and C -> q^2 T^3/E1 at
   nu1 = 0.5; a thin slipping one tends to T (1 - nu1^2)/E1, in plane strain under uniaxial stress. The mean mode (q = 0)
   is left to the indentation as on a periodic half-space: d is the approach to the surface's mean plane, without the
   layer's uniform compression under the mean pressure.

   The element's self-compliance and self-energy are the half-space's of E* (Love's, Pohrt and Popov's chi) plus what
   the layer adds under the element's own uniform pressure on the cell: the sums over the cell's wave vectors of
   C(q) - 2/(E* q) times the element's shape factor S(q) = sinc(qx hx/2) sinc(qy hy/2) (at its centre) and S(q)^2 (its
   average), carried beyond the grid's modes to where the difference vanishes (or eight bands of aliases). They are
   exact to the half-space's own offset between Love's free-space self-compliance and the periodic cell's, 0.2% of
   Love's on 512^2, which weighs more where the layer's own value is far below the half-space's: for a layer thinner
   than a grid spacing they are approximate (-adh_view says so). The criteria of zero range (crack-closure,
   pohrt-popov) and the attach rule reach use them, the cohesive laws do not. The critical stress follows from them as
   on the half-space. The estimates made before a run (the JKR radius of the smallest asperities, Tabor's parameter,
   stickiness) use the modulus 2/(q C(q)) at the contact's wave number.

   The free boundary is refused: the layer's compliance is periodic only.

.seealso: `AdhSolverSetElasticType()`, `ADHELASTICHALFSPACE`, `MatCreateAdhPeriodicSymbolOperator()`
M*/
#include "solver/solverimpl.h"

typedef enum { ADH_LAYER_BONDED, ADH_LAYER_SLIP } AdhLayerBase;
static const char *const AdhLayerBases[] = {"bonded", "slip", "AdhLayerBase", "ADH_LAYER_", NULL};

typedef struct {
  PetscReal    T;              /* -adh_layer_thickness */
  AdhLayerBase base;           /* -adh_layer_base */
  PetscReal    E1, nu1, E2, nu2;
  PetscReal    ratio;          /* the element's self-compliance over the half-space's (for the view) */
  PetscBool    thin;           /* thinner than a grid spacing: the element's constants approximate */
} Layer;

/* sinh(x) - x without the cancellation of small x */
static PetscReal SinhMinusX(PetscReal x)
{
  if (PetscAbsReal(x) < 0.5) {
    const PetscReal x2 = x * x;
    return x * x2 / 6.0 * (1.0 + x2 / 20.0 * (1.0 + x2 / 42.0 * (1.0 + x2 / 72.0 * (1.0 + x2 / 110.0 * (1.0 + x2 / 156.0)))));
  }
  return PetscSinhReal(x) - x;
}

/* The layer's factor f(qT) over the half-space's 2 (1 - nu1^2)/(E1 q); written with e = exp(-2t)
   where cosh 2t would overflow. */
static PetscReal LayerFactor(const Layer *l, PetscReal t)
{
  const PetscReal k = 3.0 - 4.0 * l->nu1;

  if (2.0 * t > 40.0) {
    const PetscReal e = PetscExpReal(-2.0 * t);
    if (l->base == ADH_LAYER_BONDED) return (k * (1.0 - e * e) - 4.0 * t * e) / (k * (1.0 + e * e) + (4.0 * t * t + 1.0 + k * k) * e);
    return (1.0 - e) * (1.0 - e) / (1.0 - e * e + 4.0 * t * e);
  }
  if (l->base == ADH_LAYER_BONDED) return (k * SinhMinusX(2.0 * t) + 2.0 * t * (k - 1.0)) / (k * PetscCoshReal(2.0 * t) + 2.0 * t * t + 0.5 * (1.0 + k * k));
  {
    const PetscReal sh = PetscSinhReal(t);
    return 2.0 * sh * sh / (PetscSinhReal(2.0 * t) + 2.0 * t);
  }
}

/* C(q): the layer's and the indenter's compliance to a pressure wave of wave number q > 0 */
static PetscReal Symbol_Layer(void *ctx, PetscReal q)
{
  const Layer    *l = (const Layer *)ctx;
  const PetscReal c = 2.0 * (1.0 - l->nu1 * l->nu1) / (l->E1 * q) * LayerFactor(l, q * l->T);
  return PetscIsInfReal(l->E2) ? c : c + 2.0 * (1.0 - l->nu2 * l->nu2) / (l->E2 * q);
}

static PetscErrorCode CreateOperators_Layer(AdhSolver s, AdhGrid grid, AdhBoundary boundary, Mat *K, Mat *S)
{
  PetscFunctionBegin;
  PetscCall(AdhElasticPeriodicOperators_Private(s, grid, boundary, Symbol_Layer, s->eops.data, K, S));
  PetscFunctionReturn(0);
}

static PetscReal Modulus_Layer(AdhSolver s, PetscReal q)
{
  return 2.0 / (q * Symbol_Layer(s->eops.data, q));
}

static PetscErrorCode SetFromOptions_Layer(AdhSolver s, AdhOptionItems PetscOptionsObject)
{
  Layer *l = (Layer *)s->eops.data;

  PetscFunctionBegin;
  PetscCall(AdhOptionsReal("-adh_layer_thickness", "layer: the layer's thickness T on its rigid base (required with -adh_elastic layer)", "ADHELASTICLAYER", l->T, &l->T, NULL));
  PetscCheck(l->T == 0 || (l->T > 0 && !PetscIsInfOrNanReal(l->T)), PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_layer_thickness must be > 0 and finite, got %g", (double)l->T);
  PetscCall(PetscOptionsEnum("-adh_layer_base", "layer: bonded to the rigid base, or slipping on it without friction", "ADHELASTICLAYER", AdhLayerBases, (PetscEnum)l->base, (PetscEnum *)&l->base, NULL));
  PetscFunctionReturn(0);
}

/* The solids' constants, and the element's self-compliance and self-energy: the half-space's of E*
   and what the layer adds. */
static PetscErrorCode SetUp_Layer(AdhSolver s)
{
  Layer             *l = (Layer *)s->eops.data;
  const AdhGrid      g = s->grid;
  const AdhMaterial *m = &s->material;

  PetscFunctionBegin;
  PetscCheck(l->T > 0, s->comm, PETSC_ERR_USER_INPUT, "-adh_elastic layer needs the thickness: give -adh_layer_thickness T (> 0)");
  PetscCheck(m->solids, s->comm, PETSC_ERR_USER_INPUT, "-adh_elastic layer needs the layer's own constants: give -adh_E1 E and -adh_nu1 NU (E* alone, -adh_E_star, does not fix a layer's stiffness)");
  PetscCheck(m->nu1_set, s->comm, PETSC_ERR_USER_INPUT, "-adh_elastic layer needs the layer's Poisson ratio: give -adh_nu1 NU (0 to 0.5; 0.5 incompressible)");
  PetscCheck(m->nu1 >= 0.0 && m->nu1 <= 0.5, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_nu1: the layer's Poisson ratio must lie in [0, 0.5], got %g", (double)m->nu1);
  l->E1 = m->E1; l->nu1 = m->nu1; l->E2 = m->E2; l->nu2 = m->nu2;
  PetscCall(AdhElasticPeriodicConstants_Private(s, Symbol_Layer, l, s->Estar, l->T, &l->thin));
  l->ratio = s->eops.self_compliance / AdhLoveCoefficient(0.0, 0.0, g->hx, g->hy, s->Estar);
  PetscFunctionReturn(0);
}

static PetscErrorCode Shape_Layer(AdhSolver s, PetscInt *n, AdhShapingOption shape[])
{
  Layer *l = (Layer *)s->eops.data;

  PetscFunctionBegin;
  shape[0] = (AdhShapingOption){"-adh_layer_thickness", PETSC_REAL, &l->T};
  shape[1] = (AdhShapingOption){"-adh_layer_base", PETSC_STRING, AdhLayerBases[l->base]};
  shape[2] = (AdhShapingOption){"-adh_E1", PETSC_REAL, &l->E1};
  shape[3] = (AdhShapingOption){"-adh_nu1", PETSC_REAL, &l->nu1};
  shape[4] = (AdhShapingOption){"-adh_E2", PETSC_REAL, &l->E2};
  shape[5] = (AdhShapingOption){"-adh_nu2", PETSC_REAL, &l->nu2};
  *n       = 6;
  PetscFunctionReturn(0);
}

/* Its lines of -adh_view, and its attributes in the results file. */
static PetscErrorCode View_Layer(AdhSolver s, PetscViewer viewer)
{
  Layer    *l = (Layer *)s->eops.data;
  PetscBool isascii, ishdf5;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERHDF5, &ishdf5));
  if (isascii) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "elastic layer of thickness %g %s on a rigid base: E1 = %g, nu1 = %g; indenter %s", (double)l->T, l->base == ADH_LAYER_BONDED ? "bonded" : "slipping", (double)l->E1, (double)l->nu1, PetscIsInfReal(l->E2) ? "rigid" : "elastic"));
    if (!PetscIsInfReal(l->E2)) PetscCall(PetscViewerASCIIPrintf(viewer, ", E2 = %g, nu2 = %g", (double)l->E2, (double)l->nu2));
    PetscCall(PetscViewerASCIIPrintf(viewer, "\n  thickness over the grid spacing %g; the element's self-compliance %g times the half-space's of E* = %g%s\n", (double)(l->T / PetscMin(s->grid->hx, s->grid->hy)), (double)l->ratio, (double)s->Estar, l->thin ? " (approximate: the layer is thinner than a grid spacing)" : ""));
  }
  if (ishdf5) {
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "layer_thickness", PETSC_REAL, &l->T));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "layer_base", PETSC_STRING, AdhLayerBases[l->base]));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "E1", PETSC_REAL, &l->E1));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "nu1", PETSC_REAL, &l->nu1));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "E2", PETSC_REAL, &l->E2));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "nu2", PETSC_REAL, &l->nu2));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Layer(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(s->eops.data));
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhElasticCreate_Layer(AdhSolver s)
{
  Layer *l;

  PetscFunctionBegin;
  PetscCall(PetscNew(&l));
  l->base                     = ADH_LAYER_BONDED;
  l->E2                       = (PetscReal)INFINITY;
  s->eops.data                = l;
  s->eops.periodic_only       = PETSC_TRUE;
  s->eops.create_operators    = CreateOperators_Layer;
  s->eops.modulus             = Modulus_Layer;
  s->eops.critical_stress     = AdhElasticCriticalStress_Private;
  s->eops.base.setfromoptions = SetFromOptions_Layer;
  s->eops.base.setup          = SetUp_Layer;
  s->eops.base.shape          = Shape_Layer;
  s->eops.base.view           = View_Layer;
  s->eops.base.destroy        = Destroy_Layer;
  PetscFunctionReturn(0);
}
