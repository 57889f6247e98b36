/* The stress-velocity Newton's dual variable: the plastic stress S of the
 * yield term at every quadrature point of every local cell, carried from
 * one nonlinear solve to the next and updated after every Newton correction
 * (slump.h, SlumpProblemDualBegin; the pointwise law in slumppointwise.h). */
#include "slumpimpl.h"

PetscErrorCode SlumpProblemSetStressVelocity(SlumpProblem prob, PetscBool on)
{
  PetscInt ncell, nq, dim, n;
  PetscFunctionBeginUser;
  PetscCheck(prob->setup, prob->comm, PETSC_ERR_ORDER, "Call SlumpProblemSetUp() before SlumpProblemSetStressVelocity()");
  PetscCheck(!on || !prob->petscAssembly, prob->comm, PETSC_ERR_USER_INPUT, "-newton_linearisation stress_velocity needs our cell loop (it hands the plastic stress to the kernels); use -assembly slump");
  prob->dualOn      = on;
  prob->dualInSolve = PETSC_FALSE;
  prob->dualSaved   = PETSC_FALSE;
  prob->dualLinSet  = PETSC_FALSE;
  if (!on || prob->dual)
    PetscFunctionReturn(0);
  PetscCall(SlumpAssemblyGetSizes(prob, &ncell, &nq, &dim));
  prob->dualNq = nq;
  prob->dualNs = dim * dim;
  n            = PetscMax(ncell * nq * prob->dualNs, 1);
  PetscCall(PetscCalloc2(n, &prob->dual, n, &prob->dualSave));
  PetscCall(PetscCalloc2(PetscMax(ncell * nq, 1), &prob->dualYield, PetscMax(ncell * nq, 1), &prob->dualYieldJ));
  PetscCall(DMCreateGlobalVector(prob->dm, &prob->dualLin));
  PetscCall(DMCreateLocalVector(prob->dm, &prob->locDual));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetStressVelocity(SlumpProblem prob, PetscBool *on)
{
  PetscFunctionBeginUser;
  *on = prob->dualOn;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetStressVelocityOption(SlumpProblem prob, PetscBool *wanted)
{
  PetscFunctionBeginUser;
  if (prob->dualWantedSet) *wanted = prob->dualWanted;
  else { /* options not read: the default */
    PetscCall(SlumpRheologyHasPlasticPart(prob->rheo, wanted));
    if (prob->petscAssembly) *wanted = PETSC_FALSE;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode DualSize(SlumpProblem prob, PetscInt *n)
{
  PetscInt ncell, nq, dim;
  PetscFunctionBeginUser;
  PetscCall(SlumpAssemblyGetSizes(prob, &ncell, &nq, &dim));
  *n = ncell * nq * prob->dualNs;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemDualBegin(SlumpProblem prob, PetscReal t, Vec X)
{
  PetscInt n;
  PetscFunctionBeginUser;
  if (!prob->dualOn)
    PetscFunctionReturn(0);
  PetscCall(DualSize(prob, &n));
  if (prob->dualSaved)
    PetscCall(PetscArraycpy(prob->dual, prob->dualSave, n));
  else {
    PetscCall(SlumpProblemFillLocal(prob, t, X));
    PetscCall(SlumpAssembleDual(prob, t, prob->locX, NULL, prob->dual, prob->dualYield));
  }
  prob->dualInSolve = PETSC_TRUE;
  prob->dualLinSet  = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* S from the last linearisation point with the step X - X_lin */
static PetscErrorCode DualStep(SlumpProblem prob, PetscReal t, Vec X)
{
  PetscFunctionBeginUser;
  PetscCall(VecAYPX(prob->dualLin, -1.0, X)); /* dualLin = X - X_lin */
  PetscCall(VecZeroEntries(prob->locDual));
  PetscCall(DMGlobalToLocal(prob->dm, prob->dualLin, INSERT_VALUES, prob->locDual));
  PetscCall(VecAYPX(prob->dualLin, -1.0, X)); /* back to X_lin */
  PetscCall(SlumpProblemFillLocal(prob, t, prob->dualLin));
  PetscCall(SlumpAssembleDual(prob, t, prob->locX, prob->locDual, prob->dual, prob->dualYield));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemDualLinearise(SlumpProblem prob, PetscReal t, Vec X)
{
  PetscFunctionBeginUser;
  if (!prob->dualOn || !prob->dualInSolve)
    PetscFunctionReturn(0);
  if (prob->dualLinSet)
    PetscCall(DualStep(prob, t, X));
  PetscCall(VecCopy(X, prob->dualLin));
  prob->dualLinSet = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemDualEnd(SlumpProblem prob, PetscReal t, Vec X, PetscBool converged)
{
  PetscInt n;
  PetscFunctionBeginUser;
  if (!prob->dualOn || !prob->dualInSolve)
    PetscFunctionReturn(0);
  if (converged) {
    if (prob->dualLinSet)
      PetscCall(DualStep(prob, t, X));
    PetscCall(DualSize(prob, &n));
    PetscCall(PetscArraycpy(prob->dualSave, prob->dual, n));
    prob->dualSaved = PETSC_TRUE;
  }
  prob->dualInSolve = PETSC_FALSE;
  prob->dualLinSet  = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemDualReset(SlumpProblem prob)
{
  PetscFunctionBeginUser;
  prob->dualSaved = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemDualGetArray(SlumpProblem prob, PetscInt *n, PetscInt *ns, const PetscScalar **S)
{
  PetscFunctionBeginUser;
  PetscCheck(prob->dualOn, prob->comm, PETSC_ERR_ORDER, "The stress-velocity Newton is off (SlumpProblemSetStressVelocity)");
  PetscCall(DualSize(prob, n));
  *n /= prob->dualNs;
  *ns = prob->dualNs;
  *S  = prob->dual;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemDualYieldChanges(SlumpProblem prob, PetscInt *nchanged)
{
  PetscInt ncell, nq, dim, n = 0;
  PetscFunctionBeginUser;
  *nchanged = 0;
  if (!prob->dualOn)
    PetscFunctionReturn(0);
  PetscCall(SlumpAssemblyGetSizes(prob, &ncell, &nq, &dim));
  for (PetscInt i = 0; i < ncell * nq; ++i)
    n += prob->dualYield[i] != prob->dualYieldJ[i] ? 1 : 0;
  PetscCall(MPIU_Allreduce(&n, nchanged, 1, MPIU_INT, MPI_SUM, prob->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemDualGetState(SlumpProblem prob, PetscInt *n, PetscBool *saved, PetscScalar **S)
{
  PetscFunctionBeginUser;
  *n     = 0;
  *saved = PETSC_FALSE;
  *S     = NULL;
  if (!prob->dualOn || !prob->dual) PetscFunctionReturn(0);
  PetscCall(DualSize(prob, n));
  *saved = prob->dualSaved;
  *S     = prob->dualSave;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemDualSetState(SlumpProblem prob, PetscInt n, PetscBool saved, const PetscScalar S[])
{
  PetscInt m;
  PetscFunctionBeginUser;
  PetscCheck(prob->dualOn && prob->dual, prob->comm, PETSC_ERR_ORDER, "The stress-velocity Newton is off (SlumpProblemSetStressVelocity)");
  PetscCall(DualSize(prob, &m));
  PetscCheck(m == n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "The plastic stress has %d values on this rank, the state given %d", (int)m, (int)n);
  PetscCall(PetscArraycpy(prob->dualSave, S, n));
  prob->dualSaved = saved;
  PetscFunctionReturn(0);
}
