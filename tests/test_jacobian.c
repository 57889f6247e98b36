/* Unit test: the assembled Jacobian J = dF/dX + shift dF/dXdot matches a
 * finite-difference directional derivative of the residual,
 *   | J v - (F(X + e v, Xdot + shift e v) - F(X - e v, Xdot - shift e v)) / 2e | <= tol |J v|,
 * for a scene given by options (rheology, effects). Prints nothing on success.
 *
 * -stress_velocity: the same check for the stress-velocity linearisation
 * with the plastic stress S consistent with X (where it must be the exact
 * Jacobian), and the dual update: S updated from X with the correction e v
 * must match the consistent S at X + e v to second order in e (the error
 * ratio between e and e/2 at least 3) and stay within ||S|| <= tau_y. */
#include "slumpscene.h"
#include <slepcsys.h>

int main(int argc, char **argv)
{
  SlumpProblem prob;
  SlumpScene   scene;
  Vec          X, Xdot, V, Xp, Xm, Xdp, Xdm, Fp, Fm, JV;
  Mat          J;
  PetscRandom  rnd;
  PetscReal    shift = 7.0, eps = 1e-6, tol = 1e-6, nJV, nd, scale = 1.0;
  char         name[64] = "mms_stokes";
  PetscInt     effects;
  PetscBool    sv = PETSC_FALSE;
  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-scene", name, sizeof(name), NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-tol", &tol, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-state_scale", &scale, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-stress_velocity", &sv, NULL));
  PetscCall(SlumpProblemCreate(PETSC_COMM_WORLD, &prob));
  PetscCall(SlumpSceneCreate(PETSC_COMM_WORLD, name, prob, &scene));
  PetscCall(SlumpProblemSetFromOptions(prob));
  PetscCall(SlumpProblemSetUp(prob));
  PetscCall(SlumpProblemGetEffects(prob, &effects));
  if (!(effects & SLUMP_EFFECT_INERTIA)) shift = 0.0;
  PetscCall(SlumpProblemCreateVector(prob, &X));
  PetscCall(VecDuplicate(X, &Xdot));
  PetscCall(VecDuplicate(X, &V));
  PetscCall(VecDuplicate(X, &Xp));
  PetscCall(VecDuplicate(X, &Xm));
  PetscCall(VecDuplicate(X, &Xdp));
  PetscCall(VecDuplicate(X, &Xdm));
  PetscCall(VecDuplicate(X, &Fp));
  PetscCall(VecDuplicate(X, &Fm));
  PetscCall(VecDuplicate(X, &JV));
  PetscCall(PetscRandomCreate(PETSC_COMM_WORLD, &rnd));
  PetscCall(PetscRandomSetSeed(rnd, 42));
  PetscCall(PetscRandomSeed(rnd));
  PetscCall(SlumpProblemProjectInitialState(prob, 0.0, X));
  PetscCall(VecSetRandom(V, rnd));
  PetscCall(VecAXPY(X, 0.1 * scale, V));
  PetscCall(VecSetRandom(Xdot, rnd));
  PetscCall(VecSetRandom(V, rnd));
  PetscCall(SlumpProblemCreateMatrix(prob, &J));
  if (sv) {
    SlumpRheology rheo;
    PetscBool     has;
    PetscCall(SlumpProblemGetRheology(prob, &rheo));
    PetscCall(SlumpRheologyHasPlasticPart(rheo, &has));
    if (!has) {
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "-stress_velocity: the scene's rheology has no plastic part\n"));
      return 1;
    }
    PetscCall(SlumpProblemSetStressVelocity(prob, PETSC_TRUE));
    PetscCall(SlumpProblemDualBegin(prob, 0.05, X)); /* S consistent with X */
    PetscCall(SlumpProblemDualLinearise(prob, 0.05, X));
  }
  PetscCall(SlumpProblemJacobian(prob, 0.05, X, Xdot, shift, J));
  PetscCall(MatMult(J, V, JV));
  PetscCall(VecWAXPY(Xp, eps, V, X));
  PetscCall(VecWAXPY(Xm, -eps, V, X));
  PetscCall(VecWAXPY(Xdp, shift * eps, V, Xdot));
  PetscCall(VecWAXPY(Xdm, -shift * eps, V, Xdot));
  PetscCall(SlumpProblemResidual(prob, 0.05, Xp, Xdp, Fp));
  PetscCall(SlumpProblemResidual(prob, 0.05, Xm, Xdm, Fm));
  PetscCall(VecAXPY(Fp, -1.0, Fm));
  PetscCall(VecScale(Fp, 0.5 / eps));
  PetscCall(VecNorm(JV, NORM_2, &nJV));
  PetscCall(VecAXPY(Fp, -1.0, JV));
  PetscCall(VecNorm(Fp, NORM_2, &nd));
  if (!(nd <= tol * nJV)) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "Jacobian mismatch (scene %s): |Jv - FD| / |Jv| = %g, expected <= %g\n", name, (double)(nd / nJV), (double)tol));
    return 1;
  }
  if (sv) {
    /* the dual update is the linearised plastic law: second order in e */
    PetscInt           n, ns;
    const PetscScalar *S;
    PetscScalar       *Supd;
    PetscReal          err[2], smax = 0.0;
    for (PetscInt k = 0; k < 2; ++k) {
      const PetscReal e = 1e-3 * scale / (1 << k);
      PetscCall(SlumpProblemDualEnd(prob, 0.05, X, PETSC_FALSE));
      PetscCall(SlumpProblemDualReset(prob));
      PetscCall(SlumpProblemDualBegin(prob, 0.05, X));
      PetscCall(SlumpProblemDualLinearise(prob, 0.05, X));
      PetscCall(VecWAXPY(Xp, e, V, X));
      PetscCall(SlumpProblemDualLinearise(prob, 0.05, Xp)); /* S updated with the step e V */
      PetscCall(SlumpProblemDualGetArray(prob, &n, &ns, &S));
      PetscCall(PetscMalloc1(n * ns, &Supd));
      PetscCall(PetscArraycpy(Supd, S, n * ns));
      PetscCall(SlumpProblemDualEnd(prob, 0.05, Xp, PETSC_FALSE));
      PetscCall(SlumpProblemDualReset(prob));
      PetscCall(SlumpProblemDualBegin(prob, 0.05, Xp)); /* consistent at X + e V */
      PetscCall(SlumpProblemDualGetArray(prob, &n, &ns, &S));
      err[k] = 0.0;
      for (PetscInt i = 0; i < n * ns; ++i) {
        err[k] = PetscMax(err[k], PetscAbsScalar(Supd[i] - S[i]));
        smax   = PetscMax(smax, PetscAbsScalar(S[i]));
      }
      PetscCall(PetscFree(Supd));
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, err, 2, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &smax, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    if (!(err[0] <= 1e-12 * smax || err[0] >= 3.0 * err[1])) {
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "Dual update not second order (scene %s): max|S_upd - S(X + e v)| = %g at e, %g at e/2 (max|S| %g)\n", name, (double)err[0], (double)err[1], (double)smax));
      return 1;
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "stress-velocity (scene %s): |Jv - FD|/|Jv| = %.2e, dual update error %.2e -> %.2e (ratio %.2f), max|S| %.3g\n", name, (double)(nd / nJV), (double)err[0], (double)err[1], (double)(err[1] > 0 ? err[0] / err[1] : 0.0), (double)smax));
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&Xdot));
  PetscCall(VecDestroy(&V));
  PetscCall(VecDestroy(&Xp));
  PetscCall(VecDestroy(&Xm));
  PetscCall(VecDestroy(&Xdp));
  PetscCall(VecDestroy(&Xdm));
  PetscCall(VecDestroy(&Fp));
  PetscCall(VecDestroy(&Fm));
  PetscCall(VecDestroy(&JV));
  PetscCall(SlumpSceneDestroy(&scene));
  PetscCall(SlumpProblemDestroy(&prob));
  PetscCall(SlepcFinalize());
  return 0;
}
