/* Batch sweeps: one run per value of an option, or per pair of values of two
 * options (Cartesian product), each run on its own MPI sub-communicator.
 *
 *   slump -scene couette_cessation -sweep rheology_papanastasiou_m:1e2,1e3,1e4 \
 *         [-sweep2 bn:0.1,1,10] [-sweep_ranks k] [-output_dir DIR]
 *
 * Under mpirun -n P the ranks are split (MPI_Comm_split) into P/k groups of k
 * ranks; run i goes to group i mod (P/k), so P/k runs proceed at a time and
 * each group works through its own queue. Every other option applies to all
 * runs. Each run writes its usual outputs to DIR/run_NNNN/ (fields off unless
 * -output_fields is given), and its group's first rank appends one row to
 * DIR/sweep.csv when the run ends: the swept values, the exit status and its
 * reason, the arrest times, the error against the scene's reference, and the
 * cost (steps, evaluations, iterations, wall time, peak memory). A run that
 * fails (an invalid value, no convergence) becomes a row with the reason, and
 * the sweep goes on. */
#include "slumpscene.h"
#include <fcntl.h>
#include <unistd.h>

#define SWEEP_MAX_VALUES 256

typedef struct {
  char  name[128];            /* option name without the dash */
  char  spec[4096];           /* the values, comma-separated (storage) */
  char *value[SWEEP_MAX_VALUES];
  int   n;
} SweepList;

static PetscErrorCode SweepListParse(MPI_Comm comm, const char opt[], const char text[], SweepList *l)
{
  const char *colon = strchr(text, ':');
  char       *s;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(l, sizeof(*l)));
  PetscCheck(colon && colon != text && colon[1], comm, PETSC_ERR_USER_INPUT, "%s takes OPTION:value1,value2,... (an option name without its dash, a colon, comma-separated values); got '%s'", opt, text);
  if (text[0] == '-') ++text;
  PetscCheck((size_t)(colon - text) < sizeof(l->name), comm, PETSC_ERR_USER_INPUT, "%s: the option name is too long", opt);
  PetscCall(PetscStrncpy(l->name, text, (size_t)(colon - text) + 1));
  PetscCall(PetscStrncpy(l->spec, colon + 1, sizeof(l->spec)));
  for (s = l->spec;;) {
    char *comma = strchr(s, ',');
    if (comma) *comma = 0;
    PetscCheck(s[0], comm, PETSC_ERR_USER_INPUT, "%s %s: value %d is empty; give comma-separated values without empty ones", opt, l->name, l->n + 1);
    PetscCheck(l->n < SWEEP_MAX_VALUES, comm, PETSC_ERR_USER_INPUT, "%s: at most %d values", opt, SWEEP_MAX_VALUES);
    l->value[l->n++] = s;
    if (!comma) break;
    s = comma + 1;
  }
  PetscCheck(l->n > 0, comm, PETSC_ERR_USER_INPUT, "%s: no values after '%s:'", opt, l->name);
  PetscFunctionReturn(0);
}

/* CSV field: quoted, with inner quotes doubled. */
static void CSVString(char *buf, size_t len, const char s[])
{
  size_t k = 0;
  if (len < 3) return;
  buf[k++] = '"';
  for (const char *c = s; *c && k + 3 < len; ++c) {
    if (*c == '"') buf[k++] = '"';
    buf[k++] = *c;
  }
  buf[k++] = '"';
  buf[k]   = 0;
}

/* Append to the row; numbers that are not available are left empty. */
static void Put(char *row, size_t len, const char *fmt, double v, PetscBool have)
{
  size_t k = strlen(row);
  if (have) snprintf(row + k, len - k, fmt, v);
  else snprintf(row + k, len - k, ",");
}

static PetscBool GetResult(const SlumpRunResult *r, const char name[], PetscReal *v)
{
  for (PetscInt i = 0; i < r->nresult; ++i)
    if (!strcmp(r->rname[i], name)) {
      *v = r->rvalue[i];
      return PETSC_TRUE;
    }
  return PETSC_FALSE;
}

