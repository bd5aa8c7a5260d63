/* The half-space compliance in a KSP of one's own: a rigid flat circular punch of radius a
   pressed in by d on an elastic half-space, K_FF p_F = d on its face F, solved by CG. The force
   against Boussinesq's 2 a E* d. Options: -n N (grid points a side), PETSc's -ksp_* (-ksp_monitor,
   -ksp_type, ...). Build against an installed adhbem:
     cc own_ksp.c $(pkg-config --cflags --libs adhbem) -o own_ksp && mpirun -n 2 ./own_ksp       */
#include <adhbem.h>

typedef struct {
  Mat        K;      /* the compliance, u = K p */
  Vec        work;
  PetscBool *face;   /* this rank's points on the punch's face */
} OnFace;

/* u = K_FF p on the face, u = p elsewhere: the system stays symmetric positive definite */
static PetscErrorCode MatMult_OnFace(Mat A, Vec p, Vec u)
{
  OnFace            *ctx;
  const PetscScalar *pa;
  PetscScalar       *wa, *ua;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(A, &ctx));
  PetscCall(VecGetLocalSize(p, &n));
  PetscCall(VecGetArrayRead(p, &pa));
  PetscCall(VecGetArray(ctx->work, &wa));
  for (PetscInt k = 0; k < n; k++) wa[k] = ctx->face[k] ? pa[k] : 0.0;
  PetscCall(VecRestoreArray(ctx->work, &wa));
  PetscCall(MatMult(ctx->K, ctx->work, u));
  PetscCall(VecGetArray(u, &ua));
  for (PetscInt k = 0; k < n; k++)
    if (!ctx->face[k]) ua[k] = pa[k];
  PetscCall(VecRestoreArray(u, &ua));
  PetscCall(VecRestoreArrayRead(p, &pa));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  AdhGrid     grid;
  OnFace      ctx;
  Mat         A;
  Vec         p, u;
  KSP         ksp;
  PetscInt    N = 128, Nx, ys, ym, n, its;
  PetscReal   L = 1.0, E_star = 1.0, a = 0.25, d = 0.01, hx, hy, x, y;
  PetscScalar F, *ua;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &N, NULL));
  PetscCall(AdhGridCreate(PETSC_COMM_WORLD, &grid));
  PetscCall(AdhGridSetFromOptions(grid)); /* -adh_fftw_planner and the other FFTW options; the sizes are set next */
  PetscCall(AdhGridSetSizes(grid, N, N, L, L));
  PetscCall(AdhGridSetUp(grid));
  PetscCall(MatCreateAdhCompliance(grid, E_star, ADH_BOUNDARY_FREE, &ctx.K));
  PetscCall(MatCreateVecs(ctx.K, &p, &u));
  PetscCall(VecDuplicate(p, &ctx.work));

  /* the face: the points whose centres lie within a; the grid is split into whole rows */
  PetscCall(AdhGridGetSizes(grid, &Nx, NULL, NULL, NULL));
  PetscCall(AdhGridGetSpacing(grid, &hx, &hy));
  PetscCall(AdhGridGetOwnership(grid, &ys, &ym));
  PetscCall(VecGetLocalSize(u, &n));
  PetscCall(PetscMalloc1(n, &ctx.face));
  PetscCall(VecGetArray(u, &ua));
  for (PetscInt j = ys; j < ys + ym; j++)
    for (PetscInt i = 0; i < Nx; i++) {
      PetscInt k = (j - ys) * Nx + i;
      PetscCall(AdhGridGetCoordinates(grid, i, j, &x, &y));
      ctx.face[k] = x * x + y * y <= a * a ? PETSC_TRUE : PETSC_FALSE;
      ua[k]       = ctx.face[k] ? d : 0.0; /* the face pressed in by d */
    }
  PetscCall(VecRestoreArray(u, &ua));

  PetscCall(MatCreateShell(PETSC_COMM_WORLD, n, n, PETSC_DETERMINE, PETSC_DETERMINE, &ctx, &A));
  PetscCall(MatShellSetOperation(A, MATOP_MULT, (void (*)(void))MatMult_OnFace));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSetType(ksp, KSPCG));
  PetscCall(KSPSetTolerances(ksp, 1e-10, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  {
    PC pc;
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCNONE)); /* a shell of one's own has no diagonal for Jacobi */
  }
  PetscCall(KSPSetFromOptions(ksp)); /* last, so that -ksp_type, -pc_type, ... can change the above */
  PetscCall(KSPSolve(ksp, u, p));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  PetscCall(VecSum(p, &F));
  F *= hx * hy;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%" PetscInt_FMT " Krylov iterations; F = %.6g, Boussinesq 2 a E* d = %.6g\n", its, (double)PetscRealPart(F), (double)(2 * a * E_star * d)));

  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&A));
  PetscCall(PetscFree(ctx.face));
  PetscCall(VecDestroy(&ctx.work));
  PetscCall(VecDestroy(&p));
  PetscCall(VecDestroy(&u));
  PetscCall(MatDestroy(&ctx.K));
  PetscCall(AdhGridDestroy(&grid));
  PetscCall(PetscFinalize());
  return 0;
}
