/*MC
   ADHCRITERIONCRACKCLOSURE - "crack-closure", the default: a point on the contact edge lets go when the edge's energy
   release rate, estimated by virtual crack closure and averaged along the edge, exceeds its dgamma

   Virtual crack closure is Rybicki and Kanninen's (1977); it was applied to this BEM before in Front. Mech. Eng. 7,
   754782 (2021), on the parabolic and sinusoidal contacts. The rate does not depend on the edge's direction on the
   grid.

   Options Database Keys:
+  -adh_criterion crack-closure   - selects this criterion (the default)
.  -adh_criterion_radius <16>     - the radius of the window the release rate is averaged in, in grid spacings, in [1, 64]
.  -adh_criterion_radius_max <64> - near dgamma, the window's radius is the front's radius of curvature up to this,
                                    at most 128 (equal to -adh_criterion_radius: a fixed window)
.  -adh_criterion_certify         - the certified early stop of intermediate solves too (off by default)
-  -adh_attach <griffith>         - griffith, this criterion's mirror for joining points, is the default with it

   Level: beginner

   Notes:
   The front is the set's points with an open 4-neighbour. When a front point lets go the edge moves by one element:
   on a straight edge in any direction the set less its front is the set shifted by one element along the grid axis
   closest to the edge's normal, so a front point gets the opening its neighbour along that axis has now. A front
   point i under tension -p_i frees G_i = -p_i delta_i / 2 per unit area when it lets go, delta_i the opening (gap) of
   its open neighbour closest to the edge's normal (the normal estimated from the open points within
   ADH_NORMAL_RADIUS, 3 grid spacings). Where the indenter has no face (outside a punch, h = PETSC_INFINITY) the
   opening is measured from the face extended flat.

   Single points of a staircase are not representative: along each run of the staircase G_i rises from about 0.6 to
   1.5 times the edge's rate, while the mean over a period of the staircase is within 1% of it. So G is averaged
   along the front, over the front points that can be reached along it within a window, with a weight that fades to
   zero at the window's radius, and a front point lets go when that mean exceeds its dgamma. The window's radius is
   -adh_criterion_radius, and where the mean over that comes near dgamma, the front's radius of curvature there, up
   to -adh_criterion_radius_max. On a curved edge the staircase's runs grow like the square root of the radius of
   curvature in grid spacings, so a window of fixed size stops spanning them as the grid is refined, and the first
   window whose mean runs high lets go (with a fixed radius of 16 the JKR sphere came off 0.6%, 1.3%, 1.5% low at
   a_c/h 25, 50, 100); a window as large as the radius of curvature spans them at any resolution and is still local
   on the scale on which the edge's release rate varies.

   A point lets go also under the pohrt-popov rule, p < -Sigma: the exact energy balance of a point alone, which lets
   a crack start inside the set. With dgamma = 0 the criterion reduces to non-adhesive contact: p < 0 lets go. The
   state's detach ratio is the larger of (G/dgamma)^(1/2) and -p/Sigma.

   A test costs one compliance multiply (the attach test after a test that let nothing go reuses its gap). With
   -adh_criterion_certify the certified early stop of intermediate solves applies, with the openings' error bounded
   through K's row norms (Decide_CrackClosure): the same sets with 12-16% fewer FFT pairs and about the default's
   time, for a cache of each set's walks along the front (about 1 kB a front point). With this criterion
   -adh_cascade_local is inf, the whole grid, by default under displacement control.

   Measured (./run bench criterion, docs/validation.md): the work of adhesion it acts with is within 1.4% of dgamma on
   straight edges in the six directions measured (0 to 45 degrees), within 0.2% on the JKR sphere at a_c/h 25 to 100,
   converging on the cone and the punch; pohrt-popov's: 1.02 to 1.88 on the straight edges, 0-6% high on the curved
   ones.

.seealso: `AdhSolverSetCriterionType()`, `ADHCRITERIONPOHRTPOPOV`, `AdhSolverEstimateMemory()`
M*/
#include "solver/solverimpl.h"

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
  PetscReal radius;     /* the release rate is averaged along the front within radius grid spacings, */
  PetscReal radius_max; /* or near dgamma within the front's radius of curvature, up to radius_max */
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

/* defined below: the certified stop, chosen at set-up (-adh_criterion_certify) */
static PetscErrorCode Decide_CrackClosure(AdhSolver, Vec, PetscReal, AdhDetachDecision *, PetscReal *);

/* The fetch of the rows each rank looks at, made at the solver's set-up. */
static PetscErrorCode SetUp_CrackClosure(AdhSolver s)
{
  CrackClosure   *cc = (CrackClosure *)s->crdata;
  const AdhGrid   g  = s->grid;
  const PetscBool periodic = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  PetscInt        ys, ym, side, *rows;

  PetscFunctionBegin;
  if (cc->fetch) PetscFunctionReturn(0);
  cc->radius     = s->criterion_radius;
  cc->radius_max = PetscMax(s->criterion_radius, s->criterion_radius_max);
  /* its certified stop: the same sets for fewer FFT pairs, about the default's time (docs/performance.md) */
  s->crops.decide = s->criterion_certify ? Decide_CrackClosure : NULL;
  /* the certified stop evaluates a set at several iterates: keep its front's walks (a PetscInt a
     point, and about 1 kB a front point: some 90 members of 12 B within the radius) */
  cc->cache     = (PetscBool)(s->criterion_certify && s->certify);
  cc->cache_set = -1;
  cc->links_set = -1;
  if (cc->cache) PetscCall(PetscMalloc1(s->nlocal + 1, &cc->slot));
  cc->width       = AdhCrackClosureWidth(cc->radius_max);
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  if (periodic) {
    cc->gys = ys - cc->width;
    cc->gym = ym + 2 * cc->width;
  } else {
    cc->gys = PetscMax(0, ys - cc->width);
    cc->gym = PetscMin(g->Ny, ys + ym + cc->width) - cc->gys;
  }
  PetscCall(PetscMalloc1(cc->gym, &rows));
  PetscCall(PetscMalloc1(cc->gym, &cc->rowmap));
  cc->nx     = g->Nx;
  cc->nghost = 0;
  for (PetscInt r = 0; r < cc->gym; r++) {
    const PetscInt b = ((cc->gys + r) % g->Ny + g->Ny) % g->Ny;
    if (b >= ys && b < ys + ym) cc->rowmap[r] = b - ys;
    else {
      rows[cc->nghost] = b;
      cc->rowmap[r]    = -1 - cc->nghost++;
    }
  }
  PetscCall(AdhGridCreateRowSF(g, cc->nghost, rows, &cc->fetch));
  PetscCall(PetscFree(rows));
  PetscCall(AdhGridGetRowType(g, MPIU_SCALAR, &cc->row_scalars));
  PetscCall(AdhGridGetRowType(g, MPI_CHAR, &cc->row_flags));
  PetscCall(AdhGridCreateVector(g, &cc->G));
  PetscCall(PetscMalloc5(cc->nghost * g->Nx + 1, &cc->O.far, cc->nghost * g->Nx + 1, &cc->H.far, cc->nghost * g->Nx + 1, &cc->Gf.far, cc->nghost * g->Nx + 1, &cc->far_set, s->nlocal + 1, &cc->set_before));
  PetscCall(PetscMalloc5(cc->gym, &cc->O.store, cc->gym, &cc->H.store, cc->gym, &cc->Gf.store, cc->gym, &cc->P.store, cc->gym, &cc->set_store));
  side = 2 * cc->width + 1;
  PetscCall(PetscCalloc3(side * side, &cc->seen, side * side, &cc->qi, side * side, &cc->qj));
  PetscCall(PetscMalloc2(side, &cc->col, side, &cc->row));
  PetscCall(PetscMalloc1(cc->gym * g->Nx, &cc->links));
  PetscFunctionReturn(0);
}

