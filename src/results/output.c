/* Results: HDF5 through PETSc's viewer (curve in /curve, parameters as root attributes, fields
   in /fields) and the curve as CSV. Both are written to FILE.part as the path goes, and renamed
   when the run ends, so a finished result file is never half-written and an older one is not
   lost to a failed run. After each recorded state its curve row and its fields are appended to
   FILE.h5.part and the file is flushed, and rank 0 appends the row to FILE.csv.part (the journal)
   and syncs it: whatever kills the job, both hold every state recorded before (adhbem.load reads
   them). A restart appends to the results of the run it goes on from. */
#include <errno.h>
#include <sys/stat.h>
#include <unistd.h>
#include "results/resultsimpl.h"

static PetscErrorCode PartName(const char file[], char part[], size_t len)
{
  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(part, len, "%s.part", file));
  PetscFunctionReturn(0);
}

/* FILE.h5 -> FILE.ext (csv, xmf); other names get .ext appended. */
static PetscErrorCode SiblingName(const char file[], const char ext[], char name[], size_t len)
{
  size_t n;

  PetscFunctionBegin;
  PetscCall(PetscStrlen(file, &n));
  if (n > 3 && !strcmp(file + n - 3, ".h5")) {
    PetscCall(PetscSNPrintf(name, len, "%.*s.%s", (int)(n - 3), file, ext));
  } else PetscCall(PetscSNPrintf(name, len, "%s.%s", file, ext));
  PetscFunctionReturn(0);
}

/* Rank 0 makes the file's directory when it is missing (results/ in a fresh clone) and tries to
   create FILE.part (or checks that an existing one is writable); everyone learns the answer, so a
   bad path fails before any work with a message that names the option and the file. */
