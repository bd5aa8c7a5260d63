/* Raw HDF5 for what PETSc's viewer does not write: datasets extended a row or a frame at a time,
   and UTF-8 string and array attributes. */
#include <stdlib.h>
#include <unistd.h>
#include "results/resultsimpl.h"

/* Dataset `name` of group, extendible along its first dimension: created with dims (and chunk) when
   missing, else opened and given the extent dims (which may also shorten it). */
PetscErrorCode AdhH5OpenExtendible_Private(hid_t group, const char name[], hid_t type, int rank, const hsize_t dims[], const hsize_t chunk[], hid_t *dset)
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

/* The innermost description on HDF5's error stack: the system's or MPI-IO's words for the cause. */
static herr_t Innermost(unsigned n, const H5E_error2_t *e, void *ctx)
{
  char *cause = (char *)ctx;

  if (n == 0 && e->desc) snprintf(cause, 256, "%s", e->desc);
  return 0;
}

/* Why this rank's write failed, in HDF5's innermost words, or "the write failed". */
void AdhH5Cause_Private(char cause[256])
{
  cause[0] = 0;
  (void)H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, Innermost, cause);
  if (!cause[0]) snprintf(cause, 256, "the write failed");
}

/* Whether a write of the phase under way (AdhOutputWriteBegin_Private) failed on any rank: a
   non-blocking reduction. A rank whose write failed waits for the others at most
   ADHBEM_ERROR_WAIT seconds (5). Parallel HDF5 cannot recover from a write that fails on some ranks
   only: the others go on into its next collective operation, where they wait for this rank
   forever. So a rank that waited in vain ends the job itself, after one line that names the file
   and the cause; the states written before are kept as after a kill (FILE.h5.part, FILE.csv.part,
   the last checkpoint), and mpirun ends the other ranks. Collective. */
PetscErrorCode AdhH5AgreeOnFailure_Private(AdhSolver s, PetscBool failed, PetscBool *any)
{
  int         mine = failed ? 1 : 0, all = 0, done = 0;
  MPI_Request request;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Iallreduce(&mine, &all, 1, MPI_INT, MPI_MAX, s->comm, &request));
  if (failed) {
    const char    *env  = getenv("ADHBEM_ERROR_WAIT");
    const double   wait = env && atof(env) > 0 ? atof(env) : 5.0;
    PetscLogDouble t0, t;
    PetscCall(PetscTime(&t0));
    for (t = t0; !done && t - t0 < wait;) {
      PetscCallMPI(MPI_Test(&request, &done, MPI_STATUS_IGNORE));
      if (!done) usleep(1000);
      PetscCall(PetscTime(&t));
    }
    if (!done) {
      PetscMPIInt rank, size;
      char        cause[256];
      PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
      PetscCallMPI(MPI_Comm_size(s->comm, &size));
      AdhH5Cause_Private(cause);
      fprintf(stderr, "adhbem: error: %s: %s, on rank %d of %d alone (parallel HDF5 cannot go on from a write that fails on some ranks only: the job ends)%s%s\n", s->writing, cause, rank, size, s->writing_kept[0] ? "; " : "", s->writing_kept);
      fflush(stderr);
      if (s->writing_discard) (void)remove(s->writing_part);
      _exit(1);
    }
  } else PetscCallMPI(MPI_Wait(&request, MPI_STATUS_IGNORE));
  *any = (PetscBool)(all != 0);
  PetscFunctionReturn(0);
}

/* An error (ierr, raised on this rank or 0) of a write that not every rank makes, made every
   rank's: the ranks leave together, none left waiting in HDF5's next collective call. Collective. */
PetscErrorCode AdhH5Agree_Private(AdhSolver s, PetscErrorCode ierr)
{
  PetscBool any;

  PetscFunctionBegin;
  PetscCall(AdhH5AgreeOnFailure_Private(s, (PetscBool)(ierr != 0), &any));
  PetscCall(ierr);
  PetscCheck(!any, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "the write failed on another rank");
  PetscFunctionReturn(0);
}

/* count (a block of rank dimensions) values of buf into dataset dset at offset. */
PetscErrorCode AdhH5WriteBlock_Private(hid_t dset, hid_t type, int rank, const hsize_t offset[], const hsize_t count[], const void *buf)
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
PetscErrorCode AdhH5WriteStringAttribute_Private(PetscViewer v, const char name[], const char value[])
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
PetscErrorCode AdhH5WriteRealArrayAttribute_Private(PetscViewer v, const char name[], PetscInt n, const PetscReal *values)
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
PetscErrorCode AdhH5AppendRows_Private(AdhSolver s, hid_t group, const char name[], PetscBool integer, PetscInt from, PetscInt count, const PetscReal *values)
{
  hid_t       dset, type = integer ? H5T_NATIVE_LLONG : H5T_NATIVE_DOUBLE;
  hsize_t     dims[1] = {(hsize_t)(from + count)}, chunk[1] = {256}, offset[1] = {(hsize_t)from}, n[1] = {(hsize_t)count};
  PetscMPIInt rank;
  PetscErrorCode ierr = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(AdhH5OpenExtendible_Private(group, name, type, 1, dims, chunk, &dset));
  if (!rank && count > 0) {
    void *buf;
    PetscCall(PetscMalloc(count * sizeof(double), &buf));
    for (PetscInt k = 0; k < count; k++) {
      if (integer) ((long long *)buf)[k] = (long long)values[k];
      else ((double *)buf)[k] = (double)values[k];
    }
    ierr = AdhH5WriteBlock_Private(dset, type, 1, offset, n, buf);
    PetscCall(PetscFree(buf));
  }
  /* a write of rank 0's that fails is every rank's failure, before the next collective call */
  PetscCall(AdhH5Agree_Private(s, ierr));
  ADH_H5(H5Dclose(dset));
  PetscFunctionReturn(0);
}

/* A 1-D dataset held by rank 0. */
PetscErrorCode AdhH5WriteRealArray_Private(AdhSolver s, PetscViewer viewer, const char name[], PetscInt n, const PetscReal *values)
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
