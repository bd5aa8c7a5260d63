/* Fields on the grid that come from the user: a topography, a work-of-adhesion map. They are
   read from a (Ny, Nx) .npy array or a 2-D HDF5 dataset, or handed over as a Vec, and checked
   here once (layout, shape, dtype, finite values) for every such input. Every check is
   collective, so all ranks fail together, and every message names the option and the file. */
#include <petscviewerhdf5.h>
#include "grid/gridimpl.h"

typedef enum { FIELD_MISSING, FIELD_NPY, FIELD_HDF5, FIELD_OTHER } FieldFormat;

/* Rank 0 opens the file and looks at its first bytes; all ranks learn the answer, so a missing
   or foreign file fails everywhere at once, before anyone starts reading. */
static PetscErrorCode FieldFormatOf(MPI_Comm comm, const char path[], int *format)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    FILE         *fp = fopen(path, "rb");
    unsigned char magic[6];

    if (!fp) *format = FIELD_MISSING;
    else {
      size_t n = fread(magic, 1, sizeof(magic), fp);
      fclose(fp);
      if (n == sizeof(magic) && !memcmp(magic, "\x93NUMPY", 6)) *format = FIELD_NPY;
      else *format = H5Fis_hdf5(path) > 0 ? FIELD_HDF5 : FIELD_OTHER;
    }
  }
  PetscCallMPI(MPI_Bcast(format, 1, MPI_INT, 0, comm));
  PetscFunctionReturn(0);
}

/* The .npy header is a Python dict literal such as
   {'descr': '<f8', 'fortran_order': False, 'shape': (64, 48), }. Only the three keys matter. */
