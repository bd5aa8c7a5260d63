/* How well the grid resolves the adhesion, told to the user: at set-up an estimate of the JKR
   contact radius of the smallest asperities in grid spacings, and at the end of a run the share of
   the tension at pull-off carried by contact patches too small to be resolved (statistics.c
   measures it per state).

   The estimate: a summit of tip radius R with work of adhesion dgamma has the JKR contact radius
   a_c = (9 pi dgamma R^2 / (8 E*))^(1/3) at pull-off, and a detachment criterion converges with
   the grid only where a_c spans many elements. For rough surfaces and topographies R is the mean
   summit radius of a Gaussian isotropic surface (Nayak 1971, wide band): its mean summit
   curvature is sqrt(8 / (3 pi)) times the rms of the Laplacian of h (roughness.c: spectral on a
   periodic cell, finite differences on a free-boundary map). A sphere has one radius, on either
   boundary. With a dgamma field the weakest adhesion present
   counts (the smallest a_c). */
#include "solver/solverimpl.h"

PetscErrorCode AdhSolverEstimateResolution_Private(AdhSolver s)
{
  PetscReal          dgamma = s->gamma, R = 0.0, h = PetscMin(s->grid->hx, s->grid->hy);
  const AdhIndenterType type = s->indenter.type;

  PetscFunctionBegin;
  s->asperity_ac    = 0.0;
  s->asperity_tabor = 0.0;
  if (s->gamma_field) { /* the weakest adhesion present: the smallest a_c, the safe side */
    const PetscScalar *ga;
    PetscInt           n;
    dgamma = PETSC_MAX_REAL;
    PetscCall(VecGetLocalSize(s->gamma_field, &n));
    PetscCall(VecGetArrayRead(s->gamma_field, &ga));
    for (PetscInt k = 0; k < n; k++)
      if (PetscRealPart(ga[k]) > 0) dgamma = PetscMin(dgamma, PetscRealPart(ga[k]));
    PetscCall(VecRestoreArrayRead(s->gamma_field, &ga));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &dgamma, 1, MPIU_REAL, MPIU_MIN, s->comm));
    if (dgamma == PETSC_MAX_REAL) dgamma = 0.0;
  }
  if (!(dgamma > 0) || s->sigma_fixed > 0) PetscFunctionReturn(0);
  if (type == ADH_INDENTER_SPHERE) R = s->indenter.radius;
  else if (s->rms_curvature > 0) R = 1.0 / (PetscSqrtReal(8.0 / (3.0 * PETSC_PI)) * 2.0 * s->rms_curvature); /* the profile's (roughness.c); the Laplacian is twice the mean curvature */
  if (R > 0) s->asperity_ac = PetscPowReal(9.0 * PETSC_PI * dgamma * R * R / (8.0 * AdhSolverSummitModulus_Private(s, R, dgamma)), 1.0 / 3.0) / h;
  if (R > 0 && s->crops.tabor) s->asperity_tabor = s->crops.tabor(s, R, dgamma);
  PetscFunctionReturn(0);
}

/*@
  AdhCurveGetPullOffState - Finds the recorded state carrying the largest tension: the pull-off force

  Not Collective

  Input Parameter:
. c - the curve, from `AdhSolverGetCurve()`

  Output Parameter:
. state - the row of the state with the most negative force (the first of equal ones), or -1 if no state carried
          tension

  Level: intermediate

  Note:
  The pull-off force is then -c->state[state].force.

.seealso: `AdhSolverGetCurve()`, `AdhSolverGetResolution()`, `AdhSolverIsPulledOff()`
@*/
PetscErrorCode AdhCurveGetPullOffState(const AdhCurve *c, PetscInt *state)
{
  PetscFunctionBegin;
  PetscValidPointer(c, 1);
  PetscValidIntPointer(state, 2);
  *state = -1;
  for (PetscInt k = 0; k < c->n; k++)
    if (c->state[k].force < 0 && (*state < 0 || c->state[k].force < c->state[*state].force)) *state = k;
  PetscFunctionReturn(0);
}