PetscErrorCode AdhOutputCheckWritable_Private(AdhSolver s, const char option[], const char file[])
{
  char        part[PETSC_MAX_PATH_LEN + 8], dir[PETSC_MAX_PATH_LEN], reason[256] = "";
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(PartName(file, part, sizeof(part)));
  if (!rank) {
    FILE       *fp;
    char       *slash;
    PetscBool   exists = PETSC_TRUE;
    struct stat st;
    size_t      len;
    PetscCall(PetscStrlen(file, &len));
    if ((len && file[len - 1] == '/') || (!stat(file, &st) && S_ISDIR(st.st_mode))) {
      /* else the run would fail only at its end, renaming its results onto the directory */
      ok = 0;
      PetscCall(PetscStrncpy(reason, "it is a directory; give a file name (DIR/run.h5)", sizeof(reason)));
    } else {
      PetscCall(PetscStrncpy(dir, file, sizeof(dir)));
      slash = strrchr(dir, '/');
      if (slash && slash != dir) {
        *slash = 0;
        PetscCall(PetscTestDirectory(dir, 'w', &exists));
        if (!exists) (void)PetscMkdir(dir); /* a failure shows in the fopen below */
      }
      if (!access(part, F_OK)) { /* a killed run's results, which a restart goes on in: left as they are */
        ok = !access(part, W_OK);
        if (!ok) PetscCall(PetscStrncpy(reason, strerror(errno), sizeof(reason)));
      } else if (!(fp = fopen(part, "w"))) {
        ok = 0;
        PetscCall(PetscStrncpy(reason, strerror(errno), sizeof(reason)));
      } else {
        fclose(fp);
        remove(part);
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCallMPI(MPI_Bcast(reason, sizeof(reason), MPI_CHAR, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_OPEN, "%s: cannot write %s: %s", option, file, reason);
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteSurface(AdhSolver, PetscViewer);
static PetscErrorCode WriteArrayTopography(AdhSolver, PetscViewer);
static PetscErrorCode Begin(AdhSolver, PetscViewer, const char[]);

PetscErrorCode AdhOutputOpen_Private(AdhSolver s, const char file[], PetscViewer *viewer)
{
  char part[PETSC_MAX_PATH_LEN + 8];

  PetscFunctionBegin;
  PetscCall(AdhOutputCheckWritable_Private(s, "-adh_output", file));
  PetscCall(PartName(file, part, sizeof(part)));
  PetscCall(PetscViewerHDF5Open(s->comm, part, FILE_MODE_WRITE, viewer));
  PetscCall(PetscFree(s->field_states));
  s->nfield_states = 0;
  /* a rough surface, generated again, goes in now, while the contact set and its solver's vectors
     are small (at the close they may be the largest of the run) */
  if (s->indenter.type == ADH_INDENTER_ROUGH) PetscCall(WriteSurface(s, *viewer));
  if (s->indenter.type == ADH_INDENTER_ARRAY) PetscCall(WriteArrayTopography(s, *viewer));
  PetscCall(Begin(s, *viewer, file));
  PetscFunctionReturn(0);
}


/* An HDF5 call that fails (a negative return) becomes a PETSc error naming it. */
#define ADH_H5(call) \
  do { \
    PetscCheck((call) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5: %s failed", #call); \
  } while (0)

/* Dataset `name` of group, extendible along its first dimension: created with dims (and chunk) when
   missing, else opened and given the extent dims (which may also shorten it). */
static PetscErrorCode OpenExtendible(hid_t group, const char name[], hid_t type, int rank, const hsize_t dims[], const hsize_t chunk[], hid_t *dset)
{
  PetscFunctionBegin;
  if (H5Lexists(group, name, H5P_DEFAULT) <= 0) {
    hsize_t maxdims[3];
    hid_t   filespace, plist;
    for (int k = 0; k < rank; k++) maxdims[k] = k ? dims[k] : H5S_UNLIMITED;
    ADH_H5(filespace = H5Screate_simple(rank, dims, maxdims));
    ADH_H5(plist = H5Pcreate(H5P_DATASET_CREATE));
    ADH_H5(H5Pset_chunk(plist, rank, chunk));
    ADH_H5(*dset = H5Dcreate2(group, name, type, filespace, H5P_DEFAULT, plist, H5P_DEFAULT));
    ADH_H5(H5Pclose(plist));
    ADH_H5(H5Sclose(filespace));
  } else {
    ADH_H5(*dset = H5Dopen2(group, name, H5P_DEFAULT));
    ADH_H5(H5Dset_extent(*dset, dims));
  }
  PetscFunctionReturn(0);
}

/* count (a block of rank dimensions) values of buf into dataset dset at offset. */
static PetscErrorCode WriteBlock(hid_t dset, hid_t type, int rank, const hsize_t offset[], const hsize_t count[], const void *buf)
{
  hid_t filespace, memspace;

  PetscFunctionBegin;
  ADH_H5(filespace = H5Dget_space(dset));
  ADH_H5(memspace = H5Screate_simple(rank, count, NULL));
  ADH_H5(H5Sselect_hyperslab(filespace, H5S_SELECT_SET, offset, NULL, count, NULL));
  ADH_H5(H5Dwrite(dset, type, memspace, filespace, H5P_DEFAULT, buf));
  ADH_H5(H5Sclose(memspace));
  ADH_H5(H5Sclose(filespace));
  PetscFunctionReturn(0);
}

/* A root attribute of text as a variable-length UTF-8 string: h5py reads it as str (PETSc's
   attributes are fixed-length ASCII, which h5py gives as bytes). Replaces one of that name. */
static PetscErrorCode WriteStringAttribute(PetscViewer v, const char name[], const char value[])
{
  hid_t file_id, type, space, attr;

  PetscFunctionBegin;
  PetscCall(PetscViewerHDF5GetFileId(v, &file_id));
  if (H5Aexists_by_name(file_id, "/", name, H5P_DEFAULT) > 0) ADH_H5(H5Adelete_by_name(file_id, "/", name, H5P_DEFAULT));
  ADH_H5(type = H5Tcopy(H5T_C_S1));
  ADH_H5(H5Tset_size(type, H5T_VARIABLE));
  ADH_H5(H5Tset_cset(type, H5T_CSET_UTF8));
  ADH_H5(space = H5Screate(H5S_SCALAR));
  ADH_H5(attr = H5Acreate_by_name(file_id, "/", name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  ADH_H5(H5Awrite(attr, type, &value));
  ADH_H5(H5Aclose(attr));
  ADH_H5(H5Sclose(space));
  ADH_H5(H5Tclose(type));
  PetscFunctionReturn(0);
}

/* A root attribute holding n reals (the path). Replaces one of that name. */
static PetscErrorCode WriteRealArrayAttribute(PetscViewer v, const char name[], PetscInt n, const PetscReal *values)
{
  hid_t   file_id, space, attr;
  hsize_t dims[1] = {(hsize_t)n};
  double *buf;

  PetscFunctionBegin;
  PetscCall(PetscViewerHDF5GetFileId(v, &file_id));
  if (H5Aexists_by_name(file_id, "/", name, H5P_DEFAULT) > 0) ADH_H5(H5Adelete_by_name(file_id, "/", name, H5P_DEFAULT));
  PetscCall(PetscMalloc1(n + 1, &buf));
  for (PetscInt k = 0; k < n; k++) buf[k] = (double)values[k];
  ADH_H5(space = H5Screate_simple(1, dims, NULL));
  ADH_H5(attr = H5Acreate_by_name(file_id, "/", name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  ADH_H5(H5Awrite(attr, H5T_NATIVE_DOUBLE, buf));
  ADH_H5(H5Aclose(attr));
  ADH_H5(H5Sclose(space));
  PetscCall(PetscFree(buf));
  PetscFunctionReturn(0);
}

/* Rows [from, from + count) of the 1-D dataset `name` of group, float64 or (integer) int64
   (created extendible when missing; its extent becomes from + count, which may also shorten it),
   written by rank 0 from values. Collective. */
static PetscErrorCode AppendRows(AdhSolver s, hid_t group, const char name[], PetscBool integer, PetscInt from, PetscInt count, const PetscReal *values)
{
  hid_t       dset, type = integer ? H5T_NATIVE_LLONG : H5T_NATIVE_DOUBLE;
  hsize_t     dims[1] = {(hsize_t)(from + count)}, chunk[1] = {256}, offset[1] = {(hsize_t)from}, n[1] = {(hsize_t)count};
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(OpenExtendible(group, name, type, 1, dims, chunk, &dset));
  if (!rank && count > 0) {
    if (integer) {
      long long *buf;
      PetscCall(PetscMalloc1(count, &buf));
      for (PetscInt k = 0; k < count; k++) buf[k] = (long long)values[k];
      PetscCall(WriteBlock(dset, type, 1, offset, n, buf));
      PetscCall(PetscFree(buf));
    } else {
      double *buf;
      PetscCall(PetscMalloc1(count, &buf));
      for (PetscInt k = 0; k < count; k++) buf[k] = (double)values[k];
      PetscCall(WriteBlock(dset, type, 1, offset, n, buf));
      PetscCall(PetscFree(buf));
    }
  }
  ADH_H5(H5Dclose(dset));
  PetscFunctionReturn(0);
}

/* The contact mask of the current state as frame `frame` of the uint8 dataset contact
   (frames, Ny, Nx) of the viewer's current group: a byte per point where VecView would write 8.
   Each rank writes its rows; the dataset grows by one frame per call. */
static PetscErrorCode WriteContactMask(AdhSolver s, PetscViewer viewer, PetscInt frame)
{
  const AdhGrid  g = s->grid;
  hid_t          file_id, group, dset;
  hsize_t        dims[3], chunk[3], offset[3], count[3];
  PetscInt       ys, ym;
  unsigned char *mask;

  PetscFunctionBegin;
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  dims[0] = (hsize_t)frame + 1;
  dims[1] = (hsize_t)g->Ny;
  dims[2] = (hsize_t)g->Nx;
  /* one frame per chunk, at most 1 GB (HDF5 chunks must stay below 4 GB) */
  chunk[0] = 1;
  chunk[1] = (hsize_t)PetscMax(1, PetscMin(g->Ny, (PetscInt)(1073741824 / g->Nx)));
  chunk[2] = (hsize_t)g->Nx;
  PetscCall(PetscViewerHDF5OpenGroup(viewer, NULL, &file_id, &group));
  PetscCall(OpenExtendible(group, AdhFieldNames[3], H5T_NATIVE_UCHAR, 3, dims, chunk, &dset));
  offset[0] = (hsize_t)frame;
  offset[1] = (hsize_t)ys;
  offset[2] = 0;
  count[0]  = 1;
  count[1]  = (hsize_t)ym;
  count[2]  = (hsize_t)g->Nx;
  PetscCall(PetscMalloc1(s->nlocal + 1, &mask));
  for (PetscInt k = 0; k < s->nlocal; k++) mask[k] = s->in_set[k] ? 1 : 0;
  PetscCall(WriteBlock(dset, H5T_NATIVE_UCHAR, 3, offset, count, mask));
  PetscCall(PetscFree(mask));
  ADH_H5(H5Dclose(dset));
  ADH_H5(H5Gclose(group));
  PetscFunctionReturn(0);
}

/* The fields chosen by -adh_fields of the current state, curve row `state`, as the next frame of
   /fields (HDF5 timestepping); the first frame also holds the profile h and the critical stress.
   /fields/state, which maps frames to curve rows, grows with them. */
PetscErrorCode AdhOutputWriteFields_Private(AdhSolver s, PetscViewer viewer, PetscInt state)
{
  const PetscInt frame = s->nfield_states;
  Vec            u;

  PetscFunctionBegin;
  if (!s->fields) PetscFunctionReturn(0);
  PetscCall(PetscRealloc((frame + 1) * sizeof(PetscInt), &s->field_states));
  s->field_states[s->nfield_states++] = state;
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/fields"));
  if (frame == 0) {
    const PetscBool made = (PetscBool)(!s->Sigma_field && !s->Sigma_view);
    Vec             Sigma;
    PetscCall(VecView(s->h, viewer));
    PetscCall(AdhSolverGetCriticalStressVec_Private(s, &Sigma));
    PetscCall(VecView(Sigma, viewer));
    if (made) PetscCall(VecDestroy(&s->Sigma_view)); /* made only for this: not kept */
  }
  PetscCall(PetscViewerHDF5PushTimestepping(viewer));
  PetscCall(PetscViewerHDF5SetTimestep(viewer, frame));
  if (s->fields & ADH_FIELD_PRESSURE) PetscCall(VecView(s->p, viewer));
  if (s->fields & ADH_FIELD_DISPLACEMENT) {
    PetscCall(AdhSolverGetDisplacement_Private(s, &u));
    PetscCall(VecView(u, viewer));
  }
  if (s->fields & ADH_FIELD_GAP) PetscCall(VecView(s->g, viewer));
  PetscCall(PetscViewerHDF5PopTimestepping(viewer));
  if (s->fields & ADH_FIELD_CONTACT) PetscCall(WriteContactMask(s, viewer, frame));
  {
    const PetscReal row = (PetscReal)state;
    hid_t           file_id, group;
    PetscCall(PetscViewerHDF5OpenGroup(viewer, NULL, &file_id, &group));
    PetscCall(AppendRows(s, group, "state", PETSC_TRUE, frame, 1, &row));
    ADH_H5(H5Gclose(group));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(0);
}

/* A 1-D dataset held by rank 0. */
static PetscErrorCode WriteRealArray(AdhSolver s, PetscViewer viewer, const char name[], PetscInt n, const PetscReal *values)
{
  PetscMPIInt  rank;
  Vec          v;
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(VecCreateMPI(s->comm, rank ? 0 : n, n, &v));
  PetscCall(PetscObjectSetName((PetscObject)v, name));
  PetscCall(VecGetArrayWrite(v, &a));
  if (!rank)
    for (PetscInt k = 0; k < n; k++) a[k] = values[k];
  PetscCall(VecRestoreArrayWrite(v, &a));
  PetscCall(VecView(v, viewer));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}

/* A rough indenter's parameters and realised statistics as root attributes, and its heights z
   (h = max z - z) as the dataset /topography, which -adh_indenter file reads back. */
static PetscErrorCode WriteSurface(AdhSolver s, PetscViewer v)
{
  AdhSurface *sf = &s->indenter.surface;

  PetscFunctionBegin;
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "hurst", PETSC_REAL, &sf->hurst));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "rolloff_wavelength", PETSC_REAL, &sf->used_rolloff_wavelength));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cutoff_wavelength", PETSC_REAL, &sf->used_cutoff_wavelength));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "seed", PETSC_INT, &sf->seed));
  if (sf->rms_height > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "rms_height", PETSC_REAL, &sf->rms_height));
  else PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "rms_slope", PETSC_REAL, &sf->realised_rms_slope));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "realised_rms_height", PETSC_REAL, &sf->realised_rms_height));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "realised_rms_slope", PETSC_REAL, &sf->realised_rms_slope));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "max_height", PETSC_REAL, &sf->max_height));
  /* generated again rather than kept through the run: the same bits, one FFT, no grid vector */
  PetscCall(AdhSurfaceWriteHeights(s->grid, sf, v, "topography"));
  PetscFunctionReturn(0);
}

