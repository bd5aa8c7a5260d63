/* A step under a cohesive law (a criterion with a law op: impls/criterion/exponential.c, ...): the
   minimum of the total energy, elastic energy plus the law's potential over the gaps, with the hard
   wall g >= 0 as a bound, reached from the current state so that the quasi-static branch is
   followed. A projected descent in the gap variables (Polonsky and Keer 1999, with the adhesive
   functional of Rey, Anciaux and Molinari 2017), started with the last state's contact at the
   wall: on the free points (gap > 0, or at 0 and pulled away) the direction is an inexact Newton
   step, the energy's Hessian there solved by CG with the compliance as preconditioner
   (-adh_minimize_direction newton), or the preconditioned gradient conjugated with Polak-Ribiere
   (polak-ribiere); the step length minimises the energy along the direction (the elastic part is
   quadratic, one stiffness multiply gives it; the law's part is pointwise); the step is projected
   back onto the bound (and the mean gap under displacement control). Why not TAO, and why Newton:
   docs/theory/minimisation.md.

   The variables. On a periodic cell the gaps: the elastic displacement is u = g - (h - d), the
   elastic pressure S u (S, the stiffness, applied to mean-free vectors: a periodic cell has no
   mean displacement), and the gradient of the energy per element area at a point is
   r = S u + phi'(g) + pbar, with pbar the mean pressure under force control. Under displacement
   control the mean gap is mean(h) - d, a constraint whose multiplier is the mean pressure. On the
   free boundary the variables live on the zero-padded grid (src/grid/padded.c): the gaps on the
   grid's points, the displacements beyond them, free; S is the inverse of the padded circulant
   of the compliance, whose energy minimised over the padding is the free half-space's. */
#include "solver/solverimpl.h"

/* Under a force, every gap beyond this many zone gaps: the attraction is gone (exp(-69) of its
   peak for the exponential law, 1e-6 for the 9-3 law's g^-4 tail) and the energy falls without
   bound, no minimum. */
#define ADH_RUNAWAY 30.0
/* A step is halved at most this often before the direction is given up. */
#define ADH_MAX_HALVINGS 10
/* The Newton direction's inner conjugate gradient stops after this many iterations (with the
   iterate so far, still a descent direction). */
#define ADH_NEWTON_MAX_CG 500
/* A move of a gap below this share of the zone gap is short: the law's energy change is integrated. */
#define ADH_SHORT_MOVE 1e-2

/* A free boundary's force control walks the branch from the step's state to the force asked. One
   that comes apart has passed the branch's largest tension; the pull-off's bisection then asks
   for forces beyond it again and again, each a walk to where the bodies let go (most of a force-
   controlled path's cost). So the walk remembers that largest tension, refined at a parabola's
   vertex, and a later walk of the same step from a state of the same branch (its start, or a
   state a walk from such a start found) answers at once for a force beyond it, and for one short
   of it brackets the force between its start and that largest force's d. */
typedef struct {
  PetscBool known;
  PetscInt  step;   /* the step it belongs to (s->step_id) */
  PetscReal dir;    /* the direction of d the walk took (+1 pressing, -1 pulling) */
  PetscReal start;  /* the d of a state of the branch from which a walk meets the same largest force */
  PetscReal startF; /* and its force */
  PetscReal Fmax;   /* the force of the branch furthest in dir's sense (its largest tension pulling) */
  PetscReal dmax;   /* and its d */
} AdhForceWalk;

struct _n_AdhMinimizer {
  Mat      S, C;        /* the stiffness and the compliance on the variables (periodic: the solver's) */
  char    *surface;     /* free boundary: which local variables are the grid's points (NULL: all are) */
  Vec      gamma;       /* free boundary: the dgamma field on the variables (NULL: uniform, or the solver's) */
  Vec      v, b;        /* the gaps (and the padding's displacements), and h - d: u = v - b */
  Vec      pel, q;      /* the elastic pressure S u, and S t */
  Vec      r, rp, z, t; /* the gradient, its projection on the free points, the preconditioned one, the direction */
  Vec      work, pold; /* scratch, and the elastic pressure before a step */
  Vec      u, rpold;   /* the elastic displacement v - b, and the previous projected gradient (Polak-Ribiere) */
  Vec      w, wr;       /* the preconditioner's scaling where the law stiffens the energy, and w r (NULL until needed) */
  PetscBool wheld, wscaled; /* inside a Newton solve: w is the linearisation point's, and whether it scales */
  Vec      pforce;      /* free boundary, force control: the pressure of the last trial short of the force (NULL until needed) */
  Vec      pbest, plo;  /* and the pressures of the walk's state nearest the force and of the one before it (NULL until needed) */
  AdhForceWalk walk;    /* what the last walk that came apart found, for the pull-off's bisection */
  PetscReal radius;     /* the Newton step's trust region (0 at a minimisation's first step: none) */
  PetscReal normd;      /* and the last Newton direction's length (Euclidean in the gaps, KSPSTCG's default) */
  PetscBool slope_known; /* the branch's slope dF/dd over the last walk that found its force, */
  PetscReal slope, slope_from, slope_to, slope_Ffrom, slope_Fto; /* from the state (d, F) at slope_from to the one at slope_to */
  PetscReal K00;        /* an element's displacement under its own unit pressure (Love), for that scaling */
  char    *active;      /* the points held at the wall (gap 0, pushed into it) */
  PetscInt n;           /* local points */
  PetscReal dgamma;     /* the largest work of adhesion present (the scales of the law: its range and peak) */
  KSP      ksp;         /* newton: the direction's inner conjugate gradient (NULL until needed) */
  Mat      H;           /* newton: the energy's Hessian on the free points, a shell */
  const PetscScalar *hgamma; /* newton: the dgamma field while H applies (NULL: uniform) */
  PetscBool hfixmean, hforce; /* newton: the mean gap held, a force's mean mode in the preconditioner */
  PetscInt cg_total;    /* newton: the inner iterations over the run */
  PetscInt its_total;   /* iterations over the run, for the view */
  PetscInt states;
};

PetscErrorCode AdhSolverMinimizeSetFromOptions_Private(AdhSolver s, AdhOptionItems PetscOptionsObject)
{
  static const char *const pcs[]  = {"none", "fourier", "AdhMinimizePC", "", NULL};
  static const char *const dirs[] = {"polak-ribiere", "newton", "AdhMinimizeDirection", "", NULL};
  PetscInt                 pc     = s->minimize_pc ? 1 : 0, dir = s->minimize_newton ? 1 : 0;

  PetscFunctionBegin;
  PetscCall(AdhOptionsReal("-adh_minimize_rtol", "A cohesive law's step stops when the projected gradient of the energy, a pressure, is this small relative to the pressure field", "AdhSolver", s->minimize_rtol, &s->minimize_rtol, NULL));
  PetscCheck(s->minimize_rtol > 0 && s->minimize_rtol < 1, PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_minimize_rtol must lie in (0, 1), got %g", (double)s->minimize_rtol);
  PetscCall(AdhOptionsInt("-adh_minimize_max_it", "The largest number of iterations of a cohesive law's energy minimisation in one step", "AdhSolver", s->minimize_max_it, &s->minimize_max_it, NULL));
  PetscCheck(s->minimize_max_it > 0, PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_minimize_max_it must be positive, got %" PetscInt_FMT, s->minimize_max_it);
  PetscCall(PetscOptionsBool("-adh_minimize_monitor", "Print a line per iteration of a cohesive law's energy minimisation (as -ksp_monitor)", "AdhSolver", s->minimize_monitor, &s->minimize_monitor, NULL));
  PetscCall(PetscOptionsEList("-adh_minimize_pc", "The preconditioner of a cohesive law's minimisation: the compliance on the free points (fourier) or none", "AdhSolver", pcs, 2, pcs[pc], &pc, NULL));
  s->minimize_pc = (PetscBool)(pc == 1);
  PetscCall(PetscOptionsEList("-adh_minimize_direction", "The direction of a cohesive law's minimisation: an inexact Newton step by conjugate gradients on the free points (newton) or the preconditioned gradient conjugated by Polak-Ribiere (polak-ribiere)", "AdhSolver", dirs, 2, dirs[dir], &dir, NULL));
  s->minimize_newton = (PetscBool)(dir == 1);
  PetscCall(AdhOptionsReal("-adh_minimize_trust_region", "The Newton direction's conjugate gradient stays within this many times the last step's length (Steihaug: along negative curvature to the region's edge); 0: it stops at negative curvature", "AdhSolver", s->minimize_trust, &s->minimize_trust, NULL));
  PetscCheck(s->minimize_trust >= 0, PetscObjectComm((PetscObject)s), PETSC_ERR_ARG_OUTOFRANGE, "-adh_minimize_trust_region must be 0 (none) or positive, got %g", (double)s->minimize_trust);
  PetscFunctionReturn(0);
}

/* The bytes a grid point costs the minimisation: its twelve vectors, three more for the Newton
   direction's conjugate gradient (KSPSTCG's work vectors), two more for the preconditioner's scaling
   of a law that stiffens the energy and three for force control on the free boundary, and two bytes
   of marks per variable, a variable a point on a periodic cell and four on the free boundary's
   padded grid. */
PetscLogDouble AdhSolverMinimizeMemory_Private(AdhSolver s)
{
  const PetscReal vectors = 12.0 + (s->minimize_newton ? 3.0 : 0.0) + (s->crops.stiffens ? 2.0 : 0.0) + (s->boundary == ADH_BOUNDARY_FREE && AdhSolverControlsForce_Private(s) ? 3.0 : 0.0);
  return (s->boundary == ADH_BOUNDARY_FREE ? 4.0 : 1.0) * (vectors * sizeof(PetscScalar) + 2.0);
}

/* Its lines in the law's -adh_view, or its attributes in the results file (the direction says what
   the curve's outer and Krylov iterations count). */
PetscErrorCode AdhSolverMinimizeView_Private(AdhSolver s, PetscViewer viewer)
{
  PetscBool isascii, ishdf5;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERHDF5, &ishdf5));
  if (ishdf5) {
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "minimize_rtol", PETSC_REAL, &s->minimize_rtol));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "minimize_direction", PETSC_STRING, s->minimize_newton ? "newton" : "polak-ribiere"));
    if (s->minimize_newton) PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "minimize_trust_region", PETSC_REAL, &s->minimize_trust));
  }
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (isascii) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "steps minimise the energy in the gaps, projected onto the wall: %s, preconditioner %s, to a relative projected gradient %g\n", s->minimize_newton ? "inexact Newton steps by conjugate gradients on the free points" : "Polak-Ribiere conjugate gradient", s->minimize_pc ? "fourier" : "none", (double)s->minimize_rtol));
    if (s->minimize_newton && s->minimize_trust > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "the Newton steps' conjugate gradients within a trust region of %.4g times the last step\n", (double)s->minimize_trust));
    else if (s->minimize_newton) PetscCall(PetscViewerASCIIPrintf(viewer, "the Newton steps' conjugate gradients stop at negative curvature (no trust region)\n"));
    if (s->minimizer && s->minimizer->states) {
      if (s->minimize_newton) PetscCall(PetscViewerASCIIPrintf(viewer, "%" PetscInt_FMT " Newton steps (%" PetscInt_FMT " conjugate gradient iterations) over %" PetscInt_FMT " steps\n", s->minimizer->its_total, s->minimizer->cg_total, s->minimizer->states));
      else PetscCall(PetscViewerASCIIPrintf(viewer, "%" PetscInt_FMT " iterations over %" PetscInt_FMT " steps\n", s->minimizer->its_total, s->minimizer->states));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverMinimizeDestroy_Private(AdhSolver s)
{
  AdhMinimizer m = s->minimizer;

  PetscFunctionBegin;
  if (!m) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&m->S));
  PetscCall(MatDestroy(&m->C));
  PetscCall(PetscFree(m->surface));
  PetscCall(VecDestroy(&m->gamma));
  PetscCall(VecDestroy(&m->v));
  PetscCall(VecDestroy(&m->b));
  PetscCall(VecDestroy(&m->pel));
  PetscCall(VecDestroy(&m->q));
  PetscCall(VecDestroy(&m->r));
  PetscCall(VecDestroy(&m->rp));
  PetscCall(VecDestroy(&m->z));
  PetscCall(VecDestroy(&m->t));
  PetscCall(VecDestroy(&m->work));
  PetscCall(VecDestroy(&m->pold));
  PetscCall(VecDestroy(&m->u));
  PetscCall(VecDestroy(&m->rpold));
  PetscCall(VecDestroy(&m->w));
  PetscCall(VecDestroy(&m->wr));
  PetscCall(VecDestroy(&m->pforce));
  PetscCall(VecDestroy(&m->pbest));
  PetscCall(VecDestroy(&m->plo));
  PetscCall(PetscFree(m->active));
  PetscCall(KSPDestroy(&m->ksp));
  PetscCall(MatDestroy(&m->H));
  PetscCall(PetscFree(s->minimizer));
  PetscFunctionReturn(0);
}

