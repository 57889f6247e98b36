/* The slump driver: one scene, from options to outputs.
 *
 * Order matters for bad input: everything the user gave is read and checked
 * (scene, mesh, rheology, solver options) before the output directory is
 * created, so a mistake leaves nothing half-written behind. */
#include "slumpscene.h"
#include "slumpinterface.h"
#include <time.h>
#include <signal.h>
#include <unistd.h>

/* The first message of the last error, for the sweep's rows. */
static char last_error[512];

const char *SlumpLastErrorMessage(void)
{
  return last_error;
}

void SlumpClearLastError(void)
{
  last_error[0] = 0;
}

PetscErrorCode SlumpErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  PetscMPIInt rank = 0;
  if (p == PETSC_ERROR_INITIAL && !last_error[0]) {
    snprintf(last_error, sizeof(last_error), "%s", mess && mess[0] ? mess : "PETSc error (no message)");
    for (char *c = last_error; *c; ++c)
      if (*c == '\n' || *c == '\r') *c = ' ';
  }
  /* PETSC_ERR_USER: PETSc's own "Unknown option x for -name. Available options: ..." */
  if (n == PETSC_ERR_USER_INPUT || n == PETSC_ERR_USER || n == PETSC_ERR_FILE_OPEN || n == PETSC_ERR_NOT_CONVERGED || n == PETSC_ERR_ARG_WRONG || n == PETSC_ERR_ARG_OUTOFRANGE || n == PETSC_ERR_FILE_WRITE || n == PETSC_ERR_FILE_UNEXPECTED || n == PETSC_ERR_SIG) {
    if (p == PETSC_ERROR_INITIAL) {
      MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
      if (!rank || comm == PETSC_COMM_SELF) {
        fprintf(stderr, "slump: error: %s\n", mess ? mess : "unknown error");
        fflush(stderr);
      }
    }
    return n;
  }
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, ctx);
}

typedef struct {
  SlumpProblem     prob;
  SlumpScene       scene;
  SlumpFieldWriter writer;
  FILE            *series, *steps; /* rank 0 */
  char             series_path[PETSC_MAX_PATH_LEN], steps_path[PETSC_MAX_PATH_LEN];
  int              signal; /* the SIGINT/SIGTERM that interrupted the run, 0 if none */
  MPI_Comm         comm;
  PetscMPIInt      rank;
  PetscInt         nout, newton_since, lin_since;
  SlumpDiagnostics last;
  PetscBool        quiet;
  /* the energy dissipated since the start (material, ambient fluid and
     walls), by the trapezoidal rule over the steps: the last two steps'
     time, rate and running total */
  struct {
    PetscReal t, rate, total;
  } diss[2];
  PetscInt ndiss;
} RunCtx;

/* The energy dissipated up to t, from the last recorded step at or before
   t and the rate at t. */
static PetscReal Dissipated(const RunCtx *r, PetscReal t, PetscReal rate)
{
  const PetscInt b = r->ndiss > 1 && r->diss[1].t > t ? 0 : 1;
  if (r->ndiss == 0) return 0.0;
  return r->diss[b].total + 0.5 * (t - r->diss[b].t) * (rate + r->diss[b].rate);
}

static void RecordDissipation(RunCtx *r, PetscReal t, PetscReal rate)
{
  const PetscReal total = Dissipated(r, t, rate);
  r->diss[0]          = r->diss[1];
  r->diss[1].t        = t;
  r->diss[1].rate     = rate;
  r->diss[1].total    = total;
  r->ndiss++;
}

/* A CSV file with its header (rank 0 writes; collective check). */
static PetscErrorCode OpenCSV(RunCtx *r, const char dir[], const char name[], const char header[], FILE **fp, char path[])
{
  int err = 0;
  PetscFunctionBeginUser;
  *fp = NULL;
  PetscCall(PetscSNPrintf(path, PETSC_MAX_PATH_LEN, "%s/%s", dir, name));
  if (!r->rank) {
    err = SlumpFileOpen(path, fp);
    if (!err) err = SlumpFilePrintf(*fp, "%s\n", header);
  }
  PetscCall(SlumpFileCheck(r->comm, err, path));
  PetscFunctionReturn(0);
}

