/* The AdhSolver's insides: the private header of the solver layer. Its interface (interface/: life
   cycle, one step, the path) and its registered types (impls/<kind>/) include it, and so does the
   results layer above it (src/results/). */
#ifndef ADHBEM_SOLVERIMPL_H
#define ADHBEM_SOLVERIMPL_H
#include <petsc/private/petscimpl.h>
#include <petscviewerhdf5.h>
#include "adhbem.h"
#include "grid/gridimpl.h"
#include "geometry/indenter.h"
#include "geometry/material.h"
#include "sys/sysimpl.h"

/* A window of the plane for the bounding-box convolution (interface/box.c). */
typedef struct {
  PetscInt bx, by;
  AdhGrid  grid;
  Mat      K, S;   /* free compliance and periodic stiffness on the window */
} AdhBox;

/* An option's value that shapes the answer, named as the user gives it: a restart must repeat it
   (the results layer's checkpoint compares them). */
typedef struct {
  const char   *option;
  PetscDataType type;
  const void   *value;
  const void   *absent; /* the value of a checkpoint written before the option existed (NULL: this run's) */
} AdhShapingOption;
#define ADH_MAX_TYPE_SHAPES 8 /* a type's shape op fills at most this many (checkpoint.c checks) */

/* What every type of the solver's four kinds (elastic body, criterion, control, predictor) may do besides its
   kind's work, as PETSc's types do (KSPSetFromOptions_CG, KSPView_CG). Each may be NULL. The
   type's data is its own (the kind's data pointer), made by its create function and freed by its
   destroy. */
typedef struct {
  PetscErrorCode (*setfromoptions)(AdhSolver, AdhOptionItems); /* its options, in a -help group of its own */
  PetscErrorCode (*view)(AdhSolver, PetscViewer); /* ASCII: its lines of AdhSolverView; HDF5: its attributes in the results file */
  PetscErrorCode (*setup)(AdhSolver);             /* at the solver's set-up, after the operators */
  PetscErrorCode (*destroy)(AdhSolver);           /* frees its data */
  /* the options of it that shape the answer, at most ADH_MAX_TYPE_SHAPES */
  PetscErrorCode (*shape)(AdhSolver, PetscInt *n, AdhShapingOption[]);
  /* its state in a checkpoint's root group: written (load false) or read */
  PetscErrorCode (*checkpoint)(AdhSolver, PetscViewer, PetscBool load);
  /* the bytes it adds to AdhSolverEstimateMemory's model: per grid point and per rank */
  PetscErrorCode (*memory)(AdhSolver, PetscLogDouble *per_point, PetscLogDouble *per_rank);
} AdhTypeOps;

/* What an elastic body does (impls/elastic/): it makes the compliance (and the periodic stiffness
   that preconditions the solves) and gives the solver every elastic constant it needs, so that no
   half-space closed form is used outside the body's files. Its setup runs first of the solver's
   set-up, before the operators are made, and fills in the constants below (the solver checks
   them). The half-space's closed forms live in the body's files: impls/elastic/ and, for the
   periodic bodies given by a symbol, interface/periodicbody.c. */
typedef struct {
  AdhTypeOps base;
  void      *data;
  PetscBool  periodic_only; /* it has no free-boundary compliance (a layer: the periodic cell only) */
  PetscBool  halfspace;     /* the closed forms of half-space contact (Hertz, JKR, Maugis) are its answers */
  /* its compliance K on a grid for a boundary (the solver's, or a bounding-box window's, free) and
     the periodic stiffness S of the grid (the Fourier preconditioner, and the energy of full contact) */
  PetscErrorCode (*create_operators)(AdhSolver, AdhGrid, AdhBoundary, Mat *K, Mat *S);
  /* the modulus 2/(q C(q)) a pressure wave of wave number q meets (the half-space: E* at every q),
     for the estimates made before a run (resolution, Tabor's parameter, stickiness) */
  PetscReal (*modulus)(AdhSolver, PetscReal q);
  /* the paper's critical stress Sigma of a work of adhesion dgamma */
  PetscReal (*critical_stress)(AdhSolver, PetscReal dgamma);
  /* the constants, set by the body's setup: */
  PetscReal self_compliance; /* K_00: an element's displacement at its centre under its own unit pressure */
  PetscReal chi_per_area;    /* dgamma = chi_per_area Sigma^2: the element's self-energy over its area, per squared stress */
  PetscReal stress_per_work; /* Sigma^2 = stress_per_work dgamma: the paper's critical stress (Sigma_field's scale) */
  PetscReal mean_compliance; /* the compliance force control gives a periodic cell's mean mode, that of the longest wave */
} AdhElasticOps;

