#include "results/resultsimpl.h"

/* The columns of the results file's curve and of its CSV: the curve's own (AdhCurveColumns), and
   on a periodic cell the two a rough-contact study reads, mean pressure F / (Lx Ly) and area
   fraction A / (Lx Ly). */
static const char *const DerivedColumns[] = {"mean_pressure", "area_fraction"};

PetscInt AdhOutputNumColumns_Private(AdhSolver s)
{
  return AdhCurveNumColumns + (s->boundary == ADH_BOUNDARY_PERIODIC ? 2 : 0);
}

const char *AdhOutputColumnName_Private(PetscInt j)
{
  return j < AdhCurveNumColumns ? AdhCurveColumns[j].name : DerivedColumns[j - AdhCurveNumColumns];
}

PetscBool AdhOutputColumnIsCount_Private(PetscInt j)
{
  return j < AdhCurveNumColumns ? AdhCurveColumns[j].integer : PETSC_FALSE;
}

PetscReal AdhOutputColumnValue_Private(AdhSolver s, const AdhState *st, PetscInt j)
{
  const PetscReal cell = s->grid->Lx * s->grid->Ly;
  if (j < AdhCurveNumColumns) return AdhStateValue(st, j);
  return (j == AdhCurveNumColumns ? st->force : st->area) / cell;
}