/* An array indenter's profile as the user gave it (heights z or the gap h, as the attribute
   topography_kind says) as the dataset /topography, so that -adh_topography FILE
   -adh_topography_dataset topography gives the same profile back. The user's Vec lends its values
   under that name. */
static PetscErrorCode WriteArrayTopography(AdhSolver s, PetscViewer v)
{
  PetscObject z = (PetscObject)s->indenter.z;
  const char *name;
  char        own[256];

  PetscFunctionBegin;
  PetscCall(PetscObjectGetName(z, &name));
  PetscCall(PetscStrncpy(own, name, sizeof(own)));
  PetscCall(PetscObjectSetName(z, "topography"));
  {
    PetscErrorCode ierr = VecView((Vec)z, v);
    PetscCall(PetscObjectSetName(z, own)); /* the user's name back, also when the view failed */
    PetscCall(ierr);
  }
  PetscFunctionReturn(0);
}

/* The pull-off force (the largest tension carried, -min F; 0: none) of curve row k, and how well
   the grid resolves it (the curve's statistics at that state; absent without tension). */
static PetscErrorCode WritePullOff(AdhSolver s, PetscViewer v, PetscInt k)
{
  const char *const resolution[] = {"pull_off_small_patch_tension", "pull_off_smallest_tensile_patch", "adhesion_resolved"};
  PetscReal         pull_off     = k >= 0 ? -s->curve.state[k].force : 0.0;

  PetscFunctionBegin;
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "pull_off_force", PETSC_REAL, &pull_off));
  if (k >= 0) {
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", resolution[0], PETSC_REAL, &s->curve.state[k].small_patch_tension));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", resolution[1], PETSC_INT, &s->curve.state[k].smallest_tensile_patch));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", resolution[2], PETSC_BOOL, &(PetscBool){AdhSolverResolves_Private(s, &s->curve.state[k])}));
  } else { /* a restart's file may hold those of states after its checkpoint */
    hid_t file_id;
    PetscCall(PetscViewerHDF5GetFileId(v, &file_id));
    for (PetscInt j = 0; j < 3; j++)
      if (H5Aexists_by_name(file_id, "/", resolution[j], H5P_DEFAULT) > 0) ADH_H5(H5Adelete_by_name(file_id, "/", resolution[j], H5P_DEFAULT));
  }
  s->pull_off_written = k;
  PetscFunctionReturn(0);
}

