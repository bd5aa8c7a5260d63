/* The curve: the recorded states and their columns (the order of the CSV and the results file). */
#include "solver/solverimpl.h"

#define COLUMN(name, integer) {#name, offsetof(AdhState, name), integer}
const AdhCurveColumn AdhCurveColumns[] = {
  COLUMN(d, PETSC_FALSE),
  COLUMN(force, PETSC_FALSE),
  COLUMN(area, PETSC_FALSE),
  COLUMN(contact_points, PETSC_TRUE),
  COLUMN(outer_iterations, PETSC_TRUE),
  COLUMN(ksp_iterations, PETSC_TRUE),
  COLUMN(seconds, PETSC_FALSE),
  COLUMN(compliance_applications, PETSC_TRUE),
  COLUMN(fft_pairs, PETSC_TRUE),
  COLUMN(patches, PETSC_TRUE),
  COLUMN(mean_gap, PETSC_FALSE),
  COLUMN(max_tension_ratio, PETSC_FALSE),
  COLUMN(area_tension, PETSC_FALSE),
  COLUMN(area_compression, PETSC_FALSE),
  COLUMN(pulled_off, PETSC_TRUE),
  COLUMN(detach_ratio, PETSC_FALSE),
  COLUMN(smallest_tensile_patch, PETSC_TRUE),
  COLUMN(small_patch_tension, PETSC_FALSE),
  COLUMN(cohesive_area, PETSC_FALSE),
  COLUMN(cohesive_force, PETSC_FALSE),
  COLUMN(contact_perimeter, PETSC_FALSE),
  COLUMN(cohesive_perimeter, PETSC_FALSE),
};
const PetscInt AdhCurveNumColumns = sizeof(AdhCurveColumns) / sizeof(AdhCurveColumns[0]);

/*@
  AdhStateValue - Gives one column of a recorded state as a real number

  Not Collective

  Input Parameters:
+ st     - the state
- column - the column's index in `AdhCurveColumns`, from 0 to `AdhCurveNumColumns` - 1

  Level: intermediate

  Notes:
  Returns the value; a count (an integer column) is converted to `PetscReal`. `AdhCurveColumns` gives each column's
  name, its place in `AdhState` and whether it is a count, in the order of the CSV file. The index is not checked.

.seealso: `AdhSolverGetCurve()`, `AdhSolverRecordState()`, `AdhSolverComputeState()`
@*/
PetscReal AdhStateValue(const AdhState *st, PetscInt column)
{
  const char *field = (const char *)st + AdhCurveColumns[column].offset;
  return AdhCurveColumns[column].integer ? (PetscReal) * (const PetscInt *)field : *(const PetscReal *)field;
}

void AdhStateSetValue(AdhState *st, PetscInt column, PetscReal value)
{
  char *field = (char *)st + AdhCurveColumns[column].offset;
  if (AdhCurveColumns[column].integer) *(PetscInt *)field = (PetscInt)value;
  else *(PetscReal *)field = value;
}

PetscErrorCode AdhCurveAppend_Private(AdhCurve *c, const AdhState *st)
{
  PetscFunctionBegin;
  if (c->n == c->cap) {
    c->cap = PetscMax(64, 2 * c->cap);
    PetscCall(PetscRealloc(c->cap * sizeof(AdhState), &c->state));
  }
  c->state[c->n++] = *st;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhCurveDestroy_Private(AdhCurve *c)
{
  PetscFunctionBegin;
  PetscCall(PetscFree(c->state));
  PetscCall(PetscMemzero(c, sizeof(*c)));
  PetscFunctionReturn(0);
}