/* The columns between reason and wall_time, left empty for a failed run. */
static const char        RunColumns[]    = "scene,rheology,regularisation,regularisation_value,integrator,rtol,atol,dt,ranks,cells,unknowns,t_final,t_arrest";
static const char *const TimeColumns[]   = {"mean_shear_rate", "max_shear_rate", "l2_shear_rate", "kinetic_energy", "yielded_fraction"};
static const char        ResultColumns[] = "threshold,t_stop_exact,t_arrest_exact,arrest_error,stop_error,t_stop_bound,err_u_rel,steps,res_evals,jac_evals,newton_its,lin_its,err_test_fails,conv_fails,h_min";
#define NTIME (sizeof(TimeColumns) / sizeof(TimeColumns[0]))

static int NumFields(const char list[])
{
  int n = 1;
  for (const char *c = list; *c; ++c) n += *c == ',';
  return n;
}

static void Header(char *row, size_t len, const SweepList *l, int nl)
{
  snprintf(row, len, "run");
  for (int j = 0; j < nl; ++j) snprintf(row + strlen(row), len - strlen(row), ",%s", l[j].name);
  snprintf(row + strlen(row), len - strlen(row), ",status,reason,%s", RunColumns);
  for (size_t k = 0; k < NTIME; ++k) snprintf(row + strlen(row), len - strlen(row), ",t_arrest_%s", TimeColumns[k]);
  snprintf(row + strlen(row), len - strlen(row), ",%s,wall_time,peak_memory_mb,results\n", ResultColumns);
}

static void Row(char *row, size_t len, int run, const SweepList *l, int nl, const int *idx, const char *status, const char *reason, const SlumpRunResult *r, PetscBool ok, double wall)
{
  char q[1024];
  snprintf(row, len, "%d", run);
  for (int j = 0; j < nl; ++j) {
    CSVString(q, sizeof(q), l[j].value[idx[j]]);
    snprintf(row + strlen(row), len - strlen(row), ",%s", q);
  }
  CSVString(q, sizeof(q), reason);
  snprintf(row + strlen(row), len - strlen(row), ",%s,%s", status, q);
  if (!ok) {
    /* the columns of a run that did not finish stay empty */
    const int nempty = NumFields(RunColumns) + (int)NTIME + NumFields(ResultColumns);
    for (int k = 0; k < nempty; ++k) snprintf(row + strlen(row), len - strlen(row), ",");
    snprintf(row + strlen(row), len - strlen(row), ",%.4f,,\n", wall);
    return;
  }
  snprintf(row + strlen(row), len - strlen(row), ",%s,%s,%s,%.6e,%s,%.3e,%.3e,%.6e,%d,%d,%d,%.10e", r->scene, r->rheology, r->regularisation, (double)r->regularisation_value, r->integrator, (double)r->rtol, (double)r->atol, (double)r->dt, (int)r->ranks, (int)r->cells, (int)r->unknowns, (double)r->t_final);
  Put(row, len, ",%.10e", (double)r->t_arrest, r->t_arrest >= 0 ? PETSC_TRUE : PETSC_FALSE);
  for (size_t k = 0; k < NTIME; ++k) {
    PetscInt c = -1;
    for (PetscInt j = r->narrest - 1; j >= 0; --j)
      if (!strcmp(SlumpDiagnosticNames[r->arrest_diag[j]], TimeColumns[k])) c = j;
    Put(row, len, ",%.10e", c >= 0 ? (double)r->arrest_time[c] : 0.0, c >= 0 && r->arrest_time[c] >= 0 ? PETSC_TRUE : PETSC_FALSE);
  }
  /* the first criterion: its threshold and its time on the exact model */
  Put(row, len, ",%.6e", r->narrest ? (double)r->arrest_threshold[0] : 0.0, r->narrest ? PETSC_TRUE : PETSC_FALSE);
  {
    PetscReal ts = 0, ta = 0, tb = 0;
    PetscBool hs = GetResult(r, "t_stop_exact", &ts), ha = GetResult(r, "t_arrest_exact", &ta), hb = GetResult(r, "t_stop_bound", &tb);
    PetscReal t0 = r->narrest ? r->arrest_time[0] : -1.0;
    Put(row, len, ",%.10e", (double)ts, hs);
    Put(row, len, ",%.10e", (double)ta, ha);
    Put(row, len, ",%.6e", ha && t0 >= 0 ? (double)(PetscAbsReal(t0 - ta) / ta) : 0.0, ha && t0 >= 0 && ta > 0 ? PETSC_TRUE : PETSC_FALSE);
    Put(row, len, ",%.6e", hs && t0 >= 0 ? (double)(PetscAbsReal(t0 - ts) / ts) : 0.0, hs && t0 >= 0 && ts > 0 ? PETSC_TRUE : PETSC_FALSE);
    Put(row, len, ",%.10e", (double)tb, hb);
  }
  Put(row, len, ",%.6e", r->norm_u > 0 ? (double)(r->err_u / r->norm_u) : 0.0, r->err_u >= 0 && r->norm_u > 0 ? PETSC_TRUE : PETSC_FALSE);
  snprintf(row + strlen(row), len - strlen(row), ",%d,%d,%d,%d,%d,%d,%d", (int)r->stats.steps, (int)r->stats.res_evals, (int)r->stats.jac_evals, (int)r->stats.newton_its, (int)r->stats.lin_its, (int)r->stats.err_test_fails, (int)r->stats.conv_fails);
  Put(row, len, ",%.6e", (double)r->stats.h_min, r->stats.steps > 0 ? PETSC_TRUE : PETSC_FALSE);
  snprintf(row + strlen(row), len - strlen(row), ",%.4f,%.1f,\"", (double)r->wall_time, (double)r->peak_mb);
  for (PetscInt i = 0; i < r->nresult; ++i) snprintf(row + strlen(row), len - strlen(row), "%s%s=%.10g", i ? ";" : "", r->rname[i], (double)r->rvalue[i]);
  snprintf(row + strlen(row), len - strlen(row), "\"\n");
}

