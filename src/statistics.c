/* Statistics of a contact state, recorded per step in the curve: contact patches, mean gap,
   largest tension over the critical stress, and the areas in tension and in compression.

   Patches are the connected clusters of the contact set with edge neighbours (4-connectivity),
   wrapping across the edges of a periodic cell. Each rank labels the clusters of its own rows
   with a union-find; rank 0 then joins the labels that touch across rank boundaries (and across
   the periodic seam), from the first and last row of every rank only. O(N) work per step. */
#include "solverimpl.h"

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

static PetscErrorCode CountPatches(AdhSolver s, PetscInt *patches)
{
  const PetscInt  Nx = s->grid->Nx, n = s->nlocal, ym = n / Nx;
  const PetscBool periodic = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  PetscInt       *parent, *label, *edges = NULL, *all = NULL, *counts = NULL, *offset = NULL;
  PetscInt       *first, *rowa, *rowb, *prev, *cur, *swap;
  PetscInt        k, i, j, local = 0, total, merged = 0, nset = 0;
  PetscMPIInt     rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  /* The union-find runs over the set's points only (numbered in row order), with the set numbers
     of the row above and of the current row: memory in proportion to the set, not the grid. */
  for (k = 0; k < n; k++) nset += s->in_set[k] ? 1 : 0;
  PetscCall(PetscMalloc2(nset + 1, &parent, nset + 1, &label));
  PetscCall(PetscMalloc3(Nx, &first, Nx, &rowa, Nx, &rowb));
  prev = rowa;
  cur  = rowb;
  for (k = 0; k < nset; k++) parent[k] = k;
  for (j = 0, k = 0; j < ym; j++) {
    for (i = 0; i < Nx; i++) {
      cur[i] = s->in_set[j * Nx + i] ? k++ : -1;
      if (cur[i] < 0) continue;
      if (i > 0 && cur[i - 1] >= 0) Union(parent, cur[i], cur[i - 1]);
      if (j > 0 && prev[i] >= 0) Union(parent, cur[i], prev[i]);
    }
    if (periodic && Nx > 1 && cur[0] >= 0 && cur[Nx - 1] >= 0) Union(parent, cur[0], cur[Nx - 1]);
    if (j == 0) PetscCall(PetscArraycpy(first, cur, Nx));
    swap = prev; prev = cur; cur = swap;
  }
  /* after the loop, prev holds the last row. Local cluster numbers 0 .. local-1 at the roots. */
  for (k = 0; k < nset; k++)
    if (Find(parent, k) == k) label[k] = local++;

  /* This rank's cluster count, then the labels of its first and last row (-1: not in the set). */
  PetscCall(PetscMalloc1(2 * Nx + 1, &edges));
  edges[0] = local;
  for (i = 0; i < Nx; i++) {
    edges[1 + i]      = first[i] >= 0 ? label[Find(parent, first[i])] : -1;
    edges[1 + Nx + i] = prev[i] >= 0 ? label[Find(parent, prev[i])] : -1;
  }
  if (!rank) PetscCall(PetscMalloc1((2 * Nx + 1) * size, &all));
  PetscCallMPI(MPI_Gather(edges, (PetscMPIInt)(2 * Nx + 1), MPIU_INT, all, (PetscMPIInt)(2 * Nx + 1), MPIU_INT, 0, s->comm));
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
      for (i = 0; i < Nx; i++)
        if (last[i] >= 0 && first[i] >= 0) merged += Union(gparent, offset[r] + last[i], offset[next] + first[i]);
    }
    *patches = total - merged;
    PetscCall(PetscFree(gparent));
    PetscCall(PetscFree2(counts, offset));
    PetscCall(PetscFree(all));
  }
  PetscCallMPI(MPI_Bcast(patches, 1, MPIU_INT, 0, s->comm));
  PetscCall(PetscFree(edges));
  PetscCall(PetscFree2(parent, label));
  PetscCall(PetscFree3(first, rowa, rowb));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhStatisticsCompute_Private(AdhSolver s, AdhState *st)
{
  const PetscReal    A = s->grid->hx * s->grid->hy;
  const PetscScalar *pa, *sa;
  PetscScalar        gsum;
  PetscReal          ratio = 0.0, su;
  PetscInt           k, count[2] = {0, 0};

  PetscFunctionBegin;
  PetscCall(CountPatches(s, &st->patches));
  PetscCall(VecSum(s->g, &gsum));
  st->mean_gap = PetscRealPart(gsum) / ((PetscReal)s->grid->Nx * (PetscReal)s->grid->Ny);
  PetscCall(VecGetArrayRead(s->p, &pa));
  PetscCall(AdhSolverGetCriticalStress_Private(s, PETSC_FALSE, &sa, &su));
  for (k = 0; k < s->nlocal; k++) {
    const PetscReal p = PetscRealPart(pa[k]), Sigma = ADH_SIGMA_AT(sa, su, k);
    if (!s->in_set[k]) continue;
    if (p < 0) count[0]++;
    else if (p > 0) count[1]++;
    if (p < 0 && Sigma > 0) ratio = PetscMax(ratio, -p / Sigma);
  }
  PetscCall(AdhSolverRestoreCriticalStress_Private(s, &sa));
  PetscCall(VecRestoreArrayRead(s->p, &pa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, count, 2, MPIU_INT, MPI_SUM, s->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ratio, 1, MPIU_REAL, MPIU_MAX, s->comm));
  st->area_tension      = count[0] * A;
  st->area_compression  = count[1] * A;
  st->max_tension_ratio = ratio;
  PetscCall(AdhSolverDetachRatio_Private(s, &st->detach_ratio));
  PetscFunctionReturn(0);
}