/* The rows this rank looks at of grid vector v: the other ranks' rows fetched into f's buffer;
   v itself must not change while they are in use. */
static PetscErrorCode FetchRows(CrackClosure *cc, Vec v, FetchedRows *f)
{
  const PetscScalar *va;

  PetscFunctionBegin;
  f->v = v;
  PetscCall(VecGetArrayRead(v, &va));
  PetscCall(PetscSFBcastBegin(cc->fetch, cc->row_scalars, va, f->far, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(cc->fetch, cc->row_scalars, va, f->far, MPI_REPLACE));
  PetscCall(VecRestoreArrayRead(v, &va));
  PetscFunctionReturn(0);
}

/* The contact set (s->in_set) as the openings were computed: a copy of the rank's own points and
   the other ranks' rows this rank looks at. It stays as it was when the detach test goes on to
   griffith's limits after letting points go (-adh_cascade_apart): those points keep their pressure
   for the limits, as in the state just solved. */
static PetscErrorCode FetchSetRows(AdhSolver s, CrackClosure *cc)
{
  PetscFunctionBegin;
  PetscCall(PetscArraycpy(cc->set_before, s->in_set, s->nlocal));
  PetscCall(PetscSFBcastBegin(cc->fetch, cc->row_flags, cc->set_before, cc->far_set, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(cc->fetch, cc->row_flags, cc->set_before, cc->far_set, MPI_REPLACE));
  PetscFunctionReturn(0);
}

/* Those rows: rows[b][i] nonzero when (i, b) was in the set, as GetRows gives a vector's. */
static PetscErrorCode GetSetRows(CrackClosure *cc, const char ***rows)
{
  PetscFunctionBegin;
  for (PetscInt r = 0; r < cc->gym; r++) cc->set_store[r] = cc->rowmap[r] >= 0 ? cc->set_before + cc->rowmap[r] * cc->nx : cc->far_set + (-1 - cc->rowmap[r]) * cc->nx;
  *rows = (const char **)(cc->set_store - cc->gys);
  PetscFunctionReturn(0);
}

/* Whether the profile has points without a face (h = PETSC_INFINITY): then the openings' rows
   need u there, kept in faceless (a grid vector only such a profile pays for). */
static PetscErrorCode EnsureFaceless(AdhSolver s, CrackClosure *cc)
{
  const PetscScalar *ha;
  PetscBool          any = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(s->h, &ha));
  for (PetscInt k = 0; k < s->nlocal && !any; k++) any = (PetscBool)(PetscRealPart(ha[k]) >= PETSC_INFINITY);
  PetscCall(VecRestoreArrayRead(s->h, &ha));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &any, 1, MPIU_BOOL, MPI_LOR, s->comm));
  if (any && !cc->faceless) PetscCall(VecDuplicate(s->h, &cc->faceless));
  if (!any) PetscCall(VecDestroy(&cc->faceless));
  PetscFunctionReturn(0);
}

/* The fetched rows of f: rows[b] is row b of the grid (gys <= b < gys + gym), as DMDA gives them. */
static PetscErrorCode GetRows(CrackClosure *cc, FetchedRows *f, const PetscScalar ***rows)
{
  const PetscInt nx = cc->nx;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(f->v, &f->own));
  for (PetscInt r = 0; r < cc->gym; r++) f->store[r] = cc->rowmap[r] >= 0 ? (PetscScalar *)f->own + cc->rowmap[r] * nx : f->far + (-1 - cc->rowmap[r]) * nx;
  *rows = (const PetscScalar **)(f->store - cc->gys);
  PetscFunctionReturn(0);
}

static PetscErrorCode RestoreRows(FetchedRows *f, const PetscScalar ***rows)
{
  PetscFunctionBegin;
  PetscCall(VecRestoreArrayRead(f->v, &f->own));
  *rows = NULL;
  PetscFunctionReturn(0);
}

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

/* Whether (i, j) lies on the grid (always on a periodic cell). Neighbour() is false there only
   when the point is outside the fetched rows: the width does not cover the offset, a bug. */
static inline PetscBool OnGrid(const AdhGrid g, PetscBool wrap, PetscInt i, PetscInt j)
{
  return (PetscBool)(wrap || (i >= 0 && i < g->Nx && j >= 0 && j < g->Ny));
}

/* The outward normal of the contact edge at set point (i, j), unnormalised: the sum of the offsets
   to the open points within ADH_NORMAL_RADIUS grid spacings (a disk cut by a straight edge gives
   its normal). Points off a free grid count as neither. */
