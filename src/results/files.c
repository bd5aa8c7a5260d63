/* The results layer's files: their names (FILE.part while written; FILE.csv and FILE.xmf beside
   FILE.h5), the check that a path can be written, and text files written whole or not at all. */
#include <errno.h>
#include <sys/stat.h>
#include <unistd.h>
#include "results/resultsimpl.h"

PetscErrorCode AdhOutputPartName_Private(const char file[], char part[], size_t len)
{
  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(part, len, "%s.part", file));
  PetscFunctionReturn(0);
}

/* FILE.h5 -> FILE.ext (csv, xmf); other names get .ext appended. */
PetscErrorCode AdhOutputSiblingName_Private(const char file[], const char ext[], char name[], size_t len)
{
  size_t n;

  PetscFunctionBegin;
  PetscCall(PetscStrlen(file, &n));
  if (n > 3 && !strcmp(file + n - 3, ".h5")) {
    PetscCall(PetscSNPrintf(name, len, "%.*s.%s", (int)(n - 3), file, ext));
  } else PetscCall(PetscSNPrintf(name, len, "%s.%s", file, ext));
  PetscFunctionReturn(0);
}

/* The folder dir and every missing folder above it, as `mkdir -p` makes them (the umask sets their
   permissions); a failure shows when the file is created in it. */
static void MakeFolders(char dir[])
{
  for (char *c = dir + 1;; c++) {
    if (*c && *c != '/') continue;
    const char keep = *c;
    *c              = 0;
    (void)mkdir(dir, 0777);
    *c = keep;
    if (!keep) break;
  }
}

/* Rank 0 makes the file's folders when they are missing, all levels (results/ in a fresh clone) and tries to
   create FILE.part (or checks that an existing one is writable); everyone learns the answer, so a
   bad path fails before any work with a message that names the option and the file. */
PetscErrorCode AdhOutputCheckWritable_Private(AdhSolver s, const char option[], const char file[])
{
  char        part[PETSC_MAX_PATH_LEN + 8], dir[PETSC_MAX_PATH_LEN], reason[256] = "";
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(AdhOutputPartName_Private(file, part, sizeof(part)));
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
        if (!exists) MakeFolders(dir); /* a failure shows in the fopen below */
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

/* Rank 0 writes a text file through body(s, h5, fp) to NAME.part and renames it NAME, so that a
   file is either whole or absent; every rank learns whether it worked. */
PetscErrorCode AdhOutputWriteTextFile_Private(AdhSolver s, const char name[], void (*body)(AdhSolver, const char h5[], FILE *), const char h5[])
{
  char        part[PETSC_MAX_PATH_LEN + 16];
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(AdhOutputPartName_Private(name, part, sizeof(part)));
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