static PetscErrorCode StepMonitor(SlumpIntegrator ti, const SlumpStepRecord *s, void *ctx)
{
  RunCtx *r = (RunCtx *)ctx;
  int      flags[2] = {0, SlumpInterruptSignal()};
  PetscFunctionBeginUser;
  r->newton_since += s->newton_its;
  r->lin_since += s->lin_its;
  {
    PetscReal e, rate[3];
    /* collective: every rank computes, rank 0 writes */
    PetscCall(SlumpProblemComputeEnergyRates(r->prob, s->t, s->X, &e, rate));
    RecordDissipation(r, s->t, rate[0] + rate[1] + rate[2]);
    flags[0] = SlumpFilePrintf(r->steps, "%.12e,%.6e,%d,%d,%d,%d,%d,%.12e\n", (double)s->t, (double)s->h, (int)s->order, (int)s->newton_its, (int)s->lin_its, (int)s->err_test_fails, (int)s->conv_fails, (double)e);
  }
  /* one reduction per step: a failed write (rank 0) and a signal (any rank) */
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, flags, 2, MPI_INT, MPI_MAX, r->comm));
  if (flags[0]) PetscCall(SlumpFileCheck(r->comm, flags[0], r->steps_path));
  if (flags[1] && !r->signal) {
    r->signal = flags[1];
    PetscCall(SlumpIntegratorRequestStop(ti));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteDiagnostics(RunCtx *r, PetscReal t, Vec X, PetscReal h, PetscInt order)
{
  SlumpDiagnostics d;
  PetscReal        rate;
  int              err;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemComputeDiagnostics(r->prob, t, X, &d));
  r->last = d;
  rate    = d.dissipation + d.dissipation_ambient + d.dissipation_wall;
  if (r->ndiss == 0) RecordDissipation(r, t, rate); /* the initial state */
  err = SlumpFilePrintf(r->series, "%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e\n", (double)t, (double)d.kinetic_energy, (double)d.mean_shear_rate, (double)d.max_shear_rate, (double)d.l2_shear_rate, (double)d.dissipation, (double)d.yielded_fraction, (double)d.flow_rate, (double)d.potential_energy, (double)d.dissipation_ambient, (double)d.dissipation_wall,
            (double)Dissipated(r, t, rate));
  PetscCall(SlumpFileCheck(r->comm, err, r->series_path));
  if (r->writer) PetscCall(SlumpFieldWriterWrite(r->writer, t, X));
  if (!r->quiet) PetscCall(PetscPrintf(r->comm, "t %10.4e  h %9.3e  q %d  newton %4d  linear %4d  KE %11.5e  mean|gdot| %11.5e\n", (double)t, (double)h, (int)order, (int)r->newton_since, (int)r->lin_since, (double)d.kinetic_energy, (double)d.mean_shear_rate));
  r->newton_since = r->lin_since = 0;
  r->nout++;
  PetscFunctionReturn(0);
}

static PetscErrorCode OutputMonitor(SlumpIntegrator ti, PetscReal t, Vec X, void *ctx)
{
  RunCtx   *r = (RunCtx *)ctx;
  PetscReal h;
  PetscInt  q;
  PetscFunctionBeginUser;
  PetscCall(SlumpIntegratorGetLastStep(ti, &h, &q));
  PetscCall(WriteDiagnostics(r, t, X, h, q));
  PetscFunctionReturn(0);
}

/* Peak resident memory of this run, summed over its ranks. On Linux the
 * high-water mark (VmHWM) is reset at the start of each run by writing 5 to
 * /proc/self/clear_refs, so runs of a sweep in one process are measured
 * separately; elsewhere PETSc's process maximum is used. */
static PetscBool hwm_reset = PETSC_FALSE;

static void ResetPeakMemory(void)
{
  FILE *fp = fopen("/proc/self/clear_refs", "w");
  hwm_reset = PETSC_FALSE;
  if (fp) {
    hwm_reset = fputs("5", fp) >= 0 ? PETSC_TRUE : PETSC_FALSE;
    if (fclose(fp)) hwm_reset = PETSC_FALSE;
  }
}

static PetscReal ReadVmHWM(void)
{
  char  line[256];
  long  kb = -1;
  FILE *fp = fopen("/proc/self/status", "r");
  if (!fp) return -1.0;
  while (fgets(line, sizeof(line), fp))
    if (!strncmp(line, "VmHWM:", 6)) kb = strtol(line + 6, NULL, 10);
  fclose(fp);
  return kb < 0 ? -1.0 : (PetscReal)kb / 1024.0;
}

static PetscErrorCode PeakMemory(MPI_Comm comm, PetscReal *mb)
{
  PetscLogDouble mem;
  PetscFunctionBeginUser;
  *mb = hwm_reset ? ReadVmHWM() : -1.0;
  if (*mb < 0) {
    PetscCall(PetscMemoryGetMaximumUsage(&mem));
    if (mem <= 0) PetscCall(PetscMemoryGetCurrentUsage(&mem));
    *mb = (PetscReal)mem / 1048576.0;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, mb, 1, MPIU_REAL, MPIU_SUM, comm));
  PetscFunctionReturn(0);
}

/* summary.csv: one header line and one row, written to summary.csv.part and
   renamed when complete. status: ok, no_arrest, not_converged, failed or
   interrupted; reason: the error or the signal (quoted CSV). Numbers a failed
   run does not have (errors, scene results) are left empty. */