static PetscErrorCode EdgeNormal(const AdhGrid g, PetscBool wrap, PetscInt gys, PetscInt gym, const char **sl, PetscInt i, PetscInt j, PetscReal n[2])
{
  const PetscInt r = ADH_NORMAL_RADIUS;

  PetscFunctionBegin;
  n[0] = n[1] = 0.0;
  for (PetscInt dj = -r; dj <= r; dj++)
    for (PetscInt di = -r; di <= r; di++) {
      PetscInt a, b;
      if (di * di + dj * dj > r * r) continue;
      if (!Neighbour(g, wrap, gys, gym, i, j, di, dj, &a, &b)) {
        PetscCheck(!OnGrid(g, wrap, i + di, j + dj), PETSC_COMM_SELF, PETSC_ERR_PLIB, "crack-closure: edge normal outside the fetched rows");
        continue;
      }
      if (!sl[b][a]) {
        n[0] += di;
        n[1] += dj;
      }
    }
  PetscFunctionReturn(0);
}

/* The front's links for the walks of FrontMean: for each fetched point of the front (G not NaN in
   Gl), bit (ej + 2) 5 + (ei + 2) set when (i + ei, j + ej) is a fetched point of the front too
   (wrapped on a periodic cell), so that a walk looks at a point's few front neighbours instead of
   all 25 offsets around it. */
/* The offset of link bit k: (k mod 5 - 2, k div 5 - 2). */
static const PetscInt LinkDi[25] = {-2, -1, 0, 1, 2, -2, -1, 0, 1, 2, -2, -1, 0, 1, 2, -2, -1, 0, 1, 2, -2, -1, 0, 1, 2};
static const PetscInt LinkDj[25] = {-2, -2, -2, -2, -2, -1, -1, -1, -1, -1, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2};

static PetscErrorCode FrontLinks(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl)
{
  const AdhGrid  g  = s->grid;
  const PetscInt Nx = g->Nx;

  PetscFunctionBegin;
  for (PetscInt b = cc->gys; b < cc->gys + cc->gym; b++)
    for (PetscInt i = 0; i < Nx; i++) {
      PetscInt bits = 0, a, bb;
      if (!IsNaN(PetscRealPart(Gl[b][i])))
        for (PetscInt ej = -2; ej <= 2; ej++)
          for (PetscInt ei = -2; ei <= 2; ei++)
            if (Neighbour(g, wrap, cc->gys, cc->gym, i, b, ei, ej, &a, &bb) && !IsNaN(PetscRealPart(Gl[bb][a]))) bits |= (PetscInt)1 << ((ej + 2) * 5 + ei + 2);
      cc->links[(b - cc->gys) * Nx + i] = bits;
    }
  PetscFunctionReturn(0);
}

static PetscErrorCode EnsureInnerLinks(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl)
{
  PetscFunctionBegin;
  if (cc->links_set == s->set_version) PetscFunctionReturn(0);
  PetscCall(FrontLinks(s, cc, wrap, Gl));
  cc->links_set = s->set_version;
  PetscFunctionReturn(0);
}

/* The front's curvature (1/grid spacings, >= 0) from a window's moments M[a][b] = sum wt di^a dj^b
   about a front point: the tangent is the major axis of the centred second moments, and
   y = c0 + c1 s + kappa s^2 / 2 is fitted by weighted least squares (s along the tangent, y along
   the normal; the offset c0 takes up where the point sits on its staircase). PETSC_MAX_REAL where
   the window does not show an arc through the point: too few points, not elongated (a small
   closed patch), or lying to one side of it (the front ends, or breaks). */
static PetscErrorCode FitCurvature(PetscReal M[5][5], PetscReal *curvature)
{
  static const PetscReal binom[5][5] = {{1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}, {1, 4, 6, 4, 1}};
  const PetscReal        w = M[0][0];
  PetscReal              cx, cy, cxx, cxy, cyy, half, root, major, minor, t[2], n[2], len, S[5], Y[3], det;

  PetscFunctionBegin;
  *curvature = PETSC_MAX_REAL;
  if (w < 6.0) PetscFunctionReturn(0);
  cx    = M[1][0] / w;
  cy    = M[0][1] / w;
  cxx   = M[2][0] / w - cx * cx;
  cxy   = M[1][1] / w - cx * cy;
  cyy   = M[0][2] / w - cy * cy;
  half  = 0.5 * (cxx - cyy);
  root  = PetscSqrtReal(half * half + cxy * cxy);
  major = 0.5 * (cxx + cyy) + root;
  minor = 0.5 * (cxx + cyy) - root;
  if (!(major > 4.0 * minor)) PetscFunctionReturn(0);
  t[0] = half + root;
  t[1] = cxy;
  if (t[0] <= 0 && cxy == 0) { /* the major axis along y */
    t[0] = 0;
    t[1] = 1;
  }
  len  = PetscSqrtReal(t[0] * t[0] + t[1] * t[1]);
  t[0] /= len;
  t[1] /= len;
  n[0] = -t[1];
  n[1] = t[0];
  if (PetscAbsReal(cx * t[0] + cy * t[1]) > 0.5 * PetscSqrtReal(major)) PetscFunctionReturn(0);
  /* S_k = sum wt s^k, Y_k = sum wt s^k y, from the moments: s = t . (di, dj), y = n . (di, dj) */
  for (PetscInt k = 0; k <= 4; k++) {
    S[k] = 0;
    if (k <= 2) Y[k] = 0;
    for (PetscInt a = 0; a <= k; a++) {
      const PetscReal c = binom[k][a] * PetscPowRealInt(t[0], a) * PetscPowRealInt(t[1], k - a);
      S[k] += c * M[a][k - a];
      if (k <= 2) Y[k] += c * (n[0] * M[a + 1][k - a] + n[1] * M[a][k - a + 1]);
    }
  }
  /* the normal equations of (c0, c1, kappa/2), by Cramer's rule for the last */
  det = S[0] * (S[2] * S[4] - S[3] * S[3]) - S[1] * (S[1] * S[4] - S[3] * S[2]) + S[2] * (S[1] * S[3] - S[2] * S[2]);
  if (!(PetscAbsReal(det) > 0)) PetscFunctionReturn(0);
  *curvature = 2.0 * PetscAbsReal(S[0] * (S[2] * Y[2] - Y[1] * S[3]) - S[1] * (S[1] * Y[2] - Y[1] * S[2]) + Y[0] * (S[1] * S[3] - S[2] * S[2])) / PetscAbsReal(det);
  PetscFunctionReturn(0);
}

