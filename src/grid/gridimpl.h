/* The grid layer's private parts: the grid's struct, the distributed transform and the operators'
   data, shared by grid.c, transform.c, multiplier.c, compliance.c, compliancequery.c and
   meancompliance.c, and read
   by the layers above (geometry, solver, results) through their private headers. */
#ifndef ADHBEM_GRIDIMPL_H
#define ADHBEM_GRIDIMPL_H
#include <fftw3-mpi.h>
#include <petsc/private/petscimpl.h>
#include "adhbem.h"

/* A distributed FFT of a grid's size, shared by its operators (below). */
typedef struct _n_AdhTransform *AdhTransform;

/* Which plans a transform on one rank gets (-adh_fftw_layout); several ranks always take
   FFTW-MPI's transposed ones. */
typedef enum { ADH_FFTW_LAYOUT_AUTO, ADH_FFTW_LAYOUT_SERIAL, ADH_FFTW_LAYOUT_TRANSPOSED } AdhFFTWLayout;

struct _AdhGridOps {
  PetscErrorCode (*view)(AdhGrid, PetscViewer);
};

/* The grid: a PETSc object (PETSCHEADER: name, reference count, -info class adhgrid). */
struct _p_AdhGrid {
  PETSCHEADER(struct _AdhGridOps);
  MPI_Comm     comm;           /* the communicator it was created on (the header holds PETSc's duplicate) */
  PetscInt     Nx, Ny;         /* elements per side */
  PetscReal    Lx, Ly;         /* domain side lengths */
  PetscReal    hx, hy;         /* element sizes Lx/Nx, Ly/Ny */
  PetscInt     ys, ym;         /* this rank's rows: j in [ys, ys + ym), all i */
  PetscBool    setup;
  const char  *prefix;         /* options prefix: the header's (PetscObjectSetOptionsPrefix), also used by the compliance */
  PetscInt     fftw_effort;    /* FFTW planner for operators on this grid: -1 from -adh_fftw_planner, 0 estimate, 1 measure, ... */
  PetscReal    fftw_timelimit; /* seconds per plan on one rank: < -1 from -adh_fftw_timelimit, -1 none */
  /* the options of the grid's operators, read by AdhGridSetFromOptions only (never by a constructor) */
  PetscInt      opt_planner;        /* -adh_fftw_planner: 0 estimate, 1 measure (the default), 2 patient, 3 exhaustive */
  PetscReal     opt_timelimit;      /* -adh_fftw_timelimit, and whether it was given (it wins over fftw_timelimit) */
  PetscBool     opt_timelimit_set;
  AdhFFTWLayout opt_layout;         /* -adh_fftw_layout */
  AdhTransform transforms[2];  /* physical size and zero-padded (2Ny x 2Nx), made on first use */
  MPI_Datatype row_types[2];   /* one row of scalars, of chars (AdhGridGetRowType), made on first use */
};

/* A distributed in-place r2c transform of one size with its array, plans and (where the grid's
   rows are not FFTW's) the redistribution. The operators of one grid share it (the compliance and
   the stiffness of a periodic cell: one array, one pair of plans, and their single-precision twins
   once asked for); only one multiply runs at a time. The grid holds a reference and each operator
   one. */
struct _n_AdhTransform {
  PetscInt   refct;
  ptrdiff_t  n0, n1;                                  /* transform size: rows (y), columns (x) */
  ptrdiff_t  stride;                                  /* doubles per row of the in-place real array */
  ptrdiff_t  local_n0, local_0_start, local_n1, local_1_start;
  PetscBool  serial;                                  /* serial plans (one rank): spectrum [ky][kx] instead of FFTW-MPI's transposed [kx][ky] */
  PetscInt   phys_rows;                               /* physical rows inside this rank's FFTW slab */
  double    *data;                                    /* in-place transform array */
  fftw_plan  forward, backward;
  unsigned   flags;                                   /* the planner's effort the plans were made with, */
  double     timelimit;                               /* and FFTW's time limit for planning */
  float     *fdata;                                   /* the same transform in single precision (MatAdhComplianceSetSinglePrecision): */
  fftwf_plan fforward, fbackward;                     /* made on first use, NULL before */
  Vec        xfft;                                    /* physical values in FFTW's row distribution */
  VecScatter toFFT;                                   /* grid rows -> FFTW's (NULL: they are the same) */
};

/* What the multiplier is: the compliance (free or periodic) or the periodic stiffness. */
typedef enum { ADH_OPERATOR_FREE, ADH_OPERATOR_PERIODIC, ADH_OPERATOR_STIFFNESS } AdhOperatorKind;

