/* -adh_cascade_apart D: a set update that lets points go lets points join too, where they lie more
   than D grid spacings (in x and in y) from every point let go in it.

   Why: in the exact cascade a point may join only in an update that lets no point go anywhere in
   the cell. On a rough cell every region's joins then wait for every other region's detachments,
   so the updates of a step add up over the regions instead of running side by side, and they grow
   with the cell's side (the median step of `./run bench scale` doubles from 256^2 to 512^2). A
   join far from the points let go sees the gap of the solved state there, which their going
   barely changes; near them it waits, as in the exact cascade. The sets differ from the exact
   cascade's, so the route is judged by its error against the converged reference
   (docs/developers/notebook/performance.md).

   The points let go in the update are marked in s->gone (AdhSolverRemovePoint_Private), and keep
   their pressure until the attach test is over, so that it (and griffith's limits) see the state
   just solved, whatever the criterion; the marks
   of the D rows beyond a rank's own come from the ranks that own them (a PetscSF of bytes), and a
   running count along x, then along y, widens the marks by D. */
#include <string.h>
#include "solver/solverimpl.h"

/* The SF that brings each rank the marks of the D rows before and after its own (wrapped on a
   periodic cell, none beyond a free grid's edge), and the source of each row of the widened band;
   D the larger of -adh_cascade_apart's and -adh_cascade_local's widths, which share the marks (made
   again when a new profile widens the local one). */
PetscErrorCode AdhSolverSetUpCascadeApart_Private(AdhSolver s)
{
  const AdhGrid g = s->grid;
  /* a band of Ny rows each side marks every row already: wider adds nothing (a window of the
     whole grid on a grid of few rows) */
  const PetscInt D = PetscMin(PetscMax(s->cascade_apart, s->local_W), g->Ny), Nx = g->Nx, Ny = g->Ny;
  const PetscBool wrap = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  PetscInt      ys, ym, nghost = 0, e, q;

  PetscFunctionBegin;
  if (s->apart_sf && s->apart_D >= D) PetscFunctionReturn(0); /* a band as wide serves */
  PetscCall(AdhSolverDestroyCascadeApart_Private(s));
  s->apart_D = D;
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  /* each row of the band ys - D .. ys + ym + D - 1: own row l (l), ghost row q (ym + q), or off
     the grid (-1); a wrapped row met twice (a cell of few rows) is fetched once */
  PetscCall(PetscMalloc2(ym + 2 * D, &s->apart_source, 2 * D + 1, &s->apart_rows));
  for (e = 0; e < ym + 2 * D; e++) {
    PetscInt r = ys - D + e;
    if (wrap) r = (r % Ny + Ny) % Ny;
    if (r < 0 || r >= Ny) s->apart_source[e] = -1;
    else if (r >= ys && r < ys + ym) s->apart_source[e] = r - ys;
    else {
      for (q = 0; q < nghost && s->apart_rows[q] != r; q++) { }
      if (q == nghost) s->apart_rows[nghost++] = r;
      s->apart_source[e] = ym + q;
    }
  }
  PetscCall(AdhGridCreateRowSF(g, nghost, s->apart_rows, &s->apart_sf));
  PetscCall(PetscCalloc1(ym * Nx + 1, &s->gone));
  PetscCall(PetscMalloc4(nghost * Nx + 1, &s->apart_ghost, (ym + 2 * D) * Nx, &s->apart_band, Nx, &s->apart_count, ym + 2 * D, &s->apart_any));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverDestroyCascadeApart_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(s->gone));
  PetscCall(PetscSFDestroy(&s->apart_sf));
  PetscCall(PetscFree2(s->apart_source, s->apart_rows));
  PetscCall(PetscFree4(s->apart_ghost, s->apart_band, s->apart_count, s->apart_any));
  PetscFunctionReturn(0);
}

/* An update whose attach test will follow its detach test: no point marked yet, and the points
   let go keep their pressure (AdhSolverRemovePoint_Private). */
