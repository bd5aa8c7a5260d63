/* -adh_cascade_local F: after a set update lets points go, the set is solved again only within W
   grid spacings (in x and in y) of them, the rest of the set frozen; what that shows lets go, and
   the next local solve is around those points; when a local solve lets nothing go, the step goes
   on with a solve of the whole set, as in the exact cascade. W is F times the smallest
   asperities' JKR contact radius, the run's estimate (resolution.c), so that the window keeps its
   physical size as the grid is refined.

   Why: a receding edge lets go one ring of elements per set update, and in the exact cascade each
   ring costs a solve of the whole set, so a step's solves grow with the grid. Letting a ring go
   changes the pressure mostly near it: the correction is the solution of K_WW dp_W = r_W on the
   window W, r = d - h - K p = -g the residual the tension let go leaves. A local solve needs a
   loose tolerance only (-adh_cascade_local_rtol, relative to that residual): it decides
   detachments, and every recorded state still ends on a solve of the whole set and its attach
   test. A point let go on a local solve's pressures does not come back (the attach rules of the
   step apply), so the states may differ from the exact cascade's: the route is judged by its
   error against the converged reference (docs/developers/notebook/performance.md).

   The frozen rest is a bias, not only an error: the set's points beyond the window would take up
   part of the tension let go, and held fixed they leave it all to the window, whose points then
   let go too early. Measured on the resolved rough cell, a window of 1.6 JKR radii or less took
   up to 3.4% off the largest tension and up to 18% off the loop's energy; the docs give the table.

   This build applies K_WW on the whole grid (the set's operator, masked to the window), so a
   local iteration costs what a global one does and the width costs nothing; the saving is in the
   iterations (a few per local solve from a zero correction, against about 11 for the whole set's).
   The window's marks are the -adh_cascade_apart band's (cascadeapart.c): the points let go,
   widened across ranks by a PetscSF of rows. */
#include "solver/solverimpl.h"

static PetscErrorCode MatMult_Window(Mat Kww, Vec x, Vec y)
{
  AdhSolver s;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(Kww, &s));
  PetscCall(AdhSolverApplyRestricted_Private(s, s->Kop, s->nwin_local, s->win_local, s->win_scatter, x, y));
  PetscFunctionReturn(0);
}

/* The Fourier preconditioner of the set's solves, restricted to the window. */
static PetscErrorCode PCApply_Window(PC pc, Vec r, Vec z)
{
  AdhSolver s;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &s));
  PetscCall(AdhSolverApplyRestricted_Private(s, s->Sop, s->nwin_local, s->win_local, s->win_scatter, r, z));
  PetscFunctionReturn(0);
}

/* The window's half-width in grid spacings, local_W = ceil(F a_c / h) for -adh_cascade_local F,
   from the run's estimate of the smallest asperities' JKR radius a_c (resolution.c), at least one
   spacing and at most the grid; without an estimate (no dgamma, a fixed critical stress, a
   profile other than a sphere or a rough surface or map) the whole grid. Made again with each profile (the estimate
   changes with it), and the band of marks widened to it. */
PetscErrorCode AdhSolverSetLocalWidth_Private(AdhSolver s)
{
  const PetscInt  whole    = PetscMax(s->grid->Nx, s->grid->Ny);
  const PetscBool periodic = (PetscBool)(s->boundary == ADH_BOUNDARY_PERIODIC);

  PetscFunctionBegin;
  if (!(s->cascade_local > 0)) PetscFunctionReturn(0);
  s->local_W = s->asperity_ac > 0 ? (PetscInt)PetscMin((PetscReal)whole, PetscMax(1.0, PetscCeilReal(s->cascade_local * s->asperity_ac))) : whole;
  /* every point within W of every other (on a periodic cell the farthest lies N/2 away) */
  s->local_whole = (PetscBool)(periodic ? 2 * s->local_W >= whole : s->local_W >= whole - 1);
  if (!s->local_whole) PetscCall(AdhSolverSetUpCascadeApart_Private(s));
  PetscFunctionReturn(0);
}

/* The default route, unless -adh_cascade_local was given: with a criterion that asks for it
   (crack-closure) under a control whose steps re-solve at a fixed target (displacement), local solves on the whole grid (F = inf) to -adh_cascade_local_rtol 1e-3. On the
   resolved rough cell's ensembles (64^2-256^2, 20 runs a grid) its errors were 0.5-1.2 times the
   exact cascade's, and on every analytic case the same or nearer, for 0.63 times the FFT pairs at
   256^2 (docs/developers/notebook/performance.md). The exact cascade (F = 0) stays with the paper's criterion, whose
   loop it is, and under force control, which has no local solves. */
PetscErrorCode AdhSolverDefaultCascadeLocal_Private(AdhSolver s)
{
  PetscFunctionBegin;
  if (s->cascade_local_set) PetscFunctionReturn(0);
  s->cascade_local = s->crops.local_solves && s->cops.cascades ? (PetscReal)INFINITY : 0.0; /* IEEE inf, so that -help and the results file say inf */
  PetscFunctionReturn(0);
}

