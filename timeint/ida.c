/* Adaptive BDF (IDA, order <= 2) on the semi-discrete DAE.
 * Velocity differential, pressure algebraic and out of the error test
 * (IDASetSuppressAlg). With Taylor-Hood and inertia the DAE has index 2 in
 * the pressure, so IDACalcIC cannot help: consistent (u'0, p0) come from one
 * saddle-point solve (SlumpConsistentInitialConditions). A quasi-static
 * flow (a level set, no inertia) has velocity and pressure algebraic and
 * index 1: IDACalcIC finds them (QuasiStaticIC). Arrest is an IDA root
 * function on the mean shear rate. */
#include "timeintimpl.h"
#include "slumprheology.h"
#include <ida/ida.h>

typedef struct {
  SlumpIntegrator ti;
  SlumpProblem    prob;
  Mat             J;
} IDAUser;

static int IdaRes(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *user)
{
  IDAUser *u  = (IDAUser *)user;
  int      st = SlumpSundialsStatus(SlumpProblemResidual(u->prob, t, N_VGetVector_Petsc(yy), N_VGetVector_Petsc(yp), N_VGetVector_Petsc(rr)));
  if (st) return st;
  return SlumpCheckFinite(N_VGetVector_Petsc(rr));
}

static int IdaJac(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr, SUNMatrix A, void *user, N_Vector t1, N_Vector t2, N_Vector t3)
{
  IDAUser *u = (IDAUser *)user;
  return SlumpSundialsStatus(SlumpProblemJacobian(u->prob, t, N_VGetVector_Petsc(yy), N_VGetVector_Petsc(yp), cj, u->J));
}

static PetscErrorCode ExactAssemble(void *ctx, PetscReal t, Vec y, Vec yp, PetscReal cj)
{
  IDAUser *u = (IDAUser *)ctx;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemJacobian(u->prob, t, y, yp, cj, u->J));
  PetscFunctionReturn(0);
}

static int IdaRoot(realtype t, N_Vector yy, N_Vector yp, realtype *gout, void *user)
{
  IDAUser *u = (IDAUser *)user;
  return SlumpSundialsStatus(SlumpIntegratorArrestFunctions(u->ti, t, N_VGetVector_Petsc(yy), gout));
}

/* A solve of the consistent initialisation. With -linear_solver iterative
   a Krylov solve that fails is repeated by LU (MUMPS), which then serves
   the remaining solve too; one line says so. */
static PetscErrorCode InitSolve(KSP ksp, Vec F, Vec W)
{
  KSPConvergedReason reason;
  PetscBool          direct;
  MPI_Comm           comm      = PetscObjectComm((PetscObject)ksp);
  char               what[320] = "";
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &direct));
  if (direct) PetscCall(SlumpKSPSolveDirect(ksp, F, W, &reason, what, sizeof(what)));
  else {
    PetscCall(KSPSolve(ksp, F, W));
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    if (reason < 0) {
      PetscInt its;
      PetscCall(KSPGetIterationNumber(ksp, &its));
      PetscCall(PetscPrintf(comm, "consistent initialisation: the Krylov solve stopped (%s after %" PetscInt_FMT " iterations); solved by LU (MUMPS) instead\n", KSPConvergedReasons[reason], its));
      PetscCall(SlumpKSPSetDirect(ksp));
      PetscCall(SlumpKSPSolveDirect(ksp, F, W, &reason, what, sizeof(what)));
    }
  }
  PetscCheck(reason > 0, comm, PETSC_ERR_NOT_CONVERGED, "The consistent-initialisation solve failed because %s", what);
  PetscFunctionReturn(0);
}

/* Consistent initial data for the index-2 DAE, with one saddle-point
 * operator [rho M, B^T; B, 0] (SlumpProblemInitJacobian), factored once:
 * 1. if the velocity violates the discrete continuity equation with the
 *    boundary data at t (an impulsive change of wall velocity, e.g. a lid
 *    stopped at t = 0), project it: rho M du + B^T phi = 0, B du = -F_p(u);
 *    this is the impulsive response of an incompressible fluid (applied
 *    when |du| > 1e-12 |u|, so that round-off leaves runs reproducible);
 * 2. rho M u' + B^T p = -F_u(u), B u' = 0 gives u'0 and p0. */
