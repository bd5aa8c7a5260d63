/* Checkpoint and restart of a path (-adh_checkpoint FILE, -adh_checkpoint_every K, -adh_restart
   FILE): the whole state a step needs, through PETSc's HDF5 viewer.

   A checkpoint holds the contact set and the pressure (and the state of the types that keep one:
   force control's unit response of the set and the indentation of its equations), the position on the path (leg and step of
   the last recorded state), the curve so far, and the options that shape the problem, which a
   restart must repeat. It is written to FILE.part and renamed over FILE, so a crash while
   writing leaves the previous checkpoint whole. A restart continues the path after the recorded
   state; with deterministic FFT plans (-adh_fftw_planner estimate) on the same number of ranks
   the curve is the uninterrupted run's to the last bit, otherwise to rounding. */
#include <stdint.h>
#include "results/resultsimpl.h"

#define ADH_CHECKPOINT_VERSION 9 /* 4: crack-closure's radius; 5: attach rule, critical stress, pull-off tolerance, predictor; 6: the results file; 7: crack-closure's largest radius, and the set-update loop of 2026-11-25 (points that let go may come back); 8: the curve's contact_perimeter and cohesive_perimeter; 9: the elastic body (-adh_elastic) and its options (a checkpoint of version 8 is read as a half-space's) */

typedef struct {
  const char *option; /* what a restart must repeat, named as the user gives it */
  PetscDataType type;
  const void   *value;
  const void   *absent; /* the value of a checkpoint written before the option was checked (NULL: this run's) */
} Shape;

/* -adh_cascade_local was 0 (off) by default when checkpoints did not record it */
static const PetscReal AdhCascadeLocalBefore = 0.0;

/* The options that shape the problem, with this run's values. */
#define ADH_MAX_SHAPES (29 + ADH_NUM_KINDS * ADH_MAX_TYPE_SHAPES)
static PetscInt Shapes(AdhSolver s, Shape shape[ADH_MAX_SHAPES], PetscInt *Nx, PetscInt *Ny, PetscReal *Lx, PetscReal *Ly)
{
  PetscInt n = 0;
  *Nx = s->grid->Nx;
  *Ny = s->grid->Ny;
  *Lx = s->grid->Lx;
  *Ly = s->grid->Ly;
  shape[n++] = (Shape){"-adh_n (Nx)", PETSC_INT, Nx};
  shape[n++] = (Shape){"-adh_n (Ny)", PETSC_INT, Ny};
  shape[n++] = (Shape){"-adh_size (Lx)", PETSC_REAL, Lx};
  shape[n++] = (Shape){"-adh_size (Ly)", PETSC_REAL, Ly};
  shape[n++] = (Shape){"-adh_boundary", PETSC_STRING, AdhBoundaries[s->boundary]};
  shape[n++] = (Shape){"-adh_indenter", PETSC_STRING, AdhIndenterTypes[s->indenter.type]};
  shape[n++] = (Shape){"-adh_elastic", PETSC_STRING, s->elastic_type, ADHELASTICHALFSPACE};
  shape[n++] = (Shape){"-adh_E_star", PETSC_REAL, &s->Estar};
  shape[n++] = (Shape){"-adh_gamma", PETSC_REAL, &s->gamma};
  shape[n++] = (Shape){"-adh_control", PETSC_STRING, s->control_type};
  shape[n++] = (Shape){"-adh_criterion", PETSC_STRING, s->criterion_type};
  shape[n++] = (Shape){"-adh_attach", PETSC_STRING, AdhAttaches[s->attach]};
  shape[n++] = (Shape){"-adh_critical_stress", PETSC_REAL, &s->sigma_fixed};
  shape[n++] = (Shape){"-adh_start", PETSC_STRING, AdhStarts[s->start]};
  shape[n++] = (Shape){"-adh_steps", PETSC_INT, &s->steps};
  shape[n++] = (Shape){"-adh_cascade_rtol", PETSC_REAL, &s->cascade_rtol};
  shape[n++] = (Shape){"-adh_cascade_apart", PETSC_INT, &s->cascade_apart};
  shape[n++] = (Shape){"-adh_cascade_local", PETSC_REAL, &s->cascade_local, &AdhCascadeLocalBefore};
  if (s->cascade_local > 0) shape[n++] = (Shape){"-adh_cascade_local_rtol", PETSC_REAL, &s->cascade_local_rtol};
  /* the predictor's guess is certified, but where a state is not unique (rounding at a pressure of
     zero) it picks one: it runs only without adhesion */
  if (!(s->Sigma > 0 || s->Sigma_field)) shape[n++] = (Shape){"-adh_predictor", PETSC_STRING, s->predictor_type};
  /* the types' own (a layer's thickness, crack-closure's radii, force control's pull-off tolerance) */
  for (PetscInt k = 0; k < ADH_NUM_KINDS; k++) {
    AdhTypeOps      *ops[ADH_NUM_KINDS];
    AdhShapingOption typed[ADH_MAX_TYPE_SHAPES];
    PetscInt         m = 0;
    AdhSolverGetTypeOps_Private(s, ops, NULL, NULL);
    if (!ops[k]->shape) continue;
    PetscCallAbort(PETSC_COMM_SELF, ops[k]->shape(s, &m, typed));
    if (m > ADH_MAX_TYPE_SHAPES) PetscCallAbort(PETSC_COMM_SELF, PETSC_ERR_PLIB); /* a type's shape op wrote past ADH_MAX_TYPE_SHAPES */
    for (PetscInt j = 0; j < m; j++) shape[n++] = (Shape){typed[j].option, typed[j].type, typed[j].value, typed[j].absent};
  }
  return n;
}

