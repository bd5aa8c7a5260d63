/* AdhSolver's life cycle: create, destroy, and the getters of what it holds. Options are read in
   solveropts.c, set-up in solversetup.c, one step in step.c and the load controls, the path in
   path.c, results in src/results/. */
#include "solver/solverimpl.h"

const char *const AdhStarts[]   = {"hertz", "adhesive", "AdhStart", "ADH_START_", NULL};
const char *const AdhAttaches[] = {"penetration", "reach", "griffith", "AdhAttach", "ADH_ATTACH_", NULL};

/*@
  AdhSolverCreate - Creates an adhesive contact solver with the default problem and settings

  Collective

  Input Parameter:
. comm - the MPI communicator of the solver

  Output Parameter:
. solver - the new solver

  Level: beginner

  Notes:
  The defaults: a free boundary, E* = 1, no adhesion (dgamma = 0), a sphere of radius 1 (punch radius 0.25 and cone
  slope 0.1 for those indenters) on a 64 x 64 grid of side 1, a Hertz start, the path 0.01,0 with 10 steps per leg,
  displacement control (`ADHCONTROLDISPLACEMENT`), the crack-closure detachment criterion (`ADHCRITERIONCRACKCLOSURE`)
  with the griffith attach rule, and the polonsky-keer predictor, which `AdhSolverSetUp()` replaces by none on a free
  boundary unless a predictor was chosen.

  Change them with `AdhSolverSetFromOptions()` and the setters, then call `AdhSolverSetUp()`, or let the first
  `AdhSolverStart()`, `AdhSolverStep()` or `AdhSolverSolvePath()` call it. Free the solver with `AdhSolverDestroy()`.

.seealso: `AdhSolverSetFromOptions()`, `AdhSolverSetUp()`, `AdhSolverSolvePath()`, `AdhSolverDestroy()`,
          `AdhSolverSetOptionsPrefix()`, `AdhSolverView()`
@*/
PetscErrorCode AdhSolverCreate(MPI_Comm comm, AdhSolver *solver)
{
  AdhSolver s;

  PetscFunctionBegin;
  PetscValidPointer(solver, 2);
  PetscCall(AdhSolverInitializePackage());
  PetscCall(PetscHeaderCreate(s, ADH_CLASSID, "AdhSolver", "Adhesive contact solver", "AdhSolver", comm, AdhSolverDestroy, AdhSolverView));
  s->ops->view             = AdhSolverView;
  PetscCall(PetscObjectChangeTypeName((PetscObject)s, "bem")); /* one kind of solver; its types are the criterion's, control's, predictor's */
  s->comm                  = comm;
  s->boundary              = ADH_BOUNDARY_FREE;
  s->Estar                 = 1.0;
  s->gamma                 = 0.0;
  s->indenter.type         = ADH_INDENTER_SPHERE;
  s->indenter.radius       = 1.0;
  s->indenter.punch_radius = 0.25;
  s->indenter.cone_slope   = 0.1;
  PetscCall(PetscStrncpy(s->indenter.dataset, "h", sizeof(s->indenter.dataset)));
  PetscCall(PetscStrncpy(s->gamma_dataset, "gamma", sizeof(s->gamma_dataset)));
  s->start     = ADH_START_HERTZ;
  s->steps     = 10;
  s->stop_at_pulloff = PETSC_TRUE;
  s->path_stopped    = -1;
  s->max_outer = 100000;
  s->minimize_rtol   = 1e-8;
  s->minimize_trust  = 2.0;
  s->minimize_max_it = 100000;
  s->minimize_pc     = PETSC_TRUE;
  s->minimize_newton = PETSC_TRUE;
  s->adhesive  = PETSC_TRUE;
  s->certify   = PETSC_TRUE;
  s->use_box   = PETSC_TRUE;
  s->cascade_local_rtol = 1e-3;
  s->fields_stride    = 1;
  s->memory_check     = PETSC_TRUE;
  s->checkpoint_every = 1;
  s->monitor_interval = 5.0;
  s->progress         = 5.0;
  PetscCall(PetscMalloc1(2, &s->path));
  s->npath   = 2;
  s->path[0] = 0.01;
  s->path[1] = 0.0;
  PetscCall(AdhGridCreate(comm, &s->grid));
  s->grid->fftw_timelimit = 0.01; /* free boundary: many windows to plan, few whole-grid multiplies */
  PetscCall(AdhSolverSetElasticType(s, ADHELASTICHALFSPACE));
  PetscCall(AdhSolverSetControlType(s, ADHCONTROLDISPLACEMENT));
  PetscCall(AdhSolverSetCriterionType(s, ADHCRITERIONCRACKCLOSURE)); /* within 2% in every edge direction; the paper's rule is one option away */
  s->attach = ADH_ATTACH_GRIFFITH; /* crack-closure's mirror: JKR's and Johnson's loading branches (reach with pohrt-popov, at set-up; penetration stays Hertz-like) */
  PetscCall(AdhSolverSetPredictorType(s, ADHPREDICTORPOLONSKYKEER));
  s->predictor_chosen = PETSC_FALSE; /* the default: polonsky-keer on a periodic cell, none on a free boundary */
  *solver = s;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverSetOptionsPrefix - Sets the prefix of every option the solver reads, its grid's and its KSP's included

  Logically Collective

  Input Parameters:
+ s      - the solver
- prefix - the prefix, without a leading hyphen, or `NULL` for none

  Level: intermediate

  Notes:
  With the prefix "a_" the solver reads -a_adh_gamma, -a_adh_n, and so on, and the KSP of its contact-set solves reads
  -a_adh_ksp_rtol. The string is copied.

  Call it before `AdhSolverSetFromOptions()`, and before `AdhSolverSetUp()`, which gives the KSP its prefix.

.seealso: `AdhSolverSetFromOptions()`, `AdhSolverCreate()`, `AdhSolverSetUp()`
@*/
PetscErrorCode AdhSolverSetOptionsPrefix(AdhSolver s, const char prefix[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscCall(PetscFree(s->prefix));
  PetscCall(PetscStrallocpy(prefix, &s->prefix));
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)s, prefix)); /* -adh_view through PetscObjectViewFromOptions */
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)s->grid, prefix)); /* the grid's own copy: it may outlive the solver */
  s->grid->prefix = ((PetscObject)s->grid)->prefix;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetGrid - Gets the element grid of the solver

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. grid - the grid: its sizes, its element sizes, and the rows of each rank

  Level: intermediate

  Note:
  The grid belongs to the solver: do not destroy it. It exists from `AdhSolverCreate()` on; its element sizes and
  the rows of each rank are set by `AdhSolverSetUp()`.

