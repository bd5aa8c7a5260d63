#include "results/resultsimpl.h"

/* FILE.xmf beside FILE.h5 when it has fields: an XDMF description that ParaView (and VisIt) open
   as a time series over the states with fields, cell data on the grid of elements: the fields of
   each state (hyperslabs of the timestepped datasets), the profile h, the critical stress, and
   the heights of a rough surface. The time of a frame is its curve row. */
void AdhOutputXDMFBody_Private(AdhSolver s, const char h5[], FILE *fp)
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
