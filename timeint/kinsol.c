/* KINSOL with line search on G(y) = F(t, y, alpha y + beta): steady states
 * (alpha = 0, beta = 0), and the implicit stage of fixed-step BDF. Exact
 * Newton: the Jacobian dF/dy + alpha dF/dy' is assembled at every iterate. */
#include "timeintimpl.h"
#include "slumprheology.h"
#include <kinsol/kinsol.h>

struct _n_SlumpImplicitSolver {
  SlumpProblem    prob;
  MPI_Comm        comm;
  SUNContext      sunctx;
  void           *kmem;
  Vec             u, scale, ydot, work;
  N_Vector        nu, nscale;
  Mat             J;
  SUNMatrix       A;
  SUNLinearSolver LS;
  PetscReal       t, alpha, fnormtol, fnormrtol, maxstep, fref;
  Vec             beta;
  PetscInt        maxit;
  PetscBool       linesearch, linesearch_set;
  SlumpStats      stats;
  PetscReal       hist[128]; /* max|F| at each Newton iterate of the last solve */
  PetscInt        nhist;
  /* Krylov solves of the last solve that did not converge (n), the last
     one's iterations and reason */
  SlumpLinearFailures linfail;
};

static PetscErrorCode FormYdot(SlumpImplicitSolver s, Vec u, Vec *ydot)
{
  PetscFunctionBeginUser;
  *ydot = NULL;
  if (s->alpha == 0.0 && !s->beta) PetscFunctionReturn(0);
  if (s->beta) PetscCall(VecWAXPY(s->ydot, s->alpha, u, s->beta));
  else PetscCall(VecAXPBY(s->ydot, s->alpha, 0.0, u));
  *ydot = s->ydot;
  PetscFunctionReturn(0);
}

static PetscErrorCode KinFunc_Private(SlumpImplicitSolver s, Vec u, Vec f)
{
  Vec ydot;
  PetscFunctionBeginUser;
  PetscCall(FormYdot(s, u, &ydot));
  PetscCall(SlumpProblemResidual(s->prob, s->t, u, ydot, f));
  PetscFunctionReturn(0);
}

static int KinFunc(N_Vector u, N_Vector f, void *user)
{
  SlumpImplicitSolver s  = (SlumpImplicitSolver)user;
  int                 st = SlumpSundialsStatus(KinFunc_Private(s, N_VGetVector_Petsc(u), N_VGetVector_Petsc(f)));
  if (st) return st;
  return SlumpCheckFinite(N_VGetVector_Petsc(f));
}

static PetscErrorCode KinJac_Private(SlumpImplicitSolver s, Vec u, Vec fu)
{
  Vec ydot;
  PetscFunctionBeginUser;
  if (s->nhist < 128) PetscCall(VecNorm(fu, NORM_INFINITY, &s->hist[s->nhist++]));
  PetscCall(FormYdot(s, u, &ydot));
  /* stress-velocity Newton: S follows the step KINSOL took to u */
  PetscCall(SlumpProblemDualLinearise(s->prob, s->t, u));
  PetscCall(SlumpProblemJacobian(s->prob, s->t, u, ydot, s->alpha, s->J));
  PetscFunctionReturn(0);
}

static int KinJac(N_Vector u, N_Vector fu, SUNMatrix J, void *user, N_Vector t1, N_Vector t2)
{
  return SlumpSundialsStatus(KinJac_Private((SlumpImplicitSolver)user, N_VGetVector_Petsc(u), N_VGetVector_Petsc(fu)));
}

