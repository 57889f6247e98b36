/* Private: the level-set object and its kernels' constants. */
#pragma once

#include "slumpinterface.h"

/* constants[SLUMP_C_FIELD + k] */
enum {
  SLUMP_LS_H      = 0, /* smallest edge length                       */
  SLUMP_LS_SUPG   = 1, /* SUPG factor                                */
  SLUMP_LS_LAMBDA = 2, /* convective redistancing speed (0: off)     */
  SLUMP_LS_E      = 3, /* filter width E                             */
  SLUMP_LS_DEG    = 4, /* polynomial degree of phi                   */
  SLUMP_LS_SPEED  = 5  /* SUPG speed floor a0 (0: tau(a) frozen)     */
};

/* The nodal picture of phi used by the geometric operations: its dofs
   (local vector indices and coordinates) and a triangulation of them
   (each P2 cell split into four P1 sub-triangles). */
typedef struct {
  PetscInt   nnode, ntri;
  PetscInt   nloc, nglob; /* sizes of the DM's local and global vectors */
  PetscInt  *lidx;      /* node -> local vector index               */
  PetscReal *xy;        /* node coordinates (2 per node)            */
  PetscInt  *tri;       /* 3 nodes per sub-triangle                 */
  PetscInt  *adjOff, *adj; /* node -> sub-triangles (CSR)           */
} SlumpLSNodes;

struct _n_SlumpLevelSet {
  MPI_Comm       comm;
  SlumpProblem   prob;
  PetscInt       degree, field;
  PetscReal      supg, supg_speed, h;
  /* reinitialisation */
  char           reinit_name[64];
  SlumpReinitOps reinit;
  PetscInt       reinit_every, nreinit;
  PetscReal      lambda, E_cells, hj_cfl;
  PetscInt       hj_iterations;
  /* initial signed distance from the scene */
  SlumpPointFn   phi0;
  void          *phi0ctx;
  /* geometry */
  SlumpLSNodes  *nodes;
  /* volume record */
  PetscReal      volume0, volume, max_drift;
  PetscBool      have_volume0;
  FILE          *log;    /* interface.csv (rank 0) */
  PetscBool      haslog; /* a log is set (every rank) */
  char           logpath[PETSC_MAX_PATH_LEN];
  PetscBool      volume_correction;
  PetscReal      volume_shift; /* sum of the corrections' shifts of phi */
  /* potential energy the between-step actions add to the material (sums of
     the jumps across each reinitialisation and each volume correction) */
  PetscReal      energy_reinit, energy_correction;
  PetscInt       ngauge;
  PetscReal      gauge[4];
  /* free-surface height handed to the kernels between steps */
  PetscBool      surface_feed;
  PetscInt       nsurf;
  PetscReal     *surf_x, *surf_h;
};

PETSC_INTERN PetscErrorCode SlumpLSNodesGet(SlumpLevelSet ls, SlumpLSNodes **nodes);
PETSC_INTERN PetscErrorCode SlumpLSNodesDestroy(SlumpLSNodes **nodes);
/* redistance.c: the two geometric between-step actions */
PETSC_INTERN PetscErrorCode SlumpReinitApply_Redistance(SlumpLevelSet ls, SlumpProblem prob, PetscReal t, Vec X, PetscBool *changed);
PETSC_INTERN PetscErrorCode SlumpReinitApply_HamiltonJacobi(SlumpLevelSet ls, SlumpProblem prob, PetscReal t, Vec X, PetscBool *changed);
/* levelset.c: kernels of the two residual hooks */
PETSC_INTERN PetscErrorCode SlumpReinitSetPointwise_Transport(SlumpLevelSet ls, PetscDS ds, PetscInt field);
PETSC_INTERN PetscErrorCode SlumpReinitSetPointwise_Convective(SlumpLevelSet ls, PetscDS ds, PetscInt field);