static PetscErrorCode WriteSummary(RunCtx *r, const char dir[], const SlumpRunResult *R, SlumpScene scene, PetscInt narrest, const SlumpArrestCriterion *arrest, char arrestname[][64], const PetscReal err[2], const PetscReal nrm[2], const char status[], const char reason[])
{
  char              path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN], q[1300];
  FILE             *fp = NULL;
  int               e  = 0;
  const SlumpStats *st = &R->stats;
  PetscBool         ok = !strcmp(status, "ok") || !strcmp(status, "no_arrest") ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/summary.csv", dir));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s/summary.csv.part", dir));
  if (!r->rank) {
    size_t k = 0;
    q[k++]   = '"';
    for (const char *c = reason; *c && k + 3 < sizeof(q); ++c) {
      if (*c == '"') q[k++] = '"';
      q[k++] = *c;
    }
    q[k++] = '"';
    q[k]   = 0;
    e      = SlumpFileOpen(tmp, &fp);
    if (!e) e = SlumpFilePrintf(fp, "scene,rheology,regularisation,regularisation_value,integrator,rtol,atol,dt,ranks,cells,unknowns");
    for (PetscInt i = 0; i < scene->nparam && !e; ++i) e = SlumpFilePrintf(fp, ",%s", scene->pname[i]);
    if (!e) e = SlumpFilePrintf(fp, ",t_final,t_arrest,steps,res_evals,jac_evals,newton_its,lin_its,lin_solves,err_test_fails,conv_fails,h_min,h_max,wall_time,peak_memory_mb,kinetic_energy,mean_shear_rate,max_shear_rate,yielded_fraction,flow_rate,err_u_l2,norm_u_l2,err_p_l2,norm_p_l2");
    for (PetscInt k = 0; k < narrest && !e; ++k) e = SlumpFilePrintf(fp, ",t_arrest_%s,threshold_%s", arrestname[k], arrestname[k]);
    for (PetscInt i = 0; i < scene->nresult && !e; ++i) e = SlumpFilePrintf(fp, ",%s", scene->rname[i]);
    if (!e) e = SlumpFilePrintf(fp, ",status,reason\n%s,%s,%s,%.6e,%s,%.3e,%.3e,%.6e,%d,%d,%d", R->scene, R->rheology, R->regularisation, (double)R->regularisation_value, R->integrator, (double)R->rtol, (double)R->atol, (double)R->dt, (int)R->ranks, (int)R->cells, (int)R->unknowns);
    for (PetscInt i = 0; i < scene->nparam && !e; ++i) e = SlumpFilePrintf(fp, ",%.10e", (double)scene->pvalue[i]);
    if (!e)
      e = SlumpFilePrintf(fp, ",%.10e,%.10e,%d,%d,%d,%d,%d,%d,%d,%d,%.6e,%.6e,%.4f,%.1f,%.10e,%.10e,%.10e,%.10e,%.10e", (double)R->t_final, (double)R->t_arrest, (int)st->steps, (int)st->res_evals, (int)st->jac_evals, (int)st->newton_its, (int)st->lin_its, (int)st->lin_solves, (int)st->err_test_fails, (int)st->conv_fails, (double)(st->steps ? st->h_min : 0.0), (double)st->h_max, (double)R->wall_time, (double)R->peak_mb, (double)r->last.kinetic_energy, (double)r->last.mean_shear_rate, (double)r->last.max_shear_rate, (double)r->last.yielded_fraction, (double)r->last.flow_rate);
    if (!e) e = ok ? SlumpFilePrintf(fp, ",%.10e,%.10e,%.10e,%.10e", (double)err[0], (double)nrm[0], (double)err[1], (double)nrm[1]) : SlumpFilePrintf(fp, ",,,,");
    for (PetscInt k = 0; k < narrest && !e; ++k) e = SlumpFilePrintf(fp, ",%.10e,%.10e", (double)arrest[k].t_arrest, (double)arrest[k].threshold);
    for (PetscInt i = 0; i < scene->nresult && !e; ++i) e = ok ? SlumpFilePrintf(fp, ",%.10e", (double)scene->rvalue[i]) : SlumpFilePrintf(fp, ",");
    if (!e) e = SlumpFilePrintf(fp, ",%s,%s\n", status, q);
    if (!e) e = SlumpFileClose(&fp);
    else (void)SlumpFileClose(&fp);
  }
  PetscCall(SlumpFileCommit(r->comm, e, tmp, path));
  PetscFunctionReturn(0);
}

/* The driver's share of a checkpoint: the dissipation integral, the output
   and iteration counts, and the level set's bookkeeping. */
