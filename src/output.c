/* Results: HDF5 through PETSc's viewer (curve in /curve, parameters as root attributes, fields
   in /fields) and the curve as CSV. Both are written to FILE.part and renamed when complete, so
   a result file is never half-written and an older one is not lost to a failed run. */
#include <errno.h>
#include "solverimpl.h"

static PetscErrorCode PartName(const char file[], char part[], size_t len)
{
  PetscFunctionBegin;
  PetscCall(PetscSNPrintf(part, len, "%s.part", file));
  PetscFunctionReturn(0);
}

/* FILE.h5 -> FILE.ext (csv, xmf); other names get .ext appended. */
static PetscErrorCode SiblingName(const char file[], const char ext[], char name[], size_t len)
{
  size_t n;

  PetscFunctionBegin;
  PetscCall(PetscStrlen(file, &n));
  if (n > 3 && !strcmp(file + n - 3, ".h5")) {
    PetscCall(PetscSNPrintf(name, len, "%.*s.%s", (int)(n - 3), file, ext));
  } else PetscCall(PetscSNPrintf(name, len, "%s.%s", file, ext));
  PetscFunctionReturn(0);
}

/* Rank 0 makes the file's directory when it is missing (results/ in a fresh clone) and tries to
   create the file; everyone learns the answer, so a bad path fails before any work with a
   message that names the option and the file. */
