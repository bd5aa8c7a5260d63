/* What a run needs before anything is allocated: the indices the PETSc build can address, and an
   estimate of the memory, so that a grid that cannot fit stops with one clear message instead of
   an allocation failure deep inside FFTW or PETSc (or the kernel's OOM killer).

   The memory model is per grid point, measured with -memory_view and -malloc_view (1024^2 and
   2048^2, and 4096^2 on two ranks): a periodic cell holds h, p, g (24 B), the FFT array (8), the
   half-spectrum multipliers (4), the contact flags (2), FFTW-MPI's transpose buffers on more than
   one rank (about 16), the heap PETSc does not count (about 11: the C library's between set
   updates of different sizes), the contact set's vectors, offsets and index set (58 B a point of
   the set, so up to 58 where everything touches) and, for a moment, a rough surface's generator
   (10, at set-up, before any set): 130 B bounds them. A free boundary holds instead of the FFT
   array the zero-padded 2Nx x 2Ny transform (32), with its redistribution (28) and the
   bounding-box windows' transforms (up to 40): measured 121-124 B above the base with little in
   contact, plus the set's 58 where everything touches: 210 B. crack-closure adds G (8), a copy of the
   contact flags (1), u = K p (8) where the profile has points without a face (a punch; the
   openings are read from g elsewhere) and the front's links over the rows
   each rank looks at (one PetscInt), and per rank the rows other ranks own among those (three
   buffers of the openings, h and G, the flags and the links): at most 2 max(3, ceil(R)) rows of
   Nx points (R the largest radius, -adh_criterion_radius_max; none on one rank, counted all the
   same); -adh_attach griffith a fourth buffer, of p (its limits are kept over G);
   -adh_criterion_certify the slots of its front's cache (one PetscInt; its entries, about 1 kB a
   front point, go with the front, not the grid, and are not counted); -adh_cascade_apart or
   -adh_cascade_local with a finite F (a window of the whole grid needs none) their marks and widened band (2 bytes, and per rank the band's D rows each
   side and the other ranks' among them; the local solves' vectors are on the window, and the
   set's KSP is reset with the set before them, their own after them, so that at most one
   window's or set's CG vectors are held at a time: not counted beyond the set's); -adh_cascade_single the float transform array (4). Each rank also holds about
   50 MB of MPI, PETSc and FFTW. */
#include <unistd.h>
#include "solver/solverimpl.h"

static const PetscLogDouble AdhRankBaseBytes = 50e6;

/* Bytes per grid point of this run, and bytes each rank holds besides: the base, and
   crack-closure's rows beyond the rank's own (see above). */
static PetscErrorCode BytesOfRun(AdhSolver s, PetscLogDouble *per_point, PetscLogDouble *per_rank)
{
  AdhTypeOps *types[ADH_NUM_KINDS];

  PetscFunctionBegin;
  AdhSolverGetTypeOps_Private(s, types, NULL, NULL);
  *per_point = (s->boundary == ADH_BOUNDARY_PERIODIC ? 130.0 : 210.0) + (s->cascade_apart > 0 || (s->cascade_local > 0 && !PetscIsInfReal(s->cascade_local)) ? 2.0 : 0.0) + (s->cascade_single && (s->cascade_rtol > 0 || s->cascade_local > 0) ? 4.0 : 0.0);
  *per_rank  = AdhRankBaseBytes;
  /* the marks' band beyond a rank's own rows and the other ranks' rows in it: 4 D rows of bytes */
  *per_rank += 4.0 * PetscMin(PetscMax(s->cascade_apart, s->local_whole ? 0 : s->local_W), s->grid->Ny) * s->grid->Nx;
  for (PetscInt k = 0; k < ADH_NUM_KINDS; k++) /* what the types add: crack-closure's (impls/criterion/crackclosure/crackclosure.c) */
    if (types[k]->memory) {
      PetscLogDouble point = 0.0, rank = 0.0;
      PetscCall(types[k]->memory(s, &point, &rank));
      *per_point += point;
      *per_rank += rank;
    }
  PetscFunctionReturn(0);
}

/*@
  AdhSolverEstimateMemory - Estimates the memory the run needs, from the grid, the boundary, the criterion and the options

  Collective

  Input Parameter:
. s - the solver

  Output Parameters:
+ total - bytes for the whole run, all ranks together (or `NULL`)
- node  - bytes for the ranks of the solver's communicator on this node (or `NULL`)

  Level: intermediate

  Notes:
  The model is per grid point, measured with -memory_view and -malloc_view (the comment at the top of estimate.c
  accounts for it): about 130 bytes a point on a periodic cell and 210 on a free boundary (its zero-padded transform
  and bounding-box windows), plus what crack-closure (more on a punch), -adh_criterion_certify, -adh_cascade_apart,
  -adh_cascade_local with a finite F and -adh_cascade_single add; and per rank about 50 MB of MPI, PETSc and FFTW,
  crack-closure's rows of other ranks (one more buffer with -adh_attach griffith) and the band of -adh_cascade_apart
  or -adh_cascade_local (the latter's width is known after set-up). The node's share assumes the points spread evenly
  over the ranks.

  It can be called before `AdhSolverSetUp()`, once the options are set. Set-up refuses a grid whose estimate for this
  node exceeds the node's physical memory, before it allocates anything (-adh_memory_check 0 skips this);
  `AdhSolverView()` prints the estimate.

.seealso: `AdhSolverView()`, `AdhSolverSetUp()`, `AdhSolverSetFromOptions()`
@*/
PetscErrorCode AdhSolverEstimateMemory(AdhSolver s, PetscLogDouble *total, PetscLogDouble *node)
{
  PetscLogDouble points;
  PetscMPIInt    size, node_size;
  MPI_Comm       shared;
  PetscLogDouble per_point, per_rank;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  points = (PetscLogDouble)s->grid->Nx * (PetscLogDouble)s->grid->Ny;
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  PetscCallMPI(MPI_Comm_split_type(s->comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &shared));
  PetscCallMPI(MPI_Comm_size(shared, &node_size));
  PetscCallMPI(MPI_Comm_free(&shared));
  PetscCall(BytesOfRun(s, &per_point, &per_rank));
  if (total) *total = points * per_point + size * per_rank;
  if (node) *node = (points * per_point / size + per_rank) * node_size;
  PetscFunctionReturn(0);
}