/* Resolved: at most this share of the tension at pull-off sits in patches smaller than
   ADH_RESOLVED_PATCH points, and the smallest asperities' JKR radius spans at least
   ADH_RESOLVED_RADIUS elements. */
#define ADH_RESOLVED_SHARE  0.1
#define ADH_RESOLVED_RADIUS 10
/* A cohesive zone narrower than this many grid spacings: the pull-off force depends on the grid
   (measured on Maugis' sphere at lambda 1: by dugdale's fixed point first order, about 0.4 / width
   relative, 4% at 10; by the minimisation 2% at 3 and 0.33% at 6). */
#define ADH_RESOLVED_ZONE 10

/* Why the grid does not resolve the adhesion at state st (ADH_UNRESOLVED_* flags; 0: it does): the
   patches that carry the tension must be large (a zero-range criterion's: the stress at their edge
   is singular; a finite-range criterion's edge is not, its zone carries the tension and must be
   wide), and so must the smallest asperities' contacts. The one rule of every verdict (line,
   results file, Python). */
PetscInt AdhSolverUnresolved_Private(AdhSolver s, const AdhState *st)
{
  const PetscReal width = AdhSolverCohesiveWidth_Private(s, st);
  PetscInt        why   = 0;
  if (!s->crops.cohesive && st->small_patch_tension > ADH_RESOLVED_SHARE) why |= ADH_UNRESOLVED_PATCHES;
  if (s->asperity_ac > 0 && s->asperity_ac < ADH_RESOLVED_RADIUS) why |= ADH_UNRESOLVED_ASPERITIES;
  if (width > 0 && width < ADH_RESOLVED_ZONE) why |= ADH_UNRESOLVED_ZONE;
  /* a finite-range criterion pulling with no zone on the grid: narrower than an element */
  if (s->crops.cohesive && st->force < 0 && !(st->cohesive_area > 0) && st->contact_points > 0) why |= ADH_UNRESOLVED_ZONE;
  return why;
}

PetscBool AdhSolverResolves_Private(AdhSolver s, const AdhState *st)
{
  return (PetscBool)!AdhSolverUnresolved_Private(s, st);
}

/* The reasons in flags why, as words, joined by "; " ("" for none). */
PetscErrorCode AdhSolverUnresolvedWords_Private(AdhSolver s, const AdhState *st, PetscInt why, char words[], size_t len)
{
  char part[160];

  PetscFunctionBegin;
  words[0] = 0;
  if (why & ADH_UNRESOLVED_PATCHES) {
    PetscCall(PetscSNPrintf(part, sizeof(part), "%.3g%% of the tension on patches of fewer than %d elements, over %g%%", 100.0 * (double)st->small_patch_tension, ADH_RESOLVED_PATCH, 100.0 * ADH_RESOLVED_SHARE));
    PetscCall(PetscStrlcat(words, part, len));
  }
  if (why & ADH_UNRESOLVED_ASPERITIES) {
    PetscCall(PetscSNPrintf(part, sizeof(part), "%sthe JKR contact radius of %s, %.3g grid spacings, under %d", words[0] ? "; " : "", s->indenter.type == ADH_INDENTER_SPHERE ? "the sphere" : "the smallest asperities", (double)s->asperity_ac, ADH_RESOLVED_RADIUS));
    PetscCall(PetscStrlcat(words, part, len));
  }
  if ((why & ADH_UNRESOLVED_ZONE) && !(st->cohesive_area > 0)) {
    PetscCall(PetscSNPrintf(part, sizeof(part), "%sthe cohesive zone narrower than an element (no point within its range)", words[0] ? "; " : ""));
    PetscCall(PetscStrlcat(words, part, len));
  } else if (why & ADH_UNRESOLVED_ZONE) {
    PetscCall(PetscSNPrintf(part, sizeof(part), "%sthe cohesive zone, %.3g grid spacings wide, under %d", words[0] ? "; " : "", (double)AdhSolverCohesiveWidth_Private(s, st), ADH_RESOLVED_ZONE));
    PetscCall(PetscStrlcat(words, part, len));
  }
  PetscFunctionReturn(0);
}