PetscErrorCode AdhOutputCheckWritable_Private(AdhSolver s, const char option[], const char file[])
{
  char        part[PETSC_MAX_PATH_LEN + 8], dir[PETSC_MAX_PATH_LEN], reason[256] = "";
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(PartName(file, part, sizeof(part)));
  if (!rank) {
    FILE      *fp;
    char      *slash;
    PetscBool  exists = PETSC_TRUE;
    PetscCall(PetscStrncpy(dir, file, sizeof(dir)));
    slash = strrchr(dir, '/');
    if (slash && slash != dir) {
      *slash = 0;
      PetscCall(PetscTestDirectory(dir, 'w', &exists));
      if (!exists) (void)PetscMkdir(dir); /* a failure shows in the fopen below */
    }
    fp = fopen(part, "w");
    if (!fp) {
      ok = 0;
      PetscCall(PetscStrncpy(reason, strerror(errno), sizeof(reason)));
    } else {
      fclose(fp);
      remove(part);
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCallMPI(MPI_Bcast(reason, sizeof(reason), MPI_CHAR, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_OPEN, "%s: cannot write %s: %s", option, file, reason);
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteSurface(AdhSolver, PetscViewer);

PetscErrorCode AdhOutputOpen_Private(AdhSolver s, const char file[], PetscViewer *viewer)
{
  char part[PETSC_MAX_PATH_LEN + 8];

  PetscFunctionBegin;
  PetscCall(AdhOutputCheckWritable_Private(s, "-adh_output", file));
  PetscCall(PartName(file, part, sizeof(part)));
  PetscCall(PetscViewerHDF5Open(s->comm, part, FILE_MODE_WRITE, viewer));
  /* a rough surface, generated again, goes in now, while the contact set and its solver's vectors
     are small (at the close they may be the largest of the run) */
  if (s->indenter.type == ADH_INDENTER_ROUGH) PetscCall(WriteSurface(s, *viewer));
  PetscFunctionReturn(0);
}

const char *const AdhFieldNames[4] = {"pressure", "displacement", "gap", "contact"};

/* An HDF5 call that fails (a negative return) becomes a PETSc error naming it. */
#define ADH_H5(call) \
  do { \
    PetscCheck((call) >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "HDF5: %s failed", #call); \
  } while (0)

/* The contact mask of the current state as frame `frame` of the uint8 dataset contact
   (frames, Ny, Nx) of the viewer's current group: a byte per point where VecView would write 8.
   Each rank writes its rows; the dataset grows by one frame per call. */
static PetscErrorCode WriteContactMask(AdhSolver s, PetscViewer viewer, PetscInt frame)
{
  const AdhGrid  g = s->grid;
  hid_t          file_id, group, dset, filespace, memspace;
  hsize_t        dims[3], maxdims[3], chunk[3], offset[3], count[3];
  PetscInt       ys, ym;
  unsigned char *mask;

  PetscFunctionBegin;
  PetscCall(AdhGridGetOwnership(g, &ys, &ym));
  dims[0] = (hsize_t)frame + 1;
  dims[1] = maxdims[1] = (hsize_t)g->Ny;
  dims[2] = maxdims[2] = (hsize_t)g->Nx;
  maxdims[0] = H5S_UNLIMITED;
  /* one frame per chunk, at most 1 GB (HDF5 chunks must stay below 4 GB) */
  chunk[0] = 1;
  chunk[1] = (hsize_t)PetscMax(1, PetscMin(g->Ny, (PetscInt)(1073741824 / g->Nx)));
  chunk[2] = (hsize_t)g->Nx;
  PetscCall(PetscViewerHDF5OpenGroup(viewer, NULL, &file_id, &group));
  if (!H5Lexists(group, AdhFieldNames[3], H5P_DEFAULT)) {
    hid_t plist;
    ADH_H5(filespace = H5Screate_simple(3, dims, maxdims));
    ADH_H5(plist = H5Pcreate(H5P_DATASET_CREATE));
    ADH_H5(H5Pset_chunk(plist, 3, chunk));
    ADH_H5(dset = H5Dcreate2(group, AdhFieldNames[3], H5T_NATIVE_UCHAR, filespace, H5P_DEFAULT, plist, H5P_DEFAULT));
    ADH_H5(H5Pclose(plist));
    ADH_H5(H5Sclose(filespace));
  } else {
    ADH_H5(dset = H5Dopen2(group, AdhFieldNames[3], H5P_DEFAULT));
    ADH_H5(H5Dset_extent(dset, dims));
  }
  offset[0] = (hsize_t)frame;
  offset[1] = (hsize_t)ys;
  offset[2] = 0;
  count[0]  = 1;
  count[1]  = (hsize_t)ym;
  count[2]  = (hsize_t)g->Nx;
  PetscCall(PetscMalloc1(s->nlocal + 1, &mask));
  for (PetscInt k = 0; k < s->nlocal; k++) mask[k] = s->in_set[k] ? 1 : 0;
  ADH_H5(filespace = H5Dget_space(dset));
  ADH_H5(memspace = H5Screate_simple(3, count, NULL));
  ADH_H5(H5Sselect_hyperslab(filespace, H5S_SELECT_SET, offset, NULL, count, NULL));
  ADH_H5(H5Dwrite(dset, H5T_NATIVE_UCHAR, memspace, filespace, H5P_DEFAULT, mask));
  PetscCall(PetscFree(mask));
  ADH_H5(H5Sclose(memspace));
  ADH_H5(H5Sclose(filespace));
  ADH_H5(H5Dclose(dset));
  ADH_H5(H5Gclose(group));
  PetscFunctionReturn(0);
}

/* The fields chosen by -adh_fields of the current state, curve row `state`, as the next frame of
   /fields (HDF5 timestepping); the first frame also holds the profile h and the critical stress.
   /fields/state (written at close) maps frames to curve rows. */
PetscErrorCode AdhOutputWriteFields_Private(AdhSolver s, PetscViewer viewer, PetscInt state)
{
  const PetscInt frame = s->nfield_states;
  Vec            u;

  PetscFunctionBegin;
  if (!s->fields) PetscFunctionReturn(0);
  PetscCall(PetscRealloc((frame + 1) * sizeof(PetscInt), &s->field_states));
  s->field_states[s->nfield_states++] = state;
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
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(0);
}

/* A 1-D dataset held by rank 0. */
static PetscErrorCode WriteRealArray(AdhSolver s, PetscViewer viewer, const char name[], PetscInt n, const PetscReal *values)
{
  PetscMPIInt  rank;
  Vec          v;
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(VecCreateMPI(s->comm, rank ? 0 : n, n, &v));
  PetscCall(PetscObjectSetName((PetscObject)v, name));
  PetscCall(VecGetArrayWrite(v, &a));
  if (!rank)
    for (PetscInt k = 0; k < n; k++) a[k] = values[k];
  PetscCall(VecRestoreArrayWrite(v, &a));
  PetscCall(VecView(v, viewer));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}

/* A rough indenter's parameters and realised statistics as root attributes, and its heights z
   (h = max z - z) as the dataset /topography, which -adh_indenter file reads back. */
static PetscErrorCode WriteSurface(AdhSolver s, PetscViewer v)
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

static PetscErrorCode WriteAttributes(AdhSolver s, PetscViewer v)
{
  const AdhGrid g = s->grid;
  PetscMPIInt   size;
  PetscInt      nranks;
  PetscReal     rtol, atol, dtol;
  PetscInt      maxits;
  KSPType       ksptype;
  PetscReal     pull_off = 0.0; /* the largest tension carried, -min F (0: none) */
  PetscInt      k;

  PetscFunctionBegin;
  PetscCall(AdhCurveGetPullOffState(&s->curve, &k));
  if (k >= 0) pull_off = -s->curve.state[k].force;
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  nranks = size;
  PetscCall(KSPGetTolerances(s->ksp, &rtol, &atol, &dtol, &maxits));
  PetscCall(KSPGetType(s->ksp, &ksptype));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "E_star", PETSC_REAL, &s->Estar));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "gamma", PETSC_REAL, &s->gamma));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "gamma_field", PETSC_BOOL, s->gamma_field ? &(PetscBool){PETSC_TRUE} : &(PetscBool){PETSC_FALSE}));
  if (s->gamma_field && s->gamma_file[0]) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "gamma_field_file", PETSC_STRING, s->gamma_file));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Sigma", PETSC_REAL, &s->Sigma));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "critical_stress_fixed", PETSC_BOOL, s->sigma_fixed > 0 ? &(PetscBool){PETSC_TRUE} : &(PetscBool){PETSC_FALSE}));
  if (s->sigma_fixed > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "critical_stress", PETSC_REAL, &s->sigma_fixed));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "attach", PETSC_STRING, AdhAttaches[s->attach]));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "predictor", PETSC_STRING, s->predictor_type));
  if (s->force_control) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "pulloff_rtol", PETSC_REAL, &s->pulloff_rtol));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "hx", PETSC_REAL, &g->hx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "hy", PETSC_REAL, &g->hy));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Lx", PETSC_REAL, &g->Lx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Ly", PETSC_REAL, &g->Ly));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Nx", PETSC_INT, &g->Nx));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "Ny", PETSC_INT, &g->Ny));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "nranks", PETSC_INT, &nranks));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "boundary", PETSC_STRING, AdhBoundaries[s->boundary]));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "indenter", PETSC_STRING, AdhIndenterTypes[s->indenter.type]));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "start", PETSC_STRING, AdhStarts[s->start]));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "control", PETSC_STRING, s->control_type));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "criterion", PETSC_STRING, s->criterion_type));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "criterion_radius", PETSC_REAL, &s->criterion_radius));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "pull_off_force", PETSC_REAL, &pull_off));
  if (s->asperity_ac > 0) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "asperity_contact_radius", PETSC_REAL, &s->asperity_ac));
  if (k >= 0) { /* how well the grid resolves it (the curve's statistics at that state) */
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "pull_off_small_patch_tension", PETSC_REAL, &s->curve.state[k].small_patch_tension));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "pull_off_smallest_tensile_patch", PETSC_INT, &s->curve.state[k].smallest_tensile_patch));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "adhesion_resolved", PETSC_BOOL, &(PetscBool){AdhSolverResolves_Private(s, &s->curve.state[k])}));
  }
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "steps", PETSC_INT, &s->steps));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "ksp_type", PETSC_STRING, ksptype));
  PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "ksp_rtol", PETSC_REAL, &rtol));
  switch (s->indenter.type) {
  case ADH_INDENTER_SPHERE: PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "radius", PETSC_REAL, &s->indenter.radius)); break;
  case ADH_INDENTER_PUNCH: PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "punch_radius", PETSC_REAL, &s->indenter.punch_radius)); break;
  case ADH_INDENTER_CONE: PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "cone_slope", PETSC_REAL, &s->indenter.cone_slope)); break;
  case ADH_INDENTER_FILE: PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "topography", PETSC_STRING, s->indenter.topography)); break;
  case ADH_INDENTER_ROUGH: break; /* written when the file was opened */
  case ADH_INDENTER_ARRAY: break;
  }
  if (s->indenter.type == ADH_INDENTER_FILE || s->indenter.type == ADH_INDENTER_ARRAY) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "topography_kind", PETSC_STRING, AdhTopographyKinds[s->indenter.kind]));
  PetscFunctionReturn(0);
}

