/* AdhSolver's life cycle: create, destroy, and the getters of what it holds. Options are read in
   solveropts.c, set-up in solversetup.c, one step in step.c and the load controls, the path in
   path.c, results in src/results/. */
#include "solver/solverimpl.h"

const char *const AdhStarts[]   = {"hertz", "adhesive", "AdhStart", "ADH_START_", NULL};
const char *const AdhAttaches[] = {"penetration", "reach", "griffith", "AdhAttach", "ADH_ATTACH_", NULL};

PetscErrorCode AdhSolverCreate(MPI_Comm comm, AdhSolver *solver)
{
  AdhSolver s;

  PetscFunctionBegin;
  PetscCall(AdhSolverInitializePackage());
  PetscCall(PetscNew(&s));
  s->comm                  = comm;
  s->boundary              = ADH_BOUNDARY_FREE;
  s->Estar                 = 1.0;
  s->gamma                 = 0.0;
  s->indenter.type         = ADH_INDENTER_SPHERE;
  s->indenter.radius       = 1.0;
  s->indenter.punch_radius = 0.25;
  s->indenter.cone_slope   = 0.1;
  PetscCall(PetscStrncpy(s->indenter.dataset, "h", sizeof(s->indenter.dataset)));
  PetscCall(PetscStrncpy(s->gamma_dataset, "gamma", sizeof(s->gamma_dataset)));
  s->start     = ADH_START_HERTZ;
  s->steps     = 10;
  s->max_outer = 100000;
  s->adhesive  = PETSC_TRUE;
  s->certify   = PETSC_TRUE;
  s->use_box   = PETSC_TRUE;
  s->pulloff_rtol     = 1e-3;
  s->cascade_local_rtol = 1e-3;
  s->criterion_radius = 16.0;
  s->criterion_radius_max = 64.0;
  s->fields_stride    = 1;
  s->memory_check     = PETSC_TRUE;
  s->checkpoint_every = 1;
  s->monitor_interval = 5.0;
  s->progress         = 5.0;
  PetscCall(PetscMalloc1(2, &s->path));
  s->npath   = 2;
  s->path[0] = 0.01;
  s->path[1] = 0.0;
  PetscCall(AdhGridCreate(comm, &s->grid));
  s->grid->fftw_timelimit = 0.01; /* free boundary: many windows to plan, few whole-grid multiplies */
  PetscCall(AdhSolverSetControlType(s, ADHCONTROLDISPLACEMENT));
  PetscCall(AdhSolverSetCriterionType(s, ADHCRITERIONCRACKCLOSURE)); /* within 2% in every edge direction; the paper's rule is one option away */
  s->attach = ADH_ATTACH_GRIFFITH; /* crack-closure's mirror: JKR's and Johnson's loading branches (reach with pohrt-popov, at set-up; penetration stays Hertz-like) */
  s->predictor_rtol   = 1e-8;
  s->predictor_max_it = 10000;
  s->predictor_fourier = PETSC_TRUE;
  PetscCall(AdhSolverSetPredictorType(s, ADHPREDICTORPOLONSKYKEER));
  s->predictor_chosen = PETSC_FALSE; /* the default: polonsky-keer on a periodic cell, none on a free boundary */
  *solver = s;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverSetOptionsPrefix(AdhSolver s, const char prefix[])
{
  PetscFunctionBegin;
  PetscCall(PetscFree(s->prefix));
  PetscCall(PetscStrallocpy(prefix, &s->prefix));
  s->grid->prefix = s->prefix;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetGrid(AdhSolver s, AdhGrid *grid)
{
  PetscFunctionBegin;
  *grid = s->grid;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetCompliance(AdhSolver s, Mat *K)
{
  PetscFunctionBegin;
  *K = s->K;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetContactSet(AdhSolver s, IS *is)
{
  PetscFunctionBegin;
  *is = s->contact;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetFields(AdhSolver s, Vec *p, Vec *u, Vec *g, Vec *h, Vec *Sigma)
{
  PetscFunctionBegin;
  if (p) *p = s->p;
  if (u) PetscCall(AdhSolverGetDisplacement_Private(s, u));
  if (g) *g = s->g;
  if (h) *h = s->h;
  if (Sigma) PetscCall(AdhSolverGetCriticalStressVec_Private(s, Sigma));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetCriticalStress(AdhSolver s, PetscReal *Sigma)
{
  PetscFunctionBegin;
  *Sigma = s->Sigma;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverSetProgress(AdhSolver s, PetscReal seconds)
{
  PetscFunctionBegin;
  PetscCheck(seconds >= 0 && !PetscIsNanReal(seconds), s->comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_progress must be >= 0 seconds, got %g", (double)seconds);
  s->progress = seconds;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetProgress(AdhSolver s, PetscReal *seconds)
{
  PetscFunctionBegin;
  *seconds = s->progress;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetBoundary(AdhSolver s, AdhBoundary *boundary)
{
  PetscFunctionBegin;
  *boundary = s->boundary;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverGetCurve(AdhSolver s, const AdhCurve **curve)
{
  PetscFunctionBegin;
  *curve = &s->curve;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverDestroy(AdhSolver *solver)
{
  AdhSolver s = *solver;

  PetscFunctionBegin;
  if (!s) PetscFunctionReturn(0);
  if (s->cops.destroy) PetscCall(s->cops.destroy(s));
  if (s->crops.destroy) PetscCall(s->crops.destroy(s));
  PetscCall(PetscFree(s->field_states));
  if (s->journal) fclose(s->journal);
  PetscCall(VecDestroy(&s->attach_limit));
  PetscCall(AdhSolverMonitorCancel(s));
  PetscCall(KSPDestroy(&s->ksp));
  PetscCall(MatDestroy(&s->Kcc));
  PetscCall(ISDestroy(&s->contact_op));
  PetscCall(VecScatterDestroy(&s->set_scatter));
  PetscCall(VecDestroy(&s->pC));
  PetscCall(VecDestroy(&s->bC));
  PetscCall(PetscFree(s->set_local));
  PetscCall(PetscFree(s->thrC));
  PetscCall(VecDestroy(&s->op_in));
  PetscCall(VecDestroy(&s->op_out));
  PetscCall(AdhSolverDestroyBoxes_Private(s));
  PetscCall(MatDestroy(&s->K));
  PetscCall(MatDestroy(&s->S));
  PetscCall(ISDestroy(&s->contact));
  PetscCall(VecDestroy(&s->h));
  PetscCall(VecDestroy(&s->Sigma_field));
  PetscCall(VecDestroy(&s->Sigma_view));
  PetscCall(VecDestroy(&s->p));
  PetscCall(VecDestroy(&s->u));
  PetscCall(VecDestroy(&s->g));
  PetscCall(VecDestroy(&s->gamma_field));
  PetscCall(VecDestroy(&s->indenter.z));
  PetscCall(PetscFree(s->in_set));
  PetscCall(PetscFree(s->left));
  PetscCall(AdhSolverDestroyCascadeApart_Private(s));
  PetscCall(AdhSolverDestroyCascadeLocal_Private(s));
  PetscCall(PetscFree(s->path));
  PetscCall(AdhCurveDestroy_Private(&s->curve));
  PetscCall(AdhGridDestroy(&s->grid));
  PetscCall(PetscFree(s->prefix));
  PetscCall(PetscFree(s));
  *solver = NULL;
  PetscFunctionReturn(0);
}