/* What every periodic body given by its compliance symbol shares (interface/periodicbody.c): its
   operators (the free boundary refused), and the element's constants, the half-space's of modulus
   Eref plus what the body adds within `depth` of the surface (approximate under an eighth of an
   element: *approximate). */
PETSC_INTERN PetscErrorCode AdhElasticPeriodicOperators_Private(AdhSolver, AdhGrid, AdhBoundary, AdhPeriodicSymbol, void *, Mat *K, Mat *S);
PETSC_INTERN PetscErrorCode AdhElasticPeriodicConstants_Private(AdhSolver, AdhPeriodicSymbol, void *, PetscReal Eref, PetscReal depth, PetscBool *approximate);
PETSC_INTERN PetscReal      AdhElasticCriticalStress_Private(AdhSolver, PetscReal dgamma);

/* What a load control's path holds. */
typedef enum { ADH_TARGET_INDENTATION, ADH_TARGET_FORCE } AdhTarget;

/* What a load control does (impls/control/): one step to a target (an indentation or a force).
   A step that runs the set-update loop (AdhSolverUpdateSet_Private, setupdate.c) gives it the
   equilibrium of the current set at the target. */
typedef struct {
  AdhTypeOps base;
  void      *data;
  AdhTarget  target;   /* what the path holds */
  PetscBool  cascades; /* its steps re-solve at a fixed target: -adh_cascade_apart and -adh_cascade_local apply */
  PetscErrorCode (*step)(AdhSolver, PetscReal target);
  /* the pressure of the current set in equilibrium at the target, or *none: no equilibrium is left
     (the set has emptied) */
  PetscErrorCode (*equilibrate)(AdhSolver, PetscReal target, PetscBool *none);
  /* optional: after a detach test that let nothing go, how fast each gap closes as the set's
     indentation e rises, and e (the points then join in the order they would touch); rate NULL:
     all at once */
  PetscErrorCode (*attach_rate)(AdhSolver, Vec *rate, PetscReal *e);
} AdhControlOps;

/* What the detach test of the exact solution of a solve is, as far as an iterate tells. */
typedef enum { ADH_DETACH_IN_DOUBT, ADH_DETACH_NONE, ADH_DETACH_SOME } AdhDetachDecision;

/* What a detachment criterion does (impls/criterion/): evaluate the current state, removing the points
   that let go (detach) or giving the largest demand over its limit on the set (ratio). */
typedef struct {
  AdhTypeOps base;
  void      *data;
  AdhAttach  attach;       /* the attach rule it pairs with, the default (the zero value: penetration) */
  PetscBool  griffith;     /* its detach test leaves the griffith attach rule's limits (s->attach_limit): only it may use griffith */
  PetscBool  local_solves; /* the default route re-solves the whole set after points let go (-adh_cascade_local inf), where the control allows it */
  PetscBool  cohesive;     /* it holds tractions off the contact set, in p there (a finite-range model's cohesive zone): the set's solves take their load */
  PetscErrorCode (*evaluate)(AdhSolver, PetscBool detach, PetscInt *removed, PetscReal *ratio);
  PetscErrorCode (*begin)(AdhSolver); /* optional: a step (or a trial of one) begins its set updates */
  /* Optional, for the certified early stop of intermediate solves: the detach test of the exact
     solution p*, decided from the iterate xC (on the set) when every point's decision holds for
     any p within perr of it (perr bounds |p - p*| at every point). With the test in doubt,
     *needed is the bound at which the decisions in doubt now would be made (the next check is
     worth its cost below it); PETSC_MAX_REAL: check again at the next iteration; 0 with NONE:
     decided for the rest of the solve. */
  PetscErrorCode (*decide)(AdhSolver, Vec xC, PetscReal perr, AdhDetachDecision *, PetscReal *needed);
  /* Optional: a cohesive law, whose steps minimise the total energy (interface/minimize.c) instead
     of updating a set. The potential phi per unit area at gap g >= 0 of a point with work of
     adhesion dgamma > 0 (phi(0) = -dgamma, phi -> 0 far apart), its derivative (the attraction,
     >= 0) and its second derivative. */
  void (*law)(const void *data, PetscReal dgamma, PetscReal g, PetscReal *phi, PetscReal *dphi, PetscReal *ddphi);
  /* with a law: the gap below which a point off the contact counts in the cohesive zone, and the
     law's largest attraction, both for a point with work of adhesion dgamma */
  PetscReal (*zone_gap)(const void *data, PetscReal dgamma);
  PetscReal (*peak)(const void *data, PetscReal dgamma);
  /* with a law whose second derivative can be positive (it stiffens the energy near the wall, as
     the 9-3 law does): the minimisation's preconditioner is scaled by it (else never looked at) */
  PetscBool stiffens;
  /* Optional, a finite-range criterion's: its Tabor parameter for a summit of radius R with work
     of adhesion dgamma, and the parameter's name ("Tabor's mu", "Maugis' lambda") */
  PetscReal (*tabor)(AdhSolver, PetscReal R, PetscReal dgamma);
  const char *tabor_name;
  /* Optional, a finite-range criterion's: the range of its attraction for work of adhesion dgamma
     (the gap over which the work is done; the stickiness report's Delta r) */
  PetscReal (*range)(AdhSolver, PetscReal dgamma);
} AdhCriterionOps;

