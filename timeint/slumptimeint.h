/* slump time integration: the semi-discrete DAE F(t, y, y') = 0 of a
 * SlumpProblem handed to SUNDIALS.
 *   ida   adaptive variable-step BDF (IDA), order <= 2, pressure algebraic
 *         and out of the error test, consistent initial conditions;
 *   bdf2  fixed-step BDF2 (first step BDF1), each step solved by KINSOL:
 *         the reference against which adaptivity is measured;
 *   steady  F(y, 0) = 0 by KINSOL with line search, with continuation in
 *         the rheology's regularisation parameter.
 * Linear systems J = dF/dy + cj dF/dy' go to a PETSc KSP (default LU with
 * MUMPS; every -ksp_/-pc_ option applies). */
#pragma once

#include "slump.h"

typedef struct _n_SlumpIntegrator *SlumpIntegrator;

typedef enum { SLUMP_INTEGRATOR_IDA, SLUMP_INTEGRATOR_BDF2, SLUMP_INTEGRATOR_EXACT } SlumpIntegratorType;
PETSC_EXTERN const char *const SlumpIntegratorTypes[];

/* Counters, cumulative over a run. */
typedef struct {
  PetscInt  steps, res_evals, jac_evals, newton_its, lin_its, lin_solves;
  PetscInt  err_test_fails, conv_fails;
  PetscInt  restarts; /* restarts after a between-step change of the state (reinitialisation) */
  PetscReal h_min, h_max;
} SlumpStats;

/* One accepted step; X is the state at t (read only, valid in the monitor). */
typedef struct {
  PetscReal t, h;
  PetscInt  order, newton_its, lin_its, err_test_fails, conv_fails;
  Vec       X;
} SlumpStepRecord;

typedef PetscErrorCode (*SlumpStepMonitorFn)(SlumpIntegrator, const SlumpStepRecord *, void *);
typedef PetscErrorCode (*SlumpOutputMonitorFn)(SlumpIntegrator, PetscReal t, Vec X, void *);
typedef PetscErrorCode (*SlumpEventMonitorFn)(SlumpIntegrator, PetscReal t, PetscInt which, void *);

PETSC_EXTERN PetscErrorCode SlumpIntegratorCreate(SlumpProblem prob, SlumpIntegrator *ti);
PETSC_EXTERN PetscErrorCode SlumpIntegratorDestroy(SlumpIntegrator *ti);
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetType(SlumpIntegrator ti, SlumpIntegratorType type);
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetType(SlumpIntegrator ti, SlumpIntegratorType *type);
/* -time_integrator ida|bdf2 -time_final -time_output_dt -time_rtol -time_atol
   -time_dt (bdf2 step; ida first step) -time_max_steps -arrest -arrest_stop */
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetFromOptions(SlumpIntegrator ti);
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetTimes(SlumpIntegrator ti, PetscReal t0, PetscReal tfinal, PetscReal dtout);
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetTimes(SlumpIntegrator ti, PetscReal *t0, PetscReal *tfinal, PetscReal *dtout);
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetRestartStep(SlumpIntegrator ti, PetscReal fraction);
/* IDA's per-step nonlinear solver: its modified Newton (PETSC_FALSE, the
   default) or KINSOL with a line search and an exact Jacobian (PETSC_TRUE);
   option -ida_nonlinear_solver newton|linesearch. */
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetLineSearch(SlumpIntegrator ti, PetscBool on);
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetTolerances(SlumpIntegrator ti, PetscReal rtol, PetscReal atol);
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetTolerances(SlumpIntegrator ti, PetscReal *rtol, PetscReal *atol);
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetTimeStep(SlumpIntegrator ti, PetscReal dt);
/* Arrest criteria: IDA root functions g = diagnostic - threshold (falling).
   The threshold is absolute, relative to the diagnostic's initial value, or
   "creep": value x (characteristic stress / plug viscosity), the shear rate
   of a Newtonian fluid with the regularised plug viscosity (Riber's thesis).
   Options: -arrest name:value[:absolute|relative|creep],... with the names
   of SlumpDiagnosticNames; -arrest_stop none|first|all. */