/* One write(2) with O_APPEND per row: rows of concurrent groups do not mix
 * on a local or POSIX-append file system (Lustre, GPFS, ext4, ...). */
static PetscErrorCode AppendRow(const char path[], const char row[])
{
  int     fd;
  ssize_t n;
  size_t  len = strlen(row);
  PetscFunctionBeginUser;
  fd = open(path, O_WRONLY | O_APPEND);
  PetscCheck(fd >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot append to %s", path);
  n = write(fd, row, len);
  close(fd);
  PetscCheck(n == (ssize_t)len, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write a row to %s", path);
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSweep(MPI_Comm comm)
{
  char          spec[2][8192] = {"", ""}, dir[PETSC_MAX_PATH_LEN] = "", scenename[64] = "couette_cessation", path[PETSC_MAX_PATH_LEN], row[16384];
  SweepList    *l;
  int           nl = 1, nruns, ngroups, group, nfailed = 0;
  PetscInt      k = 1;
  PetscBool     has2, set, hasfields, hasquiet, overwrite = PETSC_FALSE, interrupted = PETSC_FALSE;
  PetscMPIInt   rank, size, grank;
  MPI_Comm      sub;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc1(2, &l));
  PetscOptionsBegin(comm, NULL, "Sweep", "SlumpSweep");
  PetscCall(PetscOptionsString("-sweep", "OPTION:v1,v2,...: one run per value", "", spec[0], spec[0], sizeof(spec[0]), NULL));
  PetscCall(PetscOptionsString("-sweep2", "OPTION:w1,w2,...: a second list; one run per pair (Cartesian product, -sweep varying fastest)", "", spec[1], spec[1], sizeof(spec[1]), &has2));
  PetscCall(PetscOptionsInt("-sweep_ranks", "Ranks per run (the P ranks make P/k groups)", "", k, &k, NULL));
  PetscCall(PetscOptionsString("-scene", "Scene", "", scenename, scenename, sizeof(scenename), NULL));
  PetscCall(PetscOptionsString("-output_dir", "Sweep directory (default out/sweep_<scene>)", "", dir, dir, sizeof(dir), &set));
  PetscCall(PetscOptionsBool("-output_overwrite", "Write into a sweep directory another live sweep holds", "", overwrite, &overwrite, NULL));
  PetscOptionsEnd();
  PetscCall(SweepListParse(comm, "-sweep", spec[0], &l[0]));
  if (has2) {
    PetscCall(SweepListParse(comm, "-sweep2", spec[1], &l[1]));
    nl = 2;
    PetscCheck(strcmp(l[0].name, l[1].name), comm, PETSC_ERR_USER_INPUT, "-sweep and -sweep2 name the same option '%s'; give two different options", l[0].name);
  }
  for (int j = 0; j < nl; ++j) {
    PetscCheck(strcmp(l[j].name, "output_dir") && strcmp(l[j].name, "sweep_ranks"), comm, PETSC_ERR_USER_INPUT, "-sweep%s: '%s' cannot be swept; sweep any scene, rheology or solver option", j ? "2" : "", l[j].name);
  }
  for (int j = 0; j < nl; ++j) PetscCall(SlumpOptionsCheckName(comm, j ? "-sweep2" : "-sweep", l[j].name));
  PetscCheck(k >= 1 && k <= size && size % k == 0, comm, PETSC_ERR_USER_INPUT, "-sweep_ranks must divide the number of ranks (%d); got %d", (int)size, (int)k);
  if (!set) PetscCall(PetscSNPrintf(dir, sizeof(dir), "out/sweep_%s", scenename));
  nruns   = l[0].n * (nl > 1 ? l[1].n : 1);
  ngroups = size / (int)k;
  group   = rank / (int)k;
  PetscCallMPI(MPI_Comm_split(comm, group, rank, &sub));
  PetscCallMPI(MPI_Comm_rank(sub, &grank));

  /* the runs' outputs: no fields and no progress lines unless asked */
  PetscCall(PetscOptionsHasName(NULL, NULL, "-output_fields", &hasfields));
  if (!hasfields) PetscCall(PetscOptionsSetValue(NULL, "-output_fields", "false"));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-quiet", &hasquiet));
  if (!hasquiet) PetscCall(PetscOptionsSetValue(NULL, "-quiet", "true"));

  /* before the first run: the whole set-up with the first values, so that
     a swept option this scene and these settings do not read (N identical
     runs) and any other mistake are refused with nothing written */
  {
    /* the first values that set up (an invalid value becomes its runs'
       rows); if none does, the last attempt's error is the sweep's */
    const int ntry = PetscMax(l[0].n, nl > 1 ? l[1].n : 1);
    for (int t = 0; t < ntry; ++t) {
      PetscErrorCode ierr;
      for (int j = 0; j < nl; ++j) {
        char opt[160];
        PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s", l[j].name));
        PetscCall(PetscOptionsSetValue(NULL, opt, l[j].value[PetscMin(t, l[j].n - 1)]));
      }
      if (t == ntry - 1) {
        PetscCall(SlumpRunSetUp(sub));
        break;
      }
      PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
      ierr = SlumpRunSetUp(sub);
      PetscCall(PetscPopErrorHandler());
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ierr, 1, MPI_INT, MPI_MAX, comm));
      if (!ierr) break;
    }
  }
  for (int j = 0; j < nl; ++j) {
    PetscBool used;
    PetscCall(PetscOptionsUsed(NULL, l[j].name, &used)); /* the name without its dash */
    PetscCheck(used || SlumpOptionReadLate(l[j].name), comm, PETSC_ERR_USER_INPUT, "-sweep%s: option -%s is not read by scene %s with these settings (every run would be the same); sweep an option the run reads", j ? "2" : "", l[j].name, scenename);
  }

  PetscCall(SlumpMakeDirectory(comm, dir));
  PetscCall(SlumpOutputLock(comm, dir, overwrite));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/sweep.csv", dir));
  {
    FILE *fp  = NULL;
    int   err = 0;
    if (!rank) {
      Header(row, sizeof(row), l, nl);
      err = SlumpFileOpen(path, &fp);
      if (!err) err = SlumpFilePrintf(fp, "%s", row);
      if (!err) err = SlumpFileClose(&fp);
      else (void)SlumpFileClose(&fp);
    }
    PetscCall(SlumpFileCheck(comm, err, path));
  }
  PetscCall(PetscPrintf(comm, "slump %s: sweep of %d runs of %s over %s%s%s, %d group%s of %d rank%s; rows in %s\n", SLUMP_VERSION_STRING, nruns, scenename, l[0].name, nl > 1 ? " x " : "", nl > 1 ? l[1].name : "", ngroups, ngroups > 1 ? "s" : "", (int)k, k > 1 ? "s" : "", path));
  PetscCallMPI(MPI_Barrier(comm));
  PetscCall(PetscTime(&t0));

  for (int run = group; run < nruns; run += ngroups) {
    int            idx[2] = {run % l[0].n, nl > 1 ? run / l[0].n : 0};
    char           opt[160], rundir[PETSC_MAX_PATH_LEN], reason[600] = "";
    const char    *status = "ok";
    SlumpRunResult res;
    PetscErrorCode ierr;
    PetscBool      ok;
    PetscLogDouble r0, r1;

    for (int j = 0; j < nl; ++j) {
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s", l[j].name));
      PetscCall(PetscOptionsSetValue(NULL, opt, l[j].value[idx[j]]));
    }
    PetscCall(PetscSNPrintf(rundir, sizeof(rundir), "%s/run_%04d", dir, run));
    PetscCall(PetscOptionsSetValue(NULL, "-output_dir", rundir));
    SlumpClearLastError();
    PetscCall(PetscTime(&r0));
    ierr = SlumpRunOne(sub, PETSC_FALSE, &res);
    PetscCall(PetscTime(&r1));
    ok   = ierr ? PETSC_FALSE : PETSC_TRUE;
    if (!ok) {
      /* the reason: the error's first message (every rank of the group saw it) */
      status = ierr == PETSC_ERR_SIG ? "interrupted" : ierr == PETSC_ERR_NOT_CONVERGED ? "not_converged" : (ierr == PETSC_ERR_USER_INPUT || ierr == PETSC_ERR_ARG_WRONG || ierr == PETSC_ERR_ARG_OUTOFRANGE ? "invalid" : "error");
      PetscCall(PetscSNPrintf(reason, sizeof(reason), "%s", SlumpLastErrorMessage()[0] ? SlumpLastErrorMessage() : "unknown error"));
      if (!grank) ++nfailed; /* counted once per group */
    } else if (res.narrest && res.t_arrest < 0) {
      status = "no_arrest";
      PetscCall(PetscSNPrintf(reason, sizeof(reason), "no arrest criterion fired before t = %g", (double)res.t_final));
    }
    if (!grank) {
      char vals[512] = "";
      for (int j = 0; j < nl; ++j) PetscCall(PetscSNPrintf(vals + strlen(vals), sizeof(vals) - strlen(vals), "%s%s=%s", j ? " " : "", l[j].name, l[j].value[idx[j]]));
      Row(row, sizeof(row), run, l, nl, idx, status, reason, &res, ok, (double)(r1 - r0));
      PetscCall(AppendRow(path, row));
      if (ok) printf("sweep: run %d/%d (%s) %s: t_arrest %.6g, %d steps, %.2f s\n", run + 1, nruns, vals, status, (double)res.t_arrest, (int)res.stats.steps, (double)res.wall_time);
      else printf("sweep: run %d/%d (%s) %s: %s\n", run + 1, nruns, vals, status, reason);
      fflush(stdout);
    }
    /* SIGINT/SIGTERM: the run in progress ended after its step; no more runs */
    {
      int sig = SlumpInterruptSignal();
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &sig, 1, MPI_INT, MPI_MAX, sub));
      if (sig) {
        interrupted = PETSC_TRUE;
        break;
      }
    }
  }
  PetscCallMPI(MPI_Barrier(comm));
  PetscCall(PetscTime(&t1));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nfailed, 1, MPI_INT, MPI_SUM, comm));
  PetscCall(PetscPrintf(comm, "sweep: %d runs, %d failed (see the status column), %.2f s on %d rank%s; rows in %s\n", nruns, nfailed, (double)(t1 - t0), (int)size, size > 1 ? "s" : "", path));
  PetscCallMPI(MPI_Comm_free(&sub));
  PetscCall(PetscFree(l));
  PetscCall(SlumpOutputUnlock(comm, dir));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &interrupted, 1, MPIU_BOOL, MPI_LOR, comm));
  PetscCheck(!interrupted, comm, PETSC_ERR_SIG, "Sweep interrupted by a signal; the rows of the runs that ended are in %s", path);
  PetscFunctionReturn(0);
}