/* The energy minimisation of a step under a cohesive law (interface/minimize.c): its options, in
   the law's -help group, and its data (made at the first step). */
typedef struct _n_AdhMinimizer *AdhMinimizer;
PETSC_INTERN PetscErrorCode AdhSolverMinimizeSetFromOptions_Private(AdhSolver, AdhOptionItems);
PETSC_INTERN PetscErrorCode AdhSolverMinimizeView_Private(AdhSolver, PetscViewer);
PETSC_INTERN PetscErrorCode AdhSolverMinimizeDestroy_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverMinimizeMultCount_Private(AdhSolver, PetscInt *);
PETSC_INTERN PetscLogDouble AdhSolverMinimizeMemory_Private(AdhSolver);
/* The ops every smooth cohesive law shares (interface/cohesivelaw.c). */
PETSC_INTERN PetscErrorCode AdhSolverLawSetUp_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverLawEvaluate_Private(AdhSolver, PetscBool, PetscInt *, PetscReal *);
PETSC_INTERN PetscErrorCode AdhSolverLawMemory_Private(AdhSolver, PetscLogDouble *, PetscLogDouble *);
PETSC_INTERN PetscErrorCode AdhSolverLawDestroy_Private(AdhSolver);

/* What a contact-set predictor does (impls/predictor/): guess a step's set and pressure without
   adhesion, at an indentation or carrying a force (force true); NULL predict: no guess. */
typedef struct {
  AdhTypeOps base;
  void      *data;
  PetscErrorCode (*predict)(AdhSolver, PetscBool force, PetscReal target);
} AdhPredictorOps;

/* The registries of the four kinds (interface/elastic.c, criterion.c, control.c, predictor.c); the
   built-in types are registered in impls/register.c, which the solver's package calls. */
PETSC_INTERN AdhRegistry AdhElastics, AdhCriteria, AdhControls, AdhPredictors;
/* The four kinds' ops of a solver, the body first, and their registries in the same order. */
#define ADH_NUM_KINDS 4
PETSC_INTERN void AdhSolverGetTypeOps_Private(AdhSolver, AdhTypeOps *ops[ADH_NUM_KINDS], AdhRegistry *regs[ADH_NUM_KINDS], const char *names[ADH_NUM_KINDS]);
/* The modulus a JKR contact of work dgamma on a summit of radius R meets (the body's at the wave
   number 1/a of its contact radius a; E* on a half-space), for the estimates made before a run. */
PETSC_INTERN PetscReal AdhSolverSummitModulus_Private(AdhSolver, PetscReal R, PetscReal dgamma);
/* Gives the solver the type `type` of a kind (nothing if it has it): the previous type's destroy,
   the kind's ops (whose first member is its AdhTypeOps) zeroed, the new type's create, and its
   set-up if the solver's is done (fixed: the kind cannot change after set-up); current holds the
   name (types.c). */
PETSC_INTERN PetscErrorCode AdhSolverSetType_Private(AdhSolver, AdhRegistry *, char current[64], AdhTypeOps *ops, size_t size, const char type[], PetscBool fixed);
/* The options of a type in its own -help group ("adhbem <what> <name> (-option name)"; types.c). */
PETSC_INTERN PetscErrorCode AdhSolverTypeSetFromOptions_Private(AdhSolver, AdhRegistry *, const char type[], AdhTypeOps *);

/* What a path does with its results: the results file (the curve, the fields) and the checkpoint.
   Written by the results layer (src/results/), bound in interface/solverpackage.c, so that the solver calls it
   without depending on it. */
typedef struct {
  PetscErrorCode (*check_writable)(AdhSolver, const char option[], const char file[]);
  PetscErrorCode (*open)(AdhSolver, const char file[], PetscViewer *);   /* a new results file */
  PetscErrorCode (*resume)(AdhSolver, const char file[], PetscViewer *); /* a restart's: the earlier run's file taken over */
  PetscErrorCode (*write_fields)(AdhSolver, PetscViewer, PetscInt state);
  PetscErrorCode (*append)(AdhSolver, PetscViewer); /* the states recorded since the last call */
  PetscErrorCode (*close)(AdhSolver, const char file[], PetscViewer *);
  PetscErrorCode (*abandon)(PetscViewer *); /* a file whose write failed, closed as it is */
  PetscErrorCode (*checkpoint_write)(AdhSolver, PetscInt leg, PetscInt step);
  PetscErrorCode (*checkpoint_read)(AdhSolver, PetscInt *leg, PetscInt *step);
} AdhResultsOps;
PETSC_INTERN AdhResultsOps AdhResults;

