/* AdhSolverSetUp: what the problem is made of on the grid (the profile, the critical stress,
   the compliance and its preconditioner, the KSP), and the setters that change it afterwards. It
   only creates: the contact set belongs to the step. */
#include "solver/solverimpl.h"

/*@
  AdhSolverSetWorkOfAdhesionField - Replaces the scalar work of adhesion by a field dgamma(x,y)

  Collective

  Input Parameters:
+ s     - the solver
- gamma - the work of adhesion at each grid point, a `Vec` on the grid (`AdhGridCreateVector()`), >= 0 everywhere

  Options Database Keys:
+ -adh_gamma_field <FILE>          - a field read at set-up from a file instead: .npy (Ny, Nx), or HDF5
- -adh_gamma_field_dataset <gamma> - the dataset's name inside an HDF5 file

  Level: intermediate

  Notes:
  The critical stress becomes the field Sigma(x,y) = sqrt(hx hy E* dgamma(x,y) / chi) (on a half-space; the body's chi otherwise), unless -adh_critical_stress
  fixes it. The scalar -adh_gamma still gives the Sigma of `AdhSolverGetCriticalStress()`, for reports. The field
  replaces one read from -adh_gamma_field.

  After set-up the field is checked against the grid's layout and for finite values, and Sigma is computed again, as
  are the estimate of `AdhSolverGetResolution()` (from the weakest adhesion present) and the window of
  -adh_cascade_local; the contact state stays. Before set-up only its sign is checked here.

  The solver keeps a reference to gamma, not a copy: the caller may destroy its own reference, and values it changes
  later enter the critical stress at the next `AdhSolverSetUp()`, which every `AdhSolverStep()` calls.

.seealso: `AdhSolverGetCriticalStress()`, `AdhSolverGetFields()`, `AdhSolverSetTopography()`, `AdhSolverSetUp()`
@*/
PetscErrorCode AdhSolverSetWorkOfAdhesionField(AdhSolver s, Vec gamma)
{
  PetscReal min;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidHeaderSpecific(gamma, VEC_CLASSID, 2);
  if (s->setup) PetscCall(AdhFieldCheck(s->grid, "work of adhesion field", gamma));
  PetscCall(VecMin(gamma, NULL, &min));
  PetscCheck(min >= 0, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "The work of adhesion field must be >= 0 everywhere, its minimum is %g", (double)min);
  PetscCall(PetscObjectReference((PetscObject)gamma));
  PetscCall(VecDestroy(&s->gamma_field));
  s->gamma_field = gamma;
  s->gamma_file[0] = 0; /* this field replaces one read from -adh_gamma_field */
  if (s->setup) {
    PetscCall(AdhSolverSetUp(s)); /* refreshes Sigma */
    PetscCall(AdhSolverEstimateResolution_Private(s));
    PetscCall(AdhSolverEstimateStickiness_Private(s));
    PetscCall(AdhSolverSetLocalWidth_Private(s)); /* -adh_cascade_local's window, from that estimate */
  }
  PetscFunctionReturn(0);
}

