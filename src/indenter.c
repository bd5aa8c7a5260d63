/* Indenter profiles h(x,y): the gap between the undeformed bodies at indentation d = 0.
   Every built-in indenter has its apex on the centre of element (Nx/2, Ny/2). */
#include <petscviewerhdf5.h>
#include "indenter.h"

const char *const AdhIndenterTypes[] = {"sphere", "punch", "cone", "file", "rough", "AdhIndenterType", "ADH_INDENTER_", NULL};

/* Reads rows [ys, ys+ym) of a C-ordered (Ny, Nx) float64 or float32 .npy array. */
static PetscErrorCode LoadNpy(AdhGrid grid, const char *path, PetscScalar *rows, PetscInt ys, PetscInt ym)
{
  FILE          *fp;
  unsigned char  magic[8];
  char           header[4096], descr[16] = "";
  unsigned long  hlen;
  long           Ny = -1, Nx = -1;
  const char    *s;
  int            fortran = 0, itemsize;
  size_t         k, n = (size_t)ym * grid->Nx;

  PetscFunctionBegin;
  fp = fopen(path, "rb");
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "-adh_topography: cannot open %s", path);
  if (fread(magic, 1, 8, fp) != 8 || memcmp(magic, "\x93NUMPY", 6)) {
    fclose(fp);
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-adh_topography: %s is not a .npy file", path);
  }
  if (magic[6] == 1) {
    unsigned char b[2];
    PetscCheck(fread(b, 1, 2, fp) == 2, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "-adh_topography: %s: truncated header", path);
    hlen = b[0] | (b[1] << 8);
  } else {
    unsigned char b[4];
    PetscCheck(fread(b, 1, 4, fp) == 4, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "-adh_topography: %s: truncated header", path);
    hlen = b[0] | (b[1] << 8) | ((unsigned long)b[2] << 16) | ((unsigned long)b[3] << 24);
  }
  PetscCheck(hlen < sizeof(header) && fread(header, 1, hlen, fp) == hlen, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "-adh_topography: %s: bad .npy header", path);
  header[hlen] = 0;
  if ((s = strstr(header, "'descr':"))) sscanf(s + 8, " '%15[^']'", descr);
  if ((s = strstr(header, "'fortran_order':"))) {
    s += 16;
    while (*s == ' ') s++;
    fortran = !strncmp(s, "True", 4);
  }
  if ((s = strstr(header, "'shape':"))) sscanf(s + 8, " (%ld, %ld)", &Ny, &Nx);
  itemsize = !strcmp(descr, "<f8") ? 8 : !strcmp(descr, "<f4") ? 4 : 0;
  if (!itemsize || fortran || Ny != grid->Ny || Nx != grid->Nx) {
    fclose(fp);
    PetscCheck(itemsize, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-adh_topography: %s holds dtype '%s'; need float64 or float32", path, descr);
    PetscCheck(!fortran, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-adh_topography: %s is Fortran-ordered; save it C-ordered", path);
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-adh_topography: %s has shape (%ld, %ld); the grid needs (Ny, Nx) = (%" PetscInt_FMT ", %" PetscInt_FMT ")", path, Ny, Nx, grid->Ny, grid->Nx);
  }
  if (fseek(fp, (long)(8 + (magic[6] == 1 ? 2 : 4) + hlen + (size_t)ys * grid->Nx * itemsize), SEEK_SET)) {
    fclose(fp);
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "-adh_topography: %s is truncated", path);
  }
  if (itemsize == 8) {
    k = fread(rows, 8, n, fp);
  } else {
    float *tmp;
    PetscCall(PetscMalloc1(n, &tmp));
    k = fread(tmp, 4, n, fp);
    for (size_t m = 0; m < n; m++) rows[m] = tmp[m];
    PetscCall(PetscFree(tmp));
  }
  fclose(fp);
  PetscCheck(k == n, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "-adh_topography: %s is truncated", path);
  PetscFunctionReturn(0);
}

