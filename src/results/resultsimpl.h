/* The results layer's functions: the results file (output.c) and the checkpoint (checkpoint.c). A
   path reaches them through AdhResultsOps (solver/solverimpl.h), bound in solver/interface/solverpackage.c. */
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

/* An HDF5 call that fails (a negative return) becomes a PETSc error naming it. */
#define ADH_H5(call) \
  do { \
    PetscCheck((call) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5: %s failed", #call); \
  } while (0)

/* files.c: names, writable paths, text files */
PETSC_INTERN PetscErrorCode AdhOutputPartName_Private(const char file[], char part[], size_t len);
PETSC_INTERN PetscErrorCode AdhOutputSiblingName_Private(const char file[], const char ext[], char name[], size_t len);
PETSC_INTERN PetscErrorCode AdhOutputWriteTextFile_Private(AdhSolver s, const char name[], void (*body)(AdhSolver, const char h5[], FILE *), const char h5[]);

/* diskspace.c: space reserved before a write, and a write that fails told once */
PETSC_INTERN PetscErrorCode AdhOutputReserve_Private(AdhSolver s, const char part[], size_t bytes, int *err);
PETSC_INTERN PetscErrorCode AdhOutputReleaseReserve_Private(AdhSolver s, const char part[]);
PETSC_INTERN PetscErrorCode AdhOutputWriteBegin_Private(AdhSolver s, const char option[], const char part[], const char kept[], PetscBool discard);
PETSC_INTERN PetscErrorCode AdhOutputWriteEnd_Private(AdhSolver s, PetscErrorCode ierr);
PETSC_INTERN PetscErrorCode AdhOutputKept_Private(AdhSolver s, const char part[], char kept[], size_t len);
PETSC_INTERN PetscErrorCode AdhOutputRemove_Private(AdhSolver s, const char name[]);
PETSC_INTERN PetscErrorCode AdhOutputAbandon_Private(PetscViewer *v);

/* hdf5.c: raw HDF5 */
PETSC_INTERN PetscErrorCode AdhH5OpenExtendible_Private(hid_t group, const char name[], hid_t type, int rank, const hsize_t dims[], const hsize_t chunk[], hid_t *dset);
PETSC_INTERN PetscErrorCode AdhH5Agree_Private(AdhSolver s, PetscErrorCode ierr);
PETSC_INTERN PetscErrorCode AdhH5AgreeOnFailure_Private(AdhSolver s, PetscBool failed, PetscBool *any);
PETSC_INTERN void           AdhH5Cause_Private(char cause[256]);
PETSC_INTERN PetscErrorCode AdhH5WriteBlock_Private(hid_t dset, hid_t type, int rank, const hsize_t offset[], const hsize_t count[], const void *buf);
PETSC_INTERN PetscErrorCode AdhH5WriteStringAttribute_Private(PetscViewer v, const char name[], const char value[]);
PETSC_INTERN PetscErrorCode AdhH5WriteRealArrayAttribute_Private(PetscViewer v, const char name[], PetscInt n, const PetscReal *values);
PETSC_INTERN PetscErrorCode AdhH5AppendRows_Private(AdhSolver s, hid_t group, const char name[], PetscBool integer, PetscInt from, PetscInt count, const PetscReal *values);
PETSC_INTERN PetscErrorCode AdhH5WriteRealArray_Private(AdhSolver s, PetscViewer viewer, const char name[], PetscInt n, const PetscReal *values);

/* attributes.c: the root attributes */
PETSC_INTERN PetscErrorCode AdhOutputWriteSurface_Private(AdhSolver s, PetscViewer v);
PETSC_INTERN PetscErrorCode AdhOutputWriteArrayTopography_Private(AdhSolver s, PetscViewer v);
PETSC_INTERN PetscErrorCode AdhOutputWritePullOff_Private(AdhSolver s, PetscViewer v, PetscInt k);
PETSC_INTERN PetscErrorCode AdhOutputWriteAttributes_Private(AdhSolver s, PetscViewer v);

/* columns.c: the curve's columns */
PETSC_INTERN PetscReal AdhOutputColumnValue_Private(AdhSolver s, const AdhState *st, PetscInt j);
PETSC_INTERN PetscInt AdhOutputNumColumns_Private(AdhSolver s);
PETSC_INTERN PetscBool AdhOutputColumnIsCount_Private(PetscInt j);
PETSC_INTERN const char *AdhOutputColumnName_Private(PetscInt j);

/* journal.c: the CSV journal */
PETSC_INTERN PetscErrorCode AdhJournalWrite_Private(AdhSolver s, PetscInt from, PetscInt to);
PETSC_INTERN PetscErrorCode AdhJournalOpen_Private(AdhSolver s, const char file[]);
PETSC_INTERN PetscErrorCode AdhJournalClose_Private(AdhSolver s, const char file[]);

/* xdmf.c: the XDMF file */
PETSC_INTERN void AdhOutputXDMFBody_Private(AdhSolver s, const char h5[], FILE *fp);

/* output.c: the results file */
PETSC_INTERN PetscErrorCode AdhOutputBegin_Private(AdhSolver s, PetscViewer v, const char file[]);
#endif