/* PETSc's default test, and a signal stops the path within an iteration (as the set's solves do) */
static PetscErrorCode ConvergedLocal(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason *reason, void *ctx)
{
  AdhSolver s = (AdhSolver)ctx;
  PetscBool stop;

  PetscFunctionBegin;
  PetscCall(AdhSolverStopRequested_Private(s, &stop));
  if (stop) {
    *reason = KSP_DIVERGED_NULL;
    PetscFunctionReturn(0);
  }
  PetscCall(KSPConvergedDefault(ksp, it, rnorm, reason, s->local_converged));
  PetscFunctionReturn(0);
}

/* The local solves' KSP (options prefix adh_local_): CG from zero, preconditioned as the set's
   solves are, to -adh_cascade_local_rtol. */
PetscErrorCode AdhSolverSetUpCascadeLocal_Private(AdhSolver s)
{
  char prefix[256];
  PC   pc;

  PetscFunctionBegin;
  PetscCall(KSPCreate(s->comm, &s->local_ksp));
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%sadh_local_", s->prefix ? s->prefix : ""));
  PetscCall(KSPSetOptionsPrefix(s->local_ksp, prefix));
  PetscCall(KSPSetType(s->local_ksp, KSPCG));
  PetscCall(KSPSetNormType(s->local_ksp, KSP_NORM_UNPRECONDITIONED));
  PetscCall(KSPSetTolerances(s->local_ksp, s->cascade_local_rtol, 0.0, PETSC_DEFAULT, 10000));
  PetscCall(KSPGetPC(s->local_ksp, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, s));
  PetscCall(PCShellSetApply(pc, PCApply_Window));
  PetscCall(PCShellSetName(pc, "adhbem Fourier preconditioner restricted to the local solve's window"));
  PetscCall(KSPConvergedDefaultCreate(&s->local_converged));
  PetscCall(KSPSetConvergenceTest(s->local_ksp, ConvergedLocal, s, NULL));
  PetscCall(KSPSetFromOptions(s->local_ksp));
  PetscCall(AdhCheckKSPOptions_Private(s->local_ksp, s->prefix, "adh_local_"));
  PetscFunctionReturn(0);
}

