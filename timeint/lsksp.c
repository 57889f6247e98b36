/* SUNDIALS <-> PETSc: a SUNMatrix holding a PETSc Mat, and a direct
 * SUNLinearSolver solving with a PETSc KSP. The integrator's Jacobian
 * callback assembles the Mat (DMPlex, shift cj); setup hands it to the KSP
 * (which refactors), solve runs KSPSolve and checks its converged reason:
 * a failed linear solve is recoverable, so IDA cuts the step. */
#include "timeintimpl.h"
#include <ida/ida.h>

int SlumpSundialsStatus(PetscErrorCode ierr)
{
  return ierr ? -1 : 0;
}

void SlumpSilentErrHandler(int code, const char *module, const char *function, char *msg, void *user)
{
}

int SlumpCheckFinite(Vec v)
{
  PetscReal nrm;
  if (VecNorm(v, NORM_INFINITY, &nrm)) return -1;
  return PetscIsInfOrNanReal(nrm) ? 1 : 0;
}

static SUNMatrix_ID MatGetID_Slump(SUNMatrix A)
{
  return SUNMATRIX_CUSTOM;
}
static int MatZero_Slump(SUNMatrix A)
{
  return 0; /* the assembly zeroes the Mat itself */
}
static void MatDestroy_Slump(SUNMatrix A)
{
  SUNMatFreeEmpty(A);
}

SUNMatrix SlumpSUNMatCreate(Mat J, SUNContext ctx)
{
  SUNMatrix A = SUNMatNewEmpty(ctx);
  if (!A) return NULL;
  A->content      = (void *)J;
  A->ops->getid   = MatGetID_Slump;
  A->ops->zero    = MatZero_Slump;
  A->ops->destroy = MatDestroy_Slump;
  return A;
}

typedef struct {
  SlumpProblem      prob;
  KSP               ksp;
  Mat               J;
  PetscInt          nsolves, nits, last_its;
  long int          last_flag;
  void             *ida_mem;   /* exact Newton: re-assemble at IDA's iterate */
  SlumpLSAssembleFn assemble;
  void             *actx;
  /* inexact Newton (KINSOL, -linear_forcing eisenstat_walker): the relative
     tolerance of each solve from the decrease of the right-hand side (the
     residual), Eisenstat and Walker's choice 2 with its safeguard, tightened
     tenfold whenever the residual fell by less than half */
  PetscBool         forcing;
  PetscReal         bprev, eta;
} LSContent;

static SUNLinearSolver_Type LSGetType(SUNLinearSolver S)
{
  return SUNLINEARSOLVER_DIRECT;
}
static SUNLinearSolver_ID LSGetID(SUNLinearSolver S)
{
  return SUNLINEARSOLVER_CUSTOM;
}
static int LSInitialize(SUNLinearSolver S)
{
  return 0;
}

static PetscErrorCode LSSetup_Private(LSContent *c)
{
  PetscFunctionBeginUser;
  PetscCall(KSPSetOperators(c->ksp, c->J, c->J));
  PetscCall(KSPSetUp(c->ksp));
  PetscFunctionReturn(0);
}

static int LSSetup(SUNLinearSolver S, SUNMatrix A)
{
  LSContent *c = (LSContent *)S->content;
  int        st = SlumpSundialsStatus(LSSetup_Private(c));
  c->last_flag  = st;
  return st < 0 ? SUNLS_PACKAGE_FAIL_UNREC : 0;
}

