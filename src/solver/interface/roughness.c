/* A rough surface's rms slope h'_rms (of |grad h|), rms mean curvature h''_rms (half the
   Laplacian, SurfaceTopography's convention) and the elastic energy per area that flattens it, for
   the resolution and stickiness estimates made at set-up.

   On a periodic cell the slope and the curvature come from the operator |q| on the mean-free
   heights, exact in the spectral sense: | |q| h | = |grad h| and |q|^2 h = -Lap h in the mean; the
   energy is <h S h>/2 with the body's stiffness S (E* |q| / 2 on a half-space). A measured map on the free boundary is not periodic, and its edges would
   count as steps: there the slope is the forward differences between neighbouring points and the
   curvature the three-point second differences at the interior points, as SurfaceTopography takes
   them for a map (a rank fetches the rows above and below its own); they read a wave of kh as
   sinc(kh/2) and sinc(kh/2)^2 of its spectral value (0.90 and 0.81 at a cut-off of 4 spacings).
   The energy is the stiffness's on the map with its mean plane removed, the map taken as one cell
   of a periodic surface (its edge steps add a little energy, of relative order
   h_rms / (h'_rms L)). */
#include "solver/solverimpl.h"

/* The slope from forward differences over every pair of neighbours, <(dh/dx)^2> + <(dh/dy)^2>
   each averaged over its pairs; the curvature from second differences at the interior points. */
static PetscErrorCode FiniteDifferences(AdhSolver s, PetscReal *slope, PetscReal *curvature)
{
  AdhGrid            g  = s->grid;
  const PetscInt     Nx = g->Nx, Ny = g->Ny, ys = g->ys, ym = g->ym;
  const PetscReal    hx = g->hx, hy = g->hy;
  PetscInt           rows[2], nrows = 0, above = -1, below = -1;
  PetscSF            sf;
  MPI_Datatype       row;
  const PetscScalar *ha;
  PetscScalar       *ghost;
  PetscReal          sums[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}; /* (dh/dx)^2 and its pairs, (dh/dy)^2 and its pairs, (Lap h / 2)^2 and its points */

  PetscFunctionBegin;
  if (ym > 0 && ys > 0) {
    below         = nrows;
    rows[nrows++] = ys - 1;
  }
  if (ym > 0 && ys + ym < Ny) {
    above         = nrows;
    rows[nrows++] = ys + ym;
  }
  PetscCall(AdhGridCreateRowSF(g, nrows, rows, &sf));
  PetscCall(AdhGridGetRowType(g, MPIU_SCALAR, &row));
  PetscCall(PetscMalloc1(nrows * Nx + 1, &ghost));
  PetscCall(VecGetArrayRead(s->h, &ha));
  PetscCall(PetscSFBcastBegin(sf, row, ha, ghost, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, row, ha, ghost, MPI_REPLACE));
  for (PetscInt j = ys; j < ys + ym; j++) {
    const PetscScalar *mid = ha + (j - ys) * Nx;
    const PetscScalar *up  = j + 1 >= Ny ? NULL : j + 1 < ys + ym ? mid + Nx : ghost + above * Nx;
    const PetscScalar *dn  = j == 0 ? NULL : j - 1 >= ys ? mid - Nx : ghost + below * Nx;
    for (PetscInt i = 0; i < Nx; i++) {
      if (i + 1 < Nx) {
        const PetscReal gx = PetscRealPart(mid[i + 1] - mid[i]) / hx;
        sums[0] += gx * gx;
        sums[1] += 1.0;
      }
      if (up) {
        const PetscReal gy = PetscRealPart(up[i] - mid[i]) / hy;
        sums[2] += gy * gy;
        sums[3] += 1.0;
      }
      if (up && dn && i > 0 && i + 1 < Nx) {
        const PetscReal lap = PetscRealPart(mid[i + 1] - 2.0 * mid[i] + mid[i - 1]) / (hx * hx) + PetscRealPart(up[i] - 2.0 * mid[i] + dn[i]) / (hy * hy);
        sums[4] += 0.25 * lap * lap;
        sums[5] += 1.0;
      }
    }
  }
  PetscCall(VecRestoreArrayRead(s->h, &ha));
  PetscCall(PetscFree(ghost));
  PetscCall(PetscSFDestroy(&sf));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 6, MPIU_REAL, MPIU_SUM, s->comm));
  *slope     = sums[1] > 0 && sums[3] > 0 ? PetscSqrtReal(sums[0] / sums[1] + sums[2] / sums[3]) : 0.0;
  *curvature = sums[5] > 0 ? PetscSqrtReal(sums[4] / sums[5]) : 0.0;
  PetscFunctionReturn(0);
}

