/* slump interface: the material/ambient interface as the zero contour of a
 * level set phi (negative in the material, positive in the ambient fluid),
 * carried in the DAE state as an extra field and transported by the flow
 * with SUPG stabilisation.
 *
 * Reinitialisation is a registry of methods, each with two hooks:
 *   - a contribution to the level-set residual (its pointwise kernels), and
 *   - an action between accepted steps, after which the integrator restarts
 *     from the modified state (IDAReInit at order 1).
 * Registered: none, convective (Riber's thesis eq. 2.16: transport and
 * redistancing coupled in one residual, on the filtered E tanh(phi/E)),
 * redistance (geometric: signed distance to the reconstructed zero contour)
 * and hamilton_jacobi (pseudo-time iterations of phi_tau + s(phi0)(|grad phi| - 1) = 0
 * with a monotone upwind scheme).
 *
 * Options (all under -levelset_ and -reinit_):
 *   -levelset_degree 1|2          P1 or P2 level set (default 2)
 *   -levelset_supg <f>            SUPG factor (0: Galerkin; default 1)
 *   -reinit <name>                method (default: the scene's)
 *   -reinit_every <n>             between-step action every n steps (default 20)
 *   -reinit_convective_lambda <v> redistancing speed lambda (default 1)
 *   -reinit_convective_width <w>  filter width E in cells (default 2)
 *   -reinit_hj_iterations <n>     pseudo-time iterations (default 30)
 *   -reinit_hj_cfl <c>            pseudo-time step over the local mesh size (default 0.8)
 *   -reinit_volume_correction     after each between-step reinitialisation shift phi by
 *                                 a constant so that the material volume is the initial
 *                                 one (global correction; default off) */
#pragma once

#include "slump.h"

typedef struct _n_SlumpLevelSet *SlumpLevelSet;

/* A reinitialisation method. */
typedef struct {
  /* residual hook: register the level-set kernels of field `field` (NULL: plain SUPG transport) */
  PetscErrorCode (*set_pointwise)(SlumpLevelSet ls, PetscDS ds, PetscInt field);
  /* between-step hook (NULL: none); *changed if X was modified */
  PetscErrorCode (*apply)(SlumpLevelSet ls, SlumpProblem prob, PetscReal t, Vec X, PetscBool *changed);
  /* the state holds the filtered E tanh(d/E) instead of the distance d */
  PetscBool filtered;
  /* the kernels read the state of the last accepted step as auxiliary
     fields (SlumpProblemSetLaggedState, updated after every step) */
  PetscBool lagged;
} SlumpReinitOps;

PETSC_EXTERN PetscErrorCode SlumpReinitRegister(const char name[], const char description[], const SlumpReinitOps *ops);
PETSC_EXTERN PetscErrorCode SlumpReinitRegisterAll(void);

/* Create the level set and attach it to prob as its extra field (before
   SlumpProblemSetUp). phi0: signed distance, negative in the material. The
   problem owns the object. */
PETSC_EXTERN PetscErrorCode SlumpLevelSetCreate(SlumpProblem prob, SlumpPointFn phi0, void *ctx, SlumpLevelSet *ls);
/* The level set of a problem (NULL if it has none). */
PETSC_EXTERN PetscErrorCode SlumpProblemGetLevelSet(SlumpProblem prob, SlumpLevelSet *ls);
PETSC_EXTERN PetscErrorCode SlumpLevelSetSetReinitType(SlumpLevelSet ls, const char name[]);
PETSC_EXTERN PetscErrorCode SlumpLevelSetGetReinitType(SlumpLevelSet ls, const char **name);
/* Between-step reinitialisation every n accepted steps (default 20; -reinit_every). */
PETSC_EXTERN PetscErrorCode SlumpLevelSetSetReinitEvery(SlumpLevelSet ls, PetscInt n);
PETSC_EXTERN PetscErrorCode SlumpLevelSetSetFromOptions(SlumpLevelSet ls);
/* Interface record, one row per accepted step: t, material volume, drift,
   reinitialisations so far, the material's extent x_min, x_max, y_max and
   the heights at the gauges (rank 0 writes; NULL closes). */
/* The level set's bookkeeping a checkpoint keeps (SLUMP_LEVELSET_STATE
   reals: reinitialisations, initial and current volume, largest drift,
   volume shift, the energies the between-step actions added). */
#define SLUMP_LEVELSET_STATE 8
PETSC_EXTERN PetscErrorCode SlumpLevelSetGetState(SlumpLevelSet ls, PetscReal v[]);
PETSC_EXTERN PetscErrorCode SlumpLevelSetSetState(SlumpLevelSet ls, const PetscReal v[]);
PETSC_EXTERN PetscErrorCode SlumpLevelSetSetLog(SlumpLevelSet ls, const char path[]);
/* Record the volume at (t, X) (the first call sets the reference volume);
   called after every accepted step, and by the driver at the initial time. */
PETSC_EXTERN PetscErrorCode SlumpLevelSetRecordVolume(SlumpLevelSet ls, PetscReal t, Vec X);

