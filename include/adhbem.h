/* adhbem: adhesive normal contact of elastic solids with the boundary element method.
   Public C API. Conventions follow PETSc: every function returns PetscErrorCode,
   objects have Create / SetFromOptions / SetUp / View / Destroy, options use the adh_ prefix. */
#ifndef ADHBEM_H
#define ADHBEM_H

#include <petscksp.h>
#include <petscsf.h>
#include "adhbemversion.h"

PETSC_EXTERN PetscClassId ADH_CLASSID;
PETSC_EXTERN PetscLogEvent ADH_FFTForward, ADH_FFTBackward, ADH_ComplianceMult, ADH_Solve, ADH_SetUpdate, ADH_Predict, ADH_DetachTest, ADH_AttachLimits, ADH_LocalSolve;

PETSC_EXTERN PetscErrorCode AdhInitializePackage(void);
PETSC_EXTERN PetscErrorCode AdhUseOneBLASThread(void);
/* ---- sys/version.c: "adhbem 0.1.0 (PETSc 3.18.5)", and the numbers (adhbemversion.h has the macros) ---- */
PETSC_EXTERN PetscErrorCode AdhGetVersion(char version[], size_t len);
PETSC_EXTERN PetscErrorCode AdhGetVersionNumber(PetscInt *major, PetscInt *minor, PetscInt *patch);

/* ---- grid/influence.c: closed-form element integrals (docs/theory/model.md) ---- */

/* Displacement at (x,y), relative to the centre of an hx x hy element carrying unit uniform
   pressure, on a half-space of reduced modulus E* (Love, Johnson eq. 3.25). */
PETSC_EXTERN PetscReal AdhLoveCoefficient(PetscReal x, PetscReal y, PetscReal hx, PetscReal hy, PetscReal Estar);
/* Element self-energy factor chi: U_el = sigma^2 chi / E* (Pohrt & Popov eq. 11). */
PETSC_EXTERN PetscReal AdhChi(PetscReal hx, PetscReal hy);
/* The same for square elements, chi = 0.473201 h^3 (eq. 12). */
PETSC_EXTERN PetscReal AdhChiSquare(PetscReal h);
/* Mesh-dependent critical tensile stress Sigma = sqrt(hx hy E* dgamma / chi) (eq. 13). */
PETSC_EXTERN PetscReal AdhCriticalStress(PetscReal hx, PetscReal hy, PetscReal Estar, PetscReal dgamma);

/* ---- grid/grid.c: the Nx x Ny element grid, distributed by rows ---- */

/* A PETSc object (class "AdhGrid"); its insides are private (src/grid/gridimpl.h). */
typedef struct _p_AdhGrid *AdhGrid;
PETSC_EXTERN PetscClassId ADH_GRID_CLASSID;

PETSC_EXTERN PetscErrorCode AdhGridCreate(MPI_Comm, AdhGrid *);
PETSC_EXTERN PetscErrorCode AdhGridSetSizes(AdhGrid, PetscInt Nx, PetscInt Ny, PetscReal Lx, PetscReal Ly);
PETSC_EXTERN PetscErrorCode AdhGridSetFromOptions(AdhGrid);
PETSC_EXTERN PetscErrorCode AdhGridSetUp(AdhGrid);
PETSC_EXTERN PetscErrorCode AdhGridView(AdhGrid, PetscViewer);
PETSC_EXTERN PetscErrorCode AdhGridDestroy(AdhGrid *);
/* Local rows owned by this rank: j in [ys, ys+ym), all i in [0, Nx). */
PETSC_EXTERN PetscErrorCode AdhGridGetOwnership(AdhGrid, PetscInt *ys, PetscInt *ym);
/* Its elements per side and the domain's side lengths, and (after set-up) the element sizes. */
PETSC_EXTERN PetscErrorCode AdhGridGetSizes(AdhGrid, PetscInt *Nx, PetscInt *Ny, PetscReal *Lx, PetscReal *Ly);
PETSC_EXTERN PetscErrorCode AdhGridGetSpacing(AdhGrid, PetscReal *hx, PetscReal *hy);
/* The number of rows of every rank (an array of the communicator's size; PetscFree it). */
PETSC_EXTERN PetscErrorCode AdhGridGetRowsPerRank(AdhGrid, PetscInt **ly);
/* Other ranks' rows of grid data: a PetscSF with one root per row this rank owns and one leaf per
   entry of rows[] (global rows that other ranks own; a row may be listed more than once), whose
   unit is a whole row, the type AdhGridGetRowType() gives (MPIU_SCALAR for a grid vector's
   array, MPI_CHAR for a byte per point; the grid keeps the type). */
