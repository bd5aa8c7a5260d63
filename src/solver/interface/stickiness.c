/* Whether a rough surface will stick, said before the run: three criteria from its heights, the
   modulus, the work of adhesion and (for a finite-range criterion) the range of the attraction.

   - Persson & Tosatti (J. Chem. Phys. 115, 5597, 2001): full contact pays the elastic energy U_el
     that flattens the surface and gains the work of adhesion dgamma A0. The ratio
     U_el / (dgamma A0) below 1: full contact is the state of least energy at zero load, the surface
     sticks everywhere once in contact, and a compressive mean pressure is reached only in full
     contact. On a periodic cell U_el / A0 = (1/2) <h S h> exactly, S the body's stiffness (E*|q|/2 on a half-space); a
     free-boundary map is taken as one cell, its mean plane removed.
   - Pastewka & Robbins (PNAS 111, 3298, 2014, eq. 10, with kappa_rep = 2 and
     d_rep = 4 h'_rms / h''_rms): the surfaces are sticky (a finite force pulls them apart) when
     h'_rms E* Delta r / (2 dgamma) (h'_rms^2 / (h''_rms Delta r))^(2/3) < 1, Delta r the range of
     the attraction; derived for short but finite ranges, from the DMT side. The same form as the
     Adhesion package's rough example.
   - The generalised Tabor parameter (Müser's single-asperity Tabor parameter, Beilstein J.
     Nanotechnol. 5, 419, 2014, with the Adhesion package's R = 1/h''_rms for a rough surface):
     mu_T = (R dgamma^2 / (E*^2 Delta r^3))^(1/3); above about 1 the smallest asperities'
     contacts are JKR-like, below DMT-like.

   h'_rms is the rms of |grad h| and h''_rms the rms of the mean curvature, half the Laplacian (the
   conventions of SurfaceTopography, with which the Adhesion package evaluates the same criteria);
   roughness.c computes them and U_el, on a periodic cell and on a free-boundary map. A
   zero-range criterion (crack closure, Pohrt-Popov) has no Delta r: only the first is given. */
#include "solver/solverimpl.h"

PetscErrorCode AdhSolverEstimateStickiness_Private(AdhSolver s)
{
  AdhStickiness        *st   = &s->stickiness;
  const AdhIndenterType type = s->indenter.type;
  const PetscReal       N    = (PetscReal)s->grid->Nx * (PetscReal)s->grid->Ny;
  PetscReal             dgamma = s->gamma;

  PetscFunctionBegin;
  PetscCall(PetscMemzero(st, sizeof(*st)));
  if (!(type == ADH_INDENTER_ROUGH || type == ADH_INDENTER_FILE || type == ADH_INDENTER_ARRAY) || s->sigma_fixed > 0) PetscFunctionReturn(0);
  if (s->gamma_field) { /* the energy balance is over the cell: the mean work of adhesion */
    PetscScalar sum;
    PetscCall(VecSum(s->gamma_field, &sum));
    dgamma = PetscRealPart(sum) / N;
  }
  if (!(dgamma > 0)) PetscFunctionReturn(0);
  st->rms_slope           = s->rms_slope; /* the profile's (roughness.c) */
  st->rms_curvature       = s->rms_curvature;
  st->full_contact_energy = s->full_contact_energy;
  st->work_of_adhesion = dgamma;
  if (!(st->full_contact_energy > 0) || !(st->rms_curvature > 0)) { /* a flat cell */
    PetscCall(PetscMemzero(st, sizeof(*st)));
    PetscFunctionReturn(0);
  }
  st->estimated         = PETSC_TRUE;
  st->persson_tosatti   = st->full_contact_energy / dgamma;
  st->sticks_everywhere = (PetscBool)(st->persson_tosatti < 1);
  if (s->crops.range) {
    /* the body's modulus at the roughness's wave number h''_rms/h'_rms (E* on a half-space) */
    const PetscReal dr = s->crops.range(s, dgamma), h1 = st->rms_slope, E = s->eops.modulus(s, st->rms_curvature / h1);
    st->range            = dr;
    st->pastewka_robbins = h1 * E * dr / (2.0 * dgamma) * PetscPowReal(h1 * h1 / (st->rms_curvature * dr), 2.0 / 3.0);
    st->tabor            = PetscCbrtReal(dgamma * dgamma / (st->rms_curvature * E * E * dr * dr * dr));
  }
  st->sticky = (PetscBool)(st->sticks_everywhere || (st->pastewka_robbins > 0 && st->pastewka_robbins < 1));
  PetscFunctionReturn(0);
}

