/* The integrator object: options, monitors, counters; dispatch to IDA or
 * fixed-step BDF2. */
#include "timeintimpl.h"

#include "slumprheology.h"

const char *const SlumpIntegratorTypes[] = {"ida", "bdf2", "exact", "SlumpIntegratorType", "SLUMP_INTEGRATOR_", NULL};
const char *const SlumpThresholdKinds[]  = {"absolute", "relative", "creep"};
static const char *const StopKinds[]     = {"none", "first", "all", "SlumpArrestStop", "SLUMP_ARREST_STOP_", NULL};

PetscErrorCode SlumpIntegratorCreate(SlumpProblem prob, SlumpIntegrator *ti)
{
  SlumpIntegrator s;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  s->prob        = prob;
  s->type        = SLUMP_INTEGRATOR_IDA;
  s->t_stop[0]   = -1.0;
  s->t_stop[1]   = -1.0;
  s->tfinal      = 1.0;
  s->dtout       = 0.1;
  s->rtol        = 1e-4;
  s->atol        = 1e-8;
  s->atol_auto   = PETSC_TRUE;
  s->max_steps   = 1000000;
  s->max_nonlin_iters = 4;
  s->nonlin_conv_coef = 0.33;
  s->restart_step     = 1.0;
  s->sv_reuse         = PETSC_FALSE;
  s->stress_scale = 1.0;
  s->stats.h_min = PETSC_MAX_REAL;
  *ti            = s;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorDestroy(SlumpIntegrator *ti)
{
  PetscFunctionBeginUser;
  if (!*ti) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&(*ti)->ck_history));
  PetscCall(PetscFree((*ti)->ck_dual));
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

/* the first step after a between-step restart (a reinitialisation), as a
   fraction of the last step: below 1 where the restart from the old time
   derivative fails IDA's error test at the old step (bingham_dam_break) */