/* The parameters of the run, as root attributes. */
static PetscErrorCode WriteAttributes(AdhSolver s, PetscViewer v)
{
  const AdhGrid g = s->grid;
  PetscMPIInt   size;
  PetscInt      nranks;
  PetscReal     rtol, atol, dtol;
  PetscInt      maxits;
  KSPType       ksptype;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  nranks = size;
  PetscCall(KSPGetTolerances(s->ksp, &rtol, &atol, &dtol, &maxits));
  PetscCall(KSPGetType(s->ksp, &ksptype));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "E_star", PETSC_REAL, &s->Estar));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "gamma", PETSC_REAL, &s->gamma));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "gamma_field", PETSC_BOOL, s->gamma_field ? &(PetscBool){PETSC_TRUE} : &(PetscBool){PETSC_FALSE}));
  if (s->gamma_field && s->gamma_file[0]) PetscCall(WriteStringAttribute(v, "gamma_field_file", s->gamma_file));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Sigma", PETSC_REAL, &s->Sigma));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "critical_stress_fixed", PETSC_BOOL, s->sigma_fixed > 0 ? &(PetscBool){PETSC_TRUE} : &(PetscBool){PETSC_FALSE}));
  if (s->sigma_fixed > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "critical_stress", PETSC_REAL, &s->sigma_fixed));
  PetscCall(WriteStringAttribute(v, "attach", AdhAttaches[s->attach]));
  PetscCall(WriteStringAttribute(v, "predictor", s->predictor_type));
  if (s->force_control) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "pulloff_rtol", PETSC_REAL, &s->pulloff_rtol));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "hx", PETSC_REAL, &g->hx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "hy", PETSC_REAL, &g->hy));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Lx", PETSC_REAL, &g->Lx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Ly", PETSC_REAL, &g->Ly));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Nx", PETSC_INT, &g->Nx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Ny", PETSC_INT, &g->Ny));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "nranks", PETSC_INT, &nranks));
  PetscCall(WriteStringAttribute(v, "boundary", AdhBoundaries[s->boundary]));
  PetscCall(WriteStringAttribute(v, "indenter", AdhIndenterTypes[s->indenter.type]));
  PetscCall(WriteStringAttribute(v, "start", AdhStarts[s->start]));
  PetscCall(WriteStringAttribute(v, "control", s->control_type));
  PetscCall(WriteStringAttribute(v, "criterion", s->criterion_type));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "criterion_radius", PETSC_REAL, &s->criterion_radius));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "criterion_radius_max", PETSC_REAL, &s->criterion_radius_max));
  if (s->asperity_ac > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "asperity_contact_radius", PETSC_REAL, &s->asperity_ac));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "steps", PETSC_INT, &s->steps));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cascade_rtol", PETSC_REAL, &s->cascade_rtol));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cascade_apart", PETSC_INT, &s->cascade_apart));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cascade_local", PETSC_REAL, &s->cascade_local));
  if (s->cascade_local > 0) {
    PetscReal local_rtol = s->cascade_local_rtol; /* the local KSP's, which -adh_local_ksp_rtol may have changed */
    if (s->local_ksp) PetscCall(KSPGetTolerances(s->local_ksp, &local_rtol, NULL, NULL, NULL));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cascade_local_rtol", PETSC_REAL, &local_rtol));
  }
  PetscCall(WriteStringAttribute(v, "ksp_type", ksptype));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "ksp_rtol", PETSC_REAL, &rtol));
  switch (s->indenter.type) {
  case ADH_INDENTER_SPHERE: PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "radius", PETSC_REAL, &s->indenter.radius)); break;
  case ADH_INDENTER_PUNCH: PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "punch_radius", PETSC_REAL, &s->indenter.punch_radius)); break;
  case ADH_INDENTER_CONE: PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cone_slope", PETSC_REAL, &s->indenter.cone_slope)); break;
  case ADH_INDENTER_FILE: PetscCall(WriteStringAttribute(v, "topography", s->indenter.topography)); break;
  case ADH_INDENTER_ROUGH: break; /* written when the file was opened */
  case ADH_INDENTER_ARRAY: break;
  }
  if (s->indenter.type == ADH_INDENTER_FILE || s->indenter.type == ADH_INDENTER_ARRAY) PetscCall(WriteStringAttribute(v, "topography_kind", AdhTopographyKinds[s->indenter.kind]));
  PetscFunctionReturn(0);
}

/* Rank 0 writes a text file through body(s, h5, fp) to NAME.part and renames it NAME, so that a
   file is either whole or absent; every rank learns whether it worked. */