#define ADH_MAX_MONITORS 8

/* The fields a results file can hold (-adh_fields), as bits. */
enum { ADH_FIELD_PRESSURE = 1, ADH_FIELD_DISPLACEMENT = 2, ADH_FIELD_GAP = 4, ADH_FIELD_CONTACT = 8, ADH_FIELD_ALL = 15 };
PETSC_INTERN const char *const AdhFieldNames[4]; /* their names, bit k: AdhFieldNames[k] (solveropts.c) */

/* The solver's operations as a PETSc object: its view (the types' own ops are in cops, crops, pops). */
struct _AdhSolverOps {
  PetscErrorCode (*view)(AdhSolver, PetscViewer);
};

/* The solver: a PETSc object (PETSCHEADER: name, reference count, options prefix, -info class). */
struct _p_AdhSolver {
  PETSCHEADER(struct _AdhSolverOps);
  MPI_Comm    comm;           /* the communicator it was created on (the header holds PETSc's duplicate) */
  char       *prefix;
  PetscBool   setup;

  /* problem */
  AdhGrid     grid;
  AdhBoundary boundary;
  PetscBool   boundary_set;   /* -adh_boundary was given (not the default) */
  AdhIndenter indenter;
  PetscReal   Estar, gamma;
  PetscReal   sigma_fixed;    /* > 0: a mesh-independent critical stress replaces Pohrt-Popov's */
  PetscReal   Sigma;          /* critical stress of the scalar dgamma (for reports) */
  Vec         gamma_field;    /* optional dgamma(x,y) */
  char        gamma_file[PETSC_MAX_PATH_LEN]; /* -adh_gamma_field: dgamma(x,y) read at set-up */
  char        gamma_dataset[256];

  /* operators and fields on the grid */
  Mat       K;                /* compliance */
  Mat       S;                /* periodic stiffness: the preconditioner */
  Vec       h, p, g;
  PetscBool gap_current;       /* g is the gap of the current p: the detach test just computed it and let nothing go */
  Vec       Sigma_field;      /* critical stress of a dgamma field; NULL for a uniform dgamma (Sigma) */
  Vec       Sigma_view;       /* a uniform Sigma as a grid vector, made when asked for (AdhSolverGetFields) */
  Vec       u;                /* made when asked for (AdhSolverGetDisplacement_Private) */
  Vec       off_load, off_work; /* a cohesive criterion's tractions off the set and their load (setsolve.c), made on first use */
  PetscReal mean_h;           /* mean of h: a periodic cell is in full contact at d = mean_h */
  PetscInt  profile_version;  /* counts the profiles h has held (AdhSolverProfileChanged_Private) */

  /* elastic body (impls/elastic/) */
  char          elastic_type[64];
  AdhElasticOps eops;
  AdhMaterial   material;       /* the solids' constants as given (E* is Estar above) */

  /* load control (impls/control/) */
  char          control_type[64];
  AdhControlOps cops;
  Vec           set_response;   /* a control's vector on the contact set, kept zero off it (force control: the set's response to a unit indentation; NULL: none) */
  Mat           Kcontrol;       /* the operator of the set's equations on the whole grid where the control replaces K (force control on a periodic cell: K + c0 (1 1^T)/N; NULL: K) */
  PetscReal     Kcontrol_lambda; /* a lower bound on its eigenvalues beyond K's on the set */
  PetscBool     pulled_off;     /* the last step ended in pull-off */
  PetscBool     law_apart;      /* a cohesive law's last minimisation found no state carrying the force: the bodies fly apart */

  /* contact-set predictor (impls/predictor/) */
  char            predictor_type[64];
  AdhPredictorOps pops;
  PetscBool       predictor_chosen;  /* set by the user (else chosen by the boundary at set-up) */
  /* detachment criterion (impls/criterion/) */
  char            criterion_type[64];
  AdhCriterionOps crops;
  AdhMinimizer    minimizer;        /* a cohesive law's energy minimisation (NULL: none yet) */
  PetscReal       minimize_rtol;    /* -adh_minimize_rtol: it stops at this relative projected gradient */
  PetscInt        minimize_max_it;  /* -adh_minimize_max_it */
  PetscBool       minimize_pc;      /* -adh_minimize_pc fourier: the compliance preconditions it */
  PetscBool       minimize_newton;  /* -adh_minimize_direction newton (else polak-ribiere) */
  PetscReal       minimize_trust;   /* -adh_minimize_trust_region: the Newton step's trust region over the last step (0: none) */
  PetscBool       minimize_monitor; /* -adh_minimize_monitor: a line per iteration */
  PetscBool       memory_check;     /* refuse a grid that clearly does not fit into a node (estimate.c) */
  PetscReal       rms_slope, rms_curvature, full_contact_energy; /* a rough profile's, for the two estimates (roughness.c, made once a profile; 0: none) */
  PetscReal       asperity_ac;      /* estimated JKR contact radius of the smallest asperities over h (resolution.c; 0: none) */
  PetscReal       asperity_tabor;   /* a finite-range criterion's Tabor parameter of those asperities (0: none) */
  AdhStickiness   stickiness;       /* the set-up estimate of a rough surface's stickiness (stickiness.c) */

