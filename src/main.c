/* adhbem: run an indentation path of an adhesive contact and write the curve.
   mpirun -n P build/adhbem [options] (or -options_file job.opts); -help lists the options. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "adhbem.h"

static const char help[] = "adhbem: adhesive normal contact of elastic solids with the boundary element method\n"
                           "(crack-closure detachment by default; Pohrt & Popov 2015's criterion with -adh_criterion pohrt-popov), on PETSc.\n"
                           "Runs the indentation path -adh_path with -adh_steps steps per leg and writes -adh_output.\n\n";

/* An error prints its message once, on the first rank that sees it, as one line (with the
   out-of-memory case said plainly); PETSc's traceback of every frame stays behind -adh_traceback. */
static PetscBool error_on_every_rank = PETSC_TRUE; /* the error was raised on all ranks together */

static PetscErrorCode ErrorOneLine(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  PetscMPIInt rank = 0, size = 1, world = 1;

  if (p != PETSC_ERROR_INITIAL) return n;
  if (comm != PETSC_COMM_SELF) {
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
  }
  MPI_Comm_size(PETSC_COMM_WORLD, &world);
  error_on_every_rank = (PetscBool)(size == world);
  if (rank) return n;
  if (n == PETSC_ERR_SIG && mess && !strncmp(mess, "stopped by signal", 17)) fprintf(stderr, "adhbem: %s\n", mess); /* a stop, not a failure */
  else if (n == PETSC_ERR_MEM && !(mess && mess[0])) fprintf(stderr, "adhbem: error: out of memory (use a smaller grid or more nodes; -adh_view shows the memory estimate)\n");
  else if (n == PETSC_ERR_MEM) fprintf(stderr, "adhbem: error: not enough memory: %s\n", mess);
  else if (mess && mess[0]) fprintf(stderr, "adhbem: error: %s\n", mess);
  else {
    const char *text = NULL;
    PetscErrorMessage(n, &text, NULL);
    fprintf(stderr, "adhbem: error: %s (in %s() at %s:%d)\n", text ? text : "unknown error", fun ? fun : "?", file ? file : "?", line);
  }
  fflush(stderr);
  return n;
}

/* Open MPI's own MPI-IO (ompio), which HDF5 writes through, opens a shared-file-pointer
   component along with every file, though adhbem never uses shared file pointers: "sm" guards
   each file with a named semaphore keyed on the file's base name alone (a job killed while it
   held one leaves it locked in /dev/shm, and every later run that writes a file of that name
   waits on it forever), "lockedfile" creates FILE-JOBID-PID.lock beside it and "individual"
   FILE.data.RANK and FILE.metadata.RANK, all left behind by a killed job (checked: SIGKILL of a
   job writing its results). ROMIO, Open MPI's other MPI-IO, creates nothing beside the file: it
   is asked for unless the user chose, and the "sm" component is kept out for a user who asks
   for ompio. */
static void AvoidStaleLocks(void)
{
#if defined(OPEN_MPI)
  setenv("OMPI_MCA_io", "^ompio", 0);
  setenv("OMPI_MCA_sharedfp", "^sm", 0);
#endif
}

/* This process's rank as the launcher (mpirun, mpiexec, srun) says it, for what is done before MPI
   starts; NULL when run without one. */
static const char *LauncherRank(void)
{
  const char *names[] = {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK", "SLURM_PROCID"};

  for (size_t k = 0; k < sizeof(names) / sizeof(names[0]); k++) {
    const char *rank = getenv(names[k]);
    if (rank) return rank;
  }
  return NULL;
}

/* Why an options file is not one PETSc reads (NULL when it is), by PETSc's rules: '#' starts a
   comment, and the first word of every other line that is not blank is an option (-name) or
   "alias". PETSc finds the same inside its initialisation and prints its traceback and MPI's
   abort banner. */
static const char *OptionsFileFault(const char *file, char why[], size_t len)
{
  FILE  *f = fopen(file, "rb");
  char   line[4096];
  size_t n = 0;
  int    c, number = 1;

  if (!f) return "no such file (or not readable)";
  do {
    c = fgetc(f);
    if (c != EOF && c != '\n') {
      if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f) {
        snprintf(why, len, "line %d holds control bytes: not a text file of options", number);
        break;
      }
      if (n + 1 < sizeof(line)) line[n++] = (char)c;
      continue;
    }
    line[n] = 0;
    {
      char *word, *end;
      if ((end = strchr(line, '#'))) *end = 0;
      for (char *t = line; *t; t++)
        if (*t == '\t' || *t == '\r') *t = ' ';
      for (word = line; *word == ' '; word++) continue;
      for (end = word; *end && *end != ' '; end++) continue;
      *end = 0;
      if (*word && word[0] != '-' && strcasecmp(word, "alias")) {
        snprintf(why, len, "line %d: '%.60s' is not an option (each line is -name [value]; # starts a comment)%s%.60s%s", number, word, strncmp(word, "adh_", 4) ? "" : "; did you mean -", strncmp(word, "adh_", 4) ? "" : word, strncmp(word, "adh_", 4) ? "" : "?");
        break;
      }
    }
    n = 0;
    number++;
  } while (c != EOF);
  fclose(f);
  return why[0] ? why : NULL;
}