static PetscErrorCode WriteTextFile(AdhSolver s, const char name[], void (*body)(AdhSolver, const char h5[], FILE *), const char h5[])
{
  char        part[PETSC_MAX_PATH_LEN + 16];
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(PartName(name, part, sizeof(part)));
  if (!rank) {
    FILE *fp = fopen(part, "w");
    if (fp) {
      body(s, h5, fp);
      ok = !ferror(fp);
      ok = (fclose(fp) == 0) && ok;
      ok = ok && rename(part, name) == 0;
    } else ok = 0;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: could not write %s", name);
  PetscFunctionReturn(0);
}

/* The columns of the results file's curve and of its CSV: the curve's own (AdhCurveColumns), and
   on a periodic cell the two a rough-contact study reads, mean pressure F / (Lx Ly) and area
   fraction A / (Lx Ly). */
static const char *const DerivedColumns[] = {"mean_pressure", "area_fraction"};

static PetscInt NumColumns(AdhSolver s)
{
  return AdhCurveNumColumns + (s->boundary == ADH_BOUNDARY_PERIODIC ? 2 : 0);
}

static const char *ColumnName(PetscInt j)
{
  return j < AdhCurveNumColumns ? AdhCurveColumns[j].name : DerivedColumns[j - AdhCurveNumColumns];
}

static PetscBool ColumnIsCount(PetscInt j)
{
  return j < AdhCurveNumColumns ? AdhCurveColumns[j].integer : PETSC_FALSE;
}

static PetscReal ColumnValue(AdhSolver s, const AdhState *st, PetscInt j)
{
  const PetscReal cell = s->grid->Lx * s->grid->Ly;
  if (j < AdhCurveNumColumns) return AdhStateValue(st, j);
  return (j == AdhCurveNumColumns ? st->force : st->area) / cell;
}

/* The journal FILE.csv.part: the curve as CSV (a step column, then one column per curve column),
   its header written when the results file is opened and a row appended and synced by rank 0
   after each recorded state; renamed FILE.csv when the run ends. */
static PetscErrorCode JournalName(const char file[], char name[], size_t len)
{
  char csv[PETSC_MAX_PATH_LEN + 8];

  PetscFunctionBegin;
  PetscCall(SiblingName(file, "csv", csv, sizeof(csv)));
  PetscCall(PartName(csv, name, len));
  PetscFunctionReturn(0);
}

/* Rank 0 writes and syncs rows [from, to) of the curve (from < 0: the header first); every rank
   learns whether it worked. */
static PetscErrorCode JournalWrite(AdhSolver s, PetscInt from, PetscInt to)
{
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  if (!rank) {
    FILE *fp = s->journal;
    if (from < 0) {
      fprintf(fp, "step");
      for (PetscInt j = 0; j < NumColumns(s); j++) fprintf(fp, ",%s", ColumnName(j));
      fprintf(fp, "\n");
      from = 0;
    }
    for (PetscInt k = from; k < to; k++) {
      fprintf(fp, "%" PetscInt_FMT, k);
      for (PetscInt j = 0; j < NumColumns(s); j++) {
        if (ColumnIsCount(j)) fprintf(fp, ",%.0f", (double)ColumnValue(s, &s->curve.state[k], j));
        else fprintf(fp, ",%.17g", (double)ColumnValue(s, &s->curve.state[k], j));
      }
      fprintf(fp, "\n");
    }
    ok = fflush(fp) == 0 && !ferror(fp) && fsync(fileno(fp)) == 0;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: could not write the curve to %s", s->output);
  PetscFunctionReturn(0);
}

/* A new journal for the results file `file`, with its header. */
static PetscErrorCode JournalOpen(AdhSolver s, const char file[])
{
  char        name[PETSC_MAX_PATH_LEN + 16];
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(JournalName(file, name, sizeof(name)));
  if (!rank) {
    if (s->journal) fclose(s->journal);
    s->journal = fopen(name, "w");
    ok         = s->journal != NULL;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_OPEN, "-adh_output: cannot write %s", name);
  PetscCall(JournalWrite(s, -1, 0));
  PetscFunctionReturn(0);
}

/* FILE.csv.part closed and renamed FILE.csv. */
static PetscErrorCode JournalClose(AdhSolver s, const char file[])
{
  char        name[PETSC_MAX_PATH_LEN + 16], csv[PETSC_MAX_PATH_LEN + 8];
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(JournalName(file, name, sizeof(name)));
  PetscCall(SiblingName(file, "csv", csv, sizeof(csv)));
  if (!rank) {
    ok         = s->journal && fclose(s->journal) == 0;
    s->journal = NULL;
    ok         = ok && rename(name, csv) == 0;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: could not write %s", csv);
  PetscFunctionReturn(0);
}

/* FILE.xmf beside FILE.h5 when it has fields: an XDMF description that ParaView (and VisIt) open
   as a time series over the states with fields, cell data on the grid of elements: the fields of
   each state (hyperslabs of the timestepped datasets), the profile h, the critical stress, and
   the heights of a rough surface. The time of a frame is its curve row. */
static void XDMFBody(AdhSolver s, const char h5[], FILE *fp)
{
  const AdhGrid  g = s->grid;
  const PetscInt T = s->nfield_states, Nx = g->Nx, Ny = g->Ny;

  /* cell corners: element (i, j) has its centre at ((i - Nx/2) hx, (j - Ny/2) hy) */
  const double x0 = (double)((-(Nx / 2) - 0.5) * g->hx), y0 = (double)((-(Ny / 2) - 0.5) * g->hy);
  fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n");
  fprintf(fp, "  <Grid Name=\"states\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (PetscInt t = 0; t < T; t++) {
    fprintf(fp, "   <Grid Name=\"state %" PetscInt_FMT "\" GridType=\"Uniform\">\n", s->field_states[t]);
    fprintf(fp, "    <Time Value=\"%" PetscInt_FMT "\"/>\n", s->field_states[t]);
    fprintf(fp, "    <Topology TopologyType=\"2DCoRectMesh\" Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\"/>\n", Ny + 1, Nx + 1);
    fprintf(fp, "    <Geometry GeometryType=\"ORIGIN_DXDY\">\n     <DataItem Dimensions=\"2\" Format=\"XML\">%.17g %.17g</DataItem>\n", y0, x0);
    fprintf(fp, "     <DataItem Dimensions=\"2\" Format=\"XML\">%.17g %.17g</DataItem>\n    </Geometry>\n", (double)g->hy, (double)g->hx);
    for (PetscInt f = 0; f < 4; f++) {
      if (!(s->fields & (1 << f))) continue;
      fprintf(fp, "    <Attribute Name=\"%s\" Center=\"Cell\" AttributeType=\"Scalar\">\n", AdhFieldNames[f]);
      fprintf(fp, "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\">\n", Ny, Nx);
      fprintf(fp, "      <DataItem Dimensions=\"3 3\" Format=\"XML\">%" PetscInt_FMT " 0 0 1 1 1 1 %" PetscInt_FMT " %" PetscInt_FMT "</DataItem>\n", t, Ny, Nx);
      fprintf(fp, "      <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:/fields/%s</DataItem>\n", T, Ny, Nx, f == 3 ? "UChar" : "Float", f == 3 ? 1 : 8, h5, AdhFieldNames[f]);
      fprintf(fp, "     </DataItem>\n    </Attribute>\n");
    }
    for (PetscInt f = 0; f < 3; f++) {
      const char *fixed[3] = {"profile", "critical_stress", "topography"}, *where[3] = {"/fields/profile", "/fields/critical_stress", "/topography"};
      if (f == 2 && s->indenter.type != ADH_INDENTER_ROUGH) continue;
      fprintf(fp, "    <Attribute Name=\"%s\" Center=\"Cell\" AttributeType=\"Scalar\">\n", fixed[f]);
      fprintf(fp, "     <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:%s</DataItem>\n    </Attribute>\n", Ny, Nx, h5, where[f]);
    }
    fprintf(fp, "   </Grid>\n");
  }
  fprintf(fp, "  </Grid>\n </Domain>\n</Xdmf>\n");
}

/* The curve into the viewer's current group: every column as a 1-D float64 dataset (counts too:
   PETSc's IS viewer adds a block dimension), and the path. The results file and the checkpoint
   both hold it. */
PetscErrorCode AdhOutputWriteCurve_Private(AdhSolver s, PetscViewer viewer)
{
  const AdhCurve *c = &s->curve;
  PetscReal      *column;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(c->n + 1, &column));
  for (PetscInt j = 0; j < AdhCurveNumColumns; j++) {
    for (PetscInt k = 0; k < c->n; k++) column[k] = AdhStateValue(&c->state[k], j);
    PetscCall(WriteRealArray(s, viewer, AdhCurveColumns[j].name, c->n, column));
  }
  PetscCall(PetscFree(column));
  PetscCall(WriteRealArray(s, viewer, "path", s->npath, s->path));
  PetscFunctionReturn(0);
}

/* What a results file holds before its first state: the parameters, complete = 0, the curve's
   columns (empty) and the path; and the journal with its header. */
static PetscErrorCode Begin(AdhSolver s, PetscViewer v, const char file[])
{
  hid_t file_id, group;

  PetscFunctionBegin;
  PetscCall(WriteAttributes(s, v));
  PetscCall(WritePullOff(s, v, -1));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "complete", PETSC_BOOL, &(PetscBool){PETSC_FALSE}));
  PetscCall(PetscViewerHDF5PushGroup(v, "/curve"));
  PetscCall(PetscViewerHDF5OpenGroup(v, NULL, &file_id, &group));
  for (PetscInt j = 0; j < NumColumns(s); j++) {
    /* a restart's file: its rows are written again from the checkpoint's curve */
    if (H5Lexists(group, ColumnName(j), H5P_DEFAULT) > 0) ADH_H5(H5Ldelete(group, ColumnName(j), H5P_DEFAULT));
    PetscCall(AppendRows(s, group, ColumnName(j), ColumnIsCount(j), 0, 0, NULL));
  }
  /* earlier files held the path as /curve/path, a dataset of its own length among the columns:
     a restart's earlier file loses it, the root attribute replaces it */
  if (H5Lexists(group, "path", H5P_DEFAULT) > 0) ADH_H5(H5Ldelete(group, "path", H5P_DEFAULT));
  ADH_H5(H5Gclose(group));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(WriteRealArrayAttribute(v, "path", s->npath, s->path));
  ADH_H5(H5Fflush(file_id, H5F_SCOPE_GLOBAL));
  s->rows_written = 0;
  PetscCall(JournalOpen(s, file));
  PetscFunctionReturn(0);
}

