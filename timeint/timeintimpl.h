/* Private: the SUNDIALS bridge. */
#pragma once

#include "slumptimeint.h"
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <nvector/nvector_petsc.h>
#include <sundials/sundials_nonlinearsolver.h>

/* A SUNMatrix that only carries a PETSc Mat (assembled by the problem). */
PETSC_INTERN SUNMatrix       SlumpSUNMatCreate(Mat J, SUNContext ctx);
/* A direct SUNLinearSolver that solves with a PETSc KSP on that Mat. */
PETSC_INTERN SUNLinearSolver SlumpSUNLinSolCreate(SlumpProblem prob, Mat J, SUNContext ctx);
PETSC_INTERN PetscErrorCode  SlumpSUNLinSolGetCounts(SUNLinearSolver LS, PetscInt *nsolves, PetscInt *nits);
PETSC_INTERN PetscErrorCode  SlumpSUNLinSolGetKSP(SUNLinearSolver LS, KSP *ksp);
/* Exact Newton inside IDA: before each solve, re-assemble J at IDA's current
   iterate (IDAGetNonlinearSystemData) with the current cj. */
typedef PetscErrorCode (*SlumpLSAssembleFn)(void *ctx, PetscReal t, Vec y, Vec yp, PetscReal cj);
/* inexact Newton: Eisenstat-Walker relative tolerances (KINSOL) */
PETSC_INTERN PetscErrorCode  SlumpSUNLinSolSetForcing(SUNLinearSolver LS, PetscBool on);
PETSC_INTERN PetscErrorCode  SlumpSUNLinSolSetExactNewton(SUNLinearSolver LS, void *ida_mem, SlumpLSAssembleFn fn, void *ctx);
/* Convert a PETSc error code at a SUNDIALS callback boundary: 0 ok, <0 fatal. */
PETSC_INTERN int             SlumpSundialsStatus(PetscErrorCode ierr);
/* SUNDIALS error handler that prints nothing: failures are reported by slump. */
PETSC_INTERN void SlumpSilentErrHandler(int code, const char *module, const char *function, char *msg, void *user);
/* Recoverable failure (>0) if a vector holds NaN or Inf. */
PETSC_INTERN int             SlumpCheckFinite(Vec v);

/* KINSOL on G(y) = F(t, y, alpha y + beta) (beta may be NULL; alpha 0: steady). */
typedef struct _n_SlumpImplicitSolver *SlumpImplicitSolver;
PETSC_INTERN PetscErrorCode SlumpImplicitSolverCreate(SlumpProblem prob, Vec X, SlumpImplicitSolver *s);
PETSC_INTERN PetscErrorCode SlumpImplicitSolverDestroy(SlumpImplicitSolver *s);
/* Returns converged = PETSC_FALSE (no error) when KINSOL fails. */
PETSC_INTERN PetscErrorCode SlumpImplicitSolverSolve(SlumpImplicitSolver s, PetscReal t, PetscReal alpha, Vec beta, Vec X, PetscBool *converged, PetscInt *newton_its, PetscInt *lin_its);
PETSC_INTERN PetscErrorCode SlumpImplicitSolverGetHistory(SlumpImplicitSolver s, PetscInt *n, const PetscReal **hist);
/* Krylov solves of the last SlumpImplicitSolverSolve that did not converge */
PETSC_INTERN PetscErrorCode SlumpImplicitSolverGetLinearFailures(SlumpImplicitSolver s, SlumpLinearFailures *f);
PETSC_INTERN PetscErrorCode SlumpImplicitSolverGetStats(SlumpImplicitSolver s, SlumpStats *stats);
PETSC_INTERN PetscErrorCode SlumpImplicitSolverSetTolerance(SlumpImplicitSolver s, PetscReal fnormtol);
/* KINSOL's line search unless -newton_linesearch was given (default on). */
PETSC_INTERN PetscErrorCode SlumpImplicitSolverSetDefaultLineSearch(SlumpImplicitSolver s, PetscBool on);
/* For the next solve only: the relative tolerance -newton_rtol applies to
   max(max|F(X0)|, fref) instead of max|F(X0)| (X0 the initial iterate) */
PETSC_INTERN PetscErrorCode SlumpImplicitSolverSetResidualScale(SlumpImplicitSolver s, PetscReal fref);

