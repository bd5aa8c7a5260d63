/* Indenter profiles (indenter.c): the geometry layer's private header, read by the solver and the results layer. */
#ifndef ADHBEM_INDENTER_H
#define ADHBEM_INDENTER_H
#include "grid/gridimpl.h"

typedef enum { ADH_INDENTER_SPHERE, ADH_INDENTER_PUNCH, ADH_INDENTER_CONE, ADH_INDENTER_FILE, ADH_INDENTER_ROUGH, ADH_INDENTER_ARRAY } AdhIndenterType;
PETSC_INTERN const char *const AdhIndenterTypes[];

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

PETSC_INTERN PetscErrorCode AdhIndenterSetFromOptions_Private(AdhGrid, const char[], AdhIndenter *);
/* The profile h on the grid; a rough indenter's surface is generated here (its statistics are
   recorded in the indenter). */
PETSC_INTERN PetscErrorCode AdhIndenterFill_Private(AdhGrid, AdhIndenter *, Vec h);
#endif