/* The release rate averaged along the front around front point (i, j): the front points reached
   from it in steps of at most two grid spacings (a front drawn on the grid is 8-connected where
   the edge is smooth; two also bridge a missing point) without leaving the disk of the radius,
   so that the fronts of other contact patches nearby do not count. Weighted by
   (1 - r^2/radius^2)^2, which fades out at the rim: a staircase period cut by the rim then weighs
   little, and the mean over a curved edge does not depend on where the rim cuts it. With
   curvature, also the front's curvature at (i, j) (1/grid spacings), fitted to the same points. */
static PetscErrorCode FrontMean(AdhSolver s, CrackClosure *cc, PetscBool wrap, PetscInt gys, PetscInt gym, const PetscScalar **Gl, PetscInt i, PetscInt j, PetscReal radius, PetscReal *sum, PetscReal *weights, PetscReal *curvature, PetscBool record)
{
  const AdhGrid   g = s->grid;
  const PetscInt  w = cc->width, side = 2 * w + 1;
  const PetscReal rad2 = radius * radius;
  const PetscInt  r2lim = (PetscInt)PetscCeilReal(rad2);
  PetscReal       M[5][5] = {{0}}; /* the window's moments sum wt di^a dj^b about (i, j), a + b <= 4 */
  const PetscInt  NONE = PETSC_MIN_INT;
  PetscInt        head = 0, tail = 0, *col = cc->col + w, *row = cc->row + w;

  PetscFunctionBegin;
  /* the window's columns and rows in the fetched rows, once per point (Neighbour() for every
     offset of the walk, without its divisions), as far as this walk reaches (|offset| < radius);
     NONE: off the grid or the rows (a fetched row's index may be negative on a periodic cell) */
  const PetscInt reach = PetscMin(w, (PetscInt)PetscCeilReal(radius));
  for (PetscInt d = -reach; d <= reach; d++) {
    PetscInt a, b;
    col[d] = Neighbour(g, wrap, gys, gym, i, j, d, 0, &a, &b) ? a : NONE;
    row[d] = Neighbour(g, wrap, gys, gym, i, j, 0, d, &a, &b) ? b : NONE;
  }
  if (cc->stamp == PETSC_MAX_INT) {
    PetscCall(PetscArrayzero(cc->seen, side * side));
    cc->stamp = 0;
  }
  cc->stamp++;
  cc->qi[0]              = 0; /* offset (0, 0) */
  cc->qj[0]              = 0;
  tail                   = 1;
  cc->seen[w * side + w] = cc->stamp;
  /* the walk: the front points reached, in the order met (a breadth-first search over the links);
     an offset lies inside the disk when its integer r^2 is below ceil(rad2) */
  while (head < tail) {
    const PetscInt di = cc->qi[head], dj = cc->qj[head++];

    PetscCheck(col[di] != NONE && row[dj] != NONE, PETSC_COMM_SELF, PETSC_ERR_PLIB, "crack-closure: front point outside the fetched rows");
    /* its front neighbours, in the order of the offsets (ej, then ei, ascending) */
    for (PetscInt bits = cc->links[(row[dj] - cc->gys) * s->grid->Nx + col[di]]; bits; bits &= bits - 1) {
      const PetscInt k = __builtin_ctz((unsigned)bits), ni = di + LinkDi[k], nj = dj + LinkDj[k], no = (nj + w) * side + (ni + w);
      if (ni * ni + nj * nj >= r2lim || cc->seen[no] == cc->stamp) continue;
      cc->seen[no]     = cc->stamp;
      cc->qi[tail]     = ni;
      cc->qj[tail++]   = nj;
    }
  }
  /* the sums over them in that order, apart from the walk so that the weights' divisions overlap */
  *sum     = 0.0;
  *weights = 0.0;
  if (record && cc->nmember + tail > cc->capmember) { /* into the front's cache */
    cc->capmember = PetscMax(PetscMax(1024, 2 * cc->capmember), cc->nmember + tail);
    PetscCall(PetscRealloc(cc->capmember * sizeof(PetscInt), &cc->member));
    PetscCall(PetscRealloc(cc->capmember * sizeof(PetscReal), &cc->weight));
  }
  for (PetscInt m = 0; m < tail; m++) {
    const PetscInt  di = cc->qi[m], dj = cc->qj[m];
    const PetscReal r2 = (PetscReal)(di * di + dj * dj), wt = (1.0 - r2 / rad2) * (1.0 - r2 / rad2);

    *sum += wt * PetscRealPart(Gl[row[dj]][col[di]]);
    *weights += wt;
    if (record) {
      cc->member[cc->nmember]   = (row[dj] - gys) * g->Nx + col[di];
      cc->weight[cc->nmember++] = wt;
    }
    if (curvature) {
      PetscReal xa = wt;
      for (PetscInt a = 0; a <= 4; a++, xa *= di) {
        PetscReal xy = xa;
        for (PetscInt b = 0; a + b <= 4; b++, xy *= dj) M[a][b] += xy;
      }
    }
  }
  if (curvature) PetscCall(FitCurvature(M, curvature));
  PetscFunctionReturn(0);
}

/* A point's window grows only where its mean over the radius lies within this band of dgamma:
   near its decision (a mean far from dgamma decides the same with any window). */
#define ADH_WINDOW_BAND_LOW  0.8
#define ADH_WINDOW_BAND_HIGH 1.25

/* A cached walk's mean: the same sums in the same order as the walk's. */
static inline void CachedSums(CrackClosure *cc, const PetscScalar **Gl, PetscInt w0, PetscInt n, PetscReal *sum, PetscReal *weights)
{
  const PetscInt Nx = cc->nx;
  *sum     = 0.0;
  *weights = 0.0;
  for (PetscInt m = w0; m < w0 + n; m++) {
    *sum += cc->weight[m] * PetscRealPart(Gl[cc->gys + cc->member[m] / Nx][cc->member[m] % Nx]);
    *weights += cc->weight[m];
  }
}

/* One window's sums: from the front's cache where it holds the walk (w0, n; n < 0: not yet),
   else the walk (over the links of the front Gl holds), recorded into the cache when there is
   one (w0, n not NULL). */