struct _n_SlumpIntegrator {
  SlumpProblem         prob;
  SlumpIntegratorType  type;
  PetscReal            t0, tfinal, dtout, rtol, atol, dt, t, h_last;
  PetscInt             order_last, max_steps, max_nonlin_iters;
  PetscBool            exact_newton, linesearch, sv_reuse;
  PetscBool            atol_auto; /* -time_atol not given: 1e-3 rtol max|u0| (ida.c) */
  PetscReal            nonlin_conv_coef;
  PetscReal            restart_step; /* first step after a between-step restart, as a fraction of the last step */
  PetscInt             narrest;
  SlumpArrestCriterion arrest[16];
  SlumpArrestStop      arrest_stop;
  PetscReal            stress_scale;
  SlumpStats           stats;
  PetscReal            t_stop[2];      /* exact method: the flow stopped in (t_stop[0], t_stop[1]] (-1: not) */
  PetscBool            stop_requested; /* SlumpIntegratorRequestStop: end after the current step */
  /* checkpoint/restart (checkpoint.c) */
  char                 ckdir[PETSC_MAX_PATH_LEN], restart_file[PETSC_MAX_PATH_LEN];
  PetscInt             ck_every, ck_last_step, ck_count;
  PetscReal            ck_interval, ck_last_t;
  SlumpCheckpointGetFn ckget;
  SlumpCheckpointSetFn ckset;
  void                *ckctx;
  PetscBool            restarted, ck_have_prev; /* loaded from a checkpoint; BDF2: two states */
  PetscInt             ck_kout, ck_ndual;
  PetscReal            ck_gprev[16];
  Vec                  ck_history; /* BDF2: the state one step back; IDA: y' */
  PetscScalar         *ck_dual;
  PetscInt             res_offset, jac_offset; /* evaluations before the restart */
  SlumpStepMonitorFn   stepmon;
  void                *stepctx;
  SlumpOutputMonitorFn outmon;
  void                *outctx;
};

/* Resolve relative/creep thresholds from the initial state. */
PETSC_INTERN PetscErrorCode SlumpIntegratorResolveArrest(SlumpIntegrator, PetscReal t0, Vec X0);
/* g[k] = diagnostic_k(t, X) - threshold_k */
PETSC_INTERN PetscErrorCode SlumpIntegratorArrestFunctions(SlumpIntegrator, PetscReal t, Vec X, PetscReal g[]);
/* Record criterion k's arrest at t; returns whether the run should stop. */
PETSC_INTERN PetscBool      SlumpIntegratorArrestRecord(SlumpIntegrator, PetscInt k, PetscReal t);
/* The ops of a stage solver that owns its residual, linear solves,
   convergence test and iteration limit: IDA's are ignored. */
PETSC_INTERN void SlumpSUNNonlinSolSetStageOps(SUNNonlinearSolver);
/* IDA's nonlinear solver replaced by KINSOL with a line search per stage. */
PETSC_INTERN PetscErrorCode SlumpSUNNonlinSolLineSearchCreate(SlumpProblem, Vec X, SUNContext, SUNNonlinearSolver *);
PETSC_INTERN PetscErrorCode SlumpSUNNonlinSolLineSearchGetLinearIterations(SUNNonlinearSolver, PetscInt *);
/* IDA's nonlinear solver replaced by the stress-velocity Newton (exact
   Jacobian with the plastic stress at every iterate; maxit iterations). */
PETSC_INTERN PetscErrorCode SlumpSUNNonlinSolStressVelocityCreate(SlumpProblem, Vec X, PetscInt maxit, PetscBool reuse_jacobian, SUNContext, SUNNonlinearSolver *);
PETSC_INTERN PetscErrorCode SlumpSUNNonlinSolStressVelocityGetCounts(SUNNonlinearSolver, PetscInt *njac, PetscInt *nretry);
PETSC_INTERN PetscErrorCode SlumpSUNNonlinSolStressVelocityGetLinearIterations(SUNNonlinearSolver, PetscInt *);
/* The problem set up for the linearisation -newton_linearisation asked for
   (SlumpProblemGetStressVelocityOption): *sv. */
PETSC_INTERN PetscErrorCode SlumpLinearisationSetUp(SlumpProblem, MPI_Comm, PetscBool *sv);
PETSC_INTERN PetscErrorCode SlumpIntegratorSolve_IDA(SlumpIntegrator, Vec);
PETSC_INTERN PetscErrorCode SlumpIntegratorSolve_BDF2(SlumpIntegrator, Vec);
PETSC_INTERN PetscErrorCode SlumpIntegratorSolve_Exact(SlumpIntegrator, Vec);
/* bdf2.c: an arrest root and the output times on a step's interpolant
   (quadratic through Yprev, Yn, X; linear without Yprev) */
PETSC_INTERN PetscErrorCode SlumpIntegratorLocateArrest(SlumpIntegrator, PetscInt k, PetscReal tn, PetscReal ga, PetscReal tn1, PetscReal gb, PetscReal dt, Vec Yprev, Vec Yn, Vec X, Vec Y, PetscReal *troot);
PETSC_INTERN PetscErrorCode SlumpIntegratorOutputsUpTo(SlumpIntegrator, PetscReal tn, PetscReal tn1, PetscReal dt, PetscReal *next_out, PetscInt *kout, Vec Yprev, Vec Yn, Vec X, Vec Y);

/* checkpoint.c: after a step (and its outputs and between-step actions),
   write a checkpoint if one is due; H: BDF2's previous state or IDA's y'. */
PETSC_INTERN PetscErrorCode SlumpIntegratorCheckpointMaybe(SlumpIntegrator ti, Vec X, Vec H, PetscBool have_prev, PetscInt kout, const PetscReal gprev[]);
PETSC_INTERN PetscErrorCode SlumpIntegratorCheckpointWrite(SlumpIntegrator ti, Vec X, Vec H, PetscBool have_prev, PetscInt kout, const PetscReal gprev[]);
/* After the solve's SlumpLinearisationSetUp: the restarted plastic stress. */
PETSC_INTERN PetscErrorCode SlumpIntegratorRestoreDual(SlumpIntegrator ti);
