/* slump scenes and the driver. A scene is one file: geometry, boundary
 * conditions, initial state, effects, rheology defaults, and the reference
 * solution if it has one. Scenes are registered by name (-scene NAME). */
#pragma once

#include "slump.h"
#include "slumprheology.h"
#include "slumptimeint.h"

#define SLUMP_SCENE_MAX_ITEMS 24

typedef struct _n_SlumpScene *SlumpScene;
struct _n_SlumpScene {
  char      name[64];
  PetscBool steady;               /* steady state (KINSOL) or time integration */
  PetscReal t0;                   /* initial time (0 unless the scene starts later, e.g. at an impact) */
  PetscReal tfinal, dtout;        /* defaults for -time_final, -time_output_dt */
  PetscReal arrest_threshold;     /* default for -arrest_mean_shear_rate       */
  PetscReal rtol, atol;           /* defaults for -time_rtol, -time_atol (0: the integrator's) */
  PetscReal restart_step;         /* default for -ida_restart_step (0: the integrator's) */
  PetscBool linesearch;           /* default for -ida_nonlinear_solver: linesearch (else newton) */
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
  /* a steady scene whose initial() ends on the converged steady state (a
     continuation of its own): the driver reports that state and these
     counters instead of solving again from it */
  PetscBool  initial_solved;
  SlumpStats initial_stats;
  /* scene-specific results at the end of the run (plug width, bounds, ...) */
  PetscErrorCode (*results)(SlumpScene, SlumpProblem, PetscReal t, Vec X);
  PetscInt  nresult;
  char      rname[SLUMP_SCENE_MAX_ITEMS][32];
  PetscReal rvalue[SLUMP_SCENE_MAX_ITEMS];
  /* optional: the exact (unregularised) model's stopping time, and the time
     its diagnostic `diag` falls below `threshold` (-1: not available) */
  PetscErrorCode (*exact_arrest)(SlumpScene, SlumpProblem, SlumpDiagnosticKind diag, PetscReal threshold, PetscReal *t_stop, PetscReal *t_arrest);
  char      dir[PETSC_MAX_PATH_LEN]; /* the run's output directory (set by the driver before results) */
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

/* What one run measured (filled by SlumpRunOne, one row of a sweep). */
typedef struct {
  char       scene[64], rheology[64], regularisation[64], integrator[16];
  PetscReal  regularisation_value, rtol, atol, dt;
  PetscInt   ranks, cells, unknowns;
  PetscReal  t_final, t_arrest; /* t_arrest: the earliest criterion, -1 if none fired */
  PetscInt   narrest;
  PetscInt   arrest_diag[16], arrest_kind[16];
  PetscReal  arrest_time[16], arrest_threshold[16];
  SlumpStats stats;
  PetscReal  wall_time, peak_mb; /* peak resident memory summed over the run's ranks */
  PetscReal  err_u, norm_u;      /* L2 velocity error and norm (err_u < 0: no reference field) */
  PetscInt   nresult;
  char       rname[SLUMP_SCENE_MAX_ITEMS][32];
  PetscReal  rvalue[SLUMP_SCENE_MAX_ITEMS];
} SlumpRunResult;

/* The slump program: a sweep (-sweep) or one run. */
PETSC_EXTERN PetscErrorCode SlumpRun(MPI_Comm comm);
/* One run on comm: parse options, run the scene, write its outputs; banner:
   print the set-up and the summary line; res (may be NULL) gets the numbers. */
PETSC_EXTERN PetscErrorCode SlumpRunOne(MPI_Comm comm, PetscBool banner, SlumpRunResult *res);
/* Read and check every option of one run and set it up, without running it
   or writing anything (the sweep checks its swept options with it). */
PETSC_EXTERN PetscErrorCode SlumpRunSetUp(MPI_Comm comm);
/* -sweep NAME:v1,v2,... [-sweep2 NAME2:w1,w2,...]: one run per value (or
   pair), -sweep_ranks k ranks each on its own sub-communicator, one row per
   run in <output_dir>/sweep.csv as runs finish. */
PETSC_EXTERN PetscErrorCode SlumpSweep(MPI_Comm comm);
/* Every option the program reads, from its sources (optiontable.c, made by
   cases/options_table.py at build time); the last entry has name NULL. kind:
   real, int, bool, string, choice, reals, ints, strings, flag. An option
   read with PetscOptionsGet*() gets its help from a comment
   "option -name [late]: help" before the call. */
typedef struct {
  const char *name, *kind, *help, *group;
  PetscBool   late; /* read only after the run is set up (marked "option -name late:" in a comment) */
} SlumpOptionInfo;
PETSC_EXTERN const SlumpOptionInfo SlumpOptionTable[];
/* Options given but not read are errors (options.c). At the start: unknown
   names, options of PETSc objects slump does not create, missing values and
   non-finite numbers; once the run is set up (nothing written yet): options
   of the table the set-up should have read; at the end: any option the run
   did not read. -options_ignore_unused turns the unread ones off. */
typedef enum { SLUMP_OPTIONS_START, SLUMP_OPTIONS_SETUP, SLUMP_OPTIONS_END } SlumpOptionsStage;
PETSC_EXTERN PetscErrorCode SlumpOptionsCheck(MPI_Comm comm, SlumpOptionsStage stage);
/* Is the option (without its dash) one slump or the PETSc solvers it
   creates may read? */
PETSC_EXTERN PetscBool SlumpOptionKnown(const char name[]);
/* Is it read only when the run's solvers are created (KINSOL, steady
   continuation, PETSc solver options), so that a set-up cannot tell? */
PETSC_EXTERN PetscBool SlumpOptionReadLate(const char name[]);
/* An error naming `what` and the closest known option unless name is known. */
PETSC_EXTERN PetscErrorCode SlumpOptionsCheckName(MPI_Comm comm, const char what[], const char name[]);
/* -help: the program's options by group (PETSc's under -help petsc). */
PETSC_EXTERN PetscErrorCode SlumpPrintHelp(MPI_Comm comm);
/* The first message of the last error (empty if none), and its reset. */
PETSC_EXTERN const char    *SlumpLastErrorMessage(void);
PETSC_EXTERN void           SlumpClearLastError(void);
/* Error handler printing one sentence for user errors (input, files, convergence). */
PETSC_EXTERN PetscErrorCode SlumpErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx);