/* Reads a 2-D (Ny, Nx) dataset from an HDF5 file through PETSc's viewer. */
static PetscErrorCode LoadHDF5(AdhGrid grid, const char *path, const char *dataset, Vec h)
{
  PetscViewer viewer;
  hid_t       file, dset, space;
  hsize_t     dims[3] = {0, 0, 0};
  int         ndims = -1;
  PetscBool   has;

  PetscFunctionBegin;
  PetscCall(PetscViewerHDF5Open(grid->comm, path, FILE_MODE_READ, &viewer));
  PetscCall(PetscViewerHDF5HasDataset(viewer, dataset, &has));
  if (!has) {
    PetscCall(PetscViewerDestroy(&viewer));
    SETERRQ(grid->comm, PETSC_ERR_FILE_UNEXPECTED, "-adh_topography: %s has no dataset '%s' (set -adh_topography_dataset)", path, dataset);
  }
  PetscCall(PetscViewerHDF5GetFileId(viewer, &file));
  dset = H5Dopen2(file, dataset, H5P_DEFAULT);
  if (dset >= 0) {
    space = H5Dget_space(dset);
    ndims = H5Sget_simple_extent_ndims(space);
    if (ndims >= 1 && ndims <= 3) H5Sget_simple_extent_dims(space, dims, NULL);
    H5Sclose(space);
    H5Dclose(dset);
  }
  if (ndims != 2 || dims[0] != (hsize_t)grid->Ny || dims[1] != (hsize_t)grid->Nx) {
    PetscCall(PetscViewerDestroy(&viewer));
    SETERRQ(grid->comm, PETSC_ERR_FILE_UNEXPECTED, "-adh_topography: dataset '%s' in %s has %d dimension(s) (%llu, %llu); the grid needs (Ny, Nx) = (%" PetscInt_FMT ", %" PetscInt_FMT ")", dataset, path, ndims, (unsigned long long)dims[0], (unsigned long long)dims[1], grid->Ny, grid->Nx);
  }
  PetscCall(PetscObjectSetName((PetscObject)h, dataset[0] == '/' ? dataset + 1 : dataset));
  PetscCall(VecLoad(h, viewer));
  PetscCall(PetscObjectSetName((PetscObject)h, "h"));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhIndenterFill(AdhGrid grid, AdhIndenter *ind, Vec h)
{
  PetscScalar *ha;
  PetscInt     ys, ym, i, j;
  PetscBool    finite = PETSC_TRUE;

  PetscFunctionBegin;
  PetscCall(AdhGridGetOwnership(grid, &ys, &ym));
  if (ind->type == ADH_INDENTER_FILE) {
    const char *ext = strrchr(ind->topography, '.');
    PetscBool   exists;
    PetscCheck(ind->topography[0], grid->comm, PETSC_ERR_ARG_WRONG, "-adh_indenter file needs -adh_topography FILE (.npy or .h5)");
    PetscCall(PetscTestFile(ind->topography, 'r', &exists));
    PetscCheck(exists, grid->comm, PETSC_ERR_FILE_OPEN, "-adh_topography: cannot read %s", ind->topography);
    if (ext && !strcmp(ext, ".npy")) {
      PetscErrorCode ierr;
      PetscCall(VecGetArray(h, &ha));
      ierr = LoadNpy(grid, ind->topography, ha, ys, ym);
      PetscCall(VecRestoreArray(h, &ha));
      /* Every rank checks the same header, so all fail together; make that collective. */
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ierr, 1, MPI_INT, MPI_MAX, grid->comm));
      PetscCall(ierr);
    } else PetscCall(LoadHDF5(grid, ind->topography, ind->dataset, h));
  } else if (ind->type == ADH_INDENTER_ROUGH) {
    /* heights z, touched first at the highest peak: h = max(z) - z */
    PetscCall(AdhSurfaceGenerate(grid, &ind->surface, h));
    PetscCall(VecScale(h, -1.0));
    PetscCall(VecShift(h, ind->surface.max_height));
  } else {
    PetscCall(VecGetArray(h, &ha));
    for (j = ys; j < ys + ym; j++)
      for (i = 0; i < grid->Nx; i++) {
        PetscReal x, y, r;
        PetscCall(AdhGridGetCoordinates(grid, i, j, &x, &y));
        r = PetscSqrtReal(x * x + y * y);
        switch (ind->type) {
        case ADH_INDENTER_SPHERE: ha[(j - ys) * grid->Nx + i] = r * r / (2.0 * ind->radius); break;
        /* Outside the punch the gap is infinite: those points never touch. */
        case ADH_INDENTER_PUNCH: ha[(j - ys) * grid->Nx + i] = r <= ind->punch_radius ? 0.0 : PETSC_INFINITY; break;
        case ADH_INDENTER_CONE: ha[(j - ys) * grid->Nx + i] = ind->cone_slope * r; break;
        default: break;
        }
      }
    PetscCall(VecRestoreArray(h, &ha));
  }
  if (ind->type == ADH_INDENTER_FILE) {
    PetscInt n;
    PetscCall(VecGetLocalSize(h, &n));
    PetscCall(VecGetArray(h, &ha));
    for (i = 0; i < n; i++)
      if (PetscIsInfOrNanScalar(ha[i])) finite = PETSC_FALSE;
    PetscCall(VecRestoreArray(h, &ha));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &finite, 1, MPIU_BOOL, MPI_LAND, grid->comm));
    PetscCheck(finite, grid->comm, PETSC_ERR_FP, "-adh_topography: %s holds NaN or Inf values", ind->topography);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode AdhIndenterSetFromOptions(MPI_Comm comm, const char prefix[], AdhIndenter *ind)
{
  PetscFunctionBegin;
  PetscOptionsBegin(comm, prefix, "adhbem indenter", "AdhSolver");
  PetscCall(PetscOptionsEnum("-adh_indenter", "Indenter shape", "AdhSolver", AdhIndenterTypes, (PetscEnum)ind->type, (PetscEnum *)&ind->type, NULL));
  PetscCall(PetscOptionsReal("-adh_radius", "Sphere radius R (h = r^2/2R)", "AdhSolver", ind->radius, &ind->radius, NULL));
  PetscCall(PetscOptionsReal("-adh_punch_radius", "Flat punch radius a", "AdhSolver", ind->punch_radius, &ind->punch_radius, NULL));
  PetscCall(PetscOptionsReal("-adh_cone_slope", "Cone slope (h = slope r)", "AdhSolver", ind->cone_slope, &ind->cone_slope, NULL));
  PetscCall(PetscOptionsString("-adh_topography", "Topography file for -adh_indenter file: .npy (Ny, Nx) float64, or HDF5", "AdhSolver", ind->topography, ind->topography, sizeof(ind->topography), NULL));
  PetscCall(PetscOptionsString("-adh_topography_dataset", "Dataset name inside an HDF5 topography file", "AdhSolver", ind->dataset, ind->dataset, sizeof(ind->dataset), NULL));
  PetscOptionsEnd();
  if (ind->type == ADH_INDENTER_ROUGH) PetscCall(AdhSurfaceSetFromOptions(comm, prefix, &ind->surface));
  PetscCheck(ind->type != ADH_INDENTER_SPHERE || (ind->radius > 0 && PetscIsNormalReal(ind->radius)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_radius must be positive, got %g", (double)ind->radius);
  PetscCheck(ind->type != ADH_INDENTER_PUNCH || ind->punch_radius > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_punch_radius must be positive, got %g", (double)ind->punch_radius);
  PetscCheck(ind->type != ADH_INDENTER_CONE || ind->cone_slope > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_cone_slope must be positive, got %g", (double)ind->cone_slope);
  PetscFunctionReturn(0);
}
