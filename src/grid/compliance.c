/* The half-space compliance K (u = K p) as a MatShell whose multiply is a distributed FFTW
   real-to-complex convolution.

   free:     Love's influence coefficients on a zero-padded 2Ny x 2Nx grid with wrap-around, so
             the cyclic convolution equals the exact linear one on the Ny x Nx physical grid.
   periodic: the spectral multiplier 2/(E*|q|) on the Ny x Nx grid, q = 0 mode zero.

   Arrays are row-major [j][i] (j along y, the distributed direction), as in FFTW-MPI. On several
   ranks the forward transform leaves its output transposed and the backward one takes it so,
   which saves FFTW two global transposes per multiply. On one rank the plans may instead be
   FFTW's serial ones, with the spectrum in natural order (PlanTransform chooses). On the periodic
   grid the grid's rows are FFTW's (grid.c), and the multiply copies straight between the vectors
   and the transform array. FFTW's slabs split the padded rows of the free transform evenly, which
   leaves the physical rows on half the ranks; there one VecScatter, built once, moves the grid
   layout to FFTW's and back. Both layouts order the entries j*Nx + i, so it is a pure
   redistribution. */
#include "grid/gridimpl.h"
#include "sys/sysimpl.h"

const char *const AdhBoundaries[] = {"free", "periodic", "AdhBoundary", "ADH_BOUNDARY_", NULL};

/* The multiplier applied to a spectrum of complex type T (double or float) in the transform's
   layout: serial, rows ky = k0 of n1/2 + 1 modes kx (row n0 - k0 has row k0's multipliers);
   transposed, columns of n0 modes ky per local kx. */
#define ADH_APPLY_MULTIPLIER(T, spec) \
  do { \
    ptrdiff_t a_, k0_; \
    if (c->t->serial) \
      for (k0_ = 0; k0_ < c->t->n0; k0_++) { \
        T               *row_ = (spec) + k0_ * c->t->local_n1; \
        const PetscReal *m_   = c->multiplier + (k0_ <= c->t->n0 / 2 ? k0_ : c->t->n0 - k0_) * c->t->local_n1; \
        for (a_ = 0; a_ < c->t->local_n1; a_++) { \
          row_[a_][0] *= m_[a_]; \
          row_[a_][1] *= m_[a_]; \
        } \
      } \
    else \
      for (a_ = 0; a_ < c->t->local_n1; a_++) { \
        T               *col_ = (spec) + a_ * c->t->n0; \
        const PetscReal *m_   = c->multiplier + a_ * c->nhalf; \
        for (k0_ = 0; k0_ < c->t->n0; k0_++) { \
          const PetscReal mk_ = m_[k0_ <= c->t->n0 / 2 ? k0_ : c->t->n0 - k0_]; \
          col_[k0_][0] *= mk_; \
          col_[k0_][1] *= mk_; \
        } \
      } \
  } while (0)

/* Forward transform of the array, the multiplier, backward transform: in double, or in single
   precision on the float twin (MatAdhComplianceSetSinglePrecision). */
PetscErrorCode AdhComplianceConvolve_Private(Mat K, AdhComplianceCtx *c, PetscBool single)
{
  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(ADH_FFTForward, K, 0, 0, 0));
  if (single) fftwf_execute(c->t->fforward);
  else fftw_execute(c->t->forward);
  PetscCall(PetscLogEventEnd(ADH_FFTForward, K, 0, 0, 0));
  if (single) ADH_APPLY_MULTIPLIER(fftwf_complex, (fftwf_complex *)c->t->fdata);
  else ADH_APPLY_MULTIPLIER(fftw_complex, (fftw_complex *)c->t->data);
  PetscCall(PetscLogEventBegin(ADH_FFTBackward, K, 0, 0, 0));
  if (single) fftwf_execute(c->t->fbackward);
  else fftw_execute(c->t->backward);
  PetscCall(PetscLogEventEnd(ADH_FFTBackward, K, 0, 0, 0));
  c->nmult++;
  if (single) c->nmult_single++;
  PetscCall(PetscLogFlops(4.0 * c->t->local_n1 * c->t->n0));
  PetscFunctionReturn(0);
}

