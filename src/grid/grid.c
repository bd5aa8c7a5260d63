/* The element grid: Nx x Ny rectangles of hx x hy, distributed by whole rows over the ranks. */
#include "grid/gridimpl.h"
#include "sys/sysimpl.h"

/*@
  AdhGridCreate - Creates a grid of Nx x Ny rectangular elements, to be distributed by whole rows over the ranks of a communicator

  Collective

  Input Parameter:
. comm - the MPI communicator

  Output Parameter:
. grid - the new grid

  Notes:
  The grid starts as 64 x 64 elements on a 1 x 1 domain: set its sizes with `AdhGridSetSizes()` or `AdhGridSetFromOptions()`,
  then call `AdhGridSetUp()`, which distributes the rows. It initialises the package (`AdhInitializePackage()`) if needed.

  Every rank of comm must call it: the PETSc object's header duplicates the communicator, and the later calls on the grid
  are collective. The grid is a PETSc object of class "AdhGrid" (`ADH_GRID_CLASSID`): it can be named, referenced (`PetscObjectReference()`) and
  viewed like any, and -info :adhgrid shows its messages. It is not a `DM`: its layout is FFTW-MPI's slabs of whole rows,
  and what it serves (row star forests of any width, the transforms its operators share) is not what a `DMDA` offers,
  whose ghost maps would cost about 20 bytes a point that nothing here uses. It also keeps comm as it is, for FFTW-MPI:
  comm must stay valid while the grid lives.

  Level: intermediate

.seealso: `AdhGridSetSizes()`, `AdhGridSetFromOptions()`, `AdhGridSetUp()`, `AdhGridView()`, `AdhGridDestroy()`
@*/
PetscErrorCode AdhGridCreate(MPI_Comm comm, AdhGrid *grid)
{
  AdhGrid g;

  PetscFunctionBegin;
  PetscValidPointer(grid, 2);
  PetscCall(AdhInitializePackage());
  PetscCall(PetscHeaderCreate(g, ADH_GRID_CLASSID, "AdhGrid", "Element grid distributed by rows", "AdhGrid", comm, AdhGridDestroy, AdhGridView));
  g->ops->view = AdhGridView;
  PetscCall(PetscObjectChangeTypeName((PetscObject)g, "slabs")); /* one kind of grid: whole rows per rank, FFTW-MPI's slabs */
  g->comm = comm;
  g->Nx = g->Ny = 64;
  g->Lx = g->Ly = 1.0;
  g->fftw_effort = -1;
  g->fftw_timelimit = -2.0;
  g->opt_planner   = 1; /* measure */
  g->opt_timelimit = -1.0;
  g->opt_layout    = ADH_FFTW_LAYOUT_AUTO;
  g->row_types[0] = g->row_types[1] = MPI_DATATYPE_NULL;
  *grid = g;
  PetscFunctionReturn(0);
}

/*@
  AdhGridSetSizes - Sets the number of elements per side and the side lengths of a grid's domain

  Logically Collective; Nx, Ny, Lx and Ly must have the same values on every rank

  Input Parameters:
+ g  - the grid, not yet set up
. Nx - the number of elements along x (the points of a row)
. Ny - the number of elements along y (the rows, the distributed direction)
. Lx - the side length of the domain along x
- Ly - the side length of the domain along y

  Notes:
  The values are checked by `AdhGridSetUp()`, which also sets the element sizes hx = Lx/Nx and hy = Ly/Ny: Nx and Ny positive,
  Lx and Ly positive and finite, and at least as many rows as ranks. Once the grid is set up its sizes cannot change
  (`PETSC_ERR_ORDER`).

  Level: intermediate

.seealso: `AdhGridCreate()`, `AdhGridSetFromOptions()`, `AdhGridSetUp()`
@*/
PetscErrorCode AdhGridSetSizes(AdhGrid g, PetscInt Nx, PetscInt Ny, PetscReal Lx, PetscReal Ly)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  PetscValidLogicalCollectiveInt(g, Nx, 2);
  PetscValidLogicalCollectiveInt(g, Ny, 3);
  PetscValidLogicalCollectiveReal(g, Lx, 4);
  PetscValidLogicalCollectiveReal(g, Ly, 5);
  PetscCheck(!g->setup, g->comm, PETSC_ERR_ORDER, "Cannot change the grid after AdhGridSetUp()");
  g->Nx = Nx; g->Ny = Ny; g->Lx = Lx; g->Ly = Ly;
  PetscFunctionReturn(0);
}