PETSC_EXTERN PetscErrorCode AdhGridCreateRowSF(AdhGrid, PetscInt nrows, const PetscInt rows[], PetscSF *);
PETSC_EXTERN PetscErrorCode AdhGridGetRowType(AdhGrid, MPI_Datatype base, MPI_Datatype *row);
/* A new Vec on the grid: the rows of this rank, block size Nx (a block per row; PETSc's HDF5
   viewer writes it as an (Ny, Nx) dataset). */
PETSC_EXTERN PetscErrorCode AdhGridCreateVector(AdhGrid, Vec *);
/* Centre of element (i,j): x_i = (i - Nx/2) hx, y_j = (j - Ny/2) hy. */
PETSC_EXTERN PetscErrorCode AdhGridGetCoordinates(AdhGrid, PetscInt i, PetscInt j, PetscReal *x, PetscReal *y);

/* ---- geometry/fieldfile.c: fields on the grid given by the user (topographies, dgamma maps) ---- */

/* Reads a (Ny, Nx) field into v, a Vec on the grid: a C-ordered float64/float32 .npy array,
   or the 2-D float dataset `dataset` of an HDF5 file. Collective: checks that the file exists,
   its shape, dtype, and that every value is finite; errors name `option` and the file. */
PETSC_EXTERN PetscErrorCode AdhFieldLoad(AdhGrid, const char option[], const char path[], const char dataset[], Vec v);
/* Collective check that v has the grid's row layout and finite values; errors name `what`. */
PETSC_EXTERN PetscErrorCode AdhFieldCheck(AdhGrid, const char what[], Vec v);

/* ---- geometry/material.c: the reduced modulus ---- */

/* E* from -adh_E_star, or from -adh_E1 -adh_nu1 -adh_E2 -adh_nu2; errors name the option. */
PETSC_EXTERN PetscErrorCode AdhGetReducedModulusFromOptions(MPI_Comm, const char prefix[], PetscReal *Estar);

/* ---- geometry/surface.c: random rough surfaces, periodic, self-affine, Gaussian heights on the grid ---- */

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
   -adh_cutoff_wavelength, -adh_rms_height | -adh_rms_slope, -adh_seed (read with prefix); the
   grid, its sizes set, gives the defaults -help shows. */
PETSC_EXTERN PetscErrorCode AdhSurfaceSetFromOptions(AdhGrid, const char prefix[], AdhSurface *);
/* Heights z (mean zero) into z, a Vec of size Nx*Ny in the grid's ordering j*Nx + i. Resolves
   the defaults, checks the ranges, scales to the requested rms exactly and records the realised
   statistics in *s. Bit-identical for any number of ranks. Cost O(N log N): one inverse FFT. */
PETSC_EXTERN PetscErrorCode AdhSurfaceGenerate(AdhGrid, AdhSurface *, Vec z);
/* The same heights written to a viewer as the (Ny, Nx) dataset `name`, from the generator's own
   array (no grid vector). */
PETSC_EXTERN PetscErrorCode AdhSurfaceWriteHeights(AdhGrid, AdhSurface *, PetscViewer, const char name[]);
PETSC_EXTERN PetscErrorCode AdhSurfaceView(const AdhSurface *, PetscViewer);

