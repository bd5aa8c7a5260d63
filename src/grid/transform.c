/* The grid's distributed FFT: an in-place real-to-complex FFTW(-MPI) transform of the physical or
   the zero-padded size, its plans (serial or FFTW-MPI's, chosen and timed on one rank), its
   single-precision twin and the redistribution between the grid's rows and FFTW's. */
#include "grid/gridimpl.h"

/*@
  AdhTransformRelease_Private - Releases one reference to a grid's shared FFT transform, destroying it with the last one

  Collective

  Input Parameter:
. t - the transform, or a pointer to `NULL`; *t is `NULL` on return

  Notes:
  A transform of one size (its in-place array, its forward and backward plans, their single-precision twins once made, and the
  redistribution between the grid's rows and FFTW's where they differ) is shared by the operators of one grid: the grid holds one
  reference and each operator one (they share its array: only one multiply runs at a time). Only the last release frees
  anything, and that one is collective (FFTW-MPI plans, a parallel vector and a scatter).

  Level: developer

.seealso: `AdhGridDestroy()`, `MatCreateAdhCompliance()`, `MatCreateAdhPeriodicStiffness()`
@*/
PetscErrorCode AdhTransformRelease_Private(AdhTransform *t)
{
  PetscFunctionBegin;
  if (!*t || --(*t)->refct > 0) {
    *t = NULL;
    PetscFunctionReturn(0);
  }
  fftw_destroy_plan((*t)->forward);
  fftw_destroy_plan((*t)->backward);
  fftw_free((*t)->data);
  if ((*t)->fforward) fftwf_destroy_plan((*t)->fforward);
  if ((*t)->fbackward) fftwf_destroy_plan((*t)->fbackward);
  fftwf_free((*t)->fdata);
  PetscCall(VecDestroy(&(*t)->xfft));
  PetscCall(VecScatterDestroy(&(*t)->toFFT));
  PetscCall(PetscFree(*t));
  PetscFunctionReturn(0);
}

/* The single-precision twin of t (the same layout: FFTW-MPI distributes by size, not by type),
   with plans of the same family and effort; collective. */
PetscErrorCode AdhTransformEnsureSingle_Private(AdhTransform t, MPI_Comm comm)
{
  ptrdiff_t alloc, ln0, l0s, ln1, l1s;
  PetscBool ok;

  PetscFunctionBegin;
  if (t->fforward && t->fbackward) PetscFunctionReturn(0);
  alloc    = fftwf_mpi_local_size_2d_transposed(t->n0, t->n1 / 2 + 1, comm, &ln0, &l0s, &ln1, &l1s);
  ok       = (PetscBool)(ln0 == t->local_n0 && l0s == t->local_0_start && ln1 == t->local_n1 && l1s == t->local_1_start);
  t->fdata = ok ? (float *)fftwf_alloc_complex(PetscMax(alloc, 1)) : NULL;
  ok       = (PetscBool)(ok && t->fdata);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ok, 1, MPIU_BOOL, MPI_LAND, comm)); /* every rank plans, or none */
  if (ok) {
    fftwf_set_timelimit(t->timelimit);
    if (t->serial) {
      t->fforward  = fftwf_plan_dft_r2c_2d((int)t->n0, (int)t->n1, t->fdata, (fftwf_complex *)t->fdata, t->flags);
      t->fbackward = fftwf_plan_dft_c2r_2d((int)t->n0, (int)t->n1, (fftwf_complex *)t->fdata, t->fdata, t->flags);
    } else {
      t->fforward  = fftwf_mpi_plan_dft_r2c_2d(t->n0, t->n1, t->fdata, (fftwf_complex *)t->fdata, comm, t->flags | FFTW_MPI_TRANSPOSED_OUT);
      t->fbackward = fftwf_mpi_plan_dft_c2r_2d(t->n0, t->n1, (fftwf_complex *)t->fdata, t->fdata, comm, t->flags | FFTW_MPI_TRANSPOSED_IN);
    }
    ok = (PetscBool)(t->fforward && t->fbackward);
  }
  if (!ok) { /* nothing half-made stays behind */
    if (t->fforward) fftwf_destroy_plan(t->fforward);
    if (t->fbackward) fftwf_destroy_plan(t->fbackward);
    fftwf_free(t->fdata);
    t->fforward = t->fbackward = NULL;
    t->fdata                   = NULL;
  }
  PetscCheck(ok, comm, PETSC_ERR_LIB, "FFTW could not allocate or plan a single-precision %td x %td transform in the double one's layout", t->n1, t->n0);
  PetscFunctionReturn(0);
}

