/* Fields for ParaView: velocity, pressure, shear rate, effective viscosity, the level set
 * and (two-phase) the yielded indicator
 * interpolated to P1, written with PETSc's HDF5 viewer (parallel HDF5) into
 * fields.h5, and an XDMF file fields.xmf that indexes every time written. */
#include "slumpimpl.h"
#include <petscviewerhdf5.h>
#include <petscsf.h>
#include <sys/stat.h>
#include <errno.h>

struct _n_SlumpFieldWriter {
  SlumpProblem prob;
  PetscInt     nf, nc[6];
  const char  *names[6];
  DM           dmOut;
  Vec          Xout;
  char         dir[PETSC_MAX_PATH_LEN];
  PetscInt     n, cap, ncells, nverts;
  PetscReal   *times;
};

PetscErrorCode SlumpMakeDirectory(MPI_Comm comm, const char dir[])
{
  PetscMPIInt rank;
  int         err = 0;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    char   path[PETSC_MAX_PATH_LEN];
    size_t len;
    PetscCall(PetscStrncpy(path, dir, sizeof(path)));
    PetscCall(PetscStrlen(path, &len));
    for (size_t i = 1; i <= len && !err; ++i) {
      if (path[i] == '/' || path[i] == 0) {
        char c = path[i];
        path[i] = 0;
        if (mkdir(path, 0755) && errno != EEXIST) err = errno;
        path[i] = c;
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_OPEN, "Cannot create the output directory '%s' (-output_dir): %s", dir, strerror(err));
  PetscFunctionReturn(0);
}

static void CopyVelocity(SLUMP_PW_ARGS, PetscScalar f[])
{
  for (PetscInt d = 0; d < uOff[1] - uOff[0]; ++d) f[d] = u[uOff[0] + d];
}

static void CopyPressure(SLUMP_PW_ARGS, PetscScalar f[])
{
  f[0] = u[uOff[1]];
}

/* the extra field (level set) is the last one */
static void CopyLevelSet(SLUMP_PW_ARGS, PetscScalar f[])
{
  f[0] = u[uOff[Nf - 1]];
}

PetscErrorCode SlumpFieldWriterCreate(SlumpProblem prob, const char dir[], SlumpFieldWriter *writer)
{
  SlumpFieldWriter w;
  PetscInt         dim, cStart, cEnd, vStart, vEnd;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&w));
  w->prob = prob;
  PetscCall(PetscStrncpy(w->dir, dir, sizeof(w->dir)));
  PetscCall(DMGetDimension(prob->dm, &dim));
  if (prob->formulation == SLUMP_FORMULATION_TRANSPORT) {
    w->nf       = 2;
    w->names[0] = "velocity";
    w->names[1] = "levelset";
    w->nc[0]    = dim;
    w->nc[1]    = 1;
  } else if (prob->formulation == SLUMP_FORMULATION_ANTIPLANE) {
    w->nf       = 3;
    w->names[0] = "velocity";
    w->names[1] = "shear_rate";
    w->names[2] = "viscosity";
    w->nc[0] = w->nc[1] = w->nc[2] = 1;
  } else {
    w->nf       = 4;
    w->names[0] = "velocity";
    w->names[1] = "pressure";
    w->names[2] = "shear_rate";
    w->names[3] = "viscosity";
    w->nc[0]    = dim;
    w->nc[1] = w->nc[2] = w->nc[3] = 1;
    if (prob->extraField >= 0) {
      w->nf       = 5;
      w->names[4] = "levelset";
      w->nc[4]    = 1;
    }
    if (prob->twoPhase) {
      /* material fraction where yielded: 1 in the yielded material, 0 in its
         unyielded zones and in the ambient fluid */
      w->nf       = 6;
      w->names[5] = "yielded";
      w->nc[5]    = 1;
    }
  }
  PetscCall(DMClone(prob->dm, &w->dmOut));
  for (PetscInt f = 0; f < w->nf; ++f) {
    PetscFE fe;
    PetscCall(PetscFECreateLagrange(PETSC_COMM_SELF, dim, w->nc[f], PETSC_TRUE, 1, prob->quadOrder, &fe));
    PetscCall(PetscObjectSetName((PetscObject)fe, w->names[f]));
    PetscCall(DMSetField(w->dmOut, f, NULL, (PetscObject)fe));
    PetscCall(PetscFEDestroy(&fe));
  }
  PetscCall(DMCreateDS(w->dmOut));
  PetscCall(DMCreateGlobalVector(w->dmOut, &w->Xout));
  PetscCall(PetscObjectSetName((PetscObject)w->Xout, "fields"));
  PetscCall(DMPlexGetHeightStratum(prob->dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(prob->dm, 0, &vStart, &vEnd));
  *writer = w;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpFieldWriterDestroy(SlumpFieldWriter *w)
{
  PetscFunctionBeginUser;
  if (!*w) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&(*w)->Xout));
  PetscCall(DMDestroy(&(*w)->dmOut));
  PetscCall(PetscFree((*w)->times));
  PetscCall(PetscFree(*w));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteXdmf(SlumpFieldWriter w)
{
  char        path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  FILE       *fp  = NULL;
  int         err = 0;
  PetscMPIInt rank;
  PetscInt    dim;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(w->prob->comm, &rank));
  PetscCall(DMGetDimension(w->prob->dm, &dim));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields.xmf", w->dir));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s/fields.xmf.part", w->dir));
  if (rank) {
    PetscCall(SlumpFileCommit(w->prob->comm, 0, tmp, path));
    PetscFunctionReturn(0);
  }
  /* the index is rewritten whole at each output and renamed over the last */
  err = SlumpFileOpen(tmp, &fp);
  if (!err) err = SlumpFilePrintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n");
  if (!err) err = SlumpFilePrintf(fp, "  <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (PetscInt k = 0; k < w->n; ++k) {
    if (!err) err = SlumpFilePrintf(fp, "   <Grid Name=\"mesh\" GridType=\"Uniform\">\n    <Time Value=\"%.10g\"/>\n", (double)w->times[k]);
    if (!err) err = SlumpFilePrintf(fp, "    <Topology TopologyType=\"Triangle\" NumberOfElements=\"%d\">\n", (int)w->ncells);
    if (!err) err = SlumpFilePrintf(fp, "     <DataItem Dimensions=\"%d 3\" NumberType=\"Int\" Format=\"HDF\">fields.h5:/viz/topology/cells</DataItem>\n    </Topology>\n", (int)w->ncells);
    if (!err) err = SlumpFilePrintf(fp, "    <Geometry GeometryType=\"XY\">\n     <DataItem Dimensions=\"%d %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">fields.h5:/geometry/vertices</DataItem>\n    </Geometry>\n", (int)w->nverts, (int)dim);
    for (PetscInt f = 0; f < w->nf; ++f) {
      const PetscInt nc = w->nc[f];
      const char    *name = w->names[f];
      if (!err) err = SlumpFilePrintf(fp, "    <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n", name, nc > 1 ? "Vector" : "Scalar");
      if (nc > 1) {
        if (!err) err = SlumpFilePrintf(fp, "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"%d %d\" Type=\"HyperSlab\">\n", (int)w->nverts, (int)nc);
        if (!err) err = SlumpFilePrintf(fp, "      <DataItem Dimensions=\"3 3\" Format=\"XML\">%d 0 0 1 1 1 1 %d %d</DataItem>\n", (int)k, (int)w->nverts, (int)nc);
        if (!err) err = SlumpFilePrintf(fp, "      <DataItem Dimensions=\"%d %d %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">fields.h5:/vertex_fields/fields_%s</DataItem>\n", (int)w->n, (int)w->nverts, (int)nc, name);
      } else {
        if (!err) err = SlumpFilePrintf(fp, "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"%d\" Type=\"HyperSlab\">\n", (int)w->nverts);
        if (!err) err = SlumpFilePrintf(fp, "      <DataItem Dimensions=\"3 2\" Format=\"XML\">%d 0 1 1 1 %d</DataItem>\n", (int)k, (int)w->nverts);
        if (!err) err = SlumpFilePrintf(fp, "      <DataItem Dimensions=\"%d %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">fields.h5:/vertex_fields/fields_%s</DataItem>\n", (int)w->n, (int)w->nverts, name);
      }
      if (!err) err = SlumpFilePrintf(fp, "     </DataItem>\n    </Attribute>\n");
    }
    if (!err) err = SlumpFilePrintf(fp, "   </Grid>\n");
  }
  if (!err) err = SlumpFilePrintf(fp, "  </Grid>\n </Domain>\n</Xdmf>\n");
  if (!err) err = SlumpFileClose(&fp);
  else (void)SlumpFileClose(&fp);
  PetscCall(SlumpFileCommit(w->prob->comm, err, tmp, path));
  PetscFunctionReturn(0);
}

/* The mesh (first time) and the fields at one time into an open viewer. */
static PetscErrorCode WriteH5(SlumpFieldWriter w, PetscViewer v)
{
  SlumpProblem prob = w->prob;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerPushFormat(v, PETSC_VIEWER_HDF5_XDMF));
  if (!w->n) {
    PetscCall(DMView(w->dmOut, v));
    PetscInt cStart, cEnd, vStart, vEnd, nl[2];
    PetscCall(DMPlexGetHeightStratum(prob->dm, 0, &cStart, &cEnd));
    PetscCall(DMPlexGetDepthStratum(prob->dm, 0, &vStart, &vEnd));
    /* owned vertices only */
    {
      PetscSF            sf;
      PetscInt           nleaves;
      const PetscInt    *leaves;
      PetscInt           owned = vEnd - vStart;
      PetscCall(DMGetPointSF(prob->dm, &sf));
      PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &leaves, NULL));
      for (PetscInt l = 0; l < nleaves && nleaves > 0; ++l) {
        PetscInt pt = leaves ? leaves[l] : l;
        if (pt >= vStart && pt < vEnd) owned--;
      }
      nl[0] = cEnd - cStart;
      nl[1] = owned;
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, nl, 2, MPIU_INT, MPI_SUM, prob->comm));
    w->ncells = nl[0];
    w->nverts = nl[1];
  }
  PetscCall(PetscViewerHDF5PushTimestepping(v));
  PetscCall(PetscViewerHDF5SetTimestep(v, w->n));
  PetscCall(VecView(w->Xout, v));
  PetscCall(PetscViewerHDF5PopTimestepping(v));
  PetscCall(PetscViewerPopFormat(v));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpFieldWriterWrite(SlumpFieldWriter w, PetscReal t, Vec X)
{
  SlumpProblem           prob = w->prob;
  SlumpRheologyPointwise pw;
  PetscPointFunc         funcs[6];
  PetscDS                ds;
  PetscViewer            v = NULL;
  char                   path[PETSC_MAX_PATH_LEN];
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyGetPointwise(prob->rheo, &pw));
  if (prob->formulation == SLUMP_FORMULATION_TRANSPORT) {
    funcs[0] = CopyVelocity;
    funcs[1] = CopyLevelSet;
  } else if (w->nf == 3) {
    funcs[0] = CopyVelocity;
    funcs[1] = pw.shear_rate;
    funcs[2] = pw.eta;
  } else {
    funcs[0] = CopyVelocity;
    funcs[1] = CopyPressure;
    funcs[2] = pw.shear_rate;
    funcs[3] = prob->twoPhase ? pw.tp_eta : pw.eta;
    funcs[4] = CopyLevelSet;
    funcs[5] = pw.tp_yielded;
  }
  PetscCall(DMGetDS(w->dmOut, &ds));
  PetscCall(PetscDSSetConstants(ds, SLUMP_C_NUM + prob->nsurf, prob->constants));
  PetscCall(SlumpProblemFillDiagVector(prob, t, X, prob->diagX));
  PetscCall(DMProjectField(w->dmOut, t, prob->diagX, funcs, INSERT_ALL_VALUES, w->Xout));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields.h5", w->dir));
  {
    /* a failed write (full disk) closes the file and is one error naming it */
    PetscErrorCode ierr, ierr2 = 0;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* HDF5's own error stack: the error below says it */
    ierr = PetscViewerHDF5Open(prob->comm, path, w->n ? FILE_MODE_APPEND : FILE_MODE_WRITE, &v);
    if (!ierr) ierr = WriteH5(w, v);
    if (v) ierr2 = PetscViewerDestroy(&v);
    PetscCall(PetscPopErrorHandler());
    if (ierr2) SlumpSetUnclosableOutput();
    ierr = ierr ? ierr : ierr2;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ierr, 1, MPI_INT, MPI_MAX, prob->comm));
    PetscCheck(!ierr, prob->comm, PETSC_ERR_FILE_WRITE, "Cannot write the fields to %s (HDF5); free space, choose another -output_dir or give -output_fields false", path);
  }
  if (w->n == w->cap) {
    PetscReal *nt;
    w->cap = w->cap ? 2 * w->cap : 16;
    PetscCall(PetscMalloc1(w->cap, &nt));
    PetscCall(PetscArraycpy(nt, w->times, w->n));
    PetscCall(PetscFree(w->times));
    w->times = nt;
  }
  w->times[w->n++] = t;
  PetscCall(WriteXdmf(w));
  PetscFunctionReturn(0);
}