/* ---- grid/compliance.c: the half-space compliance as a MatShell on distributed FFTW ---- */

typedef enum { ADH_BOUNDARY_FREE, ADH_BOUNDARY_PERIODIC } AdhBoundary;
PETSC_EXTERN const char *const AdhBoundaries[];

/* Creates K with u = K p on the grid's layout. Options: -adh_fftw_planner estimate|measure|patient|exhaustive. */
PETSC_EXTERN PetscErrorCode MatCreateAdhCompliance(AdhGrid, PetscReal Estar, AdhBoundary, Mat *);
/* Lower bound on the smallest eigenvalue of K and of every principal submatrix K_CC. */
PETSC_EXTERN PetscErrorCode MatAdhComplianceGetLambdaMin(Mat, PetscReal *);
/* Lower bound on the smallest eigenvalue of K_CC for any set C of m grid points (periodic: it
   shrinks to zero as C fills the cell, where K_CC becomes singular). */
PETSC_EXTERN PetscErrorCode MatAdhComplianceGetSetLambdaMin(Mat, PetscInt m, PetscReal *);
/* The grid behind K: Nx points per row, Ny rows. */
PETSC_EXTERN PetscErrorCode MatAdhComplianceGetGridSize(Mat, PetscInt *Nx, PetscInt *Ny);
/* An upper bound on the 2-norm of every row of K, max_k |K e_k|: a change dp of the pressure
   changes every displacement by at most this times |dp|_2. */
PETSC_EXTERN PetscErrorCode MatAdhComplianceGetRowNormBound(Mat, PetscReal *);
PETSC_EXTERN PetscErrorCode MatAdhComplianceHasDirectLayout(Mat, PetscBool *);
PETSC_EXTERN PetscErrorCode MatAdhComplianceMultOnSet(Mat, PetscInt n, const PetscInt local[], Vec xC, Vec yC);
PETSC_EXTERN PetscErrorCode MatAdhComplianceSetSinglePrecision(Mat, PetscBool);
PETSC_EXTERN PetscErrorCode MatAdhComplianceGetSingleMultCount(Mat, PetscInt *);
/* K + c0 (1 1^T)/N: a periodic compliance whose mean mode has the compliance c0 (> 0), which makes
   every K_CC positive definite, the whole cell included; its eigenvalues are K's on mean-free
   vectors and c0. */
PETSC_EXTERN PetscErrorCode MatCreateAdhMeanCompliance(Mat K, PetscReal c0, Mat *);
/* Number of multiplies (FFT pairs) applied so far. */
PETSC_EXTERN PetscErrorCode MatAdhComplianceGetMultCount(Mat, PetscInt *);


/* The periodic stiffness E*|q|/2 on the grid (the inverse compliance symbol), used to
   precondition CG on the contact set. */
PETSC_EXTERN PetscErrorCode MatCreateAdhPeriodicStiffness(AdhGrid, PetscReal Estar, Mat *);
/* A periodic body's compliance symbol: the surface displacement of a unit pressure wave of wave
   number q > 0 (the half-space's is 2/(E* q)); and its compliance (stiffness false) or stiffness
   1/C on the grid. */
typedef PetscReal (*AdhPeriodicSymbol)(void *ctx, PetscReal q);
PETSC_EXTERN PetscErrorCode MatCreateAdhPeriodicSymbolOperator(AdhGrid, AdhPeriodicSymbol, void *ctx, PetscBool stiffness, Mat *);

/* ---- solver/: the adhesive contact solver ---- */

typedef struct _p_AdhSolver *AdhSolver; /* a PETSc object of class ADH_CLASSID */
typedef enum { ADH_START_HERTZ, ADH_START_ADHESIVE } AdhStart;
PETSC_EXTERN const char *const AdhStarts[];
/* When a point off the set joins it: penetration (g < 0), reach (g < Sigma K_00: the gap the
   element closes under its own critical tension), or griffith (crack-closure's mirror: beside the
   contact, when the edge's energy release rate one element further out is below dgamma; reach
   elsewhere). */
