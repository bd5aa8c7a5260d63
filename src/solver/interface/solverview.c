/* AdhSolverView: the solver's set-up, in words. */
#include "solver/solverimpl.h"

/* A type's own lines, indented under its kind's. */
static PetscErrorCode ViewType(PetscViewer viewer, AdhTypeOps *ops, AdhSolver s)
{
  PetscFunctionBegin;
  if (!ops->view) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(ops->view(s, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverView - Prints the solver's set-up in words

  Collective

  Input Parameters:
+ s      - the solver
- viewer - an ASCII viewer, or `NULL` for standard output on the solver's communicator

  Level: beginner

  Notes:
  Prints the boundary, the grid, E*, dgamma and Sigma, the indenter (with a rough surface's statistics), the start,
  the number of path points and the steps per leg, the load control with the lower bound on the eigenvalues of K on
  the current set, the predictor, the cascade options in use, the detachment criterion and the attach rule, each type
  followed by its own lines (`ADHCONTROLDISPLACEMENT`: whether the certified early stop is on; `ADHCONTROLFORCE`: the
  resolution of the pull-off force; `ADHCRITERIONCRACKCLOSURE`: its averaging radii; `ADHPREDICTORPOLONSKYKEER`: its
  tolerances and iterations), the estimated JKR contact radius of the smallest asperities, the memory estimate of
  `AdhSolverEstimateMemory()`, and after set-up the KSP. A viewer of another type prints nothing.

  The adhbem executable calls it after set-up when given -adh_view.

.seealso: `AdhSolverEstimateMemory()`, `AdhSolverResolutionView()`, `AdhSolverSetUp()`, `AdhSolverSetFromOptions()`
@*/
PetscErrorCode AdhSolverView(AdhSolver s, PetscViewer viewer)
{
  PetscBool   isascii;
  const char *single;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  single = s->cascade_single && s->boundary == ADH_BOUNDARY_PERIODIC ? " in single precision" : "";
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(s->comm, &viewer));
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii) PetscFunctionReturn(0);
  PetscCall(PetscObjectPrintClassNamePrefixType((PetscObject)s, viewer)); /* "AdhSolver Object: (name) N MPI processes" */
  PetscCall(PetscViewerASCIIPushTab(viewer));
  {
    char version[256];
    PetscCall(AdhGetVersion(version, sizeof(version)));
    PetscCall(PetscViewerASCIIPrintf(viewer, "%s\n", version));
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "adhesive contact, %s boundary\n", AdhBoundaries[s->boundary]));
  PetscCall(AdhGridView(s->grid, viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "elastic body %s\n", s->elastic_type));
  PetscCall(ViewType(viewer, &s->eops.base, s));
  PetscCall(PetscViewerASCIIPrintf(viewer, "E* = %g, dgamma = %g%s, Sigma = %g%s\n", (double)s->Estar, (double)s->gamma, s->gamma_field ? " (field)" : "", (double)s->Sigma, s->sigma_fixed > 0 ? " (fixed by -adh_critical_stress)" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer, "indenter %s, start %s, %" PetscInt_FMT " path points, %" PetscInt_FMT " steps per leg\n", AdhIndenterTypes[s->indenter.type], AdhStarts[s->start], s->npath, s->steps));
  if (s->indenter.type == ADH_INDENTER_ROUGH) PetscCall(AdhSurfaceView(&s->indenter.surface, viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s control; lambda_min bound on the current set %g\n", s->control_type, (double)s->lambda_set));
  PetscCall(ViewType(viewer, &s->cops.base, s));
  PetscCall(PetscViewerASCIIPrintf(viewer, "contact-set predictor without adhesion: %s\n", s->predictor_type));
  PetscCall(ViewType(viewer, &s->pops.base, s));
  if (s->cascade_apart > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "points join in set updates that let others go, %" PetscInt_FMT " grid spacings from them\n", s->cascade_apart));
  if (s->cascade_local > 0 && s->local_whole) PetscCall(PetscViewerASCIIPrintf(viewer, "after a set update lets points go, the set solved again to a relative residual %g of what they leave (-adh_cascade_local %g: the whole grid)%s, until such a solve lets nothing go\n", (double)s->cascade_local_rtol, (double)s->cascade_local, single));
  else if (s->cascade_local > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "local solves within %" PetscInt_FMT " grid spacings (%g JKR radii) of the points a set update lets go, to a relative residual %g%s\n", s->local_W, (double)s->cascade_local, (double)s->cascade_local_rtol, single));
  if (s->cascade_rtol > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "solves between set updates to a relative residual %g%s, the last of a step to the KSP's\n", (double)s->cascade_rtol, s->cascade_single && s->boundary == ADH_BOUNDARY_PERIODIC ? " in single precision" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer, "detachment criterion %s; attach rule %s\n", s->criterion_type, AdhAttaches[s->attach]));
  PetscCall(ViewType(viewer, &s->crops.base, s));
  if (s->asperity_ac > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "JKR contact radius of the smallest asperities (estimate) over the grid spacing: %g\n", (double)s->asperity_ac));
  {
    PetscLogDouble total, node;
    PetscCall(AdhSolverEstimateMemory(s, &total, &node));
    PetscCall(PetscViewerASCIIPrintf(viewer, "memory estimate: %.3g MB in all, %.3g MB on this node\n", total / 1e6, node / 1e6));
  }
  if (s->ksp) PetscCall(KSPView(s->ksp, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}