.seealso: `AdhSolverGetCompliance()`, `AdhSolverGetFields()`, `AdhGridGetOwnership()`, `AdhGridCreateVector()`
@*/
PetscErrorCode AdhSolverGetGrid(AdhSolver s, AdhGrid *grid)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(grid, 2);
  *grid = s->grid;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetCompliance - Gets the half-space compliance K of the solver, u = K p on the whole grid

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. K - the compliance, a shell matrix applied with FFTW (`NULL` before `AdhSolverSetUp()`)

  Level: advanced

  Note:
  The matrix belongs to the solver: do not destroy it. `AdhSolverSetUp()` makes it with `MatCreateAdhCompliance()` for
  the solver's boundary. The contact-set solves may apply other operators (the compliance on the set's bounding box on
  a free boundary, K + c0 (1 1^T)/N under force control on a periodic cell); this is always the whole grid's K.

.seealso: `MatCreateAdhCompliance()`, `AdhSolverGetGrid()`, `AdhSolverGetFields()`
@*/
PetscErrorCode AdhSolverGetCompliance(AdhSolver s, Mat *K)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(K, 2);
  *K = s->K;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetContactSet - Gets the current contact set, the grid points in contact

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. is - the set: on each rank the global indices (j Nx + i) of its own points in contact (`NULL` before `AdhSolverSetUp()`)

  Level: intermediate

  Note:
  The `IS` belongs to the solver: do not destroy it. The solver destroys it and makes a new one whenever the set
  changes, so get it again after each `AdhSolverStart()` or `AdhSolverStep()` (or keep one with
  `PetscObjectReference()`). Its global size is the number of points in contact.