typedef enum { ADH_ATTACH_PENETRATION, ADH_ATTACH_REACH, ADH_ATTACH_GRIFFITH } AdhAttach;
PETSC_EXTERN const char *const AdhAttaches[];

/* One recorded state: the step's result, its statistics and its cost. */
typedef struct {
  PetscReal d, force, area, seconds;
  PetscInt  contact_points, outer_iterations, ksp_iterations, compliance_applications;
  PetscInt  patches;                 /* connected clusters of the contact set (4-neighbours; wrapping on a periodic cell) */
  PetscReal mean_gap;                /* mean of the gap g over the whole grid */
  PetscReal max_tension_ratio;       /* largest tension on the set over the critical stress, max(-p/Sigma) (0 without adhesion) */
  PetscReal area_tension;            /* area of the contact set carrying tension, p < 0 */
  PetscReal area_compression;        /* area of the contact set carrying compression, p > 0 */
  PetscInt  pulled_off;              /* 1 on the state that ends a leg by pull-off */
  PetscInt  fft_pairs;               /* forward+backward FFT pairs of the step: compliance and preconditioner */
  PetscReal detach_ratio;            /* the detachment criterion's largest demand over its limit on the set, as a stress ratio (1: a point is about to let go; pohrt-popov: max_tension_ratio) */
  PetscInt  smallest_tensile_patch;  /* points of the smallest patch carrying a net tension (0: none) */
  PetscReal small_patch_tension;     /* share of the set's tension (the sum of its p < 0) carried by patches of fewer than ADH_RESOLVED_PATCH points */
  PetscReal cohesive_area, cohesive_force; /* the area off the contact set that carries a traction (a finite-range criterion's cohesive zone) and its force (0 in the JKR limit) */
  PetscReal contact_perimeter;       /* the length of the contact set's edge: its element edges facing a point off the set, times pi/4 (the mean ratio of a curve's length to its staircase's) */
  PetscReal cohesive_perimeter;      /* the same of the contact with its cohesive zone: the zone's outer edge (the contact's without a zone) */
} AdhState;
/* A contact patch smaller than this many points (a disk under 10 elements in radius) lets go as
   the mesh says rather than as the continuum does: its tension is not resolved by the grid. */
#define ADH_RESOLVED_PATCH 314

/* The recorded states of a path, and the columns of the curve (name, place in AdhState, whether
   it is a count), in the order of the CSV file. */
typedef struct {
  PetscInt  n, cap;
  AdhState *state;
} AdhCurve;
typedef struct {
  const char *name;
  size_t      offset;
  PetscBool   integer;
} AdhCurveColumn;
PETSC_EXTERN const AdhCurveColumn AdhCurveColumns[];
PETSC_EXTERN const PetscInt       AdhCurveNumColumns;
PETSC_EXTERN PetscReal            AdhStateValue(const AdhState *, PetscInt column);

PETSC_EXTERN PetscErrorCode AdhSolverCreate(MPI_Comm, AdhSolver *);
PETSC_EXTERN PetscErrorCode AdhSolverSetOptionsPrefix(AdhSolver, const char[]);
PETSC_EXTERN PetscErrorCode AdhSolverSetFromOptions(AdhSolver);
PETSC_EXTERN PetscErrorCode AdhSolverSetUp(AdhSolver);


/* ---- solver/impls/: the registered types: load control, detachment criterion, contact-set predictor ---- */
/* Load control, a registered type: "displacement" (the path holds indentations d) or "force"
   (the path holds forces F; each step finds the d at which the equilibrium set carries F). */