/* -options_file names a file that is not there, or that PETSc would refuse: one line, not PETSc's
   dump from within its initialisation (printed by the first rank; every rank stops before MPI
   starts). */
static int CheckOptionsFiles(int argc, char **argv)
{
  const char *rank = LauncherRank();

  for (int k = 1; k < argc; k++) {
    const char *file = k + 1 < argc ? argv[k + 1] : NULL, *fault = NULL;
    char        why[256] = "";
    if (strcmp(argv[k], "-options_file")) continue;
    if (file && file[0] != '-' && !(fault = OptionsFileFault(file, why, sizeof(why)))) continue;
    if (!rank || !strcmp(rank, "0")) {
      if (!file || file[0] == '-') fprintf(stderr, "adhbem: error: -options_file needs a file name\n");
      else fprintf(stderr, "adhbem: error: -options_file %s: %s\n", file, fault);
    }
    return 1;
  }
  return 0;
}

/* --version or -version: adhbem's version, the PETSc it runs with and the one it was built against, printed
   by the first rank, before PETSc starts (PETSc's own -version would add its banner and go on). Returns 0
   without such an option, 1 when it was printed (by this rank or the first), 2 when it failed. */
static int PrintVersion(int argc, char **argv)
{
  const char *rank = LauncherRank();
  char        version[256];

  for (int k = 1; k < argc; k++) {
    if (strcmp(argv[k], "--version") && strcmp(argv[k], "-version")) continue;
    if (rank && strcmp(rank, "0")) return 1;
    if (AdhGetVersion(version, sizeof(version))) return 2;
    printf("%s\nbuilt against PETSc %d.%d.%d with %d-bit indices\n", version, PETSC_VERSION_MAJOR, PETSC_VERSION_MINOR, PETSC_VERSION_SUBMINOR, (int)(8 * sizeof(PetscInt)));
    return 1;
  }
  return 0;
}

/* PETSc's KSP and PC options without adhbem's prefix (-ksp_rtol) do nothing: the solver's KSP
   reads -adh_ksp_*. Nothing else in the executable reads them. */
static PetscErrorCode CheckUnprefixedOptions(void)
{
  PetscInt n;
  char   **names, **values;
  char     message[512] = "";

  PetscFunctionBegin;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt k = 0; k < n && !message[0]; k++) {
    const char *name = names[k][0] == '-' ? names[k] + 1 : names[k];
    if (!strncmp(name, "ksp_", 4) || !strncmp(name, "pc_", 3)) PetscCall(PetscSNPrintf(message, sizeof(message), "-%s does nothing: the solver's KSP and PC options have the prefix adh_ (-adh_%s)", name, name));
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(!message[0], PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "%s", message);
  PetscFunctionReturn(0);
}

/* What the summary says of the largest tension: a pull-off force only when the surfaces came apart,
   else why it is not one (full contact to the end, or the path ended in contact). */
static PetscErrorCode PullOffWords(const AdhCurve *curve, PetscInt npoints, const AdhResolution *r, char words[], size_t len)
{
  const AdhState *st = r->state >= 0 ? &curve->state[r->state] : NULL;

  PetscFunctionBeginUser;
  words[0] = 0;
  if (r->apart >= 0 && st) PetscCall(PetscSNPrintf(words, len, "pull-off force (the largest tension) %g at d = %g; contact lost at d = %g", (double)-st->force, (double)st->d, (double)curve->state[r->apart].d));
  else if (r->apart >= 0) PetscCall(PetscSNPrintf(words, len, "no tension carried; contact lost at d = %g", (double)curve->state[r->apart].d));
  else {
    char why[128], tension[128] = "no tension carried";
    if (r->full_contact >= 0 && r->last_points == npoints) PetscCall(PetscSNPrintf(why, sizeof(why), "in full contact from state %" PetscInt_FMT " to the end of the path", r->full_contact));
    else PetscCall(PetscSNPrintf(why, sizeof(why), "the path ended with %" PetscInt_FMT " points in contact%s", r->last_points, r->full_contact >= 0 ? ", after full contact" : ""));
    if (st) PetscCall(PetscSNPrintf(tension, sizeof(tension), "the largest tension %g at d = %g is not a pull-off force", (double)-st->force, (double)st->d));
    PetscCall(PetscSNPrintf(words, len, "the surfaces did not come apart (%s): %s", why, tension));
  }
  PetscFunctionReturn(0);
}

/* -help lists adhbem's options first. PETSc prints its options for every program (the debugger,
   malloc, logging, devices: some 70 lines) inside PetscInitialize when it sees -help; so -help is
   held back from it and given to the options database after initialization, where the options
   are listed as they are read. -help petsc (or -help intro) goes to PETSc as it is. Returns 1 when
   held back. */