static PetscErrorCode Walk(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl, PetscInt i, PetscInt j, PetscReal radius, PetscInt *w0, PetscInt *n, PetscReal *sum, PetscReal *weights, PetscReal *curvature)
{
  PetscFunctionBegin;
  if (n && *n >= 0) {
    CachedSums(cc, Gl, *w0, *n, sum, weights);
    PetscFunctionReturn(0);
  }
  if (n) *w0 = cc->nmember;
  PetscCall(FrontMean(s, cc, wrap, cc->gys, cc->gym, Gl, i, j, radius, sum, weights, curvature, (PetscBool)(n != NULL)));
  if (n) *n = cc->nmember - *w0;
  PetscFunctionReturn(0);
}

/* The windowed mean of G around front point (i, j) (sum over weights): within the radius, and,
   where that mean lies within [lo, hi], within the front's radius of curvature there if that is larger,
   up to radius_max. A straight front (no curvature) takes radius_max. margin: where the window
   depends on the mean over the radius, how far that mean lies from the band's nearer end (so a
   certified decision knows whether the exact solution takes the same window), else
   PETSC_MAX_REAL. e: the point's entry in the front's cache (NULL: none), whose walks and
   curvature are made on first use and read after. */
static PetscErrorCode WindowMean(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl, PetscInt i, PetscInt j, FrontEntry *e, PetscReal lo, PetscReal hi, PetscReal *sum, PetscReal *weights, PetscReal *margin)
{
  const PetscBool adapts = (PetscBool)(cc->radius_max > cc->radius), walks = (PetscBool)(!e || e->n16 < 0);
  PetscReal       kappa  = e ? e->kappa : PETSC_MAX_REAL, R, mean;

  PetscFunctionBegin;
  *margin = PETSC_MAX_REAL;
  PetscCall(Walk(s, cc, wrap, Gl, i, j, cc->radius, e ? &e->w16 : NULL, e ? &e->n16 : NULL, sum, weights, adapts && walks ? &kappa : NULL));
  if (e && walks) e->kappa = kappa;
  if (!adapts || kappa == PETSC_MAX_REAL || !(*weights > 0)) PetscFunctionReturn(0);
  R = kappa > 1.0 / cc->radius_max ? 1.0 / kappa : cc->radius_max;
  if (R <= cc->radius + 0.5) PetscFunctionReturn(0);
  mean    = *sum / *weights;
  *margin = PetscMin(mean - lo, hi - mean);
  if (*margin < 0) *margin = -*margin; /* outside the band: the window of the radius */
  else PetscCall(Walk(s, cc, wrap, Gl, i, j, R, e ? &e->wR : NULL, e ? &e->nR : NULL, sum, weights, NULL));
  PetscFunctionReturn(0);
}

/* -adh_attach griffith: the gap below which each open point joins, the mirror of the detach test,
   for the p whose gap the detach test just computed (it let nothing go or, under
   -adh_cascade_apart, the points it let go keep their pressure and count as in the set here, as in
   the state solved, while they get no limit of their own). When an open point j beside
   the contact joins, the edge moves out by one element: j takes the tension of its set neighbour
   i closest to the edge's inward normal, and the crack it closes had the opening g_j, so
   G_j = -p_i g_j / 2 is the release rate of the edge one element further out. Averaged along the
   outer front as the detach test averages along the inner one, j joins when that mean is below
   its dgamma: when its gap is below g_j dgamma / mean. Where the neighbour is in compression, or
   j has no set neighbour (a new asperity's first touch), the reach limit Sigma K_00 holds. A
   point that penetrates always joins. */