PetscErrorCode AdhSolverBeginCascadeApart_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(PetscArrayzero(s->gone, s->nlocal));
  s->apart_pending = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The update's attach test is over: the points let go (among the marks) lose their pressure. */
PetscErrorCode AdhSolverEndCascadeApart_Private(AdhSolver s)
{
  PetscScalar *pa;

  PetscFunctionBegin;
  s->apart_pending = PETSC_FALSE;
  PetscCall(VecGetArray(s->p, &pa));
  for (PetscInt k = 0; k < s->nlocal; k++)
    if (s->gone[k] && !s->in_set[k]) pa[k] = 0.0;
  PetscCall(VecRestoreArray(s->p, &pa));
  PetscFunctionReturn(0);
}

/* s->gone: the marked points, widened by w (in x and in y; in each direction at most the grid's
   extent, which marks it all already); rows of the band from offset o = apart_D - w on, so that
   one band serves both widths (-adh_cascade_apart, -adh_cascade_local). */
PetscErrorCode AdhSolverMarkNearGone_Private(AdhSolver s, PetscInt width)
{
  const AdhGrid   g = s->grid;
  const PetscInt  Nx = g->Nx, wx = PetscMin(width, Nx), w = PetscMin(width, g->Ny), o = s->apart_D - w;
  const PetscBool wrap = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  PetscInt        ys, ym, e, i, j, active = 0;
  char           *band = s->apart_band, *any = s->apart_any;
  PetscInt       *count = s->apart_count;
  MPI_Datatype    row;

  PetscFunctionBegin;
  PetscCheck(w >= 0 && o >= 0, s->comm, PETSC_ERR_PLIB, "Marks widened by %" PetscInt_FMT " rows on a band of %" PetscInt_FMT, w, s->apart_D);
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  PetscCall(AdhGridGetRowType(g, MPI_CHAR, &row));
  PetscCall(PetscSFBcastBegin(s->apart_sf, row, s->gone, s->apart_ghost, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(s->apart_sf, row, s->gone, s->apart_ghost, MPI_REPLACE));
  /* along x: each row of the band, a running count of the marks within wx (most rows have none) */
  for (e = o; e < o + ym + 2 * w; e++) {
    const PetscInt src = s->apart_source[e];
    const char    *row = src < 0 ? NULL : src < ym ? s->gone + src * Nx : s->apart_ghost + (src - ym) * Nx;
    char          *out = band + e * Nx;
    PetscInt       c   = 0;
    any[e] = (char)(row && memchr(row, 1, (size_t)Nx));
    if (!any[e]) {
      PetscCall(PetscArrayzero(out, Nx));
      continue;
    }
#define AT(a) (wrap ? row[((a) % Nx + Nx) % Nx] : ((a) >= 0 && (a) < Nx ? row[a] : 0))
    for (i = -wx; i <= wx; i++) c += AT(i);
    for (i = 0; i < Nx; i++) {
      out[i] = (char)(c > 0);
      c += AT(i + wx + 1) - AT(i - wx);
    }
#undef AT
  }
  /* along y: for each own row j (band row o + j + w), the count over band rows o + j .. o + j + 2w;
     only rows with marks change it */
  PetscCall(PetscArrayzero(count, Nx));
  for (e = o; e <= o + 2 * w; e++) {
    if (!any[e]) continue;
    active++;
    for (i = 0; i < Nx; i++) count[i] += band[e * Nx + i];
  }
  for (j = 0; j < ym; j++) {
    if (active) for (i = 0; i < Nx; i++) s->gone[j * Nx + i] = (char)(count[i] > 0);
    else PetscCall(PetscArrayzero(s->gone + j * Nx, Nx));
    if (j + 1 == ym) break;
    if (any[o + j + 2 * w + 1]) {
      active++;
      for (i = 0; i < Nx; i++) count[i] += band[(o + j + 2 * w + 1) * Nx + i];
    }
    if (any[o + j]) {
      active--;
      for (i = 0; i < Nx; i++) count[i] -= band[(o + j) * Nx + i];
    }
  }
  PetscFunctionReturn(0);
}
