/* Random rough surfaces (surface.c): periodic, self-affine, Gaussian heights on the grid. */
#ifndef ADHBEM_SURFACE_H
#define ADHBEM_SURFACE_H
#include "adhbem.h"

/* The isotropic power spectrum, q = |q|, q = 2 pi (kx/Lx, ky/Ly):
     C(q) = C(q_r)            for 0 < q < q_r = 2 pi / rolloff_wavelength,
     C(q) ~ q^(-2(1+H))       for q_r <= q <= q_s = 2 pi / cutoff_wavelength,
     C(q) = 0                 above q_s and at q = 0 (mean-zero heights).
   Fields set to PETSC_DEFAULT take a default that depends on the grid, resolved (and every
   range checked) by AdhSurfaceGenerate. */
typedef struct {
  /* requested */
  PetscReal hurst;              /* H in (0, 1], default 0.8 */
  PetscReal rolloff_wavelength; /* PETSC_DEFAULT: the cell size max(Lx, Ly) */
  PetscReal cutoff_wavelength;  /* PETSC_DEFAULT: 4 max(hx, hy), at most the cell size */
  PetscReal rms_height;         /* at most one of these two; */
  PetscReal rms_slope;          /* neither (both PETSC_DEFAULT): rms slope 0.1 */
  PetscInt  seed;
  /* after AdhSurfaceGenerate: the resolved parameters and the realised statistics */
  PetscBool generated;
  PetscReal used_rolloff_wavelength, used_cutoff_wavelength;
  PetscReal realised_rms_height; /* sqrt(mean z^2) over the grid points */
  PetscReal realised_rms_slope;  /* sqrt(mean |grad z|^2) from the Fourier coefficients (Parseval) */
  PetscReal realised_mean, min_height, max_height;
  PetscInt  modes;               /* nonzero Fourier modes, counting +q and -q */
} AdhSurface;

/* Fills *s from the defaults and the options -adh_hurst, -adh_rolloff_wavelength,
   -adh_cutoff_wavelength, -adh_rms_height | -adh_rms_slope, -adh_seed (read with prefix). */
PETSC_EXTERN PetscErrorCode AdhSurfaceSetFromOptions(MPI_Comm, const char prefix[], AdhSurface *);
/* Heights z (mean zero) into z, a Vec of size Nx*Ny in the grid's ordering j*Nx + i. Resolves
   the defaults, checks the ranges, scales to the requested rms exactly and records the realised
   statistics in *s. Bit-identical for any number of ranks. Cost O(N log N): one inverse FFT. */
PETSC_EXTERN PetscErrorCode AdhSurfaceGenerate(AdhGrid, AdhSurface *, Vec z);
/* The same heights written to a viewer as the (Ny, Nx) dataset `name`, from the generator's own
   array (no grid vector). */
PETSC_EXTERN PetscErrorCode AdhSurfaceWriteHeights(AdhGrid, AdhSurface *, PetscViewer, const char name[]);
PETSC_EXTERN PetscErrorCode AdhSurfaceView(const AdhSurface *, PetscViewer);
#endif
