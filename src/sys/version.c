/* adhbem's version, and the check that the PETSc it runs with is the one it was built against. */
#include <petsc/private/petscimpl.h> /* PetscValid* */
#include "sys/sysimpl.h"

/*@C
  AdhGetVersion - The version of adhbem and of the PETSc it runs with, as one line

  Not Collective

  Input Parameter:
. len - the length of `version`

  Output Parameter:
. version - "adhbem 0.1.0 (PETSc 3.18.5)"

  Level: beginner

  Note:
  The executable prints it with `--version` (or `-version`); `-adh_view` and every results file (its root
  attributes `adhbem_version` and `petsc_version`) carry it too.

.seealso: `AdhGetVersionNumber()`, `ADHBEM_VERSION`, `PetscGetVersion()`
@*/
PetscErrorCode AdhGetVersion(char version[], size_t len)
{
  char petsc[128];

  PetscFunctionBegin;
  PetscValidCharPointer(version, 1);
  PetscCall(AdhGetPETScVersion_Private(petsc, sizeof(petsc)));
  PetscCall(PetscSNPrintf(version, len, "adhbem %s (PETSc %s)", ADHBEM_VERSION, petsc));
  PetscFunctionReturn(0);
}

/*@C
  AdhGetVersionNumber - The version of adhbem as numbers

  Not Collective

  Output Parameters:
+ major - the major version (or `NULL`)
. minor - the minor version (or `NULL`)
- patch - the patch level (or `NULL`)

  Level: beginner

  Note:
  These are the numbers the library was built as; the macros `ADHBEM_VERSION_MAJOR`, `ADHBEM_VERSION_MINOR`,
  `ADHBEM_VERSION_PATCH` and `ADHBEM_VERSION_GE()` of adhbemversion.h give those of the header a program is compiled with.

.seealso: `AdhGetVersion()`
@*/
PetscErrorCode AdhGetVersionNumber(PetscInt *major, PetscInt *minor, PetscInt *patch)
{
  PetscFunctionBegin;
  if (major) *major = ADHBEM_VERSION_MAJOR;
  if (minor) *minor = ADHBEM_VERSION_MINOR;
  if (patch) *patch = ADHBEM_VERSION_PATCH;
  PetscFunctionReturn(0);
}

/* "3.18.5": the PETSc the process runs with (its library's numbers, not this file's headers). */
PetscErrorCode AdhGetPETScVersion_Private(char version[], size_t len)
{
  PetscInt major, minor, subminor, release;

  PetscFunctionBegin;
  PetscCall(PetscGetVersionNumber(&major, &minor, &subminor, &release));
  PetscCall(PetscSNPrintf(version, len, "%" PetscInt_FMT ".%" PetscInt_FMT ".%" PetscInt_FMT "%s", major, minor, subminor, release ? "" : " (development)"));
  PetscFunctionReturn(0);
}

/* PETSc changes its ABI between minor releases: a library built against 3.18 that finds 3.19 at run time
   (a PETSc built from source whose library name does not carry its version, first on LD_LIBRARY_PATH) would
   misread its structs; so would one that finds a PETSc of other indices (the 64-bit-index build under the same
   name). Checked once, when the package initialises, on every rank alike (the error is raised on
   PETSC_COMM_WORLD, so it is reported once). The scalar type is not checked: PETSC_SCALAR is this file's macro
   (PETSC_DOUBLE here), so the library could only confirm the size of a double; Debian's complex PETSc has
   a library name of its own. */
PetscErrorCode AdhCheckPETSc_Private(void)
{
  PetscInt major, minor;
  size_t   isize;

  PetscFunctionBegin;
  PetscCall(PetscGetVersionNumber(&major, &minor, NULL, NULL));
  PetscCheck(major == PETSC_VERSION_MAJOR && minor == PETSC_VERSION_MINOR, PETSC_COMM_WORLD, PETSC_ERR_LIB,
             "adhbem %s was built against PETSc %d.%d but runs with PETSc %" PetscInt_FMT ".%" PetscInt_FMT ": rebuild adhbem against this PETSc, or run it with the one it was built against",
             ADHBEM_VERSION, PETSC_VERSION_MAJOR, PETSC_VERSION_MINOR, major, minor);
  PetscCall(PetscDataTypeGetSize(PETSC_INT, &isize)); /* PETSC_INT is an enum value: the size is the library's */
  PetscCheck(isize == sizeof(PetscInt), PETSC_COMM_WORLD, PETSC_ERR_LIB, "adhbem %s was built against a PETSc with %d-bit indices but runs with one with %d-bit indices: rebuild adhbem against this PETSc, or run it with the one it was built against", ADHBEM_VERSION, (int)(8 * sizeof(PetscInt)), (int)(8 * isize));
  PetscFunctionReturn(0);
}
