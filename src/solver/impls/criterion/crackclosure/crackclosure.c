/*MC
   ADHCRITERIONCRACKCLOSURE - "crack-closure", the default: a point on the contact edge lets go when the edge's energy
   release rate, estimated by virtual crack closure and averaged along the edge, exceeds its dgamma

   Virtual crack closure is Rybicki and Kanninen's (1977); it was applied to this BEM before in Front. Mech. Eng. 7,
   754782 (2021), on the parabolic and sinusoidal contacts. The rate does not depend on the edge's direction on the
   grid.

   Options Database Keys:
+  -adh_criterion crack-closure   - selects this criterion (the default)
.  -adh_criterion_radius <16>     - the radius of the window the release rate is averaged in, in grid spacings, in [1, 64]
.  -adh_criterion_radius_max <64> - near dgamma, the window's radius is the front's radius of curvature up to this,
                                    at most 128 (equal to -adh_criterion_radius: a fixed window)
.  -adh_criterion_certify         - the certified early stop of intermediate solves too (off by default)
-  -adh_attach <griffith>         - griffith, this criterion's mirror for joining points, is the default with it

   Level: beginner

   Notes:
   The front is the set's points with an open 4-neighbour. When a front point lets go the edge moves by one element:
   on a straight edge in any direction the set less its front is the set shifted by one element along the grid axis
   closest to the edge's normal, so a front point gets the opening its neighbour along that axis has now. A front
   point i under tension -p_i frees G_i = -p_i delta_i / 2 per unit area when it lets go, delta_i the opening (gap) of
   its open neighbour closest to the edge's normal (the normal estimated from the open points within
   ADH_NORMAL_RADIUS, 3 grid spacings). Where the indenter has no face (outside a punch, h = PETSC_INFINITY) the
   opening is measured from the face extended flat.

   Single points of a staircase are not representative: along each run of the staircase G_i rises from about 0.6 to
   1.5 times the edge's rate, while the mean over a period of the staircase is within 1% of it. So G is averaged
   along the front, over the front points that can be reached along it within a window, with a weight that fades to
   zero at the window's radius, and a front point lets go when that mean exceeds its dgamma. The window's radius is
   -adh_criterion_radius, and where the mean over that comes near dgamma, the front's radius of curvature there, up
   to -adh_criterion_radius_max. On a curved edge the staircase's runs grow like the square root of the radius of
   curvature in grid spacings, so a window of fixed size stops spanning them as the grid is refined, and the first
   window whose mean runs high lets go (with a fixed radius of 16 the JKR sphere came off 0.6%, 1.3%, 1.5% low at
   a_c/h 25, 50, 100); a window as large as the radius of curvature spans them at any resolution and is still local
   on the scale on which the edge's release rate varies.

   A point lets go also under the pohrt-popov rule, p < -Sigma: the exact energy balance of a point alone, which lets
   a crack start inside the set. With dgamma = 0 the criterion reduces to non-adhesive contact: p < 0 lets go. The
   state's detach ratio is the larger of (G/dgamma)^(1/2) and -p/Sigma.

   A test costs one compliance multiply (the attach test after a test that let nothing go reuses its gap). With
   -adh_criterion_certify the certified early stop of intermediate solves applies, with the openings' error bounded
   through K's row norms (Decide_CrackClosure): the same sets with 12-16% fewer FFT pairs and about the default's
   time, for a cache of each set's walks along the front (about 1 kB a front point). With this criterion
   -adh_cascade_local is inf, the whole grid, by default under displacement control.

   Measured (./run bench criterion, docs/verification/johnson-wave.md, jkr-sphere.md): the work of adhesion it acts with is within 1.4% of dgamma on
   straight edges in the six directions measured (0 to 45 degrees), within 0.2% on the JKR sphere at a_c/h 25 to 100,
   converging on the cone and the punch; pohrt-popov's: 1.02 to 1.88 on the straight edges, 0-6% high on the curved
   ones.

.seealso: `AdhSolverSetCriterionType()`, `ADHCRITERIONPOHRTPOPOV`, `AdhSolverEstimateMemory()`
M*/
#include "crackclosureimpl.h"

