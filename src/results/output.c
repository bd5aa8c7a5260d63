/* Results: HDF5 through PETSc's viewer (curve in /curve, parameters as root attributes, fields
   in /fields) and the curve as CSV. Both are written to FILE.part as the path goes, and renamed
   when the run ends, so a finished result file is never half-written and an older one is not
   lost to a failed run. After each recorded state its curve row and its fields are appended to
   FILE.h5.part and the file is flushed, and rank 0 appends the row to FILE.csv.part (the journal)
   and syncs it: whatever kills the job, both hold every state recorded before (adhbem.load reads
   them). A restart appends to the results of the run it goes on from. */
#include <errno.h>
#include "results/resultsimpl.h"

PetscErrorCode AdhOutputWriteSurface_Private(AdhSolver, PetscViewer);
PetscErrorCode AdhOutputWriteArrayTopography_Private(AdhSolver, PetscViewer);
PetscErrorCode AdhOutputBegin_Private(AdhSolver, PetscViewer, const char[]);

/* The first writes of a new results file: the rough surface or array topography, the parameters, the empty curve. */
static PetscErrorCode Begin(AdhSolver s, PetscViewer viewer, const char file[])
{
  PetscFunctionBegin;
  /* a rough surface, generated again, goes in now, while the contact set and its solver's vectors
     are small (at the close they may be the largest of the run) */
  if (s->indenter.type == ADH_INDENTER_ROUGH) PetscCall(AdhOutputWriteSurface_Private(s, viewer));
  if (s->indenter.type == ADH_INDENTER_ARRAY) PetscCall(AdhOutputWriteArrayTopography_Private(s, viewer));
  PetscCall(AdhOutputBegin_Private(s, viewer, file));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhOutputOpen_Private(AdhSolver s, const char file[], PetscViewer *viewer)
{
  char           part[PETSC_MAX_PATH_LEN + 8];
  const PetscInt n = s->grid->Nx * s->grid->Ny;
  PetscErrorCode ierr;
  int            err;

  PetscFunctionBegin;
  PetscCall(AdhOutputCheckWritable_Private(s, "-adh_output", file));
  PetscCall(AdhOutputPartName_Private(file, part, sizeof(part)));
  PetscCall(PetscViewerHDF5Open(s->comm, part, FILE_MODE_WRITE, viewer));
  PetscCall(PetscFree(s->field_states));
  s->nfield_states = 0;
  s->rows_written  = 0;
  PetscCall(AdhOutputReserve_Private(s, part, s->indenter.type == ADH_INDENTER_ROUGH || s->indenter.type == ADH_INDENTER_ARRAY ? (size_t)n * sizeof(double) : 0, &err));
  if (err) { /* nothing in it yet: not left behind */
    PetscCall(AdhOutputAbandon_Private(viewer));
    PetscCall(AdhOutputRemove_Private(s, part));
  }
  PetscCheck(!err, s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: cannot write %s: %s", part, strerror(err));
  PetscCall(AdhOutputWriteBegin_Private(s, "-adh_output", part, "no state was written", PETSC_TRUE));
  ierr             = Begin(s, *viewer, file);
  ierr             = AdhOutputWriteEnd_Private(s, ierr);
  s->output_failed = (PetscBool)(s->output_failed || ierr);
  if (ierr) { /* nothing in it that could be read: not left behind either */
    PetscCall(AdhOutputAbandon_Private(viewer));
    PetscCall(AdhOutputRemove_Private(s, part));
  }
  PetscCall(ierr);
  PetscFunctionReturn(0);
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
    PetscCall(AdhH5WriteRealArray_Private(s, viewer, AdhCurveColumns[j].name, c->n, column));
  }
  PetscCall(PetscFree(column));
  PetscCall(AdhH5WriteRealArray_Private(s, viewer, "path", s->npath, s->path));
  PetscFunctionReturn(0);
}

/* What a results file holds before its first state: the parameters, complete = 0, the curve's
   columns (empty) and the path; and the journal with its header. */
PetscErrorCode AdhOutputBegin_Private(AdhSolver s, PetscViewer v, const char file[])
{
  hid_t file_id, group;

  PetscFunctionBegin;
  PetscCall(AdhOutputWriteAttributes_Private(s, v));
  PetscCall(AdhOutputWritePullOff_Private(s, v, -1));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "complete", PETSC_BOOL, &(PetscBool){PETSC_FALSE}));
  PetscCall(PetscViewerHDF5PushGroup(v, "/curve"));
  PetscCall(PetscViewerHDF5OpenGroup(v, NULL, &file_id, &group));
  for (PetscInt j = 0; j < AdhOutputNumColumns_Private(s); j++) {
    /* a restart's file: its rows are written again from the checkpoint's curve */
    if (H5Lexists(group, AdhOutputColumnName_Private(j), H5P_DEFAULT) > 0) ADH_H5(H5Ldelete(group, AdhOutputColumnName_Private(j), H5P_DEFAULT));
    PetscCall(AdhH5AppendRows_Private(s, group, AdhOutputColumnName_Private(j), AdhOutputColumnIsCount_Private(j), 0, 0, NULL));
  }
  /* earlier files held the path as /curve/path, a dataset of its own length among the columns:
     a restart's earlier file loses it, the root attribute replaces it */
  if (H5Lexists(group, "path", H5P_DEFAULT) > 0) ADH_H5(H5Ldelete(group, "path", H5P_DEFAULT));
  ADH_H5(H5Gclose(group));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(AdhH5WriteRealArrayAttribute_Private(v, "path", s->npath, s->path));
  ADH_H5(H5Fflush(file_id, H5F_SCOPE_GLOBAL));
  s->rows_written = 0;
  PetscCall(AdhJournalOpen_Private(s, file));
  PetscFunctionReturn(0);
}