/* -adh_gamma_field: dgamma(x,y) from a file, checked like a topography and for dgamma >= 0. */
static PetscErrorCode LoadWorkOfAdhesionField(AdhSolver s)
{
  Vec            v;
  PetscReal      min;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(VecDuplicate(s->h, &v));
  PetscCall(PetscObjectSetName((PetscObject)v, "gamma_field"));
  ierr = AdhFieldLoad(s->grid, "-adh_gamma_field", s->gamma_file, s->gamma_dataset, v);
  if (ierr) PetscCall(VecDestroy(&v));
  PetscCall(ierr);
  PetscCall(VecMin(v, NULL, &min));
  if (min < 0) PetscCall(VecDestroy(&v));
  PetscCheck(min >= 0, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_gamma_field: %s holds negative values (minimum %g); the work of adhesion must be >= 0", s->gamma_file, (double)min);
  s->gamma_field = v;
  PetscFunctionReturn(0);
}

/* Sigma(x,y) = sqrt(hx hy E* dgamma(x,y) / chi) (the body's), or the fixed stress of -adh_critical_stress. */
static PetscErrorCode ComputeCriticalStress(AdhSolver s)
{
  PetscFunctionBegin;
  s->Sigma = s->sigma_fixed > 0 ? s->sigma_fixed : s->eops.critical_stress(s, s->gamma);
  if (s->gamma_field && !(s->sigma_fixed > 0)) {
    PetscCall(VecDestroy(&s->Sigma_view));
    if (!s->Sigma_field) {
      PetscCall(VecDuplicate(s->h, &s->Sigma_field));
      PetscCall(PetscObjectSetName((PetscObject)s->Sigma_field, "critical_stress"));
    }
    PetscCall(VecCopy(s->gamma_field, s->Sigma_field));
    PetscCall(VecScale(s->Sigma_field, s->eops.stress_per_work));
    PetscCall(VecSqrtAbs(s->Sigma_field));
  } else {
    PetscCall(VecDestroy(&s->Sigma_field));
    if (s->Sigma_view) PetscCall(VecSet(s->Sigma_view, s->Sigma)); /* one handed out follows Sigma */
  }
  PetscFunctionReturn(0);
}

/* The critical stress as a grid vector: the field, or a uniform Sigma made into one on request
   (then kept, and set again whenever Sigma is computed). */
PetscErrorCode AdhSolverGetCriticalStressVec_Private(AdhSolver s, Vec *Sigma)
{
  PetscFunctionBegin;
  if (s->Sigma_field) *Sigma = s->Sigma_field;
  else {
    if (!s->Sigma_view) {
      PetscCall(VecDuplicate(s->h, &s->Sigma_view));
      PetscCall(PetscObjectSetName((PetscObject)s->Sigma_view, "critical_stress"));
      PetscCall(VecSet(s->Sigma_view, s->Sigma));
    }
    *Sigma = s->Sigma_view;
  }
  PetscFunctionReturn(0);
}

/* The Fourier preconditioner: z = R S R^T r, with S the body's periodic stiffness (E*|q|/2 on a half-space) on the grid
   (or on the bounding-box window) and R the restriction to the contact set. */
static PetscErrorCode PCApply_Fourier(PC pc, Vec r, Vec z)
{
  AdhSolver s;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &s));
  PetscCall(AdhSolverApplyOnSet_Private(s, s->Sop, r, z));
  PetscFunctionReturn(0);
}


/* After the profile h is set or replaced: its mean (a periodic cell is in full contact at
   d = mean(h)), and a contact state of nothing in contact. */
PetscErrorCode AdhSolverProfileChanged_Private(AdhSolver s)
{
  PetscScalar sum;

  PetscFunctionBegin;
  PetscCall(VecSum(s->h, &sum));
  s->mean_h = PetscRealPart(sum) / ((PetscReal)s->grid->Nx * (PetscReal)s->grid->Ny);
  s->profile_version++;
  PetscCall(AdhSolverEstimateRoughness_Private(s)); /* once a profile: the two estimates read it */
  PetscCall(AdhSolverEstimateResolution_Private(s));
  PetscCall(AdhSolverEstimateStickiness_Private(s));
  PetscCall(AdhSolverSetLocalWidth_Private(s)); /* -adh_cascade_local's window, from that estimate */
  PetscCall(AdhSolverClearContact_Private(s));
  PetscCall(VecCopy(s->h, s->g)); /* the undeformed gap, g = h - d */
  PetscCall(VecShift(s->g, -s->d));
  PetscFunctionReturn(0);
}

/* A topography (a rough surface, a file) on the free boundary by default: legal (an isolated body
   of the grid's size), but usually meant as a periodic cell. */
