/* Indenter profiles (indenter.c). */
#ifndef ADHBEM_INDENTER_H
#define ADHBEM_INDENTER_H
#include "grid/gridimpl.h"

typedef enum { ADH_INDENTER_SPHERE, ADH_INDENTER_PUNCH, ADH_INDENTER_CONE, ADH_INDENTER_FILE, ADH_INDENTER_ROUGH, ADH_INDENTER_ARRAY } AdhIndenterType;
PETSC_EXTERN const char *const AdhIndenterTypes[];

typedef struct {
  AdhIndenterType type;
  PetscReal       radius;       /* sphere */
  PetscReal       punch_radius; /* punch */
  PetscReal       cone_slope;   /* cone */
  char            topography[PETSC_MAX_PATH_LEN]; /* file */
  char            dataset[256];
  AdhSurface      surface;      /* rough: the random surface's parameters and realised statistics */
  AdhTopographyKind kind;       /* file and array: height z or gap h */
  Vec             z;            /* array: the user's topography (a reference) */
} AdhIndenter;

PETSC_EXTERN PetscErrorCode AdhIndenterSetFromOptions(AdhGrid, const char[], AdhIndenter *);
/* The profile h on the grid; a rough indenter's surface is generated here (its statistics are
   recorded in the indenter). */
PETSC_EXTERN PetscErrorCode AdhIndenterFill(AdhGrid, AdhIndenter *, Vec h);
#endif