/* The cohesive zone's width at state st in grid spacings (0: no zone). A sphere's is the width of
   the annulus around the contact's disk; on any other profile (a rough surface's many patches) the
   zone's area over the mean of its inner and outer edges' lengths, the mean width of a band along
   the contact's edge (exact for an annulus, pi (b^2 - a^2) = (b - a) (2 pi a + 2 pi b) / 2). */
PetscReal AdhSolverCohesiveWidth_Private(AdhSolver s, const AdhState *st)
{
  const PetscReal h = PetscMin(s->grid->hx, s->grid->hy);
  if (!(st->cohesive_area > 0)) return 0.0;
  if (s->indenter.type == ADH_INDENTER_SPHERE) return (PetscSqrtReal((st->area + st->cohesive_area) / PETSC_PI) - PetscSqrtReal(st->area / PETSC_PI)) / h;
  return st->contact_perimeter + st->cohesive_perimeter > 0 ? 2.0 * st->cohesive_area / (st->contact_perimeter + st->cohesive_perimeter) / h : 0.0;
}

/*@
  AdhSolverGetResolution - Tells how well the grid resolves the adhesion

  Not Collective

  Input Parameter:
. s - the solver

  Output Parameter:
. r - the set-up estimate of the JKR contact radius of the smallest asperities (or of the sphere) in grid spacings;
      whether some recorded state had points in contact; the curve's state of the largest tension, with its force,
      the share of its tension carried by contact patches too small to be resolved and its smallest patch carrying a
      net tension; and the verdict

  Level: intermediate

  Notes:
  The estimate: a summit of tip radius R with work of adhesion dgamma has the JKR contact radius
  a_c = (9 pi dgamma R^2 / (8 E*))^(1/3) at pull-off, and a detachment criterion converges with the grid only where
  a_c spans many elements. R is the sphere's radius on either boundary; for a rough surface or a topography, on either
  boundary, it is the mean summit radius of a Gaussian isotropic surface (Nayak 1971), from the rms of the
  Laplacian of h. With a dgamma field the weakest adhesion present counts (the smallest a_c). It is 0, no estimate,
  without adhesion, with -adh_critical_stress, and for other profiles. It is made at set-up and whenever the profile
  or the dgamma field changes.

  The verdict r->resolved, meaningful when r->state >= 0: with a zero-range criterion at most 10% of the tension at the
  largest tension is carried by patches of fewer than `ADH_RESOLVED_PATCH` points; the estimate, if there is one, is
  at least 10 grid spacings; and a finite-range criterion's cohesive zone, if there is one, is at least 10 grid
  spacings wide (by the fixed point a sphere's pull-off force converges at first order, about 0.4/width relative). A
  finite-range criterion's small patches are not a reason: their edges are not singular, and the zone around them
  carries the tension. r->cohesive_elements gives the elements the zone covers
  at that state and r->cohesive_width its width: a sphere's annulus, or on any other profile the zone's area over the
  mean of its inner and outer edges (the state's contact_perimeter and cohesive_perimeter). Computed from the curve, so the same on every rank.

  r->apart is the first state where the surfaces came apart (a leg ended in pull-off); only then is the largest tension
  the pull-off force. Without it (-1) the path ended in contact, r->last_points of them, or in full contact,
  r->full_contact the first state with every grid point in the contact set. r->stopped is the state at which a pull-off
  ended a path with legs left (`AdhSolverSetStopAtPullOff()`), -1 otherwise.

.seealso: `AdhSolverResolutionView()`, `AdhCurveGetPullOffState()`, `AdhSolverGetCurve()`, `AdhSolverComputeState()`
@*/
PetscErrorCode AdhSolverGetResolution(AdhSolver s, AdhResolution *r)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  PetscValidPointer(r, 2);
  PetscCall(PetscMemzero(r, sizeof(*r)));
  r->asperity_contact_radius = s->asperity_ac;
  r->asperity_tabor          = s->asperity_tabor;
  for (PetscInt k = 0; k < s->curve.n; k++)
    if (s->curve.state[k].contact_points > 0) r->touched = PETSC_TRUE;
  PetscCall(AdhCurveGetPullOffState(&s->curve, &r->state));
  if (r->state >= 0) {
    const AdhState *st        = &s->curve.state[r->state];
    r->force                  = st->force;
    r->small_patch_tension    = st->small_patch_tension;
    r->smallest_tensile_patch = st->smallest_tensile_patch;
    r->unresolved             = AdhSolverUnresolved_Private(s, st);
    r->resolved               = (PetscBool)!r->unresolved;
    r->cohesive_elements      = st->cohesive_area / (s->grid->hx * s->grid->hy); /* a finite-range criterion's zone */
    r->cohesive_width         = AdhSolverCohesiveWidth_Private(s, st);
  }
  r->apart        = -1;
  r->full_contact = -1;
  for (PetscInt k = 0; k < s->curve.n; k++) {
    if (s->curve.state[k].pulled_off && r->apart < 0) r->apart = k;
    if (s->curve.state[k].contact_points == s->grid->Nx * s->grid->Ny && r->full_contact < 0) r->full_contact = k;
  }
  r->last_points = s->curve.n ? s->curve.state[s->curve.n - 1].contact_points : 0;
  r->stopped     = s->path_stopped;
  PetscFunctionReturn(0);
}