typedef const char *AdhElasticType;
#define ADHELASTICHALFSPACE "halfspace"
#define ADHELASTICLAYER     "layer"
PETSC_EXTERN PetscErrorCode AdhElasticRegister(const char[], PetscErrorCode (*)(AdhSolver));
PETSC_EXTERN PetscErrorCode AdhSolverSetElasticType(AdhSolver, AdhElasticType);
PETSC_EXTERN PetscErrorCode AdhSolverGetElasticType(AdhSolver, AdhElasticType *);
typedef const char *AdhControlType;
#define ADHCONTROLDISPLACEMENT "displacement"
#define ADHCONTROLFORCE        "force"
PETSC_EXTERN PetscErrorCode AdhControlRegister(const char[], PetscErrorCode (*)(AdhSolver));
PETSC_EXTERN PetscErrorCode AdhSolverSetControlType(AdhSolver, AdhControlType);
PETSC_EXTERN PetscErrorCode AdhSolverGetControlType(AdhSolver, AdhControlType *);
/* Detachment criterion, a registered type: "pohrt-popov" (the paper's p < -Sigma),
   "crack-closure" (the edge's energy release rate by virtual crack closure, G > dgamma, which does
   not depend on the edge's direction on the grid), both the JKR limit, or "dugdale" (finite range:
   Maugis' cohesive zone). */
typedef const char *AdhCriterionType;
#define ADHCRITERIONPOHRTPOPOV   "pohrt-popov"
#define ADHCRITERIONCRACKCLOSURE "crack-closure"
#define ADHCRITERIONDUGDALE      "dugdale"
#define ADHCRITERIONEXPONENTIAL  "exponential"
#define ADHCRITERIONLJ93         "lj93"
PETSC_EXTERN PetscErrorCode AdhCriterionRegister(const char[], PetscErrorCode (*)(AdhSolver));
PETSC_EXTERN PetscErrorCode AdhSolverSetCriterionType(AdhSolver, AdhCriterionType);
PETSC_EXTERN PetscErrorCode AdhSolverGetCriterionType(AdhSolver, AdhCriterionType *);
/* Contact-set predictor, a registered type: "polonsky-keer" (Polonsky & Keer's constrained
   conjugate gradient guesses the set of a force-controlled step without adhesion, which the
   set-update loop then certifies) or "none". It changes the cost, not the answer. */
typedef const char *AdhPredictorType;
#define ADHPREDICTORNONE         "none"
#define ADHPREDICTORPOLONSKYKEER "polonsky-keer"
PETSC_EXTERN PetscErrorCode AdhPredictorRegister(const char[], PetscErrorCode (*)(AdhSolver));
PETSC_EXTERN PetscErrorCode AdhSolverSetPredictorType(AdhSolver, AdhPredictorType);
PETSC_EXTERN PetscErrorCode AdhSolverGetPredictorType(AdhSolver, AdhPredictorType *);

/* ---- solver/interface/: the problem: option names, memory, work of adhesion field, topography ---- */
/* The names of adhbem's own options, without the leading '-' and the prefix (adh_gamma, ...). */
PETSC_EXTERN PetscErrorCode AdhGetOptionNames(PetscInt *n, const char *const **names);
/* The memory the run needs, estimated from the grid, the boundary and the criterion (bytes, all
   ranks together and the ranks on this node). */
PETSC_EXTERN PetscErrorCode AdhSolverEstimateMemory(AdhSolver, PetscLogDouble *total, PetscLogDouble *node);
/* Replaces the scalar work of adhesion by a field dgamma(x,y) (a Vec on the grid). */
PETSC_EXTERN PetscErrorCode AdhSolverSetWorkOfAdhesionField(AdhSolver, Vec);
/* What a topography holds: the height z of the surface, as instruments, SurfaceTopography and
   Tamaas give it (the profile is h = max(z) - z: the highest peak touches at d = 0), or the gap
   h itself. */