typedef enum { SLUMP_THRESHOLD_ABSOLUTE, SLUMP_THRESHOLD_RELATIVE, SLUMP_THRESHOLD_CREEP } SlumpThresholdKind;
PETSC_EXTERN const char *const SlumpThresholdKinds[];
typedef struct {
  SlumpDiagnosticKind diag;
  SlumpThresholdKind  kind;
  PetscReal           value;     /* as given                         */
  PetscReal           threshold; /* resolved at the initial time     */
  PetscReal           t_arrest;  /* first time below it; -1 if none  */
} SlumpArrestCriterion;
typedef enum { SLUMP_ARREST_STOP_NONE, SLUMP_ARREST_STOP_FIRST, SLUMP_ARREST_STOP_ALL } SlumpArrestStop;
PETSC_EXTERN PetscErrorCode SlumpIntegratorAddArrestCriterion(SlumpIntegrator ti, SlumpDiagnosticKind diag, SlumpThresholdKind kind, PetscReal value);
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetArrestCriteria(SlumpIntegrator ti, PetscInt *n, const SlumpArrestCriterion **c);
/* Stress scale of the scene for the creep threshold (default 1). */
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetCharacteristicStress(SlumpIntegrator ti, PetscReal stress);
/* Default criterion of a scene: mean shear rate below threshold (<= 0: none);
   replaced by -arrest. */
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetArrestThreshold(SlumpIntegrator ti, PetscReal threshold, PetscBool stop);
/* Earliest arrest time over the criteria (-1 if none). */
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetArrestTime(SlumpIntegrator ti, PetscReal *tarrest);
/* From a monitor: end the solve after the current step (and its outputs),
   as an interrupted run does; SlumpIntegratorGetStopRequested tells. */
/* Checkpoint/restart (checkpoint.c; options -checkpoint_every N steps,
   -checkpoint_interval T of simulated time, -restart FILE). The hook adds
   up to SLUMP_CHECKPOINT_MAX_EXTRA reals of the caller's own state (its
   accumulators) to each checkpoint and gives them back on restart.
   Checkpoints go to dir/checkpoint.h5 (SetCheckpointDirectory; none without
   it). LoadCheckpoint reads the state at t_c into X and prepares the next
   Solve to resume there (same ranks, scene, mesh and integrator). */
#define SLUMP_CHECKPOINT_MAX_EXTRA 64
typedef PetscErrorCode (*SlumpCheckpointGetFn)(void *ctx, PetscInt *n, PetscReal v[]);
typedef PetscErrorCode (*SlumpCheckpointSetFn)(void *ctx, PetscInt n, const PetscReal v[]);
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetCheckpointHook(SlumpIntegrator ti, SlumpCheckpointGetFn get, SlumpCheckpointSetFn set, void *ctx);
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetCheckpointDirectory(SlumpIntegrator ti, const char dir[]);
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetRestartFile(SlumpIntegrator ti, const char **file);
PETSC_EXTERN PetscErrorCode SlumpIntegratorLoadCheckpoint(SlumpIntegrator ti, const char file[], Vec X);
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetRestart(SlumpIntegrator ti, PetscBool *restarted, PetscReal *t);
PETSC_EXTERN PetscErrorCode SlumpIntegratorRequestStop(SlumpIntegrator ti);
/* Exact method: the flow stopped in (t_lo, t_hi] (both -1 if it did not). */
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetStopInterval(SlumpIntegrator ti, PetscReal *t_lo, PetscReal *t_hi);
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetStopRequested(SlumpIntegrator ti, PetscBool *stop);
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetStepMonitor(SlumpIntegrator ti, SlumpStepMonitorFn fn, void *ctx);
PETSC_EXTERN PetscErrorCode SlumpIntegratorSetOutputMonitor(SlumpIntegrator ti, SlumpOutputMonitorFn fn, void *ctx);
/* Integrate from t0 (X: initial velocity; on return the state at the end). */
PETSC_EXTERN PetscErrorCode SlumpIntegratorSolve(SlumpIntegrator ti, Vec X);
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetStats(SlumpIntegrator ti, SlumpStats *stats);
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetTime(SlumpIntegrator ti, PetscReal *t);
PETSC_EXTERN PetscErrorCode SlumpIntegratorGetLastStep(SlumpIntegrator ti, PetscReal *h, PetscInt *order);

/* Steady state F(y, 0) = 0 by KINSOL (line search), with continuation in the
   regularisation parameter: -steady_continuation_start v -steady_continuation_factor f
   go from v to the model's value in geometric steps. X: initial guess and result.
   A failed Newton solve is retried from softer values (smaller steps after a
   failure; -steady_continuation_retry 0: not). NoRetry: never, for callers
   with a continuation of their own (a load ramp). */
PETSC_EXTERN PetscErrorCode SlumpSteadySolve(SlumpProblem prob, Vec X, SlumpStats *stats);
PETSC_EXTERN PetscErrorCode SlumpSteadySolveNoRetry(SlumpProblem prob, Vec X, SlumpStats *stats);
/* the -steady_* options read and checked, before anything is written */
PETSC_EXTERN PetscErrorCode SlumpSteadyCheckOptions(SlumpProblem prob);