/* The types' state (force control's unit response and the indentation of its equations), in the
   group /state. */
static PetscErrorCode TypesCheckpoint(AdhSolver s, PetscViewer v, PetscBool load)
{
  AdhTypeOps *types[ADH_NUM_KINDS];

  PetscFunctionBegin;
  AdhSolverGetTypeOps_Private(s, types, NULL, NULL);
  for (PetscInt k = 0; k < ADH_NUM_KINDS; k++)
    if (types[k]->checkpoint) PetscCall(types[k]->checkpoint(s, v, load));
  PetscFunctionReturn(0);
}

/* Fingerprints of the fields that shape the problem without an option of their own (a topography
   file or array, a rough surface's parameters, a work-of-adhesion field): their 1- and 2-norms. */
static PetscErrorCode Fingerprints(AdhSolver s, PetscReal f[4])
{
  PetscFunctionBegin;
  PetscCall(VecNorm(s->h, NORM_1, &f[0]));
  PetscCall(VecNorm(s->h, NORM_2, &f[1]));
  f[2] = f[3] = 0.0;
  if (s->gamma_field) {
    PetscCall(VecNorm(s->gamma_field, NORM_1, &f[2]));
    PetscCall(VecNorm(s->gamma_field, NORM_2, &f[3]));
  }
  PetscFunctionReturn(0);
}

/* A 1-D dataset of n values of the current group (written by rank 0) onto every rank. */
static PetscErrorCode ReadRealArray(AdhSolver s, PetscViewer v, const char name[], PetscInt n, PetscReal *values)
{
  PetscMPIInt        rank;
  Vec                col, all;
  VecScatter         toall;
  const PetscScalar *a;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(VecCreateMPI(s->comm, rank ? 0 : n, n, &col));
  PetscCall(PetscObjectSetName((PetscObject)col, name));
  PetscCall(VecLoad(col, v));
  PetscCall(VecScatterCreateToAll(col, &toall, &all));
  PetscCall(VecScatterBegin(toall, col, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(toall, col, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(all, &a));
  for (PetscInt k = 0; k < n; k++) values[k] = PetscRealPart(a[k]);
  PetscCall(VecRestoreArrayRead(all, &a));
  PetscCall(VecScatterDestroy(&toall));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&col));
  PetscFunctionReturn(0);
}

/* The curve of n states (written by AdhOutputWriteCurve_Private) from the current group. */
static PetscErrorCode ReadCurve(AdhSolver s, PetscViewer v, PetscInt n)
{
  PetscReal *column;

  PetscFunctionBegin;
  PetscCall(AdhCurveDestroy_Private(&s->curve));
  for (PetscInt k = 0; k < n; k++) {
    AdhState st;
    PetscCall(PetscMemzero(&st, sizeof(st)));
    PetscCall(AdhCurveAppend_Private(&s->curve, &st));
  }
  PetscCall(PetscMalloc1(n + 1, &column));
  for (PetscInt j = 0; j < AdhCurveNumColumns; j++) {
    PetscCall(ReadRealArray(s, v, AdhCurveColumns[j].name, n, column));
    for (PetscInt k = 0; k < n; k++) AdhStateSetValue(&s->curve.state[k], j, column[k]);
  }
  PetscCall(PetscFree(column));
  PetscFunctionReturn(0);
}