/* The states recorded since the last call into the results file and the journal, flushed: after
   it, both hold every recorded state whatever happens to the job. */
PetscErrorCode AdhOutputAppend_Private(AdhSolver s, PetscViewer v)
{
  const PetscInt from = s->rows_written, n = s->curve.n;
  hid_t          file_id, group;
  PetscInt       k;

  PetscFunctionBegin;
  if (n > from) {
    PetscReal *column;
    PetscCall(PetscMalloc1(n - from, &column));
    PetscCall(PetscViewerHDF5PushGroup(v, "/curve"));
    PetscCall(PetscViewerHDF5OpenGroup(v, NULL, &file_id, &group));
    for (PetscInt j = 0; j < NumColumns(s); j++) {
      for (k = from; k < n; k++) column[k - from] = ColumnValue(s, &s->curve.state[k], j);
      PetscCall(AppendRows(s, group, ColumnName(j), ColumnIsCount(j), from, n - from, column));
    }
    ADH_H5(H5Gclose(group));
    PetscCall(PetscViewerHDF5PopGroup(v));
    PetscCall(PetscFree(column));
  }
  PetscCall(AdhCurveGetPullOffState(&s->curve, &k));
  if (k != s->pull_off_written) PetscCall(WritePullOff(s, v, k));
  PetscCall(PetscViewerHDF5GetFileId(v, &file_id));
  ADH_H5(H5Fflush(file_id, H5F_SCOPE_GLOBAL));
  PetscCall(JournalWrite(s, from, n));
  s->rows_written = n;
  PetscFunctionReturn(0);
}

