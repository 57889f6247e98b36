/* slump scenes and the driver. A scene is one file: geometry, boundary
 * conditions, initial state, effects, rheology defaults, and the reference
 * solution if it has one. Scenes are registered by name (-scene NAME). */
#pragma once

#include "slump.h"
#include "slumprheology.h"
#include "slumptimeint.h"

#define SLUMP_SCENE_MAX_ITEMS 16

typedef struct _n_SlumpScene *SlumpScene;
struct _n_SlumpScene {
  char      name[64];
  PetscBool steady;               /* steady state (KINSOL) or time integration */
  PetscReal tfinal, dtout;        /* defaults for -time_final, -time_output_dt */
  PetscReal arrest_threshold;     /* default for -arrest_mean_shear_rate       */
  PetscInt  mesh_n[2];            /* cells across (x, y) of the default mesh    */
  /* energy estimate T <= rho/(eta_p l1) ln(1 + eta_p l1 ||u0|| / (tau0 beta)):
     beta (0: unknown for this geometry) and the factor turning the L2 norm
     over the mesh into the norm of the estimate (1/sqrt(Lx) for 1-D strips) */
  PetscReal bound_beta, bound_norm_scale;
  /* key parameters, written to summary.csv */
  PetscInt  nparam;
  char      pname[SLUMP_SCENE_MAX_ITEMS][32];
  PetscReal pvalue[SLUMP_SCENE_MAX_ITEMS];
  /* optional: compute the initial state into X (e.g. a steady state by KINSOL) */
  PetscErrorCode (*initial)(SlumpScene, SlumpProblem, Vec X);
  /* scene-specific results at the end of the run (plug width, bounds, ...) */
  PetscErrorCode (*results)(SlumpScene, SlumpProblem, PetscReal t, Vec X);
  PetscInt  nresult;
  char      rname[SLUMP_SCENE_MAX_ITEMS][32];
  PetscReal rvalue[SLUMP_SCENE_MAX_ITEMS];
  void     *ctx;
};

typedef PetscErrorCode (*SlumpSceneCreateFn)(SlumpScene, SlumpProblem, MPI_Comm);

PETSC_EXTERN PetscErrorCode SlumpSceneRegister(const char name[], const char description[], SlumpSceneCreateFn create);
PETSC_EXTERN PetscErrorCode SlumpSceneRegisterAll(void);
PETSC_EXTERN PetscErrorCode SlumpSceneView(MPI_Comm comm);
PETSC_EXTERN PetscErrorCode SlumpSceneCreate(MPI_Comm comm, const char name[], SlumpProblem prob, SlumpScene *scene);
PETSC_EXTERN PetscErrorCode SlumpSceneDestroy(SlumpScene *scene);
PETSC_EXTERN PetscErrorCode SlumpSceneAddParameter(SlumpScene scene, const char name[], PetscReal value);
PETSC_EXTERN PetscErrorCode SlumpSceneAddResult(SlumpScene scene, const char name[], PetscReal value);
/* Mesh from -mesh_file, or a rectangle with -mesh_nx x -mesh_ny cells. */
PETSC_EXTERN PetscErrorCode SlumpSceneCreateMesh(SlumpScene scene, MPI_Comm comm, const PetscReal lower[2], const PetscReal upper[2], DM *dm);

/* The slump program: parse options, run one scene, write the outputs. */
PETSC_EXTERN PetscErrorCode SlumpRun(MPI_Comm comm);
/* Error handler printing one sentence for user errors (input, files, convergence). */
PETSC_EXTERN PetscErrorCode SlumpErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx);