  /* contact set: in_set[k] for the local points, and the same as a PETSc IS */
  char     *in_set;
  char     *left;             /* points that let go during the current step (they stay off: AttachLimit) */
  PetscInt  cascade_apart;    /* -adh_cascade_apart D: points join in an update that lets others go, D spacings away from them (0: off) */
  PetscInt  apart_D;          /* the width the marks' band was set up for: the larger of the two cascades' */
  PetscBool apart_pending;    /* in such an update, from before the detach to the end of the attach test (cascadeapart.c) */
  char     *gone;             /* with cascade_apart or cascade_local: the points let go in the current update, then those within D or W of them */
  PetscSF   apart_sf;         /* with either: the marks of the apart_D rows beyond a rank's own (cascadeapart.c) */
  PetscInt *apart_source, *apart_rows, *apart_count;
  char     *apart_ghost, *apart_band, *apart_any;
  PetscReal cascade_local;    /* -adh_cascade_local F: after a set update lets points go, re-solve the set within F times the smallest asperities' JKR radius of them only (0: off; inf: the whole grid, the default with crack-closure; cascadelocal.c) */
  PetscBool cascade_local_set; /* F was given: no default chosen by the criterion and the control */
  PetscInt  local_W;          /* that width in grid spacings, for the current profile (0: off) */
  PetscBool local_whole;      /* that window covers the grid: the window is the set, no marks needed */
  void     *local_converged;  /* the local KSP's default convergence test's context */
  PetscReal cascade_local_rtol; /* the relative residual those local solves stop at */
  PetscBool local_pending;    /* a detach test whose points let go are marked for the next local solve */
  KSP       local_ksp;        /* the local solves' KSP, on the window: the set's points within W of those let go */
  Mat       Kww;              /* K restricted to the window */
  Vec       pW, bW;           /* correction and right-hand side on the window */
  PetscInt *win_local, nwin_local, nwin; /* local offsets of this rank's points in the window; its global size */
  VecScatter win_scatter;     /* window values -> the operator's grid (not on the direct path) */
  PetscInt  step_local_solves; /* this step's local solves */
  PetscInt  step_largest;     /* the largest set of the current step (points) */
  PetscInt  nlocal;
  AdhAttach attach;
  PetscBool attach_chosen; /* set by the user (else griffith with crack-closure, reach otherwise, at set-up) */
  Vec       attach_limit;      /* griffith: the gap below which each open point joins, from the last detach test (crack-closure's G vector, written over) */
  PetscBool attach_limit_current; /* it belongs to the current p (the detach test just before let nothing go) */
  IS        contact;
  PetscInt  npoints;          /* global size of the set */
  PetscInt  set_version;      /* counts the sets the solver has held (AdhSolverRebuildSet_Private) */
  KSP       ksp;
  Mat       Kcc;              /* K restricted to the set, applied on the window or the grid */
  IS        contact_op;       /* the set in the numbering of the operator behind Kcc */
  Mat       Kop, Sop;         /* compliance and stiffness of the window or grid in use (borrowed) */
  PetscReal lambda_set;       /* lower bound on the eigenvalues of K_CC for the current set */
  Vec       op_in, op_out;    /* work vectors on that window or grid */
  PetscBool direct_set;       /* the periodic grid: set values go straight into the transform */
  VecScatter set_scatter;     /* set values -> that window or grid */
  PetscInt *set_local, nset_local; /* local offsets of this rank's points in the set */
  Vec       pC, bC;           /* pressure and right-hand side on the set */
  PetscScalar *thrC;          /* allowed tension on the set, with a critical stress field (NULL: uniform) */

  /* bounding-box convolution */
  PetscBool use_box;
  AdhBox   *boxes, *box;      /* cache, and the window in use (NULL: the whole grid) */
  PetscInt  nboxes, maxboxes, box_i0, box_j0;