/* Seconds of the faster of two forward-backward pairs of t's current plans (its array is zeroed:
   the values do not change FFTW's speed). */
static PetscErrorCode TimePair(AdhTransform t, PetscLogDouble *best)
{
  PetscLogDouble t0, t1;

  PetscFunctionBegin;
  PetscCall(PetscArrayzero(t->data, t->local_n0 * t->stride));
  *best = PETSC_MAX_REAL;
  for (int k = 0; k < 2; k++) {
    PetscCall(PetscTime(&t0));
    fftw_execute(t->forward);
    fftw_execute(t->backward);
    PetscCall(PetscTime(&t1));
    *best = PetscMin(*best, t1 - t0);
  }
  PetscFunctionReturn(0);
}

static void DestroyPlans(AdhTransform t)
{
  if (t->forward) fftw_destroy_plan(t->forward);
  if (t->backward) fftw_destroy_plan(t->backward);
  t->forward = t->backward = NULL;
}

static void MakePlans(AdhTransform t, MPI_Comm comm, PetscBool serial, unsigned flags)
{
  t->serial = serial;
  if (serial) {
    t->forward  = fftw_plan_dft_r2c_2d((int)t->n0, (int)t->n1, t->data, (fftw_complex *)t->data, flags);
    t->backward = fftw_plan_dft_c2r_2d((int)t->n0, (int)t->n1, (fftw_complex *)t->data, t->data, flags);
  } else {
    t->forward  = fftw_mpi_plan_dft_r2c_2d(t->n0, t->n1, t->data, (fftw_complex *)t->data, comm, flags | FFTW_MPI_TRANSPOSED_OUT);
    t->backward = fftw_mpi_plan_dft_c2r_2d(t->n0, t->n1, (fftw_complex *)t->data, t->data, comm, flags | FFTW_MPI_TRANSPOSED_IN);
  }
}

/* -adh_fftw_layout's names (gridimpl.h) */
const char *const AdhFFTWLayouts[] = {"auto", "serial", "transposed", "AdhFFTWLayout", "ADH_FFTW_LAYOUT_", NULL};

/* The plans of t: FFTW-MPI's on several ranks. On one rank FFTW's serial plans skip FFTW-MPI's
   transposes, which made a pair 10-30% faster from 256^2 to 3072^2 on the development machine
   (32 MB of L3 cache); at 4096^2 the transposes, which keep the column transforms in cache, made
   FFTW-MPI's 10% faster. So under auto a transform of up to 2^22 points (every bounding-box window
   of a grid up to 1024^2) gets serial plans; a larger one gets both, timed, and keeps the faster
   with a measuring planner, and FFTW-MPI's under estimate (nothing timed: reproducible). Should
   one family fail to plan, the other is tried. Either way the result is the same transform; only
   rounding differs. */
static PetscErrorCode PlanTransform(AdhTransform t, MPI_Comm comm, PetscMPIInt size, unsigned flags, AdhFFTWLayout layout)
{
  PetscBool serial;

  PetscFunctionBegin;
  if (size > 1) serial = PETSC_FALSE;
  else if (layout != ADH_FFTW_LAYOUT_AUTO) serial = (PetscBool)(layout == ADH_FFTW_LAYOUT_SERIAL);
  else if ((PetscLogDouble)t->n0 * (PetscLogDouble)t->n1 <= 4194304.0) serial = PETSC_TRUE;
  else if (flags == FFTW_ESTIMATE) serial = PETSC_FALSE;
  else {
    PetscLogDouble tserial = PETSC_MAX_REAL, tmpi = PETSC_MAX_REAL;
    MakePlans(t, comm, PETSC_TRUE, flags);
    if (t->forward && t->backward) PetscCall(TimePair(t, &tserial));
    DestroyPlans(t);
    MakePlans(t, comm, PETSC_FALSE, flags);
    if (t->forward && t->backward) PetscCall(TimePair(t, &tmpi));
    serial = (PetscBool)(tserial < tmpi);
    PetscCall(PetscInfo(NULL, "%td x %td transform on one rank: a pair takes %g s with serial plans, %g s with FFTW-MPI's; using %s\n", t->n1, t->n0, tserial, tmpi, serial ? "serial" : "FFTW-MPI's"));
    if (!serial) PetscFunctionReturn(0); /* FFTW-MPI's plans, just made */
    DestroyPlans(t);
  }
  MakePlans(t, comm, serial, flags); /* after timing, from FFTW's wisdom: no second measuring */
  if ((!t->forward || !t->backward) && size == 1) {
    DestroyPlans(t);
    MakePlans(t, comm, (PetscBool)!serial, flags);
  }
  PetscFunctionReturn(0);
}

