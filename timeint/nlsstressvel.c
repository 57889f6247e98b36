/* The stress-velocity Newton as IDA's nonlinear solver. Each BDF stage
 *   F(t, y, cj y + beta) = 0,  beta = yp_pred - cj y_pred,
 * is solved by Newton with a Jacobian assembled at every iterate, the
 * plastic stress S of the yield term held at the quadrature points and
 * updated after every correction (SlumpProblemDualBegin ... End): the
 * tangent's plastic term stays bounded whatever the regularisation, so the
 * iteration converges from the predictor where the primal Newton's basin
 * (|gdot| ~ 1/m around the yield surface) forced IDA to cut the step.
 * IDA keeps its error test and step control (IDA's own convergence test,
 * iteration limit and linear solver are not used); the convergence test is
 * IDA's (rate-based, on the WRMS norm of the correction with IDA's
 * weights, which leave the pressure out: timeint/ida.c), and a failure is
 * recoverable (IDA cuts the step). Selected by -newton_linearisation
 * stress_velocity (the default for models with a plastic part). */
#include "timeintimpl.h"
#include <ida/ida.h>
#include <sundials/sundials_nonlinearsolver.h>

typedef struct {
  SlumpProblem prob;
  Mat          J;
  KSP          ksp;
  Vec          y, yp, beta, f, del;
  N_Vector     ndel;
  PetscInt     maxit;
  int          curiter;
  PetscReal    ss, oldnrm; /* IDA's convergence-rate estimate, carried between solves */
  PetscBool    reuse;      /* keep the factored Jacobian across iterations and steps */
  PetscBool    haveJ;
  PetscReal    cjJ; /* cj of the factored Jacobian */
  long int     njac, nretry;
  long int     lastits, lastfail;
  PetscInt     nlin;
} SVContent;

/* IDA's test (ida_nls.c): m = 0 accepts with the rate of earlier solves;
   later iterations estimate the rate; a rate above 0.9 is a failure. */
static PetscErrorCode SVConvTest(SVContent *c, PetscReal delnrm, PetscReal tol, PetscInt m, int *status)
{
  PetscFunctionBeginUser;
  *status = SUN_NLS_CONTINUE;
  if (m == 0) {
    c->oldnrm = delnrm;
    if (delnrm <= 1e-4 * tol)
      *status = SUN_NLS_SUCCESS;
  } else {
    const PetscReal rate = PetscPowReal(delnrm / c->oldnrm, 1.0 / m);
    if (rate > 0.9) {
      *status = SUN_NLS_CONV_RECVR;
      PetscFunctionReturn(0);
    }
    c->ss = rate / (1.0 - rate);
  }
  if (*status == SUN_NLS_CONTINUE && c->ss * delnrm <= tol)
    *status = SUN_NLS_SUCCESS;
  PetscFunctionReturn(0);
}

/* One Newton solve of the stage from y0. fresh: a Jacobian at every
   iterate; otherwise the factored one is kept while cj stays within 25 %
   of its own (IDA's rule, the correction scaled by 2/(1 + cj/cj_J)) and no
   quadrature point has changed between yielded and unyielded since it was
   assembled (SlumpProblemDualYieldChanges). */
