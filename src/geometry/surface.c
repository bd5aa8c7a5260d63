/* Random rough surfaces: a periodic, self-affine, Gaussian height field made in Fourier space
   on the distributed grid and brought to real space by one inverse FFT (FFTW-MPI).

   Determinism: the surface is the same to the last bit on any number of ranks.
   - Each Fourier coefficient is drawn from (seed, kx, ky) alone by a counter-based hash
     (splitmix64) and Box-Muller, never from a per-rank random stream.
   - The inverse 2-D transform is done row-column by hand: a 1-D complex backward transform of
     every kx column (all ky local in FFTW's transposed layout), FFTW-MPI's distributed
     transpose (pure data movement, exact), then a 1-D c2r transform of every y row. Each line
     goes through the same one-line plan whatever the decomposition, so every output value comes
     from the same arithmetic. (A fftw_mpi c2r 2-D plan may pick other codelets, batch sizes or
     SIMD lanes for other slab shapes, and on one rank it is a different, serial, plan.)
   - Those plans are FFTW_ESTIMATE | FFTW_UNALIGNED (no timing, no dependence on where a line
     starts) and made with FFTW's wisdom set aside: wisdom from an earlier measured plan (the
     compliance's, possibly different on every rank) could otherwise stand in for them. The
     caller's wisdom is put back afterwards.
   - The scale factor and the realised statistics are sums over kx columns or y rows. Each
     column's (row's) sum is formed in a fixed order by its one owner, the per-column sums are
     combined by an MPI sum in which every entry has exactly one nonzero contribution (exact),
     and all ranks then add them in global order. VecNorm would round differently per layout.
   Same machine (libm, CPU features) assumed: FFTW's estimate and libm's log/cos are per build. */
#include <fftw3-mpi.h>
#include <stdint.h>
#include "grid/gridimpl.h"
#include "sys/sysimpl.h"

/* A mode whose wavenumber lies on the cut-off to this relative rounding counts as inside. */
#define EDGE_RTOL 1e-9
/* Wavelength ranges are checked with this slack so that e.g. 2*L/N passes as 2 spacings. */
#define RANGE_RTOL 1e-12

