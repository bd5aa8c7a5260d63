/* The package: class id, log events, and FFTW-MPI initialisation, done once. The solver's types
   register in solver/impls/register.c. */
#include <fftw3-mpi.h>
#include "sys/sysimpl.h"

PetscClassId  ADH_CLASSID, ADH_GRID_CLASSID;
PetscLogEvent ADH_FFTForward, ADH_FFTBackward, ADH_ComplianceMult, ADH_Solve, ADH_SetUpdate, ADH_Predict, ADH_DetachTest, ADH_AttachLimits, ADH_LocalSolve;

static PetscBool AdhPackageInitialized = PETSC_FALSE;

static PetscErrorCode AdhFinalizePackage(void)
{
  PetscFunctionBegin;
  fftw_mpi_cleanup();
  fftwf_mpi_cleanup();
  AdhPackageInitialized = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/*@
  AdhInitializePackage - Initialises the adhbem package: its class id, its log events and FFTW-MPI

  Not Collective

  Notes:
  It registers the classes "AdhSolver" (`ADH_CLASSID`, the solver's; -info :adhsolver filters its messages) and "AdhGrid"
  (`ADH_GRID_CLASSID`, -info :adhgrid) and the log events AdhFFTForward, AdhFFTBackward, AdhComplMult,
  AdhStepSolve, AdhSetUpdate, AdhPredict, AdhDetachTest, AdhAttachLimits and AdhLocalSolve, initialises FFTW-MPI in double and
  single precision, and registers with `PetscRegisterFinalize()` the clean-up of FFTW-MPI. It is done once: later calls return
  at once, until `PetscFinalize()`. `AdhGridCreate()`, `AdhGridSetUp()` and the operators' constructors call it; the solver's
  types register with the solver.

  Level: developer

.seealso: `AdhGridCreate()`, `MatCreateAdhCompliance()`, `AdhSolverCreate()`
@*/
PetscErrorCode AdhInitializePackage(void)
{
  PetscFunctionBegin;
  if (AdhPackageInitialized) PetscFunctionReturn(0);
  PetscCall(AdhCheckPETSc_Private());
  AdhPackageInitialized = PETSC_TRUE;
  fftw_mpi_init();
  fftwf_mpi_init();
  PetscCall(PetscClassIdRegister("AdhSolver", &ADH_CLASSID)); /* the class of the solver, a PETSc object (-info :adhsolver, -log_view) */
  PetscCall(PetscClassIdRegister("AdhGrid", &ADH_GRID_CLASSID)); /* the element grid, a PETSc object too */
  {
    PetscClassId classids[1];
    classids[0] = ADH_CLASSID;
    PetscCall(PetscInfoProcessClass("adhsolver", 1, classids)); /* -info [:~]adhsolver */
    classids[0] = ADH_GRID_CLASSID;
    PetscCall(PetscInfoProcessClass("adhgrid", 1, classids)); /* -info [:~]adhgrid */
  }
  PetscCall(PetscLogEventRegister("AdhFFTForward", ADH_CLASSID, &ADH_FFTForward));
  PetscCall(PetscLogEventRegister("AdhFFTBackward", ADH_CLASSID, &ADH_FFTBackward));
  PetscCall(PetscLogEventRegister("AdhComplMult", ADH_CLASSID, &ADH_ComplianceMult));
  PetscCall(PetscLogEventRegister("AdhStepSolve", ADH_CLASSID, &ADH_Solve));
  PetscCall(PetscLogEventRegister("AdhSetUpdate", ADH_CLASSID, &ADH_SetUpdate));
  PetscCall(PetscLogEventRegister("AdhPredict", ADH_CLASSID, &ADH_Predict));
  PetscCall(PetscLogEventRegister("AdhDetachTest", ADH_CLASSID, &ADH_DetachTest));
  PetscCall(PetscLogEventRegister("AdhAttachLimits", ADH_CLASSID, &ADH_AttachLimits));
  PetscCall(PetscLogEventRegister("AdhLocalSolve", ADH_CLASSID, &ADH_LocalSolve));
  PetscCall(PetscRegisterFinalize(AdhFinalizePackage));
  PetscFunctionReturn(0);
}
