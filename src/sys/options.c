/* adhbem's own options: their names, and the check that every -adh_ option given is one of them
   or one that a registered type read, so that a misspelled option (-adh_gama 0.01) stops the run,
   naming the nearest option, instead of running with the default. The types' options are not
   listed here: each type reads its own (the solver reads those of the types it does not have on
   a scratch solver before the check, solver/interface/types.c). The options of the solver's KSPs and PC (-adh_ksp_*, -adh_pc_*, -adh_local_ksp_*)
   are PETSc's, which reads some only during solves: they are not checked. tests/sys/test_options.py
   keeps this list equal to what -help shows. */
#include <petsc/private/petscimpl.h> /* PetscValid* */
#include "sys/sysimpl.h"

static const char *const AdhOptionNames[] = {
  "adh_n", "adh_size", "adh_E_star", "adh_E1", "adh_E2", "adh_nu1", "adh_nu2", "adh_gamma", "adh_gamma_field",
  "adh_gamma_field_dataset", "adh_critical_stress", "adh_boundary", "adh_indenter", "adh_radius", "adh_punch_radius",
  "adh_elastic", "adh_cone_slope", "adh_topography", "adh_topography_dataset", "adh_topography_kind", "adh_hurst",
  "adh_rms_height", "adh_rms_slope", "adh_rolloff_wavelength", "adh_cutoff_wavelength", "adh_seed", "adh_control",
  "adh_criterion", "adh_path", "adh_steps", "adh_stop_at_pulloff", "adh_start", "adh_attach", "adh_certify", "adh_cascade_rtol", "adh_cascade_single", "adh_cascade_apart", "adh_cascade_local", "adh_cascade_local_rtol",
  "adh_memory_check", "adh_box", "adh_max_outer", "adh_minimize_rtol", "adh_minimize_max_it", "adh_minimize_monitor", "adh_minimize_pc", "adh_minimize_direction", "adh_minimize_trust_region", "adh_predictor", "adh_monitor", "adh_monitor_interval", "adh_progress",
  "adh_fields", "adh_fields_stride", "adh_output", "adh_fftw_planner", "adh_fftw_timelimit", "adh_fftw_layout", "adh_view", "adh_traceback", "adh_checkpoint", "adh_checkpoint_every", "adh_restart",
};

/*@
  AdhGetOptionNames - Gets the names of the options adhbem's solver reads itself, without those of its types

  Not Collective

  Output Parameters:
+ n     - the number of names
- names - the names, without the leading '-' and the prefix (adh_gamma, ...); a static array, not to be freed

  Notes:
  `AdhSolverSetUp()` stops at any option under the solver's prefix that starts with adh_ and is neither one of these
  nor one that a registered type (a criterion, a load control, a predictor) reads (a misspelling), naming the nearest
  of these. Each type reads its own options (its manual page lists them; -help shows them in a group of the type's).
  The options of the solver's KSPs and preconditioners (-adh_ksp_*, -adh_pc_*, -adh_local_ksp_*) are PETSc's and are
  not in the list.

  Level: advanced

.seealso: `AdhSolverSetFromOptions()`, `AdhSolverSetUp()`
@*/
PetscErrorCode AdhGetOptionNames(PetscInt *n, const char *const **names)
{
  PetscFunctionBegin;
  PetscValidIntPointer(n, 1);
  PetscValidPointer(names, 2);
  *n     = (PetscInt)PETSC_STATIC_ARRAY_LENGTH(AdhOptionNames);
  *names = AdhOptionNames;
  PetscFunctionReturn(0);
}

/* Levenshtein distance of two short strings (option names). */
static PetscInt EditDistance(const char *a, const char *b)
{
  PetscInt la = (PetscInt)strlen(a), lb = (PetscInt)strlen(b), row[128], i, j;

  if (lb >= 127) return PETSC_MAX_INT;
  for (j = 0; j <= lb; j++) row[j] = j;
  for (i = 1; i <= la; i++) {
    PetscInt diag = row[0];
    row[0]        = i;
    for (j = 1; j <= lb; j++) {
      const PetscInt up = row[j];
      row[j]            = PetscMin(PetscMin(row[j] + 1, row[j - 1] + 1), diag + (a[i - 1] != b[j - 1]));
      diag              = up;
    }
  }
  return row[lb];
}

/* Every option under this solver's prefix that starts with adh_ and that no part of adhbem reads
   is an error; the message names the nearest known option. */