/* Rank 0 writes a text file through body(s, h5, fp) to NAME.part and renames it NAME, so that a
   file is either whole or absent; every rank learns whether it worked. */
static PetscErrorCode WriteTextFile(AdhSolver s, const char name[], void (*body)(AdhSolver, const char h5[], FILE *), const char h5[])
{
  char        part[PETSC_MAX_PATH_LEN + 16];
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(PartName(name, part, sizeof(part)));
  if (!rank) {
    FILE *fp = fopen(part, "w");
    if (fp) {
      body(s, h5, fp);
      ok = !ferror(fp);
      ok = (fclose(fp) == 0) && ok;
      ok = ok && rename(part, name) == 0;
    } else ok = 0;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: could not write %s", name);
  PetscFunctionReturn(0);
}

/* The curve as CSV: a step column, then one column per curve column. */
static void CSVBody(AdhSolver s, const char h5[], FILE *fp)
{
  const AdhCurve *c = &s->curve;

  fprintf(fp, "step");
  for (PetscInt j = 0; j < AdhCurveNumColumns; j++) fprintf(fp, ",%s", AdhCurveColumns[j].name);
  fprintf(fp, "\n");
  for (PetscInt k = 0; k < c->n; k++) {
    fprintf(fp, "%" PetscInt_FMT, k);
    for (PetscInt j = 0; j < AdhCurveNumColumns; j++) {
      if (AdhCurveColumns[j].integer) fprintf(fp, ",%.0f", (double)AdhStateValue(&c->state[k], j));
      else fprintf(fp, ",%.17g", (double)AdhStateValue(&c->state[k], j));
    }
    fprintf(fp, "\n");
  }
}

/* FILE.xmf beside FILE.h5 when it has fields: an XDMF description that ParaView (and VisIt) open
   as a time series over the states with fields, cell data on the grid of elements: the fields of
   each state (hyperslabs of the timestepped datasets), the profile h, the critical stress, and
   the heights of a rough surface. The time of a frame is its curve row. */
static void XDMFBody(AdhSolver s, const char h5[], FILE *fp)
{
  const AdhGrid  g = s->grid;
  const PetscInt T = s->nfield_states, Nx = g->Nx, Ny = g->Ny;

  /* cell corners: element (i, j) has its centre at ((i - Nx/2) hx, (j - Ny/2) hy) */
  const double x0 = (double)((-(Nx / 2) - 0.5) * g->hx), y0 = (double)((-(Ny / 2) - 0.5) * g->hy);
  fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n");
  fprintf(fp, "  <Grid Name=\"states\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (PetscInt t = 0; t < T; t++) {
    fprintf(fp, "   <Grid Name=\"state %" PetscInt_FMT "\" GridType=\"Uniform\">\n", s->field_states[t]);
    fprintf(fp, "    <Time Value=\"%" PetscInt_FMT "\"/>\n", s->field_states[t]);
    fprintf(fp, "    <Topology TopologyType=\"2DCoRectMesh\" Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\"/>\n", Ny + 1, Nx + 1);
    fprintf(fp, "    <Geometry GeometryType=\"ORIGIN_DXDY\">\n     <DataItem Dimensions=\"2\" Format=\"XML\">%.17g %.17g</DataItem>\n", y0, x0);
    fprintf(fp, "     <DataItem Dimensions=\"2\" Format=\"XML\">%.17g %.17g</DataItem>\n    </Geometry>\n", (double)g->hy, (double)g->hx);
    for (PetscInt f = 0; f < 4; f++) {
      if (!(s->fields & (1 << f))) continue;
      fprintf(fp, "    <Attribute Name=\"%s\" Center=\"Cell\" AttributeType=\"Scalar\">\n", AdhFieldNames[f]);
      fprintf(fp, "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\">\n", Ny, Nx);
      fprintf(fp, "      <DataItem Dimensions=\"3 3\" Format=\"XML\">%" PetscInt_FMT " 0 0 1 1 1 1 %" PetscInt_FMT " %" PetscInt_FMT "</DataItem>\n", t, Ny, Nx);
      fprintf(fp, "      <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:/fields/%s</DataItem>\n", T, Ny, Nx, f == 3 ? "UChar" : "Float", f == 3 ? 1 : 8, h5, AdhFieldNames[f]);
      fprintf(fp, "     </DataItem>\n    </Attribute>\n");
    }
    for (PetscInt f = 0; f < 3; f++) {
      const char *fixed[3] = {"profile", "critical_stress", "topography"}, *where[3] = {"/fields/profile", "/fields/critical_stress", "/topography"};
      if (f == 2 && s->indenter.type != ADH_INDENTER_ROUGH) continue;
      fprintf(fp, "    <Attribute Name=\"%s\" Center=\"Cell\" AttributeType=\"Scalar\">\n", fixed[f]);
      fprintf(fp, "     <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:%s</DataItem>\n    </Attribute>\n", Ny, Nx, h5, where[f]);
    }
    fprintf(fp, "   </Grid>\n");
  }
  fprintf(fp, "  </Grid>\n </Domain>\n</Xdmf>\n");
}

/* The curve into the viewer's current group: every column as a 1-D float64 dataset (counts too:
   PETSc's IS viewer adds a block dimension), and the path. The results file and the checkpoint
   both hold it. */
PetscErrorCode AdhOutputWriteCurve_Private(AdhSolver s, PetscViewer viewer)
{
  const AdhCurve *c = &s->curve;
  PetscReal      *column;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(c->n + 1, &column));
  for (PetscInt j = 0; j < AdhCurveNumColumns; j++) {
    for (PetscInt k = 0; k < c->n; k++) column[k] = AdhStateValue(&c->state[k], j);
    PetscCall(WriteRealArray(s, viewer, AdhCurveColumns[j].name, c->n, column));
  }
  PetscCall(PetscFree(column));
  PetscCall(WriteRealArray(s, viewer, "path", s->npath, s->path));
  PetscFunctionReturn(0);
}

