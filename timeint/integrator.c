/* The integrator object: options, monitors, counters; dispatch to IDA or
 * fixed-step BDF2. */
#include "timeintimpl.h"

const char *const SlumpIntegratorTypes[] = {"ida", "bdf2", "SlumpIntegratorType", "SLUMP_INTEGRATOR_", NULL};

PetscErrorCode SlumpIntegratorCreate(SlumpProblem prob, SlumpIntegrator *ti)
{
  SlumpIntegrator s;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  s->prob        = prob;
  s->type        = SLUMP_INTEGRATOR_IDA;
  s->tfinal      = 1.0;
  s->dtout       = 0.1;
  s->rtol        = 1e-4;
  s->atol        = 1e-8;
  s->max_steps   = 1000000;
  s->max_nonlin_iters = 4;
  s->nonlin_conv_coef = 0.33;
  s->t_arrest    = -1.0;
  s->stats.h_min = PETSC_MAX_REAL;
  *ti            = s;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorDestroy(SlumpIntegrator *ti)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(*ti));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetType(SlumpIntegrator ti, SlumpIntegratorType type)
{
  PetscFunctionBeginUser;
  ti->type = type;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetType(SlumpIntegrator ti, SlumpIntegratorType *type)
{
  PetscFunctionBeginUser;
  *type = ti->type;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetTimes(SlumpIntegrator ti, PetscReal t0, PetscReal tfinal, PetscReal dtout)
{
  PetscFunctionBeginUser;
  ti->t0     = t0;
  ti->tfinal = tfinal;
  ti->dtout  = dtout;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetTimes(SlumpIntegrator ti, PetscReal *t0, PetscReal *tfinal, PetscReal *dtout)
{
  PetscFunctionBeginUser;
  if (t0) *t0 = ti->t0;
  if (tfinal) *tfinal = ti->tfinal;
  if (dtout) *dtout = ti->dtout;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetTolerances(SlumpIntegrator ti, PetscReal rtol, PetscReal atol)
{
  PetscFunctionBeginUser;
  ti->rtol = rtol;
  ti->atol = atol;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetTolerances(SlumpIntegrator ti, PetscReal *rtol, PetscReal *atol)
{
  PetscFunctionBeginUser;
  if (rtol) *rtol = ti->rtol;
  if (atol) *atol = ti->atol;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetTimeStep(SlumpIntegrator ti, PetscReal dt)
{
  PetscFunctionBeginUser;
  ti->dt = dt;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetArrestThreshold(SlumpIntegrator ti, PetscReal threshold, PetscBool stop)
{
  PetscFunctionBeginUser;
  ti->arrest_threshold = threshold;
  ti->arrest_stop      = stop;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetArrestTime(SlumpIntegrator ti, PetscReal *tarrest)
{
  PetscFunctionBeginUser;
  *tarrest = ti->t_arrest;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetFromOptions(SlumpIntegrator ti)
{
  PetscEnum type = (PetscEnum)ti->type;
  MPI_Comm  comm;
  PetscFunctionBeginUser;
  comm = PETSC_COMM_WORLD;
  {
    DM dm;
    PetscCall(SlumpProblemGetDM(ti->prob, &dm));
    PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  }
  PetscOptionsBegin(comm, NULL, "Time integration", "SlumpIntegrator");
  PetscCall(PetscOptionsEnum("-time_integrator", "ida (adaptive BDF, order <= 2) or bdf2 (fixed step)", "SlumpIntegratorSetType", SlumpIntegratorTypes, type, &type, NULL));
  PetscCall(PetscOptionsReal("-time_final", "Final time", "", ti->tfinal, &ti->tfinal, NULL));
  PetscCall(PetscOptionsReal("-time_output_dt", "Interval between outputs", "", ti->dtout, &ti->dtout, NULL));
  PetscCall(PetscOptionsReal("-time_rtol", "Relative tolerance (ida)", "", ti->rtol, &ti->rtol, NULL));
  PetscCall(PetscOptionsReal("-time_atol", "Absolute tolerance (ida)", "", ti->atol, &ti->atol, NULL));
  PetscCall(PetscOptionsReal("-time_dt", "Time step (bdf2); first step (ida, 0: IDA's choice)", "", ti->dt, &ti->dt, NULL));
  PetscCall(PetscOptionsBool("-ida_exact_newton", "IDA: re-assemble the Jacobian at every Newton iterate (default: IDA's modified Newton)", "", ti->exact_newton, &ti->exact_newton, NULL));
  PetscCall(PetscOptionsReal("-ida_nonlin_conv_coef", "IDA: Newton stops when the correction is below this fraction of the error tolerance", "", ti->nonlin_conv_coef, &ti->nonlin_conv_coef, NULL));
  PetscCall(PetscOptionsInt("-ida_max_nonlin_iters", "IDA: Newton iterations per step before the step is cut", "", ti->max_nonlin_iters, &ti->max_nonlin_iters, NULL));
  PetscCall(PetscOptionsInt("-time_max_steps", "Maximum number of steps", "", ti->max_steps, &ti->max_steps, NULL));
  PetscCall(PetscOptionsReal("-arrest_mean_shear_rate", "Arrest when the mean shear rate falls below this (root-found; <= 0: off)", "", ti->arrest_threshold, &ti->arrest_threshold, NULL));
  PetscCall(PetscOptionsBool("-arrest_stop", "Stop the run at the arrest time", "", ti->arrest_stop, &ti->arrest_stop, NULL));
  PetscOptionsEnd();
  ti->type = (SlumpIntegratorType)type;
  PetscCheck(ti->tfinal > ti->t0, comm, PETSC_ERR_USER_INPUT, "-time_final must be greater than the initial time %g; got %g", (double)ti->t0, (double)ti->tfinal);
  PetscCheck(ti->dtout > 0, comm, PETSC_ERR_USER_INPUT, "-time_output_dt must be positive; got %g", (double)ti->dtout);
  PetscCheck(ti->rtol > 0 && ti->rtol < 1, comm, PETSC_ERR_USER_INPUT, "-time_rtol must lie in (0, 1); got %g", (double)ti->rtol);
  PetscCheck(ti->atol > 0, comm, PETSC_ERR_USER_INPUT, "-time_atol must be positive; got %g", (double)ti->atol);
  PetscCheck(ti->dt >= 0, comm, PETSC_ERR_USER_INPUT, "-time_dt must be non-negative; got %g", (double)ti->dt);
  PetscCheck(ti->type != SLUMP_INTEGRATOR_BDF2 || ti->dt > 0, comm, PETSC_ERR_USER_INPUT, "-time_integrator bdf2 needs a positive -time_dt");
  PetscCheck(ti->nonlin_conv_coef > 0 && ti->nonlin_conv_coef <= 1, comm, PETSC_ERR_USER_INPUT, "-ida_nonlin_conv_coef must lie in (0, 1]; got %g", (double)ti->nonlin_conv_coef);
  PetscCheck(ti->max_nonlin_iters > 0, comm, PETSC_ERR_USER_INPUT, "-ida_max_nonlin_iters must be a positive integer");
  PetscCheck(ti->max_steps > 0, comm, PETSC_ERR_USER_INPUT, "-time_max_steps must be a positive integer");
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetStepMonitor(SlumpIntegrator ti, SlumpStepMonitorFn fn, void *ctx)
{
  PetscFunctionBeginUser;
  ti->stepmon = fn;
  ti->stepctx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetOutputMonitor(SlumpIntegrator ti, SlumpOutputMonitorFn fn, void *ctx)
{
  PetscFunctionBeginUser;
  ti->outmon = fn;
  ti->outctx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSolve(SlumpIntegrator ti, Vec X)
{
  PetscInt effects;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetEffects(ti->prob, &effects));
  PetscCheck(effects & SLUMP_EFFECT_INERTIA, PetscObjectComm((PetscObject)X), PETSC_ERR_USER_INPUT, "Time integration needs the inertia effect; a scene without inertia is solved as a steady state");
  ti->t = ti->t0;
  if (ti->type == SLUMP_INTEGRATOR_IDA) PetscCall(SlumpIntegratorSolve_IDA(ti, X));
  else PetscCall(SlumpIntegratorSolve_BDF2(ti, X));
  PetscCall(SlumpProblemGetCounters(ti->prob, &ti->stats.res_evals, &ti->stats.jac_evals));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetStats(SlumpIntegrator ti, SlumpStats *stats)
{
  PetscFunctionBeginUser;
  *stats = ti->stats;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetTime(SlumpIntegrator ti, PetscReal *t)
{
  PetscFunctionBeginUser;
  *t = ti->t;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetLastStep(SlumpIntegrator ti, PetscReal *h, PetscInt *order)
{
  PetscFunctionBeginUser;
  if (h) *h = ti->h_last;
  if (order) *order = ti->order_last;
  PetscFunctionReturn(0);
}
