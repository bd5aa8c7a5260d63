/* The fields of the states in the results file: a frame per state written (-adh_fields,
   -adh_fields_stride), the contact set (and a cohesive zone) as a byte per point. */
#include "results/resultsimpl.h"

/* The contact mask of the current state as frame `frame` of the uint8 dataset contact
   (frames, Ny, Nx) of the viewer's current group: a byte per point where VecView would write 8.
   Each rank writes its rows; the dataset grows by one frame per call. */
static PetscErrorCode WriteContactMask(AdhSolver s, PetscViewer viewer, PetscInt frame)
{
  const AdhGrid  g = s->grid;
  hid_t          file_id, group, dset;
  hsize_t        dims[3], chunk[3], offset[3], count[3];
  PetscInt       ys, ym;
  unsigned char *mask;
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  dims[0] = (hsize_t)frame + 1;
  dims[1] = (hsize_t)g->Ny;
  dims[2] = (hsize_t)g->Nx;
  /* one frame per chunk, at most 1 GB (HDF5 chunks must stay below 4 GB) */
  chunk[0] = 1;
  chunk[1] = (hsize_t)PetscMax(1, PetscMin(g->Ny, (PetscInt)(1073741824 / g->Nx)));
  chunk[2] = (hsize_t)g->Nx;
  PetscCall(PetscViewerHDF5OpenGroup(viewer, NULL, &file_id, &group));
  PetscCall(AdhH5OpenExtendible_Private(group, AdhFieldNames[3], H5T_NATIVE_UCHAR, 3, dims, chunk, &dset));
  offset[0] = (hsize_t)frame;
  offset[1] = (hsize_t)ys;
  offset[2] = 0;
  count[0]  = 1;
  count[1]  = (hsize_t)ym;
  count[2]  = (hsize_t)g->Nx;
  PetscCall(PetscMalloc1(s->nlocal + 1, &mask));
  { /* 1 in contact, 2 in a cohesive zone (the curve's cohesive_area counts the same points), 0 free */
    const PetscScalar *pa, *ga, *gamma = NULL;
    PetscCall(VecGetArrayRead(s->p, &pa));
    PetscCall(VecGetArrayRead(s->g, &ga));
    if (s->gamma_field) PetscCall(VecGetArrayRead(s->gamma_field, &gamma));
    for (PetscInt k = 0; k < s->nlocal; k++) {
      const PetscReal dgamma = gamma ? PetscRealPart(gamma[k]) : s->gamma;
      mask[k] = s->in_set[k] ? 1 : AdhSolverInCohesiveZone_Private(s, PetscRealPart(pa[k]), PetscRealPart(ga[k]), dgamma) ? 2 : 0;
    }
    if (gamma) PetscCall(VecRestoreArrayRead(s->gamma_field, &gamma));
    PetscCall(VecRestoreArrayRead(s->g, &ga));
    PetscCall(VecRestoreArrayRead(s->p, &pa));
  }
  ierr = AdhH5WriteBlock_Private(dset, H5T_NATIVE_UCHAR, 3, offset, count, mask);
  PetscCall(PetscFree(mask));
  PetscCall(AdhH5Agree_Private(s, ierr));
  ADH_H5(H5Dclose(dset));
  ADH_H5(H5Gclose(group));
  PetscFunctionReturn(0);
}

/* The fields of the current state as frame `frame`. */
static PetscErrorCode WriteFrame(AdhSolver s, PetscViewer viewer, PetscInt frame, PetscInt state)
{
  Vec u;

  PetscFunctionBegin;
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/fields"));
  if (frame == 0) {
    const PetscBool made = (PetscBool)(!s->Sigma_field && !s->Sigma_view);
    Vec             Sigma;
    PetscCall(VecView(s->h, viewer));
    PetscCall(AdhSolverGetCriticalStressVec_Private(s, &Sigma));
    PetscCall(VecView(Sigma, viewer));
    if (made) PetscCall(VecDestroy(&s->Sigma_view)); /* made only for this: not kept */
  }
  PetscCall(PetscViewerHDF5PushTimestepping(viewer));
  PetscCall(PetscViewerHDF5SetTimestep(viewer, frame));
  if (s->fields & ADH_FIELD_PRESSURE) PetscCall(VecView(s->p, viewer));
  if (s->fields & ADH_FIELD_DISPLACEMENT) {
    PetscCall(AdhSolverGetDisplacement_Private(s, &u));
    PetscCall(VecView(u, viewer));
  }
  if (s->fields & ADH_FIELD_GAP) PetscCall(VecView(s->g, viewer));
  PetscCall(PetscViewerHDF5PopTimestepping(viewer));
  if (s->fields & ADH_FIELD_CONTACT) PetscCall(WriteContactMask(s, viewer, frame));
  {
    const PetscReal row = (PetscReal)state;
    hid_t           file_id, group;
    PetscCall(PetscViewerHDF5OpenGroup(viewer, NULL, &file_id, &group));
    PetscCall(AdhH5AppendRows_Private(s, group, "state", PETSC_TRUE, frame, 1, &row));
    ADH_H5(H5Gclose(group));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(0);
}

/* The bytes a frame takes: the fields chosen (the first frame also h and Sigma), 8 a point, and the contact's 1. */
static size_t FrameBytes(AdhSolver s, PetscInt frame)
{
  const size_t n      = (size_t)s->grid->Nx * (size_t)s->grid->Ny;
  size_t       fields = frame == 0 ? 2 : 0;

  for (unsigned f = ADH_FIELD_PRESSURE; f <= ADH_FIELD_GAP; f <<= 1) fields += (s->fields & f) != 0;
  return n * (8 * fields + ((s->fields & ADH_FIELD_CONTACT) != 0));
}

/* The fields chosen by -adh_fields of the current state, curve row `state`, as the next frame of
   /fields (HDF5 timestepping); the first frame also holds the profile h and the critical stress.
   /fields/state, which maps frames to curve rows, grows with them. A full disk or a failed write
   stops it with one error (the file as after the last state, AdhOutputAppend_Private). */
PetscErrorCode AdhOutputWriteFields_Private(AdhSolver s, PetscViewer viewer, PetscInt state)
{
  const PetscInt frame = s->nfield_states;
  const char    *part;
  char           kept[3 * PETSC_MAX_PATH_LEN];
  PetscErrorCode ierr;
  int            err;

  PetscFunctionBegin;
  if (!s->fields) PetscFunctionReturn(0);
  PetscCall(PetscViewerFileGetName(viewer, &part));
  PetscCall(AdhOutputKept_Private(s, part, kept, sizeof(kept)));
  PetscCall(AdhOutputReserve_Private(s, part, FrameBytes(s, frame), &err));
  if (err) { /* the file as after the last state: what the reservation got is given back */
    s->output_failed = PETSC_TRUE;
    PetscCall(AdhOutputReleaseReserve_Private(s, part));
  }
  PetscCheck(!err, s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: cannot write the fields of state %" PetscInt_FMT " to %s: %s; %s", state, part, strerror(err), kept);
  PetscCall(PetscRealloc((frame + 1) * sizeof(PetscInt), &s->field_states));
  s->field_states[s->nfield_states++] = state;
  PetscCall(AdhOutputWriteBegin_Private(s, "-adh_output", part, kept, PETSC_FALSE));
  ierr             = WriteFrame(s, viewer, frame, state);
  ierr             = AdhOutputWriteEnd_Private(s, ierr);
  s->output_failed = (PetscBool)(s->output_failed || ierr);
  PetscCall(ierr);
  PetscFunctionReturn(0);
}