typedef enum { ADH_TOPOGRAPHY_HEIGHT, ADH_TOPOGRAPHY_GAP } AdhTopographyKind;
PETSC_EXTERN const char *const AdhTopographyKinds[];
/* The indenter becomes the user's profile z (a Vec on the grid, indenter type "array"). Before
   set-up it is kept for set-up; after set-up the profile is replaced at once and the contact
   state is cleared (start again with AdhSolverStart or AdhSolverSolvePath). */
PETSC_EXTERN PetscErrorCode AdhSolverSetTopography(AdhSolver, Vec z, AdhTopographyKind);

/* ---- solver/interface/: the path: start, steps, monitors, progress ---- */
/* Starting state at the path's first value (an indentation d, or a force under force control):
   hertz or adhesive (loaded from first touch). It begins a new curve. */
PETSC_EXTERN PetscErrorCode AdhSolverStart(AdhSolver, PetscReal target);
/* One step of the path: the equilibrium contact set at indentation d (or carrying force F under
   force control), from the current set. Under force control a set that empties means no
   equilibrium carries F: the contact has come off (AdhSolverGetState gives 0 points). */
PETSC_EXTERN PetscErrorCode AdhSolverStep(AdhSolver, PetscReal target);
/* The whole -adh_path, recording every state in the curve. */
PETSC_EXTERN PetscErrorCode AdhSolverSolvePath(AdhSolver);
/* The -adh_path: its npath points, and the steps of each leg between them (borrowed). */
PETSC_EXTERN PetscErrorCode AdhSolverGetPath(AdhSolver, PetscInt *npath, const PetscReal *path[], PetscInt *steps);
/* Whether a pull-off ends the path (the default) or only its leg (-adh_stop_at_pulloff). */
PETSC_EXTERN PetscErrorCode AdhSolverSetStopAtPullOff(AdhSolver, PetscBool);
PETSC_EXTERN PetscErrorCode AdhSolverGetStopAtPullOff(AdhSolver, PetscBool *);
/* Records the state the last AdhSolverStart or AdhSolverStep reached, as a path does: computed
   (its seconds counted from t0, a PetscTime()), appended to the curve, and returned in *st. */
PETSC_EXTERN PetscErrorCode AdhSolverRecordState(AdhSolver, PetscLogDouble t0, AdhState *st);
/* Monitors: called on every rank after each recorded state of a path (step number, the state).
   -adh_monitor sets AdhSolverMonitorDefault, one line per state. */
PETSC_EXTERN PetscErrorCode AdhSolverMonitorSet(AdhSolver, PetscErrorCode (*)(AdhSolver, PetscInt, const AdhState *, void *), void *, PetscErrorCode (*)(void **));
PETSC_EXTERN PetscErrorCode AdhSolverMonitorCancel(AdhSolver);
/* -adh_progress: seconds of a path before its first progress line (state, time so far, time left),
   then every tenth of the time so far or this, whichever is longer; 0: none. */
PETSC_EXTERN PetscErrorCode AdhSolverSetProgress(AdhSolver, PetscReal seconds);
PETSC_EXTERN PetscErrorCode AdhSolverGetProgress(AdhSolver, PetscReal *seconds);
PETSC_EXTERN PetscErrorCode AdhSolverMonitorDefault(AdhSolver, PetscInt, const AdhState *, void *);
/* Calls the monitors with a recorded state; one that fails on any rank fails on every rank. */
PETSC_EXTERN PetscErrorCode AdhSolverMonitor(AdhSolver, PetscInt step, const AdhState *);