static PetscErrorCode Create(AdhSolver s)
{
  AdhMinimizer m;

  PetscFunctionBegin;
  PetscCall(PetscNew(&m));
  m->K00 = s->eops.self_compliance;
  if (s->boundary == ADH_BOUNDARY_PERIODIC) {
    m->S = s->S;
    m->C = s->K;
    PetscCall(PetscObjectReference((PetscObject)m->S));
    PetscCall(PetscObjectReference((PetscObject)m->C));
  } else {
    PetscCall(AdhCreatePaddedOperator_Private(s->K, PETSC_TRUE, &m->S));
    PetscCall(AdhCreatePaddedOperator_Private(s->K, PETSC_FALSE, &m->C));
  }
  PetscCall(MatCreateVecs(m->S, &m->v, NULL));
  PetscCall(VecGetLocalSize(m->v, &m->n));
  PetscCall(VecDuplicate(m->v, &m->b));
  PetscCall(VecDuplicate(m->v, &m->pel));
  PetscCall(VecDuplicate(m->v, &m->q));
  PetscCall(VecDuplicate(m->v, &m->r));
  PetscCall(VecDuplicate(m->v, &m->rp));
  PetscCall(VecDuplicate(m->v, &m->z));
  PetscCall(VecDuplicate(m->v, &m->t));
  PetscCall(VecDuplicate(m->v, &m->work));
  PetscCall(VecDuplicate(m->v, &m->pold));
  PetscCall(VecDuplicate(m->v, &m->u));
  PetscCall(VecDuplicate(m->v, &m->rpold));
  PetscCall(PetscMalloc1(m->n + 1, &m->active));
  if (s->boundary == ADH_BOUNDARY_FREE) {
    PetscCall(PetscMalloc1(m->n + 1, &m->surface));
    PetscCall(AdhPaddedGetPhysicalMask_Private(m->S, m->surface));
  }
  s->minimizer = m;
  PetscFunctionReturn(0);
}

/* A grid vector x into the variables' layout y (the padding set to outside), or (reverse) back. */
static PetscErrorCode Move(AdhSolver s, Vec x, Vec y, PetscScalar outside, PetscBool reverse)
{
  AdhMinimizer m = s->minimizer;

  PetscFunctionBegin;
  if (!m->surface) {
    if (reverse) PetscCall(VecCopy(y, x));
    else PetscCall(VecCopy(x, y));
  } else {
    if (!reverse) PetscCall(VecSet(y, outside));
    PetscCall(AdhPaddedMove_Private(m->S, x, y, reverse));
  }
  PetscFunctionReturn(0);
}

/* Local variable k is a point of the grid, behind the wall and under the law (not the padding's). */
static inline PetscBool OnSurface(AdhMinimizer m, PetscInt k)
{
  return (PetscBool)(!m->surface || m->surface[k]);
}

/* The multiplies of the free boundary's padded operators (the solver counts its own). */
PetscErrorCode AdhSolverMinimizeMultCount_Private(AdhSolver s, PetscInt *count)
{
  PetscInt a = 0, b = 0;

  PetscFunctionBegin;
  *count = 0;
  if (!s->minimizer || !s->minimizer->surface) PetscFunctionReturn(0);
  PetscCall(AdhPaddedGetMultCount_Private(s->minimizer->S, &a));
  PetscCall(AdhPaddedGetMultCount_Private(s->minimizer->C, &b));
  *count = a + b;
  PetscFunctionReturn(0);
}

/* y = S x on the mean-free part of x (the stiffness's mean mode is a preconditioner's value, not
   the cell's: it has none), or with compliance the compliance K x (mean mode zero). */
static PetscErrorCode ApplyMeanFree(AdhSolver s, Mat A, Vec x, Vec y)
{
  AdhMinimizer m = s->minimizer;
  PetscScalar  sum;

  PetscFunctionBegin;
  if (m->surface) { /* the free boundary: no mean mode to take out */
    PetscCall(MatMult(A, x, y));
    PetscFunctionReturn(0);
  }
  PetscCall(VecSum(x, &sum));
  PetscCall(VecCopy(x, m->work));
  PetscCall(VecShift(m->work, -sum / ((PetscReal)s->grid->Nx * s->grid->Ny)));
  PetscCall(MatMult(A, m->work, y));
  PetscFunctionReturn(0);
}

static inline void Law(AdhSolver, const PetscScalar *, PetscInt, PetscReal, PetscReal *, PetscReal *, PetscReal *);

/* Where the law stiffens the energy (phi'' > 0: a Lennard-Jones law near the wall) far beyond an
   element's elastic stiffness 1/K00, the compliance alone preconditions badly: the scaling
   w = 1/sqrt(1 + K00 phi''+) on each side, W K W, keeps the preconditioner symmetric and brings
   its diagonal near the inverse of the Hessian's (as far as the stiffness's diagonal is 1/K00).
   Returns whether any w differs from 1; only for a law that says it stiffens (crops.stiffens). */
static PetscErrorCode CurvatureScaling(AdhSolver s, const PetscScalar *gamma, PetscBool *scaled)
{
  AdhMinimizer       m = s->minimizer;
  const PetscScalar *va;
  PetscScalar       *wa;
  PetscInt           any = 0;

  PetscFunctionBegin;
  *scaled = PETSC_FALSE;
  if (!s->crops.stiffens) PetscFunctionReturn(0); /* the exponential, the smoothed Dugdale law: K itself */
  if (!m->w) {
    PetscCall(VecDuplicate(m->v, &m->w));
    PetscCall(VecDuplicate(m->v, &m->wr));
  }
  PetscCall(VecGetArrayRead(m->v, &va));
  PetscCall(VecGetArrayWrite(m->w, &wa));
  for (PetscInt k = 0; k < m->n; k++) {
    PetscReal phi, dphi, ddphi;
    Law(s, gamma, k, PetscRealPart(va[k]), &phi, &dphi, &ddphi);
    wa[k] = 1.0;
    if (ddphi > 0 && !m->active[k]) {
      wa[k] = 1.0 / PetscSqrtReal(1.0 + m->K00 * ddphi);
      any   = 1;
    }
  }
  PetscCall(VecRestoreArrayWrite(m->w, &wa));
  PetscCall(VecRestoreArrayRead(m->v, &va));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &any, 1, MPIU_INT, MPI_MAX, s->comm));
  *scaled = (PetscBool)any;
  PetscFunctionReturn(0);
}