static PetscErrorCode LSSolve_Private(LSContent *c, Vec x, Vec b, PetscBool *ok)
{
  KSPConvergedReason reason;
  PetscInt           its;
  PetscFunctionBeginUser;
  if (c->forcing) {
    const PetscReal gamma = 0.9, alpha = 2.0, etamax = 1e-4, etamin = 1e-10;
    PetscReal       bn, eta;
    PetscCall(VecNorm(b, NORM_2, &bn));
    if (c->bprev <= 0.0) eta = etamax;
    else if (bn > 0.5 * c->bprev) {
      /* slow progress: the inexact steps are what stalls (a line search
         that cuts them, or an ill-conditioned system whose small linear
         residual is a large error): tighten */
      eta = 0.1 * c->eta;
    } else {
      const PetscReal safe = gamma * PetscPowReal(c->eta, alpha);
      eta = gamma * PetscPowReal(bn / c->bprev, alpha);
      if (safe > 0.1) eta = PetscMax(eta, safe);
    }
    c->eta   = PetscMin(etamax, PetscMax(etamin, eta));
    c->bprev = bn;
    PetscCall(KSPSetTolerances(c->ksp, c->eta, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  }
  PetscCall(SlumpProblemKSPSolve(c->prob, c->ksp, b, x, &reason, &its));
  c->last_its = PetscMax(its, 1);
  c->nits += c->last_its;
  c->nsolves++;
  *ok = reason > 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode Reassemble_Private(LSContent *c)
{
  realtype tcur, cj;
  N_Vector yypred, yppred, yy, yp, res;
  void    *ud;
  PetscFunctionBeginUser;
  PetscCheck(!IDAGetNonlinearSystemData(c->ida_mem, &tcur, &yypred, &yppred, &yy, &yp, &res, &cj, &ud), PETSC_COMM_SELF, PETSC_ERR_LIB, "IDAGetNonlinearSystemData failed");
  PetscCall(c->assemble(c->actx, tcur, N_VGetVector_Petsc(yy), N_VGetVector_Petsc(yp), cj));
  PetscCall(LSSetup_Private(c));
  PetscFunctionReturn(0);
}

static int LSSolve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, realtype tol)
{
  LSContent *c = (LSContent *)S->content;
  PetscBool  ok = PETSC_FALSE;
  int        st;
  if (c->assemble && SlumpSundialsStatus(Reassemble_Private(c))) return SUNLS_PACKAGE_FAIL_UNREC;
  st = SlumpSundialsStatus(LSSolve_Private(c, N_VGetVector_Petsc(x), N_VGetVector_Petsc(b), &ok));
  if (st < 0) {
    c->last_flag = SUNLS_PACKAGE_FAIL_UNREC;
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
  if (!ok || SlumpCheckFinite(N_VGetVector_Petsc(x))) {
    c->last_flag = SUNLS_PACKAGE_FAIL_REC;
    return SUNLS_PACKAGE_FAIL_REC;
  }
  c->last_flag = 0;
  return 0;
}

static int LSNumIters(SUNLinearSolver S)
{
  return (int)((LSContent *)S->content)->last_its;
}
static sunindextype LSLastFlag(SUNLinearSolver S)
{
  return ((LSContent *)S->content)->last_flag;
}
static int LSFree(SUNLinearSolver S)
{
  if (!S) return 0;
  if (S->content) {
    LSContent *c = (LSContent *)S->content;
    (void)KSPDestroy(&c->ksp);
    free(c);
    S->content = NULL;
  }
  SUNLinSolFreeEmpty(S);
  return 0;
}

SUNLinearSolver SlumpSUNLinSolCreate(SlumpProblem prob, Mat J, SUNContext ctx)
{
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  LSContent      *c = (LSContent *)calloc(1, sizeof(LSContent));
  if (!S || !c) return NULL;
  S->content          = c;
  S->ops->gettype     = LSGetType;
  S->ops->getid       = LSGetID;
  S->ops->initialize  = LSInitialize;
  S->ops->setup       = LSSetup;
  S->ops->solve       = LSSolve;
  S->ops->numiters    = LSNumIters;
  S->ops->lastflag    = LSLastFlag;
  S->ops->free        = LSFree;
  c->J                = J;
  c->prob             = prob;
  if (KSPCreate(PetscObjectComm((PetscObject)J), &c->ksp)) return NULL;
  if (SlumpProblemConfigureKSP(prob, c->ksp)) return NULL;
  return S;
}

PetscErrorCode SlumpSUNLinSolGetCounts(SUNLinearSolver LS, PetscInt *nsolves, PetscInt *nits)
{
  LSContent *c = (LSContent *)LS->content;
  PetscFunctionBeginUser;
  if (nsolves) *nsolves = c->nsolves;
  if (nits) *nits = c->nits;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSUNLinSolGetKSP(SUNLinearSolver LS, KSP *ksp)
{
  PetscFunctionBeginUser;
  *ksp = ((LSContent *)LS->content)->ksp;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSUNLinSolSetForcing(SUNLinearSolver LS, PetscBool on)
{
  LSContent *c = (LSContent *)LS->content;
  PetscFunctionBeginUser;
  c->forcing = on;
  c->bprev   = -1.0;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSUNLinSolSetExactNewton(SUNLinearSolver LS, void *ida_mem, SlumpLSAssembleFn fn, void *ctx)
{
  LSContent *c = (LSContent *)LS->content;
  PetscFunctionBeginUser;
  c->ida_mem  = ida_mem;
  c->assemble = fn;
  c->actx     = ctx;
  PetscFunctionReturn(0);
}

/* A stage solver that owns its residual, linear solves, convergence test
   and iteration limit ignores what IDA hands it for those. */
static SUNNonlinearSolver_Type StageGetType(SUNNonlinearSolver NLS)
{
  return SUNNONLINEARSOLVER_ROOTFIND;
}
static int StageSetSysFn(SUNNonlinearSolver NLS, SUNNonlinSolSysFn f)
{
  return SUN_NLS_SUCCESS;
}
static int StageSetLSetupFn(SUNNonlinearSolver NLS, SUNNonlinSolLSetupFn f)
{
  return SUN_NLS_SUCCESS;
}
static int StageSetLSolveFn(SUNNonlinearSolver NLS, SUNNonlinSolLSolveFn f)
{
  return SUN_NLS_SUCCESS;
}
static int StageSetConvTestFn(SUNNonlinearSolver NLS, SUNNonlinSolConvTestFn f, void *ctx)
{
  return SUN_NLS_SUCCESS;
}
static int StageSetMaxIters(SUNNonlinearSolver NLS, int maxiters)
{
  return SUN_NLS_SUCCESS;
}

void SlumpSUNNonlinSolSetStageOps(SUNNonlinearSolver NLS)
{
  NLS->ops->gettype     = StageGetType;
  NLS->ops->setsysfn    = StageSetSysFn;
  NLS->ops->setlsetupfn = StageSetLSetupFn;
  NLS->ops->setlsolvefn = StageSetLSolveFn;
  NLS->ops->setctestfn  = StageSetConvTestFn;
  NLS->ops->setmaxiters = StageSetMaxIters;
}
