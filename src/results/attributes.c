/* The parameters of a run as the results file's root attributes: the grid, material, indenter
   (with the rough surface or array topography it ran on), criterion and solver, and the pull-off
   force with how well the grid resolves it. */
#include <math.h>
#include "results/resultsimpl.h"

/* A rough indenter's parameters and realised statistics as root attributes, and its heights z
   (h = max z - z) as the dataset /topography, which -adh_indenter file reads back. */
PetscErrorCode AdhOutputWriteSurface_Private(AdhSolver s, PetscViewer v)
{
  AdhSurface *sf = &s->indenter.surface;

  PetscFunctionBegin;
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "hurst", PETSC_REAL, &sf->hurst));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "rolloff_wavelength", PETSC_REAL, &sf->used_rolloff_wavelength));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cutoff_wavelength", PETSC_REAL, &sf->used_cutoff_wavelength));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "seed", PETSC_INT, &sf->seed));
  if (sf->rms_height > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "rms_height", PETSC_REAL, &sf->rms_height));
  else PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "rms_slope", PETSC_REAL, &sf->realised_rms_slope));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "realised_rms_height", PETSC_REAL, &sf->realised_rms_height));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "realised_rms_slope", PETSC_REAL, &sf->realised_rms_slope));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "max_height", PETSC_REAL, &sf->max_height));
  /* generated again rather than kept through the run: the same bits, one FFT, no grid vector */
  PetscCall(AdhSurfaceWriteHeights(s->grid, sf, v, "topography"));
  PetscFunctionReturn(0);
}

/* An array indenter's profile as the user gave it (heights z or the gap h, as the attribute
   topography_kind says) as the dataset /topography, so that -adh_topography FILE
   -adh_topography_dataset topography gives the same profile back. The user's Vec lends its values
   under that name. */
PetscErrorCode AdhOutputWriteArrayTopography_Private(AdhSolver s, PetscViewer v)
{
  PetscObject z = (PetscObject)s->indenter.z;
  const char *name;
  char        own[256];

  PetscFunctionBegin;
  PetscCall(PetscObjectGetName(z, &name));
  PetscCall(PetscStrncpy(own, name, sizeof(own)));
  PetscCall(PetscObjectSetName(z, "topography"));
  {
    PetscErrorCode ierr = VecView((Vec)z, v);
    PetscCall(PetscObjectSetName(z, own)); /* the user's name back, also when the view failed */
    PetscCall(ierr);
  }
  PetscFunctionReturn(0);
}

/* The pull-off force (the largest tension carried, -min F; 0: none) of curve row k, and how well
   the grid resolves it (the curve's statistics at that state; absent without tension). */