typedef struct {
  MPI_Comm     comm;
  AdhOperatorKind kind;
  AdhBoundary  boundary;
  PetscReal    Estar, hx, hy, Lx, Ly;               /* Estar: a half-space's (0 with a symbol) */
  PetscInt     Nx, Ny;
  AdhPeriodicSymbol symbol;                           /* a periodic body's compliance C(|q|) (NULL: the half-space's), */
  void             *symbol_ctx;                       /* and its context: both used while the multiplier is made only */
  AdhTransform t;                                     /* the grid's transform of this size (shared) */
  double      *multiplier;                            /* real kernel spectrum / (n0 n1), in the spectrum's layout (AdhMultiplierIndex); even in ky, so only ky = 0 .. n0/2 are kept */
  ptrdiff_t    nhalf;                                 /* n0/2 + 1 */
  PetscReal    lambda_min, diagonal;
  PetscReal    lambda_meanfree;                       /* smallest eigenvalue on mean-free vectors */
  PetscReal    rownorm;                               /* 2-norm of a row of the circulant: bounds every row of K */
  PetscInt     nmult, nmult_single;                   /* multiplies so far, and of them in single precision */
  PetscBool    single;                                /* MatAdhComplianceMultOnSet in single precision */
} AdhComplianceCtx;

/* K + c0 (1 1^T)/N: the periodic compliance with a finite compliance c0 on the mean mode. Under
   force control the mean pressure is given, so the mean displacement can be carried by any c0 and
   subtracted afterwards; with it every K_CC, the whole cell included, is positive definite. */
typedef struct {
  Mat       K;
  PetscReal c0, N;
} AdhMeanComplianceCtx;

/* Where the multiplier of local kx column a and row ky = k0 <= n0/2 is kept. */
static inline ptrdiff_t AdhMultiplierIndex(const AdhComplianceCtx *c, ptrdiff_t a, ptrdiff_t k0)
{
  return c->t->serial ? k0 * c->t->local_n1 + a : a * c->nhalf + k0;
}

PETSC_INTERN const char *const AdhFFTWLayouts[];
PETSC_INTERN PetscErrorCode AdhTransformRelease_Private(AdhTransform *);
PETSC_INTERN PetscErrorCode AdhTransformEnsureSingle_Private(AdhTransform t, MPI_Comm comm);
PETSC_INTERN PetscErrorCode AdhGridGetTransform_Private(AdhGrid grid, PetscBool padded, PetscInt effort, PetscReal timelimit, AdhFFTWLayout layout, AdhTransform *tout);
PETSC_INTERN PetscErrorCode MatMult_AdhMeanCompliance_Private(Mat A, Vec x, Vec y);
/* The compliance or stiffness shell behind K, with through_mean also behind a mean compliance
   (then *mean is the wrapper's context), or an error naming the caller (compliance.c). */
PETSC_INTERN PetscErrorCode AdhComplianceGet_Private(Mat K, const char caller[], PetscBool through_mean, AdhComplianceCtx **c, AdhMeanComplianceCtx **mean);
PETSC_INTERN PetscErrorCode AdhComplianceFreeMultiplier_Private(AdhComplianceCtx *c);
PETSC_INTERN PetscErrorCode AdhCompliancePeriodicMultiplier_Private(AdhComplianceCtx *c);
PETSC_INTERN PetscErrorCode AdhComplianceRowStatistics_Private(AdhComplianceCtx *c);
PETSC_INTERN PetscErrorCode AdhComplianceStiffnessMultiplier_Private(AdhComplianceCtx *c);
/* The free boundary's operators on the padded grid itself (padded.c): the circulant of the free
   compliance K (inverse false) or its inverse, on vectors of the padded slab layout; their
   multiplies; which local entries are the grid's points; and the moves of a grid vector into the
   physical entries of a padded one (reverse: back). */
/* The transform array's forward FFT, the multiplier and the backward FFT, counted and logged; and
   the destroy of an operator of this context (compliance.c, shared with padded.c). */
PETSC_INTERN PetscErrorCode AdhComplianceConvolve_Private(Mat K, AdhComplianceCtx *c, PetscBool single);
PETSC_INTERN PetscErrorCode AdhComplianceMatDestroy_Private(Mat K);
PETSC_INTERN PetscErrorCode AdhCreatePaddedOperator_Private(Mat K, PetscBool inverse, Mat *A);
PETSC_INTERN PetscErrorCode AdhPaddedGetMultCount_Private(Mat A, PetscInt *count);
PETSC_INTERN PetscErrorCode AdhPaddedGetPhysicalMask_Private(Mat A, char mask[]);
PETSC_INTERN PetscErrorCode AdhPaddedMove_Private(Mat A, Vec x, Vec y, PetscBool reverse);
#endif