/*@
  AdhSolverResolutionView - Prints how well the grid resolves the adhesion

  Collective

  Input Parameters:
+ s      - the solver
- viewer - an ASCII viewer, or `NULL` for standard output on the solver's communicator

  Level: intermediate

  Notes:
  One line gives the estimate of `AdhSolverGetResolution()` when there is one, with a warning below 10 grid spacings
  that the pull-off force depends on the grid. When a recorded state carried tension a second line follows on the state
  of the largest tension: with a zero-range criterion the share of its tension in patches of fewer than
  `ADH_RESOLVED_PATCH` elements, its smallest patch with a net tension, and the verdict; before it, with a finite-range
  criterion (whose line leaves the share out: its zone decides), a line on the cohesive zone there (how many grid
  spacings wide it is, with a warning below 10, and the elements it covers). Nothing
  is printed when the curve has states and none touched (the path
  has warned that it never touches).

  When a pull-off ended the path with legs left (`AdhSolverSetStopAtPullOff()`), a line says so first.

  The adhbem executable prints it at the end of a run.

.seealso: `AdhSolverGetResolution()`, `AdhSolverView()`, `AdhSolverSolvePath()`
@*/
PetscErrorCode AdhSolverResolutionView(AdhSolver s, PetscViewer viewer)
{
  AdhResolution r;
  char          smallest[96], why[512], verdict[640];

  PetscFunctionBegin;
  PetscValidHeaderSpecific(s, ADH_CLASSID, 1);
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(s->comm, &viewer));
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  PetscCall(AdhSolverGetResolution(s, &r));
  if (s->curve.n && !r.touched) PetscFunctionReturn(0); /* nothing to resolve (the path warned that it never touches) */
  if (r.stopped >= 0) PetscCall(PetscViewerASCIIPrintf(viewer, "adhbem: path: stopped where the surfaces came apart (state %" PetscInt_FMT ", d = %g), with legs left: -adh_stop_at_pulloff false runs them\n", r.stopped, (double)s->curve.state[r.stopped].d));
  if (r.asperity_contact_radius > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "adhbem: resolution: JKR contact radius at pull-off of %s: about %.3g grid spacings%s\n", s->indenter.type == ADH_INDENTER_SPHERE ? "the sphere" : "the smallest asperities (from the surface's mean summit curvature)", (double)r.asperity_contact_radius, r.asperity_contact_radius < ADH_RESOLVED_RADIUS ? (r.apart >= 0 || !s->curve.n ? " (under 10: the pull-off force depends on the grid)" : " (under 10: the largest tension depends on the grid)") : ""));
  if (r.asperity_tabor > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "adhbem: resolution: the range against %s: %s = %.3g (%s)\n", s->indenter.type == ADH_INDENTER_SPHERE ? "the sphere" : "the smallest asperities", s->crops.tabor_name, (double)r.asperity_tabor, r.asperity_tabor >= 3 ? "near the JKR limit: the cohesive zone is narrow, about a tenth of the contact radius at 3" : r.asperity_tabor <= 0.1 ? "near DMT: the zone is wide" : "between DMT and JKR"));
  if (r.state < 0) PetscFunctionReturn(0);
  smallest[0] = 0;
  if (r.smallest_tensile_patch) PetscCall(PetscSNPrintf(smallest, sizeof(smallest), "; the smallest patch carrying a net tension has %" PetscInt_FMT, r.smallest_tensile_patch));
  if (r.cohesive_width > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "adhbem: resolution: at the largest tension the cohesive zone is %s about %.3g grid spacings wide (%.0f elements)%s\n", s->indenter.type == ADH_INDENTER_SPHERE ? "an annulus" : "a band along the contact's edge, on average", (double)r.cohesive_width, (double)r.cohesive_elements, r.cohesive_width < ADH_RESOLVED_ZONE ? " (under 10: the pull-off force depends on the grid)" : ""));
  else if (r.cohesive_elements > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "adhbem: resolution: at the largest tension the cohesive zone covers %.0f elements\n", (double)r.cohesive_elements));
  if (r.apart < 0 && s->curve.state[r.state].contact_points == s->grid->Nx * s->grid->Ny) {
    /* the whole cell sticks: no edge, nothing for the grid to resolve */
    PetscCall(PetscViewerASCIIPrintf(viewer, "adhbem: resolution: at the largest tension (state %" PetscInt_FMT ", F = %g) the whole grid is in contact: no contact edge, no pull-off to resolve\n", r.state, (double)r.force));
    PetscFunctionReturn(0);
  }
  if (r.resolved) PetscCall(PetscStrncpy(verdict, r.apart >= 0 ? "the grid resolves the adhesion" : "the grid resolves the tension carried", sizeof(verdict)));
  else {
    PetscCall(AdhSolverUnresolvedWords_Private(s, &s->curve.state[r.state], r.unresolved, why, sizeof(why)));
    PetscCall(PetscSNPrintf(verdict, sizeof(verdict), "the %s depends on the grid (%s); refine it (the same surface on a finer grid) until it no longer changes", r.apart >= 0 ? "pull-off force" : "largest tension", why));
  }
  if (s->crops.cohesive) /* the zone's width decides, not the patches' size */
    PetscCall(PetscViewerASCIIPrintf(viewer, "adhbem: resolution: at the largest tension (state %" PetscInt_FMT ", F = %g%s)%s: %s\n", r.state, (double)r.force, r.apart >= 0 ? "" : ", not a pull-off: the surfaces did not come apart", smallest[0] ? smallest + 1 : "", verdict));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "adhbem: resolution: at the largest tension (state %" PetscInt_FMT ", F = %g%s) %.0f%% of the tension is carried by contact patches of fewer than %d elements (a disk of radius %d)%s: %s\n", r.state, (double)r.force, r.apart >= 0 ? "" : ", not a pull-off: the surfaces did not come apart", 100.0 * (double)r.small_patch_tension, ADH_RESOLVED_PATCH, ADH_RESOLVED_RADIUS, smallest, verdict));
  PetscFunctionReturn(0);
}