static PetscErrorCode WarnFreeTopography(AdhSolver s)
{
  PetscFunctionBegin;
  if (s->boundary != ADH_BOUNDARY_FREE || s->boundary_set) PetscFunctionReturn(0);
  if (s->indenter.type == ADH_INDENTER_ROUGH)
    PetscCall(PetscPrintf(s->comm, "adhbem: warning: -adh_indenter rough on the default free boundary: the periodic surface is cut to an isolated body of the grid's size, and its edges touch first; a rough surface is usually a periodic cell: add -adh_boundary periodic (-adh_boundary free keeps this and silences the warning)\n"));
  else if (s->indenter.type == ADH_INDENTER_ARRAY)
    PetscCall(PetscPrintf(s->comm, "adhbem: warning: a topography array on the default free boundary: it is taken as an isolated body of the grid's size; a measured or generated surface is usually a periodic cell: give boundary=\"periodic\" (-adh_boundary periodic; boundary=\"free\" keeps this and silences the warning)\n"));
  else if (s->indenter.type == ADH_INDENTER_FILE)
    PetscCall(PetscPrintf(s->comm, "adhbem: warning: -adh_topography %s on the default free boundary: it is taken as an isolated body of the grid's size; a measured or generated surface is usually a periodic cell: add -adh_boundary periodic (-adh_boundary free keeps this and silences the warning)\n", s->indenter.topography));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverSetUp - Builds the problem on the grid: the profile, critical stress, compliance, preconditioner and KSP

  Collective

  Input Parameter:
. s - the solver

  Options Database Keys:
+ -adh_ksp_rtol <1e-10>    - the relative tolerance of the CG solves on the contact set
- -adh_ksp_max_it <100000> - their largest number of iterations

  Level: beginner

  Notes:
  Set-up only creates: the contact set belongs to the step, and is empty after set-up. `AdhSolverStart()`,
  `AdhSolverStep()` and `AdhSolverSolvePath()` call it, so calling it is optional. The first call does the work; every
  call, the first included, computes the critical stress Sigma from dgamma and the elastic body's element (E* and the
  grid on a half-space), or takes the stress of -adh_critical_stress. The FFTW options (-adh_fftw_planner and the others)
  are the grid's, read by `AdhSolverSetFromOptions()` through `AdhGridSetFromOptions()`; the first call plans the
  transforms with them.

  The first call also refuses misspelled -adh_ options; chooses the defaults that depend on other settings (the
  attach rule the criterion pairs with, unless one was chosen: griffith with crack-closure, reach with pohrt-popov,
  penetration with dugdale; a criterion other than crack-closure refuses griffith; the predictor none on a free boundary unless one was chosen; FFTW plans without a time limit on a periodic cell);
  refuses a grid that the build's PetscInt cannot index, or whose memory estimate exceeds the node's
  (`AdhSolverEstimateMemory()`, -adh_memory_check); fills the profile h from the indenter and reads -adh_gamma_field;
  warns when a rough surface or a topography lies on the default free boundary; and sets up the load control and the
  criterion.

  The KSP is CG with a nonzero initial guess, the unpreconditioned residual norm, an absolute tolerance of 0 and a
  shell preconditioner, the body's periodic stiffness (E*|q|/2 on a half-space) restricted to the contact set. Its options prefix is the
  solver's followed by adh_, and its options are read here (-adh_ksp_ and -adh_pc_ options it does not read are
  refused).

.seealso: `AdhSolverCreate()`, `AdhSolverSetFromOptions()`, `AdhSolverStart()`, `AdhSolverSolvePath()`,
          `AdhSolverEstimateMemory()`, `AdhSolverView()`