  /* the current solve, read by the convergence test and the preconditioner */
  const PetscScalar *threshold_local; /* -threshold is the allowed tension, on the set (NULL: threshold_uniform) */
  PetscReal          threshold_uniform;
  PetscReal bnorm;
  PetscBool certify, certify_solve, certified_stop;
  PetscReal cascade_rtol;     /* -adh_cascade_rtol: the solves between set updates stop at this relative residual (0: at the KSP's) */
  PetscBool cascade_single;   /* -adh_cascade_single: those solves in single precision */
  PetscBool solve_loose;      /* the current solve is one of those */
  PetscReal detach_perr;      /* the error bound below which the next detach decision is worth its cost */
  PetscBool detach_none;      /* decided: the exact solution lets no point go */
  PetscBool certify_attach, certified_attach; /* the solve may stop, and did, once the points that join are certain */
  PetscReal attach_rnorm;     /* the residual below which the next attach check is worth its multiply */
  PetscInt  joined_step, joined_previous; /* points that joined in this step and in the one before */

  /* state and counters */
  PetscReal d;
  PetscBool adhesive;         /* false while computing a Hertz (dgamma = 0) start */
  PetscInt  max_outer;
  PetscInt  step_outer, step_ksp, step_mults, step_ffts;
  PetscInt  step_id; /* AdhSolverStep()s so far: which step a step-scoped memory belongs to (the force walk's) */
  PetscLogDouble progress_time;  /* last progress line inside a step (-adh_monitor) */
  PetscReal monitor_interval;   /* seconds between progress lines */
  /* the path's progress (path.c): a line now and then, with the time left (-adh_progress) */
  PetscReal      progress;         /* seconds before the first line (0: none) */
  PetscLogDouble path_start, progress_last; /* when the path began, and the last line */
  PetscInt       path_states, path_first;    /* the states a path records at most, the first row this run records */
  PetscBool      on_path;          /* inside AdhSolverSolvePath: the totals above hold */

  /* monitors, called after every recorded state */
  PetscInt nmonitors;
  PetscErrorCode (*monitors[ADH_MAX_MONITORS])(AdhSolver, PetscInt, const AdhState *, void *);
  void          *monitor_ctx[ADH_MAX_MONITORS];
  PetscErrorCode (*monitor_destroy[ADH_MAX_MONITORS])(void **);

  /* path and output */
  PetscReal *path;
  PetscInt   npath, steps;
  PetscBool  stop_at_pulloff; /* -adh_stop_at_pulloff: a pull-off ends the path, not only its leg */
  PetscInt   path_stopped;    /* the curve row at which it did, with legs left (-1: it did not) */
  AdhStart   start;
  PetscBool  monitor;
  PetscInt   fields;            /* -adh_fields: which fields to write, a mask of ADH_FIELD_* */
  PetscInt   fields_stride;     /* -adh_fields_stride: fields of every K-th state */
  PetscInt  *field_states, nfield_states; /* the curve rows whose fields the file holds */
  char       output[PETSC_MAX_PATH_LEN];
  char       checkpoint[PETSC_MAX_PATH_LEN]; /* -adh_checkpoint: where the state goes (src/results/checkpoint.c) */
  PetscInt   checkpoint_every;              /* -adh_checkpoint_every: after every K-th state */
  char       restart[PETSC_MAX_PATH_LEN];    /* -adh_restart: the checkpoint to go on from */
  char       restart_output[PETSC_MAX_PATH_LEN]; /* the results file of the run that wrote it */
  PetscInt   checkpoint_state;              /* the curve row the checkpoint file holds (-1: none) */
  AdhCurve   curve;

  /* the results file as it is written: rows of the curve already in it (and in the journal,
     FILE.csv.part, appended by rank 0), and the pull-off state its attributes describe */
  PetscInt   rows_written, pull_off_written, apart_written, full_written; /* the states the pull-off attributes describe */
  PetscBool  output_failed; /* a write into the results file failed: it is closed as it is, not written further */
  PetscViewer writer;                             /* the results file of AdhSolverOutputBegin() (writer.c; NULL: none) */
  char        writer_file[PETSC_MAX_PATH_LEN];    /* its name */
  /* the writes under way (AdhOutputWriteBegin_Private), for the error if they fail */
  char      writing[PETSC_MAX_PATH_LEN + 64];     /* "-adh_output: cannot write F.part" */
  char      writing_part[PETSC_MAX_PATH_LEN + 8]; /* F.part */
  char      writing_kept[3 * PETSC_MAX_PATH_LEN]; /* what is left if they fail */
  PetscBool writing_discard;                      /* F.part holds nothing to keep: removed by a rank that ends the job alone */
  FILE      *journal;
  char      journal_name[PETSC_MAX_PATH_LEN + 16]; /* its FILE.csv.part, for the error that it cannot be written */

  /* stopping a path on a signal (interface/path.c): the checks are on while the path runs with its
     handlers installed; stop_signal is the signal every rank agreed on */
  PetscBool  stoppable;
  int        stop_signal;
};