/* ---- solver/interface/: the state, its fields, the resolution of the adhesion, the output ---- */
/* Whether the last step ended in pull-off (the next step starts with the bodies apart). */
PETSC_EXTERN PetscErrorCode AdhSolverIsPulledOff(AdhSolver, PetscBool *);
PETSC_EXTERN PetscErrorCode AdhSolverGetCurve(AdhSolver, const AdhCurve **);
PETSC_EXTERN PetscErrorCode AdhSolverGetIterationNames(AdhSolver, const char *[], const char *[]);
PETSC_EXTERN PetscErrorCode AdhSolverGetGrid(AdhSolver, AdhGrid *);
PETSC_EXTERN PetscErrorCode AdhSolverGetCompliance(AdhSolver, Mat *);
PETSC_EXTERN PetscErrorCode AdhSolverGetContactSet(AdhSolver, IS *);
/* Fields on the grid: pressure p, displacement u = K p, gap g = h - d + u, indenter profile h,
   critical stress Sigma. Borrowed references. The solver keeps no u, nor a Sigma vector for a
   uniform dgamma: asking for them (non-NULL) makes them, current for this state. */
PETSC_EXTERN PetscErrorCode AdhSolverGetFields(AdhSolver, Vec *p, Vec *u, Vec *g, Vec *h, Vec *Sigma);
PETSC_EXTERN PetscErrorCode AdhSolverGetCriticalStress(AdhSolver, PetscReal *);
/* The boundary mode: free (an isolated contact) or periodic (a periodic cell). */
PETSC_EXTERN PetscErrorCode AdhSolverGetBoundary(AdhSolver, AdhBoundary *);
/* The current state: indentation, force, area, points in contact, and the last step's counts
   (set updates, KSP iterations, compliance applications). */
PETSC_EXTERN PetscErrorCode AdhSolverGetState(AdhSolver, PetscReal *d, PetscReal *F, PetscReal *A, PetscInt *points, PetscInt *outer, PetscInt *ksp, PetscInt *mults);
/* The current state with its statistics (patches, mean gap, tension, areas), as recorded. */
PETSC_EXTERN PetscErrorCode AdhSolverComputeState(AdhSolver, AdhState *);
PETSC_EXTERN PetscErrorCode AdhSolverView(AdhSolver, PetscViewer);
/* The recorded state carrying the largest tension, the pull-off force (-1: none carried tension). */
PETSC_EXTERN PetscErrorCode AdhCurveGetPullOffState(const AdhCurve *, PetscInt *);
/* How well the grid resolves the adhesion: the set-up estimate of the smallest asperities' (or the
   sphere's) JKR contact radius in grid spacings, and the curve's state of the largest tension with
   the share of its tension carried by contact patches too small to be resolved, and the verdict. */
typedef struct {
  PetscReal asperity_contact_radius; /* JKR contact radius at pull-off over the grid spacing (0: no estimate) */
  PetscReal asperity_tabor;          /* a finite-range criterion's Tabor parameter of the same asperities (Tabor's mu, Maugis' lambda for dugdale; 0: none) */
  PetscBool touched;                 /* some recorded state had points in contact */
  PetscInt  state;                   /* the curve row of the largest tension (-1: no tension carried) */
  PetscReal force;                   /* the force there (< 0) */
  PetscReal small_patch_tension;     /* the share of its tension in patches under ADH_RESOLVED_PATCH points */
  PetscInt  smallest_tensile_patch;  /* points of the smallest patch with a net tension there */
  PetscBool resolved;                /* the grid resolves the adhesion (meaningful when state >= 0) */
  PetscReal cohesive_elements;       /* a finite-range criterion: the elements its cohesive zone covers there (0: none) */
  PetscReal cohesive_width;          /* and how many grid spacings wide it is: a sphere's annulus around the contact's disk, else the zone's area over the mean of its inner and outer edges (0: none) */
  PetscInt  apart;                   /* the first state where the surfaces came apart (pulled_off): only then is the largest tension the pull-off force (-1: they did not) */
  PetscInt  full_contact;            /* the first state in full contact, every point of the grid in the contact set (-1: none) */
  PetscInt  last_points;             /* the points in contact at the last state (the path ended with them when not apart) */
  PetscInt  stopped;                 /* the state at which a pull-off ended the path with legs left (-adh_stop_at_pulloff; -1: it did not) */
  PetscInt  unresolved;              /* why the grid does not resolve it there: ADH_UNRESOLVED_* flags (0: it does, or no state carried tension) */
} AdhResolution;
/* The verdict's rule: the grid resolves the adhesion at the state of largest tension unless */
#define ADH_UNRESOLVED_PATCHES    1 /* more than 10% of the tension is carried by patches of fewer than ADH_RESOLVED_PATCH points */
#define ADH_UNRESOLVED_ASPERITIES 2 /* the set-up estimate of the smallest asperities' (or the sphere's) JKR radius is under 10 grid spacings */
#define ADH_UNRESOLVED_ZONE       4 /* the cohesive zone is under 10 grid spacings wide */
PETSC_EXTERN PetscErrorCode AdhSolverGetResolution(AdhSolver, AdhResolution *);
/* Whether a rough surface is sticky, estimated at set-up from its heights (either boundary): the
   elastic energy of full contact against the work of adhesion (Persson & Tosatti 2001), and with a
   finite-range criterion the Pastewka-Robbins criterion (2014) and the generalised Tabor parameter. */