/* The field datasets of the open group: which of AdhFieldNames[] it has, as ADH_FIELD_* bits. */
static PetscInt FieldsIn(hid_t group)
{
  PetscInt have = 0;
  for (PetscInt f = 0; f < 4; f++)
    if (H5Lexists(group, AdhFieldNames[f], H5P_DEFAULT) > 0) have |= 1 << f;
  return have;
}

/* A list of the fields in mask, for messages. */
static void FieldList(PetscInt mask, char *text, size_t len)
{
  text[0] = 0;
  for (PetscInt f = 0; f < 4; f++)
    if (mask & (1 << f)) {
      if (text[0]) strncat(text, ",", len - strlen(text) - 1);
      strncat(text, AdhFieldNames[f], len - strlen(text) - 1);
    }
  if (!text[0]) strncat(text, "none", len - 1);
}

/* The earlier run's results file (open in v) taken over after the checkpoint's states: the curve
   is written again from the checkpoint, the frames of states after it are dropped; kept: the
   frames left. A file that does not fit this run is left alone and `unfit` says why. */
static PetscErrorCode TakeOver(AdhSolver s, PetscViewer v, const char file[], PetscInt *kept, char unfit[], size_t len)
{
  const PetscInt n = s->curve.n;
  hid_t          file_id, group;
  PetscInt       Nx = -1, Ny = -1, have = 0, frames = 0;
  PetscBool      has;
  PetscReal     *states = NULL;

  PetscFunctionBegin;
  *kept    = 0;
  unfit[0] = 0;
  PetscCall(PetscViewerHDF5HasAttribute(v, "/", "Nx", &has));
  if (has) PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "Nx", PETSC_INT, NULL, &Nx));
  if (has) PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "Ny", PETSC_INT, NULL, &Ny));
  if (Nx != s->grid->Nx || Ny != s->grid->Ny) {
    PetscCall(PetscSNPrintf(unfit, len, "-adh_restart: the earlier results %s are not those of this problem (grid %" PetscInt_FMT " x %" PetscInt_FMT "); give another -adh_output", file, Nx, Ny));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscViewerHDF5HasGroup(v, "/fields", &has));
  if (has) {
    PetscCall(PetscViewerHDF5PushGroup(v, "/fields"));
    PetscCall(PetscViewerHDF5OpenGroup(v, NULL, &file_id, &group));
    have = FieldsIn(group);
    if (have == s->fields && have) {
      hid_t   dset, space;
      hsize_t dims[1] = {0};
      if (H5Lexists(group, "state", H5P_DEFAULT) > 0) {
        ADH_H5(dset = H5Dopen2(group, "state", H5P_DEFAULT));
        ADH_H5(space = H5Dget_space(dset));
        ADH_H5(H5Sget_simple_extent_dims(space, dims, NULL));
        PetscCall(PetscMalloc1(dims[0] + 1, &states));
        if (dims[0]) ADH_H5(H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, states));
        ADH_H5(H5Sclose(space));
        ADH_H5(H5Dclose(dset));
        ADH_H5(H5Ldelete(group, "state", H5P_DEFAULT));
      }
      /* the frames are in the order of their states: keep those of the checkpoint's states */
      for (frames = 0; frames < (PetscInt)dims[0] && states[frames] < n; frames++) continue;
      /* shorten the field datasets to them (their first dimension is the frame) */
      for (PetscInt f = 0; f < 4; f++) {
        hid_t   fset, fspace;
        hsize_t fdims[8];
        int     ndims;
        if (!(have & (1 << f))) continue;
        ADH_H5(fset = H5Dopen2(group, AdhFieldNames[f], H5P_DEFAULT));
        ADH_H5(fspace = H5Dget_space(fset));
        ADH_H5(ndims = H5Sget_simple_extent_ndims(fspace));
        PetscCheck(ndims >= 1 && ndims <= 8, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: field %s has %d dimensions", file, AdhFieldNames[f], ndims);
        ADH_H5(H5Sget_simple_extent_dims(fspace, fdims, NULL));
        fdims[0] = (hsize_t)frames;
        ADH_H5(H5Dset_extent(fset, fdims));
        ADH_H5(H5Sclose(fspace));
        ADH_H5(H5Dclose(fset));
      }
      PetscCall(AppendRows(s, group, "state", PETSC_TRUE, 0, frames, states));
    }
    ADH_H5(H5Gclose(group));
    PetscCall(PetscViewerHDF5PopGroup(v));
  }
  if (have != s->fields) {
    char theirs[64], ours[64];
    FieldList(have, theirs, sizeof(theirs));
    FieldList(s->fields, ours, sizeof(ours));
    PetscCall(PetscSNPrintf(unfit, len, "-adh_restart: the earlier results %s have the fields %s, this run's -adh_fields %s: give the same -adh_fields to go on in that file, or another -adh_output to keep it as it is", file, theirs, ours));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscFree(s->field_states));
  PetscCall(PetscMalloc1(frames + 1, &s->field_states));
  for (PetscInt k = 0; k < frames; k++) s->field_states[k] = (PetscInt)states[k];
  s->nfield_states = frames;
  PetscCall(PetscFree(states));
  *kept = frames;
  PetscFunctionReturn(0);
}

/* A restart's results: the results file of the run the checkpoint comes from, when it is this
   run's -adh_output (FILE.h5, or FILE.h5.part if that run was killed), goes on after the
   checkpoint's states, with their fields; otherwise a new file. One line says which. */