/*@
  AdhGridSetFromOptions - Sets a grid's sizes, and how the FFTs of its operators are planned, from the options database

  Collective

  Input Parameter:
. g - the grid

  Options Database Keys:
+ -adh_n <N or Nx,Ny>     - the number of elements per side: one value for both sides, or two
. -adh_size <L or Lx,Ly>  - the side lengths of the domain: one value for both sides, or two
. -adh_fftw_planner <estimate,measure,patient,exhaustive> - FFTW planner effort of the grid's operators (default measure)
. -adh_fftw_timelimit <seconds> - how long FFTW may plan one transform on one rank (negative: no limit)
- -adh_fftw_layout <auto,serial,transposed> - plans on one rank: FFTW's serial ones, FFTW-MPI's transposed ones, or chosen by size
                                              (and timing); several ranks always use FFTW-MPI's

  Notes:
  The options are read under the grid's options prefix (the solver's, for the grid of an `AdhSolver`); an option given without
  a value is an error. The sizes are checked by `AdhGridSetUp()`. The operators made on the grid afterwards
  (`MatCreateAdhCompliance()`, `MatCreateAdhPeriodicStiffness()`) plan their transforms as the FFTW options say; they read no
  options themselves.

  Call it before `AdhGridSetUp()`: unlike `AdhGridSetSizes()`, it does not check that the grid is not set up yet.

  Level: intermediate

.seealso: `AdhGridCreate()`, `AdhGridSetSizes()`, `AdhGridSetUp()`
@*/
PetscErrorCode AdhGridSetFromOptions(AdhGrid g)
{
  static const char *const planners[] = {"estimate", "measure", "patient", "exhaustive", "AdhPlanner", "", NULL};
  PetscInt  n[2], nn = 2;
  PetscReal L[2];
  PetscInt  nLi = 2;
  PetscBool set;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  n[0] = g->Nx, n[1] = g->Ny, L[0] = g->Lx, L[1] = g->Ly;
  PetscOptionsBegin(g->comm, g->prefix, "adhbem grid", "AdhGrid");
  PetscCall(AdhOptionsIntArray("-adh_n", "Grid points per side: N or Nx,Ny", "AdhGridSetSizes", n, &nn, &set));
  if (set) {
    PetscCheck(nn >= 1, g->comm, PETSC_ERR_ARG_WRONG, "-adh_n needs N or Nx,Ny");
    if (nn == 1) n[1] = n[0];
    g->Nx = n[0]; g->Ny = n[1];
  }
  PetscCall(AdhOptionsRealArray("-adh_size", "Domain side lengths: L or Lx,Ly", "AdhGridSetSizes", L, &nLi, &set));
  if (set) {
    PetscCheck(nLi >= 1, g->comm, PETSC_ERR_ARG_WRONG, "-adh_size needs L or Lx,Ly");
    if (nLi == 1) L[1] = L[0];
    g->Lx = L[0]; g->Ly = L[1];
  }
  PetscCall(PetscOptionsEList("-adh_fftw_planner", "FFTW planner effort", "AdhGridSetFromOptions", planners, 4, planners[g->opt_planner], &g->opt_planner, NULL));
  PetscCall(AdhOptionsReal("-adh_fftw_timelimit", "Seconds FFTW may spend planning one transform on one rank (negative: no limit)", "AdhGridSetFromOptions", g->opt_timelimit, &g->opt_timelimit, &set));
  if (set) g->opt_timelimit_set = PETSC_TRUE;
  PetscCall(PetscOptionsEnum("-adh_fftw_layout", "Plans on one rank: FFTW's serial ones, FFTW-MPI's transposed ones, or chosen by size (and timing)", "AdhGridSetFromOptions", AdhFFTWLayouts, (PetscEnum)g->opt_layout, (PetscEnum *)&g->opt_layout, NULL));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/*@
  AdhGridSetUp - Checks a grid's sizes and distributes its rows over the ranks

  Collective

  Input Parameter:
. g - the grid

  Notes:
  It checks that Nx and Ny are positive, that Lx and Ly are positive and finite and that there are at least as many rows as ranks
  (every rank owns at least one row); it sets the element sizes hx = Lx/Nx and hy = Ly/Ny and gives each rank a range of
  whole rows, in rank order. The rows are split as FFTW-MPI splits those of an Ny x Nx real-to-complex transform, so that the
  operators on the periodic grid use grid vectors in place; where that split would leave a rank without rows, the rows are
  balanced to within one instead. A grid that is set up already is left as it is.

  Level: intermediate

.seealso: `AdhGridCreate()`, `AdhGridSetSizes()`, `AdhGridGetOwnership()`, `AdhGridGetRowsPerRank()`, `AdhGridCreateVector()`
@*/
PetscErrorCode AdhGridSetUp(AdhGrid g)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
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

/*@
  AdhGridGetOwnership - Gets the range of rows of a grid that this rank owns

  Not Collective

  Input Parameter:
. g - the grid, set up

  Output Parameters:
+ ys - the first row this rank owns (or `NULL`)
- ym - the number of rows it owns (or `NULL`)

  Notes:
  This rank owns the points (i, j) with j in [ys, ys + ym) and every i in [0, Nx): the entries [ys Nx, (ys + ym) Nx) of a grid
  vector, whose global ordering is j Nx + i.

  Level: intermediate

.seealso: `AdhGridSetUp()`, `AdhGridGetRowsPerRank()`, `AdhGridCreateVector()`
@*/
PetscErrorCode AdhGridGetOwnership(AdhGrid g, PetscInt *ys, PetscInt *ym)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  PetscCheck(g->setup, g->comm, PETSC_ERR_ORDER, "AdhGridSetUp() first");
  if (ys) *ys = g->ys;
  if (ym) *ym = g->ym;
  PetscFunctionReturn(0);
}