static PetscErrorCode MatMult_Compliance(Mat K, Vec x, Vec y)
{
  AdhComplianceCtx  *c;
  const PetscScalar *xa;
  PetscScalar       *ya;
  PetscInt           r;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(K, &c));
  PetscCall(PetscLogEventBegin(ADH_ComplianceMult, K, x, y, 0));
  if (c->t->toFFT) {
    PetscCall(VecScatterBegin(c->t->toFFT, x, c->t->xfft, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(c->t->toFFT, x, c->t->xfft, INSERT_VALUES, SCATTER_FORWARD));
  }
  if (c->t->phys_rows < c->t->local_n0) PetscCall(PetscArrayzero(c->t->data + c->t->phys_rows * c->t->stride, (c->t->local_n0 - c->t->phys_rows) * c->t->stride));
  PetscCall(VecGetArrayRead(c->t->toFFT ? c->t->xfft : x, &xa));
  for (r = 0; r < c->t->phys_rows; r++) {
    PetscCall(PetscArraycpy(c->t->data + r * c->t->stride, xa + r * c->Nx, c->Nx));
    PetscCall(PetscArrayzero(c->t->data + r * c->t->stride + c->Nx, c->t->stride - c->Nx));
  }
  PetscCall(VecRestoreArrayRead(c->t->toFFT ? c->t->xfft : x, &xa));
  PetscCall(AdhComplianceConvolve_Private(K, c, PETSC_FALSE));
  PetscCall(VecGetArrayWrite(c->t->toFFT ? c->t->xfft : y, &ya));
  for (r = 0; r < c->t->phys_rows; r++) PetscCall(PetscArraycpy(ya + r * c->Nx, c->t->data + r * c->t->stride, c->Nx));
  PetscCall(VecRestoreArrayWrite(c->t->toFFT ? c->t->xfft : y, &ya));
  if (c->t->toFFT) {
    PetscCall(VecScatterBegin(c->t->toFFT, c->t->xfft, y, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecScatterEnd(c->t->toFFT, c->t->xfft, y, INSERT_VALUES, SCATTER_REVERSE));
  }
  PetscCall(PetscLogEventEnd(ADH_ComplianceMult, K, x, y, 0));
  PetscFunctionReturn(0);
}

/* The compliance or stiffness shell behind K (K itself, or with through_mean the one a mean
   compliance wraps, then with the wrapper's context), or an error naming the call. */
PetscErrorCode AdhComplianceGet_Private(Mat K, const char caller[], PetscBool through_mean, AdhComplianceCtx **c, AdhMeanComplianceCtx **mean)
{
  void (*mult)(void);
  PetscBool shell;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(K, MAT_CLASSID, 1);
  *mean = NULL;
  PetscCall(PetscObjectTypeCompare((PetscObject)K, MATSHELL, &shell));
  PetscCheck(shell, PetscObjectComm((PetscObject)K), PETSC_ERR_ARG_WRONG, "%s needs a %s Mat of adhbem", caller, through_mean ? "compliance, stiffness or mean compliance" : "compliance or stiffness");
  PetscCall(MatShellGetOperation(K, MATOP_MULT, &mult));
  if (mult == (void (*)(void))MatMult_AdhMeanCompliance_Private) {
    PetscCheck(through_mean, PetscObjectComm((PetscObject)K), PETSC_ERR_ARG_WRONG, "%s: K is a mean compliance (MatCreateAdhMeanCompliance()), whose bounds are not those of the compliance it wraps; ask that one", caller);
    PetscCall(MatShellGetContext(K, mean));
    K = (*mean)->K;
    PetscCall(MatShellGetOperation(K, MATOP_MULT, &mult));
  }
  PetscCheck(mult == (void (*)(void))MatMult_Compliance, PetscObjectComm((PetscObject)K), PETSC_ERR_ARG_WRONG, "%s needs a %s Mat of adhbem", caller, through_mean ? "compliance, stiffness or mean compliance" : "compliance or stiffness");
  PetscCall(MatShellGetContext(K, c));
  PetscFunctionReturn(0);
}

/*@
  MatAdhComplianceHasDirectLayout - Tells whether an operator's transform has the grid's rows (for `MatAdhComplianceMultOnSet()`)

  Not Collective

  Input Parameter:
. K - a compliance, stiffness or mean compliance of adhbem

  Output Parameter:
. direct - `PETSC_TRUE` when every rank's grid rows are its rows of the operator's transform: then
           `MatAdhComplianceMultOnSet()` applies the operator to values on a set of local points directly

  Notes:
  The periodic compliance and the stiffness have the direct layout whenever the grid splits its rows as FFTW does, the usual
  case (`AdhGridSetUp()`). The free compliance has it on one rank only: on several, the zero-padded transform leaves the
  physical rows on half the ranks, and a scatter moves them. The answer is the same on every rank. Any other `Mat` is an error
  (`PETSC_ERR_ARG_WRONG`).

  Level: advanced

.seealso: `MatAdhComplianceMultOnSet()`, `MatAdhComplianceSetSinglePrecision()`, `MatCreateAdhCompliance()`
@*/
PetscErrorCode MatAdhComplianceHasDirectLayout(Mat K, PetscBool *direct)
{
  AdhComplianceCtx     *c;
  AdhMeanComplianceCtx *mean;

  PetscFunctionBegin;
  PetscValidBoolPointer(direct, 2);
  PetscCall(AdhComplianceGet_Private(K, "MatAdhComplianceHasDirectLayout", PETSC_TRUE, &c, &mean));
  *direct = (PetscBool)!c->t->toFFT;
  PetscFunctionReturn(0);
}

/*@
  MatAdhComplianceSetSinglePrecision - Sets whether `MatAdhComplianceMultOnSet()` applies an operator in single precision

  Collective

  Input Parameters:
+ K      - a compliance, stiffness or mean compliance (then its compliance) of adhbem
- single - `PETSC_TRUE` for single precision, `PETSC_FALSE` for double; the same on every rank

  Notes:
  Single precision means float transforms, half the bytes to move, for solves that stop at a loose tolerance (the solver's
  -adh_cascade_single). It changes `MatAdhComplianceMultOnSet()` only: `MatMult()` stays in double precision.

  Turning single precision on needs the direct layout (`MatAdhComplianceHasDirectLayout()`, else `PETSC_ERR_ARG_WRONGSTATE`)
  and is collective when the float plans are not made yet: they are made then, once per transform, in the double transform's
  layout with plans of the same family and planner effort, and shared by the grid's operators of that size. If FFTW cannot
  allocate or plan them, every rank fails (`PETSC_ERR_LIB`). Turning it off communicates nothing.

  Level: advanced

.seealso: `MatAdhComplianceMultOnSet()`, `MatAdhComplianceHasDirectLayout()`, `MatAdhComplianceGetSingleMultCount()`
@*/
PetscErrorCode MatAdhComplianceSetSinglePrecision(Mat K, PetscBool single)
{
  AdhComplianceCtx     *c;
  AdhMeanComplianceCtx *mean;

  PetscFunctionBegin;
  PetscCall(AdhComplianceGet_Private(K, "MatAdhComplianceSetSinglePrecision", PETSC_TRUE, &c, &mean));
  PetscCheck(!single || !c->t->toFFT, c->comm, PETSC_ERR_ARG_WRONGSTATE, "MatAdhComplianceSetSinglePrecision: single precision is for MatAdhComplianceMultOnSet, which needs the grid's rows to be the transform's (a periodic grid)");
  if (single) PetscCall(AdhTransformEnsureSingle_Private(c->t, c->comm));
  c->single = single;
  PetscFunctionReturn(0);
}

/*@
  MatAdhComplianceMultOnSet - Applies an operator restricted to a set of grid points, yC = R K R^T xC, without grid vectors

  Collective

  Input Parameters:
+ K     - a compliance, stiffness or mean compliance of adhbem with the direct layout
. n     - the number of this rank's points in the set (0 if none)
. local - their offsets into this rank's rows, (j - ys) Nx + i, in increasing order
- xC    - the values on the set: n local entries, in the order of local[]

  Output Parameter:
. yC - (K xC) on the set, n local entries in the same order

  Notes:
  R is the restriction to the set, so xC stands for a grid vector that is zero off the set. The values go straight into the
  transform's array and come straight out of it: no grid vectors, no scatter. This needs the grid's rows to be the transform's
  (`MatAdhComplianceHasDirectLayout()`, else `PETSC_ERR_ARG_WRONGSTATE`).

  It is one FFT pair, counted by `MatAdhComplianceGetMultCount()`, in single precision after
  `MatAdhComplianceSetSinglePrecision()`. Every rank must call it. For a mean compliance, c0 sum(xC)/N is added to every entry,
  the sum taken over the whole of xC.

  Level: advanced

.seealso: `MatAdhComplianceHasDirectLayout()`, `MatAdhComplianceSetSinglePrecision()`, `MatCreateAdhMeanCompliance()`,
          `AdhGridGetOwnership()`
@*/
PetscErrorCode MatAdhComplianceMultOnSet(Mat K, PetscInt n, const PetscInt local[], Vec xC, Vec yC)
{
  AdhComplianceCtx     *c;
  AdhMeanComplianceCtx *mean;
  const PetscScalar    *xa;
  PetscScalar          *ya;
  PetscInt              k, r;
  double               *data;
  float                *fdata;

  PetscFunctionBegin;
  if (n) PetscValidIntPointer(local, 3);
  PetscValidHeaderSpecific(xC, VEC_CLASSID, 4);
  PetscValidHeaderSpecific(yC, VEC_CLASSID, 5);
  PetscCall(AdhComplianceGet_Private(K, "MatAdhComplianceMultOnSet", PETSC_TRUE, &c, &mean));
  PetscCheck(!c->t->toFFT, c->comm, PETSC_ERR_ARG_WRONGSTATE, "MatAdhComplianceMultOnSet needs the grid's rows to be the transform's (a periodic grid)");
  PetscCall(PetscLogEventBegin(ADH_ComplianceMult, K, xC, yC, 0));
  data  = c->t->data;
  fdata = c->t->fdata;
  if (c->single) PetscCall(PetscArrayzero(fdata, c->t->local_n0 * c->t->stride));
  else PetscCall(PetscArrayzero(data, c->t->local_n0 * c->t->stride));
  /* point local[k] of row r sits at local[k] + r (stride - Nx) in the padded rows */
  PetscCall(VecGetArrayRead(xC, &xa));
  for (k = 0, r = 0; k < n; k++) {
    while (local[k] >= (r + 1) * c->Nx) r++;
    if (c->single) fdata[local[k] + r * (c->t->stride - c->Nx)] = (float)PetscRealPart(xa[k]);
    else data[local[k] + r * (c->t->stride - c->Nx)] = PetscRealPart(xa[k]);
  }
  PetscCall(VecRestoreArrayRead(xC, &xa));
  PetscCall(AdhComplianceConvolve_Private(K, c, c->single));
  PetscCall(VecGetArrayWrite(yC, &ya));
  for (k = 0, r = 0; k < n; k++) {
    while (local[k] >= (r + 1) * c->Nx) r++;
    ya[k] = c->single ? (PetscScalar)fdata[local[k] + r * (c->t->stride - c->Nx)] : data[local[k] + r * (c->t->stride - c->Nx)];
  }
  PetscCall(VecRestoreArrayWrite(yC, &ya));
  if (mean) {
    PetscScalar sum;
    PetscCall(VecSum(xC, &sum));
    PetscCall(VecShift(yC, mean->c0 * sum / mean->N));
  }
  PetscCall(PetscLogEventEnd(ADH_ComplianceMult, K, xC, yC, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode MatGetDiagonal_Compliance(Mat K, Vec d)
{
  AdhComplianceCtx *c;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(K, &c));
  PetscCall(VecSet(d, c->diagonal));
  PetscFunctionReturn(0);
}

static PetscErrorCode MatView_Compliance(Mat K, PetscViewer viewer)
{
  AdhComplianceCtx *c;
  PetscBool   isascii;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(K, &c));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (isascii) {
    if (c->kind == ADH_OPERATOR_STIFFNESS && !c->Estar) PetscCall(PetscViewerASCIIPrintf(viewer, "Periodic stiffness 1/C(|q|) of an elastic body (adhbem preconditioner)\n"));
    else if (c->kind == ADH_OPERATOR_STIFFNESS) PetscCall(PetscViewerASCIIPrintf(viewer, "Periodic half-space stiffness E*|q|/2 (adhbem preconditioner), E* = %g\n", (double)c->Estar));
    else if (!c->Estar) PetscCall(PetscViewerASCIIPrintf(viewer, "Periodic compliance C(|q|) of an elastic body (adhbem)\n"));
    else PetscCall(PetscViewerASCIIPrintf(viewer, "Half-space compliance (adhbem), %s boundary, E* = %g\n", AdhBoundaries[c->boundary], (double)c->Estar));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  grid %" PetscInt_FMT " x %" PetscInt_FMT ", elements %g x %g; %s r2c transform %td x %td\n", c->Nx, c->Ny, (double)c->hx, (double)c->hy, c->t->serial ? "FFTW (one rank)" : "FFTW-MPI (transposed spectrum)", c->t->n1, c->t->n0));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  diagonal %g, lambda_min bound %g (mean-free vectors: %g), multiplies so far %" PetscInt_FMT "\n", (double)c->diagonal, (double)c->lambda_min, (double)c->lambda_meanfree, c->nmult));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode AdhComplianceMatDestroy_Private(Mat K)
{
  AdhComplianceCtx *c;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(K, &c));
  PetscCall(AdhTransformRelease_Private(&c->t));
  PetscCall(PetscFree(c->multiplier));
  PetscCall(PetscFree(c));
  PetscFunctionReturn(0);
}

/* The operator of a kind: of a half-space of modulus Estar (symbol NULL), or of a periodic body's
   compliance symbol. */
static PetscErrorCode CreateFFTShell(AdhGrid grid, PetscReal Estar, AdhPeriodicSymbol symbol, void *ctx, AdhOperatorKind kind, Mat *K)
{
  const AdhBoundary boundary = kind == ADH_OPERATOR_FREE ? ADH_BOUNDARY_FREE : ADH_BOUNDARY_PERIODIC;
  /* the planner: the grid's own (fftw_effort, fftw_timelimit: set by the solver for its windows)
     where it has one, else its options; an explicit -adh_fftw_timelimit wins */
  const PetscInt      effort    = grid->fftw_effort >= 0 ? grid->fftw_effort : grid->opt_planner;
  const PetscReal     timelimit = grid->opt_timelimit_set ? grid->opt_timelimit : grid->fftw_timelimit >= -1.0 ? grid->fftw_timelimit : -1.0;
  const AdhFFTWLayout layout    = grid->opt_layout;
  AdhComplianceCtx   *c;
  PetscInt            ys, ym;
  PetscMPIInt         size;
  ptrdiff_t           nspec;

  PetscFunctionBegin;
  PetscCall(AdhInitializePackage());
  PetscCall(AdhGridSetUp(grid));
  PetscCheck(symbol || (Estar > 0 && !PetscIsInfOrNanReal(Estar)), grid->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_E_star: the reduced modulus must be positive and finite, got %g", (double)Estar);
  PetscCallMPI(MPI_Comm_size(grid->comm, &size));
  PetscCheck(layout != ADH_FFTW_LAYOUT_SERIAL || size == 1, grid->comm, PETSC_ERR_ARG_INCOMP, "-adh_fftw_layout serial needs one rank; on %d ranks the transforms are FFTW-MPI's (transposed)", (int)size);

  PetscCall(PetscNew(&c));
  c->comm     = grid->comm;
  c->kind     = kind;
  c->boundary = boundary;
  c->Estar    = symbol ? 0.0 : Estar;
  c->symbol     = symbol;
  c->symbol_ctx = ctx;
  c->Nx = grid->Nx; c->Ny = grid->Ny; c->hx = grid->hx; c->hy = grid->hy; c->Lx = grid->Lx; c->Ly = grid->Ly;
  PetscCall(AdhGridGetTransform_Private(grid, boundary == ADH_BOUNDARY_FREE, effort, timelimit, layout, &c->t));
  c->nhalf = c->t->n0 / 2 + 1;
  nspec    = c->t->local_n1 * c->nhalf;
  PetscCall(PetscMalloc1(PetscMax(nspec, 1), &c->multiplier));
  if (kind == ADH_OPERATOR_FREE) PetscCall(AdhComplianceFreeMultiplier_Private(c));
  else if (kind == ADH_OPERATOR_PERIODIC) PetscCall(AdhCompliancePeriodicMultiplier_Private(c));
  else PetscCall(AdhComplianceStiffnessMultiplier_Private(c));
  PetscCall(AdhComplianceRowStatistics_Private(c));
  c->symbol     = NULL; /* the multiplier is made: the symbol's context need not outlive this call */
  c->symbol_ctx = NULL;

  PetscCall(AdhGridGetOwnership(grid, &ys, &ym));
  PetscCall(MatCreateShell(c->comm, ym * c->Nx, ym * c->Nx, c->Nx * c->Ny, c->Nx * c->Ny, c, K));
  PetscCall(MatShellSetOperation(*K, MATOP_MULT, (void (*)(void))MatMult_Compliance));
  PetscCall(MatShellSetOperation(*K, MATOP_MULT_TRANSPOSE, (void (*)(void))MatMult_Compliance));
  PetscCall(MatShellSetOperation(*K, MATOP_GET_DIAGONAL, (void (*)(void))MatGetDiagonal_Compliance));
  PetscCall(MatShellSetOperation(*K, MATOP_VIEW, (void (*)(void))MatView_Compliance));
  PetscCall(MatShellSetOperation(*K, MATOP_DESTROY, (void (*)(void))AdhComplianceMatDestroy_Private));
  PetscCall(MatSetBlockSizes(*K, c->Nx, c->Nx)); /* a row per block, as the grid vectors */
  PetscCall(MatSetOption(*K, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(*K, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  if (kind != ADH_OPERATOR_PERIODIC) PetscCall(MatSetOption(*K, MAT_SPD, PETSC_TRUE));
  PetscCall(MatSetUp(*K));

  PetscFunctionReturn(0);
}

/*@
  MatCreateAdhCompliance - Creates the half-space compliance K (u = K p) of a grid, a `MATSHELL` applied with distributed FFTW

  Collective

  Input Parameters:
+ grid     - the grid; it is set up here if it is not yet
. Estar    - the reduced modulus E*, positive and finite
- boundary - `ADH_BOUNDARY_FREE` (an isolated contact: exact linear convolution on the zero-padded grid) or
             `ADH_BOUNDARY_PERIODIC` (a periodic cell)

  Output Parameter:
. K - the compliance

  Notes:
  K maps the pressures p, uniform on each element, to the displacements u at the elements' centres, on the layout of
  `AdhGridCreateVector()`. With a free boundary its entries are Love's influence coefficients (`AdhLoveCoefficient()`), applied
  as a cyclic convolution on a zero-padded 2Ny x 2Nx grid, which equals the exact linear one on the Ny x Nx grid. With a periodic
  boundary the multiplier is the spectral symbol 2/(E*|q|), q = 2 pi (kx/Lx, ky/Ly), on the Ny x Nx cell, with the mode q = 0
  set to zero: the mean displacement is left to the indentation, and the constant vector is in K's null space.

  A multiply is one forward and one backward real-to-complex FFT; where the grid's rows are not the transform's
  (`MatAdhComplianceHasDirectLayout()`) a scatter built once also moves the values between the two layouts. K is symmetric
  (`MatMultTranspose()` is `MatMult()`), marked SPD with a free boundary, has block size Nx, and provides `MatGetDiagonal()`
  (a constant) and an ASCII `MatView()`.

  The operators of a grid share one transform of each size, planned for the first operator that asks, as the grid's FFTW
  options say (-adh_fftw_planner, -adh_fftw_timelimit, -adh_fftw_layout, read by `AdhGridSetFromOptions()`; the constructor
  reads no options). The grid's fftw_effort, when set (the solver's bounding-box windows), wins over -adh_fftw_planner; an
  explicit -adh_fftw_timelimit wins over the grid's fftw_timelimit. A time limit applies on one rank only
  (ranks that time their own trials could take different planning paths into different collectives). Under auto, a transform
  of up to 2^22 points gets serial plans; a larger one gets the faster of the two families, timed, under a measuring planner,
  and FFTW-MPI's under estimate. Should one family fail to plan on one rank, the other is tried.

  Level: intermediate

.seealso: `AdhGridCreate()`, `AdhGridCreateVector()`, `MatAdhComplianceHasDirectLayout()`, `MatAdhComplianceGetLambdaMin()`,
          `MatAdhComplianceGetRowNormBound()`, `MatAdhComplianceGetMultCount()`, `MatCreateAdhPeriodicStiffness()`,
          `MatCreateAdhMeanCompliance()`
@*/
PetscErrorCode MatCreateAdhCompliance(AdhGrid grid, PetscReal Estar, AdhBoundary boundary, Mat *K)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(grid, ADH_GRID_CLASSID, 1);
  PetscValidPointer(K, 4);
  PetscCheck(boundary == ADH_BOUNDARY_FREE || boundary == ADH_BOUNDARY_PERIODIC, grid->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_boundary: unknown boundary mode %d", (int)boundary);
  PetscCall(CreateFFTShell(grid, Estar, NULL, NULL, boundary == ADH_BOUNDARY_FREE ? ADH_OPERATOR_FREE : ADH_OPERATOR_PERIODIC, K));
  PetscFunctionReturn(0);
}

/*@
  MatCreateAdhPeriodicStiffness - Creates the periodic half-space stiffness E*|q|/2 of a grid, a `MATSHELL` applied with FFTW

  Collective

  Input Parameters:
+ grid  - the grid; it is set up here if it is not yet
- Estar - the reduced modulus E*, positive and finite

  Output Parameter:
. S - the stiffness

  Notes:
  The stiffness is the inverse of the periodic compliance's symbol 2/(E*|q|); the solver uses it to precondition CG on the
  contact set. The mean mode (q = 0) gets the value of the lowest nonzero wave number 2 pi/max(Lx, Ly), so S is positive
  definite (marked SPD), with smallest eigenvalue E* pi/max(Lx, Ly) (`MatAdhComplianceGetLambdaMin()`).

  S is made as `MatCreateAdhCompliance()` makes K, planned as the grid's options say, on the grid's Ny x Nx transform, shared with a
  periodic compliance of the same grid. The MatAdhCompliance functions accept it as they accept a compliance.

  Level: advanced

.seealso: `MatCreateAdhCompliance()`, `MatAdhComplianceMultOnSet()`, `MatAdhComplianceGetLambdaMin()`
@*/
PetscErrorCode MatCreateAdhPeriodicStiffness(AdhGrid grid, PetscReal Estar, Mat *S)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(grid, ADH_GRID_CLASSID, 1);
  PetscValidPointer(S, 3);
  PetscCall(CreateFFTShell(grid, Estar, NULL, NULL, ADH_OPERATOR_STIFFNESS, S));
  PetscFunctionReturn(0);
}

/*@C
  MatCreateAdhPeriodicSymbolOperator - Creates the periodic compliance C(|q|) of an elastic body, or its stiffness 1/C(|q|),
  from the body's compliance symbol: a `MATSHELL` applied with FFTW

  Collective

  Input Parameters:
+ grid      - the grid; it is set up here if it is not yet
. symbol    - the body's compliance symbol: the surface displacement of a unit pressure wave of wave number q > 0, finite and
              positive
. ctx       - the symbol's context (needed during this call only)
- stiffness - `PETSC_FALSE` for the compliance, `PETSC_TRUE` for the stiffness

  Output Parameter:
. K - the operator

  Notes:
  The operators of `MatCreateAdhCompliance()` (periodic boundary) and `MatCreateAdhPeriodicStiffness()` for a body other than
  the half-space, such as a layer on a rigid base: the multiplier C(|q|) at q = 2 pi (kx/Lx, ky/Ly) with the mode q = 0 set to
  zero (the mean displacement is left to the indentation), or 1/C(|q|) with the mean mode given the value at the lowest nonzero
  wave number 2 pi/max(Lx, Ly). Everything else is as for the half-space's operators, which the MatAdhCompliance functions
  accept them as. The symbol is evaluated once a mode, here.

  Level: developer

.seealso: `MatCreateAdhCompliance()`, `MatCreateAdhPeriodicStiffness()`, `AdhSolverSetElasticType()`
@*/
PetscErrorCode MatCreateAdhPeriodicSymbolOperator(AdhGrid grid, AdhPeriodicSymbol symbol, void *ctx, PetscBool stiffness, Mat *K)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(grid, ADH_GRID_CLASSID, 1);
  PetscValidFunction(symbol, 2);
  PetscValidLogicalCollectiveBool(grid, stiffness, 4);
  PetscValidPointer(K, 5);
  PetscCall(CreateFFTShell(grid, 0.0, symbol, ctx, stiffness ? ADH_OPERATOR_STIFFNESS : ADH_OPERATOR_PERIODIC, K));
  PetscFunctionReturn(0);
}