/* defined below: the certified stop, chosen at set-up (-adh_criterion_certify) */
static PetscErrorCode Decide_CrackClosure(AdhSolver, Vec, PetscReal, AdhDetachDecision *, PetscReal *);

/* The fetch of the rows each rank looks at, made at the solver's set-up. */
static PetscErrorCode SetUp_CrackClosure(AdhSolver s)
{
  CrackClosure   *cc = (CrackClosure *)s->crops.data;
  const AdhGrid   g  = s->grid;
  const PetscBool periodic = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);
  PetscInt        ys, ym, side, *rows;

  PetscFunctionBegin;
  if (cc->fetch) PetscFunctionReturn(0);
  cc->radius_max = PetscMax(cc->radius, cc->radius_max);
  /* its certified stop: the same sets for fewer FFT pairs, about the default's time (docs/developers/notebook/performance.md) */
  s->crops.decide = cc->certify ? Decide_CrackClosure : NULL;
  /* the certified stop evaluates a set at several iterates: keep its front's walks (a PetscInt a
     point, and about 1 kB a front point: some 90 members of 12 B within the radius) */
  cc->cache     = (PetscBool)(cc->certify && s->certify);
  cc->cache_set = -1;
  cc->links_set = -1;
  if (cc->cache) PetscCall(PetscMalloc1(s->nlocal + 1, &cc->slot));
  cc->width       = AdhCrackClosureWidth(cc->radius_max);
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  if (periodic) {
    cc->gys = ys - cc->width;
    cc->gym = ym + 2 * cc->width;
  } else {
    cc->gys = PetscMax(0, ys - cc->width);
    cc->gym = PetscMin(g->Ny, ys + ym + cc->width) - cc->gys;
  }
  PetscCall(PetscMalloc1(cc->gym, &rows));
  PetscCall(PetscMalloc1(cc->gym, &cc->rowmap));
  cc->nx     = g->Nx;
  cc->nghost = 0;
  for (PetscInt r = 0; r < cc->gym; r++) {
    const PetscInt b = ((cc->gys + r) % g->Ny + g->Ny) % g->Ny;
    if (b >= ys && b < ys + ym) cc->rowmap[r] = b - ys;
    else {
      rows[cc->nghost] = b;
      cc->rowmap[r]    = -1 - cc->nghost++;
    }
  }
  PetscCall(AdhGridCreateRowSF(g, cc->nghost, rows, &cc->fetch));
  PetscCall(PetscFree(rows));
  PetscCall(AdhGridGetRowType(g, MPIU_SCALAR, &cc->row_scalars));
  PetscCall(AdhGridGetRowType(g, MPI_CHAR, &cc->row_flags));
  PetscCall(AdhGridCreateVector(g, &cc->G));
  PetscCall(PetscMalloc5(cc->nghost * g->Nx + 1, &cc->O.far, cc->nghost * g->Nx + 1, &cc->H.far, cc->nghost * g->Nx + 1, &cc->Gf.far, cc->nghost * g->Nx + 1, &cc->far_set, s->nlocal + 1, &cc->set_before));
  PetscCall(PetscMalloc5(cc->gym, &cc->O.store, cc->gym, &cc->H.store, cc->gym, &cc->Gf.store, cc->gym, &cc->P.store, cc->gym, &cc->set_store));
  side = 2 * cc->width + 1;
  PetscCall(PetscCalloc3(side * side, &cc->seen, side * side, &cc->qi, side * side, &cc->qj));
  PetscCall(PetscMalloc2(side, &cc->col, side, &cc->row));
  PetscCall(PetscMalloc1(cc->gym * g->Nx, &cc->links));
  PetscFunctionReturn(0);
}