/* z = K r (W K W r where the law stiffens the energy), with under a force the compliance of the
   longest wave (the body's mean_compliance, 2/(E* q_min) on a half-space), on the mean mode (the cell's has none; there the mean gap is free,
   and it needs the step a wave of the cell's size would take). */
static PetscErrorCode Precondition(AdhSolver s, const PetscScalar *gamma, PetscBool force, Vec r, Vec z)
{
  AdhMinimizer m = s->minimizer;
  PetscScalar  sum;
  PetscBool    scaled;

  PetscFunctionBegin;
  if (m->wheld) scaled = m->wscaled; /* a Newton solve's v does not move: its scaling neither */
  else PetscCall(CurvatureScaling(s, gamma, &scaled));
  if (scaled) {
    PetscCall(VecPointwiseMult(m->wr, m->w, r));
    r = m->wr;
  }
  PetscCall(VecSum(r, &sum));
  PetscCall(ApplyMeanFree(s, m->C, r, z));
  if (force) PetscCall(VecShift(z, s->eops.mean_compliance * sum / ((PetscReal)s->grid->Nx * s->grid->Ny)));
  if (scaled) PetscCall(VecPointwiseMult(z, m->w, z));
  PetscFunctionReturn(0);
}

/* The work of adhesion of local point k, 0 on a non-adhesive stage. */
static inline PetscReal Dgamma(AdhSolver s, const PetscScalar *gamma, PetscInt k)
{
  if (!s->adhesive) return 0.0;
  return gamma ? PetscRealPart(gamma[k]) : s->gamma;
}

/* The law at local point k and gap g: potential, attraction and its derivative (none without adhesion). */
static inline void Law(AdhSolver s, const PetscScalar *gamma, PetscInt k, PetscReal g, PetscReal *phi, PetscReal *dphi, PetscReal *ddphi)
{
  const PetscReal dg = OnSurface(s->minimizer, k) ? Dgamma(s, gamma, k) : 0.0;

  if (dg > 0) s->crops.law(s->crops.data, dg, g, phi, dphi, ddphi);
  else *phi = *dphi = *ddphi = 0.0;
}

/* The elastic pressure of the gaps, pel = S (v - b), exactly. */
static PetscErrorCode ElasticPressure(AdhSolver s)
{
  AdhMinimizer m = s->minimizer;

  PetscFunctionBegin;
  PetscCall(VecWAXPY(m->u, -1.0, m->b, m->v));
  PetscCall(ApplyMeanFree(s, m->S, m->u, m->pel));
  PetscFunctionReturn(0);
}

/* The gradient of the energy per element area, r = pel + phi'(v) + pbar. */
static PetscErrorCode Gradient(AdhSolver s, const PetscScalar *gamma, PetscReal pbar)
{
  AdhMinimizer       m = s->minimizer;
  const PetscScalar *va, *pa;
  PetscScalar       *ra;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(m->v, &va));
  PetscCall(VecGetArrayRead(m->pel, &pa));
  PetscCall(VecGetArrayWrite(m->r, &ra));
  for (PetscInt k = 0; k < m->n; k++) {
    PetscReal phi, dphi, ddphi;
    Law(s, gamma, k, PetscRealPart(va[k]), &phi, &dphi, &ddphi);
    ra[k] = pa[k] + dphi + pbar;
  }
  PetscCall(VecRestoreArrayWrite(m->r, &ra));
  PetscCall(VecRestoreArrayRead(m->pel, &pa));
  PetscCall(VecRestoreArrayRead(m->v, &va));
  PetscFunctionReturn(0);
}

/* The change of the energy per element area from the gaps z (elastic pressure pold) to v (pel),
   from the differences: (v - z).(pold + pel)/2 + sum (phi(v) - phi(z)) + pbar sum (v - z). The
   elastic part is exact for a quadratic energy; the totals would have no digits left for it near
   the minimum. */
static PetscErrorCode EnergyChange(AdhSolver s, const PetscScalar *gamma, PetscReal pbar, PetscReal *dE)
{
  AdhMinimizer       m = s->minimizer;
  const PetscScalar *va, *za, *pa, *oa;
  const PetscReal    range = s->crops.zone_gap && s->minimizer->dgamma > 0 ? s->crops.zone_gap(s->crops.data, s->minimizer->dgamma) : 0.0;
  PetscReal          e = 0.0;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(m->v, &va));
  PetscCall(VecGetArrayRead(m->z, &za));
  PetscCall(VecGetArrayRead(m->pel, &pa));
  PetscCall(VecGetArrayRead(m->pold, &oa));
  for (PetscInt k = 0; k < m->n; k++) {
    const PetscReal v = PetscRealPart(va[k]), z = PetscRealPart(za[k]), dv = v - z;
    PetscReal       phiv, phiz, dv_, dz, ddv, ddz, dphi;
    if (dv == 0) continue;
    Law(s, gamma, k, v, &phiv, &dv_, &ddv);
    Law(s, gamma, k, z, &phiz, &dz, &ddz);
    /* the law's change: over a short move the integral of phi' by the corrected trapezoid
       (Euler-Maclaurin, error dv^5 phi''''''/720), whose digits are the change's own; the
       difference of the potentials, which loses them, over a long one */
    if (PetscAbsReal(dv) < ADH_SHORT_MOVE * range) dphi = 0.5 * dv * (dz + dv_) - dv * dv / 12.0 * (ddv - ddz);
    else dphi = phiv - phiz;
    e += 0.5 * dv * PetscRealPart(pa[k] + oa[k]) + dphi + pbar * dv;
  }
  PetscCall(VecRestoreArrayRead(m->pold, &oa));
  PetscCall(VecRestoreArrayRead(m->pel, &pa));
  PetscCall(VecRestoreArrayRead(m->z, &za));
  PetscCall(VecRestoreArrayRead(m->v, &va));
  PetscCall(MPIU_Allreduce(&e, dE, 1, MPIU_REAL, MPIU_SUM, s->comm));
  PetscFunctionReturn(0);
}

/* The points held at the wall (gap 0 and the gradient, less the mean-gap multiplier mu, pushing
   into it), the multiplier over the other points (fixmean; 0 otherwise), and the projection rp of
   the gradient on the free points (with fixmean, mean-free over them); *changed counts the points
   whose status changed. */
static PetscErrorCode Project(AdhSolver s, PetscBool fixmean, PetscReal *mu, PetscInt *changed)
{
  AdhMinimizer       m = s->minimizer;
  const PetscScalar *va, *ra;
  PetscScalar       *pa;
  PetscReal          sums[2];
  PetscInt           ch = 0;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(m->v, &va));
  PetscCall(VecGetArrayRead(m->r, &ra));
  *mu = 0.0;
  if (fixmean) { /* the multiplier over the points off the wall first, then over every free point */
    for (PetscInt pass = 0; pass < 2; pass++) {
      sums[0] = sums[1] = 0.0;
      for (PetscInt k = 0; k < m->n; k++) {
        const PetscBool held = (PetscBool)(OnSurface(m, k) && PetscRealPart(va[k]) <= 0 && (pass == 0 || PetscRealPart(ra[k]) - *mu >= 0));
        if (held) continue;
        sums[0] += PetscRealPart(ra[k]);
        sums[1] += 1.0;
      }
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 2, MPIU_REAL, MPIU_SUM, s->comm));
      *mu = sums[1] > 0 ? sums[0] / sums[1] : 0.0;
    }
  }
  PetscCall(VecGetArrayWrite(m->rp, &pa));
  for (PetscInt k = 0; k < m->n; k++) {
    const char held = (char)(OnSurface(m, k) && PetscRealPart(va[k]) <= 0 && PetscRealPart(ra[k]) - *mu >= 0);
    if (held != m->active[k]) ch++;
    m->active[k] = held;
    pa[k]        = held ? 0.0 : ra[k] - *mu;
  }
  PetscCall(VecRestoreArrayWrite(m->rp, &pa));
  PetscCall(VecRestoreArrayRead(m->r, &ra));
  PetscCall(VecRestoreArrayRead(m->v, &va));
  PetscCall(MPIU_Allreduce(&ch, changed, 1, MPIU_INT, MPI_SUM, s->comm));
  PetscFunctionReturn(0);
}

/* x = 0 at the held points, and with fixmean mean-free over the others. */
static PetscErrorCode RestrictToFree(AdhSolver s, PetscBool fixmean, Vec x)
{
  AdhMinimizer m = s->minimizer;
  PetscScalar *xa;
  PetscReal    sums[2] = {0.0, 0.0}, mean;

  PetscFunctionBegin;
  PetscCall(VecGetArray(x, &xa));
  for (PetscInt k = 0; k < m->n; k++) {
    if (m->active[k]) xa[k] = 0.0;
    else {
      sums[0] += PetscRealPart(xa[k]);
      sums[1] += 1.0;
    }
  }
  if (fixmean) {
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 2, MPIU_REAL, MPIU_SUM, s->comm));
    mean = sums[1] > 0 ? sums[0] / sums[1] : 0.0;
    for (PetscInt k = 0; k < m->n; k++)
      if (!m->active[k]) xa[k] -= mean;
  }
  PetscCall(VecRestoreArray(x, &xa));
  PetscFunctionReturn(0);
}

