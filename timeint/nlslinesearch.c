/* A globalised nonlinear solver for IDA: each BDF stage
 *   F(t, y, cj y + beta) = 0,  beta = yp_pred - cj y_pred,
 * is solved by KINSOL with a line search and an exact Jacobian at every
 * iterate (the same stage solver as fixed-step BDF2), instead of IDA's
 * modified Newton with a Jacobian frozen across the step. IDA's correction
 * is ycor = y - y_pred. A failed solve is recoverable: IDA cuts the step.
 * Selected by -ida_nonlinear_solver linesearch. */
#include "timeintimpl.h"
#include <ida/ida.h>
#include <sundials/sundials_nonlinearsolver.h>

typedef struct {
  SlumpImplicitSolver s;
  Vec                 y, beta, f;
  SlumpProblem        prob;
  long int            nits, nconvfails, lastits, lastfail;
  PetscInt            nlin;
} NLSContent;

static PetscErrorCode NLSSolve_Private(NLSContent *c, N_Vector y0, N_Vector ycor, void *mem, PetscBool *conv)
{
  realtype tcur, cj;
  N_Vector yypred, yppred, yyn, ypn, res;
  void    *ud;
  PetscInt nits, lits;
  PetscFunctionBeginUser;
  PetscCheck(!IDAGetNonlinearSystemData(mem, &tcur, &yypred, &yppred, &yyn, &ypn, &res, &cj, &ud), PETSC_COMM_SELF, PETSC_ERR_LIB, "IDAGetNonlinearSystemData failed");
  PetscCall(VecWAXPY(c->beta, -cj, N_VGetVector_Petsc(yypred), N_VGetVector_Petsc(yppred)));
  {
    /* the relative tolerance is taken on the stage's own scale, max|F| at
       y = 0 (its right-hand side), not on the residual of the predictor:
       a good predictor made the tolerance unreachable (couette_cessation at
       m = 1e6: IDA_CONV_FAIL at t = 0.004) */
    PetscReal fref;
    PetscCall(VecZeroEntries(c->y));
    PetscCall(SlumpProblemResidual(c->prob, tcur, c->y, c->beta, c->f));
    PetscCall(VecNorm(c->f, NORM_INFINITY, &fref));
    PetscCall(SlumpImplicitSolverSetResidualScale(c->s, fref));
  }
  /* y0 is the initial iterate (IDA's predictor), not a correction: adding
     it to the predictor started KINSOL from twice the state, which only a
     mass-dominated (inertial) stage survived */
  PetscCall(VecCopy(N_VGetVector_Petsc(y0), c->y));
  PetscCall(SlumpImplicitSolverSolve(c->s, tcur, cj, c->beta, c->y, conv, &nits, &lits));
  c->nits += nits;
  c->lastits = nits;
  c->nlin += lits;
  if (*conv) PetscCall(VecWAXPY(N_VGetVector_Petsc(ycor), -1.0, N_VGetVector_Petsc(y0), c->y));
  PetscFunctionReturn(0);
}

static int NLSSolve(SUNNonlinearSolver NLS, N_Vector y0, N_Vector ycor, N_Vector w, realtype tol, booleantype callLSetup, void *mem)
{
  NLSContent *c    = (NLSContent *)NLS->content;
  PetscBool   conv = PETSC_FALSE;
  if (SlumpSundialsStatus(NLSSolve_Private(c, y0, ycor, mem, &conv))) return SUN_NLS_EXT_FAIL;
  c->lastfail = conv ? 0 : 1;
  if (!conv) {
    c->nconvfails++;
    return SUN_NLS_CONV_RECVR;
  }
  return SUN_NLS_SUCCESS;
}

/* IDA adds this up after every solve: the count of the last solve */
static int NLSGetNumIters(SUNNonlinearSolver NLS, long int *n)
{
  *n = ((NLSContent *)NLS->content)->lastits;
  return SUN_NLS_SUCCESS;
}
static int NLSGetCurIter(SUNNonlinearSolver NLS, int *iter)
{
  *iter = 0;
  return SUN_NLS_SUCCESS;
}
/* likewise, per solve */
static int NLSGetNumConvFails(SUNNonlinearSolver NLS, long int *n)
{
  *n = ((NLSContent *)NLS->content)->lastfail;
  return SUN_NLS_SUCCESS;
}
static int NLSFree(SUNNonlinearSolver NLS)
{
  if (!NLS) return SUN_NLS_SUCCESS;
  if (NLS->content) {
    NLSContent *c = (NLSContent *)NLS->content;
    (void)SlumpImplicitSolverDestroy(&c->s);
    (void)VecDestroy(&c->y);
    (void)VecDestroy(&c->beta);
    (void)VecDestroy(&c->f);
    free(c);
    NLS->content = NULL;
  }
  SUNNonlinSolFreeEmpty(NLS);
  return SUN_NLS_SUCCESS;
}

PetscErrorCode SlumpSUNNonlinSolLineSearchCreate(SlumpProblem prob, Vec X, SUNContext ctx, SUNNonlinearSolver *nls)
{
  SUNNonlinearSolver NLS;
  NLSContent        *c;
  PetscFunctionBeginUser;
  NLS = SUNNonlinSolNewEmpty(ctx);
  c   = (NLSContent *)calloc(1, sizeof(NLSContent));
  PetscCheck(NLS && c, PETSC_COMM_SELF, PETSC_ERR_MEM, "Cannot allocate the nonlinear solver");
  PetscCall(SlumpImplicitSolverCreate(prob, X, &c->s));
  PetscCall(VecDuplicate(X, &c->y));
  PetscCall(VecDuplicate(X, &c->beta));
  PetscCall(VecDuplicate(X, &c->f));
  c->prob = prob;
  NLS->content              = c;
  SlumpSUNNonlinSolSetStageOps(NLS);
  NLS->ops->solve           = NLSSolve;
  NLS->ops->free            = NLSFree;
  NLS->ops->getnumiters     = NLSGetNumIters;
  NLS->ops->getcuriter      = NLSGetCurIter;
  NLS->ops->getnumconvfails = NLSGetNumConvFails;
  *nls                      = NLS;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSUNNonlinSolLineSearchGetLinearIterations(SUNNonlinearSolver nls, PetscInt *nlin)
{
  PetscFunctionBeginUser;
  *nlin = ((NLSContent *)nls->content)->nlin;
  PetscFunctionReturn(0);
}
