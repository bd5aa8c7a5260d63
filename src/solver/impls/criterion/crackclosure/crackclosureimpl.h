/* crack-closure's data and the functions its files share (impls/criterion/crackclosure/). */
#ifndef ADHBEM_CRACKCLOSUREIMPL_H
#define ADHBEM_CRACKCLOSUREIMPL_H
#include "solver/solverimpl.h"

/* the rows crack-closure looks at each side of a point: its averaging radius, and at least the radius of its estimate of the
   edge's normal */
#define ADH_NORMAL_RADIUS 3
static inline PetscInt AdhCrackClosureWidth(PetscReal radius)
{
  return PetscMax(ADH_NORMAL_RADIUS, (PetscInt)PetscCeilReal(radius));
}

/* The rows a rank looks at of one grid vector: the vector (its own rows) and the buffer of the
   rows other ranks own (FetchRows), and, while in use, the row pointers (GetRows). */
typedef struct {
  Vec                v;
  const PetscScalar *own;
  PetscScalar       *far, **store;
} FetchedRows;

/* What the evaluations of one contact set share, kept with the certified stop (which evaluates a
   set at several iterates): per front point, the open neighbours whose opening it may take (those
   closest to the edge's normal; the smallest opening among them counts) and its walks along the
   front, as members (fetched row - gys) Nx + column with their weights, in the walk's order, so
   that a cached mean is the walk's to the last bit. */
typedef struct {
  PetscInt  ncand, cand[4]; /* the open neighbours closest to the normal */
  PetscInt  w16, n16;       /* the walk within the radius: members from w16, n16 of them (-1: not walked) */
  PetscInt  wR, nR;         /* the walk within the radius of curvature (-1: not walked) */
  PetscReal kappa;          /* the front's curvature there, from the walk within the radius */
} FrontEntry;

typedef struct {
  PetscReal radius;     /* -adh_criterion_radius: the release rate is averaged along the front within radius grid spacings, */
  PetscReal radius_max; /* -adh_criterion_radius_max: or near dgamma within the front's radius of curvature, up to radius_max */
  PetscBool certify;    /* -adh_criterion_certify: its certified early stop of intermediate solves */
  PetscInt  width;      /* rows looked at each side: AdhCrackClosureWidth(radius_max) */
  /* The rows this rank looks at: its own and width rows each side, gym rows from gys (wrapped on
     a periodic cell, so a cell with fewer rows than that holds some rows several times; clipped
     to a free grid): a rank may own fewer rows than the width, and a narrow cell's averaging
     window folds onto itself. */
  PetscInt    gys, gym;
  /* Of those rows, the ones another rank owns are fetched into a buffer of their own; the rank's
     own rows (every row on one rank) are read where they are: the buffers hold at most 2 width
     rows, not copies of the grid vectors. rowmap[r] of row
     gys + r: its local row in the grid vector (>= 0), or -1 - its row in the buffer. */
  PetscInt   *rowmap, nghost, nx;
  PetscSF     fetch;        /* the other ranks' rows among them (AdhGridCreateRowSF) */
  MPI_Datatype row_scalars, row_flags; /* its units: a row of a grid vector, of s->in_set (the grid's) */
  /* An opening is the gap g of an open point, which the detach test computes for every point
     (g = h - d + u, u = K p), so its rows are read from g. Where the indenter has no face (h =
     PETSC_INFINITY, outside a punch) the opening is measured from the face extended flat, which
     needs u there: only for such a profile, faceless holds g on the faces and u off them. */
  Vec         faceless, G;  /* G per front point (NaN elsewhere) */
  FetchedRows O, H, Gf, P;  /* the rows of the openings (g, or faceless), h, G and p (griffith) */
  char       *set_before, *far_set, **set_store; /* the set as the openings were computed (FetchSetRows): own points, other ranks' rows, row pointers */
  PetscInt   *seen;         /* the walk along the front within the disk: offsets (2 width + 1)^2 met, */
  PetscInt   *qi, *qj;      /* and the offsets reached, in the order met */
  PetscInt   *col, *row;    /* the walk's columns and rows in the fetched rows, 2 width + 1 each */
  PetscInt   *links;        /* per fetched point of the front, its front neighbours within two
                               rows and columns as bits (FrontLinks) */
  PetscInt    stamp;        /* seen[o] == stamp: offset o met in the current walk */
  PetscInt    h_version;    /* the profile H's rows were fetched from (s->profile_version; 0: none yet) */
  PetscBool   decided;      /* s->g and the openings' and set's rows belong to the iterate of the last decision */
  /* the front's cache (with the certified stop): slot[k] of local point k is its FrontEntry, -1
     not made yet, -2 in the set but not on the front; valid for the set cache_set */
  PetscBool   cache;
  PetscInt    cache_set, links_set; /* the set the cache belongs to; the set whose front links holds (-1: none, or griffith's outer front) */
  PetscInt   *slot;
  FrontEntry *entry;
  PetscInt    nentry, capentry, nmember, capmember;
  PetscInt   *member;
  PetscReal  *weight;
  PetscReal  *front_limit;  /* griffith: the limits of the outer front's points, in the order of the grid */
  PetscInt    capfront;
} CrackClosure;

