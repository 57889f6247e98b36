/* Unit test: the assembled Jacobian J = dF/dX + shift dF/dXdot matches a
 * finite-difference directional derivative of the residual,
 *   | J v - (F(X + e v, Xdot + shift e v) - F(X - e v, Xdot - shift e v)) / 2e | <= tol |J v|,
 * for a scene given by options (rheology, effects). Prints nothing on success. */
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
  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-scene", name, sizeof(name), NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-tol", &tol, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-state_scale", &scale, NULL));
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