/* The contact set as a grid Vec (1 in the set), for the viewer. */
static PetscErrorCode MaskVec(AdhSolver s, Vec *mask)
{
  PetscScalar *m;

  PetscFunctionBegin;
  PetscCall(VecDuplicate(s->p, mask));
  PetscCall(PetscObjectSetName((PetscObject)*mask, "contact"));
  PetscCall(VecGetArrayWrite(*mask, &m));
  for (PetscInt k = 0; k < s->nlocal; k++) m[k] = s->in_set[k] ? 1.0 : 0.0;
  PetscCall(VecRestoreArrayWrite(*mask, &m));
  PetscFunctionReturn(0);
}

/* A 64-bit checksum of what a restart takes from a checkpoint: the pressure, the contact set and
   the curve so far. HDF5 checks its own metadata but not the data, so bytes damaged inside a
   dataset would restart a wrong state without a word. Each value is mixed with its position and
   the mixes are summed (modulo 2^64), so any number of ranks, any partition, gives the same. */
static uint64_t Mix(uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

static uint64_t MixValue(uint64_t where, PetscReal value)
{
  double   x = (double)value;
  uint64_t bits;

  memcpy(&bits, &x, sizeof(bits));
  return Mix(Mix(where) ^ bits);
}

static PetscErrorCode Checksum(AdhSolver s, Vec p, Vec mask, char hex[17])
{
  const PetscScalar *a, *m;
  PetscInt           lo, n;
  uint64_t           mine = 0, all = 0;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(p, &lo, NULL));
  PetscCall(VecGetLocalSize(p, &n));
  PetscCall(VecGetArrayRead(p, &a));
  PetscCall(VecGetArrayRead(mask, &m));
  for (PetscInt k = 0; k < n; k++) mine += MixValue(4 * (uint64_t)(lo + k), PetscRealPart(a[k])) + MixValue(4 * (uint64_t)(lo + k) + 1, PetscRealPart(m[k]));
  PetscCall(VecRestoreArrayRead(mask, &m));
  PetscCall(VecRestoreArrayRead(p, &a));
  if (!lo) /* the curve, which every rank holds, once */
    for (PetscInt k = 0; k < s->curve.n; k++)
      for (PetscInt j = 0; j < AdhCurveNumColumns; j++) mine += MixValue(4 * ((uint64_t)k * AdhCurveNumColumns + (uint64_t)j) + 2, AdhStateValue(&s->curve.state[k], j));
  PetscCallMPI(MPI_Allreduce(&mine, &all, 1, MPI_UINT64_T, MPI_SUM, s->comm));
  PetscCall(PetscSNPrintf(hex, 17, "%016llx", (unsigned long long)all));
  PetscFunctionReturn(0);
}

/* The checkpoint's contents into the open viewer v. */
static PetscErrorCode WriteOpen(AdhSolver s, PetscViewer v, PetscInt leg, PetscInt step)
{
  Vec       mask;
  Shape     shape[ADH_MAX_SHAPES];
  PetscInt  n, Nx, Ny, version = ADH_CHECKPOINT_VERSION, npath = s->npath, pulled = s->pulled_off;
  PetscReal Lx, Ly;

  PetscFunctionBegin;
  n = Shapes(s, shape, &Nx, &Ny, &Lx, &Ly);
  for (PetscInt k = 0; k < n; k++) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", shape[k].option, shape[k].type, shape[k].value));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "version", PETSC_INT, &version));
  {
    PetscReal f[4];
    PetscCall(Fingerprints(s, f));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "profile_norm1", PETSC_REAL, &f[0]));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "profile_norm2", PETSC_REAL, &f[1]));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "gamma_field_norm1", PETSC_REAL, &f[2]));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "gamma_field_norm2", PETSC_REAL, &f[3]));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "leg", PETSC_INT, &leg));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "step", PETSC_INT, &step));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "states", PETSC_INT, &s->curve.n));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "npath", PETSC_INT, &npath));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "d", PETSC_REAL, &s->d));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "pulled_off", PETSC_INT, &pulled));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "joined_previous", PETSC_INT, &s->joined_previous));
  /* where this run's results go (absolute): a restart goes on in that file */
  if (s->output[0]) {
    char full[PETSC_MAX_PATH_LEN];
    PetscCall(PetscGetFullPath(s->output, full, sizeof(full)));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "output", PETSC_STRING, full));
  }
  PetscCall(PetscViewerHDF5PushGroup(v, "/state"));
  PetscCall(VecView(s->p, v));
  PetscCall(MaskVec(s, &mask));
  PetscCall(VecView(mask, v));
  {
    char hex[17];
    PetscCall(Checksum(s, s->p, mask, hex));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "checksum", PETSC_STRING, hex));
  }
  PetscCall(VecDestroy(&mask));
  PetscCall(TypesCheckpoint(s, v, PETSC_FALSE));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerHDF5PushGroup(v, "/curve"));
  PetscCall(AdhOutputWriteCurve_Private(s, v));
  PetscCall(PetscViewerHDF5PopGroup(v));
  { /* a failure to write what HDF5 holds comes here, not in the close (after which HDF5 cannot recover) */
    hid_t file_id;
    PetscCall(PetscViewerHDF5GetFileId(v, &file_id));
    ADH_H5(H5Fflush(file_id, H5F_SCOPE_GLOBAL));
  }
  PetscFunctionReturn(0);
}

