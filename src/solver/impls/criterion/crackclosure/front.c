/* crack-closure's front geometry: openings, the edge's normal, the front's links, the walks along
   it within a window, its curvature, and the windowed mean of the release rate (with its cache). */
#include "crackclosureimpl.h"

/* Whether (i, j) lies on the grid (always on a periodic cell). Neighbour() is false there only
   when the point is outside the fetched rows: the width does not cover the offset, a bug. */
static inline PetscBool OnGrid(const AdhGrid g, PetscBool wrap, PetscInt i, PetscInt j)
{
  return (PetscBool)(wrap || (i >= 0 && i < g->Nx && j >= 0 && j < g->Ny));
}

/* The outward normal of the contact edge at set point (i, j), unnormalised: the sum of the offsets
   to the open points within ADH_NORMAL_RADIUS grid spacings (a disk cut by a straight edge gives
   its normal). Points off a free grid count as neither. */
PetscErrorCode AdhCrackClosureEdgeNormal_Private(const AdhGrid g, PetscBool wrap, PetscInt gys, PetscInt gym, const char **sl, PetscInt i, PetscInt j, PetscReal n[2])
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

PetscErrorCode AdhCrackClosureFrontLinks_Private(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl)
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

PetscErrorCode AdhCrackClosureEnsureInnerLinks_Private(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl)
{
  PetscFunctionBegin;
  if (cc->links_set == s->set_version) PetscFunctionReturn(0);
  PetscCall(AdhCrackClosureFrontLinks_Private(s, cc, wrap, Gl));
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
PetscErrorCode AdhCrackClosureWindowMean_Private(AdhSolver s, CrackClosure *cc, PetscBool wrap, const PetscScalar **Gl, PetscInt i, PetscInt j, FrontEntry *e, PetscReal lo, PetscReal hi, PetscReal *sum, PetscReal *weights, PetscReal *margin)
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