/*@
  AdhSolverGetStickiness - Tells whether a rough surface is sticky, estimated at set-up from its heights

  Not Collective

  Input Parameter:
. s - the solver, set up

  Output Parameter:
. st - the estimate: the surface's rms slope and curvature, the elastic energy per area of full contact, and the
       criteria of Persson-Tosatti, Pastewka-Robbins and the generalised Tabor parameter

  Level: intermediate

  Notes:
  Made for a rough surface, a topography file or an array with adhesion (st->estimated), on either boundary; with a
  dgamma field its mean counts. On the free boundary the slope is from forward differences and the curvature from
  second differences (as SurfaceTopography takes them for a map), and U_el is that of the map with its mean plane removed taken as one periodic cell. The criteria:

  Persson and Tosatti (2001): st->persson_tosatti = U_el / (dgamma A0), U_el the elastic energy that flattens the
  surface (full contact), exact on a periodic cell. Below 1 full contact is the state of least energy at zero load:
  once in contact the surface sticks everywhere, and a compressive mean pressure is reached only in full contact.

  Pastewka and Robbins (2014, eq. 10, kappa_rep = 2, d_rep = 4 h'_rms/h''_rms): st->pastewka_robbins =
  h'_rms E* Delta r / (2 dgamma) (h'_rms^2 / (h''_rms Delta r))^(2/3), below 1 sticky (a finite force pulls the surfaces
  apart). Delta r is the criterion's range (`ADHCRITERIONDUGDALE`: dgamma/s0; `ADHCRITERIONEXPONENTIAL`: rho); the
  zero-range criteria have none, and it is 0.

  The generalised Tabor parameter: st->tabor = (R dgamma^2 / (E*^2 Delta r^3))^(1/3) with R = 1/h''_rms (0 without a
  range): above about 1 the smallest asperities' contacts are JKR-like.

  h''_rms is the rms of the mean curvature, half the Laplacian of h.

.seealso: `AdhSolverStickinessView()`, `AdhSolverGetResolution()`
@*/
PetscErrorCode AdhSolverGetStickiness(AdhSolver s, AdhStickiness *st)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(st, 2);
  *st = s->stickiness;
  PetscFunctionReturn(0);
}

/*@
  AdhSolverStickinessView - Prints the line on a rough surface's stickiness

  Collective

  Input Parameters:
+ s      - the solver, set up
- viewer - an ASCII viewer, or `NULL` for standard output on the solver's communicator

  Level: intermediate

  Note:
  One line, `adhbem: stickiness: ...`, with the criteria of `AdhSolverGetStickiness()` and the verdict: sticks
  everywhere (Persson-Tosatti below 1), sticky (Pastewka-Robbins below 1), not sticky (Pastewka-Robbins 1 or more), or,
  with a zero-range criterion and Persson-Tosatti 1 or more, partial contact whose stickiness the run tells. Nothing
  without an estimate. The adhbem executable prints it before the path.

.seealso: `AdhSolverGetStickiness()`, `AdhSolverResolutionView()`
@*/
PetscErrorCode AdhSolverStickinessView(AdhSolver s, PetscViewer viewer)
{
  const AdhStickiness *st = &s->stickiness;
  char                 more[160] = "";
  const char          *verdict;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  if (!st->estimated) PetscFunctionReturn(0);
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(s->comm, &viewer));
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  if (st->range > 0) PetscCall(PetscSNPrintf(more, sizeof(more), ", Pastewka-Robbins %.3g, generalised Tabor %.3g", (double)st->pastewka_robbins, (double)st->tabor));
  if (st->sticks_everywhere) verdict = "sticks everywhere: flattening it costs less elastic energy than the adhesion gives, so once in contact it goes to full contact, and a compressive mean pressure is reached only in full contact (less adhesion, a stiffer solid or more roughness make a partial contact)";
  else if (st->range > 0 && st->sticky) verdict = "sticky: a finite force pulls it off, and a compressive mean pressure is reached in partial contact";
  else if (st->range > 0) verdict = "not sticky: the contact grows with the load as without adhesion, and the pull-off force is small";
  else verdict = "partial contact (a zero-range criterion: whether it is sticky the run tells; Pastewka-Robbins needs a range, -adh_criterion dugdale or exponential)";
  PetscCall(PetscViewerASCIIPrintf(viewer, "adhbem: stickiness: Persson-Tosatti U_el/(dgamma A) = %.3g%s: %s\n", (double)st->persson_tosatti, more, verdict));
  PetscFunctionReturn(0);
}