static PetscErrorCode NpyParseHeader(AdhGrid grid, const char option[], const char path[], const char header[], int *itemsize)
{
  char        descr[16] = "";
  const char *s;
  long        shape[3];
  int         ndim = 0;
  PetscBool   fortran = PETSC_FALSE;

  PetscFunctionBegin;
  if ((s = strstr(header, "'descr':"))) sscanf(s + 8, " '%15[^']'", descr);
  if ((s = strstr(header, "'fortran_order':"))) {
    for (s += 16; *s == ' '; s++) {}
    fortran = !strncmp(s, "True", 4) ? PETSC_TRUE : PETSC_FALSE;
  }
  s = strstr(header, "'shape':");
  PetscCheck(s && (s = strchr(s, '(')), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s: the .npy header has no shape", option, path);
  /* A tuple of integers: (Ny, Nx), but also (N,) or (a, b, c), which must be refused. */
  for (s++;;) {
    char *end;
    long  v;
    while (*s == ' ' || *s == ',') s++;
    if (*s == ')' || !*s) break;
    v = strtol(s, &end, 10);
    PetscCheck(end != s, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s: cannot read the shape in the .npy header", option, path);
    if (ndim < 3) shape[ndim] = v;
    ndim++;
    s = end;
  }
  *itemsize = !strcmp(descr, "<f8") ? 8 : !strcmp(descr, "<f4") ? 4 : 0;
  PetscCheck(*itemsize, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s holds dtype '%s'; need little-endian float64 or float32 ('<f8' or '<f4')", option, path, descr);
  PetscCheck(!fortran, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s is Fortran-ordered; save it C-ordered (numpy.ascontiguousarray)", option, path);
  PetscCheck(ndim == 2, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s has %d dimension(s); need a 2-D array of shape (Ny, Nx) = (%" PetscInt_FMT ", %" PetscInt_FMT ")", option, path, ndim, grid->Ny, grid->Nx);
  PetscCheck(shape[0] == grid->Ny && shape[1] == grid->Nx, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s has shape (%ld, %ld); the grid needs (Ny, Nx) = (%" PetscInt_FMT ", %" PetscInt_FMT ")", option, path, shape[0], shape[1], grid->Ny, grid->Nx);
  PetscFunctionReturn(0);
}

/* Reads this rank's rows [ys, ys+ym) of the .npy array into v. Every rank parses the same
   header, so header errors happen on all ranks; the caller makes the outcome collective. */
static PetscErrorCode NpyLoadRows(AdhGrid grid, const char option[], const char path[], Vec v)
{
  FILE          *fp;
  unsigned char  pre[12];
  char          *header = NULL;
  size_t         lenbytes, hlen, n, got = 0;
  int            itemsize = 0;
  PetscInt       ys, ym;
  PetscScalar   *a;
  PetscBool      truncated = PETSC_FALSE;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(AdhGridGetOwnership(grid, &ys, &ym));
  n  = (size_t)ym * grid->Nx;
  fp = fopen(path, "rb");
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "%s: cannot open %s", option, path);
  /* Magic (6 bytes), version (2), header length: 2 bytes little-endian in version 1, 4 after. */
  lenbytes = fread(pre, 1, 8, fp) == 8 ? (pre[6] == 1 ? 2 : (pre[6] == 2 || pre[6] == 3) ? 4 : 0) : 0;
  if (!lenbytes || fread(pre + 8, 1, lenbytes, fp) != lenbytes) {
    fclose(fp);
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s: truncated .npy header or unknown .npy version", option, path);
  }
  hlen = pre[8] | ((size_t)pre[9] << 8);
  if (lenbytes == 4) hlen |= ((size_t)pre[10] << 16) | ((size_t)pre[11] << 24);
  ierr = PetscMalloc1(hlen + 1, &header);
  if (!ierr && fread(header, 1, hlen, fp) != hlen) truncated = PETSC_TRUE;
  if (!ierr && !truncated) {
    header[hlen] = 0;
    ierr = NpyParseHeader(grid, option, path, header, &itemsize);
  }
  if (!ierr && !truncated && fseek(fp, (long)(8 + lenbytes + hlen + (size_t)ys * grid->Nx * itemsize), SEEK_SET)) truncated = PETSC_TRUE;
  PetscCall(PetscFree(header));
  if (ierr || truncated) fclose(fp);
  PetscCall(ierr);
  PetscCheck(!truncated, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "%s: %s: truncated .npy file", option, path);
  /* The host is little-endian (x86, arm64), like the accepted dtypes. */
  PetscCall(VecGetArrayWrite(v, &a));
  if (itemsize == 8) {
    double *buf;
    PetscCall(PetscMalloc1(n + 1, &buf));
    got = fread(buf, 8, n, fp);
    for (size_t k = 0; k < got; k++) a[k] = buf[k];
    PetscCall(PetscFree(buf));
  } else {
    float *buf;
    PetscCall(PetscMalloc1(n + 1, &buf));
    got = fread(buf, 4, n, fp);
    for (size_t k = 0; k < got; k++) a[k] = buf[k];
    PetscCall(PetscFree(buf));
  }
  PetscCall(VecRestoreArrayWrite(v, &a));
  fclose(fp);
  PetscCheck(got == n, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "%s: %s is truncated: rows %" PetscInt_FMT "..%" PetscInt_FMT " are not all there", option, path, ys, ys + ym - 1);
  PetscFunctionReturn(0);
}

/* Reads the 2-D float dataset of an HDF5 file through PETSc's viewer (collective). */
static PetscErrorCode HDF5Load(AdhGrid grid, const char option[], const char path[], const char dataset[], Vec v)
{
  PetscViewer viewer;
  hid_t       file, dset, space, type;
  hsize_t     dims[3] = {0, 0, 0};
  int         ndims = -1;
  H5T_class_t cls   = H5T_NO_CLASS;
  PetscBool   has;
  const char *name;
  char        oldname[256];
  PetscErrorCode ierr;

  PetscFunctionBegin;
  /* a truncated or damaged file fails inside HDF5, whose message names neither option nor file */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = PetscViewerHDF5Open(grid->comm, path, FILE_MODE_READ, &viewer);
  if (!ierr) ierr = PetscViewerHDF5HasDataset(viewer, dataset, &has);
  if (ierr) (void)PetscViewerDestroy(&viewer); /* HDF5 cannot flush the file it did not open: ignored */
  PetscCall(PetscPopErrorHandler());
  PetscCheck(!ierr, grid->comm, PETSC_ERR_FILE_READ, "%s: %s is not a readable HDF5 file (truncated or damaged?)", option, path);
  if (!has) {
    PetscCall(PetscViewerDestroy(&viewer));
    SETERRQ(grid->comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s has no dataset '%s' (set %s_dataset)", option, path, dataset, option);
  }
  PetscCall(PetscViewerHDF5GetFileId(viewer, &file));
  dset = H5Dopen2(file, dataset, H5P_DEFAULT);
  if (dset >= 0) {
    space = H5Dget_space(dset);
    ndims = H5Sget_simple_extent_ndims(space);
    if (ndims >= 1 && ndims <= 3) H5Sget_simple_extent_dims(space, dims, NULL);
    H5Sclose(space);
    type = H5Dget_type(dset);
    cls  = H5Tget_class(type);
    H5Tclose(type);
    H5Dclose(dset);
  }
  if (cls != H5T_FLOAT || ndims != 2 || dims[0] != (hsize_t)grid->Ny || dims[1] != (hsize_t)grid->Nx) {
    PetscCall(PetscViewerDestroy(&viewer));
    PetscCheck(cls == H5T_FLOAT, grid->comm, PETSC_ERR_FILE_UNEXPECTED, "%s: dataset '%s' in %s is not floating point; need float64 or float32", option, dataset, path);
    SETERRQ(grid->comm, PETSC_ERR_FILE_UNEXPECTED, "%s: dataset '%s' in %s has %d dimension(s) (%llu, %llu); the grid needs (Ny, Nx) = (%" PetscInt_FMT ", %" PetscInt_FMT ")", option, dataset, path, ndims, (unsigned long long)dims[0], (unsigned long long)dims[1], grid->Ny, grid->Nx);
  }
  /* VecLoad reads the dataset named like the Vec; the Vec keeps its own name afterwards. */
  PetscCall(PetscObjectGetName((PetscObject)v, &name));
  PetscCall(PetscStrncpy(oldname, name, sizeof(oldname)));
  PetscCall(PetscObjectSetName((PetscObject)v, dataset[0] == '/' ? dataset + 1 : dataset));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = VecLoad(v, viewer);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscObjectSetName((PetscObject)v, oldname));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCheck(!ierr, grid->comm, PETSC_ERR_FILE_READ, "%s: dataset '%s' in %s cannot be read (truncated or damaged?)", option, dataset, path);
  PetscFunctionReturn(0);
}

/*@
  AdhFieldCheck - Checks that a vector has a grid's row layout and only finite values, so that all ranks agree

  Collective

  Input Parameters:
+ grid - the grid, set up
. what - what the vector is, named in the error messages
- v    - the vector

  Notes:
  The layout is that of `AdhGridCreateVector()`: Nx Ny entries in all, ym Nx (the rank's rows) on each rank. Every rank learns
  the outcome, so all fail together: a wrong layout is `PETSC_ERR_ARG_SIZ`, a NaN or Inf value `PETSC_ERR_ARG_WRONG`, a grid
  not set up `PETSC_ERR_ORDER`.

  Level: advanced

.seealso: `AdhFieldLoad()`, `AdhGridCreateVector()`, `AdhSolverSetTopography()`, `AdhSolverSetWorkOfAdhesionField()`
@*/
PetscErrorCode AdhFieldCheck(AdhGrid grid, const char what[], Vec v)
{
  PetscInt           N, n, ys, ym;
  const PetscScalar *a;
  int                ok[2] = {1, 1};

  PetscFunctionBegin;
  PetscValidHeaderSpecific(grid, ADH_GRID_CLASSID, 1);
  PetscValidCharPointer(what, 2);
  PetscValidHeaderSpecific(v, VEC_CLASSID, 3);
  PetscCheck(grid->setup, grid->comm, PETSC_ERR_ORDER, "%s: the grid is not set up yet", what);
  PetscCall(AdhGridGetOwnership(grid, &ys, &ym));
  PetscCall(VecGetSize(v, &N));
  PetscCall(VecGetLocalSize(v, &n));
  ok[0] = N == grid->Nx * grid->Ny && n == ym * grid->Nx;
  if (ok[0]) {
    PetscCall(VecGetArrayRead(v, &a));
    for (PetscInt k = 0; k < n; k++)
      if (PetscIsInfOrNanScalar(a[k])) ok[1] = 0;
    PetscCall(VecRestoreArrayRead(v, &a));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ok, 2, MPI_INT, MPI_MIN, grid->comm));
  PetscCheck(ok[0], grid->comm, PETSC_ERR_ARG_SIZ, "%s: the Vec does not have the grid's layout: global size %" PetscInt_FMT " (need Ny*Nx = %" PetscInt_FMT "), distributed by whole rows like the solver's fields", what, N, grid->Nx * grid->Ny);
  PetscCheck(ok[1], grid->comm, PETSC_ERR_ARG_WRONG, "%s holds NaN or Inf values", what);
  PetscFunctionReturn(0);
}

/*@
  AdhFieldLoad - Reads a (Ny, Nx) field on a grid from a .npy file or a dataset of an HDF5 file

  Collective

  Input Parameters:
+ grid    - the grid, set up
. option  - the option that named the file (such as "-adh_topography"), named in the error messages
. path    - the file: a C-ordered float64 or float32 .npy array, or an HDF5 file
- dataset - the name of the 2-D floating-point dataset in an HDF5 file (not used for a .npy file)

  Output Parameter:
. v - a vector with the grid's layout (`AdhGridCreateVector()`), which receives the field

  Notes:
  Rank 0 tells the format from the file's first bytes and every rank learns it, so a missing file or one that is neither .npy
  nor HDF5 fails everywhere at once. A .npy file must be little-endian ('<f8' or '<f4'), C-ordered, of version 1 to 3, with
  shape exactly (Ny, Nx); every rank reads its own rows, and a rank that fails makes every rank fail. An HDF5 dataset must
  exist, be floating point and have dimensions (Ny, Nx); it is read with `VecLoad()` through PETSc's HDF5 viewer, and v keeps
  its own name. Then `AdhFieldCheck()` checks the layout of v and that every value is finite. Every error names option and the
  file.

  Level: advanced

.seealso: `AdhFieldCheck()`, `AdhGridCreateVector()`, `AdhSolverSetTopography()`
@*/
PetscErrorCode AdhFieldLoad(AdhGrid grid, const char option[], const char path[], const char dataset[], Vec v)
{
  int  format;
  char what[PETSC_MAX_PATH_LEN + 64];

  PetscFunctionBegin;
  PetscValidHeaderSpecific(grid, ADH_GRID_CLASSID, 1);
  PetscValidCharPointer(option, 2);
  PetscValidHeaderSpecific(v, VEC_CLASSID, 5);
  PetscCheck(path && path[0], grid->comm, PETSC_ERR_ARG_WRONG, "%s: no file given", option);
  PetscCall(FieldFormatOf(grid->comm, path, &format));
  PetscCheck(format != FIELD_MISSING, grid->comm, PETSC_ERR_FILE_OPEN, "%s: cannot open %s", option, path);
  PetscCheck(format != FIELD_OTHER, grid->comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s is neither a .npy nor an HDF5 file", option, path);
  if (format == FIELD_NPY) {
    PetscErrorCode ierr = NpyLoadRows(grid, option, path, v);
    /* A rank that failed has said why; the others stop with it instead of waiting. */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ierr, 1, MPI_INT, MPI_MAX, grid->comm));
    PetscCall(ierr);
  } else PetscCall(HDF5Load(grid, option, path, dataset, v));
  PetscCall(PetscSNPrintf(what, sizeof(what), "%s: %s", option, path));
  PetscCall(AdhFieldCheck(grid, what, v));
  PetscFunctionReturn(0);
}