PetscErrorCode AdhOutputResume_Private(AdhSolver s, const char file[], PetscViewer *viewer)
{
  char           part[PETSC_MAX_PATH_LEN + 8], full[PETSC_MAX_PATH_LEN], has[128];
  const char    *earlier = s->restart_output[0] ? s->restart_output : full;
  const PetscInt last    = s->curve.n - 1;
  PetscBool      same;
  PetscMPIInt    rank;
  int            found = 0, damaged = 0; /* found 1: FILE.part, 2: FILE (moved to FILE.part) */
  PetscErrorCode ierr;
  PetscInt       kept = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  if (s->fields) PetscCall(PetscSNPrintf(has, sizeof(has), "has the curve from state 0 and the fields from state %" PetscInt_FMT " on", last + 1));
  else PetscCall(PetscSNPrintf(has, sizeof(has), "has the curve from state 0"));
  PetscCall(PetscGetFullPath(file, full, sizeof(full))); /* the checkpoint names the file in full */
  PetscCall(PetscStrcmp(earlier, full, &same));
  if (!same) {
    PetscCall(AdhOutputOpen_Private(s, file, viewer));
    PetscCall(AdhOutputAppend_Private(s, *viewer));
    PetscCall(PetscPrintf(s->comm, "adhbem: restart after state %" PetscInt_FMT ": %s %s; those of the earlier states are in the earlier run's %s\n", last, file, has, earlier));
    PetscFunctionReturn(0);
  }
  PetscCall(AdhOutputCheckWritable_Private(s, "-adh_output", file));
  PetscCall(PartName(file, part, sizeof(part)));
  if (!rank) {
    if (!access(part, F_OK)) found = 1;
    else if (!access(file, F_OK) && !rename(file, part)) found = 2;
    if (found) {
      /* a file cut short by a kill may not open (HDF5 would say why: quiet here); it is replaced */
      H5E_auto2_t report;
      void       *data;
      hid_t       f;
      ADH_H5(H5Eget_auto2(H5E_DEFAULT, &report, &data));
      ADH_H5(H5Eset_auto2(H5E_DEFAULT, NULL, NULL));
      f       = H5Fopen(part, H5F_ACC_RDONLY, H5P_DEFAULT);
      damaged = f < 0;
      if (f >= 0) H5Fclose(f);
      ADH_H5(H5Eset_auto2(H5E_DEFAULT, report, data));
    }
  }
  PetscCallMPI(MPI_Bcast(&found, 1, MPI_INT, 0, s->comm));
  PetscCallMPI(MPI_Bcast(&damaged, 1, MPI_INT, 0, s->comm));
  if (found && !damaged) {
    char unfit[PETSC_MAX_PATH_LEN + 256];
    PetscCall(PetscViewerHDF5Open(s->comm, part, FILE_MODE_APPEND, viewer));
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = TakeOver(s, *viewer, file, &kept, unfit, sizeof(unfit));
    PetscCall(PetscPopErrorHandler());
    if (!ierr && unfit[0]) {
      /* the file is whole but not this run's: left as it was, and the run refused */
      PetscCall(PetscViewerDestroy(viewer));
      if (!rank && found == 2) (void)rename(part, file);
      SETERRQ(s->comm, PETSC_ERR_ARG_INCOMP, "%s", unfit);
    }
    if (ierr) { /* opened, but not all of it reads */
      PetscCall(PetscViewerDestroy(viewer));
      damaged = 1;
    }
  }
  if (!found || damaged) {
    PetscCall(AdhOutputOpen_Private(s, file, viewer));
    PetscCall(AdhOutputAppend_Private(s, *viewer));
    if (damaged) PetscCall(PetscPrintf(s->comm, "adhbem: restart after state %" PetscInt_FMT ": the earlier results %s could not be read (cut short when the run was killed?) and are replaced: %s %s\n", last, part, file, has));
    else PetscCall(PetscPrintf(s->comm, "adhbem: restart after state %" PetscInt_FMT ": %s %s (the earlier results were not there to keep)\n", last, file, has));
    PetscFunctionReturn(0);
  }
  if (!rank) { /* what the earlier run wrote at its end is written again at this one's */
    char name[PETSC_MAX_PATH_LEN + 8];
    PetscCall(SiblingName(file, "csv", name, sizeof(name)));
    (void)remove(name);
    PetscCall(SiblingName(file, "xmf", name, sizeof(name)));
    (void)remove(name);
  }
  PetscCall(Begin(s, *viewer, file));
  PetscCall(AdhOutputAppend_Private(s, *viewer));
  if (s->fields) PetscCall(PetscPrintf(s->comm, "adhbem: restart after state %" PetscInt_FMT ": %s goes on, with the curve and the fields of the earlier states (%" PetscInt_FMT " frames)\n", last, file, kept));
  else PetscCall(PetscPrintf(s->comm, "adhbem: restart after state %" PetscInt_FMT ": %s goes on, with the curve of the earlier states\n", last, file));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhOutputClose_Private(AdhSolver s, const char file[], PetscViewer *viewer)
{
  char        part[PETSC_MAX_PATH_LEN + 8], xmf[PETSC_MAX_PATH_LEN + 8];
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCall(AdhOutputAppend_Private(s, *viewer));
  PetscCall(PetscViewerDestroy(viewer));
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(PartName(file, part, sizeof(part)));
  if (!rank) ok = rename(part, file) == 0;
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: could not move %s to %s", part, file);
  PetscCall(JournalClose(s, file));
  if (s->nfield_states) {
    /* the XDMF names the HDF5 file without its directory: the pair can move together */
    PetscCall(SiblingName(file, "xmf", xmf, sizeof(xmf)));
    PetscCall(WriteTextFile(s, xmf, XDMFBody, strrchr(file, '/') ? strrchr(file, '/') + 1 : file));
  }
  PetscCall(PetscFree(s->field_states));
  s->nfield_states = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverWriteOutput(AdhSolver s, const char file[])
{
  PetscViewer viewer;

  PetscFunctionBegin;
  PetscCall(AdhOutputOpen_Private(s, file, &viewer));
  PetscCall(AdhOutputWriteFields_Private(s, viewer, PetscMax(s->curve.n - 1, 0)));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "complete", PETSC_BOOL, &(PetscBool){PETSC_TRUE}));
  PetscCall(AdhOutputClose_Private(s, file, &viewer));
  PetscFunctionReturn(0);
}