static PetscErrorCode SVNewton(SVContent *c, N_Vector y0, N_Vector w, realtype tol, realtype tcur, realtype cj, PetscBool fresh, int *status)
{
  KSPConvergedReason reason;
  PetscInt           its;
  PetscReal          fn;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(N_VGetVector_Petsc(y0), c->y));
  PetscCall(SlumpProblemDualBegin(c->prob, tcur, c->y));
  *status = SUN_NLS_CONV_RECVR;
  for (c->curiter = 0; c->curiter < c->maxit; ++c->curiter) {
    PetscReal delnrm;
    PetscInt  changed = 0;
    PetscBool assemble;
    PetscCall(VecWAXPY(c->yp, cj, c->y, c->beta));
    PetscCall(SlumpProblemResidual(c->prob, tcur, c->y, c->yp, c->f));
    PetscCall(VecNorm(c->f, NORM_INFINITY, &fn));
    if (PetscIsInfOrNanReal(fn))
      break;
    PetscCall(SlumpProblemDualLinearise(c->prob, tcur, c->y));
    assemble = (fresh || !c->haveJ || PetscAbsReal(cj / c->cjJ - 1.0) > 0.25) ? PETSC_TRUE : PETSC_FALSE;
    if (!assemble) {
      PetscCall(SlumpProblemDualYieldChanges(c->prob, &changed));
      if (changed)
        assemble = PETSC_TRUE;
    }
    if (assemble) {
      PetscCall(SlumpProblemJacobian(c->prob, tcur, c->y, c->yp, cj, c->J));
      PetscCall(KSPSetOperators(c->ksp, c->J, c->J));
      c->haveJ = PETSC_TRUE;
      c->cjJ   = cj;
      c->njac++;
    }
    PetscCall(VecScale(c->f, -1.0));
    PetscCall(SlumpProblemKSPSolve(c->prob, c->ksp, c->f, c->del, &reason, &its));
    c->nlin += PetscMax(its, 1);
    c->lastits++;
    if (reason <= 0)
      break;
    if (cj != c->cjJ)
      PetscCall(VecScale(c->del, 2.0 / (1.0 + cj / c->cjJ)));
    PetscCall(VecAXPY(c->y, 1.0, c->del));
    delnrm = N_VWrmsNorm(c->ndel, w);
    if (PetscIsInfOrNanReal(delnrm))
      break;
    PetscCall(SVConvTest(c, delnrm, tol, c->curiter, status));
    if (*status != SUN_NLS_CONTINUE)
      break;
    *status = SUN_NLS_CONV_RECVR;
  }
  if (*status == SUN_NLS_CONTINUE)
    *status = SUN_NLS_CONV_RECVR;
  PetscCall(SlumpProblemDualEnd(c->prob, tcur, c->y, *status == SUN_NLS_SUCCESS ? PETSC_TRUE : PETSC_FALSE));
  PetscFunctionReturn(0);
}

static PetscErrorCode SVSolve_Private(SUNNonlinearSolver NLS, N_Vector y0, N_Vector ycor, N_Vector w, realtype tol, void *mem, int *status)
{
  SVContent *c = (SVContent *)NLS->content;
  realtype   tcur, cj;
  N_Vector   yypred, yppred, yyn, ypn, res;
  void      *ud;
  PetscFunctionBeginUser;
  PetscCheck(!IDAGetNonlinearSystemData(mem, &tcur, &yypred, &yppred, &yyn, &ypn, &res, &cj, &ud), PETSC_COMM_SELF, PETSC_ERR_LIB, "IDAGetNonlinearSystemData failed");
  PetscCall(VecWAXPY(c->beta, -cj, N_VGetVector_Petsc(yypred), N_VGetVector_Petsc(yppred)));
  c->lastits = 0;
  /* y0 is the initial iterate (IDA's predictor) */
  PetscCall(SVNewton(c, y0, w, tol, tcur, cj, c->reuse ? PETSC_FALSE : PETSC_TRUE, status));
  if (*status != SUN_NLS_SUCCESS && c->reuse) {
    /* a kept Jacobian may be what failed: again with a fresh one at every
       iterate before IDA cuts the step */
    c->ss = 20.0;
    c->nretry++;
    PetscCall(SVNewton(c, y0, w, tol, tcur, cj, PETSC_TRUE, status));
  }
  if (*status == SUN_NLS_SUCCESS)
    PetscCall(VecWAXPY(N_VGetVector_Petsc(ycor), -1.0, N_VGetVector_Petsc(y0), c->y));
  else
    c->ss = 20.0; /* IDA's value after a fresh Jacobian */
  PetscFunctionReturn(0);
}

static int SVSolve(SUNNonlinearSolver NLS, N_Vector y0, N_Vector ycor, N_Vector w, realtype tol, booleantype callLSetup, void *mem)
{
  SVContent *c      = (SVContent *)NLS->content;
  int        status = SUN_NLS_CONV_RECVR;
  if (SlumpSundialsStatus(SVSolve_Private(NLS, y0, ycor, w, tol, mem, &status)))
    return SUN_NLS_EXT_FAIL;
  c->lastfail = status == SUN_NLS_SUCCESS ? 0 : 1;
  return status;
}

