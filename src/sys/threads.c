/* One BLAS thread per rank for the executable: the ranks are the parallelism. OpenBLAS (Debian's
   default BLAS, behind PETSc's vector operations) otherwise splits long vector updates over a pool
   of threads that spin in sched_yield between them: on one rank of the JKR curve at 256^2 they
   doubled the CPU time (2.2 s of it in the kernel), and on a node whose cores all run ranks they
   take cores from the ranks. A library must not change its host's threads, so the Python layer
   leaves this to the user (OPENBLAS_NUM_THREADS=1, as ./run sets). */
#define _GNU_SOURCE /* RTLD_DEFAULT, before any system header */
#include <dlfcn.h>
#include <stdlib.h>
#include "adhbem.h"

/* Sets OpenBLAS to one thread unless OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS or OMP_NUM_THREADS
   chose a count; says what it did under -info. OpenBLAS's functions are found at run time (the
   executable sees its libraries globally), so that another BLAS needs nothing. */
PetscErrorCode AdhUseOneBLASThread(void)
{
  void (*set_threads)(int);
  int (*get_threads)(void);

  PetscFunctionBegin;
  *(void **)&set_threads = dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
  *(void **)&get_threads = dlsym(RTLD_DEFAULT, "openblas_get_num_threads");
  if (!set_threads || !get_threads) {
    PetscCall(PetscInfo(NULL, "BLAS threads: not OpenBLAS, left as they are\n"));
  } else if (getenv("OPENBLAS_NUM_THREADS") || getenv("GOTO_NUM_THREADS") || getenv("OMP_NUM_THREADS")) {
    PetscCall(PetscInfo(NULL, "BLAS threads: %d, as the environment sets\n", get_threads()));
  } else {
    const int had = get_threads();
    set_threads(1);
    PetscCall(PetscInfo(NULL, "BLAS threads: OpenBLAS set to 1 per rank (it started %d)\n", had));
  }
  PetscFunctionReturn(0);
}
