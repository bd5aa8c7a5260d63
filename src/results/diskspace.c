/* Writes that fail: a full disk met before a state is written rather than in the middle of it, and
   a write that fails anyway turned into one error that names the file and the cause.

   Before the writes of a state (its fields, its curve rows), at the opening of a results file and
   of each checkpoint, rank 0 reserves the space they will take past the HDF5 file's end of
   allocation (fallocate, keeping the file's size). On a full disk or over a quota that fails with
   the system's reason while the file still holds every state written and flushed before, whole:
   HDF5 never meets the full disk half-way through an update, which would leave the file's
   metadata half-written (and Open MPI's MPI-IO crashing at exit on the file left open). Where the
   file system has no fallocate the reservation is skipped, and a failed write is caught as it
   comes (AdhOutputWriteEnd_Private), its cause taken from HDF5's innermost error. */
#if !defined(_GNU_SOURCE)
  #define _GNU_SOURCE /* fallocate */
#endif
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>
#include "results/resultsimpl.h"

/* What is reserved beyond the data itself: HDF5's chunk index, object headers and heaps. */
#define ADH_RESERVE_SLACK ((size_t)1 << 20)

/* Rank 0 reserves bytes (plus a quarter and a slack) past the end of the open HDF5 file part; every rank gets the system's error number (0: reserved, or the
   file system cannot reserve). Collective. */
PetscErrorCode AdhOutputReserve_Private(AdhSolver s, const char part[], size_t bytes, int *err)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  *err = 0;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  if (!rank) {
#if defined(__linux__) && defined(FALLOC_FL_KEEP_SIZE)
    struct stat st;
    int         fd = open(part, O_WRONLY);
    if (fd < 0) *err = errno;
    else if (fstat(fd, &st)) {
      *err = errno;
      close(fd);
    } else {
      /* from the file's end, which is HDF5's end of allocation after each flush (the MPI-IO driver
         extends the file to it); KEEP_SIZE: the blocks are the file's, its size (and HDF5's view
         of it) unchanged */
      if (fallocate(fd, FALLOC_FL_KEEP_SIZE, st.st_size, (off_t)(bytes + bytes / 4 + ADH_RESERVE_SLACK))) *err = errno;
      if (*err == EOPNOTSUPP || *err == ENOSYS || *err == EINTR) *err = 0; /* this file system cannot: the write will tell */
      close(fd);
    }
#else
    (void)part;
    (void)bytes;
#endif
  }
  PetscCallMPI(MPI_Bcast(err, 1, MPI_INT, 0, s->comm));
  PetscFunctionReturn(0);
}

/* Rank 0 gives back what the last reservation left beyond the end of the closed file part. */
PetscErrorCode AdhOutputReleaseReserve_Private(AdhSolver s, const char part[])
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  if (!rank) {
#if defined(__linux__) && defined(FALLOC_FL_PUNCH_HOLE)
    int         fd = open(part, O_WRONLY);
    struct stat st;
    if (fd >= 0) {
      if (!fstat(fd, &st)) {
        /* blocks past the end: tmpfs and XFS free them on a punched hole, ext4 on a truncation to the same size */
        (void)fallocate(fd, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE, st.st_size, (off_t)1 << 40);
        if (ftruncate(fd, st.st_size)) { /* nothing to give back */ }
      }
      close(fd);
    }
#else
    (void)part;
#endif
  }
  PetscFunctionReturn(0);
}

/* The writes of one phase (a state's fields or rows, a checkpoint) of file part for option begin:
   PETSc's error printing is held back, so that a failure inside them is told once, by
   AdhOutputWriteEnd_Private, with kept (what is left if it fails). discard: part holds nothing
   to keep if the phase fails (removed where a failing rank ends the job alone). */
PetscErrorCode AdhOutputWriteBegin_Private(AdhSolver s, const char option[], const char part[], const char kept[], PetscBool discard)
{
  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(s->writing, sizeof(s->writing), "%s: cannot write %s", option, part));
  PetscCall(PetscStrncpy(s->writing_part, part, sizeof(s->writing_part)));
  PetscCall(PetscStrncpy(s->writing_kept, kept ? kept : "", sizeof(s->writing_kept)));
  s->writing_discard = discard;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  PetscFunctionReturn(0);
}

/* The writes that began with AdhOutputWriteBegin_Private ended with ierr on this rank. If they
   failed on any rank: one error, on every rank, naming the option and the file with the cause
   (the lowest failing rank's: a full file system said as such, else HDF5's innermost words) and
   what the file still holds. Collective. */
PetscErrorCode AdhOutputWriteEnd_Private(AdhSolver s, PetscErrorCode ierr)
{
  const char *part = s->writing_part, *kept = s->writing_kept;

  char        cause[256] = "";
  PetscMPIInt rank, size, first;

  PetscFunctionBegin;
  PetscCall(PetscPopErrorHandler());
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  if (ierr) {
    struct statvfs fs;
    char           dir[PETSC_MAX_PATH_LEN], *slash;
    AdhH5Cause_Private(cause);
    PetscCall(PetscStrncpy(dir, part, sizeof(dir)));
    slash = strrchr(dir, '/');
    if (slash) *slash = 0;
    else PetscCall(PetscStrncpy(dir, ".", sizeof(dir)));
    /* MPI-IO says "input/output error" for a full disk too: the file system says it plainly */
    if (!statvfs(dir, &fs) && (size_t)fs.f_bavail * fs.f_frsize < ADH_RESERVE_SLACK) PetscCall(PetscStrncpy(cause, strerror(ENOSPC), sizeof(cause)));
  }
  {
    PetscBool any;
    PetscCall(AdhH5AgreeOnFailure_Private(s, (PetscBool)(ierr != 0), &any));
    if (!any) PetscFunctionReturn(0);
  }
  first = ierr ? rank : size;
  PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, s->comm));
  if (first == size) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Bcast(cause, sizeof(cause), MPI_CHAR, first, s->comm));
  SETERRQ(s->comm, PETSC_ERR_FILE_WRITE, "%s: %s%s%s", s->writing, cause, kept[0] ? "; " : "", kept);
}