static int HoldBackHelp(int *argc, char **argv)
{
  for (int k = 1; k < *argc; k++) {
    if (strcmp(argv[k], "-help") && strcmp(argv[k], "--help")) continue;
    if (k + 1 < *argc && (!strcmp(argv[k + 1], "petsc") || !strcmp(argv[k + 1], "intro"))) {
      if (!strcmp(argv[k + 1], "petsc")) argv[k + 1] = (char *)"";
      return 0;
    }
    for (int j = k; j + 1 < *argc; j++) argv[j] = argv[j + 1];
    (*argc)--;
    argv[*argc] = NULL;
    return 1;
  }
  return 0;
}

static PetscErrorCode Run(AdhSolver solver)
{
  const AdhCurve *curve;
  PetscBool       has_help;

  PetscFunctionBeginUser;
  PetscCall(AdhSolverSetFromOptions(solver));
  PetscCall(PetscOptionsHasHelp(NULL, &has_help));
  if (has_help) {
    /* The options above were listed as they were read; the solver's KSP ones come with set-up. */
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  -adh_view [ascii[:FILE]]: Print the solver set-up (to FILE) (PetscObjectViewFromOptions)\n"));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  -adh_traceback: <FALSE> On an error, print PETSc's traceback instead of one line (None)\n"));
    PetscCall(AdhSolverSetUp(solver));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "----------------------------------------\nPETSc's options for every program (-log_view, -info, -options_file, -malloc_debug, the debugger, ...): adhbem -help petsc\n"));
    PetscFunctionReturn(0);
  }
  PetscCall(AdhSolverSetUp(solver));
  PetscCall(CheckUnprefixedOptions());
  /* -adh_view [ascii[:file]]: PETSc's viewer options, as -ksp_view's */
  PetscCall(PetscObjectViewFromOptions((PetscObject)solver, NULL, "-adh_view"));
  PetscCall(AdhSolverStickinessView(solver, NULL)); /* a rough surface's: before the path */
  PetscCall(AdhSolverSolvePath(solver));
  PetscCall(AdhSolverGetCurve(solver, &curve));
  {
    /* The words, one meaning each: the pull-off force is the largest tension the contact carried
       (-min F; the results file's pull_off_force), and only when the surfaces came apart (a leg
       ended by pull-off: nothing in contact after it, or force control's bisected pull-off). */
    PetscInt      ksp = 0, mults = 0, outer = 0, ffts = 0, touched = 0, Nx, Ny;
    AdhResolution r;
    char          words[512];
    const char   *outer_name, *inner_name;
    for (PetscInt k = 0; k < curve->n; k++) {
      const AdhState *st = &curve->state[k];
      touched += st->contact_points > 0;
      ksp += st->ksp_iterations;
      mults += st->compliance_applications;
      outer += st->outer_iterations;
      ffts += st->fft_pairs;
    }
    PetscCall(AdhSolverGetResolution(solver, &r));
    {
      AdhGrid grid;
      PetscCall(AdhSolverGetGrid(solver, &grid));
      PetscCall(AdhGridGetSizes(grid, &Nx, &Ny, NULL, NULL));
    }
    if (!touched) PetscCall(PetscSNPrintf(words, sizeof(words), "the surfaces never touched"));
    else PetscCall(PullOffWords(curve, Nx * Ny, &r, words, sizeof(words)));
    PetscCall(AdhSolverGetIterationNames(solver, &outer_name, &inner_name));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "adhbem: %" PetscInt_FMT " states; %s; %" PetscInt_FMT " %s, %" PetscInt_FMT " %s, %" PetscInt_FMT " compliance applications, %" PetscInt_FMT " FFT pairs\n", curve->n, words, outer, outer_name, ksp, inner_name, mults, ffts));
  }
  PetscCall(AdhSolverResolutionView(solver, NULL));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscErrorCode ierr;
  PetscBool      traceback = PETSC_FALSE;
  AdhSolver      solver = NULL;

  {
    int printed = PrintVersion(argc, argv);
    if (printed) return printed == 1 ? 0 : 1;
  }
  AvoidStaleLocks();
  if (CheckOptionsFiles(argc, argv)) return 1;
  {
    const int held = HoldBackHelp(&argc, argv);
    PetscCall(PetscInitialize(&argc, &argv, NULL, help));
    if (held) {
      PetscCall(PetscOptionsSetValue(NULL, "-help", NULL));
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s", help));
    }
  }
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-adh_traceback", &traceback, NULL));
  if (!traceback) PetscCall(PetscPushErrorHandler(ErrorOneLine, NULL));
  PetscCall(AdhUseOneBLASThread());
  /* creating the solver can fail too (the library finds another PETSc than it was built against) */
  ierr = AdhSolverCreate(PETSC_COMM_WORLD, &solver);
  if (!ierr) ierr = Run(solver);
  if (ierr && traceback) return (int)ierr;
  /* an error every rank saw ends the run cleanly; one that only some ranks saw must abort the others */
  if (ierr && !error_on_every_rank) MPI_Abort(PETSC_COMM_WORLD, 1);
  if (solver) PetscCall(AdhSolverDestroy(&solver));
  if (!traceback) PetscCall(PetscPopErrorHandler());
  PetscCall(PetscFinalize());
  return ierr ? 1 : 0;
}