.seealso: `AdhSolverGetFields()`, `AdhSolverGetState()`, `AdhSolverGetGrid()`
@*/
PetscErrorCode AdhSolverGetContactSet(AdhSolver s, IS *is)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(is, 2);
  *is = s->contact;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetFields - Gets the fields of the current state: pressure, displacement, gap, profile, critical stress

  Collective if `u` or `Sigma` is requested, otherwise Not Collective

  Input Parameter:
. s - the solver

  Output Parameters:
+ p     - the pressure p (or `NULL`)
. u     - the displacement u = K p (or `NULL`)
. g     - the gap g = h - d + u (or `NULL`)
. h     - the indenter profile h (or `NULL`)
- Sigma - the critical stress Sigma (or `NULL`)

  Level: intermediate

  Notes:
  Borrowed references: the vectors belong to the solver, do not destroy them. They are grid vectors
  (`AdhGridCreateVector()`), made by `AdhSolverSetUp()`.

  The solver keeps no u, nor a Sigma vector for a uniform dgamma: asking for them (non-`NULL`) makes them, current for
  this state. A u made so is kept and brought up to date by every later `AdhSolverStep()`; it is computed as
  g - h + d. A uniform Sigma vector is kept and set again whenever Sigma is computed (every `AdhSolverSetUp()`); it is
  destroyed when a dgamma field is set after set-up (`AdhSolverSetWorkOfAdhesionField()`): get it again then. With a
  dgamma field Sigma is the field's critical stress.