PetscErrorCode SlumpConsistentInitialConditions(SlumpProblem prob, PetscReal t, Vec X, Vec Xdot)
{
  Vec                F, W, sub, subw;
  Mat                J;
  KSP                ksp;
  IS                 isu, isp;
  MPI_Comm           comm = PetscObjectComm((PetscObject)X);
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetFieldIS(prob, &isu, &isp));
  if (isp) {
    PetscCall(VecGetSubVector(X, isp, &sub));
    PetscCall(VecZeroEntries(sub));
    PetscCall(VecRestoreSubVector(X, isp, &sub));
  }
  PetscCall(VecDuplicate(X, &F));
  PetscCall(VecDuplicate(X, &W));
  PetscCall(SlumpProblemCreateMatrix(prob, &J));
  PetscCall(SlumpProblemInitJacobian(prob, t, X, J));
  PetscCall(KSPCreate(comm, &ksp));
  PetscCall(KSPSetOptionsPrefix(ksp, "ic_"));
  PetscCall(SlumpProblemConfigureInitKSP(prob, ksp));
  PetscCall(KSPSetOperators(ksp, J, J));
  if (isp) {
    PetscReal nf, nu, ndu;
    PetscCall(SlumpProblemResidual(prob, t, X, NULL, F));
    PetscCall(VecGetSubVector(F, isu, &sub));
    PetscCall(VecZeroEntries(sub));
    PetscCall(VecRestoreSubVector(F, isu, &sub));
    PetscCall(VecNorm(F, NORM_INFINITY, &nf));
    if (nf > 0) {
      PetscCall(VecScale(F, -1.0));
      PetscCall(InitSolve(ksp, F, W));
      /* only the velocity moves: the pressure part is the impulse, and an
         extra field's part (a level set's phi_t) is not a correction */
      PetscCall(VecGetSubVector(W, isu, &subw));
      PetscCall(VecGetSubVector(X, isu, &sub));
      PetscCall(VecNorm(subw, NORM_2, &ndu));
      PetscCall(VecNorm(sub, NORM_2, &nu));
      /* a correction at round-off level is noise (and differs between
         partitions): keep the velocity as it is then */
      if (ndu > 1e-12 * nu) PetscCall(VecAXPY(sub, 1.0, subw));
      PetscCall(VecRestoreSubVector(X, isu, &sub));
      PetscCall(VecRestoreSubVector(W, isu, &subw));
      PetscCall(PetscInfo(NULL, "divergence-free projection of the initial velocity: |du|/|u| = %g (%s)\n", (double)(nu > 0 ? ndu / nu : ndu), ndu > 1e-12 * nu ? "applied" : "round-off, not applied"));
    }
  }
  PetscCall(SlumpProblemResidual(prob, t, X, NULL, F));
  if (isp) {
    PetscCall(VecGetSubVector(F, isp, &sub));
    PetscCall(VecZeroEntries(sub));
    PetscCall(VecRestoreSubVector(F, isp, &sub));
  }
  PetscCall(VecScale(F, -1.0));
  PetscCall(InitSolve(ksp, F, W));
  /* X_p = w_p, Xdot = (w_u, 0) */
  if (isp) {
    PetscCall(VecGetSubVector(X, isp, &sub));
    PetscCall(VecGetSubVector(W, isp, &subw));
    PetscCall(VecCopy(subw, sub));
    PetscCall(VecZeroEntries(subw));
    PetscCall(VecRestoreSubVector(W, isp, &subw));
    PetscCall(VecRestoreSubVector(X, isp, &sub));
  }
  PetscCall(VecCopy(W, Xdot));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&F));
  PetscCall(VecDestroy(&W));
  PetscCall(ISDestroy(&isu));
  PetscCall(ISDestroy(&isp));
  PetscFunctionReturn(0);
}

#define IDACHECK(call) PetscCheck((call) >= 0, comm, PETSC_ERR_LIB, "%s failed", #call)

