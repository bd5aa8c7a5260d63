/* Statistics of a contact state, recorded per step in the curve: contact patches, mean gap,
   largest tension over the critical stress, the areas in tension and in compression, and how well
   the grid resolves the patches that carry tension.

   Patches are the connected clusters of the contact set with edge neighbours (4-connectivity),
   wrapping across the edges of a periodic cell. Each rank labels the clusters of its own rows
   with a union-find; rank 0 then joins the labels that touch across rank boundaries (and across
   the periodic seam), from the first and last row of every rank only, and sums each patch's
   points, force and tension from its pieces. O(N) work per step. The same pass counts the set's
   edges that face a point off it, for the contact's perimeter (the rows across rank boundaries
   from the same gathered first and last rows).

   Resolution: a detachment criterion converges with the grid only where the contact edge is long
   on the scale of an element. A patch of a few elements lets go at a load the mesh sets (on a
   rough surface the last asperity contacts before pull-off are such patches when their JKR
   radius is near one element), so the share of the tension carried by patches of fewer than
   ADH_RESOLVED_PATCH points says how much of the adhesive force the grid does not resolve. */
#include "solver/solverimpl.h"

static PetscInt Find(PetscInt *parent, PetscInt a)
{
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

/* Joins the sets of a and b; returns 1 when they were apart. */
static PetscInt Union(PetscInt *parent, PetscInt a, PetscInt b)
{
  a = Find(parent, a);
  b = Find(parent, b);
  if (a == b) return 0;
  if (a < b) parent[b] = a;
  else parent[a] = b;
  return 1;
}

/* What a patch holds: its points, its force sum(p), its tension sum(min(p, 0)), the grid rows it
   meets and its rows that are wholly in contact. A patch that meets every row, or holds a whole row,
   is a band around a periodic cell (a line contact on a strip): its edge is long, whatever its
   points. */
#define ADH_PATCH_SUMS 5

/* The patches of the set: their number, the points of the smallest one carrying a net tension, and
   the share of the tension in patches of fewer than ADH_RESOLVED_PATCH points. */
static PetscErrorCode CountPatches(AdhSolver s, const PetscBool zone[], AdhState *st)
{
  const PetscInt     Nx = s->grid->Nx, n = s->nlocal, ym = n / Nx;
  const PetscBool    periodic = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  PetscInt          *parent, *label, *edges = NULL, *all = NULL, *counts = NULL, *offset = NULL;
  PetscInt          *first, *rowa, *rowb, *prev, *cur, *swap;
  PetscInt           k, i, j, local = 0, total, merged = 0, nset = 0, result[4] = {0, 0, 0, 0};
  PetscInt           edge[4] = {0, 0, 0, 0}; /* edges facing a point off the set: between columns (length hy), between rows (hx); the same of the set with its cohesive zone */
  PetscBool         *out, *prevout;           /* the current and previous rows of the set with its zone */
  PetscReal         *sums, *allsums = NULL, small[2] = {0.0, 0.0};
  PetscInt          *lastrow, *inrow;
  const PetscScalar *pa;
  PetscMPIInt        rank, size, *rcounts = NULL, *displs = NULL;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  /* The union-find runs over the set's points only (numbered in row order), with the set numbers
     of the row above and of the current row: memory in proportion to the set, not the grid. */
  for (k = 0; k < n; k++) nset += s->in_set[k] ? 1 : 0;
  PetscCall(PetscMalloc2(nset + 1, &parent, nset + 1, &label));
  PetscCall(PetscMalloc3(Nx, &first, Nx, &rowa, Nx, &rowb));
  PetscCall(PetscMalloc2(Nx, &out, Nx, &prevout));
  prev = rowa;
  cur  = rowb;
  for (k = 0; k < nset; k++) parent[k] = k;
  for (j = 0, k = 0; j < ym; j++) {
    for (i = 0; i < Nx; i++) {
      cur[i] = s->in_set[j * Nx + i] ? k++ : -1;
      out[i] = (PetscBool)(cur[i] >= 0 || zone[j * Nx + i]);
      if (i > 0 && (cur[i] < 0) != (cur[i - 1] < 0)) edge[0]++;
      if (j > 0 && (cur[i] < 0) != (prev[i] < 0)) edge[1]++;
      if (i > 0 && out[i] != out[i - 1]) edge[2]++;
      if (j > 0 && out[i] != prevout[i]) edge[3]++;
      if (cur[i] < 0) continue;
      if (i > 0 && cur[i - 1] >= 0) Union(parent, cur[i], cur[i - 1]);
      if (j > 0 && prev[i] >= 0) Union(parent, cur[i], prev[i]);
    }
    if (periodic && Nx > 1 && cur[0] >= 0 && cur[Nx - 1] >= 0) Union(parent, cur[0], cur[Nx - 1]);
    if (periodic && Nx > 1 && (cur[0] < 0) != (cur[Nx - 1] < 0)) edge[0]++;
    if (periodic && Nx > 1 && out[0] != out[Nx - 1]) edge[2]++;
    PetscCall(PetscArraycpy(prevout, out, Nx));
    if (j == 0) PetscCall(PetscArraycpy(first, cur, Nx));
    swap = prev; prev = cur; cur = swap;
  }
  /* after the loop, prev holds the last row. Local cluster numbers 0 .. local-1 at the roots. */
  for (k = 0; k < nset; k++)
    if (Find(parent, k) == k) label[k] = local++;
  /* each local cluster's sums */
  PetscCall(PetscCalloc1(ADH_PATCH_SUMS * local + 1, &sums));
  PetscCall(PetscMalloc2(local + 1, &lastrow, local + 1, &inrow));
  for (k = 0; k < local; k++) lastrow[k] = -1;
  PetscCall(VecGetArrayRead(s->p, &pa));
  for (j = 0, k = 0; j < n; j++) {
    const PetscReal p = PetscRealPart(pa[j]);
    const PetscInt  l = s->in_set[j] ? label[Find(parent, k++)] : -1, row = j / Nx;
    PetscReal      *c;
    if (l < 0) continue;
    c = sums + ADH_PATCH_SUMS * l;
    c[0] += 1.0;
    c[1] += p;
    c[2] += PetscMin(p, 0.0);
    if (lastrow[l] != row) { /* the first point of this patch in this row */
      lastrow[l] = row;
      inrow[l]   = 0;
      c[3] += 1.0;
    }
    if (++inrow[l] == Nx) c[4] += 1.0;
  }
  PetscCall(VecRestoreArrayRead(s->p, &pa));
  PetscCall(PetscFree2(lastrow, inrow));

  /* This rank's cluster count, then the labels of its first and last row (-1: not in the set, -2:
     in its cohesive zone). */
  PetscCall(PetscMalloc1(2 * Nx + 1, &edges));
  edges[0] = local;
  for (i = 0; i < Nx; i++) {
    edges[1 + i]      = ym == 0 ? -1 : first[i] >= 0 ? label[Find(parent, first[i])] : zone[i] ? -2 : -1;
    edges[1 + Nx + i] = ym == 0 ? -1 : prev[i] >= 0 ? label[Find(parent, prev[i])] : zone[(ym - 1) * Nx + i] ? -2 : -1;
  }
  if (!rank) PetscCall(PetscMalloc1((2 * Nx + 1) * size, &all));
  PetscCallMPI(MPI_Gather(edges, (PetscMPIInt)(2 * Nx + 1), MPIU_INT, all, (PetscMPIInt)(2 * Nx + 1), MPIU_INT, 0, s->comm));
  if (!rank) {
    PetscCall(PetscMalloc2(size, &rcounts, size, &displs));
    for (PetscMPIInt r = 0, at = 0; r < size; r++) {
      PetscCall(PetscMPIIntCast(ADH_PATCH_SUMS * all[r * (2 * Nx + 1)], &rcounts[r]));
      displs[r] = at;
      at += rcounts[r];
    }
    PetscCall(PetscMalloc1(displs[size - 1] + rcounts[size - 1] + 1, &allsums));
  }
  PetscCallMPI(MPI_Gatherv(sums, (PetscMPIInt)(ADH_PATCH_SUMS * local), MPIU_REAL, allsums, rcounts, displs, MPIU_REAL, 0, s->comm));
  if (!rank) {
    PetscInt *gparent;
    PetscCall(PetscMalloc2(size, &counts, size + 1, &offset));
    offset[0] = 0;
    for (PetscMPIInt r = 0; r < size; r++) {
      counts[r]     = all[r * (2 * Nx + 1)];
      offset[r + 1] = offset[r] + counts[r];
    }
    total = offset[size];
    PetscCall(PetscMalloc1(total + 1, &gparent));
    for (k = 0; k < total; k++) gparent[k] = k;
    /* last row of rank r against first row of rank r+1; on a periodic cell the last rank's last
       row also meets rank 0's first row */
    for (PetscMPIInt r = 0; r < size; r++) {
      const PetscMPIInt next = r + 1 < size ? r + 1 : 0;
      const PetscInt   *last = all + r * (2 * Nx + 1) + 1 + Nx, *first = all + next * (2 * Nx + 1) + 1;
      if (r + 1 == size && !periodic) break;
      for (i = 0; i < Nx; i++) {
        if (last[i] >= 0 && first[i] >= 0) merged += Union(gparent, offset[r] + last[i], offset[next] + first[i]);
        if ((last[i] < 0) != (first[i] < 0)) result[2]++;
        if ((last[i] == -1) != (first[i] == -1)) result[3]++;
      }
    }
    result[0] = total - merged;
    /* each patch's sums at its root (the pieces are numbered as the gathered sums are laid out) */
    for (k = 0; k < total; k++) {
      const PetscInt root = Find(gparent, k);
      if (root == k) continue;
      for (PetscInt c = 0; c < ADH_PATCH_SUMS; c++) allsums[ADH_PATCH_SUMS * root + c] += allsums[ADH_PATCH_SUMS * k + c];
    }
    for (k = 0; k < total; k++) {
      const PetscReal *c = allsums + ADH_PATCH_SUMS * k;
      if (Find(gparent, k) != k) continue;
      small[1] += c[2];
      if (c[0] < ADH_RESOLVED_PATCH && !(periodic && (c[3] >= s->grid->Ny || c[4] > 0))) small[0] += c[2];
      if (c[1] < 0 && (!result[1] || c[0] < result[1])) result[1] = (PetscInt)c[0];
    }
    PetscCall(PetscFree(gparent));
    PetscCall(PetscFree2(counts, offset));
    PetscCall(PetscFree2(rcounts, displs));
    PetscCall(PetscFree(allsums));
    PetscCall(PetscFree(all));
  }
  PetscCallMPI(MPI_Bcast(result, 4, MPIU_INT, 0, s->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, edge, 4, MPIU_INT, MPI_SUM, s->comm));
  edge[1] += result[2];
  edge[3] += result[3];
  /* a staircase of edges is 4/pi times as long as the isotropic curve it follows, on average */
  st->contact_perimeter  = 0.25 * PETSC_PI * ((PetscReal)edge[0] * s->grid->hy + (PetscReal)edge[1] * s->grid->hx);
  st->cohesive_perimeter = 0.25 * PETSC_PI * ((PetscReal)edge[2] * s->grid->hy + (PetscReal)edge[3] * s->grid->hx);
  PetscCallMPI(MPI_Bcast(small, 2, MPIU_REAL, 0, s->comm));
  st->patches                = result[0];
  st->smallest_tensile_patch = result[1];
  st->small_patch_tension    = small[1] < 0 ? PetscMax(0.0, small[0] / small[1]) : 0.0; /* not -0 */
  PetscCall(PetscFree(sums));
  PetscCall(PetscFree(edges));
  PetscCall(PetscFree2(parent, label));
  PetscCall(PetscFree3(first, rowa, rowb));
  PetscCall(PetscFree2(out, prevout));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhStatisticsCompute_Private(AdhSolver s, AdhState *st)
{
  const PetscReal    A = s->grid->hx * s->grid->hy;
  const PetscScalar *pa, *sa, *ga, *gamma = NULL;
  PetscScalar        gsum;
  PetscReal          ratio = 0.0, su, zone[2] = {0.0, 0.0};
  PetscInt           k, count[2] = {0, 0};
  PetscBool         *in_zone;

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(s->nlocal + 1, &in_zone));
  PetscCall(VecSum(s->g, &gsum));
  st->mean_gap = PetscRealPart(gsum) / ((PetscReal)s->grid->Nx * (PetscReal)s->grid->Ny);
  PetscCall(VecGetArrayRead(s->p, &pa));
  PetscCall(VecGetArrayRead(s->g, &ga));
  if (s->gamma_field) PetscCall(VecGetArrayRead(s->gamma_field, &gamma));
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_FALSE, &sa, &su));
  for (k = 0; k < s->nlocal; k++) {
    const PetscReal p = PetscRealPart(pa[k]), Sigma = ADH_SIGMA_AT(sa, su, k);
    if (!s->in_set[k]) { /* a traction off the set: a cohesive zone's (a law's: within its zone gap) */
      if (p != 0) {
        const PetscReal dgamma = gamma ? PetscRealPart(gamma[k]) : s->gamma;
        in_zone[k] = AdhSolverInCohesiveZone_Private(s, p, PetscRealPart(ga[k]), dgamma);
        if (in_zone[k]) zone[0] += A;
        zone[1] += p * A;
      }
      continue;
    }
    if (p < 0) count[0]++;
    else if (p > 0) count[1]++;
    if (p < 0 && Sigma > 0) ratio = PetscMax(ratio, -p / Sigma);
  }
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &sa));
  if (gamma) PetscCall(VecRestoreArrayRead(s->gamma_field, &gamma));
  PetscCall(VecRestoreArrayRead(s->g, &ga));
  PetscCall(VecRestoreArrayRead(s->p, &pa));
  PetscCall(CountPatches(s, in_zone, st));
  PetscCall(PetscFree(in_zone));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, count, 2, MPIU_INT, MPI_SUM, s->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ratio, 1, MPIU_REAL, MPIU_MAX, s->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, zone, 2, MPIU_REAL, MPIU_SUM, s->comm));
  st->cohesive_area     = zone[0];
  st->cohesive_force    = zone[1];
  st->area_tension      = count[0] * A;
  st->area_compression  = count[1] * A;
  st->max_tension_ratio = ratio;
  PetscCall(AdhSolverDetachRatio_Private(s, &st->detach_ratio));
  PetscFunctionReturn(0);
}