static PetscErrorCode GriffithLimits(AdhSolver s, CrackClosure *cc)
{
  const AdhGrid      g  = s->grid;
  const PetscReal    chi_per_area = AdhChi(g->hx, g->hy) / (g->hx * g->hy * s->Estar);
  const PetscReal    K00  = AdhLoveCoefficient(0.0, 0.0, g->hx, g->hy, s->Estar);
  const PetscBool    wrap = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  const PetscScalar *ta, **ol, **hl, **pl, **Gl;
  const char       **sl;
  PetscScalar       *Ga, *la;
  PetscReal          tu;
  PetscInt           ys, ym, gys = cc->gys, gym = cc->gym, i, j, k, a, b, nfront;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(ADH_AttachLimits, 0, 0, 0, 0));
  if (!s->attach_limit) { /* G's storage: the limits are written over it once G is no longer read */
    PetscCall(PetscObjectReference((PetscObject)cc->G));
    s->attach_limit = cc->G;
  }
  if (!cc->P.far) PetscCall(PetscMalloc1(cc->nghost * g->Nx + 1, &cc->P.far));
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  PetscCall(FetchRows(cc, s->p, &cc->P));
  PetscCall(GetSetRows(cc, &sl));
  PetscCall(GetRows(cc, &cc->O, &ol));
  PetscCall(GetRows(cc, &cc->H, &hl));
  PetscCall(GetRows(cc, &cc->P, &pl));
  PetscCall(VecGetArray(cc->G, &Ga));
  for (j = ys; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) {
      const PetscInt  k = (j - ys) * g->Nx + i, di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
      const PetscReal hj = PetscRealPart(hl[j][i]);
      PetscReal       normal[2], best = PETSC_MAX_REAL, tension = 0.0;
      PetscBool       beside = PETSC_FALSE;
      Ga[k] = NAN;
      if (cc->set_before[k] || hj >= PETSC_INFINITY) continue; /* points let go since the openings (-adh_cascade_apart) have none */
      for (PetscInt n = 0; n < 4 && !beside; n++) beside = (PetscBool)(Neighbour(g, wrap, gys, gym, i, j, di[n], dj[n], &a, &b) && sl[b][a]);
      if (!beside) continue;
      /* the outward normal (towards the open side), as for a front point */
      PetscCall(EdgeNormal(g, wrap, gys, gym, sl, i, j, normal));
      for (PetscInt n = 0; n < 4; n++) { /* the set neighbour closest to the inward normal (ties: the more tensile) */
        PetscReal along, p;
        if (!Neighbour(g, wrap, gys, gym, i, j, di[n], dj[n], &a, &b) || !sl[b][a]) continue;
        along = di[n] * normal[0] + dj[n] * normal[1];
        p     = PetscRealPart(pl[b][a]);
        if (along < best || (along == best && -p > tension)) {
          best    = along;
          tension = -p;
        }
      }
      if (tension > 0) Ga[k] = tension * PetscRealPart(ol[j][i]) / 2.0; /* ol: j's gap (it has a face) */
    }
  PetscCall(VecRestoreArray(cc->G, &Ga));
  PetscCall(RestoreRows(&cc->P, &pl));
  PetscCall(FetchRows(cc, cc->G, &cc->Gf));

  /* the mean along the outer front, against dgamma, as a limit on the gap: first into a list of
     the front's points (the walks read G's rows), then over G itself, which holds the limits */
  PetscCall(GetRows(cc, &cc->Gf, &Gl));
  PetscCall(FrontLinks(s, cc, wrap, Gl));
  cc->links_set = -1; /* the outer front's now */
  for (j = ys, nfront = 0; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) nfront += (!s->in_set[(j - ys) * g->Nx + i] && !IsNaN(PetscRealPart(Gl[j][i])));
  if (nfront > cc->capfront) {
    cc->capfront = PetscMax(nfront, 2 * cc->capfront);
    PetscCall(PetscFree(cc->front_limit));
    PetscCall(PetscMalloc1(cc->capfront, &cc->front_limit));
  }
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_FALSE, &ta, &tu));
  for (j = ys, nfront = 0; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) {
      const PetscInt  k = (j - ys) * g->Nx + i;
      const PetscReal Sigma = ADH_SIGMA_AT(ta, tu, k), dgamma = chi_per_area * Sigma * Sigma;
      PetscReal       sum, n, gap, margin;
      if (s->in_set[k] || IsNaN(PetscRealPart(Gl[j][i]))) continue;
      PetscCall(WindowMean(s, cc, wrap, Gl, i, j, NULL, ADH_WINDOW_BAND_LOW * dgamma, ADH_WINDOW_BAND_HIGH * dgamma, &sum, &n, &margin));
      gap                       = PetscRealPart(ol[j][i]); /* a front point has a face */
      cc->front_limit[nfront++] = sum > 0 ? PetscMax(0.0, gap * dgamma * n / sum) : PETSC_MAX_REAL;
    }
  PetscCall(RestoreRows(&cc->Gf, &Gl));
  PetscCall(VecGetArray(s->attach_limit, &la));
  for (k = 0, nfront = 0; k < s->nlocal; k++) {
    const PetscBool front = (PetscBool)(!s->in_set[k] && !IsNaN(PetscRealPart(la[k])));
    la[k] = front ? cc->front_limit[nfront++] : ADH_SIGMA_AT(ta, tu, k) * K00; /* else reach */
  }
  PetscCall(VecRestoreArray(s->attach_limit, &la));
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &ta));
  PetscCall(RestoreRows(&cc->H, &hl));
  PetscCall(RestoreRows(&cc->O, &ol));
  s->attach_limit_current = PETSC_TRUE;
  PetscCall(PetscLogEventEnd(ADH_AttachLimits, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The release rate of every front point (pass 1), averaged over the front points within its window
   (pass 2), against dgamma; under detach, removal where either rule says so. The gap of the
   current p is left in s->g.
   With decision (perr > 0), nothing is removed: the decision of the exact solution p*, within perr
   of p at every point. Then the openings are within gerr = rho perr of theirs (rho bounds K's row
   norms), each front point's G = t delta / 2 within (|t| gerr + |delta| perr + perr gerr) / 2,
   and so every windowed mean within the largest of these over the front, E. A point's decision is
   made when its margins exceed these bounds: |p + Sigma| > perr, |p| > perr where the front rule
   may apply, |mean - dgamma| > E. */
static PetscErrorCode Rules(AdhSolver s, PetscBool detach, PetscReal perr, PetscInt *removed, PetscReal *ratio, AdhDetachDecision *decision, PetscReal *needed)
{
  CrackClosure      *cc = (CrackClosure *)s->crdata;
  const AdhGrid      g  = s->grid;
  const PetscReal    chi_per_area = AdhChi(g->hx, g->hy) / (g->hx * g->hy * s->Estar); /* dgamma = chi Sigma^2 / (hx hy E*) */
  const PetscBool    wrap = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  PetscScalar       *pa, *xa = NULL, *Ga;
  const PetscScalar *ta, **ol, **hl, **Gl;
  const char       **sl;
  PetscReal          tu, r = 0.0, gerr = 0.0, E = 0.0, ratio_in_doubt = PETSC_MAX_REAL;
  PetscInt           ys, ym, gys, gym, i, j, k, a, b, count = 0, doubt = 0;

  PetscFunctionBegin;
  PetscCheck(cc->fetch, s->comm, PETSC_ERR_ORDER, "crack-closure: evaluated before set-up");
  s->attach_limit_current = PETSC_FALSE; /* griffith's limits are kept in G's storage, written below */
  if (decision) {
    PetscReal rho;
    PetscCall(MatAdhComplianceGetRowNormBound(s->K, &rho));
    gerr = rho * perr;
  }
  if (cc->h_version != s->profile_version) { /* h changes only with the profile */
    PetscCall(FetchRows(cc, s->h, &cc->H));
    PetscCall(EnsureFaceless(s, cc));
    cc->h_version = s->profile_version;
    cc->decided   = PETSC_FALSE; /* the openings below are of this profile */
  }
  /* u = K p and g = (h - d) + u, the openings' rows, and the set's. After a certified stop p is
     the iterate the stop was decided on, whose g is at hand. */
  if (!(cc->decided && s->certified_stop && !decision)) {
    if (cc->faceless) { /* u into faceless, g from it, then g over u where there is a face */
      const PetscScalar *ha, *ga;
      PetscScalar       *fa;
      PetscCall(MatMult(s->K, s->p, cc->faceless));
      PetscCall(AdhSolverGapFromDisplacement_Private(s, cc->faceless));
      PetscCall(VecGetArrayRead(s->h, &ha));
      PetscCall(VecGetArrayRead(s->g, &ga));
      PetscCall(VecGetArray(cc->faceless, &fa));
      for (k = 0; k < s->nlocal; k++)
        if (PetscRealPart(ha[k]) < PETSC_INFINITY) fa[k] = ga[k];
      PetscCall(VecRestoreArray(cc->faceless, &fa));
      PetscCall(VecRestoreArrayRead(s->g, &ga));
      PetscCall(VecRestoreArrayRead(s->h, &ha));
    } else PetscCall(AdhSolverComputeGap_Private(s));
    PetscCall(FetchRows(cc, cc->faceless ? cc->faceless : s->g, &cc->O));
    PetscCall(FetchSetRows(s, cc));
  }
  cc->decided = (PetscBool)(decision != NULL);
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  gys = cc->gys;
  gym = cc->gym;
  if (cc->cache && cc->cache_set != s->set_version) { /* a new set: a new front */
    for (k = 0; k < s->nlocal; k++) cc->slot[k] = -1;
    cc->nentry    = 0;
    cc->nmember   = 0;
    cc->cache_set = s->set_version;
  }

  /* pass 1: G = -p delta / 2 on the front, the points of the set with an open 4-neighbour. When
     the front lets go, the edge moves by one element towards its open side: on a straight edge
     the set less its front is the set shifted by one element along the grid axis closest to the
     edge's normal. So the opening a front point gets is, by that shift, the one its neighbour
     along that axis has now: delta is the opening of the open neighbour closest to the normal
     (ties: the smaller opening). */
  PetscCall(GetRows(cc, &cc->O, &ol));
  PetscCall(GetRows(cc, &cc->H, &hl));
  PetscCall(GetSetRows(cc, &sl));
  PetscCall(VecGetArray(s->p, &pa));
  PetscCall(VecGetArray(cc->G, &Ga));
  for (j = ys; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) {
      const PetscInt  k = (j - ys) * g->Nx + i, di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
      const PetscReal hi = PetscRealPart(hl[j][i]), ti = -PetscRealPart(pa[k]);
      PetscReal       delta[4], open = PETSC_MAX_REAL, best = -PETSC_MAX_REAL, normal[2];
      PetscInt        dir[4], nopen = 0;
      Ga[k] = NAN;
      if (!s->in_set[k]) continue;
      if (cc->cache && cc->slot[k] == -2) continue; /* not on the front */
      if (cc->cache && cc->slot[k] >= 0) { /* the open neighbours closest to the normal, known */
        const FrontEntry *e = &cc->entry[cc->slot[k]];
        for (PetscInt m = 0; m < e->ncand; m++) {
          const PetscInt  bb = gys + e->cand[m] / g->Nx, aa = e->cand[m] % g->Nx;
          const PetscReal dn = Opening(PetscRealPart(hl[bb][aa]), hi, s->d, PetscRealPart(ol[bb][aa]));
          if (m == 0 || dn < open) open = dn;
        }
        Ga[k] = ti * open / 2.0;
        if (decision) E = PetscMax(E, (PetscAbsReal(ti) * gerr + PetscAbsReal(open) * perr + perr * gerr) / 2.0);
        continue;
      }
      for (PetscInt n = 0; n < 4; n++) { /* the open 4-neighbours and their openings */
        PetscReal hn;
        if (!Neighbour(g, wrap, gys, gym, i, j, di[n], dj[n], &a, &b)) continue; /* off the grid: EdgeNormal checks the rows */
        if (sl[b][a]) continue; /* in the set */
        hn             = PetscRealPart(hl[b][a]); /* PETSC_INFINITY (finite): no face there */
        dir[nopen]     = n;
        delta[nopen++] = Opening(hn, hi, s->d, PetscRealPart(ol[b][a]));
      }
      if (!nopen) { /* not on the front */
        if (cc->cache) cc->slot[k] = -2;
        continue;
      }
      PetscCall(EdgeNormal(g, wrap, gys, gym, sl, i, j, normal));
      for (PetscInt m = 0; m < nopen; m++) {
        const PetscReal along = di[dir[m]] * normal[0] + dj[dir[m]] * normal[1];
        if (along > best || (along == best && delta[m] < open)) {
          best = along;
          open = delta[m];
        }
      }
      if (cc->cache) { /* its entry: the open neighbours along the normal as far as the best */
        FrontEntry *e;
        if (cc->nentry == cc->capentry) {
          cc->capentry = PetscMax(256, 2 * cc->capentry);
          PetscCall(PetscRealloc(cc->capentry * sizeof(FrontEntry), &cc->entry));
        }
        cc->slot[k] = cc->nentry;
        e           = &cc->entry[cc->nentry++];
        e->ncand    = 0;
        e->n16 = e->nR = -1;
        e->w16 = e->wR = 0;
        e->kappa       = PETSC_MAX_REAL;
        for (PetscInt m = 0; m < nopen; m++)
          if (di[dir[m]] * normal[0] + dj[dir[m]] * normal[1] == best) {
            PetscCheck(Neighbour(g, wrap, gys, gym, i, j, di[dir[m]], dj[dir[m]], &a, &b), PETSC_COMM_SELF, PETSC_ERR_PLIB, "crack-closure: an open neighbour outside the fetched rows");
            e->cand[e->ncand++] = (b - gys) * g->Nx + a;
          }
      }
      Ga[k] = ti * open / 2.0;
      if (decision) E = PetscMax(E, (PetscAbsReal(ti) * gerr + PetscAbsReal(open) * perr + perr * gerr) / 2.0);
    }
  PetscCall(VecRestoreArray(cc->G, &Ga));
  PetscCall(RestoreRows(&cc->H, &hl));
  PetscCall(RestoreRows(&cc->O, &ol));
  PetscCall(FetchRows(cc, cc->G, &cc->Gf));
  if (decision) PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &E, 1, MPIU_REAL, MPIU_MAX, s->comm));

  /* pass 2: the mean release rate of the front points within each point's window, against dgamma */
  if (detach && s->xunit) PetscCall(VecGetArray(s->xunit, &xa));
  PetscCall(GetRows(cc, &cc->Gf, &Gl));
  PetscCall(EnsureInnerLinks(s, cc, wrap, Gl)); /* the set's front decides them: once a set */
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_TRUE, &ta, &tu));
  for (j = ys; j < ys + ym; j++)
    for (i = 0; i < g->Nx; i++) {
      const PetscInt  k = (j - ys) * g->Nx + i;
      const PetscReal p = PetscRealPart(pa[k]), Sigma = ADH_SIGMA_AT(ta, tu, k), dgamma = chi_per_area * Sigma * Sigma;
      PetscReal       sum = 0.0, load, n = 0.0, margin = PETSC_MAX_REAL; /* weighted sum of G along the front, and of weights */
      PetscBool       lets_go;
      if (!s->in_set[k]) continue;
      /* the release-rate rule applies to front points in tension, with adhesion */
      if (p < perr && Sigma > 0 && !IsNaN(PetscRealPart(Gl[j][i]))) {
        PetscCheck(!cc->cache || cc->slot[k] >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "crack-closure: a front point without its cache entry");
        PetscCall(WindowMean(s, cc, wrap, Gl, i, j, cc->cache ? &cc->entry[cc->slot[k]] : NULL, ADH_WINDOW_BAND_LOW * dgamma, ADH_WINDOW_BAND_HIGH * dgamma, &sum, &n, &margin));
      }
      if (decision) {
        /* each rule's decision for p*: made (true or false), or in doubt with the factor by which
           the bounds must shrink to make it */
        const PetscBool front = (PetscBool)(n > 0), sigma_go = (PetscBool)(p + perr < -Sigma), sigma_stay = (PetscBool)(p - perr >= -Sigma);
        const PetscBool applies = (PetscBool)(front && p + perr < 0), not_applies = (PetscBool)(!front || p - perr >= 0);
        const PetscReal mean = front ? sum / n : 0.0;
        const PetscBool window = (PetscBool)(!front || margin > E); /* p*'s window is this one */
        const PetscBool above = (PetscBool)(front && window && mean - E > dgamma), below = (PetscBool)(!front || (window && mean + E <= dgamma));
        if (sigma_go || (applies && above)) count++;
        else if (!(sigma_stay && (not_applies || below))) {
          doubt++;
          if (!sigma_go && !sigma_stay) ratio_in_doubt = PetscMin(ratio_in_doubt, PetscAbsReal(p + Sigma) / perr);
          if (!applies && !not_applies) ratio_in_doubt = PetscMin(ratio_in_doubt, PetscAbsReal(p) / perr);
          if (!above && !below) ratio_in_doubt = PetscMin(ratio_in_doubt, PetscMin(PetscAbsReal(mean - dgamma), margin) / E);
        }
        continue;
      }
      /* both rules as stress ratios: (G / dgamma)^(1/2) and -p / Sigma */
      load    = p < 0 && Sigma > 0 ? -p / Sigma : 0.0;
      lets_go = (PetscBool)(p < -Sigma);
      if (n && sum > 0) {
        load    = PetscMax(load, PetscSqrtReal(sum / n / dgamma));
        lets_go = (PetscBool)(lets_go || sum / n > dgamma);
      }
      if (detach && lets_go) {
        AdhSolverRemovePoint_Private(s, k, pa, xa);
        count++;
      } else r = PetscMax(r, load);
    }
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &ta));
  PetscCall(RestoreRows(&cc->Gf, &Gl));
  if (xa) PetscCall(VecRestoreArray(s->xunit, &xa));
  PetscCall(VecRestoreArray(s->p, &pa));
  if (removed) {
    PetscCall(MPIU_Allreduce(&count, removed, 1, MPIU_INT, MPI_SUM, s->comm));
    /* p unchanged (-adh_cascade_apart: the points let go keep theirs until the attach test): it
       takes this gap, and griffith's limits of this p */
    s->gap_current = (PetscBool)(*removed == 0 || s->apart_pending);
    if ((!*removed || s->apart_pending) && s->attach == ADH_ATTACH_GRIFFITH && AdhSolverIsAdhesive_Private(s)) PetscCall(GriffithLimits(s, cc));
  }
  if (ratio) PetscCall(MPIU_Allreduce(&r, ratio, 1, MPIU_REAL, MPIU_MAX, s->comm));
  if (decision) {
    PetscInt counts[2] = {count, doubt};
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, s->comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ratio_in_doubt, 1, MPIU_REAL, MPIU_MIN, s->comm));
    *decision = counts[1] ? ADH_DETACH_IN_DOUBT : counts[0] ? ADH_DETACH_SOME : ADH_DETACH_NONE;
    *needed   = counts[1] ? PetscMin(0.5, ratio_in_doubt) * perr : 0.0;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Evaluate_CrackClosure(AdhSolver s, PetscBool detach, PetscInt *removed, PetscReal *ratio)
{
  PetscFunctionBegin;
  PetscCall(Rules(s, detach, 0.0, removed, ratio, NULL, NULL));
  PetscFunctionReturn(0);
}