static PetscErrorCode Evaluate_CrackClosure(AdhSolver s, PetscBool detach, PetscInt *removed, PetscReal *ratio)
{
  PetscFunctionBegin;
  PetscCall(AdhCrackClosureDetach_Private(s, detach, removed, ratio));
  PetscFunctionReturn(0);
}

/* The certified early stop: the iterate xC into p (the solve's vector, so its values off the set
   stay), and the decision of the rules. One compliance multiply, so checked only once the bound
   has come down to where the decisions in doubt at the last check would be made. */
static PetscErrorCode Decide_CrackClosure(AdhSolver s, Vec xC, PetscReal perr, AdhDetachDecision *decision, PetscReal *needed)
{
  PetscFunctionBegin;
  PetscCall(AdhSolverSetIterate_Private(s, xC));
  PetscCall(AdhCrackClosureDecide_Private(s, perr, decision, needed));
  /* AdhCrackClosureDecide_Private left the gap of this iterate in g: an attach check, which follows only a NONE, takes it */
  s->gap_current = (PetscBool)(*decision == ADH_DETACH_NONE);
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_CrackClosure(AdhSolver s)
{
  CrackClosure *cc = (CrackClosure *)s->crops.data;

  PetscFunctionBegin;
  PetscCall(VecDestroy(&cc->faceless));
  PetscCall(VecDestroy(&cc->G));
  PetscCall(PetscFree(cc->rowmap));
  PetscCall(PetscSFDestroy(&cc->fetch));
  PetscCall(PetscFree5(cc->O.far, cc->H.far, cc->Gf.far, cc->far_set, cc->set_before));
  PetscCall(PetscFree(cc->P.far));
  PetscCall(PetscFree5(cc->O.store, cc->H.store, cc->Gf.store, cc->P.store, cc->set_store));
  PetscCall(PetscFree3(cc->seen, cc->qi, cc->qj));
  PetscCall(PetscFree2(cc->col, cc->row));
  PetscCall(PetscFree(cc->links));
  PetscCall(PetscFree(cc->slot));
  PetscCall(PetscFree(cc->entry));
  PetscCall(PetscFree(cc->member));
  PetscCall(PetscFree(cc->weight));
  PetscCall(PetscFree(cc->front_limit));
  PetscCall(PetscFree(s->crops.data));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetFromOptions_CrackClosure(AdhSolver s, AdhOptionItems PetscOptionsObject)
{
  CrackClosure *cc = (CrackClosure *)s->crops.data;

  PetscFunctionBegin;
  PetscCall(AdhOptionsReal("-adh_criterion_radius", "crack-closure: average the release rate along the contact edge within this many grid spacings (the weight fades to 0 there), or more near the detachment (-adh_criterion_radius_max)", "ADHCRITERIONCRACKCLOSURE", cc->radius, &cc->radius, NULL));
  PetscCall(AdhOptionsReal("-adh_criterion_radius_max", "crack-closure: near the detachment, average within the edge's radius of curvature where that is larger, up to this many grid spacings (so that curved edges converge with the grid; equal to -adh_criterion_radius: a fixed window)", "ADHCRITERIONCRACKCLOSURE", cc->radius_max, &cc->radius_max, NULL));
  PetscCall(PetscOptionsBool("-adh_criterion_certify", "crack-closure: the certified early stop of intermediate solves too (its openings bounded through K's row norms): the same sets with 12-16% fewer FFT pairs and about the default's time (it keeps each set's walks along the front, about 1 kB a front point)", "ADHCRITERIONCRACKCLOSURE", cc->certify, &cc->certify, NULL));
  PetscCheck(cc->radius >= 1 && cc->radius <= 64, PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_criterion_radius must lie in [1, 64] grid spacings, got %g", (double)cc->radius);
  PetscCheck(cc->radius_max <= 128, PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_criterion_radius_max must be at most 128 grid spacings, got %g", (double)cc->radius_max);
  PetscCheck(cc->radius_max >= cc->radius, PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_criterion_radius_max (%g) must be at least -adh_criterion_radius (%g)", (double)cc->radius_max, (double)cc->radius);
  PetscFunctionReturn(0);
}

/* Its line of -adh_view, and its attributes in the results file. */
static PetscErrorCode View_CrackClosure(AdhSolver s, PetscViewer viewer)
{
  CrackClosure *cc = (CrackClosure *)s->crops.data;
  PetscBool     isascii, ishdf5;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERHDF5, &ishdf5));
  if (isascii && cc->radius_max > cc->radius) PetscCall(PetscViewerASCIIPrintf(viewer, "release rate averaged within %g grid spacings (near the detachment within the edge's radius of curvature, up to %g)%s\n", (double)cc->radius, (double)cc->radius_max, cc->certify ? "; its certified early stop" : ""));
  else if (isascii) PetscCall(PetscViewerASCIIPrintf(viewer, "release rate averaged within %g grid spacings%s\n", (double)cc->radius, cc->certify ? "; its certified early stop" : ""));
  if (ishdf5) {
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "criterion_radius", PETSC_REAL, &cc->radius));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "criterion_radius_max", PETSC_REAL, &cc->radius_max));
  }
  PetscFunctionReturn(0);
}

