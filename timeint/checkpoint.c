/* Checkpoint and restart of a time integration (-checkpoint_every,
 * -checkpoint_interval, -restart).
 *
 * A checkpoint is one HDF5 file (written as checkpoint.h5.part and renamed
 * when complete, so the last complete checkpoint survives a crash while the
 * next is written) holding, as plain vectors:
 *   state    the solution at the checkpoint time t_c;
 *   history  what the next step needs besides it: the state one step back
 *            (fixed-step BDF2) or the time derivative at t_c (IDA);
 *   dual     the plastic stress of the stress-velocity Newton at every
 *            quadrature point of every local cell (empty without it);
 *   meta     (rank 0) the time, the last step and order, the counters, the
 *            next output index, the arrest criteria (time, threshold, last
 *            value), the absolute tolerance, and the values of the
 *            checkpoint hook (the driver's accumulators, the level set's
 *            bookkeeping).
 * A restart reads it on the same number of ranks (the partition and the
 * quadrature-point layout of the dual must match) and resumes at t_c:
 * fixed-step BDF2 exactly (the next step sees the same two states and the
 * same dual); IDA restarts its BDF at order 1 from (y, y') with the last
 * step size, since its divided-difference history is not public: its result
 * differs from the uninterrupted run by the local error control, of the
 * order of rtol. */
#include "timeintimpl.h"
#include <petscviewerhdf5.h>
#include <errno.h>
#include <unistd.h>

#define META_VERSION 1
enum {
  M_VERSION,
  M_TYPE,
  M_T,
  M_H,
  M_ORDER,
  M_HAVE_PREV,
  M_KOUT,
  M_STEPS,
  M_RES,
  M_JAC,
  M_NEWTON,
  M_LIN,
  M_LINSOLVES,
  M_ETF,
  M_CONVF,
  M_RESTARTS,
  M_HMIN,
  M_HMAX,
  M_ATOL,
  M_NARREST,
  M_RANKS,
  M_SIZE,
  M_DUALSAVED,
  M_DUALSIZE,
  M_NEXTRA,
  M_ARREST, /* 3 x 16: t_arrest, threshold, last value */
  M_EXTRA = M_ARREST + 48,
  M_LEN   = M_EXTRA + SLUMP_CHECKPOINT_MAX_EXTRA
};

PetscErrorCode SlumpIntegratorSetCheckpointHook(SlumpIntegrator ti, SlumpCheckpointGetFn get, SlumpCheckpointSetFn set, void *ctx)
{
  PetscFunctionBeginUser;
  ti->ckget = get;
  ti->ckset = set;
  ti->ckctx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSetCheckpointDirectory(SlumpIntegrator ti, const char dir[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(ti->ckdir, dir, sizeof(ti->ckdir)));
  PetscFunctionReturn(0);
}

/* A plain (DM-free) copy of a vector, viewed or loaded under a name. */
static PetscErrorCode PlainVec(Vec X, const char name[], Vec *P)
{
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)X), n, PETSC_DETERMINE, P));
  PetscCall(PetscObjectSetName((PetscObject)*P, name));
  PetscFunctionReturn(0);
}

static PetscErrorCode MetaVec(MPI_Comm comm, Vec *M)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecCreateMPI(comm, rank ? 0 : M_LEN, M_LEN, M));
  PetscCall(PetscObjectSetName((PetscObject)*M, "meta"));
  PetscFunctionReturn(0);
}

