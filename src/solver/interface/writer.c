/* A results file written state by state from a loop of the caller's (AdhSolverStart() and
   AdhSolverStep(), Python's iterate_path()): the file AdhSolverSolvePath() writes for -adh_output,
   with every state's row and, with -adh_fields, its fields, flushed as each state is recorded. */
#include "solver/solverimpl.h"

/*@
  AdhSolverOutputBegin - Opens a results file that the states recorded from now on go into, one by one

  Collective

  Input Parameters:
+ s    - the solver, set up
- file - the results file, FILE.h5 (and FILE.csv; FILE.xmf with fields), written as FILE.part until `AdhSolverOutputEnd()`

  Level: intermediate

  Notes:
  The rows already in the curve are written at once (without fields). After each recorded state call
  `AdhSolverOutputRecord()`; after the last, `AdhSolverOutputEnd()`. Whatever ends the job, FILE.h5.part and FILE.csv.part
  hold every state recorded before, as with -adh_output. `AdhSolverDestroy()` ends an open file, marked incomplete.

.seealso: `AdhSolverOutputRecord()`, `AdhSolverOutputEnd()`, `AdhSolverWriteOutput()`, `AdhSolverSolvePath()`
@*/
PetscErrorCode AdhSolverOutputBegin(AdhSolver s, const char file[])
{
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidCharPointer(file, 2);
  PetscCheck(!s->writer, s->comm, PETSC_ERR_ORDER, "AdhSolverOutputBegin: %s is open still (end it with AdhSolverOutputEnd())", s->writer_file);
  PetscCall(AdhSolverSetUp(s));
  s->output_failed = PETSC_FALSE;
  PetscCall(AdhResults.open(s, file, &s->writer));
  PetscCall(PetscStrncpy(s->writer_file, file, sizeof(s->writer_file)));
  ierr = AdhResults.append(s, s->writer);
  if (ierr) PetscCall(AdhSolverOutputEnd(s, PETSC_FALSE));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

/*@
  AdhSolverOutputRecord - Writes the states recorded since the last call into the file of `AdhSolverOutputBegin()`

  Collective

  Input Parameter:
. s - the solver

  Level: intermediate

  Note:
  With -adh_fields the last state's fields go in too (every -adh_fields_stride-th state), so call it after each
  recorded state, while its fields are current. A failed write ends the file (FILE.part, whole to the states before) and
  is the error.

.seealso: `AdhSolverOutputBegin()`, `AdhSolverOutputEnd()`
@*/
PetscErrorCode AdhSolverOutputRecord(AdhSolver s)
{
  PetscErrorCode ierr = 0;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscCheck(s->writer, s->comm, PETSC_ERR_ORDER, "AdhSolverOutputRecord: no results file is open (AdhSolverOutputBegin())");
  if (s->curve.n > 0 && (s->curve.n - 1) % s->fields_stride == 0) ierr = AdhResults.write_fields(s, s->writer, s->curve.n - 1);
  if (!ierr) ierr = AdhResults.append(s, s->writer);
  if (ierr) PetscCall(AdhSolverOutputEnd(s, PETSC_FALSE));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

/*@
  AdhSolverOutputEnd - Closes the file of `AdhSolverOutputBegin()` under its name

  Collective

  Input Parameters:
+ s        - the solver
- complete - whether the states written are the whole run (the root attribute `complete`)

  Level: intermediate

  Note:
  FILE.h5, FILE.csv (and FILE.xmf) replace FILE.part. After a failed write the file stays FILE.h5.part, as it was; nothing
  to do if no file is open.

.seealso: `AdhSolverOutputBegin()`, `AdhSolverOutputRecord()`
@*/
PetscErrorCode AdhSolverOutputEnd(AdhSolver s, PetscBool complete)
{
  PetscErrorCode ierr = 0;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidLogicalCollectiveBool(s, complete, 2);
  if (!s->writer) PetscFunctionReturn(0);
  if (!s->output_failed) {
    ierr = PetscViewerHDF5WriteAttribute(s->writer, "/", "complete", PETSC_BOOL, &complete);
    if (!ierr) ierr = AdhResults.close(s, s->writer_file, &s->writer);
  }
  PetscCall(AdhResults.abandon(&s->writer)); /* after a failed write: FILE.part as it is */
  s->writer_file[0] = 0;
  PetscCall(ierr);
  PetscFunctionReturn(0);
}