/* The curve's rows recorded since the last call, and the pull-off attributes, into the file, flushed. */
static PetscErrorCode AppendRows(AdhSolver s, PetscViewer v)
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
    for (PetscInt j = 0; j < AdhOutputNumColumns_Private(s); j++) {
      for (k = from; k < n; k++) column[k - from] = AdhOutputColumnValue_Private(s, &s->curve.state[k], j);
      PetscCall(AdhH5AppendRows_Private(s, group, AdhOutputColumnName_Private(j), AdhOutputColumnIsCount_Private(j), from, n - from, column));
    }
    ADH_H5(H5Gclose(group));
    PetscCall(PetscViewerHDF5PopGroup(v));
    PetscCall(PetscFree(column));
  }
  {
    AdhResolution r;
    PetscCall(AdhSolverGetResolution(s, &r));
    if (r.state != s->pull_off_written || r.apart != s->apart_written || r.full_contact != s->full_written) PetscCall(AdhOutputWritePullOff_Private(s, v, r.state));
  }
  PetscCall(PetscViewerHDF5GetFileId(v, &file_id));
  ADH_H5(H5Fflush(file_id, H5F_SCOPE_GLOBAL));
  PetscFunctionReturn(0);
}

/* The states recorded since the last call into the results file and the journal, flushed: after
   it, both hold every recorded state whatever happens to the job. A full disk or a failed write
   stops it with one error, the file as it was after the last call. */