/* b = h less its mean plane (on a regular grid the centred coordinates are orthogonal to the
   constant and to each other, so each coefficient is one projection). */
static PetscErrorCode RemoveMeanPlane(AdhSolver s, Vec b)
{
  AdhGrid         g  = s->grid;
  const PetscReal cx = 0.5 * (PetscReal)(g->Nx - 1), cy = 0.5 * (PetscReal)(g->Ny - 1);
  PetscReal       m[2] = {0.0, 0.0}, xx = 0.0, yy = 0.0;
  PetscScalar    *ba;

  PetscFunctionBegin;
  PetscCall(VecCopy(s->h, b));
  PetscCall(VecShift(b, -s->mean_h));
  PetscCall(VecGetArray(b, &ba));
  for (PetscInt j = g->ys; j < g->ys + g->ym; j++)
    for (PetscInt i = 0; i < g->Nx; i++) {
      m[0] += ((PetscReal)i - cx) * PetscRealPart(ba[(j - g->ys) * g->Nx + i]);
      m[1] += ((PetscReal)j - cy) * PetscRealPart(ba[(j - g->ys) * g->Nx + i]);
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, m, 2, MPIU_REAL, MPIU_SUM, s->comm));
  for (PetscInt i = 0; i < g->Nx; i++) xx += ((PetscReal)i - cx) * ((PetscReal)i - cx) * (PetscReal)g->Ny;
  for (PetscInt j = 0; j < g->Ny; j++) yy += ((PetscReal)j - cy) * ((PetscReal)j - cy) * (PetscReal)g->Nx;
  for (PetscInt j = g->ys; j < g->ys + g->ym; j++)
    for (PetscInt i = 0; i < g->Nx; i++) ba[(j - g->ys) * g->Nx + i] -= (xx > 0 ? m[0] / xx * ((PetscReal)i - cx) : 0.0) + (yy > 0 ? m[1] / yy * ((PetscReal)j - cy) : 0.0);
  PetscCall(VecRestoreArray(b, &ba));
  PetscFunctionReturn(0);
}

/* The three for a rough surface, a topography file or an array, into the solver (0 for any other
   profile, and for a free-boundary map of fewer than 3 x 3 points); once a profile, the two
   estimates read them. */
PetscErrorCode AdhSolverEstimateRoughness_Private(AdhSolver s)
{
  PetscReal            *slope = &s->rms_slope, *curvature = &s->rms_curvature, *energy = &s->full_contact_energy;
  const AdhIndenterType type  = s->indenter.type;
  const PetscReal       N    = (PetscReal)s->grid->Nx * (PetscReal)s->grid->Ny;
  Vec                   b, a, c;
  PetscScalar           dot;
  PetscReal             norm_a, norm_c;

  PetscFunctionBegin;
  *slope = *curvature = *energy = 0.0;
  if (!s->S || !(type == ADH_INDENTER_ROUGH || type == ADH_INDENTER_FILE || type == ADH_INDENTER_ARRAY)) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(s->h, &b));
  PetscCall(VecDuplicate(s->h, &a));
  PetscCall(VecDuplicate(s->h, &c));
  if (s->boundary == ADH_BOUNDARY_PERIODIC) {
    PetscCall(VecCopy(s->h, b));
    PetscCall(VecShift(b, -s->mean_h)); /* S keeps the mean mode (positive definite); it carries no energy */
  } else PetscCall(RemoveMeanPlane(s, b));
  PetscCall(MatMult(s->S, b, a)); /* the pressure of full contact: the body's stiffness */
  PetscCall(VecDot(a, b, &dot));
  *energy = 0.5 * PetscRealPart(dot) / N;
  if (s->boundary == ADH_BOUNDARY_PERIODIC) {
    Mat Q; /* |q|: the half-space stiffness of E* = 2, on the grid's transform */
    PetscCall(MatCreateAdhPeriodicStiffness(s->grid, 2.0, &Q));
    PetscCall(MatMult(Q, b, a));
    PetscCall(MatMult(Q, a, c));
    PetscCall(MatDestroy(&Q));
    PetscCall(VecNorm(a, NORM_2, &norm_a));
    PetscCall(VecNorm(c, NORM_2, &norm_c));
    *slope     = norm_a / PetscSqrtReal(N);
    *curvature = 0.5 * norm_c / PetscSqrtReal(N);
  } else if (s->grid->Nx >= 3 && s->grid->Ny >= 3) PetscCall(FiniteDifferences(s, slope, curvature));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&a));
  PetscCall(VecDestroy(&c));
  if (!PetscIsNormalReal(*curvature)) *slope = *curvature = *energy = 0.0; /* a flat map */
  PetscFunctionReturn(0);
}
