/* The semi-discrete DAE F(t, X, Xdot) and its Jacobian on global vectors:
 * global -> local, insert boundary values (and their time derivatives),
 * pointwise assembly by DMPlex, local -> global. */
#include "slumpimpl.h"

static PetscErrorCode InsertStaticBC(SlumpProblem prob, Vec loc)
{
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(loc, &a));
  for (PetscInt k = 0; k < prob->nbcIdx; ++k) a[prob->bcIdx[k]] = prob->bcVal[k];
  PetscCall(VecRestoreArray(loc, &a));
  PetscFunctionReturn(0);
}

static PetscErrorCode TakeLag(SlumpProblem);

/* PETSc's cell loop (-assembly petsc) passes no auxiliary fields */
static PetscErrorCode CheckLagAssembly(SlumpProblem prob)
{
  PetscFunctionBeginUser;
  PetscCheck(!prob->petscAssembly, prob->comm, PETSC_ERR_USER_INPUT, "-assembly petsc does not hand the last step's state to the kernels, which this problem needs (e.g. -reinit convective); use -assembly slump");
  PetscFunctionReturn(0);
}

static PetscErrorCode FillLocal(SlumpProblem prob, PetscReal t, Vec X, Vec Xdot)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  if (prob->lagOn && !prob->lagSet) PetscCall(TakeLag(prob));
  PetscCall(VecZeroEntries(prob->locXdot));
  if (Xdot) PetscCall(DMGlobalToLocal(prob->dm, Xdot, INSERT_VALUES, prob->locXdot));
  /* static conditions have zero time derivative: the zeroed entries stay */
  if (!prob->bcStatic) PetscCall(DMPlexInsertTimeDerivativeBoundaryValues(prob->dm, PETSC_TRUE, prob->locXdot, t, NULL, NULL, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetLagged(SlumpProblem prob, PetscBool on)
{
  PetscFunctionBeginUser;
  if (on) PetscCall(CheckLagAssembly(prob));
  prob->lagOn = on;
  if (!on) {
    prob->lagSet = PETSC_FALSE;
    PetscCall(VecDestroy(&prob->locLag));
  }
  PetscFunctionReturn(0);
}

/* the lagged local vector from prob->locX (filled at t) */
static PetscErrorCode TakeLag(SlumpProblem prob)
{
  PetscFunctionBeginUser;
  PetscCall(CheckLagAssembly(prob));
  if (!prob->locLag) PetscCall(VecDuplicate(prob->locX, &prob->locLag));
  PetscCall(VecCopy(prob->locX, prob->locLag));
  prob->lagSet = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetLaggedState(SlumpProblem prob, PetscReal t, Vec X)
{
  PetscFunctionBeginUser;
  if (!prob->lagOn) PetscFunctionReturn(0);
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  PetscCall(TakeLag(prob));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemResidual(SlumpProblem prob, PetscReal t, Vec X, Vec Xdot, Vec F)
{
  PetscFunctionBeginUser;
  PetscCall(FillLocal(prob, t, X, Xdot));
  PetscCall(VecZeroEntries(prob->locF));
  if (prob->petscAssembly) PetscCall(DMPlexTSComputeIFunctionFEM(prob->dm, t, prob->locX, prob->locXdot, prob->locF, prob));
  else PetscCall(SlumpAssembleResidual(prob, t, prob->locX, prob->locXdot, prob->locF));
  PetscCall(VecZeroEntries(F));
  PetscCall(DMLocalToGlobal(prob->dm, prob->locF, ADD_VALUES, F));
  prob->nres++;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemJacobian(SlumpProblem prob, PetscReal t, Vec X, Vec Xdot, PetscReal shift, Mat J)
{
  PetscFunctionBeginUser;
  PetscCall(FillLocal(prob, t, X, Xdot));
  if (prob->petscAssembly) PetscCall(DMPlexTSComputeIJacobianFEM(prob->dm, t, prob->locX, prob->locXdot, shift, J, J, prob));
  else PetscCall(SlumpAssembleJacobian(prob, t, prob->locX, prob->locXdot, shift, J));
  if (prob->Sp) PetscCall(SlumpAssembleSchurMass(prob, t, prob->locX, prob->locXdot, shift, prob->Sp));
  prob->njac++;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemInitJacobian(SlumpProblem prob, PetscReal t, Vec X, Mat J)
{
  PetscFunctionBeginUser;
  prob->jacmode = 1;
  PetscCall(SlumpProblemSetConstantsAll(prob));
  PetscCall(SlumpProblemJacobian(prob, t, X, NULL, 1.0, J));
  prob->jacmode = 0;
  PetscCall(SlumpProblemSetConstantsAll(prob));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemFillLocal(SlumpProblem prob, PetscReal t, Vec X)
{
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(prob->locX));
  PetscCall(DMGlobalToLocal(prob->dm, X, INSERT_VALUES, prob->locX));
  if (prob->bcStatic) PetscCall(InsertStaticBC(prob, prob->locX));
  else PetscCall(DMPlexInsertBoundaryValues(prob->dm, PETSC_TRUE, prob->locX, t, NULL, NULL, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemFillDiagVector(SlumpProblem prob, PetscReal t, Vec X, Vec Xdiag)
{
  Vec                loc;
  const PetscScalar *a;
  PetscScalar       *b;
  PetscInt           n;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  PetscCall(DMGetLocalVector(prob->dmDiag, &loc));
  PetscCall(VecGetLocalSize(loc, &n));
  PetscCall(VecGetArrayRead(prob->locX, &a));
  PetscCall(VecGetArray(loc, &b));
  PetscCall(PetscArraycpy(b, a, n));
  PetscCall(VecRestoreArray(loc, &b));
  PetscCall(VecRestoreArrayRead(prob->locX, &a));
  PetscCall(DMLocalToGlobal(prob->dmDiag, loc, INSERT_VALUES, Xdiag));
  PetscCall(DMRestoreLocalVector(prob->dmDiag, &loc));
  PetscFunctionReturn(0);
}