/* Refuse a grid the build's PetscInt cannot address: Nx Ny points, or 4 Nx Ny for the zero-padded
   transform of a free boundary. With 32-bit indices that is about 46 000 points a side on a
   periodic cell and 23 000 on a free boundary; with 64-bit indices (sizeof(PetscInt) == 8) the
   limit lies far beyond any memory, so only a build with 32-bit indices is told to change. */
static PetscErrorCode CheckIndices(AdhSolver s)
{
  const AdhGrid        g      = s->grid;
  const PetscBool      padded = (PetscBool)(s->boundary == ADH_BOUNDARY_FREE);
  const PetscLogDouble points = (padded ? 4.0 : 1.0) * (PetscLogDouble)g->Nx * (PetscLogDouble)g->Ny;
  const char          *remedy = sizeof(PetscInt) < 8 ? "build adhbem against a PETSc with 64-bit indices (ADHBEM_INDICES=64 ./run build, into build64/; or your own PETSc configured --with-64-bit-indices), or use a smaller grid" : "use a smaller grid";

  PetscFunctionBegin;
  PetscCheck(points <= (PetscLogDouble)PETSC_MAX_INT, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_n: %" PetscInt_FMT " x %" PetscInt_FMT " %s %.3g grid points, more than this PETSc build's %d-bit indices address (%" PetscInt_FMT "): %s", g->Nx, g->Ny, padded ? "needs a zero-padded transform (free boundary) of" : "has", (double)points, (int)(8 * sizeof(PetscInt)), (PetscInt)PETSC_MAX_INT, remedy);
  PetscFunctionReturn(0);
}

/* Refuse a grid that clearly does not fit into the memory of a node (-adh_memory_check 0 skips
   this). */
static PetscErrorCode CheckMemory(AdhSolver s)
{
  const AdhGrid  g = s->grid;
  PetscLogDouble node, physical, per_point, per_rank;
  long           pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);

  PetscFunctionBegin;
  if (!s->memory_check || pages <= 0 || page <= 0) PetscFunctionReturn(0);
  physical = (PetscLogDouble)pages * (PetscLogDouble)page;
  PetscCall(AdhSolverEstimateMemory(s, NULL, &node));
  PetscCall(BytesOfRun(s, &per_point, &per_rank));
  PetscCheck(node <= physical, s->comm, PETSC_ERR_MEM, "-adh_n: %" PetscInt_FMT " x %" PetscInt_FMT " needs about %.3g GB on this node (about %.0f bytes per grid point, %.0f MB per rank), which has %.3g GB of memory: spread the run over more nodes or use a smaller grid (-adh_memory_check 0 skips this check)", g->Nx, g->Ny, node / 1e9, (double)per_point, (double)per_rank / 1e6, physical / 1e9);
  PetscFunctionReturn(0);
}

/* Refuse a path whose curve (a record a state, on every rank) PetscInt cannot count or no memory
   holds: -adh_steps 2000000000 would otherwise run until the job's time limit. */
static PetscErrorCode CheckPath(AdhSolver s)
{
  const PetscLogDouble states = (PetscLogDouble)PetscMax(s->npath - 1, 1) * (PetscLogDouble)s->steps + 1;
  const PetscLogDouble bytes  = states * (PetscLogDouble)sizeof(AdhState);
  long                 pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);

  PetscFunctionBegin;
  PetscCheck(states <= (PetscLogDouble)PETSC_MAX_INT, s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_steps: %" PetscInt_FMT " steps on each of the %" PetscInt_FMT " legs of -adh_path make %.3g states, more than this PETSc build's %d-bit indices count", s->steps, s->npath - 1, (double)states, (int)(8 * sizeof(PetscInt)));
  if (!s->memory_check || pages <= 0 || page <= 0) PetscFunctionReturn(0);
  PetscCheck(bytes <= (PetscLogDouble)pages * (PetscLogDouble)page, s->comm, PETSC_ERR_MEM, "-adh_steps: %" PetscInt_FMT " steps on each of the %" PetscInt_FMT " legs of -adh_path make %.3g states, whose curve (%d bytes a state, on every rank) needs %.3g GB, more than this node's %.3g GB (-adh_memory_check 0 skips this check)", s->steps, s->npath - 1, (double)states, (int)sizeof(AdhState), bytes / 1e9, (double)pages * (double)page / 1e9);
  PetscFunctionReturn(0);
}

/* The indices first: no option gets past them, and a user who spread the run over more nodes for
   its memory would only then learn that it needs another build. */
PetscErrorCode AdhSolverCheckResources_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(CheckIndices(s));
  PetscCall(CheckMemory(s));
  PetscCall(CheckPath(s));
  PetscFunctionReturn(0);
}
