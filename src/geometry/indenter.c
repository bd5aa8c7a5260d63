/* Indenter profiles h(x,y): the gap between the undeformed bodies at indentation d = 0.
   Every built-in indenter has its apex on the centre of element (Nx/2, Ny/2). A topography
   (from a file through fieldfile.c, or a user's Vec) is a height map z or the gap h itself. */
#include "geometry/indenter.h"
#include "sys/sysimpl.h"

const char *const AdhIndenterTypes[]    = {"sphere", "punch", "cone", "file", "rough", "array", "AdhIndenterType", "ADH_INDENTER_", NULL};
const char *const AdhTopographyKinds[] = {"height", "gap", "AdhTopographyKind", "ADH_TOPOGRAPHY_", NULL};

/* A topography in h: a height map becomes the gap h = max(z) - z, whose zero is the highest
   peak; a gap is kept. Computed as (-z) + max(z), exactly max(z) - z. */
static PetscErrorCode TopographyToProfile(AdhTopographyKind kind, Vec h)
{
  PetscReal zmax;

  PetscFunctionBegin;
  if (kind == ADH_TOPOGRAPHY_HEIGHT) {
    PetscCall(VecMax(h, NULL, &zmax));
    PetscCall(VecScale(h, -1.0));
    PetscCall(VecShift(h, zmax));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode AdhIndenterFill_Private(AdhGrid grid, AdhIndenter *ind, Vec h)
{
  PetscScalar *ha;
  PetscInt     ys, ym, i, j;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(grid, ADH_GRID_CLASSID, 1);
  PetscCall(AdhGridGetOwnership(grid, &ys, &ym));
  if (ind->type == ADH_INDENTER_FILE) {
    PetscCheck(ind->topography[0], grid->comm, PETSC_ERR_ARG_WRONG, "-adh_indenter file needs -adh_topography FILE (.npy or .h5)");
    PetscCall(AdhFieldLoad(grid, "-adh_topography", ind->topography, ind->dataset, h));
    PetscCall(TopographyToProfile(ind->kind, h));
  } else if (ind->type == ADH_INDENTER_ROUGH) {
    PetscCall(AdhSurfaceGenerate(grid, &ind->surface, h));
    PetscCall(TopographyToProfile(ADH_TOPOGRAPHY_HEIGHT, h));
  } else if (ind->type == ADH_INDENTER_ARRAY) {
    PetscCheck(ind->z, grid->comm, PETSC_ERR_ARG_WRONGSTATE, "-adh_indenter array takes its profile from AdhSolverSetTopography() (Python: Solver(topography=array)); for a file use -adh_topography FILE");
    PetscCall(AdhFieldCheck(grid, "topography", ind->z));
    PetscCall(VecCopy(ind->z, h));
    PetscCall(TopographyToProfile(ind->kind, h));
  } else {
    PetscCall(VecGetArray(h, &ha));
    for (j = ys; j < ys + ym; j++)
      for (i = 0; i < grid->Nx; i++) {
        PetscReal x, y, r;
        PetscCall(AdhGridGetCoordinates(grid, i, j, &x, &y));
        r = PetscSqrtReal(x * x + y * y);
        switch (ind->type) {
        case ADH_INDENTER_SPHERE: ha[(j - ys) * grid->Nx + i] = r * r / (2.0 * ind->radius); break;
        /* Outside the punch the gap is infinite: those points never touch. */
        case ADH_INDENTER_PUNCH: ha[(j - ys) * grid->Nx + i] = r <= ind->punch_radius ? 0.0 : PETSC_INFINITY; break;
        case ADH_INDENTER_CONE: ha[(j - ys) * grid->Nx + i] = ind->cone_slope * r; break;
        default: break;
        }
      }
    PetscCall(VecRestoreArray(h, &ha));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode AdhIndenterSetFromOptions_Private(AdhGrid grid, const char prefix[], AdhIndenter *ind)
{
  MPI_Comm  comm = grid->comm;
  PetscBool typeset = PETSC_FALSE, topo = PETSC_FALSE;

  PetscFunctionBegin;
  PetscOptionsBegin(comm, prefix, "adhbem indenter", "AdhSolver");
  PetscCall(PetscOptionsEnum("-adh_indenter", "Indenter shape (array: a profile given through the API)", "AdhSolver", AdhIndenterTypes, (PetscEnum)ind->type, (PetscEnum *)&ind->type, &typeset));
  PetscCall(AdhOptionsReal("-adh_radius", "Sphere radius R (h = r^2/2R)", "AdhSolver", ind->radius, &ind->radius, NULL));
  PetscCall(AdhOptionsReal("-adh_punch_radius", "Flat punch radius a", "AdhSolver", ind->punch_radius, &ind->punch_radius, NULL));
  PetscCall(AdhOptionsReal("-adh_cone_slope", "Cone slope (h = slope r)", "AdhSolver", ind->cone_slope, &ind->cone_slope, NULL));
  PetscCall(PetscOptionsString("-adh_topography", "Topography file (implies -adh_indenter file): .npy (Ny, Nx) float64/float32, or HDF5", "AdhSolver", ind->topography, ind->topography, sizeof(ind->topography), &topo));
  PetscCall(PetscOptionsString("-adh_topography_dataset", "Dataset name inside an HDF5 topography file", "AdhSolver", ind->dataset, ind->dataset, sizeof(ind->dataset), NULL));
  PetscCall(PetscOptionsEnum("-adh_topography_kind", "What the topography holds: height z of the surface as measured (profile h = max(z) - z, the highest peak touches at d = 0) or gap h itself", "AdhSolver", AdhTopographyKinds, (PetscEnum)ind->kind, (PetscEnum *)&ind->kind, NULL));
  PetscOptionsEnd();
  /* A topography file given without an indenter type is the indenter. */
  if (topo && !typeset && ind->topography[0]) ind->type = ADH_INDENTER_FILE;
  /* read always, so that -help lists them; they shape only a rough indenter */
  PetscCall(AdhSurfaceSetFromOptions(grid, prefix, &ind->surface));
  PetscCheck(ind->type != ADH_INDENTER_SPHERE || (ind->radius > 0 && PetscIsNormalReal(ind->radius)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_radius must be positive and finite, got %g", (double)ind->radius);
  PetscCheck(ind->type != ADH_INDENTER_PUNCH || (ind->punch_radius > 0 && PetscIsNormalReal(ind->punch_radius)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_punch_radius must be positive and finite, got %g", (double)ind->punch_radius);
  PetscCheck(ind->type != ADH_INDENTER_CONE || (ind->cone_slope > 0 && PetscIsNormalReal(ind->cone_slope)), comm, PETSC_ERR_ARG_OUTOFRANGE, "-adh_cone_slope must be positive and finite, got %g", (double)ind->cone_slope);
  PetscFunctionReturn(0);
}