/* A direction that moves no point into the wall: t = 0 at the points at the wall it pushes into
   it (a preconditioned direction may, at a point the gradient pulls away), and with fixmean t
   mean-free again by a shift of the points off the wall. */
static PetscErrorCode KeepOffWall(AdhSolver s, PetscBool fixmean, Vec t)
{
  AdhMinimizer       m = s->minimizer;
  const PetscScalar *va;
  PetscScalar       *ta;
  PetscReal          sums[2] = {0.0, 0.0}, shift;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(m->v, &va));
  PetscCall(VecGetArray(t, &ta));
  for (PetscInt k = 0; k < m->n; k++) {
    if (OnSurface(m, k) && PetscRealPart(va[k]) <= 0 && PetscRealPart(ta[k]) < 0) ta[k] = 0.0;
    sums[0] += PetscRealPart(ta[k]);
    if (PetscRealPart(va[k]) > 0) sums[1] += 1.0;
  }
  if (fixmean) {
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 2, MPIU_REAL, MPIU_SUM, s->comm));
    shift = sums[1] > 0 ? sums[0] / sums[1] : 0.0;
    for (PetscInt k = 0; k < m->n; k++)
      if (PetscRealPart(va[k]) > 0) ta[k] -= shift;
  }
  PetscCall(VecRestoreArray(t, &ta));
  PetscCall(VecRestoreArrayRead(m->v, &va));
  PetscFunctionReturn(0);
}

/* The slope and curvature along t at step a of the energy's model: the elastic part exact,
   a (t.pel) + a^2 (t.q)/2, the law's at the gaps v + a t (continued linearly below the wall). */
static PetscErrorCode Slope(AdhSolver s, const PetscScalar *gamma, const PetscReal tr0, const PetscReal tq, PetscReal a, const PetscScalar *va, const PetscScalar *ta, PetscReal *slope, PetscReal *curv)
{
  AdhMinimizer m = s->minimizer;
  PetscReal    sc[2] = {0.0, 0.0};

  PetscFunctionBegin;
  for (PetscInt k = 0; k < m->n; k++) {
    const PetscReal t = PetscRealPart(ta[k]), v = PetscRealPart(va[k]);
    PetscReal       phi, dphi0, ddphi0, dphi, ddphi, x;
    if (t == 0) continue;
    x = v + a * t;
    Law(s, gamma, k, v, &phi, &dphi0, &ddphi0);
    /* below the wall the law goes on linearly: the projection puts the point at the wall, where
       it holds the law's attraction at contact (the exponential's largest; the 9-3 law's none) */
    Law(s, gamma, k, PetscMax(x, 0.0), &phi, &dphi, &ddphi);
    if (x < 0) ddphi = 0.0;
    sc[0] += t * (dphi - dphi0); /* tr0 holds t.(pel + phi'(v) + pbar) */
    sc[1] += t * t * ddphi;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sc, 2, MPIU_REAL, MPIU_SUM, s->comm));
  *slope = tr0 + a * tq + sc[0];
  *curv  = tq + sc[1];
  PetscFunctionReturn(0);
}

/* The step along t: the first minimum of the model along it, bracketed from the Newton step and
   found by regula falsi (Illinois) on the slope, to a tenth of the slope at 0. */
static PetscErrorCode LineSearch(AdhSolver s, const PetscScalar *gamma, PetscReal tr0, PetscReal tq, PetscReal *alpha)
{
  AdhMinimizer       m = s->minimizer;
  const PetscScalar *va, *ta;
  PetscReal          a = 0.0, fa = tr0, b, fb, c0, curv, x, fx;
  PetscInt           side = 0;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(m->v, &va));
  PetscCall(VecGetArrayRead(m->t, &ta));
  PetscCall(Slope(s, gamma, tr0, tq, 0.0, va, ta, &fa, &c0));
  /* the Newton step, or without curvature along t (a concave law, a uniform t) one that moves the
     fastest gap by the law's range */
  if (c0 > 0) b = -tr0 / c0;
  else if (tq > 0) b = -tr0 / tq;
  else {
    PetscReal tmax;
    PetscCall(VecNorm(m->t, NORM_INFINITY, &tmax));
    b = (s->crops.zone_gap && m->dgamma > 0 ? s->crops.zone_gap(s->crops.data, m->dgamma) : 1.0) / tmax;
  }
  PetscCall(Slope(s, gamma, tr0, tq, b, va, ta, &fb, &curv));
  for (PetscInt k = 0; fb < 0 && k < 60; k++) { /* still going down: further */
    a  = b;
    fa = fb;
    b *= 2.0;
    PetscCall(Slope(s, gamma, tr0, tq, b, va, ta, &fb, &curv));
  }
  x = b;
  if (fb > 0 && PetscAbsReal(fb) > 0.1 * PetscAbsReal(tr0)) {
    for (PetscInt k = 0; k < 60; k++) {
      x = (a * fb - b * fa) / (fb - fa);
      PetscCall(Slope(s, gamma, tr0, tq, x, va, ta, &fx, &curv));
      if (PetscAbsReal(fx) <= 0.1 * PetscAbsReal(tr0)) break;
      if (fx < 0) {
        a  = x;
        fa = fx;
        if (side == -1) fb *= 0.5;
        side = -1;
      } else {
        b  = x;
        fb = fx;
        if (side == 1) fa *= 0.5;
        side = 1;
      }
    }
  }
  PetscCall(VecRestoreArrayRead(m->t, &ta));
  PetscCall(VecRestoreArrayRead(m->v, &va));
  *alpha = x;
  PetscFunctionReturn(0);
}

/* v = the projection of y onto the gaps allowed: max(y, 0), and with fixmean the mean gap mean
   too (max(y - tau, 0), tau by Michelot's finite iteration); *clamped: some point was held at 0
   or shifted unevenly (the elastic pressure must be computed again). */
static PetscErrorCode ProjectOntoBound(AdhSolver s, PetscBool fixmean, PetscReal mean, Vec y, PetscBool *clamped)
{
  AdhMinimizer m = s->minimizer;
  PetscScalar *ya;
  PetscReal    tau = 0.0, N = (PetscReal)s->grid->Nx * s->grid->Ny;
  PetscInt     neg = 0;

  PetscFunctionBegin;
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt k = 0; k < m->n; k++)
    if (OnSurface(m, k) && PetscRealPart(ya[k]) < 0) neg++;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &neg, 1, MPIU_INT, MPI_SUM, s->comm));
  /* with nothing below the wall the mean is right (the directions are mean-free): a shift by
     the rounding would lift the points at the wall off it */
  if (fixmean && neg) {
    PetscReal in = -1;
    for (PetscInt it = 0;; it++) { /* the count of points above tau falls at each pass: at most N passes */
      PetscReal sums[2] = {0.0, 0.0};
      for (PetscInt k = 0; k < m->n; k++)
        if (it == 0 || PetscRealPart(ya[k]) > tau) {
          sums[0] += PetscRealPart(ya[k]);
          sums[1] += 1.0;
        }
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 2, MPIU_REAL, MPIU_SUM, s->comm));
      tau = (sums[0] - N * mean) / sums[1];
      if (sums[1] == in) break;
      in = sums[1];
    }
  }
  if (neg)
    for (PetscInt k = 0; k < m->n; k++) {
      const PetscReal x = PetscRealPart(ya[k]) - tau;
      if (OnSurface(m, k)) ya[k] = x > 0 ? x : 0.0;
    }
  PetscCall(VecRestoreArray(y, &ya));
  *clamped = (PetscBool)(neg > 0);
  PetscFunctionReturn(0);
}

/* The Newton direction. Far from the wall's changes the energy is smooth, and the compliance
   preconditions its elastic part exactly; the conjugate gradient of the nonlinear problem loses
   its conjugacy wherever the law's curvature changes along the path (half its iterations restart,
   docs/theory/minimisation.md), so the direction is instead an inexact Newton step: the Hessian
   on the free points, H = S + phi''(v), solved by CG with the same preconditioner, to a relative
   residual min(1/2, sqrt(rel)) (Eisenstat and Walker's choice 2 in the spirit, which measured
   cheaper than 0.1 or 0.01). Where the law's concave part makes H indefinite, CG follows the
   direction of negative curvature to the edge of a trust region (Steihaug's KSPSTCG), whose
   radius is -adh_minimize_trust_region times the last step's length (Euclidean in the gaps;
   none at a minimisation's first step and after a stall: there, and with the option 0, CG stops
   with the iterate so far, Nash's truncation); either is a descent direction, and the line search is the one the
   gradient's directions take, so the branch is followed the same way. The soft directions the
   edge of the zone moves along are where H turns indefinite; stopping there cost Maugis' sphere at
   lambda 3 a fifth more FFT pairs (docs/theory/minimisation.md). */

/* y = P (S x + phi''(v) x), P the restriction to the free points (and mean-free with fixmean). */
static PetscErrorCode HessianMult(Mat H, Vec x, Vec y)
{
  AdhSolver          s;
  AdhMinimizer       m;
  const PetscScalar *va, *xa;
  PetscScalar       *ya;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(H, &s));
  m = s->minimizer;
  PetscCall(ApplyMeanFree(s, m->S, x, y));
  PetscCall(VecGetArrayRead(m->v, &va));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt k = 0; k < m->n; k++) {
    PetscReal phi, dphi, ddphi;
    Law(s, m->hgamma, k, PetscMax(PetscRealPart(va[k]), 0.0), &phi, &dphi, &ddphi);
    ya[k] += ddphi * xa[k];
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArrayRead(m->v, &va));
  PetscCall(RestrictToFree(s, m->hfixmean, y));
  PetscFunctionReturn(0);
}