typedef struct {
  PetscBool estimated;           /* the estimate exists (a rough surface, topography or array, with adhesion) */
  PetscReal rms_slope;           /* h'_rms, the rms of |grad h| */
  PetscReal rms_curvature;       /* h''_rms, the rms of the mean curvature (half the Laplacian of h) */
  PetscReal full_contact_energy; /* U_el / A0, the elastic energy per area that flattens the surface (full contact) */
  PetscReal work_of_adhesion;    /* dgamma (with a field: its mean) */
  PetscReal persson_tosatti;     /* U_el / (dgamma A0): below 1 full contact costs less than the adhesion gives */
  PetscReal range;               /* the criterion's range Delta r (0: a zero-range criterion) */
  PetscReal pastewka_robbins;    /* h'_rms E* Delta r / (2 dgamma) (h'_rms^2 / (h''_rms Delta r))^(2/3): below 1 sticky (0: zero range) */
  PetscReal tabor;               /* the generalised Tabor parameter (R dgamma^2 / (E*^2 Delta r^3))^(1/3), R = 1/h''_rms (0: zero range) */
  PetscBool sticks_everywhere;   /* persson_tosatti < 1 */
  PetscBool sticky;              /* sticks_everywhere, or pastewka_robbins < 1; known only with one of them (sticks_everywhere, or range > 0): a zero-range criterion on a surface that does not stick everywhere leaves it to the run (PETSC_FALSE) */
} AdhStickiness;
PETSC_EXTERN PetscErrorCode AdhSolverGetStickiness(AdhSolver, AdhStickiness *);
/* The line on the stickiness ("adhbem: stickiness: ..."; nothing without an estimate). */
PETSC_EXTERN PetscErrorCode AdhSolverStickinessView(AdhSolver, PetscViewer);
/* The lines on how well the grid resolves the adhesion (nothing without tension; a run that never
   touched says so). */
PETSC_EXTERN PetscErrorCode AdhSolverResolutionView(AdhSolver, PetscViewer);
/* Writes the curve and parameters to FILE.h5 and FILE.csv (with -adh_fields, the fields of
   every step too). Files appear whole or not at all. */
PETSC_EXTERN PetscErrorCode AdhSolverWriteOutput(AdhSolver, const char file[]);
/* A results file written state by state from the caller's loop of AdhSolverStart()/AdhSolverStep():
   opened, a call after each recorded state (its row, and its fields with -adh_fields), closed. */
PETSC_EXTERN PetscErrorCode AdhSolverOutputBegin(AdhSolver, const char file[]);
PETSC_EXTERN PetscErrorCode AdhSolverOutputRecord(AdhSolver);
PETSC_EXTERN PetscErrorCode AdhSolverOutputEnd(AdhSolver, PetscBool complete);
PETSC_EXTERN PetscErrorCode AdhSolverDestroy(AdhSolver *);

#endif
