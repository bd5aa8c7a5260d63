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

/*@
  AdhUseOneBLASThread - Sets OpenBLAS to one thread per rank, unless the environment chose a count

  Not Collective

  Notes:
  OpenBLAS is set to one thread unless OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS or OMP_NUM_THREADS is set; another BLAS is left as
  it is. What it did is reported through `PetscInfo()` (-info). OpenBLAS's functions are looked up at run time (an executable
  sees its libraries globally), so that another BLAS needs nothing.

  The ranks are the parallelism: OpenBLAS's threads, which spin between long vector updates, otherwise take CPU time and cores
  from the ranks. It is meant for an executable; a library must not change its host's threads, so the Python layer leaves this
  to the user (OPENBLAS_NUM_THREADS=1).

  Level: advanced

.seealso: `AdhInitializePackage()`
@*/
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
