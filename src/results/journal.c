#include <unistd.h>
#include "results/resultsimpl.h"

/* The journal FILE.csv.part: the curve as CSV (a step column, then one column per curve column),
   its header written when the results file is opened and a row appended and synced by rank 0
   after each recorded state; renamed FILE.csv when the run ends. */
static PetscErrorCode JournalName(const char file[], char name[], size_t len)
{
  char csv[PETSC_MAX_PATH_LEN + 8];

  PetscFunctionBegin;
  PetscCall(AdhOutputSiblingName_Private(file, "csv", csv, sizeof(csv)));
  PetscCall(AdhOutputPartName_Private(csv, name, len));
  PetscFunctionReturn(0);
}

/* Rank 0 writes and syncs rows [from, to) of the curve (from < 0: the header first); every rank
   learns whether it worked. */
PetscErrorCode AdhJournalWrite_Private(AdhSolver s, PetscInt from, PetscInt to)
{
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  if (!rank) {
    FILE *fp = s->journal;
    if (from < 0) {
      fprintf(fp, "step");
      for (PetscInt j = 0; j < AdhOutputNumColumns_Private(s); j++) fprintf(fp, ",%s", AdhOutputColumnName_Private(j));
      fprintf(fp, "\n");
      from = 0;
    }
    for (PetscInt k = from; k < to; k++) {
      fprintf(fp, "%" PetscInt_FMT, k);
      for (PetscInt j = 0; j < AdhOutputNumColumns_Private(s); j++) {
        if (AdhOutputColumnIsCount_Private(j)) fprintf(fp, ",%.0f", (double)AdhOutputColumnValue_Private(s, &s->curve.state[k], j));
        else fprintf(fp, ",%.17g", (double)AdhOutputColumnValue_Private(s, &s->curve.state[k], j));
      }
      fprintf(fp, "\n");
    }
    ok = fflush(fp) == 0 && !ferror(fp) && fsync(fileno(fp)) == 0;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_WRITE, "could not write the curve to %s", s->journal_name);
  PetscFunctionReturn(0);
}

/* A new journal for the results file `file`, with its header. */
PetscErrorCode AdhJournalOpen_Private(AdhSolver s, const char file[])
{
  char        name[PETSC_MAX_PATH_LEN + 16];
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(JournalName(file, name, sizeof(name)));
  PetscCall(PetscStrncpy(s->journal_name, name, sizeof(s->journal_name)));
  if (!rank) {
    if (s->journal) fclose(s->journal);
    s->journal = fopen(name, "w");
    ok         = s->journal != NULL;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_OPEN, "-adh_output: cannot write %s", name);
  PetscCall(AdhJournalWrite_Private(s, -1, 0));
  PetscFunctionReturn(0);
}

/* FILE.csv.part closed and renamed FILE.csv. */
PetscErrorCode AdhJournalClose_Private(AdhSolver s, const char file[])
{
  char        name[PETSC_MAX_PATH_LEN + 16], csv[PETSC_MAX_PATH_LEN + 8];
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(JournalName(file, name, sizeof(name)));
  PetscCall(AdhOutputSiblingName_Private(file, "csv", csv, sizeof(csv)));
  if (!rank) {
    ok         = s->journal && fclose(s->journal) == 0;
    s->journal = NULL;
    ok         = ok && rename(name, csv) == 0;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: could not write %s", csv);
  PetscFunctionReturn(0);
}