PetscErrorCode AdhOutputClose_Private(AdhSolver s, const char file[], PetscViewer *viewer)
{
  char            part[PETSC_MAX_PATH_LEN + 8], csv[PETSC_MAX_PATH_LEN + 8], xmf[PETSC_MAX_PATH_LEN + 8];
  PetscMPIInt     rank;
  int             ok = 1;
  PetscReal      *column;

  PetscFunctionBegin;
  PetscCall(WriteAttributes(s, *viewer));
  PetscCall(PetscViewerHDF5PushGroup(*viewer, "/curve"));
  PetscCall(AdhOutputWriteCurve_Private(s, *viewer));
  PetscCall(PetscViewerHDF5PopGroup(*viewer));
  if (s->nfield_states) {
    PetscCall(PetscMalloc1(s->nfield_states, &column));
    for (PetscInt k = 0; k < s->nfield_states; k++) column[k] = (PetscReal)s->field_states[k];
    PetscCall(PetscViewerHDF5PushGroup(*viewer, "/fields"));
    PetscCall(WriteRealArray(s, *viewer, "state", s->nfield_states, column));
    PetscCall(PetscViewerHDF5PopGroup(*viewer));
    PetscCall(PetscFree(column));
  }

  PetscCall(PetscViewerDestroy(viewer));
  PetscCallMPI(MPI_Comm_rank(s->comm, &rank));
  PetscCall(PartName(file, part, sizeof(part)));
  if (!rank) ok = rename(part, file) == 0;
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, s->comm));
  PetscCheck(ok, s->comm, PETSC_ERR_FILE_WRITE, "-adh_output: could not move %s to %s", part, file);
  PetscCall(SiblingName(file, "csv", csv, sizeof(csv)));
  PetscCall(WriteTextFile(s, csv, CSVBody, NULL));
  if (s->nfield_states) {
    /* the XDMF names the HDF5 file without its directory: the pair can move together */
    PetscCall(SiblingName(file, "xmf", xmf, sizeof(xmf)));
    PetscCall(WriteTextFile(s, xmf, XDMFBody, strrchr(file, '/') ? strrchr(file, '/') + 1 : file));
  }
  PetscCall(PetscFree(s->field_states));
  s->nfield_states = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode AdhSolverWriteOutput(AdhSolver s, const char file[])
{
  PetscViewer viewer;

  PetscFunctionBegin;
  PetscCall(AdhOutputOpen_Private(s, file, &viewer));
  PetscCall(AdhOutputWriteFields_Private(s, viewer, PetscMax(s->curve.n - 1, 0)));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/", "complete", PETSC_BOOL, &(PetscBool){PETSC_TRUE}));
  PetscCall(AdhOutputClose_Private(s, file, &viewer));
  PetscFunctionReturn(0);
}