PetscErrorCode AdhOutputWritePullOff_Private(AdhSolver s, PetscViewer v, PetscInt k)
{
  const char *const resolution[] = {"pull_off_small_patch_tension", "pull_off_smallest_tensile_patch", "adhesion_resolved", "pull_off_cohesive_width", "adhesion_unresolved_by"};
  const PetscReal   largest      = k >= 0 ? -s->curve.state[k].force : 0.0;
  AdhResolution     r;
  PetscReal         pull_off;

  PetscFunctionBegin;
  /* a pull-off force only where the surfaces came apart; else NaN, and the largest tension as such */
  PetscCall(AdhSolverGetResolution(s, &r));
  pull_off = r.apart >= 0 ? largest : (PetscReal)NAN;
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "pull_off_force", PETSC_REAL, &pull_off));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "largest_tension", PETSC_REAL, &largest));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "came_apart", PETSC_BOOL, &(PetscBool){r.apart >= 0}));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "full_contact", PETSC_BOOL, &(PetscBool){r.full_contact >= 0}));
  if (k >= 0) {
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", resolution[0], PETSC_REAL, &s->curve.state[k].small_patch_tension));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", resolution[1], PETSC_INT, &s->curve.state[k].smallest_tensile_patch));
    {
      const PetscInt why = AdhSolverUnresolved_Private(s, &s->curve.state[k]);
      char           words[512];
      PetscCall(PetscViewerHDF5WriteAttribute(v, "/", resolution[2], PETSC_BOOL, &(PetscBool){!why}));
      PetscCall(AdhSolverUnresolvedWords_Private(s, &s->curve.state[k], why, words, sizeof(words)));
      PetscCall(AdhH5WriteStringAttribute_Private(v, resolution[4], words)); /* "" when resolved */
    }
    if (s->curve.state[k].cohesive_area > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", resolution[3], PETSC_REAL, &(PetscReal){AdhSolverCohesiveWidth_Private(s, &s->curve.state[k])}));
  } else { /* a restart's file may hold those of states after its checkpoint */
    hid_t file_id;
    PetscCall(PetscViewerHDF5GetFileId(v, &file_id));
    for (PetscInt j = 0; j < 5; j++)
      if (H5Aexists_by_name(file_id, "/", resolution[j], H5P_DEFAULT) > 0) ADH_H5(H5Adelete_by_name(file_id, "/", resolution[j], H5P_DEFAULT));
  }
  s->pull_off_written = k;
  s->apart_written    = r.apart;
  s->full_written     = r.full_contact;
  PetscFunctionReturn(0);
}