/* y = P K P x, the gradient's preconditioner on the free points (-adh_minimize_pc none: P x). */
static PetscErrorCode PreconditionFree(AdhSolver s, const PetscScalar *gamma, PetscBool force, PetscBool fixmean, Vec x, Vec y)
{
  PetscFunctionBegin;
  if (s->minimize_pc) PetscCall(Precondition(s, gamma, force, x, y));
  else PetscCall(VecCopy(x, y));
  PetscCall(RestrictToFree(s, fixmean, y));
  PetscFunctionReturn(0);
}

static PetscErrorCode HessianPC(PC pc, Vec x, Vec y)
{
  AdhSolver    s;
  AdhMinimizer m;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &s));
  m = s->minimizer;
  PetscCall(PreconditionFree(s, m->hgamma, m->hforce, m->hfixmean, x, y));
  PetscFunctionReturn(0);
}

/* t: the inexact Newton direction, H t = -rp to rtol on the free points; *its the inner
   iterations. KSPSTCG follows a direction of negative curvature to the trust region's edge, or
   without one (radius 0) stops before it (KSPCG does not at its first iteration: it would step
   uphill); one at the first iteration without a region leaves t = 0, and then the direction is
   the preconditioned gradient, CG's own first. */
static PetscErrorCode NewtonDirection(AdhSolver s, const PetscScalar *gamma, PetscBool fixmean, PetscBool force, PetscReal rtol, PetscInt *its)
{
  AdhMinimizer       m = s->minimizer;
  KSPConvergedReason reason;
  PetscReal          tn;

  PetscFunctionBegin;
  if (!m->ksp) {
    PC pc;
    PetscCall(MatCreateShell(s->comm, m->n, m->n, PETSC_DETERMINE, PETSC_DETERMINE, s, &m->H));
    PetscCall(MatShellSetOperation(m->H, MATOP_MULT, (void (*)(void))HessianMult));
    char prefix[256];
    PetscCall(KSPCreate(s->comm, &m->ksp));
    PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%sadh_minimize_", s->prefix ? s->prefix : "")); /* a solve's -ksp_view and the like are not this KSP's */
    PetscCall(KSPSetOptionsPrefix(m->ksp, prefix));
    PetscCall(KSPSetType(m->ksp, KSPSTCG)); /* CG within a trust region (radius 0: none, and it stops at negative curvature, even on its first iteration, as KSPCG does not) */
    PetscCall(KSPSetOperators(m->ksp, m->H, m->H));
    PetscCall(KSPGetPC(m->ksp, &pc));
    PetscCall(PCSetType(pc, PCSHELL));
    PetscCall(PCShellSetContext(pc, s));
    PetscCall(PCShellSetApply(pc, HessianPC));
    PetscCall(PCShellSetName(pc, "the compliance on the free points"));
    PetscCall(KSPSetNormType(m->ksp, KSP_NORM_NATURAL)); /* r.z, which CG computes anyway */
  }
  m->hgamma   = gamma;
  m->hfixmean = fixmean;
  m->hforce   = force;
  PetscCall(KSPSetTolerances(m->ksp, rtol, 0.0, PETSC_DEFAULT, ADH_NEWTON_MAX_CG));
  PetscCall(VecAXPBY(m->z, -1.0, 0.0, m->rp));
  if (s->minimize_pc) PetscCall(CurvatureScaling(s, gamma, &m->wscaled)); /* once for the solve, not at every iteration */
  m->wheld = s->minimize_pc;
  PetscCall(KSPCGSetRadius(m->ksp, m->radius));
  PetscCall(KSPSolve(m->ksp, m->z, m->t));
  PetscCall(KSPCGGetNormD(m->ksp, &m->normd));
  m->wheld = PETSC_FALSE;
  PetscCall(KSPGetConvergedReason(m->ksp, &reason));
  PetscCall(KSPGetIterationNumber(m->ksp, its));
  PetscCall(VecNorm(m->t, NORM_2, &tn));
  if (!(tn > 0)) PetscCall(PreconditionFree(s, gamma, force, fixmean, m->z, m->t));
  if (s->minimize_monitor) PetscCall(PetscPrintf(s->comm, "         Newton direction: %" PetscInt_FMT " conjugate gradient iterations, %s\n", *its, KSPConvergedReasons[reason]));
  PetscFunctionReturn(0);
}

/* The minimum at d = target, or (force) under the force target on a periodic cell; hold: the
   solver's contact set is the start's (s->p's). */