static PetscErrorCode DualVec(SlumpProblem prob, MPI_Comm comm, PetscBool *saved, Vec *D)
{
  PetscInt     n = 0;
  PetscScalar *S = NULL;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemDualGetState(prob, &n, saved, &S));
  PetscCall(VecCreateMPI(comm, n, PETSC_DETERMINE, D));
  PetscCall(PetscObjectSetName((PetscObject)*D, "dual"));
  if (n) {
    PetscScalar *d;
    PetscCall(VecGetArray(*D, &d));
    PetscCall(PetscArraycpy(d, S, n));
    PetscCall(VecRestoreArray(*D, &d));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorCheckpointWrite(SlumpIntegrator ti, Vec X, Vec H, PetscBool have_prev, PetscInt kout, const PetscReal gprev[])
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)X);
  PetscMPIInt rank, size;
  char        path[PETSC_MAX_PATH_LEN], part[PETSC_MAX_PATH_LEN];
  Vec         P, Q, D, M;
  PetscViewer v;
  PetscBool   saved;
  PetscInt    N;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/checkpoint.h5", ti->ckdir));
  PetscCall(PetscSNPrintf(part, sizeof(part), "%s/checkpoint.h5.part", ti->ckdir));
  PetscCall(PlainVec(X, "state", &P));
  PetscCall(VecCopy(X, P));
  PetscCall(PlainVec(X, "history", &Q));
  if (H) PetscCall(VecCopy(H, Q));
  PetscCall(DualVec(ti->prob, comm, &saved, &D));
  PetscCall(MetaVec(comm, &M));
  PetscCall(VecGetSize(X, &N));
  {
    SlumpStats st;
    PetscCall(SlumpIntegratorGetStats(ti, &st));
    if (!rank) {
      PetscScalar *m;
      PetscInt     nd;
      PetscCall(VecGetArray(M, &m));
      PetscCall(PetscArrayzero(m, M_LEN));
      PetscCall(VecGetLocalSize(D, &nd));
      m[M_VERSION]   = META_VERSION;
      m[M_TYPE]      = ti->type;
      m[M_T]         = ti->t;
      m[M_H]         = ti->h_last;
      m[M_ORDER]     = ti->order_last;
      m[M_HAVE_PREV] = have_prev;
      m[M_KOUT]      = kout;
      m[M_STEPS]     = st.steps;
      m[M_RES]       = st.res_evals;
      m[M_JAC]       = st.jac_evals;
      m[M_NEWTON]    = st.newton_its;
      m[M_LIN]       = st.lin_its;
      m[M_LINSOLVES] = st.lin_solves;
      m[M_ETF]       = st.err_test_fails;
      m[M_CONVF]     = st.conv_fails;
      m[M_RESTARTS]  = st.restarts;
      m[M_HMIN]      = st.h_min;
      m[M_HMAX]      = st.h_max;
      m[M_ATOL]      = ti->atol;
      m[M_NARREST]   = ti->narrest;
      m[M_RANKS]     = size;
      m[M_SIZE]      = N;
      m[M_DUALSAVED] = saved;
      m[M_DUALSIZE]  = nd; /* rank 0's: a check of the layout */
      for (PetscInt k = 0; k < ti->narrest; ++k) {
        m[M_ARREST + 3 * k]     = ti->arrest[k].t_arrest;
        m[M_ARREST + 3 * k + 1] = ti->arrest[k].threshold;
        m[M_ARREST + 3 * k + 2] = gprev ? gprev[k] : 0.0;
      }
      if (ti->ckget) {
        PetscInt  ne = 0;
        PetscReal e[SLUMP_CHECKPOINT_MAX_EXTRA];
        PetscCall(ti->ckget(ti->ckctx, &ne, e));
        m[M_NEXTRA] = ne;
        for (PetscInt i = 0; i < ne; ++i) m[M_EXTRA + i] = e[i];
      }
      PetscCall(VecRestoreArray(M, &m));
    } else if (ti->ckget) {
      PetscInt  ne = 0;
      PetscReal e[SLUMP_CHECKPOINT_MAX_EXTRA];
      PetscCall(ti->ckget(ti->ckctx, &ne, e)); /* collective hooks */
    }
  }
  {
    PetscErrorCode ierr, ierr2 = 0;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    v    = NULL;
    ierr = PetscViewerHDF5Open(comm, part, FILE_MODE_WRITE, &v);
    if (!ierr) ierr = VecView(P, v);
    if (!ierr) ierr = VecView(Q, v);
    if (!ierr) ierr = VecView(D, v);
    if (!ierr) ierr = VecView(M, v);
    if (v) ierr2 = PetscViewerDestroy(&v);
    PetscCall(PetscPopErrorHandler());
    if (ierr2) SlumpSetUnclosableOutput();
    ierr = ierr ? ierr : ierr2;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ierr, 1, MPI_INT, MPI_MAX, comm));
    PetscCheck(!ierr, comm, PETSC_ERR_FILE_WRITE, "Cannot write the checkpoint %s (HDF5); free space or choose another -output_dir", part);
  }
  PetscCall(SlumpFileCommit(comm, 0, part, path));
  PetscCall(VecDestroy(&P));
  PetscCall(VecDestroy(&Q));
  PetscCall(VecDestroy(&D));
  PetscCall(VecDestroy(&M));
  ti->ck_last_t    = ti->t;
  ti->ck_last_step = ti->stats.steps;
  ti->ck_count++;
  PetscCall(PetscInfo(NULL, "checkpoint at t = %g (step %d) in %s\n", (double)ti->t, (int)ti->stats.steps, path));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorCheckpointMaybe(SlumpIntegrator ti, Vec X, Vec H, PetscBool have_prev, PetscInt kout, const PetscReal gprev[])
{
  PetscBool due = PETSC_FALSE;
  PetscFunctionBeginUser;
  if (!ti->ckdir[0]) PetscFunctionReturn(0);
  if (ti->ck_every > 0 && ti->stats.steps - ti->ck_last_step >= ti->ck_every) due = PETSC_TRUE;
  if (ti->ck_interval > 0 && ti->t - ti->ck_last_t >= ti->ck_interval * (1 - 1e-12)) due = PETSC_TRUE;
  /* an interrupted run leaves a checkpoint where it stopped */
  if ((ti->ck_every > 0 || ti->ck_interval > 0) && ti->stop_requested) due = PETSC_TRUE;
  if (due) PetscCall(SlumpIntegratorCheckpointWrite(ti, X, H, have_prev, kout, gprev));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorLoadCheckpoint(SlumpIntegrator ti, const char file[], Vec X)
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)X);
  PetscMPIInt rank, size;
  PetscViewer v;
  Vec         P, D, M;
  PetscReal   m[M_LEN];
  PetscInt    N, nd;
  PetscBool   saved, sv;
  int         ok = 0;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (!rank) ok = access(file, R_OK) == 0;
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot read the checkpoint '%s' (-restart); give a checkpoint.h5 written with -checkpoint_every or -checkpoint_interval", file);
  PetscCall(PlainVec(X, "state", &P));
  PetscCall(PlainVec(X, "history", &ti->ck_history));
  PetscCall(MetaVec(comm, &M));
  {
    PetscErrorCode ierr;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    v    = NULL;
    ierr = PetscViewerHDF5Open(comm, file, FILE_MODE_READ, &v);
    if (!ierr) ierr = VecLoad(M, v);
    PetscCall(PetscPopErrorHandler());
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ierr, 1, MPI_INT, MPI_MAX, comm));
    if (ierr && v) PetscCall(PetscViewerDestroy(&v));
    PetscCheck(!ierr, comm, PETSC_ERR_FILE_UNEXPECTED, "The file '%s' (-restart) is not a slump checkpoint", file);
  }
  if (!rank) {
    const PetscScalar *a;
    PetscCall(VecGetArrayRead(M, &a));
    for (PetscInt i = 0; i < M_LEN; ++i) m[i] = PetscRealPart(a[i]);
    PetscCall(VecRestoreArrayRead(M, &a));
  }
  PetscCallMPI(MPI_Bcast(m, M_LEN, MPIU_REAL, 0, comm));
  PetscCall(VecGetSize(X, &N));
  PetscCheck(m[M_VERSION] == META_VERSION, comm, PETSC_ERR_FILE_UNEXPECTED, "The checkpoint '%s' (-restart) has version %g; this slump reads version %d", file, (double)m[M_VERSION], META_VERSION);
  PetscCheck((PetscInt)m[M_RANKS] == size, comm, PETSC_ERR_USER_INPUT, "The checkpoint '%s' (-restart) was written on %d rank(s); restart it on as many (mpiexec -n %d)", file, (int)m[M_RANKS], (int)m[M_RANKS]);
  PetscCheck((PetscInt)m[M_SIZE] == N, comm, PETSC_ERR_USER_INPUT, "The checkpoint '%s' (-restart) holds %d unknowns, this run has %d; restart with the scene, mesh and discretisation options of the run that wrote it", file, (int)m[M_SIZE], (int)N);
  PetscCheck((SlumpIntegratorType)(PetscInt)m[M_TYPE] == ti->type, comm, PETSC_ERR_USER_INPUT, "The checkpoint '%s' (-restart) was written by -time_integrator %s; restart with the same integrator", file, SlumpIntegratorTypes[(PetscInt)m[M_TYPE]]);
  PetscCheck((PetscInt)m[M_NARREST] == ti->narrest, comm, PETSC_ERR_USER_INPUT, "The checkpoint '%s' (-restart) has %d arrest criteria, this run %d; restart with the same -arrest options", file, (int)m[M_NARREST], (int)ti->narrest);
  PetscCall(VecLoad(P, v));
  PetscCall(VecLoad(ti->ck_history, v));
  PetscCall(VecCopy(P, X));
  /* the dual: only with the stress-velocity Newton, on the same layout */
  PetscCall(SlumpLinearisationSetUp(ti->prob, comm, &sv));
  PetscCall(DualVec(ti->prob, comm, &saved, &D));
  PetscCall(VecGetLocalSize(D, &nd));
  if (sv && m[M_DUALSAVED] != 0) {
    PetscInt Nfile = 0;
    {
      Vec F;
      PetscCall(VecCreateMPI(comm, nd, PETSC_DETERMINE, &F));
      PetscCall(PetscObjectSetName((PetscObject)F, "dual"));
      PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
      if (VecLoad(F, v)) Nfile = -1;
      PetscCall(PetscPopErrorHandler());
      if (Nfile == 0) {
        /* applied by the solve once it has set up its linearisation */
        const PetscScalar *a;
        PetscCall(VecGetArrayRead(F, &a));
        PetscCall(PetscFree(ti->ck_dual));
        PetscCall(PetscMalloc1(PetscMax(nd, 1), &ti->ck_dual));
        PetscCall(PetscArraycpy(ti->ck_dual, a, nd));
        ti->ck_ndual = nd;
        PetscCall(VecRestoreArrayRead(F, &a));
      }
      PetscCall(VecDestroy(&F));
    }
    PetscCheck(Nfile == 0, comm, PETSC_ERR_USER_INPUT, "The checkpoint '%s' (-restart) holds the plastic stress of another quadrature layout; restart with the -newton_linearisation, -quadrature_order and rank count of the run that wrote it", file);
  }
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(VecDestroy(&P));
  PetscCall(VecDestroy(&D));
  PetscCall(VecDestroy(&M));

  ti->restarted            = PETSC_TRUE;
  ti->t                    = m[M_T];
  ti->h_last               = m[M_H];
  ti->order_last           = (PetscInt)m[M_ORDER];
  ti->ck_have_prev         = m[M_HAVE_PREV] != 0 ? PETSC_TRUE : PETSC_FALSE;
  ti->ck_kout              = (PetscInt)m[M_KOUT];
  ti->stats.steps          = (PetscInt)m[M_STEPS];
  ti->stats.newton_its     = (PetscInt)m[M_NEWTON];
  ti->stats.lin_its        = (PetscInt)m[M_LIN];
  ti->stats.lin_solves     = (PetscInt)m[M_LINSOLVES];
  ti->stats.err_test_fails = (PetscInt)m[M_ETF];
  ti->stats.conv_fails     = (PetscInt)m[M_CONVF];
  ti->stats.restarts       = (PetscInt)m[M_RESTARTS];
  ti->stats.h_min          = m[M_HMIN];
  ti->stats.h_max          = m[M_HMAX];
  ti->atol                 = m[M_ATOL];
  ti->atol_auto            = PETSC_FALSE;
  /* the problem's evaluation counters start again in this process */
  {
    PetscInt r, j;
    PetscCall(SlumpProblemGetCounters(ti->prob, &r, &j));
    ti->res_offset = (PetscInt)m[M_RES] - r;
    ti->jac_offset = (PetscInt)m[M_JAC] - j;
  }
  ti->ck_last_t    = ti->t;
  ti->ck_last_step = ti->stats.steps;
  for (PetscInt k = 0; k < ti->narrest; ++k) {
    ti->arrest[k].t_arrest  = m[M_ARREST + 3 * k];
    ti->arrest[k].threshold = m[M_ARREST + 3 * k + 1];
    ti->ck_gprev[k]         = m[M_ARREST + 3 * k + 2];
  }
  if (ti->ckset) {
    PetscReal e[SLUMP_CHECKPOINT_MAX_EXTRA];
    PetscInt  ne = (PetscInt)m[M_NEXTRA];
    for (PetscInt i = 0; i < ne; ++i) e[i] = m[M_EXTRA + i];
    PetscCall(ti->ckset(ti->ckctx, ne, e));
  }
  PetscCall(PetscInfo(NULL, "restart from %s at t = %g, step %d\n", file, (double)ti->t, (int)ti->stats.steps));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorRestoreDual(SlumpIntegrator ti)
{
  PetscFunctionBeginUser;
  if (ti->ck_dual) {
    PetscCall(SlumpProblemDualSetState(ti->prob, ti->ck_ndual, PETSC_TRUE, ti->ck_dual));
    PetscCall(PetscFree(ti->ck_dual));
    ti->ck_ndual = 0;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetRestart(SlumpIntegrator ti, PetscBool *restart, PetscReal *t)
{
  PetscFunctionBeginUser;
  if (restart) *restart = ti->restarted;
  if (t) *t = ti->t;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorGetRestartFile(SlumpIntegrator ti, const char **file)
{
  PetscFunctionBeginUser;
  *file = ti->restart_file[0] ? ti->restart_file : NULL;
  PetscFunctionReturn(0);
}