/* The certified early stop: the iterate xC into p (the solve's vector, so its values off the set
   stay), and the decision of the rules. One compliance multiply, so checked only once the bound
   has come down to where the decisions in doubt at the last check would be made. */
static PetscErrorCode Decide_CrackClosure(AdhSolver s, Vec xC, PetscReal perr, AdhDetachDecision *decision, PetscReal *needed)
{
  PetscFunctionBegin;
  PetscCall(AdhSolverSetIterate_Private(s, xC));
  PetscCall(Rules(s, PETSC_FALSE, perr, NULL, NULL, decision, needed));
  /* Rules left the gap of this iterate in g: an attach check, which follows only a NONE, takes it */
  s->gap_current = (PetscBool)(*decision == ADH_DETACH_NONE);
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_CrackClosure(AdhSolver s)
{
  CrackClosure *cc = (CrackClosure *)s->crdata;

  PetscFunctionBegin;
  PetscCall(VecDestroy(&cc->faceless));
  PetscCall(VecDestroy(&cc->G));
  PetscCall(PetscFree(cc->rowmap));
  PetscCall(PetscSFDestroy(&cc->fetch));
  PetscCall(PetscFree5(cc->O.far, cc->H.far, cc->Gf.far, cc->far_set, cc->set_before));
  PetscCall(PetscFree(cc->P.far));
  PetscCall(PetscFree5(cc->O.store, cc->H.store, cc->Gf.store, cc->P.store, cc->set_store));
  PetscCall(PetscFree3(cc->seen, cc->qi, cc->qj));
  PetscCall(PetscFree2(cc->col, cc->row));
  PetscCall(PetscFree(cc->links));
  PetscCall(PetscFree(cc->slot));
  PetscCall(PetscFree(cc->entry));
  PetscCall(PetscFree(cc->member));
  PetscCall(PetscFree(cc->weight));
  PetscCall(PetscFree(cc->front_limit));
  PetscCall(PetscFree(s->crdata));
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhCriterionCreate_CrackClosure(AdhSolver s)
{
  CrackClosure *cc;

  PetscFunctionBegin;
  PetscCall(PetscNew(&cc));
  s->crdata            = cc;
  s->crops.setup       = SetUp_CrackClosure;
  s->crops.evaluate    = Evaluate_CrackClosure;
  s->crops.destroy     = Destroy_CrackClosure;
  PetscFunctionReturn(0);
}