/* The state after the recorded state at (leg, step) of the path, into s->checkpoint: written to
   FILE.part and renamed over FILE. On a full disk or a failed write FILE.part is removed and the
   previous checkpoint stays as it was, whole. */
PetscErrorCode AdhCheckpointWrite_Private(AdhSolver s, PetscInt leg, PetscInt step)
{
  const size_t   n = (size_t)s->grid->Nx * (size_t)s->grid->Ny;
  char           part[PETSC_MAX_PATH_LEN + 8], kept[PETSC_MAX_PATH_LEN + 64];
  PetscViewer    v;
  PetscErrorCode ierr = 0;
  PetscMPIInt    rank;
  int            ok = 1, err;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(PetscSNPrintf(part, sizeof(part), "%s.part", s->checkpoint));
  if (s->checkpoint_state >= 0) PetscCall(PetscSNPrintf(kept, sizeof(kept), "the checkpoint %s of state %" PetscInt_FMT " is kept, whole", s->checkpoint, s->checkpoint_state));
  else PetscCall(PetscSNPrintf(kept, sizeof(kept), "no checkpoint was written before"));
  PetscCall(PetscViewerHDF5Open(s->comm, part, FILE_MODE_WRITE, &v));
  /* the pressure, the contact set and a type's vector (force control's unit response) */
  PetscCall(AdhOutputReserve_Private(s, part, 3 * 8 * n, &err));
  if (!err) {
    PetscCall(AdhOutputWriteBegin_Private(s, "-adh_checkpoint", part, kept, PETSC_TRUE));
    ierr = WriteOpen(s, v, leg, step);
    ierr = AdhH5Agree_Private(s, ierr); /* a rank's failure is every rank's before the collective close */
    if (!ierr) {
      ierr = PetscViewerDestroy(&v);
      if (ierr) v = NULL; /* half-destroyed: not to be closed again */
    }
    ierr = AdhOutputWriteEnd_Private(s, ierr);
  }
  PetscCall(AdhOutputAbandon_Private(&v)); /* after a failure: not a write more (its FILE.part is removed) */
  if (err || ierr) PetscCall(AdhOutputRemove_Private(s, part));
  PetscCheck(!err, s->comm, PETSC_ERR_FILE_WRITE, "-adh_checkpoint: cannot write %s: %s; %s", part, strerror(err), kept);
  PetscCall(ierr);
  PetscCall(AdhOutputReleaseReserve_Private(s, part));
  if (!rank) ok = rename(part, s->checkpoint) == 0;
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_WRITE, "-adh_checkpoint: could not move %s to %s", part, s->checkpoint);
  s->checkpoint_state = s->curve.n - 1;
  PetscFunctionReturn(0);
}