PetscErrorCode AdhCheckOptions_Private(MPI_Comm comm, const char prefix_or_null[])
{
  PetscInt    n, k, o;
  char      **names, **values;
  size_t      plen = 0;
  const char *prefix = prefix_or_null ? prefix_or_null : "";

  PetscFunctionBegin;
  PetscCall(PetscStrlen(prefix, &plen));
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (k = 0; k < n; k++) {
    const char *name = names[k][0] == '-' ? names[k] + 1 : names[k];
    PetscBool   ours, theirs = PETSC_FALSE, known = PETSC_FALSE;
    PetscInt    best = PETSC_MAX_INT, nearest = 0;
    PetscCall(PetscStrncmp(name, prefix, plen, &ours));
    if (!ours) continue;
    name += plen;
    PetscCall(PetscStrncmp(name, "adh_", 4, &ours));
    if (!ours) continue;
    for (const char *const *p = (const char *const[]){"adh_ksp_", "adh_pc_", "adh_local_ksp_", NULL}; *p && !theirs; p++) PetscCall(PetscStrncmp(name, *p, strlen(*p), &theirs));
    if (theirs) continue;
    for (o = 0; o < (PetscInt)PETSC_STATIC_ARRAY_LENGTH(AdhOptionNames) && !known; o++) {
      const PetscInt dist = EditDistance(name, AdhOptionNames[o]);
      PetscCall(PetscStrcasecmp(name, AdhOptionNames[o], &known));
      if (dist < best) {
        best    = dist;
        nearest = o;
      }
    }
    if (known) continue;
    {
      char message[512];
      PetscCall(PetscSNPrintf(message, sizeof(message), "Unknown option -%s%s (did you mean -%s%s?); build/adhbem -help lists the options", prefix, name, prefix, AdhOptionNames[nearest]));
      PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
      SETERRQ(comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "%s", message);
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(0);
}

/* PETSc options that the solver's KSP reads only during a solve (KSPSolve's views and reports),
   and the common ones, for the nearest name of a misspelled one. */
static const char *const SolveTimePrefixes[] = {"ksp_view", "ksp_converged_reason", "ksp_converged_rate", "ksp_compute_", "ksp_plot_", "ksp_final_residual", NULL};
static const char *const KSPOptionNames[]    = {"ksp_rtol", "ksp_atol", "ksp_divtol", "ksp_max_it", "ksp_type", "ksp_norm_type", "ksp_monitor", "ksp_monitor_short", "ksp_monitor_true_residual", "ksp_converged_reason", "ksp_view", "ksp_error_if_not_converged", "ksp_initial_guess_nonzero", "ksp_pc_side", "ksp_compute_eigenvalues", "ksp_view_final_residual", "pc_type", NULL};

/* After a KSP's set-up from the options: every -{which}ksp_ and -{which}pc_ option under this
   solver's prefix that neither it nor a solve reads (misspelled, or of another KSP type) is an
   error naming it, before any solve. which: "adh_" (the set's solves) or "adh_local_"
   (-adh_cascade_local's). */
PetscErrorCode AdhCheckKSPOptions_Private(KSP ksp, const char prefix_or_null[], const char which[])
{
  PetscInt    n;
  char      **names, **values, message[512] = "", kspname[64], pcname[64];
  size_t      plen   = 0, wlen = 0;
  const char *prefix = prefix_or_null ? prefix_or_null : "";
  KSPType     type;

  PetscFunctionBegin;
  PetscCall(KSPGetType(ksp, &type));
  PetscCall(PetscStrlen(prefix, &plen));
  PetscCall(PetscStrlen(which, &wlen));
  PetscCall(PetscSNPrintf(kspname, sizeof(kspname), "%sksp_", which));
  PetscCall(PetscSNPrintf(pcname, sizeof(pcname), "%spc_", which));
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt k = 0; k < n && !message[0]; k++) {
    const char *name = names[k][0] == '-' ? names[k] + 1 : names[k], *inner;
    PetscBool   ours, ksp, pc, later = PETSC_FALSE;
    PetscInt    best = PETSC_MAX_INT, nearest = 0;
    PetscCall(PetscStrncmp(name, prefix, plen, &ours));
    if (!ours) continue;
    name += plen;
    PetscCall(PetscStrncmp(name, kspname, wlen + 4, &ksp));
    PetscCall(PetscStrncmp(name, pcname, wlen + 3, &pc));
    if (!ksp && !pc) continue;
    inner = name + wlen;
    for (const char *const *p = SolveTimePrefixes; *p && !later; p++) PetscCall(PetscStrncmp(inner, *p, strlen(*p), &later));
    if (later) continue;
    for (PetscInt o = 0; KSPOptionNames[o]; o++) {
      const PetscInt dist = EditDistance(inner, KSPOptionNames[o]);
      if (dist < best) {
        best    = dist;
        nearest = o;
      }
    }
    if (best <= 3) PetscCall(PetscSNPrintf(message, sizeof(message), "Option -%s%s is not read by the solver's KSP (%s) or its preconditioner (did you mean -%s%s%s?)", prefix, name, type, prefix, which, KSPOptionNames[nearest]));
    else PetscCall(PetscSNPrintf(message, sizeof(message), "Option -%s%s is not read by the solver's KSP (%s) or its preconditioner: misspelled, or an option of another KSP or PC type", prefix, name, type));
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(!message[0], PetscObjectComm((PetscObject)ksp), PETSC_ERR_ARG_UNKNOWN_TYPE, "%s", message);
  /* PETSc's initial guesses (KSPGuess: fischer, pod) keep vectors of one operator size, and the
     contact set changes size at every set update: PETSc would stop deep inside the first solve
     after one with "Incompatible vector local lengths" */
  {
    char      option[256];
    PetscBool guess;
    PetscCall(PetscSNPrintf(option, sizeof(option), "-%s%sksp_guess_type", prefix, which));
    PetscCall(PetscOptionsHasName(NULL, NULL, option, &guess));
    PetscCheck(!guess, PetscObjectComm((PetscObject)ksp), PETSC_ERR_ARG_INCOMP, "%s: PETSc's initial guesses (KSPGuess) need one operator size, and the contact set changes size at every set update; each solve starts from the pressures of the last one instead", option);
  }
  PetscFunctionReturn(0);
}
