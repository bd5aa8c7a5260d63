/* The AdhSolver's insides: the private header of the solver layer. Its interface (interface/: life
   cycle, one step, the path) and its registered types (impls/<kind>/) include it, and so does the
   results layer above it (src/results/). */
#ifndef ADHBEM_SOLVERIMPL_H
#define ADHBEM_SOLVERIMPL_H
#include <petsc/private/petscimpl.h>
#include <petscviewerhdf5.h>
#include "adhbem.h"
#include "geometry/indenter.h"
#include "sys/sysimpl.h"

/* A window of the plane for the bounding-box convolution (interface/box.c). */
typedef struct {
  PetscInt bx, by;
  AdhGrid  grid;
  Mat      K, S;   /* free compliance and periodic stiffness on the window */
} AdhBox;

/* What a load control does (impls/control/): set-up of its own objects, one step to a target (an
   indentation or a force), and clean-up. */
typedef struct {
  PetscErrorCode (*setup)(AdhSolver);
  PetscErrorCode (*step)(AdhSolver, PetscReal);
  PetscErrorCode (*destroy)(AdhSolver);
} AdhControlOps;

/* What the detach test of the exact solution of a solve is, as far as an iterate tells. */
typedef enum { ADH_DETACH_IN_DOUBT, ADH_DETACH_NONE, ADH_DETACH_SOME } AdhDetachDecision;

/* What a detachment criterion does (impls/criterion/): evaluate the current state, removing the points
   that let go (detach) or giving the largest demand over its limit on the set (ratio). */
typedef struct {
  PetscErrorCode (*setup)(AdhSolver); /* at the solver's set-up: what the criterion needs on the grid */
  PetscErrorCode (*evaluate)(AdhSolver, PetscBool detach, PetscInt *removed, PetscReal *ratio);
  PetscErrorCode (*destroy)(AdhSolver);
  /* Optional, for the certified early stop of intermediate solves: the detach test of the exact
     solution p*, decided from the iterate xC (on the set) when every point's decision holds for
     any p within perr of it (perr bounds |p - p*| at every point). With the test in doubt,
     *needed is the bound at which the decisions in doubt now would be made (the next check is
     worth its cost below it); PETSC_MAX_REAL: check again at the next iteration; 0 with NONE:
     decided for the rest of the solve. */
  PetscErrorCode (*decide)(AdhSolver, Vec xC, PetscReal perr, AdhDetachDecision *, PetscReal *needed);
} AdhCriterionOps;

/* A copy of the contact state (force control: the state before a step, for pull-off). */
typedef struct {
  char     *in_set;
  Vec       p, xunit;
  PetscReal d;
} AdhSavedState;

/* What a path does with its results: the results file (the curve, the fields) and the checkpoint.
   Written by the results layer (src/results/), bound in solverregis.c, so that the solver calls it
   without depending on it. */
typedef struct {
  PetscErrorCode (*check_writable)(AdhSolver, const char option[], const char file[]);
  PetscErrorCode (*open)(AdhSolver, const char file[], PetscViewer *);   /* a new results file */
  PetscErrorCode (*resume)(AdhSolver, const char file[], PetscViewer *); /* a restart's: the earlier run's file taken over */
  PetscErrorCode (*write_fields)(AdhSolver, PetscViewer, PetscInt state);
  PetscErrorCode (*append)(AdhSolver, PetscViewer); /* the states recorded since the last call */
  PetscErrorCode (*close)(AdhSolver, const char file[], PetscViewer *);
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
  PetscReal mean_h;           /* mean of h: a periodic cell is in full contact at d = mean_h */
  PetscInt  profile_version;  /* counts the profiles h has held (AdhSolverProfileChanged_Private) */

  /* load control */
  char          control_type[64];
  AdhControlOps cops;
  PetscBool     force_control;  /* the path holds forces */
  Vec           xunit;          /* force control: response of the set to a unit indentation, K_CC x = 1 */
  Vec           gap_rate;       /* force control: how fast each gap closes as the set's indentation rises */
  Mat           Kmean;          /* force control, periodic: K + c0 (1 1^T)/N, positive definite on every set */
  PetscReal     c0;             /* its mean-mode compliance */
  PetscReal     e;              /* force control: the indentation of K_op's equations, d + c0 mean(p) */
  PetscReal     pulloff_rtol;   /* force control: resolution of the pull-off force */
  AdhSavedState previous;       /* force control: the state before the current step */
  PetscBool     pulled_off;     /* the last step ended in pull-off */

  /* contact-set predictor (impls/predictor/) */
  char      predictor_type[64];
  PetscErrorCode (*predict)(AdhSolver, PetscBool force, PetscReal target); /* NULL: none */
  PetscReal predictor_rtol;
  PetscInt  predictor_max_it, predictor_its;
  PetscBool predictor_fourier; /* precondition with the stiffness E*|q|/2 */
  PetscBool predictor_chosen;  /* set by the user (else chosen by the boundary at set-up) */
  /* detachment criterion */
  char            criterion_type[64];
  AdhCriterionOps crops;
  void           *crdata;
  PetscReal       criterion_radius; /* crack-closure: averaging radius, in grid spacings, */
  PetscReal       criterion_radius_max; /* and up to this where the front's radius of curvature is larger */
  PetscBool       criterion_certify; /* crack-closure: its certified early stop (-adh_criterion_certify) */
  PetscBool       memory_check;     /* refuse a grid that clearly does not fit into a node (estimate.c) */
  PetscReal       asperity_ac;      /* estimated JKR contact radius of the smallest asperities over h (resolution.c; 0: none) */

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
  PetscInt   rows_written, pull_off_written;
  FILE      *journal;

  /* stopping a path on a signal (interface/path.c): the checks are on while the path runs with its
     handlers installed; stop_signal is the signal every rank agreed on */
  PetscBool  stoppable;
  int        stop_signal;
};

