/* Meshes: structured triangulated rectangles and Gmsh files, partitioned with
 * METIS on the cell dual graph and distributed by DMPlex. */
#include "slump.h"
#include <metis.h>
#include <unistd.h>
#include <sys/stat.h>

/* Label boundary faces of a rectangle by position: bottom, right, top, left (value 1). */
static PetscErrorCode LabelRectangleFaces(DM dm, const PetscReal lower[2], const PetscReal upper[2])
{
  const char *names[4] = {"bottom", "right", "top", "left"};
  DMLabel     bnd, side[4];
  IS          faceIS;
  PetscReal   tol = 1e-10 * PetscMax(upper[0] - lower[0], upper[1] - lower[1]);

  PetscFunctionBeginUser;
  PetscCall(DMCreateLabel(dm, "boundary"));
  PetscCall(DMGetLabel(dm, "boundary", &bnd));
  PetscCall(DMPlexMarkBoundaryFaces(dm, 1, bnd));
  for (PetscInt s = 0; s < 4; ++s) {
    PetscCall(DMCreateLabel(dm, names[s]));
    PetscCall(DMGetLabel(dm, names[s], &side[s]));
  }
  PetscCall(DMLabelGetStratumIS(bnd, 1, &faceIS));
  if (faceIS) {
    const PetscInt *faces;
    PetscInt        n;
    PetscCall(ISGetLocalSize(faceIS, &n));
    PetscCall(ISGetIndices(faceIS, &faces));
    for (PetscInt i = 0; i < n; ++i) {
      PetscReal c[3], area;
      PetscCall(DMPlexComputeCellGeometryFVM(dm, faces[i], &area, c, NULL));
      if (PetscAbsReal(c[1] - lower[1]) < tol) PetscCall(DMLabelSetValue(side[0], faces[i], 1));
      else if (PetscAbsReal(c[0] - upper[0]) < tol) PetscCall(DMLabelSetValue(side[1], faces[i], 1));
      else if (PetscAbsReal(c[1] - upper[1]) < tol) PetscCall(DMLabelSetValue(side[2], faces[i], 1));
      else if (PetscAbsReal(c[0] - lower[0]) < tol) PetscCall(DMLabelSetValue(side[3], faces[i], 1));
    }
    PetscCall(ISRestoreIndices(faceIS, &faces));
    PetscCall(ISDestroy(&faceIS));
  }
  PetscCall(DMPlexLabelComplete(dm, bnd));
  for (PetscInt s = 0; s < 4; ++s) PetscCall(DMPlexLabelComplete(dm, side[s]));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpMeshCreateRectangle(MPI_Comm comm, PetscInt nx, PetscInt ny, const PetscReal lower[2], const PetscReal upper[2], DM *dm)
{
  PetscMPIInt rank;
  PetscInt   *cells = NULL, nv = 0, nc = 0;
  PetscReal  *coords = NULL;

  PetscFunctionBeginUser;
  PetscCheck(nx > 0 && ny > 0, comm, PETSC_ERR_USER_INPUT, "-mesh_nx and -mesh_ny must be positive integers; got %" PetscInt_FMT " and %" PetscInt_FMT, nx, ny);
  PetscCheck(upper[0] > lower[0] && upper[1] > lower[1], comm, PETSC_ERR_USER_INPUT, "The domain must have positive extent; got [%g,%g] x [%g,%g]", (double)lower[0], (double)upper[0], (double)lower[1], (double)upper[1]);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    nv = (nx + 1) * (ny + 1);
    nc = 2 * nx * ny;
    PetscCall(PetscMalloc2(3 * nc, &cells, 2 * nv, &coords));
    for (PetscInt j = 0; j <= ny; ++j)
      for (PetscInt i = 0; i <= nx; ++i) {
        coords[2 * (j * (nx + 1) + i) + 0] = lower[0] + (upper[0] - lower[0]) * i / nx;
        coords[2 * (j * (nx + 1) + i) + 1] = lower[1] + (upper[1] - lower[1]) * j / ny;
      }
    for (PetscInt j = 0, c = 0; j < ny; ++j)
      for (PetscInt i = 0; i < nx; ++i, c += 2) {
        const PetscInt v00 = j * (nx + 1) + i, v10 = v00 + 1, v01 = v00 + nx + 1, v11 = v01 + 1;
        /* counter-clockwise triangles (v00, v10, v11) and (v00, v11, v01) */
        cells[3 * c + 0] = v00;
        cells[3 * c + 1] = v10;
        cells[3 * c + 2] = v11;
        cells[3 * c + 3] = v00;
        cells[3 * c + 4] = v11;
        cells[3 * c + 5] = v01;
      }
  }
  PetscCall(DMPlexCreateFromCellListPetsc(comm, 2, nc, nv, 3, PETSC_TRUE, cells, 2, coords, dm));
  PetscCall(PetscFree2(cells, coords));
  PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
  PetscCall(LabelRectangleFaces(*dm, lower, upper));
  PetscCall(SlumpMeshDistribute(dm));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpMeshCreateGmsh(MPI_Comm comm, const char filename[], DM *dm)
{
  PetscMPIInt    rank;
  int            state = 0; /* 0 readable, 1 unreadable, 2 a directory, 3 empty, 4 not a Gmsh file */
  DMLabel        bnd;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    struct stat st;
    if (stat(filename, &st) || access(filename, R_OK)) state = 1;
    else if (S_ISDIR(st.st_mode)) state = 2;
    else if (!S_ISREG(st.st_mode) || st.st_size == 0) state = 3;
    else {
      char  head[16] = "";
      FILE *fp       = fopen(filename, "r");
      if (!fp || !fgets(head, sizeof(head), fp) || strncmp(head, "$MeshFormat", 11)) state = 4;
      if (fp) fclose(fp);
    }
  }
  PetscCallMPI(MPI_Bcast(&state, 1, MPI_INT, 0, comm));
  PetscCheck(state != 1, comm, PETSC_ERR_FILE_OPEN, "Cannot read the mesh file '%s' (-mesh_file); give the path of a readable Gmsh .msh file", filename);
  PetscCheck(state != 2, comm, PETSC_ERR_FILE_OPEN, "The mesh file '%s' (-mesh_file) is a directory; give the path of a Gmsh .msh file", filename);
  PetscCheck(state != 3, comm, PETSC_ERR_FILE_OPEN, "The mesh file '%s' (-mesh_file) is empty; give a Gmsh .msh file", filename);
  PetscCheck(state != 4, comm, PETSC_ERR_FILE_OPEN, "The mesh file '%s' (-mesh_file) is not a Gmsh .msh file (it does not start with $MeshFormat)", filename);
  /* physical names become labels of the same name; a file Gmsh's reader
     cannot parse is one sentence, not PETSc's traceback */
  PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_use_regions", "true"));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = DMPlexCreateGmshFromFile(comm, filename, PETSC_TRUE, dm);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscOptionsClearValue(NULL, "-dm_plex_gmsh_use_regions"));
  PetscCheck(!ierr, comm, PETSC_ERR_FILE_UNEXPECTED, "The mesh file '%s' (-mesh_file) could not be read as a Gmsh mesh (format 2.2 or 4.1, triangles, physical names for the boundaries); check it with gmsh", filename);
  PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
  PetscCall(DMCreateLabel(*dm, "boundary"));
  PetscCall(DMGetLabel(*dm, "boundary", &bnd));
  PetscCall(DMPlexMarkBoundaryFaces(*dm, 1, bnd));
  /* complete every label so essential conditions reach edges and vertices */
  {
    PetscInt nl;
    PetscCall(DMGetNumLabels(*dm, &nl));
    for (PetscInt l = 0; l < nl; ++l) {
      DMLabel     label;
      const char *name;
      PetscBool   skip;
      PetscCall(DMGetLabelByNum(*dm, l, &label));
      PetscCall(PetscObjectGetName((PetscObject)label, &name));
      PetscCall(PetscStrcmp(name, "depth", &skip));
      if (!skip) PetscCall(PetscStrcmp(name, "celltype", &skip));
      if (!skip) PetscCall(PetscStrcmp(name, "Cell Sets", &skip));
      if (!skip) PetscCall(DMPlexLabelComplete(*dm, label));
    }
  }
  PetscCall(SlumpMeshDistribute(dm));
  PetscFunctionReturn(0);
}

