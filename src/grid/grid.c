/* The element grid: Nx x Ny rectangles of hx x hy, distributed by whole rows over the ranks. */
#include <fftw3-mpi.h>
#include "adhbem.h"

PetscErrorCode AdhGridCreate(MPI_Comm comm, AdhGrid *grid)
{
  AdhGrid g;

  PetscFunctionBegin;
  PetscCall(AdhInitializePackage());
  PetscCall(PetscNew(&g));
  g->comm = comm;
  g->Nx = g->Ny = 64;
  g->Lx = g->Ly = 1.0;
  g->fftw_effort = -1;
  g->fftw_timelimit = -2.0;
  g->row_types[0] = g->row_types[1] = MPI_DATATYPE_NULL;
  *grid = g;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridSetSizes(AdhGrid g, PetscInt Nx, PetscInt Ny, PetscReal Lx, PetscReal Ly)
{
  PetscFunctionBegin;
  PetscCheck(!g->setup, g->comm, PETSC_ERR_ORDER, "Cannot change the grid after AdhGridSetUp()");
  g->Nx = Nx; g->Ny = Ny; g->Lx = Lx; g->Ly = Ly;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridSetFromOptions(AdhGrid g)
{
  PetscInt  n[2] = {g->Nx, g->Ny}, nn = 2;
  PetscReal L[2] = {g->Lx, g->Ly};
  PetscInt  nLi = 2;
  PetscBool set;

  PetscFunctionBegin;
  PetscOptionsBegin(g->comm, g->prefix, "adhbem grid", "AdhGrid");
  PetscCall(PetscOptionsIntArray("-adh_n", "Grid points per side: N or Nx,Ny", "AdhGridSetSizes", n, &nn, &set));
  if (set) {
    PetscCheck(nn >= 1, g->comm, PETSC_ERR_ARG_WRONG, "-adh_n needs N or Nx,Ny");
    if (nn == 1) n[1] = n[0];
    g->Nx = n[0]; g->Ny = n[1];
  }
  PetscCall(PetscOptionsRealArray("-adh_size", "Domain side lengths: L or Lx,Ly", "AdhGridSetSizes", L, &nLi, &set));
  if (set) {
    PetscCheck(nLi >= 1, g->comm, PETSC_ERR_ARG_WRONG, "-adh_size needs L or Lx,Ly");
    if (nLi == 1) L[1] = L[0];
    g->Lx = L[0]; g->Ly = L[1];
  }
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridSetUp(AdhGrid g)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  if (g->setup) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_size(g->comm, &size));
  PetscCheck(g->Nx > 0 && g->Ny > 0, g->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_n: grid points per side must be positive, got %" PetscInt_FMT ",%" PetscInt_FMT, g->Nx, g->Ny);
  PetscCheck(g->Lx > 0 && g->Ly > 0 && PetscIsNormalReal(g->Lx) && PetscIsNormalReal(g->Ly), g->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_size: domain side lengths must be positive and finite, got %g,%g", (double)g->Lx, (double)g->Ly);
  PetscCheck(g->Ny >= size, g->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_n: %" PetscInt_FMT " rows cannot be shared by %d ranks (every rank owns at least one row); use fewer ranks or a larger Ny", g->Ny, size);
  g->hx = g->Lx / g->Nx;
  g->hy = g->Ly / g->Ny;
  /* Each rank owns whole rows, so the global ordering is the natural row-major one j*Nx + i, the
     same as FFTW's. The rows are split as FFTW-MPI splits those of an Ny x Nx transform, so an
     operator on the whole periodic grid reads and writes vectors in place, without a
     redistribution; where that split would leave a rank without rows, the rows are balanced to
     within one. A grid vector is a plain MPI Vec with block size Nx: a row per block, which
     PETSc's HDF5 viewer writes as an (Ny, Nx) dataset (a DMDA would add its ghost maps, about
     20 bytes per point, that nothing here uses). */
  {
    ptrdiff_t   n0, s0, n1, s1;
    PetscInt    rows, fewest, *ly;
    PetscMPIInt rank;

    PetscCall(AdhInitializePackage());
    PetscCallMPI(MPI_Comm_rank(g->comm, &rank));
    (void)fftw_mpi_local_size_2d_transposed(g->Ny, g->Nx / 2 + 1, g->comm, &n0, &s0, &n1, &s1);
    rows = (PetscInt)n0;
    PetscCall(PetscMalloc1(size, &ly));
    PetscCallMPI(MPI_Allgather(&rows, 1, MPIU_INT, ly, 1, MPIU_INT, g->comm));
    fewest = ly[0];
    for (PetscMPIInt r = 1; r < size; r++) fewest = PetscMin(fewest, ly[r]);
    if (fewest <= 0)
      for (PetscMPIInt r = 0; r < size; r++) ly[r] = g->Ny / size + (g->Ny % size > r ? 1 : 0);
    g->ys = 0;
    for (PetscMPIInt r = 0; r < rank; r++) g->ys += ly[r];
    g->ym = ly[rank];
    PetscCall(PetscFree(ly));
  }
  g->setup = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridGetOwnership(AdhGrid g, PetscInt *ys, PetscInt *ym)
{
  PetscFunctionBegin;
  PetscCheck(g->setup, g->comm, PETSC_ERR_ORDER, "AdhGridSetUp() first");
  if (ys) *ys = g->ys;
  if (ym) *ym = g->ym;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridGetRowsPerRank(AdhGrid g, PetscInt **ly)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCheck(g->setup, g->comm, PETSC_ERR_ORDER, "AdhGridSetUp() first");
  PetscCallMPI(MPI_Comm_size(g->comm, &size));
  PetscCall(PetscMalloc1(size, ly));
  PetscCallMPI(MPI_Allgather(&g->ym, 1, MPIU_INT, *ly, 1, MPIU_INT, g->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridCreateRowSF(AdhGrid g, PetscInt nrows, const PetscInt rows[], PetscSF *sf)
{
  PetscInt    *ly, *start;
  PetscMPIInt  size;
  PetscSFNode *owner;

  PetscFunctionBegin;
  PetscCall(AdhGridGetRowsPerRank(g, &ly));
  PetscCallMPI(MPI_Comm_size(g->comm, &size));
  PetscCall(PetscMalloc1(size + 1, &start));
  start[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) start[r + 1] = start[r] + ly[r];
  PetscCall(PetscMalloc1(nrows, &owner));
  for (PetscInt q = 0; q < nrows; q++) {
    PetscMPIInt o = 0;
    PetscCheck(rows[q] >= 0 && rows[q] < g->Ny, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Row %" PetscInt_FMT " is not on the grid of %" PetscInt_FMT " rows", rows[q], g->Ny);
    while (start[o + 1] <= rows[q]) o++; /* ranks without rows are passed over */
    owner[q].rank  = o;
    owner[q].index = rows[q] - start[o];
  }
  PetscCall(PetscSFCreate(g->comm, sf));
  PetscCall(PetscSFSetGraph(*sf, g->ym, nrows, NULL, PETSC_OWN_POINTER, owner, PETSC_OWN_POINTER));
  PetscCall(PetscSFSetUp(*sf));
  PetscCall(PetscFree(start));
  PetscCall(PetscFree(ly));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridGetRowType(AdhGrid g, MPI_Datatype base, MPI_Datatype *row)
{
  const PetscInt k = base == MPIU_SCALAR ? 0 : base == MPI_CHAR ? 1 : -1;

  PetscFunctionBegin;
  PetscCheck(g->setup, g->comm, PETSC_ERR_ORDER, "AdhGridSetUp() first");
  PetscCheck(k >= 0, g->comm, PETSC_ERR_SUP, "A grid row of MPIU_SCALAR or MPI_CHAR only");
  if (g->row_types[k] == MPI_DATATYPE_NULL) {
    PetscCallMPI(MPI_Type_contiguous((PetscMPIInt)g->Nx, base, &g->row_types[k]));
    PetscCallMPI(MPI_Type_commit(&g->row_types[k]));
  }
  *row = g->row_types[k];
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridCreateVector(AdhGrid g, Vec *v)
{
  PetscFunctionBegin;
  PetscCall(AdhGridSetUp(g));
  PetscCall(VecCreate(g->comm, v));
  PetscCall(VecSetSizes(*v, g->ym * g->Nx, g->Nx * g->Ny));
  PetscCall(VecSetBlockSize(*v, g->Nx));
  PetscCall(VecSetType(*v, VECSTANDARD));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridGetCoordinates(AdhGrid g, PetscInt i, PetscInt j, PetscReal *x, PetscReal *y)
{
  PetscFunctionBegin;
  if (x) *x = (i - g->Nx / 2) * g->hx;
  if (y) *y = (j - g->Ny / 2) * g->hy;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridView(AdhGrid g, PetscViewer viewer)
{
  PetscBool   isascii;
  PetscMPIInt size;

  PetscFunctionBegin;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(g->comm, &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  PetscCallMPI(MPI_Comm_size(g->comm, &size));
  if (isascii) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "AdhGrid: %" PetscInt_FMT " x %" PetscInt_FMT " elements of %g x %g, domain %g x %g, %d rank(s)\n", g->Nx, g->Ny, (double)g->hx, (double)g->hy, (double)g->Lx, (double)g->Ly, size));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode AdhGridDestroy(AdhGrid *grid)
{
  PetscFunctionBegin;
  if (!*grid) PetscFunctionReturn(0);
  PetscCall(AdhTransformRelease_Private(&(*grid)->transforms[0]));
  PetscCall(AdhTransformRelease_Private(&(*grid)->transforms[1]));
  for (PetscInt k = 0; k < 2; k++)
    if ((*grid)->row_types[k] != MPI_DATATYPE_NULL) PetscCallMPI(MPI_Type_free(&(*grid)->row_types[k]));
  PetscCall(PetscFree(*grid));
  PetscFunctionReturn(0);
}