/* Refuse a checkpoint whose problem differs from this run's, naming the option. */
static PetscErrorCode CheckShape(AdhSolver s, PetscViewer v)
{
  Shape     shape[ADH_MAX_SHAPES];
  PetscInt  n, Nx, Ny, version = 0;
  PetscReal Lx, Ly;

  PetscFunctionBegin;
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "version", PETSC_INT, NULL, &version));
  /* an older checkpoint came from another set-update loop or criterion: its curve would not go on as
     it began; version 8 holds the same state, of a half-space (its -adh_elastic absent), and goes on */
  PetscCheck(version == ADH_CHECKPOINT_VERSION || version == 8, s->comm, PETSC_ERR_FILE_UNEXPECTED, "-adh_restart %s: not an adhbem checkpoint of version %d (it has version %" PetscInt_FMT "; a checkpoint of an older adhbem cannot be continued: run the path again)", s->restart, ADH_CHECKPOINT_VERSION, version);
  n = Shapes(s, shape, &Nx, &Ny, &Lx, &Ly);
  for (PetscInt k = 0; k < n; k++) {
    PetscBool same = PETSC_FALSE;
    if (shape[k].type == PETSC_STRING) {
      char     *saved = NULL;
      char      text[64];
      PetscBool has;
      /* absent (a checkpoint written before the option existed): the value such checkpoints had */
      PetscCall(PetscViewerHDF5HasAttribute(v, "/", shape[k].option, &has));
      if (has) PetscCall(PetscViewerHDF5ReadAttribute(v, "/", shape[k].option, PETSC_STRING, NULL, &saved));
      else PetscCall(PetscStrallocpy(shape[k].absent ? (const char *)shape[k].absent : (const char *)shape[k].value, &saved));
      PetscCall(PetscStrcmp(saved, (const char *)shape[k].value, &same));
      PetscCall(PetscStrncpy(text, saved, sizeof(text)));
      PetscCall(PetscFree(saved));
      PetscCheck(same, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_restart %s: the checkpoint has %s %s, this run %s", s->restart, shape[k].option, text, (const char *)shape[k].value);
    } else if (shape[k].type == PETSC_INT) {
      PetscInt saved = 0;
      /* absent (a checkpoint written before the option was checked): the value such checkpoints had
         (Shape.absent), else taken as this run's; the same for reals below */
      PetscCall(PetscViewerHDF5ReadAttribute(v, "/", shape[k].option, PETSC_INT, shape[k].absent ? shape[k].absent : shape[k].value, &saved));
      PetscCheck(saved == *(const PetscInt *)shape[k].value, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_restart %s: the checkpoint has %s %" PetscInt_FMT ", this run %" PetscInt_FMT, s->restart, shape[k].option, saved, *(const PetscInt *)shape[k].value);
    } else {
      PetscReal saved = 0;
      PetscCall(PetscViewerHDF5ReadAttribute(v, "/", shape[k].option, PETSC_REAL, shape[k].absent ? shape[k].absent : shape[k].value, &saved));
      PetscCheck(saved == *(const PetscReal *)shape[k].value, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_restart %s: the checkpoint has %s %.17g, this run %.17g", s->restart, shape[k].option, (double)saved, (double)*(const PetscReal *)shape[k].value);
    }
  }
  {
    /* norms summed in another order on another number of ranks: equal to rounding */
    const char *names[4] = {"profile_norm1", "profile_norm2", "gamma_field_norm1", "gamma_field_norm2"};
    PetscReal   f[4], saved;
    PetscCall(Fingerprints(s, f));
    for (PetscInt k = 0; k < 4; k++) {
      PetscCall(PetscViewerHDF5ReadAttribute(v, "/", names[k], PETSC_REAL, NULL, &saved));
      PetscCheck(PetscAbsReal(saved - f[k]) <= 1e-12 * PetscMax(PetscAbsReal(saved), PetscAbsReal(f[k])), s->comm, PETSC_ERR_ARG_INCOMP, "-adh_restart %s: the checkpoint's %s differs from this run's (%s: another topography, rough surface (-adh_seed, -adh_hurst, ...) or indenter parameter)", s->restart, k < 2 ? "indenter profile" : "work-of-adhesion field", k < 2 ? "-adh_indenter" : "-adh_gamma_field");
    }
  }
  PetscFunctionReturn(0);
}

/* The checkpoint's state from the open viewer v, after checking that it fits this run. */
static PetscErrorCode ReadOpen(AdhSolver s, PetscViewer v, PetscInt *leg, PetscInt *step)
{
  Vec                mask;
  const PetscScalar *m;
  PetscReal         *path;
  PetscInt           states = 0, npath = 0, pulled = 0, k;

  PetscFunctionBegin;
  PetscCall(CheckShape(s, v));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "npath", PETSC_INT, NULL, &npath));
  PetscCheck(npath == s->npath, s->comm, PETSC_ERR_ARG_INCOMP, "-adh_restart %s: the checkpoint's -adh_path has %" PetscInt_FMT " points, this run's %" PetscInt_FMT, s->restart, npath, s->npath);
  PetscCall(PetscMalloc1(npath, &path));
  PetscCall(PetscViewerHDF5PushGroup(v, "/curve"));
  PetscCall(ReadRealArray(s, v, "path", npath, path));
  PetscCall(PetscViewerHDF5PopGroup(v));
  for (k = 0; k < npath && path[k] == s->path[k]; k++) continue;
  if (k < npath) {
    const double saved = (double)path[k];
    PetscCall(PetscFree(path));
    SETERRQ(s->comm, PETSC_ERR_ARG_INCOMP, "-adh_restart %s: the checkpoint's -adh_path point %" PetscInt_FMT " is %.17g, this run's %.17g", s->restart, k, saved, (double)s->path[k]);
  }
  PetscCall(PetscFree(path));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "leg", PETSC_INT, NULL, leg));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "step", PETSC_INT, NULL, step));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "states", PETSC_INT, NULL, &states));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "d", PETSC_REAL, NULL, &s->d));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "pulled_off", PETSC_INT, NULL, &pulled));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "joined_previous", PETSC_INT, NULL, &s->joined_previous));
  s->pulled_off        = (PetscBool)(pulled != 0);
  s->restart_output[0] = 0;
  {
    PetscBool has;
    PetscCall(PetscViewerHDF5HasAttribute(v, "/", "output", &has));
    if (has) {
      char *output = NULL;
      PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "output", PETSC_STRING, NULL, &output));
      PetscCall(PetscStrncpy(s->restart_output, output, sizeof(s->restart_output)));
      PetscCall(PetscFree(output));
    }
  }
  PetscCall(PetscViewerHDF5PushGroup(v, "/state"));
  PetscCall(VecLoad(s->p, v));
  PetscCall(VecDuplicate(s->p, &mask));
  PetscCall(PetscObjectSetName((PetscObject)mask, "contact"));
  PetscCall(VecLoad(mask, v));
  PetscCall(VecGetArrayRead(mask, &m));
  for (k = 0; k < s->nlocal; k++) s->in_set[k] = PetscRealPart(m[k]) > 0.5;
  PetscCall(VecRestoreArrayRead(mask, &m));
  PetscCall(TypesCheckpoint(s, v, PETSC_TRUE));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscViewerHDF5PushGroup(v, "/curve"));
  PetscCall(ReadCurve(s, v, states));
  PetscCall(PetscViewerHDF5PopGroup(v));
  { /* checkpoints before the checksum have none: taken as they are */
    PetscBool has;
    char      hex[17], *saved = NULL;
    PetscCall(PetscViewerHDF5HasAttribute(v, "/", "checksum", &has));
    if (has) {
      PetscBool same;
      PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "checksum", PETSC_STRING, NULL, &saved));
      PetscCall(Checksum(s, s->p, mask, hex));
      PetscCall(PetscStrcmp(hex, saved, &same));
      PetscCall(PetscFree(saved));
      if (!same) PetscCall(VecDestroy(&mask));
      PetscCheck(same, s->comm, PETSC_ERR_FILE_UNEXPECTED, "-adh_restart %s: the state it holds does not match its checksum (the file is damaged): restart from another checkpoint or run the path again", s->restart);
    }
  }
  PetscCall(VecDestroy(&mask));
  PetscFunctionReturn(0);
}