/* IDACalcIC at the regularisation parameter v (if the rheology has one). */
static PetscErrorCode CalcICAt(void *mem, SlumpProblem prob, const char *regname, PetscReal v, realtype tout, int *flag)
{
  PetscFunctionBeginUser;
  *flag = IDA_ILL_INPUT;
  if (regname) PetscCall(SlumpProblemSetRheologyParameter(prob, regname, v));
  *flag = IDACalcIC(mem, IDA_YA_YDP_INIT, tout);
  PetscFunctionReturn(0);
}

/* IDACalcIC at the target regularisation, by continuation if it fails: a
   stiff Papanastasiou-Stokes solve from rest (bingham_dam_break -re 0 at
   m = 1e5: IDA_LINESEARCH_FAIL, also from the m = 1e4 solution) is found
   from a softer value (10, 100, ... up to 1e4 times softer), then towards
   the target by factors that halve (in log) after a failure and grow after
   a success. A failed IDACalcIC may have overwritten IDA's internal copy of
   the state, so every try restarts IDA from yy, yp, which hold the last
   consistent state (the caller's state until a softer solve succeeds).
   *reached: the stiffest value solved. */
static PetscErrorCode CalcICContinued(MPI_Comm comm, void *mem, SlumpProblem prob, const char *regname, PetscBool stiffer, PetscReal target, realtype t, realtype tout, N_Vector yy, N_Vector yp, PetscInt *ntries, PetscReal *reached, int *flag)
{
  PetscReal v = target, f = 10.0;
  PetscFunctionBeginUser;
  *ntries  = 1;
  *reached = 0.0;
  PetscCall(CalcICAt(mem, prob, regname, target, tout, flag));
  if (*flag >= 0) *reached = target;
  if (*flag >= 0 || !regname) PetscFunctionReturn(0);
  for (PetscInt k = 1; k <= 4 && *flag < 0; ++k) {
    v = stiffer ? target / PetscPowReal(10.0, k) : target * PetscPowReal(10.0, k);
    IDACHECK(IDAReInit(mem, t, yy, yp));
    PetscCall(CalcICAt(mem, prob, regname, v, tout, flag));
    ++*ntries;
  }
  if (*flag < 0) PetscFunctionReturn(0);
  *reached = v;
  IDACHECK(IDAGetConsistentIC(mem, yy, yp));
  while (v != target) {
    const PetscReal vt = stiffer ? PetscMin(v * f, target) : PetscMax(v / f, target);
    IDACHECK(IDAReInit(mem, t, yy, yp));
    PetscCall(CalcICAt(mem, prob, regname, vt, tout, flag));
    ++*ntries;
    if (*flag >= 0) {
      v = *reached = vt;
      f = f * f;
      IDACHECK(IDAGetConsistentIC(mem, yy, yp));
    } else {
      f = PetscSqrtReal(f);
      if (f < 1.05) PetscFunctionReturn(0);
    }
  }
  PetscFunctionReturn(0);
}

/* Consistent (u, p) and phi' at the current time of a quasi-static DAE:
   IDACalcIC's Newton on the algebraic unknowns, the level set held (a
   nonlinear Stokes solve), with continuation in the regularisation
   parameter if it fails (up to 1e4 times softer). Its first step only sets
   IDACalcIC's time scale (cj): the last step, else 1e-3 of the run. */
