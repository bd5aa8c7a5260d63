/* AdhSolver: lifecycle, options and set-up of the adhesive contact solver. The step algorithm
   is in contact.c, paths in path.c, output in output.c. */
#include "solver/solverimpl.h"

const char *const AdhStarts[]   = {"hertz", "adhesive", "AdhStart", "ADH_START_", NULL};
const char *const AdhAttaches[] = {"penetration", "reach", "griffith", "AdhAttach", "ADH_ATTACH_", NULL};

PetscErrorCode AdhSolverCreate(MPI_Comm comm, AdhSolver *solver)
{
  AdhSolver s;

  PetscFunctionBegin;
  PetscCall(AdhInitializePackage());
  PetscCall(PetscNew(&s));
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
  s->max_outer = 100000;
  s->adhesive  = PETSC_TRUE;
  s->certify   = PETSC_TRUE;
  s->use_box   = PETSC_TRUE;
  s->pulloff_rtol     = 1e-3;
  s->criterion_radius = 16.0;
  s->fields_stride    = 1;
  s->memory_check     = PETSC_TRUE;
  s->checkpoint_every = 1;
  s->monitor_interval = 5.0;
  PetscCall(PetscMalloc1(2, &s->path));
  s->npath   = 2;
  s->path[0] = 0.01;
  s->path[1] = 0.0;
  PetscCall(AdhGridCreate(comm, &s->grid));
  s->grid->fftw_timelimit = 0.01; /* free boundary: many windows to plan, few whole-grid multiplies */
  PetscCall(AdhSolverSetControlType(s, ADHCONTROLDISPLACEMENT));
  PetscCall(AdhSolverSetCriterionType(s, ADHCRITERIONCRACKCLOSURE)); /* within 2% in every edge direction; the paper's rule is one option away */
  s->attach = ADH_ATTACH_REACH; /* the JKR jump-in and loading branch (penetration stays Hertz-like) */
  s->predictor_rtol   = 1e-8;
  s->predictor_max_it = 10000;
  s->predictor_fourier = PETSC_TRUE;
  PetscCall(AdhSolverSetPredictorType(s, ADHPREDICTORPOLONSKYKEER));
  s->predictor_chosen = PETSC_FALSE; /* the default: polonsky-keer on a periodic cell, none on a free boundary */
  *solver = s;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverSetOptionsPrefix(AdhSolver s, const char prefix[])
{
  PetscFunctionBegin;
  PetscCall(PetscFree(s->prefix));
  PetscCall(PetscStrallocpy(prefix, &s->prefix));
  s->grid->prefix = s->prefix;
  PetscFunctionReturn(0);
}

/* -adh_fields [LIST]: the fields to write, a comma-separated list of pressure, displacement, gap,
   contact; given alone (or all, 1, true) all four, none (or 0, false) no fields. Inside
   PetscOptionsBegin/End, so that -help shows it. */
static PetscErrorCode ParseFields_Private(PetscOptionItems *PetscOptionsObject, AdhSolver s)
{
  char      value[256] = "", *item, *rest;
  PetscBool set, all, none;

  PetscFunctionBegin;
  PetscCall(PetscOptionsString("-adh_fields", "Fields written for the states (pressure, displacement, gap, contact; comma-separated; alone: all four)", "AdhSolver", "", value, sizeof(value), &set));
  if (!set) PetscFunctionReturn(0);
  PetscCall(PetscStrInList(value, "all,1,true,yes", ',', &all));
  PetscCall(PetscStrInList(value, "none,0,false,no", ',', &none));
  if (!value[0] || all) s->fields = ADH_FIELD_ALL;
  else if (none) s->fields = 0;
  else {
    s->fields = 0;
    for (item = strtok_r(value, ",", &rest); item; item = strtok_r(NULL, ",", &rest)) {
      PetscInt k;
      for (k = 0; k < 4; k++) {
        PetscBool same;
        PetscCall(PetscStrcmp(item, AdhFieldNames[k], &same));
        if (same) break;
      }
      PetscCheck(k < 4, s->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "-adh_fields: unknown field '%s' (pressure, displacement, gap, contact, or all)", item);
      s->fields |= 1 << k;
    }
  }
  PetscFunctionReturn(0);
}
#define ParseFields(s) ParseFields_Private(PetscOptionsObject, s)

PetscErrorCode AdhSolverSetFromOptions(AdhSolver s)
{
  PetscInt          n = 256;
  PetscReal         path[256];
  PetscBool         set, certify = s->certify;
  char              control[64], criterion[64], predictor[64];
  PetscFunctionList controls, criteria, predictors;
  PetscBool         monitor_set;

  PetscFunctionBegin;
  PetscCall(AdhGridSetFromOptions(s->grid));
  PetscCall(AdhGetReducedModulusFromOptions(s->comm, s->prefix, &s->Estar));
  PetscCall(AdhIndenterSetFromOptions(s->comm, s->prefix, &s->indenter));
  for (PetscInt k = 0; k < s->npath && k < n; k++) path[k] = s->path[k]; /* shown as the default by -help */
  PetscOptionsBegin(s->comm, s->prefix, "adhbem adhesion", "AdhSolver");
  PetscCall(PetscOptionsReal("-adh_gamma", "Work of adhesion dgamma (0: non-adhesive)", "AdhSolver", s->gamma, &s->gamma, NULL));
  PetscCall(PetscOptionsString("-adh_gamma_field", "Work of adhesion field dgamma(x,y) from a file (.npy (Ny, Nx), or HDF5), replacing -adh_gamma in Sigma", "AdhSolver", s->gamma_file, s->gamma_file, sizeof(s->gamma_file), NULL));
  PetscCall(PetscOptionsString("-adh_gamma_field_dataset", "Dataset name inside an HDF5 -adh_gamma_field file", "AdhSolver", s->gamma_dataset, s->gamma_dataset, sizeof(s->gamma_dataset), NULL));
  PetscCall(AdhCriterionGetList_Private(&criteria));
  PetscCall(PetscOptionsFList("-adh_criterion", "When a point lets go: crack-closure (the contact edge's energy release rate, averaged along it, exceeds dgamma; the default) or pohrt-popov (the paper: p < -Sigma; acts as if dgamma were up to 1.85 times larger on straight edges)", "AdhSolverSetCriterionType", criteria, s->criterion_type, criterion, sizeof(criterion), &set));
  if (set) PetscCall(AdhSolverSetCriterionType(s, criterion));
  PetscCall(PetscOptionsReal("-adh_criterion_radius", "crack-closure: average the release rate along the contact edge within this many grid spacings (the weight fades to 0 there)", "AdhSolver", s->criterion_radius, &s->criterion_radius, NULL));
  PetscCall(PetscOptionsReal("-adh_critical_stress", "Fixed critical tensile stress, replacing the mesh-dependent Sigma (for studies of the criterion; 0: use Sigma)", "AdhSolver", s->sigma_fixed, &s->sigma_fixed, NULL));
  PetscOptionsEnd();
  PetscOptionsBegin(s->comm, s->prefix, "adhbem boundary, path and load control", "AdhSolver");
  PetscCall(PetscOptionsEnum("-adh_boundary", "Boundary: free (isolated contact) or periodic", "AdhSolver", AdhBoundaries, (PetscEnum)s->boundary, (PetscEnum *)&s->boundary, &set));
  if (set) s->boundary_set = PETSC_TRUE;
  PetscCall(AdhControlGetList_Private(&controls));
  PetscCall(PetscOptionsFList("-adh_control", "What -adh_path holds: indentations d (displacement) or forces F = sum p hx hy (force; periodic: mean pressure x cell area)", "AdhSolverSetControlType", controls, s->control_type, control, sizeof(control), &set));
  if (set) PetscCall(AdhSolverSetControlType(s, control));
  PetscCall(PetscOptionsRealArray("-adh_path", "Path breakpoints: indentations d0,d1,... (forces under -adh_control force)", "AdhSolver", path, &n, &set));
  if (set) {
    PetscCheck(n >= 2, s->comm, PETSC_ERR_ARG_WRONG, "-adh_path needs at least two points d0,d1,..., got %" PetscInt_FMT, n);
    PetscCall(PetscFree(s->path));
    PetscCall(PetscMalloc1(n, &s->path));
    PetscCall(PetscArraycpy(s->path, path, n));
    s->npath = n;
  }
  PetscCall(PetscOptionsInt("-adh_steps", "Steps per leg of the path", "AdhSolver", s->steps, &s->steps, NULL));
  PetscCall(PetscOptionsEnum("-adh_start", "Starting state: hertz (adhesion-free at d0) or adhesive (loaded from first touch)", "AdhSolver", AdhStarts, (PetscEnum)s->start, (PetscEnum *)&s->start, NULL));
  PetscCall(PetscOptionsEnum("-adh_attach", "When a point joins the set: reach (its gap is below Sigma K_00, the gap it closes under its own critical tension: the JKR jump-in; the default), griffith (beside the contact, when the edge's energy release rate one element further out is below dgamma: crack-closure's mirror) or penetration (g < 0: loading stays Hertz-like)", "AdhSolver", AdhAttaches, (PetscEnum)s->attach, (PetscEnum *)&s->attach, NULL));
  PetscCall(AdhPredictorGetList_Private(&predictors));
  PetscCall(PetscOptionsFList("-adh_predictor", "Without adhesion: guess each step's contact set with Polonsky-Keer's conjugate gradient (polonsky-keer, the default on a periodic cell) before the set-update loop certifies it, or not (none, the default on a free boundary); the answer is the same", "AdhSolverSetPredictorType", predictors, s->predictor_type, predictor, sizeof(predictor), &set));
  if (set) PetscCall(AdhSolverSetPredictorType(s, predictor));
  PetscCall(PetscOptionsReal("-adh_predictor_rtol", "polonsky-keer: stop when an iteration changes the pressure by less than this fraction of its 1-norm", "AdhSolver", s->predictor_rtol, &s->predictor_rtol, NULL));
  PetscCall(PetscOptionsBool("-adh_predictor_fourier", "polonsky-keer under force control: precondition with the inverse of the compliance's symbol, as the set solves do", "AdhSolver", s->predictor_fourier, &s->predictor_fourier, NULL));
  PetscCall(PetscOptionsInt("-adh_predictor_max_it", "polonsky-keer: at most this many iterations per step", "AdhSolver", s->predictor_max_it, &s->predictor_max_it, NULL));
  PetscCall(PetscOptionsReal("-adh_pulloff_rtol", "Force control: relative resolution of the pull-off force", "AdhSolver", s->pulloff_rtol, &s->pulloff_rtol, NULL));
  PetscOptionsEnd();
  PetscOptionsBegin(s->comm, s->prefix, "adhbem output, monitoring and long runs", "AdhSolver");
  PetscCall(PetscOptionsString("-adh_output", "Results file FILE.h5 (the curve also as FILE.csv)", "AdhSolver", s->output, s->output, sizeof(s->output), NULL));
  PetscCall(ParseFields(s));
  PetscCall(PetscOptionsInt("-adh_fields_stride", "Write the fields of every K-th state (0, K, 2K, ...)", "AdhSolver", s->fields_stride, &s->fields_stride, NULL));
  monitor_set = s->monitor;
  PetscCall(PetscOptionsBool("-adh_monitor", "Print one line per step, and progress inside long steps", "AdhSolverMonitorSet", s->monitor, &s->monitor, NULL));
  PetscCall(PetscOptionsReal("-adh_monitor_interval", "Seconds between progress lines inside a step (-adh_monitor)", "AdhSolver", s->monitor_interval, &s->monitor_interval, NULL));
  PetscCall(PetscOptionsString("-adh_checkpoint", "Checkpoint file: the state after recorded states (replaced atomically), to go on from with -adh_restart", "AdhSolver", s->checkpoint, s->checkpoint, sizeof(s->checkpoint), NULL));
  PetscCall(PetscOptionsInt("-adh_checkpoint_every", "Write the checkpoint after every K-th state (and when SIGTERM or SIGINT stops the run)", "AdhSolver", s->checkpoint_every, &s->checkpoint_every, NULL));
  PetscCall(PetscOptionsString("-adh_restart", "Go on from this checkpoint (the options that shape the problem must be the checkpoint's)", "AdhSolver", s->restart, s->restart, sizeof(s->restart), NULL));
  PetscOptionsEnd();
  PetscOptionsBegin(s->comm, s->prefix, "adhbem solver tuning", "AdhSolver");
  PetscCall(PetscOptionsBool("-adh_certify", "Stop intermediate CG solves once the next update of the contact set (points that let go or join) is certain", "AdhSolver", certify, &certify, NULL));
  PetscCall(PetscOptionsBool("-adh_box", "Convolve on the bounding box of the contact set (free boundary)", "AdhSolver", s->use_box, &s->use_box, NULL));
  PetscCall(PetscOptionsInt("-adh_max_outer", "Largest number of set updates in one step", "AdhSolver", s->max_outer, &s->max_outer, NULL));
  PetscCall(PetscOptionsBool("-adh_memory_check", "Refuse a grid whose estimated memory exceeds a node's (the estimate: -adh_view)", "AdhSolverEstimateMemory", s->memory_check, &s->memory_check, NULL));
  PetscOptionsEnd();
  s->certify = certify;
  if (s->monitor && !monitor_set) PetscCall(AdhSolverMonitorSet(s, AdhSolverMonitorDefault, NULL, NULL));
  PetscCheck(s->gamma >= 0 && !PetscIsInfOrNanReal(s->gamma), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_gamma: the work of adhesion must be >= 0, got %g", (double)s->gamma);
  PetscCheck(s->sigma_fixed >= 0, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_critical_stress must be >= 0, got %g", (double)s->sigma_fixed);
  PetscCheck(s->criterion_radius >= 1 && s->criterion_radius <= 64, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_criterion_radius must lie in [1, 64] grid spacings, got %g", (double)s->criterion_radius);
  PetscCheck(s->checkpoint_every >= 1, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_checkpoint_every must be >= 1, got %" PetscInt_FMT, s->checkpoint_every);
  PetscCheck(s->fields_stride >= 1, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_fields_stride must be >= 1, got %" PetscInt_FMT, s->fields_stride);
  PetscCheck(s->steps >= 1, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_steps must be >= 1, got %" PetscInt_FMT, s->steps);
  PetscCheck(s->pulloff_rtol > 0 && s->pulloff_rtol < 1, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_pulloff_rtol must lie in (0, 1), got %g", (double)s->pulloff_rtol);
  for (PetscInt k = 0; k < s->npath; k++) PetscCheck(!PetscIsInfOrNanReal(s->path[k]), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_path: point %" PetscInt_FMT " is not finite", k);
  if (s->ksp) PetscCall(KSPSetFromOptions(s->ksp));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverSetWorkOfAdhesionField(AdhSolver s, Vec gamma)
{
  PetscReal min;

  PetscFunctionBegin;
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

/* Sigma(x,y) = sqrt(hx hy E* dgamma(x,y) / chi), or the fixed stress of -adh_critical_stress. */
static PetscErrorCode ComputeCriticalStress(AdhSolver s)
{
  const AdhGrid g = s->grid;

  PetscFunctionBegin;
  s->Sigma = s->sigma_fixed > 0 ? s->sigma_fixed : AdhCriticalStress(g->hx, g->hy, s->Estar, s->gamma);
  if (s->gamma_field && !(s->sigma_fixed > 0)) {
    PetscCall(VecDestroy(&s->Sigma_view));
    if (!s->Sigma_field) {
      PetscCall(VecDuplicate(s->h, &s->Sigma_field));
      PetscCall(PetscObjectSetName((PetscObject)s->Sigma_field, "critical_stress"));
    }
    PetscCall(VecCopy(s->gamma_field, s->Sigma_field));
    PetscCall(VecScale(s->Sigma_field, g->hx * g->hy * s->Estar / AdhChi(g->hx, g->hy)));
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

/* The Fourier preconditioner: z = R S R^T r, with S the periodic stiffness E*|q|/2 on the grid
   (or on the bounding-box window) and R the restriction to the contact set. */
static PetscErrorCode PCApply_Fourier(PC pc, Vec r, Vec z)
{
  AdhSolver s;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &s));
  PetscCall(AdhSolverApplyOnSet_Private(s, s->Sop, r, z));
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhConvergedCertified_Private(KSP, PetscInt, PetscReal, KSPConvergedReason *, void *);

/* After the profile h is set or replaced: its mean (a periodic cell is in full contact at
   d = mean(h)), and a contact state of nothing in contact. */
PetscErrorCode AdhSolverProfileChanged_Private(AdhSolver s)
{
  PetscScalar sum;

  PetscFunctionBegin;
  PetscCall(VecSum(s->h, &sum));
  s->mean_h = PetscRealPart(sum) / ((PetscReal)s->grid->Nx * (PetscReal)s->grid->Ny);
  s->profile_version++;
  PetscCall(AdhSolverEstimateResolution_Private(s));
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
  else if (s->indenter.type == ADH_INDENTER_FILE)
    PetscCall(PetscPrintf(s->comm, "adhbem: warning: -adh_topography %s on the default free boundary: it is taken as an isolated body of the grid's size; a measured or generated surface is usually a periodic cell: add -adh_boundary periodic (-adh_boundary free keeps this and silences the warning)\n", s->indenter.topography));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverSetUp(AdhSolver s)
{
  PC       pc;
  PetscInt nlocal;
  char     kspprefix[256];

  PetscFunctionBegin;
  if (!s->setup) {
    PetscCall(AdhSolverCheckOptions_Private(s));
    /* A periodic cell does every multiply on the whole grid: plan it without a time limit (a
       limited plan transforms 2x slower at 512^2). */
    if (s->boundary == ADH_BOUNDARY_PERIODIC) s->grid->fftw_timelimit = -1.0;
    /* The predictor transforms the whole grid; on a free boundary the loop's bounding-box
       windows cost less (Hertz 256^2: 0.5 s against 3.1 s), so it is used there only if asked. */
    {
      PetscBool cc;
      PetscCall(PetscStrcmp(s->criterion_type, ADHCRITERIONCRACKCLOSURE, &cc));
      PetscCheck(cc || s->attach != ADH_ATTACH_GRIFFITH, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_attach griffith is the mirror of -adh_criterion crack-closure's detachment test; with -adh_criterion %s use -adh_attach reach or penetration", s->criterion_type);
    }
    if (!s->predictor_chosen && s->boundary == ADH_BOUNDARY_FREE) {
      PetscCall(AdhSolverSetPredictorType(s, ADHPREDICTORNONE));
      s->predictor_chosen = PETSC_FALSE;
    }
    PetscCall(AdhSolverCheckResources_Private(s));
    PetscCall(AdhGridSetUp(s->grid));
    PetscCall(MatCreateAdhCompliance(s->grid, s->Estar, s->boundary, &s->K));
    PetscCall(MatCreateAdhPeriodicStiffness(s->grid, s->Estar, &s->S));
    PetscCall(AdhGridCreateVector(s->grid, &s->h));
    PetscCall(VecDuplicate(s->h, &s->p));
    PetscCall(VecDuplicate(s->h, &s->g));
    PetscCall(PetscObjectSetName((PetscObject)s->h, "profile"));
    PetscCall(PetscObjectSetName((PetscObject)s->p, "pressure"));
    PetscCall(PetscObjectSetName((PetscObject)s->g, "gap"));
    PetscCall(VecSet(s->p, 0.0));
    PetscCall(AdhIndenterFill(s->grid, &s->indenter, s->h));
    if (s->gamma_file[0] && !s->gamma_field) PetscCall(LoadWorkOfAdhesionField(s));
    PetscCall(VecGetLocalSize(s->h, &nlocal));
    PetscCall(PetscCalloc1(nlocal + 1, &s->in_set));
    PetscCall(PetscCalloc1(nlocal + 1, &s->left));
    s->nlocal = nlocal;
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
    PetscCall(PCShellSetName(pc, "adhbem Fourier preconditioner: periodic stiffness E*|q|/2 restricted to the contact set"));
    PetscCall(KSPSetConvergenceTest(s->ksp, AdhConvergedCertified_Private, s, NULL));
    PetscCall(KSPSetFromOptions(s->ksp));
    PetscCall(AdhSolverCheckKSPOptions_Private(s));
    PetscCall(WarnFreeTopography(s));
    if (s->cops.setup) PetscCall(s->cops.setup(s));
    if (s->crops.setup) PetscCall(s->crops.setup(s));
    s->setup = PETSC_TRUE;
  }
  PetscCall(ComputeCriticalStress(s));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetGrid(AdhSolver s, AdhGrid *grid)
{
  PetscFunctionBegin;
  *grid = s->grid;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetCompliance(AdhSolver s, Mat *K)
{
  PetscFunctionBegin;
  *K = s->K;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetContactSet(AdhSolver s, IS *is)
{
  PetscFunctionBegin;
  *is = s->contact;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetFields(AdhSolver s, Vec *p, Vec *u, Vec *g, Vec *h, Vec *Sigma)
{
  PetscFunctionBegin;
  if (p) *p = s->p;
  if (u) PetscCall(AdhSolverGetDisplacement_Private(s, u));
  if (g) *g = s->g;
  if (h) *h = s->h;
  if (Sigma) PetscCall(AdhSolverGetCriticalStressVec_Private(s, Sigma));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetCriticalStress(AdhSolver s, PetscReal *Sigma)
{
  PetscFunctionBegin;
  *Sigma = s->Sigma;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetCurve(AdhSolver s, const AdhCurve **curve)
{
  PetscFunctionBegin;
  *curve = &s->curve;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverView(AdhSolver s, PetscViewer viewer)
{
  PetscBool isascii;

  PetscFunctionBegin;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(s->comm, &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "AdhSolver: adhesive contact, %s boundary\n", AdhBoundaries[s->boundary]));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(AdhGridView(s->grid, viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "E* = %g, dgamma = %g%s, Sigma = %g%s\n", (double)s->Estar, (double)s->gamma, s->gamma_field ? " (field)" : "", (double)s->Sigma, s->sigma_fixed > 0 ? " (fixed by -adh_critical_stress)" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer, "indenter %s, start %s, %" PetscInt_FMT " path points, %" PetscInt_FMT " steps per leg\n", AdhIndenterTypes[s->indenter.type], AdhStarts[s->start], s->npath, s->steps));
  if (s->indenter.type == ADH_INDENTER_ROUGH) PetscCall(AdhSurfaceView(&s->indenter.surface, viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s control; lambda_min bound on the current set %g, certified early stop %s\n", s->control_type, (double)s->lambda_set, s->certify && s->crops.certifiable && !s->force_control ? "on" : "off"));
  PetscCall(PetscViewerASCIIPrintf(viewer, "contact-set predictor without adhesion: %s\n", s->predictor_type));
  if (s->crops.setup) PetscCall(PetscViewerASCIIPrintf(viewer, "detachment criterion %s, averaged within %g grid spacings; attach rule %s\n", s->criterion_type, (double)s->criterion_radius, AdhAttaches[s->attach]));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "detachment criterion %s; attach rule %s\n", s->criterion_type, AdhAttaches[s->attach]));
  if (s->force_control) PetscCall(PetscViewerASCIIPrintf(viewer, "pull-off force resolved to a relative %g\n", (double)s->pulloff_rtol));
  if (s->asperity_ac > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "JKR contact radius of the smallest asperities (estimate) over the grid spacing: %g\n", (double)s->asperity_ac));
  {
    PetscLogDouble total, node;
    PetscCall(AdhSolverEstimateMemory(s, &total, &node));
    PetscCall(PetscViewerASCIIPrintf(viewer, "memory estimate: %.3g MB in all, %.3g MB on this node\n", total / 1e6, node / 1e6));
  }
  if (s->ksp) PetscCall(KSPView(s->ksp, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverDestroy(AdhSolver *solver)
{
  AdhSolver s = *solver;

  PetscFunctionBegin;
  if (!s) PetscFunctionReturn(0);
  if (s->cops.destroy) PetscCall(s->cops.destroy(s));
  if (s->crops.destroy) PetscCall(s->crops.destroy(s));
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
  PetscCall(VecDestroy(&s->g));
  PetscCall(VecDestroy(&s->gamma_field));
  PetscCall(VecDestroy(&s->indenter.z));
  PetscCall(PetscFree(s->in_set));
  PetscCall(PetscFree(s->left));
  PetscCall(PetscFree(s->path));
  PetscCall(AdhCurveDestroy_Private(&s->curve));
  PetscCall(AdhGridDestroy(&s->grid));
  PetscCall(PetscFree(s->prefix));
  PetscCall(PetscFree(s));
  *solver = NULL;
  PetscFunctionReturn(0);
}