.seealso: `AdhSolverGetState()`, `AdhSolverGetContactSet()`, `AdhSolverGetCriticalStress()`, `AdhSolverGetCompliance()`
@*/
PetscErrorCode AdhSolverGetFields(AdhSolver s, Vec *p, Vec *u, Vec *g, Vec *h, Vec *Sigma)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  if (p) *p = s->p;
  if (u) PetscCall(AdhSolverGetDisplacement_Private(s, u));
  if (g) *g = s->g;
  if (h) *h = s->h;
  if (Sigma) PetscCall(AdhSolverGetCriticalStressVec_Private(s, Sigma));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetCriticalStress - Gets the critical tensile stress Sigma of the scalar work of adhesion

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. Sigma - the mesh-dependent Sigma = sqrt(hx hy E* dgamma / chi) (Pohrt & Popov eq. 13; the elastic body's element self-energy chi), or the stress fixed by
          -adh_critical_stress

  Level: intermediate

  Notes:
  Computed by `AdhSolverSetUp()`, at every call: 0 before set-up and without adhesion.

  With a dgamma field (`AdhSolverSetWorkOfAdhesionField()`, -adh_gamma_field) this is still the Sigma of the scalar
  dgamma (-adh_gamma), for reports; the field's critical stress is the `Sigma` vector of `AdhSolverGetFields()`. A
  stress fixed by -adh_critical_stress replaces the field's too.

.seealso: `AdhSolverGetFields()`, `AdhCriticalStress()`, `AdhSolverSetWorkOfAdhesionField()`
@*/
PetscErrorCode AdhSolverGetCriticalStress(AdhSolver s, PetscReal *Sigma)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidRealPointer(Sigma, 2);
  *Sigma = s->Sigma;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverSetProgress - Sets when `AdhSolverSolvePath()` prints progress lines

  Logically Collective

  Input Parameters:
+ s       - the solver
- seconds - the seconds of a path before its first progress line, >= 0; 0 for none

  Options Database Key:
. -adh_progress <5> - the same, read by `AdhSolverSetFromOptions()`

  Level: intermediate

  Notes:
  A progress line gives the state, the time so far and an estimate of the time left. After the first, one comes every
  tenth of the time so far or every `seconds`, whichever is longer. Lines are printed only inside
  `AdhSolverSolvePath()`, and not with -adh_monitor, which prints a line per state instead.

  A negative or NaN value is an error.

.seealso: `AdhSolverGetProgress()`, `AdhSolverSolvePath()`, `AdhSolverMonitorSet()`, `AdhSolverMonitorDefault()`
@*/
PetscErrorCode AdhSolverSetProgress(AdhSolver s, PetscReal seconds)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidLogicalCollectiveReal(s, seconds, 2);
  PetscCheck(seconds >= 0 && !PetscIsNanReal(seconds), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_progress must be >= 0 seconds, got %g", (double)seconds);
  s->progress = seconds;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetProgress - Gets the seconds of a path before its first progress line

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. seconds - the seconds before the first progress line of `AdhSolverSolvePath()` (0: none; 5 by default)

  Level: intermediate

.seealso: `AdhSolverSetProgress()`, `AdhSolverSolvePath()`
@*/
PetscErrorCode AdhSolverGetProgress(AdhSolver s, PetscReal *seconds)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidRealPointer(seconds, 2);
  *seconds = s->progress;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetBoundary - Gets the boundary mode: free (an isolated contact) or periodic (a periodic cell)

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. boundary - `ADH_BOUNDARY_FREE` (the default) or `ADH_BOUNDARY_PERIODIC`

  Options Database Key:
. -adh_boundary <free,periodic> - the boundary, read by `AdhSolverSetFromOptions()`

  Level: intermediate

.seealso: `AdhSolverSetFromOptions()`, `AdhSolverGetCompliance()`
@*/
PetscErrorCode AdhSolverGetBoundary(AdhSolver s, AdhBoundary *boundary)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(boundary, 2);
  *boundary = s->boundary;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetCurve - Gets the curve: the states recorded so far

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. curve - the curve: curve->n states, curve->state[k] the k-th, an `AdhState`

  Level: beginner

  Notes:
  The curve belongs to the solver: do not free it. `AdhSolverSolvePath()` and `AdhSolverRecordState()` append states to
  it, and `AdhSolverStart()` and `AdhSolverSolvePath()` begin it anew. The array curve->state may move when a state is
  appended: read it through the curve each time. Each rank holds its copy.

  The columns of a state, in the order of the CSV file, are `AdhCurveColumns`; `AdhStateValue()` gives one of them.

.seealso: `AdhSolverSolvePath()`, `AdhSolverRecordState()`, `AdhStateValue()`, `AdhCurveGetPullOffState()`,
          `AdhSolverWriteOutput()`
@*/
PetscErrorCode AdhSolverGetCurve(AdhSolver s, const AdhCurve **curve)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(curve, 2);
  *curve = &s->curve;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetIterationNames - Gets what a state's two iteration counts count: the curve's outer_iterations and
  ksp_iterations

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameters:
+ outer - "set updates" (a criterion's set-update loop), "Newton steps" (a cohesive law minimised with
          `-adh_minimize_direction newton`) or "minimisations" (one a state, `polak-ribiere`)
- inner - "KSP iterations", "conjugate gradient iterations" (Newton's inner ones) or "Polak-Ribiere iterations"

  Level: intermediate

  Note:
  The strings belong to the library; either pointer may be `NULL`. The answer depends on the criterion and its route,
  so ask after `AdhSolverSetFromOptions()` or `AdhSolverSetUp()`.

.seealso: `AdhSolverGetCurve()`, `AdhState`, `ADHCRITERIONEXPONENTIAL`, `ADHCRITERIONDUGDALE`
@*/
PetscErrorCode AdhSolverGetIterationNames(AdhSolver s, const char *outer[], const char *inner[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  if (outer) *outer = !s->crops.law ? "set updates" : s->minimize_newton ? "Newton steps" : "minimisations";
  if (inner) *inner = !s->crops.law ? "KSP iterations" : s->minimize_newton ? "conjugate gradient iterations" : "Polak-Ribiere iterations";
  PetscFunctionReturn(0);
}

/*@
  AdhSolverDestroy - Destroys the solver and everything it holds

  Collective

  Input Parameter:
. solver - the solver; `*solver` may be `NULL`

  Level: beginner

  Note:
  The monitors' contexts are destroyed with their destroy functions (`AdhSolverMonitorCancel()`), and the solver
  drops its references to the vectors it was given (`AdhSolverSetTopography()`, `AdhSolverSetWorkOfAdhesionField()`).
  Sets `*solver` to `NULL`.

.seealso: `AdhSolverCreate()`, `AdhSolverMonitorCancel()`
@*/
PetscErrorCode AdhSolverDestroy(AdhSolver *solver)
{
  AdhSolver s = *solver;

  PetscFunctionBegin;
  if (!s) PetscFunctionReturn(0);
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  if (--((PetscObject)s)->refct > 0) { /* others hold it still */
    *solver = NULL;
    PetscFunctionReturn(0);
  }
  /* first, while the solver is whole: a file of AdhSolverOutputBegin() left open ends incomplete */
  PetscCall(AdhSolverOutputEnd(s, PETSC_FALSE));
  if (s->eops.base.destroy) PetscCall(s->eops.base.destroy(s));
  if (s->cops.base.destroy) PetscCall(s->cops.base.destroy(s));
  if (s->crops.base.destroy) PetscCall(s->crops.base.destroy(s));
  if (s->pops.base.destroy) PetscCall(s->pops.base.destroy(s));
  PetscCall(PetscFree(s->field_states));
  if (s->journal) fclose(s->journal);
  PetscCall(VecDestroy(&s->attach_limit));
  PetscCall(AdhSolverMonitorCancel(s));
  PetscCall(KSPDestroy(&s->ksp));
  PetscCall(MatDestroy(&s->Kcc));
  PetscCall(ISDestroy(&s->contact_op));
  PetscCall(VecScatterDestroy(&s->set_scatter));
  PetscCall(VecDestroy(&s->pC));
  PetscCall(VecDestroy(&s->bC));
  PetscCall(PetscFree(s->set_local));
  PetscCall(PetscFree(s->thrC));
  PetscCall(VecDestroy(&s->op_in));
  PetscCall(VecDestroy(&s->op_out));
  PetscCall(AdhSolverDestroyBoxes_Private(s));
  PetscCall(MatDestroy(&s->K));
  PetscCall(MatDestroy(&s->S));
  PetscCall(ISDestroy(&s->contact));
  PetscCall(VecDestroy(&s->h));
  PetscCall(VecDestroy(&s->Sigma_field));
  PetscCall(VecDestroy(&s->Sigma_view));
  PetscCall(VecDestroy(&s->p));
  PetscCall(VecDestroy(&s->u));
  PetscCall(VecDestroy(&s->off_load));
  PetscCall(VecDestroy(&s->off_work));
  PetscCall(VecDestroy(&s->g));
  PetscCall(VecDestroy(&s->gamma_field));
  PetscCall(VecDestroy(&s->indenter.z));
  PetscCall(PetscFree(s->in_set));
  PetscCall(PetscFree(s->left));
  PetscCall(AdhSolverDestroyCascadeApart_Private(s));
  PetscCall(AdhSolverDestroyCascadeLocal_Private(s));
  PetscCall(PetscFree(s->path));
  PetscCall(AdhCurveDestroy_Private(&s->curve));
  PetscCall(AdhGridDestroy(&s->grid));
  PetscCall(PetscFree(s->prefix));
  PetscCall(PetscHeaderDestroy(solver));
  PetscFunctionReturn(0);
}