static PetscErrorCode QuasiStaticIC(void *mem, SlumpIntegrator ti, N_Vector yy, N_Vector yp, SUNLinearSolver LS, void *user, MPI_Comm comm)
{
  realtype       t;
  int            flag;
  PetscReal      h = ti->h_last > 0 ? ti->h_last : 1e-3 * (ti->tfinal - ti->t0), target = 0.0, reached = 0.0;
  SlumpRheology  rheo;
  const char    *regname = NULL;
  PetscBool      stiffer = PETSC_TRUE;
  PetscInt       ntries  = 0;
  PetscErrorCode ierr;
  PetscFunctionBeginUser;
  IDACHECK(IDAGetCurrentTime(mem, &t));
  PetscCall(SlumpProblemGetRheology(ti->prob, &rheo));
  if (rheo) PetscCall(SlumpRheologyGetRegularisation(rheo, &regname, &target, &stiffer));
  /* IDACalcIC's Newton has its own iteration data: no reassembly per
     iterate from the step's (-ida_exact_newton) */
  if (ti->exact_newton) PetscCall(SlumpSUNLinSolSetExactNewton(LS, mem, NULL, NULL));
  IDACHECK(IDASetMaxNumItersIC(mem, 20));
  IDACHECK(IDASetMaxNumJacsIC(mem, 20));
  /* on every path, error or not, the model's parameter and the step's
     Jacobian callback are put back before returning */
  ierr = CalcICContinued(comm, mem, ti->prob, regname, stiffer, target, t, t + h, yy, yp, &ntries, &reached, &flag);
  if (ti->exact_newton) PetscCall(SlumpSUNLinSolSetExactNewton(LS, mem, ExactAssemble, user));
  if (regname) PetscCall(SlumpProblemSetRheologyParameter(ti->prob, regname, target));
  PetscCall(ierr);
  if (flag < 0 && regname && reached > 0)
    SETERRQ(comm, PETSC_ERR_NOT_CONVERGED, "The quasi-static initial solve (IDACalcIC) failed at t = %g: %s at %s = %g; continuation from softer values reached %s = %g", (double)t, IDAGetReturnFlagName(flag), regname, (double)target, regname, (double)reached);
  PetscCheck(flag >= 0, comm, PETSC_ERR_NOT_CONVERGED, "The quasi-static initial solve (IDACalcIC) failed at t = %g: %s%s", (double)t, IDAGetReturnFlagName(flag), regname ? ", also at a regularisation 1e4 times softer" : "");
  if (ntries > 1) PetscCall(PetscPrintf(comm, "quasi-static initial solve at t = %g: %s = %g reached by continuation (%" PetscInt_FMT " IDACalcIC solves)\n", (double)t, regname, (double)target, ntries));
  IDACHECK(IDAGetConsistentIC(mem, yy, yp));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpIntegratorSolve_IDA(SlumpIntegrator ti, Vec X)
{
  MPI_Comm        comm;
  SUNContext      ctx;
  Vec             Xdot, Y, idv, atolv;
  N_Vector        yy, yp, yout, nid, natol;
  PetscBool       sv;
  SUNMatrix       A;
  SUNLinearSolver LS;
  SUNNonlinearSolver NLS = NULL;
  IDAUser         user;
  void           *mem;
  realtype        tret;
  PetscReal       next_out;
  PetscInt        kout = 1;
  long int        nni_prev = 0, netf_prev = 0, ncfn_prev = 0;
  PetscBool       quasistatic;
  PetscInt        nli_prev = 0, nni_tot = 0, netf_tot = 0, ncfn_tot = 0, lin_base = 0, lin_solves_base = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)X, &comm));
  PetscCheck(!SUNContext_Create((void *)&comm, &ctx), comm, PETSC_ERR_LIB, "SUNContext_Create failed");
  PetscCall(VecDuplicate(X, &Xdot));
  PetscCall(VecDuplicate(X, &Y));
  PetscCall(VecDuplicate(X, &idv));
  PetscCall(VecDuplicate(X, &atolv));
  {
    /* quasi-static (a level set, no inertia): velocity and pressure are
       algebraic and the DAE has index 1, so IDACalcIC finds them (a
       nonlinear Stokes solve for the level set given) and phi' below */
    PetscInt effects;
    IS       isu, isp;
    PetscCall(SlumpProblemGetEffects(ti->prob, &effects));
    PetscCall(SlumpProblemGetFieldIS(ti->prob, &isu, &isp));
    quasistatic = (!(effects & SLUMP_EFFECT_INERTIA) && (effects & SLUMP_EFFECT_FREE_SURFACE) && isp) ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(ISDestroy(&isu));
    PetscCall(ISDestroy(&isp));
  }
  if (ti->restarted) PetscCall(VecCopy(ti->ck_history, Xdot)); /* y' at the checkpoint */
  else if (quasistatic) PetscCall(VecZeroEntries(Xdot));
  else PetscCall(SlumpConsistentInitialConditions(ti->prob, ti->t0, X, Xdot));
  PetscCall(SlumpProblemGetDifferentialMarker(ti->prob, idv));
  yy   = N_VMake_Petsc(X, ctx);
  yp   = N_VMake_Petsc(Xdot, ctx);
  yout = N_VMake_Petsc(Y, ctx);
  nid  = N_VMake_Petsc(idv, ctx);
  natol = N_VMake_Petsc(atolv, ctx);
  user.ti   = ti;
  user.prob = ti->prob;
  PetscCall(SlumpProblemCreateMatrix(ti->prob, &user.J));
  A  = SlumpSUNMatCreate(user.J, ctx);
  LS = SlumpSUNLinSolCreate(ti->prob, user.J, ctx);
  PetscCheck(A && LS, comm, PETSC_ERR_LIB, "Cannot create the KSP-backed linear solver");
  mem = IDACreate(ctx);
  PetscCheck(mem, comm, PETSC_ERR_LIB, "IDACreate failed");
  IDACHECK(IDASetErrHandlerFn(mem, SlumpSilentErrHandler, NULL));
  IDACHECK(IDAInit(mem, IdaRes, ti->restarted ? ti->t : ti->t0, yy, yp));
  if (ti->atol_auto) {
    /* the absolute tolerance on the velocity's scale: 1e-3 rtol max|u(0)|.
       A fixed 1e-8 made IDA resolve the relative error of velocities a
       million times below the flow's (couette_cessation at rtol 1e-2: 1918
       steps with it, 214 with this, arrest time within 0.9 %); a flow
       starting from rest keeps 1e-8 */
    IS        isu, isp;
    Vec       sub;
    PetscReal umax = 0.0;
    PetscCall(SlumpProblemGetFieldIS(ti->prob, &isu, &isp));
    PetscCall(VecGetSubVector(X, isu, &sub));
    PetscCall(VecNorm(sub, NORM_INFINITY, &umax));
    PetscCall(VecRestoreSubVector(X, isu, &sub));
    PetscCall(ISDestroy(&isu));
    PetscCall(ISDestroy(&isp));
    ti->atol = umax > 0 ? 1e-3 * ti->rtol * umax : 1e-8;
    PetscCall(PetscInfo(NULL, "absolute tolerance %g (max|u(0)| = %g)\n", (double)ti->atol, (double)umax));
  }
  PetscCall(SlumpLinearisationSetUp(ti->prob, comm, &sv));
  PetscCall(SlumpIntegratorRestoreDual(ti));
  if (!quasistatic && sv) {
    /* the pressure (algebraic, out of the error test) is also left out of
       the Newton convergence norm: its absolute tolerance is so large that
       its weight vanishes (the velocity and the level set keep -time_atol).
       Only with the stress-velocity Newton: IDA's primal modified Newton
       fails far more often with it (couette_cessation rtol 1e-3, atol 1e-5:
       6198 convergence failures and 14173 steps against 1132 and 2289) */
    IS isu, isp;
    PetscCall(SlumpProblemGetFieldIS(ti->prob, &isu, &isp));
    PetscCall(VecSet(atolv, ti->atol));
    if (isp) {
      Vec sub;
      PetscCall(VecGetSubVector(atolv, isp, &sub));
      PetscCall(VecSet(sub, 1e100));
      PetscCall(VecRestoreSubVector(atolv, isp, &sub));
    }
    PetscCall(ISDestroy(&isu));
    PetscCall(ISDestroy(&isp));
    IDACHECK(IDASVtolerances(mem, ti->rtol, natol));
  } else IDACHECK(IDASStolerances(mem, ti->rtol, ti->atol));
  IDACHECK(IDASetUserData(mem, &user));
  IDACHECK(IDASetLinearSolver(mem, LS, A));
  IDACHECK(IDASetJacFn(mem, IdaJac));
  IDACHECK(IDASetMaxOrd(mem, 2));
  IDACHECK(IDASetMaxNonlinIters(mem, (int)ti->max_nonlin_iters));
  IDACHECK(IDASetNonlinConvCoef(mem, ti->nonlin_conv_coef));
  if (ti->linesearch) {
    PetscCall(SlumpSUNNonlinSolLineSearchCreate(ti->prob, X, ctx, &NLS));
    IDACHECK(IDASetNonlinearSolver(mem, NLS));
  } else if (sv) {
    PetscCall(SlumpSUNNonlinSolStressVelocityCreate(ti->prob, X, ti->max_nonlin_iters, ti->sv_reuse, ctx, &NLS));
    IDACHECK(IDASetNonlinearSolver(mem, NLS));
  }
  if (ti->exact_newton && !(sv && !ti->linesearch)) {
    PetscCall(SlumpSUNLinSolSetExactNewton(LS, mem, ExactAssemble, &user));
    IDACHECK(IDASetLinearSolutionScaling(mem, SUNFALSE));
  }
  IDACHECK(IDASetId(mem, nid));
  IDACHECK(IDASetSuppressAlg(mem, SUNTRUE));
  IDACHECK(IDASetStopTime(mem, ti->tfinal));
  IDACHECK(IDASetMaxNumSteps(mem, ti->max_steps));
  if (quasistatic && !ti->restarted) PetscCall(QuasiStaticIC(mem, ti, yy, yp, LS, &user, comm));
  /* a restart: BDF order 1 from (y, y') with the last step size (IDA's
     history is not public; checkpoint.c) */
  if (ti->restarted) IDACHECK(IDASetInitStep(mem, ti->h_last));
  else if (ti->dt > 0) IDACHECK(IDASetInitStep(mem, ti->dt));
  else {
    /* IDA's own first step, min(1e-3 (tf - t0), 0.5/|u'|_WRMS), floored at
       1e-7 (tf - t0): at tight tolerances (rtol 1e-8, atol 1e-9 on Couette)
       it fell to ~1e-11, where the first Newton solve failed (IDA_CONV_FAIL
       at t = 0); a floor of 1e-8 (tf - t0) and above worked (docs/sweeps.md). */
    Vec       w;
    PetscReal nrm, h0;
    PetscInt  n;
    PetscCall(VecDuplicate(X, &w));
    PetscCall(VecCopy(X, w));
    PetscCall(VecAbs(w));
    PetscCall(VecScale(w, ti->rtol));
    PetscCall(VecShift(w, ti->atol));
    PetscCall(VecReciprocal(w));
    PetscCall(VecPointwiseMult(w, w, Xdot));
    PetscCall(VecPointwiseMult(w, w, idv));
    PetscCall(VecNorm(w, NORM_2, &nrm));
    PetscCall(VecGetSize(w, &n));
    PetscCall(VecDestroy(&w));
    nrm /= PetscSqrtReal((PetscReal)n);
    h0 = 1e-3 * (ti->tfinal - ti->t0);
    if (nrm > 0) h0 = PetscMin(h0, 0.5 / nrm);
    h0 = PetscMax(h0, 1e-7 * (ti->tfinal - ti->t0));
    IDACHECK(IDASetInitStep(mem, h0));
  }
  if (!ti->restarted) PetscCall(SlumpIntegratorResolveArrest(ti, ti->t0, X));
  if (ti->narrest) {
    int dir[16];
    for (PetscInt k = 0; k < ti->narrest; ++k) dir[k] = -1;
    IDACHECK(IDARootInit(mem, (int)ti->narrest, IdaRoot));
    IDACHECK(IDASetRootDirection(mem, dir));
  }
  if (ti->restarted) {
    kout     = ti->ck_kout;
    nni_tot  = ti->stats.newton_its;
    netf_tot = ti->stats.err_test_fails;
    ncfn_tot = ti->stats.conv_fails;
    lin_base = ti->stats.lin_its;
    lin_solves_base = ti->stats.lin_solves;
  } else if (ti->outmon) PetscCall(ti->outmon(ti, ti->t0, X, ti->outctx));
  next_out = ti->t0 + kout * ti->dtout;
  for (;;) {
    SlumpLinearFailures lf0, lf;
    int                 flag;
    PetscCall(SlumpProblemGetLinearFailures(ti->prob, &lf0));
    flag = IDASolve(mem, ti->tfinal, &tret, yy, yp, IDA_ONE_STEP);
    if (flag < 0) {
      char *name = IDAGetReturnFlagName(flag);
      ti->t      = tret;
      PetscCall(PetscStrallocpy(name, &name));
      /* the step failed because Krylov solves did: say so */
      PetscCall(SlumpProblemGetLinearFailures(ti->prob, &lf));
      if (lf.n > lf0.n && lf.direct) SETERRQ(comm, PETSC_ERR_NOT_CONVERGED, "IDA failed at t = %g: %s because %s", (double)tret, name, lf.what);
      if (lf.n > lf0.n) SETERRQ(comm, PETSC_ERR_NOT_CONVERGED, "IDA failed at t = %g: %s because %" PetscInt_FMT " Krylov solves of -linear_solver iterative did not converge (the last: %s after %" PetscInt_FMT " iterations); use -linear_solver direct or a stronger preconditioner (see docs/performance.md)", (double)tret, name, lf.n - lf0.n, KSPConvergedReasons[lf.reason], lf.its);
      if (flag == IDA_CONV_FAIL && !sv && !ti->linesearch) SETERRQ(comm, PETSC_ERR_NOT_CONVERGED, "IDA failed at t = %g: %s (the primal Newton; -newton_linearisation stress_velocity converges on stiff yield laws, or try -ida_nonlinear_solver linesearch)", (double)tret, name);
      if (flag == IDA_CONV_FAIL) SETERRQ(comm, PETSC_ERR_NOT_CONVERGED, "IDA failed at t = %g: %s (raise -ida_max_nonlin_iters, e.g. 8, or try -ida_nonlinear_solver linesearch)", (double)tret, name);
      SETERRQ(comm, PETSC_ERR_NOT_CONVERGED, "IDA failed at t = %g: %s (try smaller -time_rtol/-time_dt, a softer regularisation, or -time_max_steps)", (double)tret, name);
    }
    ti->t = tret;
    if (flag == IDA_ROOT_RETURN) {
      int       info[16];
      PetscBool stop = PETSC_FALSE;
      IDACHECK(IDAGetRootInfo(mem, info));
      for (PetscInt k = 0; k < ti->narrest; ++k)
        if (info[k]) {
          PetscCall(PetscInfo(NULL, "arrest (%s) at t = %g\n", SlumpDiagnosticNames[ti->arrest[k].diag], (double)tret));
          if (SlumpIntegratorArrestRecord(ti, k, tret)) stop = PETSC_TRUE;
        }
      if (stop) {
        if (ti->outmon) PetscCall(ti->outmon(ti, tret, X, ti->outctx));
        break;
      }
      continue;
    }
    {
      SlumpStepRecord r;
      long int        nni, netf, ncfn;
      PetscInt        nsolves, nli;
      realtype        h;
      int             q;
      IDAGetLastStep(mem, &h);
      IDAGetLastOrder(mem, &q);
      IDAGetNumNonlinSolvIters(mem, &nni);
      IDAGetNumErrTestFails(mem, &netf);
      IDAGetNumNonlinSolvConvFails(mem, &ncfn);
      PetscCall(SlumpSUNLinSolGetCounts(LS, &nsolves, &nli));
      if (NLS) {
        if (ti->linesearch) PetscCall(SlumpSUNNonlinSolLineSearchGetLinearIterations(NLS, &nli));
        else PetscCall(SlumpSUNNonlinSolStressVelocityGetLinearIterations(NLS, &nli));
        nsolves = nli;
      }
      r.t              = tret;
      r.h              = h;
      r.order          = q;
      r.newton_its     = (PetscInt)(nni - nni_prev);
      r.lin_its        = nli - nli_prev;
      r.err_test_fails = (PetscInt)(netf - netf_prev);
      r.conv_fails     = (PetscInt)(ncfn - ncfn_prev);
      nni_tot += r.newton_its;
      netf_tot += r.err_test_fails;
      ncfn_tot += r.conv_fails;
      r.X              = X;
      nni_prev         = nni;
      netf_prev        = netf;
      ncfn_prev        = ncfn;
      nli_prev         = nli;
      ti->h_last       = h;
      ti->order_last   = q;
      ti->stats.steps++;
      /* IDA's counters restart with IDAReInit: totals are accumulated here */
      ti->stats.newton_its     = nni_tot;
      ti->stats.lin_its        = lin_base + nli;
      ti->stats.lin_solves     = lin_solves_base + nsolves;
      ti->stats.err_test_fails = netf_tot;
      ti->stats.conv_fails     = ncfn_tot;
      ti->stats.h_min          = PetscMin(ti->stats.h_min, h);
      ti->stats.h_max          = PetscMax(ti->stats.h_max, h);
      if (ti->stepmon) PetscCall(ti->stepmon(ti, &r, ti->stepctx));
      /* IDASetMaxNumSteps counts per IDASolve call, i.e. one step here */
      PetscCheck(ti->stats.steps < ti->max_steps || tret >= ti->tfinal * (1 - 1e-14), comm, PETSC_ERR_NOT_CONVERGED, "IDA took -time_max_steps = %" PetscInt_FMT " steps and stopped at t = %g (h = %g) before t_end = %g; try -ida_nonlinear_solver linesearch, looser -time_rtol/-time_atol or a softer regularisation", ti->max_steps, (double)tret, (double)h, (double)ti->tfinal);
    }
    while (next_out <= tret * (1 + 1e-12) + 1e-300 && next_out <= ti->tfinal * (1 + 1e-12)) {
      PetscReal tout = PetscMin(next_out, ti->tfinal);
      if (PetscAbsReal(tout - tret) <= 1e-12 * PetscMax(1.0, PetscAbsReal(tret))) PetscCall(VecCopy(X, Y));
      else IDACHECK(IDAGetDky(mem, tout, 0, yout));
      if (ti->outmon) PetscCall(ti->outmon(ti, tout, Y, ti->outctx));
      next_out = ti->t0 + (++kout) * ti->dtout;
    }
    {
      /* between steps (level-set reinitialisation): if the state changed,
         restart IDA from it at order 1 with the last step size */
      PetscBool changed;
      PetscCall(SlumpProblemPostStep(ti->prob, ti->stats.steps, tret, X, &changed));
      if (changed) {
        PetscCall(SlumpProblemDualReset(ti->prob));
        IDACHECK(IDAReInit(mem, tret, yy, yp));
        /* quasi-static: the velocity follows the new level set at once;
           the line-search stage solve finds it from the old one (IDACalcIC's
           modified Newton failed there: bingham_dam_break -re 0 at t = 7.8) */
        if (quasistatic && !ti->linesearch) PetscCall(QuasiStaticIC(mem, ti, yy, yp, LS, &user, comm));
        IDACHECK(IDASetInitStep(mem, ti->restart_step * ti->h_last));
        ti->stats.restarts++;
        nni_prev = netf_prev = ncfn_prev = 0;
      }
    }
    PetscCall(SlumpIntegratorCheckpointMaybe(ti, X, Xdot, PETSC_FALSE, kout, NULL));
    if (ti->stop_requested) break;
    if (tret >= ti->tfinal * (1 - 1e-14)) break;
  }
  IDAFree(&mem);
  if (NLS) SUNNonlinSolFree(NLS);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(yy);
  N_VDestroy(yp);
  N_VDestroy(yout);
  N_VDestroy(nid);
  N_VDestroy(natol);
  PetscCall(VecDestroy(&atolv));
  PetscCall(MatDestroy(&user.J));
  PetscCall(VecDestroy(&Xdot));
  PetscCall(VecDestroy(&Y));
  PetscCall(VecDestroy(&idv));
  SUNContext_Free(&ctx);
  PetscFunctionReturn(0);
}
