/* The AdhSolver's insides, shared by solver.c (lifecycle), contact.c (one step), path.c
   (indentation paths) and output.c (HDF5/CSV). */
#ifndef ADHBEM_SOLVERIMPL_H
#define ADHBEM_SOLVERIMPL_H
#include <petscviewerhdf5.h>
#include "adhbem.h"
#include "indenter.h"

/* A window of the plane for the bounding-box convolution (box.c). */
typedef struct {
  PetscInt bx, by;
  AdhGrid  grid;
  Mat      K, S;   /* free compliance and periodic stiffness on the window */
} AdhBox;

struct _n_AdhSolver {
  MPI_Comm    comm;
  char       *prefix;
  PetscBool   setup;

  /* problem */
  AdhGrid     grid;
  AdhBoundary boundary;
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
  Vec       h, Sigma_field, p, u, g, zero;
  PetscReal lambda_min;       /* lower bound on eigenvalues of every K_CC */

  /* contact set: in_set[k] for the local points, and the same as a PETSc IS */
  char     *in_set;
  char     *left;             /* points that let go during the current step */
  PetscInt  nlocal;
  AdhAttach attach;
  IS        contact;
  PetscInt  npoints;          /* global size of the set */
  KSP       ksp;
  Mat       Kcc;              /* K restricted to the set, applied on the window or the grid */
  IS        contact_op;       /* the set in the numbering of the operator behind Kcc */
  Mat       Kop, Sop;         /* compliance and stiffness of the window or grid in use (borrowed) */
  Vec       op_in, op_out;    /* work vectors on that window or grid */
  VecScatter set_scatter;     /* set values -> that window or grid */
  PetscInt *set_local, nset_local; /* local offsets of this rank's points in the set */
  Vec       pC, bC;           /* pressure and right-hand side on the set */
  PetscScalar *thrC;          /* allowed tension on the set */

  /* bounding-box convolution */
  PetscBool use_box;
  AdhBox   *boxes, *box;      /* cache, and the window in use (NULL: the whole grid) */
  PetscInt  nboxes, maxboxes, box_i0, box_j0;

  /* the current solve, read by the convergence test and the preconditioner */
  const PetscScalar *threshold_local; /* -threshold is the allowed tension, on the set */
  PetscReal bnorm;
  PetscBool certify, certified_stop;

  /* state and counters */
  PetscReal d;
  PetscBool adhesive;         /* false while computing a Hertz (dgamma = 0) start */
  PetscInt  max_outer;
  PetscInt  step_outer, step_ksp, step_mults;

  /* path and output */
  PetscReal *path;
  PetscInt   npath, steps;
  AdhStart   start;
  PetscBool  monitor, fields;
  char       output[PETSC_MAX_PATH_LEN];
  AdhCurve   curve;
};

PETSC_INTERN PetscErrorCode AdhSolverRebuildSet_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverApplyOnSet_Private(AdhSolver, Mat, Vec, Vec);
PETSC_INTERN PetscErrorCode AdhSolverSelectOperator_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverOperatorIndices_Private(AdhSolver, PetscInt, const PetscInt *, PetscInt *);
PETSC_INTERN PetscErrorCode AdhSolverDestroyBoxes_Private(AdhSolver);
PETSC_INTERN PetscErrorCode AdhSolverMultCount_Private(AdhSolver, PetscInt *);
PETSC_INTERN PetscErrorCode AdhCurveAppend_Private(AdhCurve *, PetscReal d, PetscReal F, PetscReal A, PetscInt pts, PetscInt outer, PetscInt ksp, PetscInt mults, PetscReal sec);
PETSC_INTERN PetscErrorCode AdhCurveDestroy_Private(AdhCurve *);
PETSC_INTERN PetscErrorCode AdhOutputOpen_Private(AdhSolver, const char file[], PetscViewer *);
PETSC_INTERN PetscErrorCode AdhOutputWriteFields_Private(AdhSolver, PetscViewer, PetscInt step);
PETSC_INTERN PetscErrorCode AdhOutputClose_Private(AdhSolver, const char file[], PetscViewer *);
PETSC_INTERN PetscErrorCode AdhOutputCheckWritable_Private(AdhSolver, const char file[]);
#endif