/*@
  AdhGridGetRowsPerRank - Gets the number of rows that every rank of a grid owns

  Collective

  Input Parameter:
. g - the grid, set up

  Output Parameter:
. ly - an array of the communicator's size: the number of rows of each rank, in rank order

  Notes:
  The array is allocated here: free it with `PetscFree()`. The ranks own consecutive ranges of rows in rank order, so a rank's
  first row is the sum of ly over the ranks before it.

  Level: developer

.seealso: `AdhGridGetOwnership()`, `AdhGridCreateRowSF()`
@*/
PetscErrorCode AdhGridGetRowsPerRank(AdhGrid g, PetscInt **ly)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  PetscValidPointer(ly, 2);
  PetscCheck(g->setup, g->comm, PETSC_ERR_ORDER, "AdhGridSetUp() first");
  PetscCallMPI(MPI_Comm_size(g->comm, &size));
  PetscCall(PetscMalloc1(size, ly));
  PetscCallMPI(MPI_Allgather(&g->ym, 1, MPIU_INT, *ly, 1, MPIU_INT, g->comm));
  PetscFunctionReturn(0);
}

/*@
  AdhGridCreateRowSF - Creates a star forest that fetches whole rows of grid data from the ranks that own them

  Collective

  Input Parameters:
+ g     - the grid, set up
. nrows - the number of rows this rank asks for
- rows  - the global rows, in [0, Ny), that this rank asks for (usually rows that other ranks own); a row may be listed more
          than once

  Output Parameter:
. sf - the star forest

  Notes:
  The unit of the star forest is a whole row: it has one root per row this rank owns, in order, and one leaf per entry of
  rows[], in the order given (contiguous leaves). Communicate with it in the row type of `AdhGridGetRowType()`: `MPIU_SCALAR`
  for the rows of a grid vector's array, `MPI_CHAR` for a byte per point. The grid keeps the type; destroy the star forest with
  `PetscSFDestroy()`.

  A row outside [0, Ny) is an error raised on the rank that lists it (`PETSC_COMM_SELF`).

  Level: developer

.seealso: `AdhGridGetRowType()`, `AdhGridGetRowsPerRank()`, `AdhGridGetOwnership()`, `PetscSFBcastBegin()`
@*/
PetscErrorCode AdhGridCreateRowSF(AdhGrid g, PetscInt nrows, const PetscInt rows[], PetscSF *sf)
{
  PetscInt    *ly, *start;
  PetscMPIInt  size;
  PetscSFNode *owner;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  if (nrows) PetscValidIntPointer(rows, 3);
  PetscValidPointer(sf, 4);
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

/*@
  AdhGridGetRowType - Gets the MPI datatype of one row of a grid: Nx contiguous values of a base type

  Not Collective

  Input Parameters:
+ g    - the grid, set up
- base - the type of one value: `MPIU_SCALAR` or `MPI_CHAR`

  Output Parameter:
. row - the committed datatype of a row

  Notes:
  The type is made on first use and kept by the grid, which frees it in `AdhGridDestroy()`: do not free it. It is the unit of
  the star forests of `AdhGridCreateRowSF()`. Any other base type is an error (`PETSC_ERR_SUP`).

  Level: developer

.seealso: `AdhGridCreateRowSF()`, `AdhGridDestroy()`
@*/
PetscErrorCode AdhGridGetRowType(AdhGrid g, MPI_Datatype base, MPI_Datatype *row)
{
  const PetscInt k = base == MPIU_SCALAR ? 0 : base == MPI_CHAR ? 1 : -1;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  PetscValidPointer(row, 3);
  PetscCheck(g->setup, g->comm, PETSC_ERR_ORDER, "AdhGridSetUp() first");
  PetscCheck(k >= 0, g->comm, PETSC_ERR_SUP, "A grid row of MPIU_SCALAR or MPI_CHAR only");
  if (g->row_types[k] == MPI_DATATYPE_NULL) {
    PetscCallMPI(MPI_Type_contiguous((PetscMPIInt)g->Nx, base, &g->row_types[k]));
    PetscCallMPI(MPI_Type_commit(&g->row_types[k]));
  }
  *row = g->row_types[k];
  PetscFunctionReturn(0);
}

/*@
  AdhGridCreateVector - Creates a vector on a grid, with the rows of each rank

  Collective

  Input Parameter:
. g - the grid; it is set up here if it is not yet

  Output Parameter:
. v - the new vector, its values not set

  Notes:
  The vector is a `VECSTANDARD` of Nx Ny entries in the order j Nx + i, ym Nx of them on each rank (its rows, see
  `AdhGridGetOwnership()`), with block size Nx, a block per row: PETSc's HDF5 viewer writes it as an (Ny, Nx) dataset. It has
  the layout of the grid's operators, such as `MatCreateAdhCompliance()`. Destroy it with `VecDestroy()`.

  Level: intermediate

.seealso: `AdhGridGetOwnership()`, `AdhGridGetCoordinates()`, `AdhFieldCheck()`, `MatCreateAdhCompliance()`
@*/
PetscErrorCode AdhGridCreateVector(AdhGrid g, Vec *v)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  PetscValidPointer(v, 2);
  PetscCall(AdhGridSetUp(g));
  PetscCall(VecCreate(g->comm, v));
  PetscCall(VecSetSizes(*v, g->ym * g->Nx, g->Nx * g->Ny));
  PetscCall(VecSetBlockSize(*v, g->Nx));
  PetscCall(VecSetType(*v, VECSTANDARD));
  PetscFunctionReturn(0);
}