static PetscErrorCode MinimizeAt(AdhSolver s, PetscBool force, PetscReal target, PetscBool hold, PetscBool *none)
{
  const PetscBool    fixmean = (PetscBool)(!force && s->boundary == ADH_BOUNDARY_PERIODIC); /* a periodic cell's mean gap is held by d */
  const PetscReal    N = (PetscReal)s->grid->Nx * s->grid->Ny, cell = s->grid->Lx * s->grid->Ly;
  const PetscReal    pbar = force ? target / cell : 0.0;
  const PetscScalar *gamma = NULL;
  AdhMinimizer       m;
  PetscScalar        sum;
  PetscReal          mu = 0.0, mean = s->mean_h - target, zrp_old = 0.0, rel = 1.0, scale;
  PetscInt           it, changed, since_exact = 0, restarts = 0, stalls = 0, cg_its = 0;
  PetscBool          clamped, restart = PETSC_TRUE, steepest = PETSC_FALSE, down = PETSC_FALSE, stalled = PETSC_FALSE, stop = PETSC_FALSE;
  PetscInt           failed = 0; /* 1: the iteration limit, 2: a stall down the gradient */

  PetscFunctionBegin;
  *none = PETSC_FALSE;
  if (!s->minimizer) PetscCall(Create(s));
  m = s->minimizer;
  m->radius = 0.0; /* a minimisation's first Newton step: no trust region */
  if (s->gamma_field && m->surface) { /* the field on the variables, none on the padding */
    if (!m->gamma) PetscCall(VecDuplicate(m->v, &m->gamma));
    PetscCall(Move(s, s->gamma_field, m->gamma, 0.0, PETSC_FALSE));
  }
  m->dgamma = s->gamma;
  if (s->gamma_field) PetscCall(VecMax(s->gamma_field, NULL, &m->dgamma));
  if (s->gamma_field) PetscCall(VecGetArrayRead(m->surface ? m->gamma : s->gamma_field, &gamma));
  /* from the last state's pressure (a force control's trial may have gone back to it): its
     displacement C p and the gaps v = u + h - d at the new d, the surfaces moved rigidly (under a
     force d is the output, and u = v - b is mean-free either way on a periodic cell) */
  if (!force) s->d = target;
  PetscCall(VecCopy(s->h, s->g));
  PetscCall(VecShift(s->g, -s->d));
  PetscCall(Move(s, s->g, m->b, 0.0, PETSC_FALSE));
  PetscCall(Move(s, s->p, m->work, 0.0, PETSC_FALSE));
  PetscCall(ApplyMeanFree(s, m->C, m->work, m->v));
  PetscCall(VecAXPY(m->v, 1.0, m->b));
  if (hold && s->npoints) { /* the last state's contact stays at the wall: pulled back, the rigid
                               move would lift it all off, to be found again point by point (on
                               Maugis' sphere at lambda 2 a tenth of the FFT pairs); s->g is free
                               until the state is written */
    const PetscScalar *za;
    PetscScalar       *ga, *va;
    PetscReal          sums[2] = {0.0, 0.0}; /* the contact's gaps given up, the points left */
    PetscCall(VecGetArrayWrite(s->g, &ga));
    for (PetscInt k = 0; k < s->nlocal; k++) ga[k] = s->in_set[k] ? 1.0 : 0.0;
    PetscCall(VecRestoreArrayWrite(s->g, &ga));
    PetscCall(Move(s, s->g, m->z, 0.0, PETSC_FALSE));
    PetscCall(VecGetArrayRead(m->z, &za));
    PetscCall(VecGetArray(m->v, &va));
    for (PetscInt k = 0; k < m->n; k++) {
      if (PetscRealPart(za[k]) > 0) {
        sums[0] += PetscRealPart(va[k]);
        va[k] = 0.0;
      } else sums[1] += 1.0;
    }
    if (fixmean) { /* the mean gap kept: what the contact gave up spread over the rest (the
                      projection below takes any point it puts under the wall) */
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 2, MPIU_REAL, MPIU_SUM, s->comm));
      for (PetscInt k = 0; k < m->n && sums[1] > 0; k++)
        if (!(PetscRealPart(za[k]) > 0)) va[k] += sums[0] / sums[1];
    }
    PetscCall(VecRestoreArray(m->v, &va));
    PetscCall(VecRestoreArrayRead(m->z, &za));
  }
  PetscCall(ProjectOntoBound(s, fixmean, mean, m->v, &clamped));
  PetscCall(PetscArrayzero(m->active, m->n));
  PetscCall(ElasticPressure(s));
  PetscCall(Gradient(s, gamma, pbar));
  scale = 0.0;
  if (s->crops.peak && s->adhesive && m->dgamma > 0) scale = s->crops.peak(s->crops.data, m->dgamma);
  for (it = 0;; it++) {
    PetscReal rpn, pn, tr0, tq, alpha, zrp, beta = 0.0;
    PetscInt  restarts0;
    PetscScalar dot;
    const PetscBool newton = (PetscBool)(s->minimize_newton && !steepest); /* this iteration's direction a Newton step */

    PetscCall(AdhSolverStopRequested_Private(s, &stop));
    if (stop) break;
    PetscCall(Project(s, fixmean, &mu, &changed));
    /* the measure: the projected gradient against the pressure field (elastic plus mean) */
    PetscCall(VecNorm(m->rp, NORM_2, &rpn));
    PetscCall(VecCopy(m->pel, m->work));
    PetscCall(VecShift(m->work, force ? pbar : -mu));
    PetscCall(VecNorm(m->work, NORM_2, &pn));
    pn  = PetscMax(pn, 1e-12 * PetscSqrtReal(N) * scale);
    rel = pn > 0 ? rpn / pn : 0.0;
    if (rel <= s->minimize_rtol) {
      if (since_exact == 0) break;
      PetscCall(ElasticPressure(s)); /* the updated pressure has drifted: confirm on an exact one */
      PetscCall(Gradient(s, gamma, pbar));
      since_exact = 0;
      continue;
    }
    if (force && s->crops.zone_gap) { /* no minimum under this force: the bodies fly apart */
      PetscReal vmin;
      PetscCall(VecMin(m->v, NULL, &vmin));
      if (m->dgamma > 0 && vmin > ADH_RUNAWAY * s->crops.zone_gap(s->crops.data, m->dgamma)) {
        *none = PETSC_TRUE;
        break;
      }
    }
    if (it >= s->minimize_max_it) {
      failed = 1;
      break;
    }
    /* the direction: the Newton step on the free points, or the preconditioned projected gradient
       conjugated unless the held points changed; after a stall, the gradient itself */
    if (newton) {
      PetscInt cg;
      PetscCall(NewtonDirection(s, gamma, fixmean, force, PetscMin(0.5, PetscSqrtReal(rel)), &cg));
      cg_its += cg;
      zrp = 0.0; /* nothing to conjugate (a switch to Polak-Ribiere comes only after a stall, which restarts it) */
    } else {
      if (!steepest) PetscCall(PreconditionFree(s, gamma, force, fixmean, m->rp, m->z));
      else PetscCall(VecCopy(m->rp, m->z));
      PetscCall(VecDot(m->z, m->rp, &dot));
      zrp = PetscRealPart(dot);
      if (changed || restart) beta = 0.0;
      else {
        PetscCall(VecDot(m->z, m->rpold, &dot));
        beta = PetscMax(0.0, (zrp - PetscRealPart(dot)) / zrp_old);
      }
      if (beta > 0) PetscCall(VecAYPX(m->t, beta, m->z));
      else PetscCall(VecCopy(m->z, m->t));
      PetscCall(VecScale(m->t, -1.0));
      if (beta > 0) PetscCall(RestrictToFree(s, fixmean, m->t));
    }
    PetscCall(KeepOffWall(s, fixmean, m->t));
    PetscCall(VecDot(m->t, m->r, &dot));
    tr0       = PetscRealPart(dot);
    restarts0 = restarts;
    if (!(tr0 < 0)) { /* not downhill: the steepest descent, which pulls every free point at the wall away */
      PetscCall(VecAXPBY(m->t, -1.0, 0.0, m->rp));
      PetscCall(KeepOffWall(s, fixmean, m->t));
      PetscCall(VecDot(m->t, m->r, &dot));
      tr0 = PetscRealPart(dot);
      restarts++;
    }
    zrp_old = zrp;
    down = (PetscBool)(steepest || (!s->minimize_newton && !s->minimize_pc && beta == 0) || restarts > restarts0); /* down the gradient: a stall now is the end */
    restart  = PETSC_FALSE;
    steepest = PETSC_FALSE;
    /* the step: the elastic part along t is quadratic, S t gives it */
    PetscCall(ApplyMeanFree(s, m->S, m->t, m->q));
    PetscCall(VecDot(m->t, m->q, &dot));
    tq = PetscRealPart(dot);
    PetscCall(LineSearch(s, gamma, tr0, tq, &alpha));
    /* the step, projected; shorter while the projection undoes the descent (the energy's change
       is taken from the differences, exact where the energy itself has no digits left) */
    PetscCall(VecCopy(m->v, m->z)); /* z: the gaps before, pold: their elastic pressure */
    PetscCall(VecCopy(m->pel, m->pold));
    stalled = PETSC_FALSE;
    for (PetscInt half = 0;; half++) {
      PetscReal dE;
      PetscCall(VecWAXPY(m->v, alpha, m->t, m->z));
      PetscCall(ProjectOntoBound(s, fixmean, mean, m->v, &clamped));
      if (clamped) PetscCall(ElasticPressure(s));
      else PetscCall(VecWAXPY(m->pel, alpha, m->q, m->pold));
      PetscCall(EnergyChange(s, gamma, pbar, &dE));
      if (dE <= 0) break;
      if (half == ADH_MAX_HALVINGS) { /* no descent along t: stay, and go down the gradient next */
        PetscCall(VecCopy(m->z, m->v));
        PetscCall(VecCopy(m->pold, m->pel));
        if (down) failed = 2;
        stalled = PETSC_TRUE;
        stalls++;
        restart = steepest = PETSC_TRUE;
        break;
      }
      alpha *= 0.5;
    }
    if (newton && restarts == restarts0) m->radius = stalled ? 0.0 : s->minimize_trust * alpha * m->normd; /* the next Newton step's region: the option times the step taken (none after a stall) */
    if (s->minimize_monitor) {
      char conj[64] = "";
      if (!s->minimize_newton) PetscCall(PetscSNPrintf(conj, sizeof(conj), ", beta %.3g", (double)beta));
      PetscCall(PetscPrintf(s->comm, "    %4" PetscInt_FMT " relative projected gradient %.6e, step %.3e%s, %" PetscInt_FMT " points changed at the wall%s\n", it, (double)rel, (double)alpha, clamped ? " (projected)" : "", changed, conj));
    }
    if (failed) break;
    if (!stalled) since_exact = clamped ? 0 : since_exact + 1; /* a stall went back to the pressure before */
    PetscCall(Gradient(s, gamma, pbar));
    if (since_exact >= 50) { /* updates drift: recompute now and then */
      PetscCall(ElasticPressure(s));
      PetscCall(Gradient(s, gamma, pbar));
      since_exact = 0;
    }
    PetscCall(VecCopy(m->rp, m->rpold)); /* the previous projected gradient, for Polak-Ribiere */
    if (clamped) restart = PETSC_TRUE;
  }
  if (gamma) PetscCall(VecRestoreArrayRead(m->surface ? m->gamma : s->gamma_field, &gamma));
  if (stop) PetscFunctionReturn(0); /* a signal asks every rank to stop: the step is abandoned (stop_signal says so) */
  PetscCheck(failed != 1, s->comm, PETSC_ERR_NOT_CONVERGED, "The energy minimisation of %s %g stopped at %" PetscInt_FMT " iterations (-adh_minimize_max_it) with a relative projected gradient %g (-adh_minimize_rtol %g)", force ? "the force" : "d =", (double)target, it, (double)rel, (double)s->minimize_rtol);
  PetscCheck(failed != 2, s->comm, PETSC_ERR_NOT_CONVERGED, "The energy minimisation of %s %g stalled at a relative projected gradient %g (-adh_minimize_rtol %g): no step down the gradient lowers the energy", force ? "the force" : "d =", (double)target, (double)rel, (double)s->minimize_rtol);
  /* the state: the gaps, the pressure (elastic plus mean), the contact set where the gap is 0 */
  PetscCall(Move(s, s->g, m->v, 0.0, PETSC_TRUE));
  PetscCall(Move(s, s->p, m->pel, 0.0, PETSC_TRUE));
  PetscCall(VecShift(s->p, force ? pbar : -mu));
  if (force) { /* d follows: the mean gap is mean(h) - d */
    PetscCall(VecSum(s->g, &sum));
    s->d = s->mean_h - PetscRealPart(sum) / N;
  }
  { /* and off the wall, where the law pulls with nothing (beyond its support, or on a stage
       without adhesion), no traction: the elastic pressure there is the residual gradient (within
       -adh_minimize_rtol of the field), dropped so that the pressure field is 0 off the contact and
       the zone, as on a set's route */
    const PetscScalar *ga, *gf = NULL;
    PetscScalar       *pa;
    PetscCall(VecGetArrayRead(s->g, &ga));
    PetscCall(VecGetArray(s->p, &pa));
    if (s->gamma_field) PetscCall(VecGetArrayRead(s->gamma_field, &gf));
    for (PetscInt k = 0; k < s->nlocal; k++) {
      const PetscReal g = PetscRealPart(ga[k]), dg = !s->adhesive ? 0.0 : gf ? PetscRealPart(gf[k]) : s->gamma;
      PetscReal       phi = 0.0, dphi = 0.0, ddphi = 0.0;
      s->in_set[k] = (char)(g <= 0);
      if (s->in_set[k]) continue;
      if (dg > 0) s->crops.law(s->crops.data, dg, g, &phi, &dphi, &ddphi);
      if (dphi == 0) pa[k] = 0.0;
    }
    if (gf) PetscCall(VecRestoreArrayRead(s->gamma_field, &gf));
    PetscCall(VecRestoreArray(s->p, &pa));
    PetscCall(VecRestoreArrayRead(s->g, &ga));
  }
  PetscCall(AdhSolverRebuildSet_Private(s));
  s->gap_current = PETSC_TRUE;
  /* the cost in the curve: Newton steps as the outer iterations and their conjugate gradients' as
     the Krylov ones, as a set's route counts its updates and KSP iterations */
  s->step_outer += s->minimize_newton ? it : 1;
  s->step_ksp += s->minimize_newton ? cg_its : it;
  m->its_total += it;
  m->cg_total += cg_its;
  m->states++;
  PetscCall(PetscInfo(s, "%s %g: energy minimised in %" PetscInt_FMT " iterations (%" PetscInt_FMT " not downhill, %" PetscInt_FMT " stalled), relative projected gradient %g, %" PetscInt_FMT " points at the wall\n", force ? "the force" : "d =", (double)target, it, restarts, stalls, (double)rel, s->npoints));
  PetscFunctionReturn(0);
}


