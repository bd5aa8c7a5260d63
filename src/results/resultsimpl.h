/* The results layer's functions: the results file (output.c) and the checkpoint (checkpoint.c). A
   path reaches them through AdhResultsOps (solver/solverimpl.h), bound in solverregis.c. */
#ifndef ADHBEM_RESULTSIMPL_H
#define ADHBEM_RESULTSIMPL_H
#include "solver/solverimpl.h"

PETSC_INTERN PetscErrorCode AdhOutputOpen_Private(AdhSolver, const char file[], PetscViewer *);
PETSC_INTERN PetscErrorCode AdhOutputResume_Private(AdhSolver, const char file[], PetscViewer *);
PETSC_INTERN PetscErrorCode AdhOutputAppend_Private(AdhSolver, PetscViewer);
PETSC_INTERN PetscErrorCode AdhOutputWriteFields_Private(AdhSolver, PetscViewer, PetscInt step);
PETSC_INTERN PetscErrorCode AdhOutputClose_Private(AdhSolver, const char file[], PetscViewer *);
PETSC_INTERN PetscErrorCode AdhOutputWriteCurve_Private(AdhSolver, PetscViewer);
PETSC_INTERN PetscErrorCode AdhOutputCheckWritable_Private(AdhSolver, const char option[], const char file[]);
PETSC_INTERN PetscErrorCode AdhCheckpointWrite_Private(AdhSolver, PetscInt leg, PetscInt step);
PETSC_INTERN PetscErrorCode AdhCheckpointRead_Private(AdhSolver, PetscInt *leg, PetscInt *step);
#endif