@*/
PetscErrorCode AdhSolverSetUp(AdhSolver s)
{
  PC       pc;
  PetscInt nlocal;
  char     kspprefix[256];

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  if (!s->setup) {
    PetscCall(AdhSolverReadTypesOptions_Private(s)); /* the types' options are not misspellings */
    PetscCall(AdhCheckOptions_Private(s->comm, s->prefix));
    /* A periodic cell does every multiply on the whole grid: plan it without a time limit (a
       limited plan transforms 2x slower at 512^2). */
    if (s->boundary == ADH_BOUNDARY_PERIODIC) s->grid->fftw_timelimit = -1.0;
    /* The predictor transforms the whole grid; on a free boundary the loop's bounding-box
       windows cost less (Hertz 256^2: 0.5 s against 3.1 s), so it is used there only if asked. */
    if (!s->attach_chosen) s->attach = s->crops.attach; /* the criterion's own: griffith with crack-closure, reach with pohrt-popov */
    PetscCheck(s->crops.griffith || s->attach != ADH_ATTACH_GRIFFITH, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_attach griffith is the mirror of -adh_criterion crack-closure's detachment test; with -adh_criterion %s use -adh_attach reach or penetration", s->criterion_type);
    if (!s->predictor_chosen && s->boundary == ADH_BOUNDARY_FREE) {
      PetscCall(AdhSolverSetPredictorType(s, ADHPREDICTORNONE));
      s->predictor_chosen = PETSC_FALSE;
    }
    PetscCall(AdhSolverCheckResources_Private(s));
    PetscCall(AdhGridSetUp(s->grid));
    /* the body first: its constants and its operators */
    PetscCheck(!(s->eops.periodic_only && s->boundary == ADH_BOUNDARY_FREE), s->comm, PETSC_ERR_ARG_INCOMP, "-adh_elastic %s is a periodic cell only; give -adh_boundary periodic (the free boundary is a half-space's)", s->elastic_type);
    PetscCheck(s->eops.create_operators && s->eops.modulus && s->eops.critical_stress, s->comm, PETSC_ERR_PLIB, "-adh_elastic %s: the body's create function must set create_operators, modulus and critical_stress", s->elastic_type);
    if (s->eops.base.setup) PetscCall(s->eops.base.setup(s));
    {
      const PetscReal c[4] = {s->eops.self_compliance, s->eops.chi_per_area, s->eops.stress_per_work, s->eops.mean_compliance};
      for (PetscInt k = 0; k < 4; k++) PetscCheck(!PetscIsInfOrNanReal(c[k]), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_size %g x %g: the elastic body's element constants are not finite for elements of %g x %g (self-compliance %g, chi per area %g): the element is beyond what double precision holds", (double)s->grid->Lx, (double)s->grid->Ly, (double)s->grid->hx, (double)s->grid->hy, (double)c[0], (double)c[1]);
      for (PetscInt k = 0; k < 4; k++) PetscCheck(c[k] > 0, s->comm, PETSC_ERR_PLIB, "-adh_elastic %s: the body's set-up left its element's constants unset or not positive (self-compliance %g, chi per area %g, stress per work %g, mean compliance %g)", s->elastic_type, (double)c[0], (double)c[1], (double)c[2], (double)c[3]);
    }
    PetscCall(s->eops.create_operators(s, s->grid, s->boundary, &s->K, &s->S));
    PetscCall(AdhGridCreateVector(s->grid, &s->h));
    PetscCall(VecDuplicate(s->h, &s->p));
    PetscCall(VecDuplicate(s->h, &s->g));
    PetscCall(PetscObjectSetName((PetscObject)s->h, "profile"));
    PetscCall(PetscObjectSetName((PetscObject)s->p, "pressure"));
    PetscCall(PetscObjectSetName((PetscObject)s->g, "gap"));
    PetscCall(VecSet(s->p, 0.0));
    PetscCall(AdhIndenterFill_Private(s->grid, &s->indenter, s->h));
    if (s->gamma_file[0] && !s->gamma_field) PetscCall(LoadWorkOfAdhesionField(s));
    PetscCall(VecGetLocalSize(s->h, &nlocal));
    PetscCall(PetscCalloc1(nlocal + 1, &s->in_set));
    PetscCall(PetscCalloc1(nlocal + 1, &s->left));
    s->nlocal = nlocal;
    if (s->cascade_apart > 0) PetscCall(AdhSolverSetUpCascadeApart_Private(s));
    PetscCall(AdhSolverDefaultCascadeLocal_Private(s)); /* the criterion or the control may have changed since the options were read */
    PetscCheck(!(s->cascade_local > 0 && !s->cops.cascades), s->comm, PETSC_ERR_ARG_INCOMP, "-adh_cascade_local: displacement control only (-adh_control displacement)");
    if (s->cascade_local > 0) PetscCall(AdhSolverSetUpCascadeLocal_Private(s));
    PetscCall(AdhSolverProfileChanged_Private(s));

    PetscCall(KSPCreate(s->comm, &s->ksp));
    PetscCall(PetscSNPrintf(kspprefix, sizeof(kspprefix), "%sadh_", s->prefix ? s->prefix : ""));
    PetscCall(KSPSetOptionsPrefix(s->ksp, kspprefix));
    PetscCall(KSPSetType(s->ksp, KSPCG));
    PetscCall(KSPSetNormType(s->ksp, KSP_NORM_UNPRECONDITIONED));
    PetscCall(KSPSetTolerances(s->ksp, 1e-10, 0.0, PETSC_DEFAULT, 100000));
    PetscCall(KSPSetInitialGuessNonzero(s->ksp, PETSC_TRUE));
    PetscCall(KSPGetPC(s->ksp, &pc));
    PetscCall(PCSetType(pc, PCSHELL));
    PetscCall(PCShellSetContext(pc, s));
    PetscCall(PCShellSetApply(pc, PCApply_Fourier));
    PetscCall(PCShellSetName(pc, "adhbem Fourier preconditioner: the body's periodic stiffness (E*|q|/2 on a half-space) restricted to the contact set"));
    PetscCall(KSPSetConvergenceTest(s->ksp, AdhConvergedCertified_Private, s, NULL));
    PetscCall(KSPSetFromOptions(s->ksp));
    PetscCall(AdhCheckKSPOptions_Private(s->ksp, s->prefix, "adh_"));
    PetscCall(WarnFreeTopography(s));
    if (s->cops.base.setup) PetscCall(s->cops.base.setup(s));
    if (s->crops.base.setup) PetscCall(s->crops.base.setup(s));
    if (s->pops.base.setup) PetscCall(s->pops.base.setup(s));
    s->setup = PETSC_TRUE;
    PetscCall(PetscInfo(s, "set up: %" PetscInt_FMT " x %" PetscInt_FMT " grid, %s boundary, criterion %s, control %s, predictor %s, Sigma %g\n", s->grid->Nx, s->grid->Ny, AdhBoundaries[s->boundary], s->criterion_type, s->control_type, s->predictor_type, (double)s->Sigma));
  }
  PetscCall(ComputeCriticalStress(s));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverSetTopography - Makes the indenter a profile given by the user, a topography on the grid

  Collective

  Input Parameters:
+ s    - the solver
. z    - the topography, a `Vec` on the grid (`AdhGridCreateVector()`), in the grid's order j Nx + i
- kind - what z holds: `ADH_TOPOGRAPHY_HEIGHT`, the height of the surface, as instruments, SurfaceTopography and
         Tamaas give it (the profile is h = max(z) - z: the highest peak touches at d = 0), or `ADH_TOPOGRAPHY_GAP`,
         the gap h itself

  Level: intermediate

  Notes:
  The indenter becomes of type array, replacing a -adh_topography file. Before set-up the topography is kept for
  set-up, which checks it and makes the profile; after set-up the profile is replaced at once and the contact state
  is cleared: start again with `AdhSolverStart()` or `AdhSolverSolvePath()`. The new profile is built aside, so a
  topography refused (another layout than the grid's, values that are not finite) leaves the solver as it was.
  After set-up the mean of h, the estimate of `AdhSolverGetResolution()` and the window of -adh_cascade_local follow
  the new profile.

  The solver keeps a reference to z: the caller may destroy its own. On the default free boundary a warning says that
  the topography is taken as an isolated body of the grid's size (-adh_boundary periodic makes it a periodic cell;
  -adh_boundary free keeps this and silences the warning).

.seealso: `AdhSolverSetWorkOfAdhesionField()`, `AdhSolverGetFields()`, `AdhSolverSetUp()`, `AdhSolverStart()`
@*/
PetscErrorCode AdhSolverSetTopography(AdhSolver s, Vec z, AdhTopographyKind kind)
{
  AdhIndenter ind;
  Vec         h;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscCheck(z, s->comm, PETSC_ERR_ARG_NULL, "AdhSolverSetTopography: no topography Vec given");
  PetscValidHeaderSpecific(z, VEC_CLASSID, 2);
  ind = s->indenter;
  PetscCheck(kind == ADH_TOPOGRAPHY_HEIGHT || kind == ADH_TOPOGRAPHY_GAP, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "topography kind: height or gap, got %d", (int)kind);
  ind.type = ADH_INDENTER_ARRAY;
  ind.kind = kind;
  ind.z    = z;
  if (s->setup) {
    /* Build the new profile aside: a bad topography leaves the solver as it was. */
    PetscCall(VecDuplicate(s->h, &h));
    {
      PetscErrorCode ierr = AdhIndenterFill_Private(s->grid, &ind, h);
      if (ierr) PetscCall(VecDestroy(&h));
      PetscCall(ierr);
    }
    PetscCall(VecCopy(h, s->h));
    PetscCall(VecDestroy(&h));
  }
  PetscCall(PetscObjectReference((PetscObject)z));
  PetscCall(VecDestroy(&s->indenter.z));
  s->indenter               = ind;
  s->indenter.topography[0] = 0;
  /* after the indenter is this topography: the resolution estimate reads its type */
  if (s->setup) {
    PetscCall(AdhSolverProfileChanged_Private(s));
    PetscCall(WarnFreeTopography(s));
  }
  PetscFunctionReturn(0);
}