/* The force the current state carries, and whether the bodies have come apart (no gap within the
   law's zone: nothing attracts them any more). */
static PetscErrorCode ForceOf(AdhSolver s, PetscReal zone, PetscReal *F, PetscBool *apart)
{
  PetscScalar sum;
  PetscReal   gmin;

  PetscFunctionBegin;
  PetscCall(VecSum(s->p, &sum));
  *F = PetscRealPart(sum) * s->grid->hx * s->grid->hy;
  PetscCall(VecMin(s->g, NULL, &gmin));
  *apart = (PetscBool)(gmin > zone);
  PetscFunctionReturn(0);
}

/* One trial of the free boundary's force control: the minimum at d reached from the pressure
   `from` (a state at a d on the step's side of this one, so that the trials walk along the branch
   as displacement steps would), its force and whether the bodies came apart. */
static PetscErrorCode TrialAt(AdhSolver s, Vec from, PetscReal d, PetscReal zone, PetscReal *F, PetscBool *apart)
{
  PetscBool none;

  PetscFunctionBegin;
  PetscCall(VecCopy(from, s->p));
  PetscCall(MinimizeAt(s, PETSC_FALSE, d, PETSC_FALSE, &none));
  AdhSolverReturnIfStopped_Private(s);
  PetscCall(ForceOf(s, zone, F, apart));
  PetscFunctionReturn(0);
}

/* A free boundary's force-control trial moves d by at most this share of the law's zone gap where
   the branch's force turns back (five times it where it gains, and where it keeps falling away
   past the turn): the steps of a
   displacement-controlled path of some hundred states, fine enough that the march does not step
   over the branch's largest tension (the force is flat there, its error of the second order in
   the move). */
#define ADH_FORCE_MOVE 0.02
/* The bodies let go within this share of the zone gap between the last state on the branch and
   the first trial that came apart: the pull-off's d to that, its force far finer than the
   control's bisection asks. */
#define ADH_FORCE_APART 1e-6

/* The walk's state furthest towards T, refined: the vertex of the parabola in d through it (x2,
   r2, r the shortfall from T; its pressure m->pbest) and the accepted states either side (x1, its
   pressure m->plo, and x3), a trial there from the state before it in the walk's direction (so
   that the trials follow the branch as the walk's own), until the shortfall changes by less than
   tol (a few times; the walk's moves leave an error of the second order in them, the vertex one
   of the third). A vertex that carries T (r <= tol) ends it: *xT is its d, *rT its shortfall, and
   for one past T (r < -tol) *xs, *rs the state it was tried from, whose pressure is *ps. */
static PetscErrorCode RefineWalkBest(AdhSolver s, PetscReal T, PetscReal dir, PetscReal zone, PetscReal tol, PetscReal x1, PetscReal r1, PetscReal *x2, PetscReal *r2, PetscReal x3, PetscReal r3, PetscBool *carries, PetscReal *xT, PetscReal *rT, PetscReal *xs, PetscReal *rs, Vec *ps)
{
  AdhMinimizer m = s->minimizer;

  PetscFunctionBegin;
  *carries = PETSC_FALSE;
  for (PetscInt k = 0; k < 4; k++) {
    const PetscReal a = (*x2 - x1) * (*r2 - r3), b = (*x2 - x3) * (*r2 - r1), den = a - b;
    PetscReal       xv, Fv, rv;
    PetscBool       apart, behind;

    if (!(PetscAbsReal(den) > 0)) break;
    xv = *x2 - 0.5 * ((*x2 - x1) * a - (*x2 - x3) * b) / den;
    if (!((xv - x1) * (xv - x3) < 0) || xv == *x2) break; /* strictly between the neighbours */
    behind = (PetscBool)((xv - x1) * (xv - *x2) < 0);      /* between x1 and x2: tried from x1's state */
    PetscCall(TrialAt(s, behind ? m->plo : m->pbest, xv, zone, &Fv, &apart));
    AdhSolverReturnIfStopped_Private(s);
    if (apart) break;
    rv = dir * (T - Fv);
    if (rv <= tol) { /* the branch carries T here, or passes it between the trial's start and here */
      *carries = PETSC_TRUE;
      *xT      = xv;
      *rT      = rv;
      *xs      = behind ? x1 : *x2;
      *rs      = behind ? r1 : *r2;
      *ps      = behind ? m->plo : m->pbest;
      break;
    }
    if (rv < *r2) {
      const PetscBool done = (PetscBool)(*r2 - rv <= tol);
      if (behind) { /* x2 becomes the far neighbour */
        x3 = *x2;
        r3 = *r2;
      } else { /* x2 the near one */
        x1 = *x2;
        r1 = *r2;
        PetscCall(VecCopy(m->pbest, m->plo));
      }
      *x2 = xv;
      *r2 = rv;
      PetscCall(VecCopy(s->p, m->pbest));
      if (done) break;
    } else {
      if (behind) {
        x1 = xv;
        r1 = rv;
        PetscCall(VecCopy(s->p, m->plo));
      } else {
        x3 = xv;
        r3 = rv;
      }
      if (rv - *r2 <= tol) break;
    }
  }
  PetscFunctionReturn(0);
}

/* Force control on the free boundary, whose padded minimisation has no mean mode to carry a force:
   the d on the step's branch at which the minimum carries the force T. From the step's state (d0,
   F0) it marches towards T, each trial a minimisation at a fixed d from the last one accepted
   (so the branch is followed as by displacement steps), by secant moves of at most 5
   ADH_FORCE_MOVE zone gaps, the first aimed by the branch's slope over the last walk that found
   its force (from this state or to it). Past T, regula falsi (Illinois) between the last two, each trial from
   the last one short of T. Where the branch's force turns back before T (a few points letting go
   at once), the march goes on through it: under the force the state snaps through to the next
   one that carries it, by moves that grow while the force keeps falling away. A trial that comes
   apart bounds the march: the moves halve towards it, and when the last state on the branch and
   the first apart are within ADH_FORCE_APART zone gaps (or the branch's largest force lies behind
   and the walk's steepest slope cannot reach it before the bodies let go) they let go before T
   is reached: none, and the control bisects the force for the pull-off,
   the largest tension the branch carries before the bodies come apart (each trial of it beyond the
   force a walk of the step found, m->walk, answered at once; short of it, the march starts towards
   that force's d). Where the refinement of a walk's largest force finds a state that carries T
   after all, that state is the answer, or the bracket from it (once: the march is not retried
   twice). */
