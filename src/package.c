/* Package registration: class id, log events, FFTW-MPI initialisation and one BLAS thread per
   rank, done once. */
#define _GNU_SOURCE /* RTLD_DEFAULT */
#include <dlfcn.h>
#include <stdlib.h>
#include <fftw3-mpi.h>
#include "solverimpl.h"

PetscClassId  ADH_CLASSID;
PetscLogEvent ADH_FFTForward, ADH_FFTBackward, ADH_ComplianceMult, ADH_Solve, ADH_SetUpdate, ADH_Predict;

static PetscBool AdhPackageInitialized = PETSC_FALSE;

static PetscErrorCode AdhFinalizePackage(void)
{
  PetscFunctionBegin;
  fftw_mpi_cleanup();
  PetscCall(AdhControlDestroyList_Private());
  PetscCall(AdhCriterionDestroyList_Private());
  PetscCall(AdhPredictorDestroyList_Private());
  AdhPackageInitialized = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The ranks are the parallelism: one BLAS thread each. OpenBLAS (Debian's default BLAS, behind
   PETSc's vector operations) otherwise splits long vector updates over a pool of threads that
   spin in sched_yield between them: on one rank of the JKR curve at 256^2 they doubled the CPU
   time (2.2 s of it in the kernel) and cost 15% of the wall time, and on a node whose cores all
   run ranks they compete with the ranks. A thread count the user set is left as it is. Found at
   run time, so that another BLAS needs nothing. */
static void OneBLASThread(void)
{
  /* the executable sees every library; a Python extension's libraries are not global, so the
     BLAS is also looked up by the names Debian's OpenBLAS is loaded under */
  const char *const names[] = {"libblas.so.3", "libopenblas.so.0"};
  void (*set_threads)(int);

  if (getenv("OPENBLAS_NUM_THREADS") || getenv("GOTO_NUM_THREADS") || getenv("OMP_NUM_THREADS")) return;
  *(void **)&set_threads = dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
  for (size_t k = 0; !set_threads && k < sizeof(names) / sizeof(names[0]); k++) {
    void *lib = dlopen(names[k], RTLD_LAZY | RTLD_NOLOAD);
    if (!lib) continue;
    *(void **)&set_threads = dlsym(lib, "openblas_set_num_threads");
    dlclose(lib);
  }
  if (set_threads) set_threads(1);
}

PetscErrorCode AdhInitializePackage(void)
{
  PetscFunctionBegin;
  if (AdhPackageInitialized) PetscFunctionReturn(0);
  AdhPackageInitialized = PETSC_TRUE;
  fftw_mpi_init();
  OneBLASThread();
  PetscCall(PetscClassIdRegister("Adhesive BEM", &ADH_CLASSID));
  PetscCall(PetscLogEventRegister("AdhFFTForward", ADH_CLASSID, &ADH_FFTForward));
  PetscCall(PetscLogEventRegister("AdhFFTBackward", ADH_CLASSID, &ADH_FFTBackward));
  PetscCall(PetscLogEventRegister("AdhComplMult", ADH_CLASSID, &ADH_ComplianceMult));
  PetscCall(PetscLogEventRegister("AdhStepSolve", ADH_CLASSID, &ADH_Solve));
  PetscCall(PetscLogEventRegister("AdhSetUpdate", ADH_CLASSID, &ADH_SetUpdate));
  PetscCall(PetscLogEventRegister("AdhPredict", ADH_CLASSID, &ADH_Predict));
  PetscCall(PetscRegisterFinalize(AdhFinalizePackage));
  PetscFunctionReturn(0);
}