/* The state of s->restart: the contact set, pressure and position; the curve so far. */
PetscErrorCode AdhCheckpointRead_Private(AdhSolver s, PetscInt *leg, PetscInt *step)
{
  PetscViewer    v;
  PetscBool      exists;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(PetscTestFile(s->restart, 'r', &exists));
  PetscCheck(exists, s->comm, PETSC_ERR_FILE_OPEN, "-adh_restart: cannot read %s", s->restart);
  /* a truncated or foreign file fails in HDF5: say which option and file */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = PetscViewerHDF5Open(s->comm, s->restart, FILE_MODE_READ, &v);
  PetscCall(PetscPopErrorHandler());
  PetscCheck(!ierr, s->comm, PETSC_ERR_FILE_READ, "-adh_restart %s: not a readable HDF5 file (truncated or corrupted?)", s->restart);
  PetscCall(PetscViewerHDF5HasAttribute(v, "/", "version", &exists));
  if (!exists) PetscCall(PetscViewerDestroy(&v));
  PetscCheck(exists, s->comm, PETSC_ERR_FILE_UNEXPECTED, "-adh_restart %s: not an adhbem checkpoint (written by -adh_checkpoint)", s->restart);
  ierr = ReadOpen(s, v, leg, step);
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(ierr);
  s->adhesive = PETSC_TRUE;
  PetscCall(AdhSolverRebuildSet_Private(s));
  PetscFunctionReturn(0);
}