PetscErrorCode AdhOutputAppend_Private(AdhSolver s, PetscViewer v)
{
  const char    *part;
  char           kept[3 * PETSC_MAX_PATH_LEN];
  PetscErrorCode ierr;
  int            err;

  PetscFunctionBegin;
  PetscCall(PetscViewerFileGetName(v, &part));
  PetscCall(AdhOutputKept_Private(s, part, kept, sizeof(kept)));
  PetscCall(AdhOutputReserve_Private(s, part, 0, &err));
  if (err) { /* the file as after the last state: what the reservation got is given back */
    s->output_failed = PETSC_TRUE;
    PetscCall(AdhOutputReleaseReserve_Private(s, part));
  }
  PetscCheck(!err, s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: cannot write %s: %s; %s", part, strerror(err), kept);
  PetscCall(AdhOutputWriteBegin_Private(s, "-adh_output", part, kept, PETSC_FALSE));
  ierr             = AppendRows(s, v);
  ierr             = AdhOutputWriteEnd_Private(s, ierr);
  s->output_failed = (PetscBool)(s->output_failed || ierr);
  PetscCall(ierr);
  PetscCall(AdhJournalWrite_Private(s, s->rows_written, s->curve.n));
  s->rows_written = s->curve.n;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhOutputClose_Private(AdhSolver s, const char file[], PetscViewer *viewer)
{
  char        part[PETSC_MAX_PATH_LEN + 8], xmf[PETSC_MAX_PATH_LEN + 8];
  PetscMPIInt rank;
  int         ok = 0; /* rank 0's errno of the rename */

  PetscFunctionBegin;
  PetscCall(AdhOutputAppend_Private(s, *viewer));
  { /* flushed just now: a close that fails anyway leaves the viewer half-destroyed, not to be closed again */
    PetscErrorCode ierr = PetscViewerDestroy(viewer);
    if (ierr) *viewer = NULL;
    PetscCall(ierr);
  }
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(AdhOutputPartName_Private(file, part, sizeof(part)));
  PetscCall(AdhOutputReleaseReserve_Private(s, part));
  if (!rank) ok = rename(part, file) == 0 ? 0 : errno;
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  if (ok) {
    char kept[3 * PETSC_MAX_PATH_LEN];
    PetscCall(AdhOutputKept_Private(s, part, kept, sizeof(kept)));
    SETERRQ(s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: could not move %s to %s: %s; %s", part, file, strerror(ok), kept);
  }
  PetscCall(AdhJournalClose_Private(s, file));
  if (s->nfield_states) {
    /* the XDMF names the HDF5 file without its directory: the pair can move together */
    PetscCall(AdhOutputSiblingName_Private(file, "xmf", xmf, sizeof(xmf)));
    PetscCall(AdhOutputWriteTextFile_Private(s, xmf, AdhOutputXDMFBody_Private, strrchr(file, '/') ? strrchr(file, '/') + 1 : file));
  }
  PetscCall(PetscFree(s->field_states));
  s->nfield_states = 0;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverWriteOutput - Writes the curve recorded so far (and, with -adh_fields, the current fields, as those of the
  curve's last row) to a results file and its CSV

  Collective

  Input Parameters:
+ s    - the solver
- file - the results file, FILE.h5; the curve also goes to FILE.csv (and, with fields, FILE.xmf)

  Level: intermediate

  Notes:
  For states computed with `AdhSolverStart()` and `AdhSolverStep()`; `AdhSolverSolvePath()` writes -adh_output itself,
  as it goes. The files appear whole or not at all (written as FILE.part and renamed).

.seealso: `AdhSolverSolvePath()`, `AdhSolverGetCurve()`
@*/
PetscErrorCode AdhSolverWriteOutput(AdhSolver s, const char file[])
{
  PetscViewer    viewer = NULL;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidCharPointer(file, 2);
  /* the open file shares the journal and the count of rows and frames written */
  PetscCheck(!s->writer, s->comm, PETSC_ERR_ORDER, "%s is being written state by state (AdhSolverOutputBegin(), Python's iterate_path(output=...)): end it before writing another file", s->writer_file);
  ierr = AdhOutputOpen_Private(s, file, &viewer);
  if (!ierr) ierr = AdhOutputWriteFields_Private(s, viewer, PetscMax(s->curve.n - 1, 0));
  if (!ierr) ierr = PetscViewerHDF5WriteAttribute(viewer, "/", "complete", PETSC_BOOL, &(PetscBool){PETSC_TRUE});
  if (!ierr) ierr = AdhOutputClose_Private(s, file, &viewer);
  PetscCall(AdhOutputAbandon_Private(&viewer)); /* after a failed write: FILE.part as it is */
  PetscCall(ierr);
  PetscFunctionReturn(0);
}