/*@
  AdhGridGetCoordinates - Gets the centre of an element of a grid

  Not Collective

  Input Parameters:
+ g - the grid, set up
. i - the element's column, in [0, Nx)
- j - the element's row, in [0, Ny)

  Output Parameters:
+ x - the x coordinate of its centre (or `NULL`)
- y - the y coordinate of its centre (or `NULL`)

  Notes:
  x = (i - Nx/2) hx and y = (j - Ny/2) hy, with integer division: the centre of element (Nx/2, Ny/2) is the origin. Neither the
  indices nor the set-up are checked; before `AdhGridSetUp()` the element sizes, and so the coordinates, are zero.

  Level: intermediate

.seealso: `AdhGridGetOwnership()`, `AdhGridSetSizes()`
@*/
PetscErrorCode AdhGridGetCoordinates(AdhGrid g, PetscInt i, PetscInt j, PetscReal *x, PetscReal *y)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  if (x) *x = (i - g->Nx / 2) * g->hx;
  if (y) *y = (j - g->Ny / 2) * g->hy;
  PetscFunctionReturn(0);
}

/*@
  AdhGridGetSizes - Gets the number of elements per side and the side lengths of a grid's domain

  Not Collective

  Input Parameter:
. g - the grid

  Output Parameters:
+ Nx - the number of elements along x, the points of a row (or `NULL`)
. Ny - the number of elements along y, the rows (or `NULL`)
. Lx - the side length of the domain along x (or `NULL`)
- Ly - the side length of the domain along y (or `NULL`)

  Level: beginner

.seealso: `AdhGridSetSizes()`, `AdhGridGetSpacing()`, `AdhGridGetOwnership()`, `AdhSolverGetGrid()`
@*/
PetscErrorCode AdhGridGetSizes(AdhGrid g, PetscInt *Nx, PetscInt *Ny, PetscReal *Lx, PetscReal *Ly)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  if (Nx) *Nx = g->Nx;
  if (Ny) *Ny = g->Ny;
  if (Lx) *Lx = g->Lx;
  if (Ly) *Ly = g->Ly;
  PetscFunctionReturn(0);
}