/* Its radii shape its answer: a restart repeats them. */
static PetscErrorCode Shape_CrackClosure(AdhSolver s, PetscInt *n, AdhShapingOption shape[])
{
  CrackClosure *cc = (CrackClosure *)s->crops.data;

  PetscFunctionBegin;
  shape[0] = (AdhShapingOption){"-adh_criterion_radius", PETSC_REAL, &cc->radius};
  shape[1] = (AdhShapingOption){"-adh_criterion_radius_max", PETSC_REAL, &cc->radius_max};
  *n       = 2;
  PetscFunctionReturn(0);
}

/* What it adds to the memory model (the comment of interface/estimate.c accounts for it): G, a
   copy of the flags, u where the profile has points without a face, the front's links, the
   cache's slots with its certified stop; per rank the rows of other ranks it looks at (three
   buffers, a fourth of p with -adh_attach griffith, the flags and the links). */
static PetscErrorCode Memory_CrackClosure(AdhSolver s, PetscLogDouble *per_point, PetscLogDouble *per_rank)
{
  CrackClosure   *cc       = (CrackClosure *)s->crops.data;
  const PetscBool faceless = (PetscBool)(s->indenter.type == ADH_INDENTER_PUNCH); /* a file's or an array's profile is finite */

  PetscFunctionBegin;
  *per_point = 9.0 + (faceless ? 8.0 : 0.0) + sizeof(PetscInt) + (cc->certify && s->certify ? sizeof(PetscInt) : 0.0);
  *per_rank  = ((s->attach == ADH_ATTACH_GRIFFITH ? 4 : 3) * 8.0 + 1.0 + sizeof(PetscInt)) * 2 * AdhCrackClosureWidth(PetscMax(cc->radius, cc->radius_max)) * s->grid->Nx;
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode AdhCriterionCreate_CrackClosure(AdhSolver s)
{
  CrackClosure *cc;

  PetscFunctionBegin;
  PetscCall(PetscNew(&cc));
  cc->radius                   = 16.0;
  cc->radius_max               = 64.0;
  s->crops.data                = cc;
  s->crops.attach              = ADH_ATTACH_GRIFFITH; /* its mirror: JKR's and Johnson's loading branches */
  s->crops.griffith            = PETSC_TRUE;
  s->crops.local_solves        = PETSC_TRUE;
  s->crops.evaluate            = Evaluate_CrackClosure;
  s->crops.base.setfromoptions = SetFromOptions_CrackClosure;
  s->crops.base.view           = View_CrackClosure;
  s->crops.base.setup          = SetUp_CrackClosure;
  s->crops.base.destroy        = Destroy_CrackClosure;
  s->crops.base.shape          = Shape_CrackClosure;
  s->crops.base.memory         = Memory_CrackClosure;
  PetscFunctionReturn(0);
}
