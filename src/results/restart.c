/* A restart's results file: the earlier run's file taken over after the checkpoint's states. */
#include <unistd.h>
#include "results/resultsimpl.h"

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
      PetscCall(AdhH5AppendRows_Private(s, group, "state", PETSC_TRUE, 0, frames, states));
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
  PetscCall(AdhOutputPartName_Private(file, part, sizeof(part)));
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
    PetscCall(AdhOutputSiblingName_Private(file, "csv", name, sizeof(name)));
    (void)remove(name);
    PetscCall(AdhOutputSiblingName_Private(file, "xmf", name, sizeof(name)));
    (void)remove(name);
  }
  PetscCall(AdhOutputBegin_Private(s, *viewer, file));
  PetscCall(AdhOutputAppend_Private(s, *viewer));
  if (s->fields) PetscCall(PetscPrintf(s->comm, "adhbem: restart after state %" PetscInt_FMT ": %s goes on, with the curve and the fields of the earlier states (%" PetscInt_FMT " frames)\n", last, file, kept));
  else PetscCall(PetscPrintf(s->comm, "adhbem: restart after state %" PetscInt_FMT ": %s goes on, with the curve of the earlier states\n", last, file));
  PetscFunctionReturn(0);
}