static PetscErrorCode DestroyWindow(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(MatDestroy(&s->Kww));
  PetscCall(VecDestroy(&s->pW));
  PetscCall(VecDestroy(&s->bW));
  PetscCall(VecScatterDestroy(&s->win_scatter));
  PetscCall(PetscFree(s->win_local));
  s->nwin_local = s->nwin = 0;
  if (s->local_ksp) PetscCall(KSPReset(s->local_ksp)); /* its work vectors are the window's */
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverDestroyCascadeLocal_Private(AdhSolver s)
{
  PetscFunctionBegin;
  PetscCall(DestroyWindow(s));
  PetscCall(KSPDestroy(&s->local_ksp));
  if (s->local_converged) PetscCall(AdhKSPConvergedDefaultDestroy(&s->local_converged));
  PetscFunctionReturn(0);
}

/* The window: the points of the set among the widened marks (s->gone; all of them where the
   window covers the grid), its vectors, K_WW and, off the direct path, the scatter to the
   operator's grid (the set's: the window lies in the set). */
static PetscErrorCode BuildWindow(AdhSolver s)
{
  PetscInt count = 0, rstart, *idx, *opidx;
  IS       is;

  PetscFunctionBegin;
  PetscCall(DestroyWindow(s));
#define IN_WINDOW(k) (s->in_set[k] && (s->local_whole || s->gone[k]))
  for (PetscInt k = 0; k < s->nlocal; k++) count += IN_WINDOW(k);
  PetscCall(PetscMalloc1(count + 1, &s->win_local));
  for (PetscInt k = 0, n = 0; k < s->nlocal; k++)
    if (IN_WINDOW(k)) s->win_local[n++] = k;
#undef IN_WINDOW
  s->nwin_local = count;
  PetscCall(MPIU_Allreduce(&count, &s->nwin, 1, MPIU_INT, MPI_SUM, s->comm));
  if (!s->nwin) PetscFunctionReturn(0);
  PetscCall(VecCreateMPI(s->comm, count, s->nwin, &s->pW));
  PetscCall(VecDuplicate(s->pW, &s->bW));
  if (!s->direct_set) {
    PetscCall(VecGetOwnershipRange(s->p, &rstart, NULL));
    PetscCall(PetscMalloc2(count + 1, &idx, count + 1, &opidx));
    for (PetscInt n = 0; n < count; n++) idx[n] = rstart + s->win_local[n];
    PetscCall(AdhSolverOperatorIndices_Private(s, count, idx, opidx));
    PetscCall(ISCreateGeneral(s->comm, count, opidx, PETSC_USE_POINTER, &is));
    PetscCall(VecScatterCreate(s->pW, NULL, s->op_in, is, &s->win_scatter));
    PetscCall(ISDestroy(&is));
    PetscCall(PetscFree2(idx, opidx));
  }
  PetscCall(MatCreateShell(s->comm, count, count, s->nwin, s->nwin, s, &s->Kww));
  PetscCall(MatShellSetOperation(s->Kww, MATOP_MULT, (void (*)(void))MatMult_Window));
  PetscCall(MatSetOption(s->Kww, MAT_SPD, PETSC_TRUE));
  PetscCall(KSPSetOperators(s->local_ksp, s->Kww, s->Kww));
  PetscFunctionReturn(0);
}

/* p_W += dp_W from K_WW dp_W = -g_W, g the gap of the current p (one compliance multiply). */
static PetscErrorCode SolveOnWindow(AdhSolver s)
{
  KSPConvergedReason reason;
  PetscInt           its;
  const PetscScalar *ga, *da;
  PetscScalar       *ba, *pa;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(ADH_LocalSolve, 0, 0, 0, 0));
  PetscCall(AdhSolverComputeGap_Private(s));
  PetscCall(VecGetArrayRead(s->g, &ga));
  PetscCall(VecGetArrayWrite(s->bW, &ba));
  for (PetscInt n = 0; n < s->nwin_local; n++) ba[n] = -ga[s->win_local[n]];
  PetscCall(VecRestoreArrayWrite(s->bW, &ba));
  PetscCall(VecRestoreArrayRead(s->g, &ga));
  /* a loose solve (1e-3 by default): in single precision under -adh_cascade_single; from zero,
     pW being new (zeroed) with each window */
  PetscCall(AdhSolverKSPSolve_Private(s, s->local_ksp, PETSC_TRUE, s->bW, s->pW));
  PetscCall(KSPGetConvergedReason(s->local_ksp, &reason));
  PetscCall(KSPGetIterationNumber(s->local_ksp, &its));
  s->step_ksp += its;
  if (AdhSolverStopped_Private(s)) { /* stopped: the step is abandoned */
    PetscCall(PetscLogEventEnd(ADH_LocalSolve, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  PetscCheck(reason > 0, s->comm, PETSC_ERR_NOT_CONVERGED, "The local solve of -adh_cascade_local (%" PetscInt_FMT " points) at d = %g did not converge: %s after %" PetscInt_FMT " iterations (see -adh_local_ksp_max_it, -adh_local_ksp_monitor)", s->nwin, (double)s->d, KSPConvergedReasons[reason], its);
  s->step_local_solves++;
  PetscCall(VecGetArray(s->p, &pa));
  PetscCall(VecGetArrayRead(s->pW, &da));
  for (PetscInt n = 0; n < s->nwin_local; n++) pa[s->win_local[n]] += da[n];
  PetscCall(VecRestoreArrayRead(s->pW, &da));
  PetscCall(VecRestoreArray(s->p, &pa));
  s->gap_current = PETSC_FALSE;
  PetscCall(PetscLogEventEnd(ADH_LocalSolve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The local cascade after a set update that let points go (marked in s->gone, and widened by
   `widened` already: -adh_cascade_apart's D, whose joins came first) and rebuilt the set: local
   solves and detach tests until one lets nothing go. Square widenings add up, so the first
   window is widened by the rest only (by none where D is the wider). The set is rebuilt after
   each test that lets points go, so the criterion's caches (keyed on the set) stay right. */
PetscErrorCode AdhSolverCascadeLocal_Private(AdhSolver s, PetscInt widened)
{
  PetscInt removed;

  PetscFunctionBegin;
  s->certified_stop = PETSC_FALSE; /* the tests below are of the local solves' pressures */
  do {
    AdhSolverCheckStop_Private(s);
    if (!s->local_whole) PetscCall(AdhSolverMarkNearGone_Private(s, PetscMax(s->local_W - widened, 0)));
    widened = 0;
    PetscCall(BuildWindow(s));
    if (!s->nwin) break;
    PetscCall(SolveOnWindow(s));
    AdhSolverReturnIfStopped_Private(s);
    if (!s->local_whole) PetscCall(PetscArrayzero(s->gone, s->nlocal));
    s->local_pending = (PetscBool)!s->local_whole;
    PetscCall(AdhSolverDetach_Private(s, &removed));
    s->local_pending = PETSC_FALSE;
    if (removed) PetscCall(AdhSolverRebuildSet_Private(s));
    PetscCall(PetscInfo(s, "d = %g, local solve %" PetscInt_FMT " on %" PetscInt_FMT " points: %" PetscInt_FMT " let go, %" PetscInt_FMT " in the set\n", (double)s->d, s->step_local_solves, s->nwin, removed, s->npoints));
  } while (removed);
  PetscCall(DestroyWindow(s));
  PetscFunctionReturn(0);
}
