/* adhbem: run an indentation path of an adhesive contact and write the curve.
   mpirun -n P build/adhbem [options] (or -options_file job.opts); -help lists the options. */
#include "adhbem.h"

static const char help[] = "adhbem: adhesive normal contact of elastic solids with the boundary element method\n"
                           "(Pohrt & Popov 2015 mesh-dependent detachment criterion), on PETSc.\n"
                           "Runs the indentation path -adh_path with -adh_steps steps per leg and writes -adh_output.\n\n";

int main(int argc, char **argv)
{
  AdhSolver       solver;
  const AdhCurve *curve;
  PetscBool       has_help, view = PETSC_FALSE;
  PetscReal       Fmin = 0, dmin = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(AdhSolverCreate(PETSC_COMM_WORLD, &solver));
  PetscCall(AdhSolverSetFromOptions(solver));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-adh_view", &view, NULL));
  PetscCall(PetscOptionsHasHelp(NULL, &has_help));
  if (has_help) {
    /* The options above were listed as they were read; the solver's KSP ones come with set-up. */
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  -adh_view: <FALSE> Print the solver set-up (None)\n"));
    PetscCall(AdhSolverSetUp(solver));
    PetscCall(AdhSolverDestroy(&solver));
    PetscCall(PetscFinalize());
    return 0;
  }
  PetscCall(AdhSolverSetUp(solver));
  if (view) PetscCall(AdhSolverView(solver, NULL));
  PetscCall(AdhSolverSolvePath(solver));
  PetscCall(AdhSolverGetCurve(solver, &curve));
  {
    PetscInt ksp = 0, mults = 0, outer = 0, ffts = 0;
    for (PetscInt k = 0; k < curve->n; k++) {
      const AdhState *st = &curve->state[k];
      if (st->force < Fmin) {
        Fmin = st->force;
        dmin = st->d;
      }
      ksp += st->ksp_iterations;
      mults += st->compliance_applications;
      outer += st->outer_iterations;
      ffts += st->fft_pairs;
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "adhbem: %" PetscInt_FMT " states; largest tensile force (pull-off force) %g at d = %g; %" PetscInt_FMT " set updates, %" PetscInt_FMT " KSP iterations, %" PetscInt_FMT " compliance applications, %" PetscInt_FMT " FFT pairs\n", curve->n, (double)(Fmin < 0 ? -Fmin : 0.0), (double)dmin, outer, ksp, mults, ffts));
  }
  PetscCall(AdhSolverDestroy(&solver));
  PetscCall(PetscFinalize());
  return 0;
}