PetscErrorCode SlumpImplicitSolverCreate(SlumpProblem prob, Vec X, SlumpImplicitSolver *solver)
{
  SlumpImplicitSolver s;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  s->prob = prob;
  PetscCall(PetscObjectGetComm((PetscObject)X, &s->comm));
  s->fnormtol  = 1e-10;
  s->fnormrtol = 1e-9;
  s->maxit     = 50;
  s->maxstep   = 1e12;
  s->linesearch = PETSC_TRUE;
  PetscOptionsBegin(s->comm, NULL, "Newton (KINSOL)", "SlumpImplicitSolver");
  PetscCall(PetscOptionsReal("-newton_atol", "Absolute tolerance on max |F|", "", s->fnormtol, &s->fnormtol, NULL));
  PetscCall(PetscOptionsReal("-newton_rtol", "Tolerance on max |F| relative to its initial value", "", s->fnormrtol, &s->fnormrtol, NULL));
  PetscCall(PetscOptionsReal("-newton_max_step", "Largest scaled Newton step (KINSOL's default is 1 from a zero guess)", "", s->maxstep, &s->maxstep, NULL));
  PetscCall(PetscOptionsInt("-newton_max_it", "Maximum Newton iterations per solve", "", s->maxit, &s->maxit, NULL));
  PetscCall(PetscOptionsBool("-newton_linesearch", "KINSOL's line search on |F| (default: on, except in fixed-step BDF2 stages with the stress-velocity Newton)", "", s->linesearch, &s->linesearch, &s->linesearch_set));
  PetscOptionsEnd();
  PetscCheck(s->fnormtol > 0 && s->fnormrtol >= 0, s->comm, PETSC_ERR_USER_INPUT, "-newton_atol must be positive and -newton_rtol non-negative");
  PetscCheck(s->maxit > 0, s->comm, PETSC_ERR_USER_INPUT, "-newton_max_it must be a positive integer");
  PetscCheck(!SUNContext_Create((void *)&s->comm, &s->sunctx), s->comm, PETSC_ERR_LIB, "SUNContext_Create failed");
  PetscCall(VecDuplicate(X, &s->u));
  PetscCall(VecDuplicate(X, &s->scale));
  PetscCall(VecDuplicate(X, &s->ydot));
  PetscCall(VecDuplicate(X, &s->work));
  PetscCall(VecSet(s->scale, 1.0));
  s->nu     = N_VMake_Petsc(s->u, s->sunctx);
  s->nscale = N_VMake_Petsc(s->scale, s->sunctx);
  PetscCall(SlumpProblemCreateMatrix(prob, &s->J));
  s->A  = SlumpSUNMatCreate(s->J, s->sunctx);
  s->LS = SlumpSUNLinSolCreate(prob, s->J, s->sunctx);
  PetscCheck(s->A && s->LS, s->comm, PETSC_ERR_LIB, "Cannot create the KSP-backed linear solver");
  {
    PetscBool ew;
    PetscCall(SlumpProblemGetLinearForcing(prob, &ew));
    PetscCall(SlumpSUNLinSolSetForcing(s->LS, ew));
  }
  s->kmem = KINCreate(s->sunctx);
  PetscCheck(s->kmem, s->comm, PETSC_ERR_LIB, "KINCreate failed");
  PetscCheck(!KINInit(s->kmem, KinFunc, s->nu), s->comm, PETSC_ERR_LIB, "KINInit failed");
  PetscCheck(!KINSetUserData(s->kmem, s), s->comm, PETSC_ERR_LIB, "KINSetUserData failed");
  PetscCheck(!KINSetLinearSolver(s->kmem, s->LS, s->A), s->comm, PETSC_ERR_LIB, "KINSetLinearSolver failed");
  PetscCheck(!KINSetJacFn(s->kmem, KinJac), s->comm, PETSC_ERR_LIB, "KINSetJacFn failed");
  PetscCheck(!KINSetMaxSetupCalls(s->kmem, 1), s->comm, PETSC_ERR_LIB, "KINSetMaxSetupCalls failed");
  PetscCheck(!KINSetNumMaxIters(s->kmem, s->maxit), s->comm, PETSC_ERR_LIB, "KINSetNumMaxIters failed");
  PetscCheck(s->maxstep > 0, s->comm, PETSC_ERR_USER_INPUT, "-newton_max_step must be positive");
  PetscCheck(!KINSetMaxNewtonStep(s->kmem, s->maxstep), s->comm, PETSC_ERR_LIB, "KINSetMaxNewtonStep failed");
  PetscCheck(!KINSetScaledStepTol(s->kmem, 1e-15), s->comm, PETSC_ERR_LIB, "KINSetScaledStepTol failed");
  PetscCheck(!KINSetMaxBetaFails(s->kmem, 50), s->comm, PETSC_ERR_LIB, "KINSetMaxBetaFails failed");
  PetscCheck(!KINSetPrintLevel(s->kmem, 0), s->comm, PETSC_ERR_LIB, "KINSetPrintLevel failed");
  PetscCheck(!KINSetErrHandlerFn(s->kmem, SlumpSilentErrHandler, NULL), s->comm, PETSC_ERR_LIB, "KINSetErrHandlerFn failed");
  *solver = s;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpImplicitSolverDestroy(SlumpImplicitSolver *solver)
{
  SlumpImplicitSolver s = *solver;
  PetscFunctionBeginUser;
  if (!s) PetscFunctionReturn(0);
  KINFree(&s->kmem);
  SUNLinSolFree(s->LS);
  SUNMatDestroy(s->A);
  N_VDestroy(s->nu);
  N_VDestroy(s->nscale);
  PetscCall(MatDestroy(&s->J));
  PetscCall(VecDestroy(&s->u));
  PetscCall(VecDestroy(&s->scale));
  PetscCall(VecDestroy(&s->ydot));
  PetscCall(VecDestroy(&s->work));
  SUNContext_Free(&s->sunctx);
  PetscCall(PetscFree(*solver));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpImplicitSolverSetDefaultLineSearch(SlumpImplicitSolver s, PetscBool on)
{
  PetscFunctionBeginUser;
  if (!s->linesearch_set) s->linesearch = on;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpImplicitSolverSetTolerance(SlumpImplicitSolver s, PetscReal fnormtol)
{
  PetscFunctionBeginUser;
  s->fnormtol = fnormtol;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpImplicitSolverSetResidualScale(SlumpImplicitSolver s, PetscReal fref)
{
  PetscFunctionBeginUser;
  s->fref = fref;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpImplicitSolverSolve(SlumpImplicitSolver s, PetscReal t, PetscReal alpha, Vec beta, Vec X, PetscBool *converged, PetscInt *newton_its, PetscInt *lin_its)
{
  long int  nni1 = 0;
  PetscInt  ls0, ls1, li0, li1;
  SlumpLinearFailures lf0;
  PetscReal f0, tol, fnorm;
  int       flag;
  PetscFunctionBeginUser;
  s->t     = t;
  s->alpha = alpha;
  s->beta  = beta;
  PetscCall(VecCopy(X, s->u));
  s->nhist = 0;
  PetscCall(KinFunc_Private(s, s->u, s->work));
  PetscCall(VecNorm(s->work, NORM_INFINITY, &f0));
  tol     = PetscMax(s->fnormtol, s->fnormrtol * PetscMax(f0, s->fref));
  s->fref = 0.0;
  PetscCheck(!KINSetFuncNormTol(s->kmem, tol), s->comm, PETSC_ERR_LIB, "KINSetFuncNormTol failed");
  PetscCall(SlumpSUNLinSolGetCounts(s->LS, &ls0, &li0));
  PetscCall(SlumpProblemGetLinearFailures(s->prob, &lf0));
  PetscCall(SlumpProblemDualBegin(s->prob, t, s->u));
  flag = KINSol(s->kmem, s->nu, s->linesearch ? KIN_LINESEARCH : KIN_NONE, s->nscale, s->nscale);
  KINGetNumNonlinSolvIters(s->kmem, &nni1);
  PetscCall(SlumpSUNLinSolGetCounts(s->LS, &ls1, &li1));
  PetscCall(SlumpProblemGetLinearFailures(s->prob, &s->linfail));
  s->linfail.n -= lf0.n;
  KINGetFuncNorm(s->kmem, &fnorm);
  PetscCall(PetscInfo(NULL, "KINSol flag %d (%s), fnorm %g, tol %g\n", flag, KINGetReturnFlagName(flag), (double)fnorm, (double)tol));
  if (flag == KIN_SUCCESS || flag == KIN_INITIAL_GUESS_OK) *converged = PETSC_TRUE;
  /* a step below the step tolerance, or a line search that finds no decrease,
     with max|F| within 100 tol: the iterate sits at the residual's round-off
     floor (granular_cylinder: a re-solve from its own converged state,
     max|F| 1.4e-10 against the absolute 1e-10, failed its line search) */
  else if (flag == KIN_STEP_LT_STPTOL || flag == KIN_LINESEARCH_NONCONV) *converged = (fnorm <= 100 * tol) ? PETSC_TRUE : PETSC_FALSE;
  else *converged = PETSC_FALSE;
  if (flag == KIN_INITIAL_GUESS_OK) nni1 = 0; /* KINSol counts per call */
  PetscCall(SlumpProblemDualEnd(s->prob, t, s->u, *converged));
  if (*converged) PetscCall(VecCopy(s->u, X));
  if (newton_its) *newton_its = (PetscInt)nni1;
  if (lin_its) *lin_its = li1 - li0;
  s->stats.newton_its += (PetscInt)nni1;
  s->stats.lin_its += li1 - li0;
  s->stats.lin_solves += ls1 - ls0;
  if (!*converged) s->stats.conv_fails++;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpImplicitSolverGetLinearFailures(SlumpImplicitSolver s, SlumpLinearFailures *f)
{
  PetscFunctionBeginUser;
  *f = s->linfail;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpImplicitSolverGetHistory(SlumpImplicitSolver s, PetscInt *n, const PetscReal **hist)
{
  PetscFunctionBeginUser;
  *n    = s->nhist;
  *hist = s->hist;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpImplicitSolverGetStats(SlumpImplicitSolver s, SlumpStats *stats)
{
  PetscFunctionBeginUser;
  *stats = s->stats;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLinearisationSetUp(SlumpProblem prob, MPI_Comm comm, PetscBool *sv)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetStressVelocityOption(prob, sv));
  PetscCall(SlumpProblemSetStressVelocity(prob, *sv));
  PetscFunctionReturn(0);
}

/* -steady_* and -newton_monitor, read and checked (also before anything is
   written, by SlumpSteadyCheckOptions) */
typedef struct {
  PetscReal start, factor;
  PetscInt  nrho;
  PetscBool set, monitor, retry;
} SteadyOptions;

static PetscErrorCode SteadyReadOptions(SlumpProblem prob, MPI_Comm comm, SteadyOptions *o)
{
  SlumpRheology rheo;
  const char   *regname;
  PetscReal     target;
  PetscBool     larger_stiffer;
  PetscInt      effects;
  PetscFunctionBeginUser;
  o->start   = 0.0;
  o->factor  = 10.0;
  o->nrho    = 1;
  o->monitor = PETSC_FALSE;
  o->retry   = PETSC_TRUE;
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologyGetRegularisation(rheo, &regname, &target, &larger_stiffer));
  PetscOptionsBegin(comm, NULL, "Steady solve", "SlumpSteadySolve");
  PetscCall(PetscOptionsReal("-steady_continuation_start", "First value of the regularisation parameter (continuation towards the model's value)", "", o->start, &o->start, &o->set));
  PetscCall(PetscOptionsBool("-newton_monitor", "Print max|F| at every Newton iterate", "", o->monitor, &o->monitor, NULL));
  PetscCall(PetscOptionsReal("-steady_continuation_factor", "Factor between continuation steps (> 1)", "", o->factor, &o->factor, NULL));
  PetscCall(PetscOptionsBool("-steady_continuation_retry", "Retry a failed Newton solve from softer regularisation values (continuation with smaller factors)", "", o->retry, &o->retry, NULL));
  PetscCall(PetscOptionsInt("-steady_inertia_steps", "Continuation in the Reynolds number: solve at the densities rho k/n, k = 1 ... n, at the first regularisation value (1: none)", "", o->nrho, &o->nrho, NULL));
  PetscOptionsEnd();
  PetscCheck(o->factor > 1.0, comm, PETSC_ERR_USER_INPUT, "-steady_continuation_factor must be > 1; got %g", (double)o->factor);
  PetscCheck(!o->set || regname, comm, PETSC_ERR_USER_INPUT, "-steady_continuation_start needs a regularised rheology; this one has no regularisation parameter");
  PetscCheck(!o->set || o->start > 0, comm, PETSC_ERR_USER_INPUT, "-steady_continuation_start must be positive; got %g", (double)o->start);
  PetscCheck(o->nrho >= 1, comm, PETSC_ERR_USER_INPUT, "-steady_inertia_steps must be a positive integer (1: no continuation); got %" PetscInt_FMT, o->nrho);
  PetscCall(SlumpProblemGetEffects(prob, &effects));
  PetscCheck(o->nrho == 1 || (effects & SLUMP_EFFECT_CONVECTION), comm, PETSC_ERR_USER_INPUT, "-steady_inertia_steps needs a steady flow with convection (the cavity with -re > 0, for instance); this one's steady state does not depend on the density");
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSteadyCheckOptions(SlumpProblem prob)
{
  SteadyOptions o;
  DM            dm;
  MPI_Comm      comm;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetDM(prob, &dm));
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCall(SteadyReadOptions(prob, comm, &o));
  PetscFunctionReturn(0);
}

/* The value f times stiffer than v (f < 1: softer), for a model stiffer as
   its parameter grows (Papanastasiou m) or as it falls (Bercovier eps) */
static PetscReal Stiffer(PetscReal v, PetscReal f, PetscBool larger_stiffer)
{
  return larger_stiffer ? v * f : v / f;
}

/* The value to retry from after a failed solve at v (0: none left).
   Nothing solved yet (reached 0; every retry so far was one of these): 100,
   then 1e4 times softer than the first value tried. Else, from the stiffest value solved, the
   square root of the step that failed (*f; the last step to the target may
   have been shorter than the factor); at most 10 retries. */
static PetscReal RetryValue(PetscReal first, PetscReal reached, PetscReal v, PetscBool larger_stiffer, PetscInt nretry, PetscReal *f)
{
  if (reached == 0.0) return nretry < 2 ? Stiffer(first, PetscPowReal(100.0, -(PetscReal)(nretry + 1)), larger_stiffer) : 0.0;
  if (nretry >= 10) return 0.0;
  *f = PetscSqrtReal(larger_stiffer ? v / reached : reached / v);
  return *f >= 1.05 ? Stiffer(reached, *f, larger_stiffer) : 0.0;
}

/* The steady solve, with continuation in the regularisation as the options
   ask. retry: a Newton solve that fails (not for a Krylov solve's sake) is
   retried from softer values, as IDACalcIC is (ida.c): before anything has
   converged, from 100 and then 1e4 times softer than the first value tried;
   after, from the stiffest value solved (X holds its solution) with the
   square root of the step that failed, which grows back (squared, up to
   -steady_continuation_factor) after each success; at most 10 retries. The
   Bingham cavity on 256 x 256 cells fails at m = 1e4 from rest (50 Newton
   steps, max|F| 1.34) and converges from m = 1e2 (docs/performance.md). */
static PetscErrorCode SteadySolve(SlumpProblem prob, Vec X, SlumpStats *stats, PetscBool retry)
{
  SlumpImplicitSolver s;
  SlumpRheology       rheo;
  SteadyOptions       o;
  const char         *regname;
  PetscReal           target, v, rho, f, first, reached = 0.0;
  PetscInt            kr, effects, nretry = 0;
  PetscBool           larger_stiffer, cont;
  MPI_Comm            comm;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)X, &comm));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologyGetRegularisation(rheo, &regname, &target, &larger_stiffer));
  PetscCall(SteadyReadOptions(prob, comm, &o));
  PetscCall(SlumpProblemGetEffects(prob, &effects));
  PetscCall(SlumpProblemGetDensity(prob, &rho));
  {
    PetscBool sv;
    PetscCall(SlumpLinearisationSetUp(prob, comm, &sv));
  }
  PetscCall(SlumpImplicitSolverCreate(prob, X, &s));
  retry = (PetscBool)(retry && o.retry && regname);
  cont  = o.set;
  v = first = o.set ? o.start : target;
  f  = o.factor;
  kr = 1;
  for (;;) {
    PetscBool           conv, last;
    PetscInt            nits, lits;
    Vec                 F;
    PetscReal           fn;
    SlumpLinearFailures lf;
    if (cont) {
      last = larger_stiffer ? (v >= target * (1 - 1e-12)) : (v <= target * (1 + 1e-12));
      if (last) v = target;
      PetscCall(SlumpProblemSetRheologyParameter(prob, regname, v));
      /* the plastic stress carried from another regularisation is not the
         law's at this one: start from the value consistent with X (steady
         duct, Bn 0.05, 40 x 40, from m = 1e-3 to 1e8: 16 Newton iterations
         instead of 19) */
      PetscCall(SlumpProblemDualReset(prob));
    } else last = PETSC_TRUE;
    if (o.nrho > 1) PetscCall(SlumpProblemSetDensity(prob, rho * kr / o.nrho));
    PetscCall(SlumpImplicitSolverSolve(s, 0.0, 0.0, NULL, X, &conv, &nits, &lits));
    PetscCall(VecDuplicate(X, &F));
    PetscCall(SlumpProblemResidual(prob, 0.0, X, NULL, F));
    PetscCall(VecNorm(F, NORM_INFINITY, &fn));
    PetscCall(VecDestroy(&F));
    if (o.monitor) {
      PetscInt         nh;
      const PetscReal *h;
      PetscCall(SlumpImplicitSolverGetHistory(s, &nh, &h));
      for (PetscInt k = 0; k < nh; ++k) PetscCall(PetscPrintf(comm, "  newton %3" PetscInt_FMT " max|F| %.6e\n", k, (double)h[k]));
      PetscCall(PetscPrintf(comm, "  newton %3" PetscInt_FMT " max|F| %.6e (final)\n", nh, (double)fn));
    }
    if (o.nrho > 1 && kr <= o.nrho) PetscCall(PetscPrintf(comm, "steady: density %-10.4g (%" PetscInt_FMT " of %" PetscInt_FMT ")\n", (double)(rho * kr / o.nrho), kr, o.nrho));
    if (regname) PetscCall(PetscPrintf(comm, "steady: %s = %-10.4g Newton %3" PetscInt_FMT "  linear %4" PetscInt_FMT "  max|F| %.3e%s\n", regname, (double)v, nits, lits, (double)fn, conv ? "" : "  (not converged)"));
    else PetscCall(PetscPrintf(comm, "steady: Newton %3" PetscInt_FMT "  linear %4" PetscInt_FMT "  max|F| %.3e%s\n", nits, lits, (double)fn, conv ? "" : "  (not converged)"));
    PetscCall(SlumpImplicitSolverGetLinearFailures(s, &lf));
    /* a retry from softer values, after the density ramp; X holds the last
       converged state (the initial guess if none) */
    if (!conv && retry && !lf.n && (o.nrho == 1 || kr > o.nrho)) {
      const PetscReal vn = RetryValue(first, reached, v, larger_stiffer, nretry, &f);
      if (vn > 0.0) {
        PetscCall(PetscPrintf(comm, "steady: no convergence at %s = %.6g; retrying from %s = %.6g\n", regname, (double)v, regname, (double)vn));
        ++nretry;
        v    = vn;
        cont = PETSC_TRUE;
        continue;
      }
    }
    if (!conv) {
      /* leave the model's own value in place: a caller that retries (a load
         continuation) would otherwise go on at this intermediate one */
      if (cont) PetscCall(SlumpProblemSetRheologyParameter(prob, regname, target));
      if (o.nrho > 1) PetscCall(SlumpProblemSetDensity(prob, rho));
      PetscCall(SlumpImplicitSolverDestroy(&s));
      /* the Newton iteration stopped because a Krylov solve did: say so (the
         steady Poiseuille at m = 1e6 with -linear_solver iterative) */
      if (lf.n) {
        SlumpFormulation form;
        char             at[64] = "";
        PetscCall(SlumpProblemGetFormulation(prob, &form));
        if (regname) (void)snprintf(at, sizeof(at), " at %s = %g", regname, (double)v); /* C's %g: no trailing point */
        PetscCheck(!lf.direct, comm, PETSC_ERR_NOT_CONVERGED, "The steady Newton solve did not converge%s because %s", at, lf.what);
        SETERRQ(comm, PETSC_ERR_NOT_CONVERGED, "The steady Newton solve did not converge%s because a Krylov solve of -linear_solver iterative did not (%s after %" PetscInt_FMT " iterations); use -linear_solver direct%s (see docs/performance.md)", at, KSPConvergedReasons[lf.reason], lf.its,
                form == SLUMP_FORMULATION_PLANE ? ", or an inner Krylov solve of the velocity block (-fieldsplit_u_ksp_type gmres -fieldsplit_u_ksp_rtol 1e-2)" : "");
      }
      PetscCheck(!nretry || reached > 0.0, comm, PETSC_ERR_NOT_CONVERGED, "The steady Newton solve did not converge at %s = %g, nor from 1e4 times softer; try -newton_max_it or a better initial state", regname, (double)first);
      PetscCheck(!nretry, comm, PETSC_ERR_NOT_CONVERGED, "The steady Newton solve did not reach %s = %g: after %" PetscInt_FMT " retries from softer values the stiffest value solved is %s = %g; try -newton_max_it or a softer regularisation", regname, (double)target, nretry, regname, (double)reached);
    }
    PetscCheck(conv || !regname, comm, PETSC_ERR_NOT_CONVERGED, "The steady Newton solve did not converge at %s = %g; try -steady_continuation_start, -newton_max_it or a softer regularisation", regname, (double)v);
    PetscCheck(conv, comm, PETSC_ERR_NOT_CONVERGED, "The steady Newton solve did not converge; try -newton_max_it or a better initial state%s", effects & SLUMP_EFFECT_CONVECTION ? ", or a continuation in the Reynolds number (-steady_inertia_steps)" : "");
    if (regname) reached = v;
    /* the density ramp, at the first regularisation value */
    if (kr < o.nrho) {
      ++kr;
      continue;
    }
    kr = o.nrho + 1;
    if (last) break;
    if (nretry) f = PetscMin(f * f, o.factor);
    v = Stiffer(v, f, larger_stiffer);
  }
  if (nretry) PetscCall(PetscPrintf(comm, "steady: %s = %.6g reached after %" PetscInt_FMT " retr%s from softer values\n", regname, (double)target, nretry, nretry > 1 ? "ies" : "y"));
  PetscCall(SlumpImplicitSolverGetStats(s, stats));
  PetscCall(SlumpProblemGetCounters(prob, &stats->res_evals, &stats->jac_evals));
  PetscCall(SlumpImplicitSolverDestroy(&s));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSteadySolve(SlumpProblem prob, Vec X, SlumpStats *stats)
{
  PetscFunctionBeginUser;
  PetscCall(SteadySolve(prob, X, stats, PETSC_TRUE));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSteadySolveNoRetry(SlumpProblem prob, Vec X, SlumpStats *stats)
{
  PetscFunctionBeginUser;
  PetscCall(SteadySolve(prob, X, stats, PETSC_FALSE));
  PetscFunctionReturn(0);
}