PetscErrorCode SlumpIntegratorSetRestartStep(SlumpIntegrator ti, PetscReal fraction)
{
  PetscFunctionBeginUser;
  ti->restart_step = fraction;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetLineSearch(SlumpIntegrator ti, PetscBool on)
{
  PetscFunctionBeginUser;
  ti->linesearch = on;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetTolerances(SlumpIntegrator ti, PetscReal rtol, PetscReal atol)
{
  PetscFunctionBeginUser;
  ti->rtol      = rtol;
  ti->atol      = atol;
  ti->atol_auto = PETSC_FALSE;
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

PetscErrorCode SlumpIntegratorAddArrestCriterion(SlumpIntegrator ti, SlumpDiagnosticKind diag, SlumpThresholdKind kind, PetscReal value)
{
  SlumpArrestCriterion *c;
  PetscFunctionBeginUser;
  PetscCheck(ti->narrest < 16, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "At most 16 arrest criteria (-arrest)");
  PetscCheck(kind != SLUMP_THRESHOLD_CREEP || diag == SLUMP_DIAG_MEAN_SHEAR_RATE || diag == SLUMP_DIAG_MAX_SHEAR_RATE || diag == SLUMP_DIAG_L2_SHEAR_RATE, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-arrest: a creep threshold applies to shear rates (mean_shear_rate, max_shear_rate, l2_shear_rate), not to %s", SlumpDiagnosticNames[diag]);
  PetscCheck(value > 0, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-arrest: the threshold of %s must be positive; got %g", SlumpDiagnosticNames[diag], (double)value);
  c            = &ti->arrest[ti->narrest++];
  c->diag      = diag;
  c->kind      = kind;
  c->value     = value;
  c->threshold = value;
  c->t_arrest  = -1.0;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetArrestCriteria(SlumpIntegrator ti, PetscInt *n, const SlumpArrestCriterion **c)
{
  PetscFunctionBeginUser;
  *n = ti->narrest;
  *c = ti->arrest;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetCharacteristicStress(SlumpIntegrator ti, PetscReal stress)
{
  PetscFunctionBeginUser;
  ti->stress_scale = stress;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetArrestThreshold(SlumpIntegrator ti, PetscReal threshold, PetscBool stop)
{
  PetscFunctionBeginUser;
  ti->narrest = 0;
  if (threshold > 0) PetscCall(SlumpIntegratorAddArrestCriterion(ti, SLUMP_DIAG_MEAN_SHEAR_RATE, SLUMP_THRESHOLD_ABSOLUTE, threshold));
  ti->arrest_stop = stop ? SLUMP_ARREST_STOP_FIRST : SLUMP_ARREST_STOP_NONE;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetArrestTime(SlumpIntegrator ti, PetscReal *tarrest)
{
  PetscFunctionBeginUser;
  *tarrest = -1.0;
  for (PetscInt k = 0; k < ti->narrest; ++k)
    if (ti->arrest[k].t_arrest >= 0 && (*tarrest < 0 || ti->arrest[k].t_arrest < *tarrest)) *tarrest = ti->arrest[k].t_arrest;
  PetscFunctionReturn(0);
}

/* "name:value[:kind]" */
static PetscErrorCode ParseCriterion(SlumpIntegrator ti, MPI_Comm comm, char *spec)
{
  char     *name = spec, *val, *kind, *end;
  PetscInt  d, k = SLUMP_THRESHOLD_ABSOLUTE;
  PetscReal v;
  char      names[256] = "";
  PetscFunctionBeginUser;
  for (d = 0; d < SLUMP_DIAG_NUM; ++d) {
    if (d) PetscCall(PetscStrlcat(names, ", ", sizeof(names)));
    PetscCall(PetscStrlcat(names, SlumpDiagnosticNames[d], sizeof(names)));
  }
  val = strchr(spec, ':');
  PetscCheck(val, comm, PETSC_ERR_USER_INPUT, "-arrest takes name:value[:absolute|relative|creep],...; got '%s'", spec);
  *val++ = 0;
  kind   = strchr(val, ':');
  if (kind) *kind++ = 0;
  for (d = 0; d < SLUMP_DIAG_NUM; ++d) {
    PetscBool same;
    PetscCall(PetscStrcmp(name, SlumpDiagnosticNames[d], &same));
    if (same) break;
  }
  PetscCheck(d < SLUMP_DIAG_NUM, comm, PETSC_ERR_USER_INPUT, "-arrest: unknown diagnostic '%s'; accepted: %s", name, names);
  v = strtod(val, &end);
  PetscCheck(end != val && *end == 0, comm, PETSC_ERR_USER_INPUT, "-arrest: '%s' is not a number (criterion %s)", val, name);
  if (kind) {
    for (k = 0; k < 3; ++k) {
      PetscBool same;
      PetscCall(PetscStrcmp(kind, SlumpThresholdKinds[k], &same));
      if (same) break;
    }
    PetscCheck(k < 3, comm, PETSC_ERR_USER_INPUT, "-arrest: unknown threshold kind '%s' (criterion %s); accepted: absolute, relative, creep", kind, name);
  }
  PetscCall(SlumpIntegratorAddArrestCriterion(ti, (SlumpDiagnosticKind)d, (SlumpThresholdKind)k, v));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorResolveArrest(SlumpIntegrator ti, PetscReal t0, Vec X0)
{
  SlumpRheology rheo;
  PetscReal     etaplug;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetRheology(ti->prob, &rheo));
  PetscCall(SlumpRheologyGetPlugViscosity(rheo, 0.0, &etaplug));
  for (PetscInt k = 0; k < ti->narrest; ++k) {
    SlumpArrestCriterion *c = &ti->arrest[k];
    c->t_arrest             = -1.0;
    if (c->kind == SLUMP_THRESHOLD_ABSOLUTE) c->threshold = c->value;
    else if (c->kind == SLUMP_THRESHOLD_CREEP) c->threshold = c->value * ti->stress_scale / etaplug;
    else {
      PetscReal v0;
      PetscCall(SlumpProblemComputeDiagnosticList(ti->prob, t0, X0, 1, &c->diag, &v0));
      c->threshold = c->value * v0;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorArrestFunctions(SlumpIntegrator ti, PetscReal t, Vec X, PetscReal g[])
{
  SlumpDiagnosticKind kinds[16];
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < ti->narrest; ++k) kinds[k] = ti->arrest[k].diag;
  PetscCall(SlumpProblemComputeDiagnosticList(ti->prob, t, X, ti->narrest, kinds, g));
  for (PetscInt k = 0; k < ti->narrest; ++k) g[k] -= ti->arrest[k].threshold;
  PetscFunctionReturn(0);
}

PetscBool SlumpIntegratorArrestRecord(SlumpIntegrator ti, PetscInt k, PetscReal t)
{
  PetscBool all = PETSC_TRUE;
  if (ti->arrest[k].t_arrest < 0) ti->arrest[k].t_arrest = t;
  for (PetscInt j = 0; j < ti->narrest; ++j)
    if (ti->arrest[j].t_arrest < 0) all = PETSC_FALSE;
  if (ti->arrest_stop == SLUMP_ARREST_STOP_FIRST) return PETSC_TRUE;
  if (ti->arrest_stop == SLUMP_ARREST_STOP_ALL) return all;
  return PETSC_FALSE;
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
  PetscCall(PetscOptionsEnum("-time_integrator", "ida (adaptive BDF, order <= 2), bdf2 (fixed step) or exact (unregularised Bingham: backward Euler + ALG2; -method exact)", "SlumpIntegratorSetType", SlumpIntegratorTypes, type, &type, NULL));
  PetscCall(PetscOptionsReal("-time_final", "Final time", "", ti->tfinal, &ti->tfinal, NULL));
  PetscCall(PetscOptionsReal("-time_output_dt", "Interval between outputs", "", ti->dtout, &ti->dtout, NULL));
  PetscCall(PetscOptionsReal("-time_rtol", "Relative tolerance (ida)", "", ti->rtol, &ti->rtol, NULL));
  {
    PetscBool set;
    PetscCall(PetscOptionsReal("-time_atol", "Absolute tolerance of the velocity (ida; default 1e-3 rtol max|u(0)|, or 1e-8 from rest)", "", ti->atol, &ti->atol, &set));
    if (set) ti->atol_auto = PETSC_FALSE;
  }
  PetscCall(PetscOptionsReal("-time_dt", "Time step (bdf2); first step (ida, 0: IDA's choice)", "", ti->dt, &ti->dt, NULL));
  {
    const char *kinds[] = {"newton", "linesearch"};
    PetscInt    k       = ti->linesearch ? 1 : 0;
    PetscCall(PetscOptionsEList("-ida_nonlinear_solver", "IDA's per-step nonlinear solver: newton (IDA's modified Newton) or linesearch (KINSOL, exact Jacobian, line search)", "", kinds, 2, kinds[k], &k, NULL));
    ti->linesearch = k == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(PetscOptionsBool("-ida_sv_reuse_jacobian", "IDA, stress-velocity Newton: keep the factored Jacobian while cj stays within 25 % and the yielded set does not change (default false: a Jacobian at every iterate, measured cheaper)", "", ti->sv_reuse, &ti->sv_reuse, NULL));
  PetscCall(PetscOptionsBool("-ida_exact_newton", "IDA: re-assemble the Jacobian at every Newton iterate (default: IDA's modified Newton)", "", ti->exact_newton, &ti->exact_newton, NULL));
  PetscCall(PetscOptionsReal("-ida_nonlin_conv_coef", "IDA: Newton stops when the correction is below this fraction of the error tolerance", "", ti->nonlin_conv_coef, &ti->nonlin_conv_coef, NULL));
  PetscCall(PetscOptionsInt("-ida_max_nonlin_iters", "IDA: Newton iterations per step before the step is cut", "", ti->max_nonlin_iters, &ti->max_nonlin_iters, NULL));
  PetscCall(PetscOptionsReal("-ida_restart_step", "IDA: first step after a between-step restart (reinitialisation), as a fraction of the last step", "", ti->restart_step, &ti->restart_step, NULL));
  PetscCall(PetscOptionsInt("-time_max_steps", "Maximum number of steps", "", ti->max_steps, &ti->max_steps, NULL));
  PetscCall(PetscOptionsInt("-checkpoint_every", "Write the integrator's state to <output_dir>/checkpoint.h5 every N steps (0: off; an interrupted run also leaves one)", "", ti->ck_every, &ti->ck_every, NULL));
  PetscCall(PetscOptionsReal("-checkpoint_interval", "Write the integrator's state to <output_dir>/checkpoint.h5 every T of simulated time (0: off)", "", ti->ck_interval, &ti->ck_interval, NULL));
  PetscCall(PetscOptionsString("-restart", "Resume from a checkpoint.h5 (same scene, mesh, integrator and ranks)", "", ti->restart_file, ti->restart_file, sizeof(ti->restart_file), NULL));
  {
    PetscReal thr  = ti->narrest ? ti->arrest[0].value : 0.0;
    char      spec[1024] = "";
    PetscBool set_thr, set_spec;
    PetscEnum stop = (PetscEnum)ti->arrest_stop;
    PetscCall(PetscOptionsReal("-arrest_mean_shear_rate", "Arrest when the mean shear rate falls below this (root-found; <= 0: off)", "", thr, &thr, &set_thr));
    PetscCall(PetscOptionsString("-arrest", "Arrest criteria name:value[:absolute|relative|creep],... (names: mean_shear_rate, max_shear_rate, l2_shear_rate, kinetic_energy, yielded_fraction)", "", spec, spec, sizeof(spec), &set_spec));
    PetscCall(PetscOptionsEnum("-arrest_stop", "Stop at the first arrest, when all criteria have arrested, or never", "", StopKinds, stop, &stop, NULL));
    ti->arrest_stop = (SlumpArrestStop)stop;
    if (set_thr) {
      ti->narrest = 0;
      if (thr > 0) PetscCall(SlumpIntegratorAddArrestCriterion(ti, SLUMP_DIAG_MEAN_SHEAR_RATE, SLUMP_THRESHOLD_ABSOLUTE, thr));
    }
    if (set_spec) {
      char *tok, *save = NULL;
      ti->narrest = 0;
      for (tok = strtok_r(spec, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) PetscCall(ParseCriterion(ti, comm, tok));
    }
  }
  PetscOptionsEnd();
  ti->type = (SlumpIntegratorType)type;
  PetscCheck(ti->tfinal > ti->t0, comm, PETSC_ERR_USER_INPUT, "-time_final must be greater than the initial time %g; got %g", (double)ti->t0, (double)ti->tfinal);
  PetscCheck(ti->dtout > 0, comm, PETSC_ERR_USER_INPUT, "-time_output_dt must be positive; got %g", (double)ti->dtout);
  PetscCheck(ti->rtol > 0 && ti->rtol < 1, comm, PETSC_ERR_USER_INPUT, "-time_rtol must lie in (0, 1); got %g", (double)ti->rtol);
  PetscCheck(ti->atol > 0, comm, PETSC_ERR_USER_INPUT, "-time_atol must be positive; got %g", (double)ti->atol);
  PetscCheck(ti->dt >= 0, comm, PETSC_ERR_USER_INPUT, "-time_dt must be non-negative; got %g", (double)ti->dt);
  PetscCheck(ti->type != SLUMP_INTEGRATOR_BDF2 || ti->dt > 0, comm, PETSC_ERR_USER_INPUT, "-time_integrator bdf2 needs a positive -time_dt");
  PetscCheck(ti->type != SLUMP_INTEGRATOR_EXACT || ti->dt > 0, comm, PETSC_ERR_USER_INPUT, "-method exact needs a positive -time_dt (its backward Euler step)");
  PetscCheck(ti->type != SLUMP_INTEGRATOR_EXACT || (ti->ck_every == 0 && ti->ck_interval == 0 && !ti->restart_file[0]), comm, PETSC_ERR_USER_INPUT, "-method exact does not write or read checkpoints (-checkpoint_every, -checkpoint_interval, -restart): its stress multipliers are not saved");
  PetscCheck(ti->nonlin_conv_coef > 0 && ti->nonlin_conv_coef <= 1, comm, PETSC_ERR_USER_INPUT, "-ida_nonlin_conv_coef must lie in (0, 1]; got %g", (double)ti->nonlin_conv_coef);
  PetscCheck(ti->max_nonlin_iters > 0, comm, PETSC_ERR_USER_INPUT, "-ida_max_nonlin_iters must be a positive integer");
  PetscCheck(ti->restart_step > 0 && ti->restart_step <= 1, comm, PETSC_ERR_USER_INPUT, "-ida_restart_step must lie in (0, 1]; got %g", (double)ti->restart_step);
  PetscCheck(ti->max_steps > 0, comm, PETSC_ERR_USER_INPUT, "-time_max_steps must be a positive integer");
  PetscCheck(ti->ck_every >= 0, comm, PETSC_ERR_USER_INPUT, "-checkpoint_every must be a non-negative number of steps (0: off); got %d", (int)ti->ck_every);
  PetscCheck(ti->ck_interval >= 0, comm, PETSC_ERR_USER_INPUT, "-checkpoint_interval must be a non-negative time (0: off); got %g", (double)ti->ck_interval);
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetStopInterval(SlumpIntegrator ti, PetscReal *t_lo, PetscReal *t_hi)
{
  PetscFunctionBeginUser;
  *t_lo = ti->t_stop[0];
  *t_hi = ti->t_stop[1];
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorRequestStop(SlumpIntegrator ti)
{
  PetscFunctionBeginUser;
  ti->stop_requested = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetStopRequested(SlumpIntegrator ti, PetscBool *stop)
{
  PetscFunctionBeginUser;
  *stop = ti->stop_requested;
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
  PetscCheck(effects & (SLUMP_EFFECT_INERTIA | SLUMP_EFFECT_FREE_SURFACE), PetscObjectComm((PetscObject)X), PETSC_ERR_USER_INPUT, "Time integration needs the inertia or free-surface effect (a differential unknown); a scene without either is solved as a steady state");
  if (!ti->restarted) ti->t = ti->t0;
  ti->stop_requested = PETSC_FALSE;
  ti->t_stop[0] = ti->t_stop[1] = -1.0;
  if (ti->type == SLUMP_INTEGRATOR_IDA) PetscCall(SlumpIntegratorSolve_IDA(ti, X));
  else if (ti->type == SLUMP_INTEGRATOR_EXACT) PetscCall(SlumpIntegratorSolve_Exact(ti, X));
  else PetscCall(SlumpIntegratorSolve_BDF2(ti, X));
  PetscCall(SlumpProblemGetCounters(ti->prob, &ti->stats.res_evals, &ti->stats.jac_evals));
  ti->stats.res_evals += ti->res_offset;
  ti->stats.jac_evals += ti->jac_offset;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetStats(SlumpIntegrator ti, SlumpStats *stats)
{
  PetscFunctionBeginUser;
  /* current also while a solve is under way or after it failed */
  PetscCall(SlumpProblemGetCounters(ti->prob, &ti->stats.res_evals, &ti->stats.jac_evals));
  ti->stats.res_evals += ti->res_offset;
  ti->stats.jac_evals += ti->jac_offset;
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