/*@
  AdhGridGetSpacing - Gets the element sizes of a grid, hx = Lx/Nx and hy = Ly/Ny

  Not Collective

  Input Parameter:
. g - the grid, set up

  Output Parameters:
+ hx - the element size along x (or `NULL`)
- hy - the element size along y (or `NULL`)

  Level: beginner

.seealso: `AdhGridGetSizes()`, `AdhGridSetUp()`, `AdhGridGetCoordinates()`
@*/
PetscErrorCode AdhGridGetSpacing(AdhGrid g, PetscReal *hx, PetscReal *hy)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  PetscCheck(g->setup, g->comm, PETSC_ERR_ORDER, "AdhGridGetSpacing: the grid is not set up (AdhGridSetUp())");
  if (hx) *hx = g->hx;
  if (hy) *hy = g->hy;
  PetscFunctionReturn(0);
}

/*@
  AdhGridView - Prints a grid's sizes

  Collective

  Input Parameters:
+ g      - the grid
- viewer - an ASCII viewer, or `NULL` for the standard output of the grid's communicator

  Notes:
  The object's line (class, name, number of ranks), then the number of elements per side, the element sizes (zero before
  `AdhGridSetUp()`) and the domain. Other viewer types print nothing.

  Level: intermediate

.seealso: `AdhGridCreate()`, `AdhGridSetUp()`, `AdhSolverView()`
@*/
PetscErrorCode AdhGridView(AdhGrid g, PetscViewer viewer)
{
  PetscBool isascii;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(g, ADH_GRID_CLASSID, 1);
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(g->comm, &viewer));
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (isascii) {
    PetscCall(PetscObjectPrintClassNamePrefixType((PetscObject)g, viewer)); /* "AdhGrid Object: (name) N MPI processes" */
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(PetscViewerASCIIPrintf(viewer, "%" PetscInt_FMT " x %" PetscInt_FMT " elements of %g x %g, domain %g x %g, distributed by rows\n", g->Nx, g->Ny, (double)g->hx, (double)g->hy, (double)g->Lx, (double)g->Ly));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  }
  PetscFunctionReturn(0);
}

/*@
  AdhGridDestroy - Destroys a grid

  Collective

  Input Parameter:
. grid - the grid; nothing happens when *grid is `NULL`

  Notes:
  It drops one reference; the last releases the grid's references to its FFT transforms, frees its row datatypes
  (`AdhGridGetRowType()`) and the grid. It sets *grid to `NULL`. The operators made on the grid (`MatCreateAdhCompliance()`, `MatCreateAdhPeriodicStiffness()`) hold their own
  reference to the transforms and keep working after the grid is destroyed.

  Level: intermediate

.seealso: `AdhGridCreate()`, `AdhTransformRelease_Private()`
@*/
PetscErrorCode AdhGridDestroy(AdhGrid *grid)
{
  PetscFunctionBegin;
  if (!*grid) PetscFunctionReturn(0);
  PetscValidHeaderSpecific(*grid, ADH_GRID_CLASSID, 1);
  if (--((PetscObject)(*grid))->refct > 0) { /* others hold it still */
    *grid = NULL;
    PetscFunctionReturn(0);
  }
  PetscCall(AdhTransformRelease_Private(&(*grid)->transforms[0]));
  PetscCall(AdhTransformRelease_Private(&(*grid)->transforms[1]));
  for (PetscInt k = 0; k < 2; k++)
    if ((*grid)->row_types[k] != MPI_DATATYPE_NULL) PetscCallMPI(MPI_Type_free(&(*grid)->row_types[k]));
  PetscCall(PetscHeaderDestroy(grid));
  PetscFunctionReturn(0);
}