/* METIS k-way partition of the cell dual graph (computed where the cells are,
   i.e. on rank 0 for a freshly created mesh), handed to DMPlex through a shell
   partitioner. -petscpartitioner_type still overrides. */
PetscErrorCode SlumpMeshDistribute(DM *dm)
{
  MPI_Comm         comm;
  PetscMPIInt      size, rank;
  PetscPartitioner part;
  DM               dist = NULL;
  PetscInt         nvtx, *offsets = NULL, *adjacency = NULL, *sizes, *points;
  IS               gnum;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)*dm, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (size == 1) PetscFunctionReturn(0);
  PetscCall(DMPlexCreatePartitionerGraph(*dm, 0, &nvtx, &offsets, &adjacency, &gnum));
  PetscCall(PetscCalloc2(size, &sizes, nvtx, &points));
  if (nvtx > 0) {
    idx_t  n = (idx_t)nvtx, ncon = 1, nparts = (idx_t)size, objval, options[METIS_NOPTIONS];
    idx_t *xadj, *adjncy, *owner;
    int    status;
    PetscCall(PetscMalloc3(nvtx + 1, &xadj, offsets[nvtx], &adjncy, nvtx, &owner));
    for (PetscInt i = 0; i <= nvtx; ++i) xadj[i] = (idx_t)offsets[i];
    for (PetscInt i = 0; i < offsets[nvtx]; ++i) adjncy[i] = (idx_t)adjacency[i];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED]    = 0;
    options[METIS_OPTION_NUMBERING] = 0;
    if (nvtx >= size) {
      status = METIS_PartGraphKway(&n, &ncon, xadj, adjncy, NULL, NULL, NULL, &nparts, NULL, NULL, options, &objval, owner);
      PetscCheck(status == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_PartGraphKway failed (status %d)", status);
    } else {
      for (PetscInt i = 0; i < nvtx; ++i) owner[i] = (idx_t)i;
    }
    for (PetscInt i = 0; i < nvtx; ++i) sizes[owner[i]]++;
    {
      PetscInt *start;
      PetscCall(PetscCalloc1(size + 1, &start));
      for (PetscInt p = 0; p < size; ++p) start[p + 1] = start[p] + sizes[p];
      for (PetscInt i = 0; i < nvtx; ++i) points[start[owner[i]]++] = i;
      PetscCall(PetscFree(start));
    }
    PetscCall(PetscFree3(xadj, adjncy, owner));
  }
  PetscCall(PetscFree(offsets));
  PetscCall(PetscFree(adjacency));
  PetscCall(ISDestroy(&gnum));
  PetscCall(DMPlexGetPartitioner(*dm, &part));
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSHELL));
  PetscCall(PetscPartitionerShellSetPartition(part, size, sizes, points));
  PetscCall(PetscPartitionerSetFromOptions(part));
  PetscCall(PetscFree2(sizes, points));
  PetscCall(DMPlexDistribute(*dm, 0, NULL, &dist));
  if (dist) {
    PetscCall(DMDestroy(dm));
    *dm = dist;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpMeshGetMinEdgeLength(DM dm, PetscReal *hmin)
{
  PetscInt  eStart, eEnd;
  PetscReal h = PETSC_MAX_REAL;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 1, &eStart, &eEnd));
  for (PetscInt e = eStart; e < eEnd; ++e) {
    PetscReal len, c[3];
    PetscCall(DMPlexComputeCellGeometryFVM(dm, e, &len, c, NULL));
    h = PetscMin(h, len);
  }
  PetscCall(MPIU_Allreduce(&h, hmin, 1, MPIU_REAL, MPIU_MIN, PetscObjectComm((PetscObject)dm)));
  PetscFunctionReturn(0);
}