/* IDA adds these up after every solve: the counts of the last solve */
static int SVGetNumIters(SUNNonlinearSolver NLS, long int *n)
{
  *n = ((SVContent *)NLS->content)->lastits;
  return SUN_NLS_SUCCESS;
}
static int SVGetCurIter(SUNNonlinearSolver NLS, int *iter)
{
  *iter = ((SVContent *)NLS->content)->curiter;
  return SUN_NLS_SUCCESS;
}
static int SVGetNumConvFails(SUNNonlinearSolver NLS, long int *n)
{
  *n = ((SVContent *)NLS->content)->lastfail;
  return SUN_NLS_SUCCESS;
}
static int SVFree(SUNNonlinearSolver NLS)
{
  if (!NLS)
    return SUN_NLS_SUCCESS;
  if (NLS->content) {
    SVContent *c = (SVContent *)NLS->content;
    (void)KSPDestroy(&c->ksp);
    (void)MatDestroy(&c->J);
    N_VDestroy(c->ndel);
    (void)VecDestroy(&c->y);
    (void)VecDestroy(&c->yp);
    (void)VecDestroy(&c->beta);
    (void)VecDestroy(&c->f);
    (void)VecDestroy(&c->del);
    free(c);
    NLS->content = NULL;
  }
  SUNNonlinSolFreeEmpty(NLS);
  return SUN_NLS_SUCCESS;
}

PetscErrorCode SlumpSUNNonlinSolStressVelocityCreate(SlumpProblem prob, Vec X, PetscInt maxit, PetscBool reuse, SUNContext ctx, SUNNonlinearSolver *nls)
{
  SUNNonlinearSolver NLS;
  SVContent         *c;
  MPI_Comm           comm;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)X, &comm));
  NLS = SUNNonlinSolNewEmpty(ctx);
  c   = (SVContent *)calloc(1, sizeof(SVContent));
  PetscCheck(NLS && c, PETSC_COMM_SELF, PETSC_ERR_MEM, "Cannot allocate the nonlinear solver");
  c->prob  = prob;
  c->maxit = maxit;
  c->reuse = reuse;
  c->ss    = 20.0;
  PetscCall(VecDuplicate(X, &c->y));
  PetscCall(VecDuplicate(X, &c->yp));
  PetscCall(VecDuplicate(X, &c->beta));
  PetscCall(VecDuplicate(X, &c->f));
  PetscCall(VecDuplicate(X, &c->del));
  c->ndel = N_VMake_Petsc(c->del, ctx);
  PetscCall(SlumpProblemCreateMatrix(prob, &c->J));
  PetscCall(KSPCreate(comm, &c->ksp));
  PetscCall(SlumpProblemConfigureKSP(prob, c->ksp));
  NLS->content              = c;
  SlumpSUNNonlinSolSetStageOps(NLS);
  NLS->ops->solve           = SVSolve;
  NLS->ops->free            = SVFree;
  NLS->ops->getnumiters     = SVGetNumIters;
  NLS->ops->getcuriter      = SVGetCurIter;
  NLS->ops->getnumconvfails = SVGetNumConvFails;
  *nls                      = NLS;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSUNNonlinSolStressVelocityGetLinearIterations(SUNNonlinearSolver nls, PetscInt *nlin)
{
  PetscFunctionBeginUser;
  *nlin = ((SVContent *)nls->content)->nlin;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSUNNonlinSolStressVelocityGetCounts(SUNNonlinearSolver nls, PetscInt *njac, PetscInt *nretry)
{
  SVContent *c = (SVContent *)nls->content;
  PetscFunctionBeginUser;
  if (njac)
    *njac = (PetscInt)c->njac;
  if (nretry)
    *nretry = (PetscInt)c->nretry;
  PetscFunctionReturn(0);
}