/* Material volume (area in 2D; int r dA, the volume per radian, in the
   axisymmetric geometry) of {phi < 0}, exact for the piecewise linear
   interpolant of the nodal values (collective). */
PETSC_EXTERN PetscErrorCode SlumpLevelSetComputeVolume(SlumpLevelSet ls, PetscReal t, Vec X, PetscReal *volume);
/* Bounding box {xmin, xmax, ymin, ymax} of the material {phi < 0} of the
   linear interpolant (the front is xmax for a collapse spreading to +x). */
PETSC_EXTERN PetscErrorCode SlumpLevelSetComputeExtent(SlumpLevelSet ls, PetscReal t, Vec X, PetscReal box[4]);
/* Highest point of the material on the vertical line x = x0 (a wall, the
   symmetry axis, a gauge); found = PETSC_FALSE if no material is there. */
PETSC_EXTERN PetscErrorCode SlumpLevelSetComputeHeightAt(SlumpLevelSet ls, PetscReal t, Vec X, PetscReal x0, PetscReal *top, PetscBool *found);
/* Vertical gauges whose material height is logged (up to 4): the log then
   has the columns height_at_<x> after x_min, x_max, y_max. */
/* Heights of the material on the vertical lines x0[npt] (0 where there is
   none), in one pass (collective). */
PETSC_EXTERN PetscErrorCode SlumpLevelSetComputeProfile(SlumpLevelSet ls, PetscReal t, Vec X, PetscInt npt, const PetscReal x0[], PetscReal top[]);
/* The profile across the mesh (four samples per smallest edge) as CSV
   x,height (rank 0 writes): the deposit of a collapse at its final time. */
PETSC_EXTERN PetscErrorCode SlumpLevelSetWriteProfile(SlumpLevelSet ls, PetscReal t, Vec X, const char path[]);
/* Hand the current free-surface height h(x) (SlumpLevelSetComputeProfile on
   four samples per smallest edge) to the kernels at the start and after
   every accepted step (SlumpProblemSetSurfaceHeight): the lithostatic
   yield stress then uses the depth below the current surface, lagged by
   one step. Option -levelset_surface_feed. */
PETSC_EXTERN PetscErrorCode SlumpLevelSetSetSurfaceFeed(SlumpLevelSet ls, PetscBool on);
/* Speed floor a0 >= 0 of the transport's SUPG, tau = h/(2 sqrt(|a|^2 + a0^2)):
   a0 > 0 makes tau smooth in the velocity and the Jacobian exact (0, the
   default: tau(a) frozen in the Jacobian). Option -levelset_supg_speed. */
PETSC_EXTERN PetscErrorCode SlumpLevelSetSetSUPGSpeed(SlumpLevelSet ls, PetscReal a0);
/* Compute and hand over the surface now (collective; no-op if not fed). */
PETSC_EXTERN PetscErrorCode SlumpLevelSetUpdateSurface(SlumpLevelSet ls, PetscReal t, Vec X);
PETSC_EXTERN PetscErrorCode SlumpLevelSetSetGauges(SlumpLevelSet ls, PetscInt n, const PetscReal x[]);
/* | |grad d| - 1 | over the band of cells within `band` cells of the zero
   contour (d: the distance, recovered from the filtered state if need be):
   area-weighted mean and maximum (collective). */
PETSC_EXTERN PetscErrorCode SlumpLevelSetComputeGradientDeviation(SlumpLevelSet ls, PetscReal t, Vec X, PetscReal band, PetscReal *mean, PetscReal *max);
/* Apply the between-step action now (whatever -reinit_every says). */
PETSC_EXTERN PetscErrorCode SlumpLevelSetReinitialise(SlumpLevelSet ls, PetscReal t, Vec X, PetscBool *changed);
/* Volumes: initial, current; number of between-step actions applied. */
/* Global volume correction after each between-step reinitialisation. */
PETSC_EXTERN PetscErrorCode SlumpLevelSetSetVolumeCorrection(SlumpLevelSet ls, PetscBool on);
/* Sum of the shifts applied by the volume correction (its total effect on phi). */
PETSC_EXTERN PetscErrorCode SlumpLevelSetGetVolumeShift(SlumpLevelSet ls, PetscReal *shift);
/* Potential energy the between-step actions have added to the material so
   far: the sums of its jumps across the reinitialisations and across the
   volume corrections (0 without gravity). A closed energy budget reads
   kinetic + dissipated = released + reinit + correction, less the floor's
   friction and the ambient fluid's dissipation. Also the columns
   energy_reinit and energy_correction of interface.csv. */
PETSC_EXTERN PetscErrorCode SlumpLevelSetGetEnergyInput(SlumpLevelSet ls, PetscReal *reinit, PetscReal *correction);
PETSC_EXTERN PetscErrorCode SlumpLevelSetGetStats(SlumpLevelSet ls, PetscReal *volume0, PetscReal *volume, PetscReal *max_drift, PetscInt *nreinit);
/* Smallest edge length used by the stabilisation and the widths. */
PETSC_EXTERN PetscErrorCode SlumpLevelSetGetMeshSize(SlumpLevelSet ls, PetscReal *h);