/* Consistent initial conditions for the index-2 Navier-Stokes DAE: given a
   velocity in X, solve [rho M, B^T; B, 0] (u', p) = (-(A(u) - f), 0) and
   return X with the pressure set, Xdot = (u', 0). */
PETSC_EXTERN PetscErrorCode SlumpConsistentInitialConditions(SlumpProblem prob, PetscReal t, Vec X, Vec Xdot);

/* The exact (unregularised) Bingham cessation between two walls, in 1-D
 * (timeint/alg2.c): P1 in y, backward Euler, ALG2 augmented Lagrangian per
 * step. The reference of the Couette and Poiseuille cessation scenes. */
typedef struct {
  PetscReal L;                /* wall distance (walls at y = 0 and y = L, no slip) */
  PetscReal rho, eta, tau0;   /* density, plastic viscosity, yield stress (all > 0) */
  PetscInt  ncells;           /* P1 elements across */
  PetscReal dt, t_max;        /* backward Euler step, end time */
  PetscReal r;                /* augmentation (<= 0: max(eta, 0.3 L sqrt(rho eta / dt))) */
  PetscReal tol;              /* ALG2 tolerance on |du| and |g - gamma| L relative to max|u^n| (<= 0: 1e-9) */
  PetscInt  max_iter;         /* ALG2 iterations per step (<= 0: 100000) */
  PetscReal threshold;        /* t_arrest: mean shear rate below this (<= 0: not computed) */
  PetscReal (*u0)(PetscReal y, void *ctx);
  void     *ctx;
} SlumpBinghamStripSpec;

typedef struct {
  PetscReal t_stop;           /* stopping time (-1: still moving at t_max) */
  PetscReal t_arrest;         /* mean shear rate < threshold (-1: not reached) */
  PetscReal energy0, shear0, r;
  PetscInt  steps, iterations, max_iterations, unconverged_steps;
  PetscBool energy_monotone;  /* the kinetic energy never increased */
} SlumpBinghamStripResult;

PETSC_EXTERN PetscErrorCode SlumpBinghamStripCessation(const SlumpBinghamStripSpec *spec, SlumpBinghamStripResult *res);
/* t_stop and t_arrest extrapolated from the steps dt and dt/2 (-1: not reached). */
PETSC_EXTERN PetscErrorCode SlumpBinghamStripReference(const SlumpBinghamStripSpec *spec, PetscReal *t_stop, PetscReal *t_arrest);

/* The exact (unregularised) Bingham model on the 2-D mesh (timeint/exact.c):
 * ALG2 with the plastic stress and the strain rate's auxiliary variable at
 * the quadrature points, for steady states and backward Euler steps
 * (integrator type exact). Options -alg2_r, -alg2_tol, -alg2_max_it, and
 * the u-step's linear solver under the prefix alg2_ (default LU). */
typedef struct _n_SlumpExactSolver *SlumpExactSolver;
/* One sentence unless the problem is one the exact method solves (Bingham or
   Newtonian, one material, no convection, free surface or wall friction). */
PETSC_EXTERN PetscErrorCode SlumpExactCheckProblem(SlumpProblem prob);
PETSC_EXTERN PetscErrorCode SlumpExactSolverCreate(SlumpProblem prob, Vec X, SlumpExactSolver *s);
PETSC_EXTERN PetscErrorCode SlumpExactSolverDestroy(SlumpExactSolver *s);
PETSC_EXTERN PetscErrorCode SlumpExactSolverSolve(SlumpExactSolver s, PetscReal t, PetscReal alpha, Vec beta, PetscReal gref, Vec X, PetscBool *converged, PetscInt *its);
PETSC_EXTERN PetscErrorCode SlumpExactSolverVelocityNorm(SlumpExactSolver s, Vec X, PetscReal *nrm);
/* The area fraction where the material flows (gamma != 0). */
PETSC_EXTERN PetscErrorCode SlumpExactSolverGetYieldedFraction(SlumpExactSolver s, PetscReal *fraction);
PETSC_EXTERN PetscErrorCode SlumpExactSolverGetStats(SlumpExactSolver s, PetscInt *its, PetscInt *solves, PetscInt *factorisations, PetscInt *lin_its);
/* A steady state of the unregularised model (X: initial iterate and result). */
PETSC_EXTERN PetscErrorCode SlumpSteadySolveExact(SlumpProblem prob, Vec X, SlumpStats *stats, PetscReal *yielded_fraction);
