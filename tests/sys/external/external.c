/* A program of a user's own, built against an installed adhbem (tests/sys/test_install.py): the
   path the options give, then the version and the largest tension, printed by the first rank. */
#include <adhbem.h>

#if !ADHBEM_VERSION_GE(0, 1, 0)
  #error "adhbem 0.1.0 or later is needed"
#endif

int main(int argc, char **argv)
{
  AdhSolver       solver;
  const AdhCurve *curve;
  PetscReal       largest_tension = 0;
  char            version[256];
  PetscInt        major, minor, patch;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(AdhGetVersion(version, sizeof(version)));
  /* the library found at run time is the one whose header this was compiled with */
  PetscCall(AdhGetVersionNumber(&major, &minor, &patch));
  PetscCheck(major == ADHBEM_VERSION_MAJOR && minor == ADHBEM_VERSION_MINOR && patch == ADHBEM_VERSION_PATCH, PETSC_COMM_WORLD, PETSC_ERR_LIB,
             "header %s, library %" PetscInt_FMT ".%" PetscInt_FMT ".%" PetscInt_FMT, ADHBEM_VERSION, major, minor, patch);
  PetscCall(AdhSolverCreate(PETSC_COMM_WORLD, &solver));
  PetscCall(AdhSolverSetFromOptions(solver));
  PetscCall(AdhSolverSetUp(solver));
  PetscCall(AdhSolverSolvePath(solver));
  PetscCall(AdhSolverGetCurve(solver, &curve));
  for (PetscInt k = 0; k < curve->n; k++) largest_tension = PetscMax(largest_tension, -curve->state[k].force);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\nlargest tension %.17g\n", version, (double)largest_tension));
  PetscCall(AdhSolverDestroy(&solver));
  PetscCall(PetscFinalize());
  return 0;
}