static uint64_t SplitMix64(uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/* A complex Gaussian with E|c|^2 = 1 that depends only on the seed and the wavevector, so a
   coefficient is the same whichever rank draws it (and on a finer grid of the same cell). */
static void ModeGaussian(PetscInt seed, PetscInt kx, PetscInt ky, double *re, double *im)
{
  const uint64_t key = SplitMix64(SplitMix64(SplitMix64((uint64_t)seed) ^ (uint64_t)kx) ^ (uint64_t)ky);
  const double   u1  = ((double)(SplitMix64(key ^ 1) >> 11) + 0.5) * 0x1p-53; /* in (0,1): log finite */
  const double   u2  = (double)(SplitMix64(key ^ 2) >> 11) * 0x1p-53;
  const double   r   = sqrt(-log(u1)); /* Rayleigh modulus with E r^2 = 1 */

  *re = r * cos(2.0 * PETSC_PI * u2);
  *im = r * sin(2.0 * PETSC_PI * u2);
}

/* The defaults that depend on the grid: the cell size and 4 spacings (at most the cell); 0 while
   the grid's sizes are not valid yet (the -help line then says so). */
static void GridDefaults(AdhGrid grid, PetscReal *lr, PetscReal *lc)
{
  *lr = *lc = 0.0;
  if (!(grid->Nx > 0 && grid->Ny > 0 && grid->Lx > 0 && grid->Ly > 0)) return;
  *lr = PetscMax(grid->Lx, grid->Ly);
  *lc = PetscMin(4.0 * PetscMax(grid->Lx / (PetscReal)grid->Nx, grid->Ly / (PetscReal)grid->Ny), *lr);
}

/*@
  AdhSurfaceSetFromOptions - Fills the parameters of a random rough surface from their defaults and the options database

  Collective

  Input Parameters:
+ grid   - the grid the surface will be generated on, its sizes set (it need not be set up)
- prefix - the options prefix, or `NULL`

  Output Parameter:
. s - the surface's parameters; every field is overwritten

  Options Database Keys:
+ -adh_hurst <H> - the Hurst exponent H in (0, 1], C(q) ~ q^(-2(1+H)) between roll-off and cut-off (default 0.8)
. -adh_rolloff_wavelength <lambda_r> - the roll-off wavelength 2 pi/q_r, C(q) flat below q_r (default: the cell size max(Lx, Ly))
. -adh_cutoff_wavelength <lambda_s> - the short-wavelength cut-off 2 pi/q_s, C(q) = 0 above q_s (default: 4 max(hx, hy), at
                                      most the cell size)
. -adh_rms_height <h> - the rms height sqrt(mean z^2) over the grid points, realised exactly (not with -adh_rms_slope)
. -adh_rms_slope <s> - the rms slope sqrt(mean (grad z)^2), from the Fourier coefficients, realised exactly (default 0.1
                       unless -adh_rms_height is given)
- -adh_seed <seed> - the random seed: each Fourier coefficient is a hash of (seed, kx, ky) (default 1)

  Notes:
  `-help` shows the defaults that depend on the grid as this grid's values. Parameters left at their defaults hold
  `PETSC_DEFAULT`, so that a grid changed afterwards gets its own; they are resolved, and every range checked, by
  `AdhSurfaceGenerate()`. Here only the rms height and slope are checked: not both, and a given value positive and finite.

  Level: intermediate

.seealso: `AdhSurfaceGenerate()`, `AdhSurfaceView()`, `AdhSurfaceWriteHeights()`
@*/
PetscErrorCode AdhSurfaceSetFromOptions(AdhGrid grid, const char prefix[], AdhSurface *s)
{
  MPI_Comm  comm;
  PetscBool seth, sets, setr, setc;
  PetscReal lr, lc, height = 0.0, slope = 0.1;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(grid, ADH_GRID_CLASSID, 1);
  PetscValidPointer(s, 3);
  comm = grid->comm;
  GridDefaults(grid, &lr, &lc);
  PetscCall(PetscMemzero(s, sizeof(*s)));
  s->hurst              = 0.8;
  s->rolloff_wavelength = PETSC_DEFAULT;
  s->cutoff_wavelength  = PETSC_DEFAULT;
  s->rms_height         = PETSC_DEFAULT;
  s->rms_slope          = PETSC_DEFAULT;
  s->seed               = 1;
  PetscOptionsBegin(comm, prefix, "adhbem rough surface (-adh_indenter rough)", "AdhSurface");
  PetscCall(AdhOptionsReal("-adh_hurst", "Hurst exponent H in (0, 1]: C(q) ~ q^(-2(1+H)) between roll-off and cut-off", "AdhSurfaceGenerate", s->hurst, &s->hurst, NULL));
  PetscCall(AdhOptionsReal("-adh_rolloff_wavelength", "Roll-off wavelength 2 pi/q_r, C(q) flat below q_r (default: the cell size max(Lx,Ly)); between the cut-off and the cell size", "AdhSurfaceGenerate", lr, &lr, &setr));
  PetscCall(AdhOptionsReal("-adh_cutoff_wavelength", "Short-wavelength cut-off 2 pi/q_s, C(q) = 0 above q_s (default: 4 max(hx,hy)); at least 2 grid spacings, at most the cell size", "AdhSurfaceGenerate", lc, &lc, &setc));
  PetscCall(AdhOptionsReal("-adh_rms_height", "Rms height sqrt(mean z^2) over the grid points, realised exactly (default 0: not set, -adh_rms_slope sets the amplitude; not with -adh_rms_slope)", "AdhSurfaceGenerate", height, &height, &seth));
  PetscCall(AdhOptionsReal("-adh_rms_slope", "Rms slope sqrt(mean (grad z)^2), defined spectrally from the Fourier coefficients (sum of q^2 abs(z_q)^2, Parseval; exact for this band-limited periodic surface), realised exactly (not used with -adh_rms_height)", "AdhSurfaceGenerate", slope, &slope, &sets));
  PetscCall(AdhOptionsInt("-adh_seed", "Random seed: each Fourier coefficient is a hash of (seed, kx, ky)", "AdhSurfaceGenerate", s->seed, &s->seed, NULL));
  PetscOptionsEnd();
  if (setr) s->rolloff_wavelength = lr;
  if (setc) s->cutoff_wavelength = lc;
  if (seth) s->rms_height = height;
  if (sets) s->rms_slope = slope;
  PetscCheck(!(seth && sets), comm, PETSC_ERR_ARG_INCOMP, "-adh_rms_height and -adh_rms_slope: give one of them, not both");
  PetscCheck(s->seed >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_seed must be >= 0, got %" PetscInt_FMT, s->seed);
  /* Checked here as well as in AdhSurfaceGenerate: a given value must not pass as PETSC_DEFAULT. */
  PetscCheck(!seth || (s->rms_height > 0 && PetscIsNormalReal(s->rms_height)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_rms_height must be positive and finite, got %g", (double)s->rms_height);
  PetscCheck(!sets || (s->rms_slope > 0 && PetscIsNormalReal(s->rms_slope)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_rms_slope must be positive and finite, got %g", (double)s->rms_slope);
  PetscCheck(!setr || (s->rolloff_wavelength > 0 && PetscIsNormalReal(s->rolloff_wavelength)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_rolloff_wavelength must be positive and finite, got %g", (double)s->rolloff_wavelength);
  PetscCheck(!setc || (s->cutoff_wavelength > 0 && PetscIsNormalReal(s->cutoff_wavelength)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_cutoff_wavelength must be positive and finite, got %g", (double)s->cutoff_wavelength);
  PetscFunctionReturn(0);
}

/* The defaults that need the grid, and every range check, naming the option. */
static PetscErrorCode Resolve(AdhGrid grid, AdhSurface *s, PetscReal *lr, PetscReal *lc)
{
  const PetscReal L = PetscMax(grid->Lx, grid->Ly), h = PetscMax(grid->hx, grid->hy);
  const PetscBool seth = (PetscBool)(s->rms_height != PETSC_DEFAULT), sets = (PetscBool)(s->rms_slope != PETSC_DEFAULT);

  PetscFunctionBegin;
  PetscCheck(s->hurst > 0 && s->hurst <= 1, grid->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_hurst: the Hurst exponent must lie in (0, 1], got %g", (double)s->hurst);
  PetscCheck(!(seth && sets), grid->comm, PETSC_ERR_ARG_INCOMP, "-adh_rms_height and -adh_rms_slope: give one of them, not both");
  PetscCheck(!seth || (s->rms_height > 0 && PetscIsNormalReal(s->rms_height)), grid->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_rms_height must be positive and finite, got %g", (double)s->rms_height);
  PetscCheck(!sets || (s->rms_slope > 0 && PetscIsNormalReal(s->rms_slope)), grid->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_rms_slope must be positive and finite, got %g", (double)s->rms_slope);
  *lc = s->cutoff_wavelength == PETSC_DEFAULT ? PetscMin(4.0 * h, L) : s->cutoff_wavelength;
  PetscCheck(*lc >= 2.0 * h * (1.0 - RANGE_RTOL) && *lc <= L * (1.0 + RANGE_RTOL), grid->comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-adh_cutoff_wavelength must lie in [2 max(hx,hy), max(Lx,Ly)] = [%g, %g] (from 2 grid spacings, the Nyquist wavelength, to the cell size), got %g", (double)(2.0 * h), (double)L, (double)*lc);
  *lr = s->rolloff_wavelength == PETSC_DEFAULT ? L : s->rolloff_wavelength;
  PetscCheck(*lr >= *lc * (1.0 - RANGE_RTOL) && *lr <= L * (1.0 + RANGE_RTOL), grid->comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-adh_rolloff_wavelength must lie in [cut-off, max(Lx,Ly)] = [%g, %g] (not shorter than -adh_cutoff_wavelength, not longer than the cell), got %g", (double)*lc, (double)L, (double)*lr);
  PetscFunctionReturn(0);
}

/* Sums over the global index range [0, n) whose entries [start, start+count) this rank formed:
   every entry has one owner, so the MPI sum is exact, and all ranks add them in global order. */
static PetscErrorCode OrderedSum(MPI_Comm comm, PetscInt n, PetscInt nsums, PetscReal *parts, PetscReal *total)
{
  PetscInt k, m;

  PetscFunctionBegin;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, parts, (PetscMPIInt)(n * nsums), MPIU_REAL, MPIU_SUM, comm));
  for (m = 0; m < nsums; m++) {
    total[m] = 0.0;
    for (k = 0; k < n; k++) total[m] += parts[k * nsums + m];
  }
  PetscFunctionReturn(0);
}

/* Fills this rank's kx columns with the coefficients times the spectrum's amplitude and forms
   the per-column sums of |z_q|^2 and q^2 |z_q|^2 over the full spectrum (Hermitian weights). */
static void FillSpectrum(AdhGrid grid, const AdhSurface *s, PetscReal lr, PetscReal lc, ptrdiff_t nkx, ptrdiff_t kx0, fftw_complex *spec, PetscReal *colsums, PetscInt *modes)
{
  const PetscInt  Nx = grid->Nx, Ny = grid->Ny;
  const PetscReal fr = 1.0 / lr, fs2 = 1.0 / (lc * lc) * (1.0 + EDGE_RTOL), e = -(1.0 + s->hurst);
  ptrdiff_t       a;
  PetscInt        k0;

  for (a = 0; a < nkx; a++) {
    const PetscInt  kx        = (PetscInt)(kx0 + a);
    const PetscBool hermitian = (PetscBool)(kx == 0 || 2 * kx == Nx); /* columns whose -kx is not stored */
    const PetscReal w         = hermitian ? 1.0 : 2.0;                /* the -kx half mirrors the others */
    PetscReal       sh = 0.0, ss = 0.0;

    for (k0 = 0; k0 < Ny; k0++) {
      const PetscInt  ky = k0 <= Ny / 2 ? k0 : k0 - Ny;
      const PetscReal fx = kx / grid->Lx, fy = ky / grid->Ly, f2 = fx * fx + fy * fy; /* cycles per length */
      double          re = 0.0, im = 0.0;

      if (f2 > 0 && f2 <= fs2) {
        const PetscReal amp = PetscPowReal(PetscMax(PetscSqrtReal(f2), fr) / fr, e); /* sqrt(C(q)/C(q_r)) */
        if (hermitian && (ky == 0 || 2 * ky == Ny)) { /* self-conjugate: real, variance 1 */
          ModeGaussian(s->seed, kx, ky, &re, &im);
          re *= PETSC_SQRT2;
          im = 0.0;
        } else if (hermitian && ky < 0) { /* the conjugate of the +ky coefficient */
          ModeGaussian(s->seed, kx, -ky, &re, &im);
          im = -im;
        } else ModeGaussian(s->seed, kx, ky, &re, &im);
        re *= amp;
        im *= amp;
        sh += w * (re * re + im * im);
        ss += w * (re * re + im * im) * (4.0 * PETSC_PI * PETSC_PI * f2);
        *modes += hermitian ? 1 : 2;
      }
      spec[a * Ny + k0][0] = re;
      spec[a * Ny + k0][1] = im;
    }
    colsums[2 * (kx0 + a)]     = sh;
    colsums[2 * (kx0 + a) + 1] = ss;
  }
}

/* Per-column sums of the (scaled) coefficients, as FillSpectrum forms them. */
static void ColumnSums(AdhGrid grid, ptrdiff_t nkx, ptrdiff_t kx0, const fftw_complex *spec, PetscReal *colsums)
{
  const PetscInt Nx = grid->Nx, Ny = grid->Ny;
  ptrdiff_t      a;
  PetscInt       k0;

  for (a = 0; a < nkx; a++) {
    const PetscInt  kx = (PetscInt)(kx0 + a);
    const PetscReal w  = (kx == 0 || 2 * kx == Nx) ? 1.0 : 2.0;
    PetscReal       sh = 0.0, ss = 0.0;
    for (k0 = 0; k0 < Ny; k0++) {
      const PetscInt  ky = k0 <= Ny / 2 ? k0 : k0 - Ny;
      const PetscReal fx = kx / grid->Lx, fy = ky / grid->Ly, f2 = fx * fx + fy * fy;
      const double    p  = spec[a * Ny + k0][0] * spec[a * Ny + k0][0] + spec[a * Ny + k0][1] * spec[a * Ny + k0][1];
      sh += w * p;
      ss += w * p * (4.0 * PETSC_PI * PETSC_PI * f2);
    }
    colsums[2 * (kx0 + a)]     = sh;
    colsums[2 * (kx0 + a) + 1] = ss;
  }
}

/* The heights in FFTW's layout: *rows rows of Nx values from row *first on, packed at the start
   of *heights (fftw_free it); the realised statistics go into s. */
static PetscErrorCode GenerateRows(AdhGrid grid, AdhSurface *s, double **heights, PetscInt *first, PetscInt *rows)
{
  PetscInt     Nx, Ny, n1c, N, modes = 0, k, r;
  PetscReal    lr, lc, *sums, tot[2], scale, zmin = PETSC_MAX_REAL, zmax = PETSC_MIN_REAL;
  ptrdiff_t    nn[2], alloc, nkx, kx0, ny, y0;
  double      *data;
  fftw_complex *spec;
  fftw_plan    column, transpose, row;
  char        *wisdom;
  PetscBool    ok;

  PetscFunctionBegin;
  PetscCall(AdhInitializePackage());
  PetscCall(AdhGridSetUp(grid));
  PetscCall(Resolve(grid, s, &lr, &lc));
  Nx = grid->Nx; Ny = grid->Ny; n1c = Nx / 2 + 1; N = Nx * Ny;

  /* One array: kx columns of Ny complex (FFTW's transposed layout), then after the transpose
     y rows of n1c complex, in which each row's c2r transform leaves its Nx heights. */
  nn[0] = n1c; nn[1] = Ny;
  alloc = fftw_mpi_local_size_many_transposed(2, nn, 2, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, grid->comm, &nkx, &kx0, &ny, &y0);
  data  = fftw_alloc_real(PetscMax(alloc, 2));
  PetscCheck(data, grid->comm, PETSC_ERR_MEM, "FFTW could not allocate %td doubles", alloc);
  spec = (fftw_complex *)data;

  wisdom = fftw_export_wisdom_to_string();
  fftw_forget_wisdom();
  column    = fftw_plan_dft_1d((int)Ny, spec, spec, FFTW_BACKWARD, FFTW_ESTIMATE | FFTW_UNALIGNED);
  row       = fftw_plan_dft_c2r_1d((int)Nx, spec, data, FFTW_ESTIMATE | FFTW_UNALIGNED);
  transpose = fftw_mpi_plan_many_transpose(n1c, Ny, 2, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, data, data, grid->comm, FFTW_ESTIMATE);
  fftw_forget_wisdom();
  if (wisdom) {
    (void)fftw_import_wisdom_from_string(wisdom);
    free(wisdom); /* FFTW allocates it with malloc */
  }
  PetscCheck(column && row && transpose, grid->comm, PETSC_ERR_LIB, "FFTW could not plan the %" PetscInt_FMT " x %" PetscInt_FMT " surface transform", Nx, Ny);

  /* Spectrum and its sums; the scale that makes the requested statistic exact (Parseval:
     mean z^2 = sum |z_q|^2 and mean |grad z|^2 = sum q^2 |z_q|^2 for z = sum z_q e^{iqx}). */
  PetscCall(PetscCalloc1(2 * n1c, &sums));
  FillSpectrum(grid, s, lr, lc, nkx, kx0, spec, sums, &modes);
  PetscCall(OrderedSum(grid->comm, n1c, 2, sums, tot));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &modes, 1, MPIU_INT, MPI_SUM, grid->comm));
  ok = (PetscBool)(tot[0] > 0 && tot[1] > 0);
  if (ok) {
    if (s->rms_height != PETSC_DEFAULT) scale = s->rms_height / PetscSqrtReal(tot[0]);
    else scale = (s->rms_slope != PETSC_DEFAULT ? s->rms_slope : 0.1) / PetscSqrtReal(tot[1]);
    for (k = 0; k < (PetscInt)(nkx * Ny); k++) {
      spec[k][0] *= scale;
      spec[k][1] *= scale;
    }
    PetscCall(PetscArrayzero(sums, 2 * n1c));
    ColumnSums(grid, nkx, kx0, spec, sums);
    PetscCall(OrderedSum(grid->comm, n1c, 2, sums, tot));
    s->realised_rms_slope = PetscSqrtReal(tot[1]);
  }
  PetscCall(PetscFree(sums));
  if (!ok) {
    fftw_destroy_plan(column); fftw_destroy_plan(row); fftw_destroy_plan(transpose);
    fftw_free(data);
    SETERRQ(grid->comm, PETSC_ERR_PLIB, "The surface spectrum is empty (cut-off %g on a %g x %g cell)", (double)lc, (double)grid->Lx, (double)grid->Ly);
  }

  /* The inverse transform: columns, transpose, rows; then the rows packed to Nx values each. */
  PetscCall(PetscLogEventBegin(ADH_FFTBackward, 0, 0, 0, 0));
  for (k = 0; k < (PetscInt)nkx; k++) fftw_execute_dft(column, spec + k * Ny, spec + k * Ny);
  fftw_execute(transpose);
  for (r = 0; r < (PetscInt)ny; r++) fftw_execute_dft_c2r(row, spec + r * n1c, data + 2 * r * n1c);
  PetscCall(PetscLogEventEnd(ADH_FFTBackward, 0, 0, 0, 0));
  for (r = 0; r < (PetscInt)ny; r++) memmove(data + r * Nx, data + 2 * r * n1c, (size_t)Nx * sizeof(double));
  fftw_destroy_plan(column); fftw_destroy_plan(row); fftw_destroy_plan(transpose);

  /* Realised statistics from the heights, per row in order, rows added in global order. */
  PetscCall(PetscCalloc1(2 * Ny, &sums));
  for (r = 0; r < (PetscInt)ny; r++) {
    PetscReal s1 = 0.0, s2 = 0.0;
    for (k = 0; k < Nx; k++) {
      const PetscReal v = data[r * Nx + k];
      s1 += v;
      s2 += v * v;
      zmin = PetscMin(zmin, v);
      zmax = PetscMax(zmax, v);
    }
    sums[2 * (y0 + r)]     = s1;
    sums[2 * (y0 + r) + 1] = s2;
  }
  PetscCall(OrderedSum(grid->comm, Ny, 2, sums, tot));
  PetscCall(PetscFree(sums));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &zmin, 1, MPIU_REAL, MPIU_MIN, grid->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &zmax, 1, MPIU_REAL, MPIU_MAX, grid->comm));
  s->realised_mean           = tot[0] / N;
  s->realised_rms_height     = PetscSqrtReal(tot[1] / N);
  s->min_height              = zmin;
  s->max_height              = zmax;
  s->modes                   = modes;
  s->used_rolloff_wavelength = lr;
  s->used_cutoff_wavelength  = lc;
  s->generated               = PETSC_TRUE;

  *heights = data;
  *first   = (PetscInt)y0;
  *rows    = (PetscInt)ny;
  PetscFunctionReturn(0);
}

/*@
  AdhSurfaceGenerate - Generates the heights of a periodic, self-affine, Gaussian random rough surface on a grid

  Collective

  Input Parameters:
+ grid - the grid; it is set up here if it is not yet
- s    - the surface's parameters, from `AdhSurfaceSetFromOptions()`; on return also the resolved parameters and the realised
         statistics

  Output Parameter:
. z - the heights, mean zero, in a vector with the grid's layout (`AdhGridCreateVector()`)

  Notes:
  It resolves the defaults that depend on the grid and checks every range, naming the option: the Hurst exponent in (0, 1],
  the cut-off wavelength in [2 max(hx, hy), max(Lx, Ly)], the roll-off wavelength between the cut-off and max(Lx, Ly). The
  heights are scaled to the requested rms height or slope exactly. The realised statistics (rms height and slope, mean,
  extreme heights, number of Fourier modes) and the wavelengths used are recorded in s.

  The surface is the same to the last bit on any number of ranks (on one machine): each Fourier coefficient is drawn from
  (seed, kx, ky) alone, and the transform and the sums are done in an order that does not depend on the ranks. The cost is
  O(N log N): one inverse FFT. Only the global size of z is checked.

  Level: intermediate

.seealso: `AdhSurfaceSetFromOptions()`, `AdhSurfaceWriteHeights()`, `AdhSurfaceView()`, `AdhGridCreateVector()`
@*/
PetscErrorCode AdhSurfaceGenerate(AdhGrid grid, AdhSurface *s, Vec z)
{
  double  *data;
  PetscInt y0, ny, ys, ym, n, N;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(grid, ADH_GRID_CLASSID, 1);
  PetscValidPointer(s, 2);
  PetscValidHeaderSpecific(z, VEC_CLASSID, 3);
  N = grid->Nx * grid->Ny;
  PetscCall(AdhInitializePackage());
  PetscCall(AdhGridSetUp(grid));
  PetscCall(VecGetSize(z, &n));
  PetscCheck(n == N, grid->comm, PETSC_ERR_ARG_SIZ, "The height Vec has %" PetscInt_FMT " entries; the grid has %" PetscInt_FMT, n, N);
  PetscCall(GenerateRows(grid, s, &data, &y0, &ny));
  /* Where FFTW's rows are the grid's (the usual case: the grid splits its rows as FFTW does) they
     are copied; otherwise one scatter moves them (same global order). */
  PetscCall(AdhGridGetOwnership(grid, &ys, &ym));
  {
    PetscBool same = (PetscBool)(ys == y0 && ym == ny);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &same, 1, MPIU_BOOL, MPI_LAND, grid->comm));
    if (same) {
      PetscScalar *za;
      PetscCall(VecGetArrayWrite(z, &za));
      PetscCall(PetscArraycpy(za, data, ym * grid->Nx));
      PetscCall(VecRestoreArrayWrite(z, &za));
    } else {
      Vec        zf;
      IS         is;
      VecScatter toGrid;
      PetscCall(VecCreateMPIWithArray(grid->comm, 1, ny * grid->Nx, N, data, &zf));
      PetscCall(ISCreateStride(grid->comm, ny * grid->Nx, y0 * grid->Nx, 1, &is));
      PetscCall(VecScatterCreate(zf, is, z, is, &toGrid));
      PetscCall(VecScatterBegin(toGrid, zf, z, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecScatterEnd(toGrid, zf, z, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecScatterDestroy(&toGrid));
      PetscCall(ISDestroy(&is));
      PetscCall(VecDestroy(&zf));
    }
  }
  fftw_free(data);
  PetscFunctionReturn(0);
}

/*@
  AdhSurfaceWriteHeights - Writes the heights of a random rough surface to a viewer as the (Ny, Nx) dataset name

  Collective

  Input Parameters:
+ grid   - the grid; it is set up here if it is not yet
. s      - the surface's parameters; on return also the resolved parameters and the realised statistics, as
           `AdhSurfaceGenerate()` records them
. viewer - the viewer, such as an HDF5 viewer
- name   - the name of the dataset

  Notes:
  It generates the surface again, the same heights z as `AdhSurfaceGenerate()` (not the indenter's profile), and writes them
  with `VecView()` from the generator's own array, in its own row distribution, without a grid vector.

  Level: intermediate

.seealso: `AdhSurfaceGenerate()`, `AdhSurfaceSetFromOptions()`, `AdhSolverWriteOutput()`
@*/
PetscErrorCode AdhSurfaceWriteHeights(AdhGrid grid, AdhSurface *s, PetscViewer viewer, const char name[])
{
  double  *data;
  PetscInt y0, ny;
  Vec      z;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(grid, ADH_GRID_CLASSID, 1);
  PetscValidPointer(s, 2);
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 3);
  PetscValidCharPointer(name, 4);
  PetscCall(AdhInitializePackage());
  PetscCall(AdhGridSetUp(grid));
  PetscCall(GenerateRows(grid, s, &data, &y0, &ny));
  /* the rows where FFTW made them: the viewer writes every rank's rows at their global place */
  PetscCall(VecCreateMPIWithArray(grid->comm, grid->Nx, ny * grid->Nx, grid->Nx * grid->Ny, data, &z));
  PetscCall(PetscObjectSetName((PetscObject)z, name));
  PetscCall(VecView(z, viewer));
  PetscCall(VecDestroy(&z));
  fftw_free(data);
  PetscFunctionReturn(0);
}

/*@
  AdhSurfaceView - Prints the parameters of a random rough surface and, once generated, its realised statistics

  Collective

  Input Parameters:
+ s      - the surface's parameters
- viewer - an ASCII viewer, or `NULL` for `PETSC_VIEWER_STDOUT_WORLD`

  Notes:
  Before `AdhSurfaceGenerate()` it prints the requested parameters, with the defaults in words; after, the wavelengths used, the
  number of Fourier modes and the realised rms height and slope, mean and range of heights. Other viewer types print nothing.

  Level: intermediate

.seealso: `AdhSurfaceSetFromOptions()`, `AdhSurfaceGenerate()`, `AdhSolverView()`
@*/
PetscErrorCode AdhSurfaceView(const AdhSurface *s, PetscViewer viewer)
{
  PetscBool isascii;

  PetscFunctionBegin;
  PetscValidPointer(s, 1);
  if (!viewer) viewer = PETSC_VIEWER_STDOUT_WORLD;
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "Rough surface: self-affine Gaussian, Hurst %g, seed %" PetscInt_FMT "\n", (double)s->hurst, s->seed));
  if (s->rms_height != PETSC_DEFAULT) PetscCall(PetscViewerASCIIPrintf(viewer, "  requested rms height %g\n", (double)s->rms_height));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "  requested rms slope %g (spectral)\n", (double)(s->rms_slope != PETSC_DEFAULT ? s->rms_slope : 0.1)));
  if (s->generated) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  roll-off wavelength %g, cut-off wavelength %g, %" PetscInt_FMT " Fourier modes\n", (double)s->used_rolloff_wavelength, (double)s->used_cutoff_wavelength, s->modes));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  realised: rms height %.15g, rms slope %.15g (spectral), mean %g, heights in [%g, %g]\n", (double)s->realised_rms_height, (double)s->realised_rms_slope, (double)s->realised_mean, (double)s->min_height, (double)s->max_height));
  } else {
    char lr[32] = "the cell size", lc[32] = "4 grid spacings";
    if (s->rolloff_wavelength != PETSC_DEFAULT) PetscCall(PetscSNPrintf(lr, sizeof(lr), "%g", (double)s->rolloff_wavelength));
    if (s->cutoff_wavelength != PETSC_DEFAULT) PetscCall(PetscSNPrintf(lc, sizeof(lc), "%g", (double)s->cutoff_wavelength));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  roll-off wavelength %s, cut-off wavelength %s (not generated yet)\n", lr, lc));
  }
  PetscFunctionReturn(0);
}
