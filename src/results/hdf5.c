/* Raw HDF5 for what PETSc's viewer does not write: datasets extended a row or a frame at a time,
   and UTF-8 string and array attributes. */
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

/* An error (ierr, raised on this rank or 0) of a write that not every rank makes, made every
   rank's: the ranks leave together, none left waiting in HDF5's next collective call. Collective. */
PetscErrorCode AdhH5Agree_Private(MPI_Comm comm, PetscErrorCode ierr)
{
  int failed = ierr != 0;

  PetscFunctionBegin;
  PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, comm));
  PetscCall(ierr);
  PetscCheck(!failed, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "the write failed on another rank");
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
  PetscCall(AdhH5Agree_Private(s->comm, ierr));
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