static PetscErrorCode CheckpointGet(void *ctx, PetscInt *n, PetscReal v[])
{
  RunCtx       *r = (RunCtx *)ctx;
  SlumpLevelSet ls;
  PetscFunctionBeginUser;
  for (int k = 0; k < 2; ++k) {
    v[3 * k]     = r->diss[k].t;
    v[3 * k + 1] = r->diss[k].rate;
    v[3 * k + 2] = r->diss[k].total;
  }
  v[6] = r->ndiss;
  v[7] = r->nout;
  v[8] = r->newton_since;
  v[9] = r->lin_since;
  *n   = 10;
  PetscCall(SlumpProblemGetLevelSet(r->prob, &ls));
  if (ls) {
    PetscCall(SlumpLevelSetGetState(ls, v + 10));
    *n += SLUMP_LEVELSET_STATE;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckpointSet(void *ctx, PetscInt n, const PetscReal v[])
{
  RunCtx       *r = (RunCtx *)ctx;
  SlumpLevelSet ls;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetLevelSet(r->prob, &ls));
  PetscCheck(n == 10 + (ls ? SLUMP_LEVELSET_STATE : 0), r->comm, PETSC_ERR_USER_INPUT, "The checkpoint (-restart) was written by a run %s a level set; restart with the scene that wrote it", ls ? "without" : "with");
  for (int k = 0; k < 2; ++k) {
    r->diss[k].t     = v[3 * k];
    r->diss[k].rate  = v[3 * k + 1];
    r->diss[k].total = v[3 * k + 2];
  }
  r->ndiss        = (PetscInt)v[6];
  r->nout         = (PetscInt)v[7];
  r->newton_since = (PetscInt)v[8];
  r->lin_since    = (PetscInt)v[9];
  if (ls) PetscCall(SlumpLevelSetSetState(ls, v + 10));
  PetscFunctionReturn(0);
}

static PetscBool setup_only = PETSC_FALSE;

PetscErrorCode SlumpRunSetUp(MPI_Comm comm)
{
  PetscErrorCode ierr;
  PetscFunctionBeginUser;
  setup_only = PETSC_TRUE;
  ierr       = SlumpRunOne(comm, PETSC_FALSE, NULL);
  setup_only = PETSC_FALSE;
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRunOne(MPI_Comm comm, PetscBool banner, SlumpRunResult *res)
{
  char            scenename[64] = "couette_cessation", dir[PETSC_MAX_PATH_LEN] = "";
  PetscBool       list = PETSC_FALSE, fields = PETSC_TRUE, set, quiet = PETSC_FALSE, eigen = PETSC_FALSE, overwrite = PETSC_FALSE, exact = PETSC_FALSE, yield_map = PETSC_TRUE;
  PetscReal       exact_yielded = -1.0;
  SlumpLevelSet   ls;
  PetscErrorCode  solve_err = 0;
  char            status[32] = "ok", reason[600] = "";
  const char     *restart_file = NULL;
  SlumpProblem    prob;
  SlumpScene      scene;
  SlumpIntegrator ti = NULL;
  SlumpRheology   rheo;
  SlumpStats      stats;
  RunCtx          r;
  SlumpRunResult  local, *R = res ? res : &local;
  DM              dm;
  Vec             X;
  PetscLogDouble  t_start, t_end;
  PetscReal       t_final, t_arrest = -1.0, err[2], nrm[2], rtol = 0, atol = 0, dt = 0, peak;
  PetscInt        narrest = 0;
  const SlumpArrestCriterion *arrest = NULL;
  char            arrestname[16][64];
  PetscMPIInt     size;
  PetscInt        N, ncells, cStart, cEnd;
  SlumpIntegratorType itype = SLUMP_INTEGRATOR_IDA;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t_start));
  ResetPeakMemory();
  PetscCall(PetscMemorySetGetMaximumUsage());
  PetscCall(PetscMemzero(&r, sizeof(r)));
  PetscCallMPI(MPI_Comm_rank(comm, &r.rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  r.comm = comm;
  PetscOptionsBegin(comm, NULL, "slump", "SlumpRun");
  PetscCall(PetscOptionsString("-scene", "Scene to run ('list' lists them)", "", scenename, scenename, sizeof(scenename), NULL));
  PetscCall(PetscOptionsString("-output_dir", "Output directory (default out/<scene>)", "", dir, dir, sizeof(dir), &set));
  PetscCall(PetscOptionsBool("-output_fields", "Write fields (XDMF + HDF5) at output times", "", fields, &fields, NULL));
  PetscCall(PetscOptionsBool("-output_overwrite", "Write into an output directory another live run holds (its lock file)", "", overwrite, &overwrite, NULL));
  PetscCall(PetscOptionsBool("-quiet", "No progress lines", "", quiet, &quiet, NULL));
  PetscCall(PetscOptionsBool("-output_yield_map", "Steady runs: write yield_map.csv (x, y, yielded at every quadrature point)", "", yield_map, &yield_map, NULL));
  {
    const char *methods[] = {"regularised", "exact"};
    PetscInt    m         = 0;
    PetscCall(PetscOptionsEList("-method", "Yield law: regularised (the rheology's regularisation) or exact (unregularised Bingham by ALG2, timeint/exact.c)", "", methods, 2, methods[0], &m, NULL));
    exact = m == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(PetscOptionsBool("-viscous_eigenvalue", "Compute lambda1 of the viscous operator (SLEPc) and the energy bound on the stopping time", "", eigen, &eigen, NULL));
  PetscOptionsEnd();
  r.quiet = quiet;
  PetscCall(PetscStrcmp(scenename, "list", &list));
  if (list) {
    PetscCall(SlumpSceneView(comm));
    PetscFunctionReturn(0);
  }
  if (!dir[0]) PetscCall(PetscSNPrintf(dir, sizeof(dir), "out/%s", scenename));

  /* --- read and check everything --- */
  PetscCall(SlumpProblemCreate(comm, &prob));
  PetscCall(SlumpSceneCreate(comm, scenename, prob, &scene));
  r.prob  = prob;
  r.scene = scene;
  PetscCall(SlumpProblemSetFromOptions(prob));
  PetscCall(SlumpProblemSetUp(prob));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  if (!scene->steady) {
    PetscCall(SlumpIntegratorCreate(prob, &ti));
    PetscCall(SlumpIntegratorSetTimes(ti, scene->t0, scene->tfinal, scene->dtout));
    PetscCall(SlumpIntegratorSetArrestThreshold(ti, scene->arrest_threshold, PETSC_FALSE));
    if (scene->rtol > 0 || scene->atol > 0) {
      PetscCall(SlumpIntegratorGetTolerances(ti, &rtol, &atol));
      PetscCall(SlumpIntegratorSetTolerances(ti, scene->rtol > 0 ? scene->rtol : rtol, scene->atol > 0 ? scene->atol : atol));
    }
    if (scene->restart_step > 0) PetscCall(SlumpIntegratorSetRestartStep(ti, scene->restart_step));
    if (scene->linesearch) PetscCall(SlumpIntegratorSetLineSearch(ti, PETSC_TRUE));
    if (exact) PetscCall(SlumpIntegratorSetType(ti, SLUMP_INTEGRATOR_EXACT));
    PetscCall(SlumpIntegratorSetFromOptions(ti));
    PetscCall(SlumpIntegratorGetType(ti, &itype));
    PetscCheck(!exact || itype == SLUMP_INTEGRATOR_EXACT, comm, PETSC_ERR_USER_INPUT, "-time_integrator %s contradicts -method exact, which integrates with backward Euler steps (-time_integrator exact); give one of them", SlumpIntegratorTypes[itype]);
    if (itype == SLUMP_INTEGRATOR_EXACT) exact = PETSC_TRUE;
    PetscCall(SlumpIntegratorGetTolerances(ti, &rtol, &atol));
    PetscCall(PetscOptionsGetReal(NULL, NULL, "-time_dt", &dt, NULL));
    PetscCall(SlumpIntegratorGetArrestCriteria(ti, &narrest, &arrest));
    /* unique column names: t_arrest_<diagnostic>[_<kind>][_<k>] */
    for (PetscInt k = 0; k < narrest; ++k) {
      PetscBool dup = PETSC_FALSE;
      for (PetscInt j = 0; j < narrest; ++j)
        if (j != k && arrest[j].diag == arrest[k].diag && arrest[j].kind == arrest[k].kind) dup = PETSC_TRUE;
      PetscCall(PetscSNPrintf(arrestname[k], sizeof(arrestname[k]), "%s%s%s", SlumpDiagnosticNames[arrest[k].diag], arrest[k].kind == SLUMP_THRESHOLD_ABSOLUTE ? "" : "_", arrest[k].kind == SLUMP_THRESHOLD_ABSOLUTE ? "" : SlumpThresholdKinds[arrest[k].kind]));
      if (dup) {
        char tmp[64];
        PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s_%d", arrestname[k], (int)k));
        PetscCall(PetscStrncpy(arrestname[k], tmp, sizeof(arrestname[k])));
      }
    }
  }
  if (exact) PetscCall(SlumpExactCheckProblem(prob)); /* before anything is written */
  else if (scene->steady) PetscCall(SlumpSteadyCheckOptions(prob));
  if (banner) {
    PetscCall(PetscPrintf(comm, "slump %s: scene %s on %d rank%s\n", SLUMP_VERSION_STRING, scenename, (int)size, size > 1 ? "s" : ""));
    PetscCall(SlumpProblemView(prob, PETSC_VIEWER_STDOUT_(comm)));
  }

  {
    PetscBool help;
    PetscCall(PetscOptionsHasHelp(NULL, &help));
    /* set up, nothing written: the options every part of the run reads */
    if (!help) PetscCall(SlumpOptionsCheck(comm, SLUMP_OPTIONS_SETUP));
    if (help || setup_only) {
      PetscCall(SlumpIntegratorDestroy(&ti));
      PetscCall(SlumpSceneDestroy(&scene));
      PetscCall(SlumpProblemDestroy(&prob));
      PetscFunctionReturn(0);
    }
  }

  if (ti) {
    /* a restart file that cannot be read is refused before anything is written */
    const char *rf;
    int         ok = 1;
    PetscCall(SlumpIntegratorGetRestartFile(ti, &rf));
    if (rf) {
      if (!r.rank) ok = access(rf, R_OK) == 0;
      PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
      PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot read the checkpoint '%s' (-restart); give a checkpoint.h5 written with -checkpoint_every or -checkpoint_interval", rf);
      restart_file = rf;
    }
  }

  /* the state (from a checkpoint: read and checked before anything is written) */
  PetscCall(SlumpProblemGetDM(prob, &dm));
  PetscCall(SlumpProblemCreateVector(prob, &X));
  PetscCall(PetscObjectSetName((PetscObject)X, "solution"));
  PetscCall(SlumpProblemProjectInitialState(prob, scene->t0, X));
  PetscCall(SlumpProblemGetLevelSet(prob, &ls));
  if (ti) {
    PetscCall(SlumpIntegratorSetCheckpointDirectory(ti, dir));
    PetscCall(SlumpIntegratorSetCheckpointHook(ti, CheckpointGet, CheckpointSet, &r));
  }
  if (restart_file) PetscCall(SlumpIntegratorLoadCheckpoint(ti, restart_file, X));

  /* --- outputs --- */
  PetscCall(SlumpMakeDirectory(comm, dir));
  PetscCall(SlumpOutputLock(comm, dir, overwrite));
  if (!r.rank) {
    /* a summary left by an earlier run in this directory is not this run's */
    char old[PETSC_MAX_PATH_LEN];
    PetscCall(PetscSNPrintf(old, sizeof(old), "%s/summary.csv", dir));
    (void)unlink(old);
  }
  PetscCall(OpenCSV(&r, dir, "series.csv", "t,kinetic_energy,mean_shear_rate,max_shear_rate,l2_shear_rate,dissipation,yielded_fraction,flow_rate,potential_energy,dissipation_ambient,dissipation_wall,dissipated", &r.series, r.series_path));
  if (!scene->steady) PetscCall(OpenCSV(&r, dir, "steps.csv", "t,h,order,newton_its,lin_its,err_test_fails,conv_fails,kinetic_energy", &r.steps, r.steps_path));
  if (fields) PetscCall(SlumpFieldWriterCreate(prob, dir, &r.writer));

  /* --- run --- */
  if (restart_file) {
    /* the state, the integrator's history and the accumulators at t_c are
       loaded; the outputs of this run start after t_c */
    PetscReal tc;
    PetscCall(SlumpIntegratorGetRestart(ti, NULL, &tc));
    PetscCall(PetscPrintf(comm, "restart from %s at t = %.6g\n", restart_file, (double)tc));
    if (ls) {
      char path[PETSC_MAX_PATH_LEN];
      PetscCall(PetscSNPrintf(path, sizeof(path), "%s/interface.csv", dir));
      PetscCall(SlumpLevelSetSetLog(ls, path));
      PetscCall(SlumpLevelSetUpdateSurface(ls, tc, X));
    }
  } else {
    if (scene->initial) PetscCall(scene->initial(scene, prob, X));
    if (ls) {
      char path[PETSC_MAX_PATH_LEN];
      PetscCall(PetscSNPrintf(path, sizeof(path), "%s/interface.csv", dir));
      PetscCall(SlumpLevelSetSetLog(ls, path));
      PetscCall(SlumpLevelSetRecordVolume(ls, scene->t0, X));
      PetscCall(SlumpLevelSetUpdateSurface(ls, scene->t0, X));
    }
  }
  PetscCall(PetscMemzero(&stats, sizeof(stats)));
  if (eigen) {
    PetscReal l1;
    PetscCall(SlumpProblemComputeViscousEigenvalue(prob, &l1));
    PetscCall(PetscPrintf(comm, "viscous operator: lambda1 = %.8g (SLEPc)\n", (double)l1));
    PetscCall(SlumpSceneAddResult(scene, "lambda1", l1));
    if (!scene->steady) {
      PetscReal tau0 = 0.0, etap = 1.0, rho = 1.0;
      PetscBool has;
      PetscCall(SlumpRheologyHasParameter(rheo, "yield_stress", &has));
      if (has) PetscCall(SlumpRheologyGetParameter(rheo, "yield_stress", &tau0));
      PetscCall(SlumpRheologyHasParameter(rheo, "viscosity", &has));
      if (has) PetscCall(SlumpRheologyGetParameter(rheo, "viscosity", &etap));
      PetscCall(PetscOptionsGetReal(NULL, NULL, "-density", &rho, NULL));
      if (scene->bound_beta > 0 && tau0 > 0) {
        SlumpDiagnosticKind ke = SLUMP_DIAG_KINETIC_ENERGY;
        PetscReal           e0, u0, T;
        PetscCall(SlumpProblemComputeDiagnosticList(prob, 0.0, X, 1, &ke, &e0));
        u0 = PetscSqrtReal(2.0 * e0 / rho) * scene->bound_norm_scale;
        T  = rho / (etap * l1) * PetscLogReal(1.0 + etap * l1 * u0 / (tau0 * scene->bound_beta));
        PetscCall(PetscPrintf(comm, "energy bound on the exact stopping time: T <= %.6g (||u0|| = %.6g, beta = %.6g)\n", (double)T, (double)u0, (double)scene->bound_beta));
        PetscCall(SlumpSceneAddResult(scene, "t_stop_bound_slepc", T));
      } else PetscCall(PetscPrintf(comm, "no stopping-time bound printed: %s\n", tau0 > 0 ? "the constant beta of the estimate is not known for this geometry" : "no yield stress"));
    }
  }
  /* A failed solve (no convergence, a failed write) still gets its summary,
     with the status and the reason; an interrupted one (SIGINT, SIGTERM)
     ends after its current step and gets its summary too. */
  if (scene->steady) {
    if (scene->initial_solved && !exact && !restart_file) {
      stats     = scene->initial_stats;
      solve_err = 0;
      PetscCall(SlumpProblemGetCounters(prob, &stats.res_evals, &stats.jac_evals));
    } else solve_err = exact ? SlumpSteadySolveExact(prob, X, &stats, &exact_yielded) : SlumpSteadySolve(prob, X, &stats);
    t_final   = 0.0;
    if (!solve_err) PetscCall(WriteDiagnostics(&r, 0.0, X, 0.0, 0));
  } else {
    PetscCall(SlumpIntegratorSetStepMonitor(ti, StepMonitor, &r));
    PetscCall(SlumpIntegratorSetOutputMonitor(ti, OutputMonitor, &r));
    solve_err = SlumpIntegratorSolve(ti, X);
    PetscCall(SlumpIntegratorGetStats(ti, &stats));
    PetscCall(SlumpIntegratorGetTime(ti, &t_final));
    PetscCall(SlumpIntegratorGetArrestTime(ti, &t_arrest));
    if (!solve_err) PetscCall(SlumpProblemComputeDiagnostics(prob, t_final, X, &r.last));
  }
  if (scene->steady && !solve_err && SlumpInterruptSignal()) r.signal = SlumpInterruptSignal();
  if (solve_err) {
    PetscCall(PetscStrncpy(status, solve_err == PETSC_ERR_NOT_CONVERGED ? "not_converged" : "failed", sizeof(status)));
    PetscCall(PetscStrncpy(reason, SlumpLastErrorMessage()[0] ? SlumpLastErrorMessage() : "unknown error", sizeof(reason)));
  } else if (r.signal) {
    PetscCall(PetscStrncpy(status, "interrupted", sizeof(status)));
    PetscCall(PetscSNPrintf(reason, sizeof(reason), "%s at t = %g", r.signal == SIGINT ? "SIGINT" : (r.signal == SIGTERM ? "SIGTERM" : "a signal"), (double)t_final));
  } else if (narrest && t_arrest < 0) PetscCall(PetscStrncpy(status, "no_arrest", sizeof(status)));
  err[0] = err[1] = nrm[0] = nrm[1] = -1.0;
  PetscCall(PetscStrncpy(scene->dir, dir, sizeof(scene->dir)));
  if (!solve_err) {
    PetscCall(SlumpProblemComputeErrors(prob, t_final, X, err, nrm));
    if (scene->results) PetscCall(scene->results(scene, prob, t_final, X));
    if (exact && scene->steady) PetscCall(SlumpSceneAddResult(scene, "yielded_fraction_exact", exact_yielded));
    if (scene->steady && yield_map) {
      /* where the material flows: the exact method's yield surface, or the
         rheology's criterion ||tau|| > tau_y */
      SlumpFormulation form;
      PetscCall(SlumpProblemGetFormulation(prob, &form));
      if (form != SLUMP_FORMULATION_TRANSPORT) {
        char path[PETSC_MAX_PATH_LEN];
        PetscCall(PetscSNPrintf(path, sizeof(path), "%s/yield_map.csv", dir));
        PetscCall(SlumpProblemWriteYieldMap(prob, t_final, X, path));
      }
    }
    if (exact && ti) {
      PetscReal lo, hi;
      PetscCall(SlumpIntegratorGetStopInterval(ti, &lo, &hi));
      PetscCall(SlumpSceneAddResult(scene, "t_stop_lower", lo));
      PetscCall(SlumpSceneAddResult(scene, "t_stop_upper", hi));
    }
    /* free surface: the final profile (the deposit of a collapse) */
    SlumpFormulation form;
    PetscCall(SlumpProblemGetFormulation(prob, &form));
    if (ls && form == SLUMP_FORMULATION_PLANE) {
      char path[PETSC_MAX_PATH_LEN];
      PetscCall(PetscSNPrintf(path, sizeof(path), "%s/deposit.csv", dir));
      PetscCall(SlumpLevelSetWriteProfile(ls, t_final, X, path));
    }
  }
  PetscCall(PetscTime(&t_end));
  PetscCall(PeakMemory(comm, &peak));
  if (!solve_err && !scene->steady && scene->exact_arrest) {
    /* the exact model's times, for the first criterion (not in the cost) */
    PetscReal ts = -1.0, ta = -1.0;
    PetscCall(scene->exact_arrest(scene, prob, narrest ? (SlumpDiagnosticKind)arrest[0].diag : SLUMP_DIAG_MEAN_SHEAR_RATE, narrest ? arrest[0].threshold : 0.0, &ts, &ta));
    if (ts >= 0) PetscCall(SlumpSceneAddResult(scene, "t_stop_exact", ts));
    if (ta >= 0) PetscCall(SlumpSceneAddResult(scene, "t_arrest_exact", ta));
  }
  PetscCall(VecGetSize(X, &N));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  ncells = cEnd - cStart;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm));

  {
    /* the run's numbers: summary.csv and, for sweeps, the caller */
    SlumpRheologyType rtype;
    const char       *regname;
    PetscCall(PetscMemzero(R, sizeof(*R)));
    PetscCall(PetscStrncpy(R->scene, scenename, sizeof(R->scene)));
    PetscCall(SlumpRheologyGetType(rheo, &rtype));
    PetscCall(PetscStrncpy(R->rheology, rtype, sizeof(R->rheology)));
    PetscCall(SlumpRheologyGetRegularisation(rheo, &regname, &R->regularisation_value, NULL));
    PetscCall(PetscStrncpy(R->regularisation, exact ? "exact" : (regname ? regname : "none"), sizeof(R->regularisation)));
    if (exact) R->regularisation_value = 0.0;
    PetscCall(PetscStrncpy(R->integrator, scene->steady ? (exact ? "steady_exact" : "steady") : SlumpIntegratorTypes[itype], sizeof(R->integrator)));
    if (ti) PetscCall(SlumpIntegratorGetTolerances(ti, &rtol, &atol)); /* the absolute tolerance the run resolved */
    R->rtol     = rtol;
    R->atol     = atol;
    R->dt       = dt;
    R->ranks    = size;
    R->cells    = ncells;
    R->unknowns = N;
    R->t_final  = t_final;
    R->t_arrest = t_arrest;
    R->narrest  = narrest;
    for (PetscInt k = 0; k < narrest; ++k) {
      R->arrest_diag[k]      = arrest[k].diag;
      R->arrest_kind[k]      = arrest[k].kind;
      R->arrest_time[k]      = arrest[k].t_arrest;
      R->arrest_threshold[k] = arrest[k].threshold;
    }
    R->stats     = stats;
    R->wall_time = t_end - t_start;
    R->peak_mb   = peak;
    R->err_u     = err[0];
    R->norm_u    = nrm[0];
    R->nresult   = scene->nresult;
    for (PetscInt i = 0; i < scene->nresult; ++i) {
      PetscCall(PetscStrncpy(R->rname[i], scene->rname[i], sizeof(R->rname[i])));
      R->rvalue[i] = scene->rvalue[i];
    }
  }
  /* --- the time series, then the summary (whole or absent) --- */
  {
    int e = SlumpFileClose(&r.series);
    PetscCall(SlumpFileCheck(comm, e, r.series_path));
    e = SlumpFileClose(&r.steps);
    if (!scene->steady) PetscCall(SlumpFileCheck(comm, e, r.steps_path));
    if (ls) PetscCall(SlumpLevelSetSetLog(ls, NULL));
  }
  PetscCall(WriteSummary(&r, dir, R, scene, narrest, arrest, arrestname, err, nrm, status, reason));
  if (solve_err) {
    /* the solver's error, already reported; the outputs are closed */
    PetscCall(SlumpOutputUnlock(comm, dir));
    goto cleanup;
  }
  if (r.signal) {
    PetscCall(SlumpOutputUnlock(comm, dir));
    PetscCall(PetscPrintf(comm, "interrupted (%s) at t = %.6g after %d steps; outputs up to it in %s/ (summary.csv status interrupted)\n", r.signal == SIGINT ? "SIGINT" : "SIGTERM", (double)t_final, (int)stats.steps, dir));
    solve_err = PETSC_ERR_SIG;
    goto cleanup;
  }
  if (!banner) goto unlock;
  PetscCall(PetscPrintf(comm, "summary: scene %s, t %.6g", scenename, (double)t_final));
  if (!scene->steady) {
    for (PetscInt k = 0; k < narrest; ++k) {
      if (arrest[k].t_arrest >= 0) PetscCall(PetscPrintf(comm, ", arrest (%s < %.4g) at t = %.6g", SlumpDiagnosticNames[arrest[k].diag], (double)arrest[k].threshold, (double)arrest[k].t_arrest));
      else PetscCall(PetscPrintf(comm, ", no arrest (%s < %.4g)", SlumpDiagnosticNames[arrest[k].diag], (double)arrest[k].threshold));
    }
    if (!narrest) PetscCall(PetscPrintf(comm, ", no arrest criterion"));
  }
  PetscCall(PetscPrintf(comm, ", %d steps, %d residual and %d Jacobian evaluations, %d Newton and %d linear iterations, %.3f s, %.0f MB", (int)stats.steps, (int)stats.res_evals, (int)stats.jac_evals, (int)stats.newton_its, (int)stats.lin_its, (double)(t_end - t_start), (double)peak));
  if (err[0] >= 0) PetscCall(PetscPrintf(comm, ", relative L2 velocity error %.3e", (double)(err[0] / (nrm[0] > 0 ? nrm[0] : 1.0))));
  for (PetscInt i = 0; i < scene->nresult; ++i) PetscCall(PetscPrintf(comm, ", %s %.6g", scene->rname[i], (double)scene->rvalue[i]));
  PetscCall(PetscPrintf(comm, "\noutputs in %s/\n", dir));

unlock:
  PetscCall(SlumpOutputUnlock(comm, dir));
cleanup:
  PetscCall(VecDestroy(&X));
  PetscCall(SlumpFieldWriterDestroy(&r.writer));
  PetscCall(SlumpIntegratorDestroy(&ti));
  PetscCall(SlumpSceneDestroy(&scene));
  PetscCall(SlumpProblemDestroy(&prob));
  if (solve_err == PETSC_ERR_SIG) SETERRQ(comm, PETSC_ERR_SIG, "Interrupted by %s at t = %g; the outputs up to it are in %s", r.signal == SIGINT ? "SIGINT" : "SIGTERM", (double)t_final, dir);
  PetscFunctionReturn(solve_err);
}

/* slump: a sweep when -sweep is given, otherwise one run. */
PetscErrorCode SlumpRun(MPI_Comm comm)
{
  PetscBool sweep;
  PetscBool help, sweep2, ranks;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-sweep", &sweep));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-sweep2", &sweep2));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-sweep_ranks", &ranks));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (!help) PetscCall(SlumpOptionsCheck(comm, SLUMP_OPTIONS_START));
  PetscCheck(sweep || !(sweep2 || ranks), comm, PETSC_ERR_USER_INPUT, "%s is given without -sweep; give -sweep OPTION:v1,v2,... first", sweep2 ? "-sweep2" : "-sweep_ranks");
  if (sweep) PetscCall(SlumpSweep(comm));
  else PetscCall(SlumpRunOne(comm, PETSC_TRUE, NULL));
  /* every option given was read by some part of the run */
  if (!help) PetscCall(SlumpOptionsCheck(comm, SLUMP_OPTIONS_END));
  PetscFunctionReturn(0);
}
