/* AdhSolverSetFromOptions: the -adh_ options of the solver and of its types. */
#include "solver/solverimpl.h"

const char *const AdhFieldNames[4] = {"pressure", "displacement", "gap", "contact"};

/* -adh_fields [LIST]: the fields to write, a comma-separated list of pressure, displacement, gap,
   contact; given alone (or all, 1, true) all four, none (or 0, false) no fields. Inside
   PetscOptionsBegin/End, so that -help shows it. */
static PetscErrorCode ParseFields_Private(AdhOptionItems PetscOptionsObject, AdhSolver s)
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

/*@
  AdhSolverSetFromOptions - Sets the problem and the solver's settings from the options database

  Collective

  Input Parameter:
. s - the solver

  Options Database Keys:
+ -adh_n <N or Nx,Ny>                                - elements per side (default 64)
. -adh_size <L or Lx,Ly>                             - the domain's side lengths (default 1)
. -adh_E_star <E>                                    - the reduced modulus, or -adh_E1, -adh_nu1, -adh_E2, -adh_nu2
. -adh_indenter <sphere,punch,cone,rough,file,array> - the indenter; -adh_radius, -adh_topography FILE, -adh_hurst, ...
. -adh_gamma <dgamma>                                - the work of adhesion (0: non-adhesive)
. -adh_gamma_field <FILE>                            - a work of adhesion field dgamma(x,y), .npy or HDF5, read at set-up
. -adh_criterion <crack-closure,pohrt-popov,dugdale> - the detachment criterion, `AdhSolverSetCriterionType()`
. -adh_critical_stress <0>                           - a fixed critical stress replacing Sigma (0: Sigma)
. -adh_boundary <free,periodic>                      - an isolated contact or a periodic cell
. -adh_control <displacement,force>                  - the load control, `AdhSolverSetControlType()`
. -adh_path <v0,v1,...>                              - the path's breakpoints, at least two (default 0.01,0)
. -adh_steps <10>                                    - the steps per leg of the path
. -adh_stop_at_pulloff <true>                        - a pull-off ends the path (false: only its leg)
. -adh_start <hertz,adhesive>                        - the starting state, `AdhSolverStart()`
. -adh_attach <griffith,reach,penetration>           - when a point joins the set
. -adh_predictor <polonsky-keer,none>                - the contact-set predictor, `AdhSolverSetPredictorType()`
. -adh_output <FILE>                                 - the results file FILE.h5, and FILE.csv
. -adh_fields [LIST]                                 - the fields written: pressure, displacement, gap, contact (alone: all)
. -adh_monitor                                       - one line per state, `AdhSolverMonitorDefault()`
. -adh_progress <5>                                  - progress lines of a path, `AdhSolverSetProgress()`
. -adh_checkpoint <FILE>                             - a checkpoint, with -adh_checkpoint_every and -adh_restart FILE
. -adh_certify <true>                                - the certified early stop of intermediate solves
. -adh_cascade_local <F>                             - local solves after a set update lets points go
- -adh_max_outer <100000>                            - the largest number of set updates in one step

  Level: beginner

  Notes:
  The options come in the groups -help shows, with every option and its default: the grid; the material; the
  indenter and the rough surface; the adhesion (work of adhesion, criterion); the boundary, path and load control
  (with the predictor); output, monitoring and long runs; and the solver's tuning (-adh_certify, -adh_cascade_*,
  -adh_box, -adh_max_outer, -adh_memory_check). docs/reference/options.md lists them by task.

  Values out of range are errors naming the option: -adh_gamma below 0 or not finite, -adh_critical_stress below 0,
  -adh_cascade_rtol outside [0, 1), -adh_cascade_apart outside [0, 64], -adh_cascade_local below 0 or NaN,
  -adh_cascade_local_rtol outside (0, 1), -adh_steps, -adh_checkpoint_every and -adh_fields_stride below 1,
  -adh_progress below 0 or NaN, a point of -adh_path that is not finite; and -adh_cascade_apart or -adh_cascade_local
  under a control whose steps do not re-solve at a fixed target (force control). -adh_path takes at most 256 points.

  The types' own options are read by the type in use, in a -help group of its own, and checked there: crack-closure's
  -adh_criterion_radius and -adh_criterion_radius_max (`ADHCRITERIONCRACKCLOSURE`), force control's -adh_pulloff_rtol
  (`ADHCONTROLFORCE`), polonsky-keer's -adh_predictor_rtol, -adh_predictor_max_it and -adh_predictor_fourier
  (`ADHPREDICTORPOLONSKYKEER`). With -help the options of every registered type are listed; those of the types not in
  use are read (and checked) on a scratch solver, so that set-up does not take them for misspellings. Set a type
  before this call: a type set afterwards keeps its defaults.

  -adh_monitor sets `AdhSolverMonitorDefault()` once. The KSP of the contact-set solves reads its options
  (-adh_ksp_rtol, ...) at set-up, and here again once it exists. A misspelled -adh_ option is refused at set-up.

  Call it before `AdhSolverSetUp()`: what set-up builds from the options (the grid, the boundary, the profile, the
  operators) is not rebuilt by a later call, and the load control and the criterion cannot change after set-up.

.seealso: `AdhSolverCreate()`, `AdhSolverSetUp()`, `AdhSolverSetOptionsPrefix()`, `AdhSolverSetCriterionType()`,
          `AdhSolverSetControlType()`, `AdhSolverSetPredictorType()`, `AdhSolverMonitorSet()`, `AdhSolverView()`
@*/
PetscErrorCode AdhSolverSetFromOptions(AdhSolver s)
{
  PetscInt          n = 256;
  PetscReal         path[256];
  PetscBool         set, certify;
  char              control[64], criterion[64], predictor[64], elastic[64];
  PetscBool         monitor_set, help;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  certify = s->certify;
  PetscCall(AdhGridSetFromOptions(s->grid));
  s->material.Estar = s->Estar;
  PetscCall(AdhMaterialSetFromOptions_Private(s->comm, s->prefix, &s->material));
  s->Estar = s->material.Estar;
  PetscOptionsBegin(s->comm, s->prefix, "adhbem elastic body", "AdhSolver");
  PetscCall(PetscOptionsFList("-adh_elastic", "What deforms: halfspace (an elastic half-space of modulus E*, free or periodic; the default) or layer (an elastic layer of thickness -adh_layer_thickness on a rigid base, bonded or slipping, periodic; needs -adh_E1 and -adh_nu1)", "AdhSolverSetElasticType", AdhElastics.list, s->elastic_type, elastic, sizeof(elastic), &set));
  if (set) PetscCall(AdhSolverSetElasticType(s, elastic));
  PetscOptionsEnd();
  PetscCall(AdhIndenterSetFromOptions_Private(s->grid, s->prefix, &s->indenter));
  for (PetscInt k = 0; k < s->npath && k < n; k++) path[k] = s->path[k]; /* shown as the default by -help */
  PetscOptionsBegin(s->comm, s->prefix, "adhbem adhesion", "AdhSolver");
  PetscCall(AdhOptionsReal("-adh_gamma", "Work of adhesion dgamma (0: non-adhesive)", "AdhSolver", s->gamma, &s->gamma, NULL));
  PetscCall(PetscOptionsString("-adh_gamma_field", "Work of adhesion field dgamma(x,y) from a file (.npy (Ny, Nx), or HDF5), replacing -adh_gamma in Sigma", "AdhSolver", s->gamma_file, s->gamma_file, sizeof(s->gamma_file), NULL));
  PetscCall(PetscOptionsString("-adh_gamma_field_dataset", "Dataset name inside an HDF5 -adh_gamma_field file", "AdhSolver", s->gamma_dataset, s->gamma_dataset, sizeof(s->gamma_dataset), NULL));
  PetscCall(PetscOptionsFList("-adh_criterion", "When a point lets go: crack-closure (the contact edge's energy release rate, averaged along it, exceeds dgamma; the default) or pohrt-popov (the paper: p < -Sigma; acts as if dgamma were up to 1.85 times larger on straight edges), both the JKR limit (zero range); or a finite range: dugdale (Maugis' cohesive zone, -adh_dugdale_stress), exponential (an exponential attraction, -adh_exponential_range; steps minimise the energy)", "AdhSolverSetCriterionType", AdhCriteria.list, s->criterion_type, criterion, sizeof(criterion), &set));
  if (set) PetscCall(AdhSolverSetCriterionType(s, criterion));
  PetscCall(AdhOptionsReal("-adh_critical_stress", "Fixed critical tensile stress, replacing the mesh-dependent Sigma (for studies of the criterion; 0: use Sigma)", "AdhSolver", s->sigma_fixed, &s->sigma_fixed, NULL));
  PetscOptionsEnd();
  PetscOptionsBegin(s->comm, s->prefix, "adhbem boundary, path and load control", "AdhSolver");
  PetscCall(PetscOptionsEnum("-adh_boundary", "Boundary: free (isolated contact) or periodic", "AdhSolver", AdhBoundaries, (PetscEnum)s->boundary, (PetscEnum *)&s->boundary, &set));
  if (set) s->boundary_set = PETSC_TRUE;
  PetscCall(PetscOptionsFList("-adh_control", "What -adh_path holds: indentations d (displacement) or forces F = sum p hx hy (force; periodic: mean pressure x cell area)", "AdhSolverSetControlType", AdhControls.list, s->control_type, control, sizeof(control), &set));
  if (set) PetscCall(AdhSolverSetControlType(s, control));
  PetscCall(AdhOptionsRealArray("-adh_path", "Path breakpoints: indentations d0,d1,... (forces under -adh_control force); default 0.01,0 (-help shows an array's first value only)", "AdhSolver", path, &n, &set));
  if (set) {
    PetscCheck(n >= 2, s->comm, PETSC_ERR_ARG_WRONG, "-adh_path needs at least two points d0,d1,..., got %" PetscInt_FMT, n);
    PetscCall(PetscFree(s->path));
    PetscCall(PetscMalloc1(n, &s->path));
    PetscCall(PetscArraycpy(s->path, path, n));
    s->npath = n;
  }
  PetscCall(AdhOptionsInt("-adh_steps", "Steps per leg of the path", "AdhSolver", s->steps, &s->steps, NULL));
  PetscCall(PetscOptionsBool("-adh_stop_at_pulloff", "A pull-off ends the path (false: only its leg, and the legs after it run, to come back into contact)", "AdhSolver", s->stop_at_pulloff, &s->stop_at_pulloff, NULL));
  PetscCall(PetscOptionsEnum("-adh_start", "Starting state: hertz (adhesion-free at d0) or adhesive (loaded from first touch)", "AdhSolver", AdhStarts, (PetscEnum)s->start, (PetscEnum *)&s->start, NULL));
  PetscCall(PetscOptionsEnum("-adh_attach", "When a point joins the set: griffith (beside the contact, when the edge's energy release rate one element further out is below dgamma: crack-closure's mirror; the default with crack-closure), reach (its gap is below Sigma K_00, the gap it closes under its own critical tension; the default with pohrt-popov) or penetration (g < 0: loading stays Hertz-like)", "AdhSolver", AdhAttaches, (PetscEnum)s->attach, (PetscEnum *)&s->attach, &set));
  if (set) s->attach_chosen = PETSC_TRUE;
  PetscCall(PetscOptionsFList("-adh_predictor", "Without adhesion: guess each step's contact set with Polonsky-Keer's conjugate gradient (polonsky-keer, the default on a periodic cell) before the set-update loop certifies it, or not (none, the default on a free boundary); the answer is the same", "AdhSolverSetPredictorType", AdhPredictors.list, s->predictor_type, predictor, sizeof(predictor), &set));
  if (set) PetscCall(AdhSolverSetPredictorType(s, predictor));
  PetscOptionsEnd();
  /* the types' own options, each in a group of its own (and under -help those of the types not chosen) */
  PetscCall(AdhSolverTypeSetFromOptions_Private(s, &AdhElastics, s->elastic_type, &s->eops.base));
  PetscCall(AdhSolverTypeSetFromOptions_Private(s, &AdhCriteria, s->criterion_type, &s->crops.base));
  PetscCall(AdhSolverTypeSetFromOptions_Private(s, &AdhControls, s->control_type, &s->cops.base));
  PetscCall(AdhSolverTypeSetFromOptions_Private(s, &AdhPredictors, s->predictor_type, &s->pops.base));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (help) PetscCall(AdhSolverReadTypesOptions_Private(s));
  PetscOptionsBegin(s->comm, s->prefix, "adhbem output, monitoring and long runs", "AdhSolver");
  PetscCall(PetscOptionsString("-adh_output", "Results file FILE.h5 (the curve also as FILE.csv)", "AdhSolver", s->output, s->output, sizeof(s->output), NULL));
  PetscCall(ParseFields(s));
  PetscCall(AdhOptionsInt("-adh_fields_stride", "Write the fields of every K-th state (0, K, 2K, ...)", "AdhSolver", s->fields_stride, &s->fields_stride, NULL));
  monitor_set = s->monitor;
  PetscCall(PetscOptionsBool("-adh_monitor", "Print one line per step, and progress inside long steps", "AdhSolverMonitorSet", s->monitor, &s->monitor, NULL));
  PetscCall(AdhOptionsReal("-adh_progress", "Print a progress line (state, time so far and an estimate of the time left) after this many seconds of a path, then every tenth of the time so far or this, whichever is longer (0: none; -adh_monitor prints a line a state instead)", "AdhSolver", s->progress, &s->progress, NULL));
  PetscCall(AdhOptionsReal("-adh_monitor_interval", "Seconds between progress lines inside a step (-adh_monitor)", "AdhSolver", s->monitor_interval, &s->monitor_interval, NULL));
  PetscCall(PetscOptionsString("-adh_checkpoint", "Checkpoint file: the state after recorded states (replaced atomically), to go on from with -adh_restart", "AdhSolver", s->checkpoint, s->checkpoint, sizeof(s->checkpoint), NULL));
  PetscCall(AdhOptionsInt("-adh_checkpoint_every", "Write the checkpoint after every K-th state (and when SIGTERM or SIGINT stops the run)", "AdhSolver", s->checkpoint_every, &s->checkpoint_every, NULL));
  PetscCall(PetscOptionsString("-adh_restart", "Go on from this checkpoint (the options that shape the problem must be the checkpoint's)", "AdhSolver", s->restart, s->restart, sizeof(s->restart), NULL));
  PetscOptionsEnd();
  PetscOptionsBegin(s->comm, s->prefix, "adhbem solver tuning", "AdhSolver");
  PetscCall(PetscOptionsBool("-adh_certify", "Stop intermediate CG solves once the next update of the contact set (points that let go or join) is certain", "AdhSolver", certify, &certify, NULL));
  PetscCall(PetscOptionsBool("-adh_cascade_single", "The solves that stop at -adh_cascade_rtol, and the local solves of -adh_cascade_local, apply the compliance and the preconditioner in single precision (float transforms: half the bytes to move; periodic cells); the last solve of a step stays in double", "AdhSolver", s->cascade_single, &s->cascade_single, NULL));
  PetscCall(AdhOptionsInt("-adh_cascade_apart", "Points may join in a set update that lets others go, where they lie more than this many grid spacings from every point let go in it (0: joins only in an update that lets nothing go, the exact cascade)", "AdhSolver", s->cascade_apart, &s->cascade_apart, NULL));
  PetscCall(AdhOptionsReal("-adh_cascade_rtol", "Solves between set updates of a step stop at this relative residual, and the set is updated on their pressures (0: every solve to -adh_ksp_rtol); a set that stands on one is solved to -adh_ksp_rtol and tested again. Fewer KSP iterations; the sets along the way may differ from the exact cascade's", "AdhSolver", s->cascade_rtol, &s->cascade_rtol, NULL));
  PetscCall(AdhSolverDefaultCascadeLocal_Private(s)); /* the default follows the criterion and the control read above */
  PetscCall(AdhOptionsReal("-adh_cascade_local", "After a set update lets points go, solve the set again only within this many times the smallest asperities' JKR contact radius (the estimate the run prints) of them, the rest frozen; let go what that shows, and repeat; the whole set is solved again when a local solve lets nothing go (0: every solve on the whole set, the exact cascade of the paper; inf: the whole grid, the default with crack-closure under displacement control, 0 otherwise; below 3 the frozen rest biases the path towards letting go)", "AdhSolver", s->cascade_local, &s->cascade_local, &set));
  if (set) s->cascade_local_set = PETSC_TRUE;
  PetscCall(AdhOptionsReal("-adh_cascade_local_rtol", "The relative residual at which the local solves of -adh_cascade_local stop, relative to the residual the points let go leave", "AdhSolver", s->cascade_local_rtol, &s->cascade_local_rtol, NULL));
  PetscCall(PetscOptionsBool("-adh_box", "Convolve on the bounding box of the contact set (free boundary)", "AdhSolver", s->use_box, &s->use_box, NULL));
  PetscCall(AdhOptionsInt("-adh_max_outer", "Largest number of set updates in one step", "AdhSolver", s->max_outer, &s->max_outer, NULL));
  PetscCall(AdhSolverMinimizeSetFromOptions_Private(s, PetscOptionsObject)); /* the cohesive laws' steps */
  PetscCall(PetscOptionsBool("-adh_memory_check", "Refuse a grid whose estimated memory exceeds a node's (the estimate: -adh_view)", "AdhSolverEstimateMemory", s->memory_check, &s->memory_check, NULL));
  PetscOptionsEnd();
  s->certify = certify;
  if (s->monitor && !monitor_set) PetscCall(AdhSolverMonitorSet(s, AdhSolverMonitorDefault, NULL, NULL));
  PetscCheck(s->gamma >= 0 && !PetscIsInfOrNanReal(s->gamma), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_gamma: the work of adhesion must be >= 0, got %g", (double)s->gamma);
  PetscCheck(s->sigma_fixed >= 0 && !PetscIsInfReal(s->sigma_fixed), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_critical_stress must be >= 0 and finite, got %g", (double)s->sigma_fixed);
  PetscCheck(s->max_outer >= 1, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_max_outer must be at least 1, got %" PetscInt_FMT, s->max_outer);
  PetscCheck(s->monitor_interval >= 0, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_monitor_interval must be >= 0 seconds (0: a line at every chance; inf: none inside a step), got %g", (double)s->monitor_interval);
  PetscCheck(s->cascade_rtol >= 0 && s->cascade_rtol < 1, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_cascade_rtol must lie in [0, 1), got %g", (double)s->cascade_rtol);
  PetscCheck(s->cascade_apart >= 0 && s->cascade_apart <= 64, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_cascade_apart must lie in [0, 64] grid spacings, got %" PetscInt_FMT, s->cascade_apart);
  PetscCheck(!(s->cascade_apart > 0 && !s->cops.cascades), s->comm, PETSC_ERR_ARG_INCOMP, "-adh_cascade_apart: displacement control only (-adh_control displacement)");
  PetscCheck(s->cascade_local >= 0 && !PetscIsNanReal(s->cascade_local), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_cascade_local must be >= 0 (times the JKR contact radius; inf: the whole grid), got %g", (double)s->cascade_local);
  PetscCheck(s->cascade_local_rtol > 0 && s->cascade_local_rtol < 1, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_cascade_local_rtol must lie in (0, 1), got %g", (double)s->cascade_local_rtol);
  PetscCheck(!(s->cascade_local > 0 && !s->cops.cascades), s->comm, PETSC_ERR_ARG_INCOMP, "-adh_cascade_local: displacement control only (-adh_control displacement)");
  PetscCheck(s->checkpoint_every >= 1, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_checkpoint_every must be >= 1, got %" PetscInt_FMT, s->checkpoint_every);
  PetscCheck(s->fields_stride >= 1, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_fields_stride must be >= 1, got %" PetscInt_FMT, s->fields_stride);
  PetscCheck(s->progress >= 0 && !PetscIsNanReal(s->progress), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_progress must be >= 0 seconds, got %g", (double)s->progress);
  PetscCheck(s->steps >= 1, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_steps must be >= 1, got %" PetscInt_FMT, s->steps);
  for (PetscInt k = 0; k < s->npath; k++) PetscCheck(!PetscIsInfOrNanReal(s->path[k]), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_path: point %" PetscInt_FMT " is not finite", k);
  if (s->ksp) PetscCall(KSPSetFromOptions(s->ksp));
  PetscFunctionReturn(0);
}