PETSC_INTERN PetscErrorCode AdhSolverRebuildSet_Private(AdhSolver);
/* The path holds forces (the load control's target). */
static inline PetscBool AdhSolverControlsForce_Private(AdhSolver s)
{
  return (PetscBool)(s->cops.target == ADH_TARGET_FORCE);
}
/* Tension is allowed somewhere: not the adhesion-free start, and a work of adhesion (or a fixed
   critical stress). Without it the state at a given d or F is unique, whatever the path. */
static inline PetscBool AdhSolverIsAdhesive_Private(AdhSolver s)
{
  return (PetscBool)(s->adhesive && (s->Sigma > 0 || s->Sigma_field));
}
/* A point off the contact set is in the cohesive zone: it carries a traction p, and under a law its
   gap g is within the law's zone gap (a law's tail may reach further). */
static inline PetscBool AdhSolverInCohesiveZone_Private(AdhSolver s, PetscReal p, PetscReal g, PetscReal dgamma)
{
  return (PetscBool)(p != 0 && (!s->crops.zone_gap || g <= s->crops.zone_gap(s->crops.data, dgamma)));
}
PETSC_INTERN PetscErrorCode AdhSolverApplyOnSet_Private(AdhSolver, Mat, Vec, Vec);
PETSC_INTERN PetscErrorCode AdhSolverSelectOperator_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverOperatorIndices_Private(AdhSolver, PetscInt, const PetscInt *, PetscInt *);
PETSC_INTERN PetscErrorCode AdhSolverDestroyBoxes_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverMultCount_Private(AdhSolver, PetscInt *, PetscInt *);
PETSC_INTERN PetscErrorCode AdhCurveAppend_Private(AdhCurve *, const AdhState *);
PETSC_INTERN PetscErrorCode AdhSolverGetCriticalStress_Private(AdhSolver, PetscBool threshold, const PetscScalar **, PetscReal *);
PETSC_INTERN PetscErrorCode AdhSolverRestoreCriticalStress_Private(AdhSolver, const PetscScalar **);
PETSC_INTERN PetscErrorCode AdhSolverGetCriticalStressVec_Private(AdhSolver, Vec *);
/* The critical stress of local point k from what AdhSolverGetCriticalStress_Private gave. */
#define ADH_SIGMA_AT(a, uniform, k) ((a) ? PetscRealPart((a)[k]) : (uniform))
/* the KSP convergence test of the set's solves: full tolerance, or the certified early stop (step.c) */
PETSC_INTERN PetscErrorCode AdhConvergedCertified_Private(KSP, PetscInt, PetscReal, KSPConvergedReason *, void *);
PETSC_INTERN PetscErrorCode AdhSolverSetIterate_Private(AdhSolver, Vec xC);
/* What a solve on the contact set solves for: the pressure p of the profile h at an indentation,
   or the set's response to a unit indentation without a profile (s->set_response, force control). */
typedef enum { ADH_SET_SOLVE_PRESSURE, ADH_SET_SOLVE_UNIT_RESPONSE } AdhSetSolve;
PETSC_INTERN PetscErrorCode AdhSolverSolveOnSet_Private(AdhSolver, AdhSetSolve what, PetscReal d, PetscBool certify);
PETSC_INTERN PetscErrorCode AdhSolverDetach_Private(AdhSolver, PetscInt *);
/* A new step, or a trial of one: no point has let go in it yet, and its largest set is the
   current one (AttachLimit). */
static inline PetscErrorCode AdhSolverBeginSetUpdates_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(PetscArrayzero(s->left, s->nlocal));
  s->step_largest = s->npoints;
  if (s->crops.begin) PetscCall(s->crops.begin(s));
  PetscFunctionReturn(0);
}
/* A criterion lets local point k go: it leaves the set, and its pressure (and its force-control
   response xa, when given) become zero. In an update of -adh_cascade_apart the point is marked
   instead, and its pressure stays until the update's attach test has seen the solved state
   (AdhSolverEndCascadeApart_Private). */