/* The parameters of the run, as root attributes. */
PetscErrorCode AdhOutputWriteAttributes_Private(AdhSolver s, PetscViewer v)
{
  const AdhGrid g = s->grid;
  PetscMPIInt   size;
  PetscInt      nranks;
  PetscReal     rtol, atol, dtol;
  PetscInt      maxits;
  KSPType       ksptype;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  nranks = size;
  PetscCall(KSPGetTolerances(s->ksp, &rtol, &atol, &dtol, &maxits));
  PetscCall(KSPGetType(s->ksp, &ksptype));
  { /* which adhbem and PETSc wrote the file */
    char petsc[128];
    PetscCall(AdhGetPETScVersion_Private(petsc, sizeof(petsc)));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "adhbem_version", PETSC_STRING, ADHBEM_VERSION));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "petsc_version", PETSC_STRING, petsc));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "E_star", PETSC_REAL, &s->Estar));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "gamma", PETSC_REAL, &s->gamma));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "gamma_field", PETSC_BOOL, s->gamma_field ? &(PetscBool){PETSC_TRUE} : &(PetscBool){PETSC_FALSE}));
  if (s->gamma_field && s->gamma_file[0]) PetscCall(AdhH5WriteStringAttribute_Private(v, "gamma_field_file", s->gamma_file));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Sigma", PETSC_REAL, &s->Sigma));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "critical_stress_fixed", PETSC_BOOL, s->sigma_fixed > 0 ? &(PetscBool){PETSC_TRUE} : &(PetscBool){PETSC_FALSE}));
  if (s->sigma_fixed > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "critical_stress", PETSC_REAL, &s->sigma_fixed));
  PetscCall(AdhH5WriteStringAttribute_Private(v, "attach", AdhAttaches[s->attach]));
  PetscCall(AdhH5WriteStringAttribute_Private(v, "predictor", s->predictor_type));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "hx", PETSC_REAL, &g->hx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "hy", PETSC_REAL, &g->hy));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Lx", PETSC_REAL, &g->Lx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Ly", PETSC_REAL, &g->Ly));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Nx", PETSC_INT, &g->Nx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Ny", PETSC_INT, &g->Ny));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "nranks", PETSC_INT, &nranks));
  PetscCall(AdhH5WriteStringAttribute_Private(v, "boundary", AdhBoundaries[s->boundary]));
  PetscCall(AdhH5WriteStringAttribute_Private(v, "indenter", AdhIndenterTypes[s->indenter.type]));
  PetscCall(AdhH5WriteStringAttribute_Private(v, "start", AdhStarts[s->start]));
  PetscCall(AdhH5WriteStringAttribute_Private(v, "control", s->control_type));
  PetscCall(AdhH5WriteStringAttribute_Private(v, "criterion", s->criterion_type));
  PetscCall(AdhH5WriteStringAttribute_Private(v, "elastic", s->elastic_type));
  /* the types' own (the body's, crack-closure's radii, force control's pull-off tolerance): their views on the HDF5 viewer */
  if (s->eops.base.view) PetscCall(s->eops.base.view(s, v));
  if (s->crops.base.view) PetscCall(s->crops.base.view(s, v));
  if (s->cops.base.view) PetscCall(s->cops.base.view(s, v));
  if (s->pops.base.view) PetscCall(s->pops.base.view(s, v));
  if (s->asperity_ac > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "asperity_contact_radius", PETSC_REAL, &s->asperity_ac));
  if (s->asperity_tabor > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "asperity_tabor", PETSC_REAL, &s->asperity_tabor));
  if (s->stickiness.estimated) { /* a rough surface's stickiness (stickiness.c) */
    const AdhStickiness *st = &s->stickiness;
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stickiness_rms_slope", PETSC_REAL, &st->rms_slope));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stickiness_rms_curvature", PETSC_REAL, &st->rms_curvature));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stickiness_full_contact_energy", PETSC_REAL, &st->full_contact_energy));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stickiness_persson_tosatti", PETSC_REAL, &st->persson_tosatti));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stickiness_work_of_adhesion", PETSC_REAL, &st->work_of_adhesion));
    if (st->range > 0) {
      PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stickiness_range", PETSC_REAL, &st->range));
      PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stickiness_pastewka_robbins", PETSC_REAL, &st->pastewka_robbins));
      PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "stickiness_tabor", PETSC_REAL, &st->tabor));
    }
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "sticks_everywhere", PETSC_BOOL, &st->sticks_everywhere));
    /* known with either criterion; a zero-range criterion on a partial contact leaves it to the run */
    if (st->sticks_everywhere || st->range > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "sticky", PETSC_BOOL, &st->sticky));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "steps", PETSC_INT, &s->steps));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cascade_rtol", PETSC_REAL, &s->cascade_rtol));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cascade_apart", PETSC_INT, &s->cascade_apart));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cascade_local", PETSC_REAL, &s->cascade_local));
  if (s->cascade_local > 0) {
    PetscReal local_rtol = s->cascade_local_rtol; /* the local KSP's, which -adh_local_ksp_rtol may have changed */
    if (s->local_ksp) PetscCall(KSPGetTolerances(s->local_ksp, &local_rtol, NULL, NULL, NULL));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cascade_local_rtol", PETSC_REAL, &local_rtol));
  }
  PetscCall(AdhH5WriteStringAttribute_Private(v, "ksp_type", ksptype));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "ksp_rtol", PETSC_REAL, &rtol));
  switch (s->indenter.type) {
  case ADH_INDENTER_SPHERE: PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "radius", PETSC_REAL, &s->indenter.radius)); break;
  case ADH_INDENTER_PUNCH: PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "punch_radius", PETSC_REAL, &s->indenter.punch_radius)); break;
  case ADH_INDENTER_CONE: PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cone_slope", PETSC_REAL, &s->indenter.cone_slope)); break;
  case ADH_INDENTER_FILE: PetscCall(AdhH5WriteStringAttribute_Private(v, "topography", s->indenter.topography)); break;
  case ADH_INDENTER_ROUGH: break; /* written when the file was opened */
  case ADH_INDENTER_ARRAY: break;
  }
  if (s->indenter.type == ADH_INDENTER_FILE || s->indenter.type == ADH_INDENTER_ARRAY) PetscCall(AdhH5WriteStringAttribute_Private(v, "topography_kind", AdhTopographyKinds[s->indenter.kind]));
  PetscFunctionReturn(0);
}