static PetscErrorCode MinimizeForceFree(AdhSolver s, PetscReal T, PetscBool *none)
{
  AdhMinimizer m;
  PetscReal    dgamma = s->gamma, zone, F0, tol, dir, xa, ra, h, hmax, d, xapart = PETSC_MAX_REAL;
  PetscReal    x0, Ffound = 0.0, xbest, rbest, xlo = 0.0, rlo = 0.0, xhi = 0.0, rhi = 0.0; /* the walk's state nearest T, the accepted ones either side */
  PetscReal    steepest = 0.0; /* the largest |dF/dd| between the walk's accepted states */
  PetscBool    apart, found, fromwalk, haslo = PETSC_FALSE, hashi = PETSC_FALSE, jumped = PETSC_FALSE, rebracketed = PETSC_FALSE;
  PetscInt     receding = 0; /* the walk's accepted moves in a row along which the force fell away from T */
  Vec          pa; /* the last accepted trial's pressure (the step's own at first) */

  PetscFunctionBegin;
  *none = PETSC_FALSE;
  if (s->gamma_field) PetscCall(VecMax(s->gamma_field, NULL, &dgamma));
  if (!s->adhesive) dgamma = 0.0;
  if (!(dgamma > 0) && T < 0) { /* nothing holds the bodies under a tension */
    *none = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  /* the scale of the moves: the law's zone gap, or without adhesion an element */
  zone = dgamma > 0 ? s->crops.zone_gap(s->crops.data, dgamma) : PetscMin(s->grid->hx, s->grid->hy);
  if (!s->minimizer) PetscCall(Create(s));
  m = s->minimizer;
  if (!m->pforce) PetscCall(VecDuplicate(s->p, &m->pforce));
  if (!m->pbest) PetscCall(VecDuplicate(s->p, &m->pbest));
  if (!m->plo) PetscCall(VecDuplicate(s->p, &m->plo));
  pa = m->pforce;
  PetscCall(VecCopy(s->p, pa));
  xa = d = s->d;
  /* the step's state at d0, minimised: it need not be a minimum (a first touch starts from p = 0) */
  PetscCall(TrialAt(s, pa, xa, zone, &F0, &apart));
  AdhSolverReturnIfStopped_Private(s);
  PetscCall(VecCopy(s->p, pa));
  tol   = 10.0 * s->minimize_rtol * PetscMax(PetscMax(PetscAbsReal(T), PetscAbsReal(F0)), dgamma > 0 ? s->crops.peak(s->crops.data, dgamma) * s->grid->hx * s->grid->hy : 0.0);
  dir   = T > F0 ? 1.0 : -1.0; /* more force: press on (d up); less: pull (d down) */
  ra    = dir * (T - F0);      /* the shortfall, > 0 short of T */
  found = (PetscBool)(PetscAbsReal(ra) <= tol);
  if (found) Ffound = F0;
  /* from a state of a branch this step already walked until it came apart: beyond its largest force, none */
  fromwalk = (PetscBool)(m->walk.known && m->walk.step == s->step_id && dir == m->walk.dir && xa == m->walk.start && PetscAbsReal(F0 - m->walk.startF) <= tol);
  if (!fromwalk) m->walk.known = PETSC_FALSE;
  if (!found && fromwalk && dir * (T - m->walk.Fmax) > tol) {
    *none = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  x0    = xa;
  xbest = xa;
  rbest = ra;
  PetscCall(VecCopy(pa, m->pbest));
  hmax = ADH_FORCE_MOVE * zone;
  h    = hmax;
  if (fromwalk && dir * (m->walk.dmax - xa) > 0) h = PetscMin(dir * (m->walk.dmax - xa), 5.0 * hmax); /* towards the largest force's d, as far as a move goes */
  else if (m->slope_known && m->slope > 0 && ((xa == m->slope_to && PetscAbsReal(F0 - m->slope_Fto) <= tol) || (xa == m->slope_from && PetscAbsReal(F0 - m->slope_Ffrom) <= tol))) /* a walk on from the last one's state, or again from its start: aimed by its slope */
    h = PetscMax(PetscMin(ra / m->slope, 5.0 * hmax), 1e-3 * hmax);
again: /* a refinement of the walk's largest force found the branch past T: the bracket from there */
  for (PetscInt k = 0; !found && k < 100000; k++) {
    const PetscReal xb = xa + dir * h;
    PetscReal       Fb, rb;
    PetscCall(TrialAt(s, pa, xb, zone, &Fb, &apart));
    AdhSolverReturnIfStopped_Private(s);
    rb = dir * (T - Fb);
    if (!apart && PetscAbsReal(rb) <= tol) {
      d      = xb;
      Ffound = Fb;
      found  = PETSC_TRUE;
    } else if (!apart && rb < 0) { /* past T: regula falsi in (xa, xb), each trial from the last state short of T */
      PetscReal a = xa, fa = ra, b = xb, fb = rb;
      PetscInt  kept = 0;
      PetscBool jump = PETSC_FALSE;
      for (PetscInt j = 0; j < 200 && !found && !jump; j++) {
        const PetscReal c = (a * fb - b * fa) / (fb - fa);
        PetscReal       Fc, rc;
        PetscCall(TrialAt(s, pa, c, zone, &Fc, &apart));
        AdhSolverReturnIfStopped_Private(s);
        rc = apart ? -PetscAbsReal(fb) : dir * (T - Fc); /* apart inside: as past T */
        if (!apart && PetscAbsReal(rc) <= tol) {
          d      = c;
          Ffound = Fc;
          found  = PETSC_TRUE;
        } else if (PetscAbsReal(b - a) < 1e-12 * zone) jump = PETSC_TRUE; /* the force jumps across T here */
        else if (rc > 0) {
          a  = c;
          fa = rc;
          PetscCall(VecCopy(s->p, pa)); /* short of T: a state of the branch, the next trials' start */
          if (kept == 1) fb *= 0.5;
          kept = 1;
        } else {
          b  = c;
          fb = rc;
          if (kept == -1) fa *= 0.5;
          kept = -1;
        }
      }
      if (jump) { /* no state on this branch carries T: it snaps through to the state past the jump */
        PetscReal Fj;
        jumped = PETSC_TRUE; /* a walk of two branches: not one to remember */
        PetscCall(TrialAt(s, pa, b, zone, &Fj, &apart));
        AdhSolverReturnIfStopped_Private(s);
        if (apart) { /* past the jump the bodies are apart: they let go before T */
          *none = PETSC_TRUE;
          break;
        }
        PetscCall(VecCopy(s->p, pa)); /* and marches back to T on the new branch */
        xa = d = b;
        dir = -dir;
        receding = 0; /* the new branch's moves and slopes are its own */
        steepest = 0.0;
        ra  = dir * (T - Fj);
        h   = hmax;
        xapart = PETSC_MAX_REAL;
        continue;
      }
      PetscCheck(found, s->comm, PETSC_ERR_NOT_CONVERGED, "Force control on the free boundary: the trials' forces do not converge to %g", (double)T);
    } else if (!apart) { /* short still: on along the branch, by the secant where it gains, capped */
      const PetscReal gain = (ra - rb) / h;
      steepest = PetscMax(steepest, PetscAbsReal(gain));
      if (rb < rbest) { /* the walk's nearest to T yet, the state before it one neighbour */
        PetscCall(VecCopy(pa, m->plo));
        xlo   = xa;
        rlo   = ra;
        haslo = PETSC_TRUE;
        hashi = PETSC_FALSE;
        xbest = xb;
        rbest = rb;
        PetscCall(VecCopy(s->p, m->pbest));
      } else if (!hashi && xa == xbest) { /* the state after it, the other */
        xhi   = xb;
        rhi   = rb;
        hashi = PETSC_TRUE;
      }
      xa = d = xb;
      ra = rb;
      PetscCall(VecCopy(s->p, pa));
      receding = gain > 0 ? 0 : receding + 1;
      /* where it turns back, the short moves; once past the turn (three moves receding), moves that
         grow as the force keeps falling away, to the gaining moves' cap */
      h = gain > 0 ? PetscMax(PetscMin(1.5 * rb / gain, 5.0 * hmax), 1e-3 * hmax) : receding > 2 ? PetscMin(1.5 * h, 5.0 * hmax) : hmax;
      if (xapart < PETSC_MAX_REAL) h = PetscMin(h, 0.5 * PetscAbsReal(xapart - xa)); /* towards where the bodies let go */
    } else { /* apart: the march's bound; halfway to it from the same state */
      xapart = xb;
      h *= 0.5;
    }
    if (!found && xapart < PETSC_MAX_REAL && PetscAbsReal(xapart - xa) < ADH_FORCE_APART * zone) {
      *none = PETSC_TRUE; /* the bodies let go between the last state on the branch and xapart */
      break;
    }
    if (!found && !jumped && xapart < PETSC_MAX_REAL && haslo && hashi && xbest != xa && ra - 2.0 * steepest * PetscAbsReal(xapart - xa) > PetscMax(rbest, 0.0) + tol) {
      /* the branch's largest force lies behind, and even at twice the walk's steepest slope the
         states before xapart cannot come nearer T than it: where exactly they let go is moot */
      *none = PETSC_TRUE;
      break;
    }
  }
  PetscCheck(found || *none, s->comm, PETSC_ERR_NOT_CONVERGED, "Force control on the free boundary: no d found that carries the force %g", (double)T);
  if (*none && !jumped && (haslo && hashi ? PETSC_TRUE : (PetscBool)(xbest == xa && xapart < PETSC_MAX_REAL))) {
    /* the branch's largest force in dir's sense: between the walk's neighbours of its nearest
       state, refined; or where the bodies let go, just past the last state */
    PetscBool carries = PETSC_FALSE;
    PetscReal xT, rT, xs, rs;
    Vec       ps;
    if (haslo && hashi) PetscCall(RefineWalkBest(s, T, dir, zone, tol, xlo, rlo, &xbest, &rbest, xhi, rhi, &carries, &xT, &rT, &xs, &rs, &ps));
    AdhSolverReturnIfStopped_Private(s);
    if (carries && PetscAbsReal(rT) <= tol) { /* the refinement's trial carries T: the accepted state */
      *none  = PETSC_FALSE;
      found  = PETSC_TRUE;
      d      = xT;
      Ffound = T - dir * rT;
      m->walk.known = PETSC_FALSE;
    } else if (carries && !rebracketed) { /* past T: regula falsi between the state it was tried from and it */
      *none       = PETSC_FALSE;
      rebracketed = PETSC_TRUE;
      PetscCall(VecCopy(ps, pa));
      xa       = xs;
      ra       = rs;
      h        = dir * (xT - xs);
      xapart   = PETSC_MAX_REAL;
      haslo    = hashi = PETSC_FALSE;
      receding = 0;
      steepest = 0.0;
      m->walk.known = PETSC_FALSE;
      fromwalk = PETSC_FALSE;
      goto again;
    } else m->walk = (AdhForceWalk){PETSC_TRUE, s->step_id, dir, x0, F0, T - dir * rbest, xbest};
  } else if (found && fromwalk && !jumped && dir * (d - m->walk.dmax) <= 0 && dir * (Ffound - m->walk.Fmax) <= tol) { /* a state further along the remembered branch, short of its top */
    m->walk.start  = d;
    m->walk.startF = Ffound;
  } else m->walk.known = PETSC_FALSE;
  /* the slope that aims the next walk's first move: over this one, where it found T on one branch */
  m->slope_known = (PetscBool)(found && !jumped && d != x0);
  if (m->slope_known) {
    m->slope       = (Ffound - F0) / (d - x0);
    m->slope_from  = x0;
    m->slope_Ffrom = F0;
    m->slope_to    = d;
    m->slope_Fto   = Ffound;
  }
  /* found: the last trial is the accepted state; none: the control goes back to the step's */
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverMinimize_Private(AdhSolver s, PetscReal target, PetscBool *none)
{
  const PetscBool force = AdhSolverControlsForce_Private(s);

  PetscFunctionBegin;
  if (force && s->boundary == ADH_BOUNDARY_FREE) PetscCall(MinimizeForceFree(s, target, none));
  else PetscCall(MinimizeAt(s, force, target, PETSC_TRUE, none));
  AdhSolverReturnIfStopped_Private(s);
  s->law_apart = *none;
  PetscFunctionReturn(0);
}