static inline void AdhSolverRemovePoint_Private(AdhSolver s, PetscInt k, PetscScalar *pa, PetscScalar *xa)
{
  s->in_set[k] = 0;
  s->left[k]   = 1;
  if (s->apart_pending || s->local_pending) s->gone[k] = 1;
  if (!s->apart_pending) pa[k] = 0.0;
  if (xa) xa[k] = 0.0;
}
PETSC_INTERN PetscErrorCode AdhSolverDetachRatio_Private(AdhSolver, PetscReal *);
PETSC_INTERN PetscErrorCode AdhSolverSetUpCascadeApart_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverBeginCascadeApart_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverMarkNearGone_Private(AdhSolver, PetscInt w);
PETSC_INTERN PetscErrorCode AdhSolverEndCascadeApart_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverDestroyCascadeApart_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverSetUpCascadeLocal_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverDefaultCascadeLocal_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverSetLocalWidth_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverCascadeLocal_Private(AdhSolver, PetscInt widened);
PETSC_INTERN PetscErrorCode AdhSolverDestroyCascadeLocal_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverKSPSolve_Private(AdhSolver, KSP, PetscBool loose, Vec, Vec);
PETSC_INTERN PetscErrorCode AdhSolverApplyRestricted_Private(AdhSolver, Mat, PetscInt n, const PetscInt local[], VecScatter, Vec, Vec);
PETSC_INTERN PetscErrorCode AdhSolverCheckResources_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverStopRequested_Private(AdhSolver, PetscBool *);
/* A stop by signal inside a path is a state of the solver, not an error code: once every rank has
   agreed on a signal (AdhSolverStopRequested_Private sets stop_signal), the step in progress is
   abandoned: each part of it returns as it sees the mark, without finishing, and
   AdhSolverSolvePath closes the results and reports the stop. AdhSolverCheckStop_Private asks
   (collective) and returns if stopped; AdhSolverReturnIfStopped_Private only looks, after a call
   that may have stopped. */
#define AdhSolverStopped_Private(s) ((PetscBool)((s)->stoppable && (s)->stop_signal))
#define AdhSolverReturnIfStopped_Private(s) \
  do { \
    if (AdhSolverStopped_Private(s)) PetscFunctionReturn(0); \
  } while (0)
#define AdhSolverCheckStop_Private(s) \
  do { \
    PetscBool stop_; \
    PetscCall(AdhSolverStopRequested_Private((s), &stop_)); \
    if (stop_) PetscFunctionReturn(0); \
  } while (0)
PETSC_INTERN void           AdhStateSetValue(AdhState *, PetscInt column, PetscReal value);
/* the solver's package (interface/solverpackage.c), and the registration of the built-in types (impls/register.c) */
PETSC_INTERN PetscErrorCode AdhSolverInitializePackage(void);
PETSC_INTERN PetscErrorCode AdhSolverAttach_Private(AdhSolver, Vec rate, PetscReal e, PetscInt removed, PetscInt *);
/* The set-update loop of a step at the target, from the current set: solve (the control's
   equilibrate), let go, let join, until the set stands or no equilibrium is left (setupdate.c). */
PETSC_INTERN PetscErrorCode AdhSolverUpdateSet_Private(AdhSolver, PetscReal target);
/* A step's state under a cohesive law: the minimum of the total energy at the target reached from
   the current state, or *none: no minimum is left under a force (the bodies fly apart). */
PETSC_INTERN PetscErrorCode AdhSolverMinimize_Private(AdhSolver, PetscReal target, PetscBool *none);
/* The options of every registered type, read on a scratch solver: -help shows those of the types
   the solver does not have, and set-up does not take any for misspellings (types.c). */
PETSC_INTERN PetscErrorCode AdhSolverReadTypesOptions_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverAttachDecided_Private(AdhSolver, Vec xC, PetscReal rnorm, PetscBool *certain, PetscReal *needed);
PETSC_INTERN PetscErrorCode AdhSolverComputeGap_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverGapFromDisplacement_Private(AdhSolver, Vec);
PETSC_INTERN PetscErrorCode AdhSolverGetDisplacement_Private(AdhSolver, Vec *);
PETSC_INTERN PetscErrorCode AdhSolverProfileChanged_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverClearContact_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverMonitorProgress_Private(AdhSolver, PetscInt outer);
PETSC_INTERN PetscErrorCode AdhSolverProgress_Private(AdhSolver); /* -adh_progress's line after a recorded state (monitor.c) */
PETSC_INTERN PetscErrorCode AdhSolverSetFromOverlap_Private(AdhSolver, PetscReal d, PetscBool strict);
PETSC_INTERN PetscErrorCode AdhSolverCheckBelowFullContact_Private(AdhSolver, PetscReal d);
PETSC_INTERN PetscErrorCode AdhStatisticsCompute_Private(AdhSolver, AdhState *);
PETSC_INTERN PetscErrorCode AdhSolverEstimateResolution_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverEstimateStickiness_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverEstimateRoughness_Private(AdhSolver);
PETSC_INTERN PetscBool      AdhSolverResolves_Private(AdhSolver, const AdhState *);
PETSC_INTERN PetscInt       AdhSolverUnresolved_Private(AdhSolver, const AdhState *);
PETSC_INTERN PetscErrorCode AdhSolverUnresolvedWords_Private(AdhSolver, const AdhState *, PetscInt, char[], size_t);
PETSC_INTERN PetscReal      AdhSolverCohesiveWidth_Private(AdhSolver, const AdhState *);
PETSC_INTERN PetscErrorCode AdhCurveDestroy_Private(AdhCurve *);
#endif