/* What the results file part (FILE.part) that could not be written further still holds, for the
   error that says so. */
PetscErrorCode AdhOutputKept_Private(AdhSolver s, const char part[], char kept[], size_t len)
{
  char   file[PETSC_MAX_PATH_LEN + 8], csv[PETSC_MAX_PATH_LEN + 8], csvpart[PETSC_MAX_PATH_LEN + 16];
  size_t n;

  PetscFunctionBegin;
  PetscCall(PetscStrncpy(file, part, sizeof(file)));
  PetscCall(PetscStrlen(file, &n));
  if (n > 5 && !strcmp(file + n - 5, ".part")) file[n - 5] = 0;
  PetscCall(AdhOutputSiblingName_Private(file, "csv", csv, sizeof(csv)));
  PetscCall(AdhOutputPartName_Private(csv, csvpart, sizeof(csvpart)));
  if (s->rows_written) PetscCall(PetscSNPrintf(kept, len, "the %" PetscInt_FMT " states written before are in %s and %s (adhbem.load reads them)", s->rows_written, part, csvpart));
  else PetscCall(PetscSNPrintf(kept, len, "no state was written"));
  PetscFunctionReturn(0);
}

/* Rank 0 removes the file name (a file that holds nothing worth keeping). */
PetscErrorCode AdhOutputRemove_Private(AdhSolver s, const char name[])
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  if (!rank) (void)remove(name);
  PetscFunctionReturn(0);
}

static PetscBool ending_without_mpi = PETSC_FALSE;

/* Registered with PetscRegisterFinalize(): the process ends in PetscFinalize(), before MPI does. */
static PetscErrorCode EndWithoutMPIFinalize(void)
{
  fflush(NULL);
  _exit(1);
  return 0;
}

/* The HDF5 file open in *v, let go of after a failed write without touching the file on disk
   again: this rank's descriptors of it are first pointed at an anonymous file in memory, so that
   whatever HDF5 still writes goes there. The file on disk stays as the failed write left it
   (after a refused reservation: as after the last state).

   On one rank the file is then closed. On several it cannot be: after a failed write, parallel
   HDF5's close flushes its metadata cache with a barrier that the ranks whose cache is broken
   never reach (checked: a write failed on every rank before the file's first flush, and rank 0
   waits there for ever; HDF5 would try again at the end of MPI, with the same result). So the
   viewer is left open and the job ends in PetscFinalize(), before MPI's end, with status 1 on
   every rank: the error goes up and is told as usual first, and there is no MPI_Abort banner.
   Collective. */
PetscErrorCode AdhOutputAbandon_Private(PetscViewer *v)
{
  const char *part;
  MPI_Comm    comm;
  PetscMPIInt size;

  PetscFunctionBegin;
  if (!*v) PetscFunctionReturn(0);
  PetscCall(PetscViewerFileGetName(*v, &part));
#if defined(__linux__)
  {
    char real[PATH_MAX];
    int  sink = -1;
    DIR *fds  = opendir("/proc/self/fd");
    if (fds && realpath(part, real)) {
      struct dirent *e;
      while ((e = readdir(fds))) {
        char    link[64], target[PATH_MAX];
        ssize_t n;
        if (e->d_name[0] == '.') continue;
        snprintf(link, sizeof(link), "/proc/self/fd/%s", e->d_name);
        n = readlink(link, target, sizeof(target) - 1);
        if (n <= 0) continue;
        target[n] = 0;
        if (strcmp(target, real)) continue;
        if (sink < 0) sink = memfd_create("adhbem-abandoned", 0);
        if (sink >= 0) (void)dup2(sink, atoi(e->d_name));
      }
    }
    if (fds) closedir(fds);
    if (sink >= 0) close(sink);
  }
#endif
  PetscCall(PetscObjectGetComm((PetscObject)*v, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size > 1) {
    *v = NULL; /* not destroyed: its close is HDF5's */
    if (!ending_without_mpi) PetscCall(PetscRegisterFinalize(EndWithoutMPIFinalize));
    ending_without_mpi = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  {
    /* a write that failed half-way left its dataset or group open: HDF5 would keep the file open
       for it, and close it only as MPI ends */
    hid_t   file_id, ids[64];
    ssize_t n;
    PetscCall(PetscViewerHDF5GetFileId(*v, &file_id));
    while ((n = H5Fget_obj_ids(file_id, H5F_OBJ_DATASET | H5F_OBJ_GROUP | H5F_OBJ_DATATYPE | H5F_OBJ_ATTR | H5F_OBJ_LOCAL, 64, ids)) > 0) {
      ssize_t closed = 0;
      for (ssize_t k = 0; k < n; k++) {
        H5I_type_t type = H5Iget_type(ids[k]);
        closed += (type == H5I_ATTR ? H5Aclose(ids[k]) : type == H5I_DATATYPE ? H5Tclose(ids[k]) : H5Oclose(ids[k])) >= 0;
      }
      if (!closed) break;
    }
  }
  /* a close that fails (a write failed before the file's first flush) is retried by HDF5 as MPI
     ends, and fails quietly there on one rank */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  (void)PetscViewerDestroy(v);
  PetscCall(PetscPopErrorHandler());
  *v = NULL;
  PetscFunctionReturn(0);
}