static unsigned PlannerFlag(PetscInt effort)
{
  const unsigned flags[] = {FFTW_ESTIMATE, FFTW_MEASURE, FFTW_PATIENT, FFTW_EXHAUSTIVE};
  return flags[effort];
}

/* The grid's transform of the physical size (periodic) or the zero-padded one (free), created on
   first use with the planner effort of the first operator that asks. */
PetscErrorCode AdhGridGetTransform_Private(AdhGrid grid, PetscBool padded, PetscInt effort, PetscReal timelimit, AdhFFTWLayout layout, AdhTransform *tout)
{
  AdhTransform t = grid->transforms[padded ? 1 : 0];
  ptrdiff_t    alloc_local;
  PetscInt     ys, ym, first_row, phys_start;
  PetscMPIInt  size;
  PetscBool    same;
  Vec          x;
  IS           is;

  PetscFunctionBegin;
  if (!t) {
    PetscCall(PetscNew(&t));
    t->refct    = 1; /* the grid's */
    t->n0       = padded ? 2 * grid->Ny : grid->Ny;
    t->n1       = padded ? 2 * grid->Nx : grid->Nx;
    t->stride   = 2 * (t->n1 / 2 + 1);
    PetscCallMPI(MPI_Comm_size(grid->comm, &size));
    /* on one rank either layout fits: the whole transform, n0 x (n1/2 + 1) complex values */
    alloc_local = fftw_mpi_local_size_2d_transposed(t->n0, t->n1 / 2 + 1, grid->comm, &t->local_n0, &t->local_0_start, &t->local_n1, &t->local_1_start);
    t->data     = (double *)fftw_alloc_complex(PetscMax(alloc_local, 1));
    if (!t->data) PetscCall(PetscFree(t));
    PetscCheck(t, grid->comm, PETSC_ERR_MEM, "FFTW could not allocate %td complex values (out of memory?)", alloc_local);
    /* By default plans have no limit (a limited plan multiplies 1.4x slower at 2048); the solver,
       which plans many windows and uses the whole-grid operator rarely, asks for a short limit
       through the grid (the solver and its bounding boxes). An explicit -adh_fftw_timelimit wins. Only on one rank:
       each rank times its own trials, and a limit would let ranks take different planning paths
       into different collectives (a deadlock). */
    fftw_set_timelimit(size == 1 && timelimit >= 0 ? timelimit : FFTW_NO_TIMELIMIT);
    t->flags     = PlannerFlag(effort);
    t->timelimit = size == 1 && timelimit >= 0 ? timelimit : FFTW_NO_TIMELIMIT;
    PetscCall(PlanTransform(t, grid->comm, size, t->flags, layout));
    if (!t->forward || !t->backward) { /* nothing half-made stays behind */
      const ptrdiff_t n0 = t->n0, n1 = t->n1;
      DestroyPlans(t);
      fftw_free(t->data);
      PetscCall(PetscFree(t));
      SETERRQ(grid->comm, PETSC_ERR_LIB, "FFTW could not plan a %td x %td transform", n1, n0);
    }

    /* The scatter between the grid's rows and the physical rows of FFTW's slab, where they differ. */
    first_row    = (PetscInt)t->local_0_start;
    t->phys_rows = (PetscInt)PetscMax(0, PetscMin(t->local_0_start + t->local_n0, (ptrdiff_t)grid->Ny) - t->local_0_start);
    phys_start   = PetscMin(first_row, grid->Ny) * grid->Nx;
    PetscCall(AdhGridGetOwnership(grid, &ys, &ym));
    same = (PetscBool)(ys == first_row && ym == t->phys_rows);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &same, 1, MPIU_BOOL, MPI_LAND, grid->comm));
    if (!same) {
      PetscCall(AdhGridCreateVector(grid, &x));
      PetscCall(VecCreateMPI(grid->comm, t->phys_rows * grid->Nx, grid->Nx * grid->Ny, &t->xfft));
      PetscCall(ISCreateStride(grid->comm, t->phys_rows * grid->Nx, phys_start, 1, &is));
      PetscCall(VecScatterCreate(x, is, t->xfft, is, &t->toFFT));
      PetscCall(ISDestroy(&is));
      PetscCall(VecDestroy(&x));
    }
    grid->transforms[padded ? 1 : 0] = t;
  }
  t->refct++;
  *tout = t;
  PetscFunctionReturn(0);
}