/* The opening of open point n for a front point of profile hi at indentation d. on is n's gap
   g_n = (h_n - d) + u_n, or u_n where n has no face (h_n infinite): there the opening is
   measured from the front point's face extended flat. */
static inline PetscReal Opening(PetscReal hn, PetscReal hi, PetscReal d, PetscReal on)
{
  return hn >= PETSC_INFINITY ? (hi - d) + on : on;
}

/* NaN marks points without a value (G off the front); PETSc 3.18's
   PetscIsNanReal is a function call, and the walks below test millions of points. */
static inline PetscBool IsNaN(PetscReal x)
{
  return (PetscBool)(x != x);
}

/* Grid neighbour (i + di, j + dj) in the fetched rows: wraps on a periodic cell, false off a
   free grid. */
static inline PetscBool Neighbour(const AdhGrid g, PetscBool wrap, PetscInt gys, PetscInt gym, PetscInt i, PetscInt j, PetscInt di, PetscInt dj, PetscInt *a, PetscInt *b)
{
  *a = i + di;
  *b = j + dj;
  if (wrap) {
    if (*a < 0 || *a >= g->Nx) *a = (*a % g->Nx + g->Nx) % g->Nx; /* offsets reach beyond a narrow cell's width */
  } else if (*a < 0 || *a >= g->Nx || *b < 0 || *b >= g->Ny) return PETSC_FALSE;
  return (PetscBool)(*b >= gys && *b < gys + gym);
}

/* A point's window grows only where its mean over the radius lies within this band of dgamma:
   near its decision (a mean far from dgamma decides the same with any window). */
#define ADH_WINDOW_BAND_LOW  0.8
#define ADH_WINDOW_BAND_HIGH 1.25

PETSC_INTERN PetscErrorCode AdhCrackClosureFetchRows_Private(CrackClosure *cc, Vec v, FetchedRows *f);
PETSC_INTERN PetscErrorCode AdhCrackClosureFetchSetRows_Private(AdhSolver s, CrackClosure *cc);
PETSC_INTERN PetscErrorCode AdhCrackClosureGetSetRows_Private(CrackClosure *cc, const char ***rows);
PETSC_INTERN PetscErrorCode AdhCrackClosureEnsureFaceless_Private(AdhSolver s, CrackClosure *cc);
PETSC_INTERN PetscErrorCode AdhCrackClosureGetRows_Private(CrackClosure *cc, FetchedRows *f, const PetscScalar ***rows);
PETSC_INTERN PetscErrorCode AdhCrackClosureRestoreRows_Private(FetchedRows *f, const PetscScalar ***rows);
PETSC_INTERN PetscErrorCode AdhCrackClosureEdgeNormal_Private(const AdhGrid g, PetscBool wrap, PetscInt gys, PetscInt gym, const char **sl, PetscInt i, PetscInt j, PetscReal n[2]);
PETSC_INTERN PetscErrorCode AdhCrackClosureFrontLinks_Private(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl);
PETSC_INTERN PetscErrorCode AdhCrackClosureEnsureInnerLinks_Private(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl);
PETSC_INTERN PetscErrorCode AdhCrackClosureWindowMean_Private(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl, PetscInt i, PetscInt j, FrontEntry *e, PetscReal lo, PetscReal hi, PetscReal *sum, PetscReal *weights, PetscReal *margin);
PETSC_INTERN PetscErrorCode AdhCrackClosureGriffithLimits_Private(AdhSolver s, CrackClosure *cc);
/* the detach test of the current p (rules.c), and the certified decision of an iterate's exact solution */
PETSC_INTERN PetscErrorCode AdhCrackClosureDetach_Private(AdhSolver s, PetscBool detach, PetscInt *removed, PetscReal *ratio);
PETSC_INTERN PetscErrorCode AdhCrackClosureDecide_Private(AdhSolver s, PetscReal perr, AdhDetachDecision *decision, PetscReal *needed);
#endif