PETSC_INTERN PetscErrorCode AdhSolverRebuildSet_Private(AdhSolver);
/* Tension is allowed somewhere: not the adhesion-free start, and a work of adhesion (or a fixed
   critical stress). Without it the state at a given d or F is unique, whatever the path. */
static inline PetscBool AdhSolverIsAdhesive_Private(AdhSolver s)
{
  return (PetscBool)(s->adhesive && (s->Sigma > 0 || s->Sigma_field));
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
PETSC_INTERN PetscErrorCode AdhSolverSolveOnSet_Private(AdhSolver, Vec x, PetscReal shift, Vec prof, PetscBool certify);
PETSC_INTERN PetscErrorCode AdhSolverDetach_Private(AdhSolver, PetscInt *);
/* A new step, or a trial of one: no point has let go in it yet, and its largest set is the
   current one (AttachLimit). */
static inline PetscErrorCode AdhSolverBeginSetUpdates_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(PetscArrayzero(s->left, s->nlocal));
  s->step_largest = s->npoints;
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
/* Inside a path: returns PETSC_ERR_SIG, without a message, once a signal asks every rank to stop;
   the step in progress is abandoned and AdhSolverSolvePath closes the results. */
#define AdhSolverCheckStop_Private(s) \
  do { \
    PetscBool stop_; \
    PetscCall(AdhSolverStopRequested_Private((s), &stop_)); \
    if (stop_) PetscFunctionReturn(PETSC_ERR_SIG); \
  } while (0)
PETSC_INTERN void           AdhStateSetValue(AdhState *, PetscInt column, PetscReal value);
/* the registries of the solver's types (interface/solverregis.c lists the built-in ones) */
PETSC_INTERN PetscErrorCode AdhSolverInitializePackage(void);
PETSC_INTERN PetscErrorCode AdhCriterionDestroyList_Private(void);
PETSC_INTERN PetscErrorCode AdhCriterionGetList_Private(PetscFunctionList *);
/* the rows crack-closure looks at each side of a point: its averaging radius, and at least the radius of its estimate of the
   edge's normal */
#define ADH_NORMAL_RADIUS 3
static inline PetscInt AdhCrackClosureWidth(PetscReal radius)
{
  return PetscMax(ADH_NORMAL_RADIUS, (PetscInt)PetscCeilReal(radius));
}
PETSC_INTERN PetscErrorCode AdhSolverAttach_Private(AdhSolver, Vec rate, PetscInt removed, PetscInt *);
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
PETSC_INTERN PetscErrorCode AdhPredictorDestroyList_Private(void);
PETSC_INTERN PetscErrorCode AdhPredictorGetList_Private(PetscFunctionList *);
PETSC_INTERN PetscErrorCode AdhControlDestroyList_Private(void);
PETSC_INTERN PetscErrorCode AdhControlGetList_Private(PetscFunctionList *);
PETSC_INTERN PetscErrorCode AdhStatisticsCompute_Private(AdhSolver, AdhState *);
PETSC_INTERN PetscErrorCode AdhSolverEstimateResolution_Private(AdhSolver);
PETSC_INTERN PetscBool      AdhSolverResolves_Private(AdhSolver, const AdhState *);
PETSC_INTERN PetscErrorCode AdhCurveDestroy_Private(AdhCurve *);
#endif
