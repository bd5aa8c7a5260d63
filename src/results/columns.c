#include "results/resultsimpl.h"

/* The columns of the results file's curve and of its CSV: the curve's own (AdhCurveColumns), then
   the area fraction A / (Lx Ly) on every boundary (on a free boundary, of the grid's area: for a
   measured map the scan's), and on a periodic cell the mean pressure F / (Lx Ly), which a
   rough-contact study reads beside it. */
static const char *const DerivedColumns[] = {"area_fraction", "mean_pressure"};

PetscInt AdhOutputNumColumns_Private(AdhSolver s)
{
  return AdhCurveNumColumns + (s->boundary == ADH_BOUNDARY_PERIODIC ? 2 : 1);
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
  return (j == AdhCurveNumColumns ? st->area : st->force) / cell;
}
