/* The two solids' elastic constants as the options give them (material.c): the reduced modulus
   alone (-adh_E_star), or each solid's Young's modulus and Poisson ratio. A half-space needs E*
   only; a layer needs its own E and nu (solver/impls/elastic/). */
#ifndef ADHBEM_MATERIAL_H
#define ADHBEM_MATERIAL_H
#include "adhbem.h"

typedef struct {
  PetscReal Estar;    /* 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, however given */
  PetscReal E1, nu1;  /* body 1 (the substrate or layer) */
  PetscReal E2, nu2;  /* body 2 (the indenter; E2 infinite: rigid) */
  PetscBool solids;   /* E1 (and so nu1, E2, nu2) were given; else E* alone */
  PetscBool nu1_set;  /* -adh_nu1 was given (a layer's stiffness depends on it beyond E*) */
} AdhMaterial;

PETSC_INTERN PetscErrorCode AdhMaterialSetFromOptions_Private(MPI_Comm, const char prefix[], AdhMaterial *);
#endif
