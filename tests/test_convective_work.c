/* Unit test: the work of the convective terms on the discrete velocity.
 *
 * With the velocity set to s U (U random, zero on the walls through the
 * essential conditions), p = 0, Xdot = 0 and a Newtonian scene, the momentum
 * residual tested with s U is W(s) = s^3 C + s^2 V + s G: C the convective
 * work, V the viscous and friction work (quadratic), G the body force's. The
 * odd part O(s) = (W(s) - W(-s))/2 gives C = (O(2) - 2 O(1))/6.
 *
 * -convection_form skew must do no work: |C| <= tol |C_advective|, with
 * C_advective from the same state and -convection_form advective. With
 * -uniform_phase the level set is set to -1 (all material: constant density,
 * and the quadrature integrates the skew identity exactly); otherwise the
 * scene's own level set is kept and the smoothed density, which the
 * quadrature does not integrate exactly, leaves a small remainder.
 * Prints C for both forms and their ratio; returns 1 on failure. */
#include "slumpscene.h"
#include <slepcsys.h>

static PetscErrorCode Work(SlumpProblem prob, Vec X, Vec Xdot, Vec F, IS isu, Vec U, PetscReal s, PetscReal *w)
{
  Vec Xu, Fu;
  PetscFunctionBeginUser;
  PetscCall(VecGetSubVector(X, isu, &Xu));
  PetscCall(VecAXPBY(Xu, s, 0.0, U));
  PetscCall(VecRestoreSubVector(X, isu, &Xu));
  PetscCall(SlumpProblemResidual(prob, 0.05, X, Xdot, F));
  PetscCall(VecGetSubVector(F, isu, &Fu));
  PetscCall(VecDot(Fu, U, w));
  *w *= s;
  PetscCall(VecRestoreSubVector(F, isu, &Fu));
  PetscFunctionReturn(0);
}

static PetscErrorCode ConvectiveWork(const char scenename[], const char form[], PetscBool uniform, PetscReal *C)
{
  SlumpProblem prob;
  SlumpScene   scene;
  Vec          X, Xdot, F, U, Xu;
  IS           isu, isp, isphi = NULL;
  PetscRandom  rnd;
  PetscReal    W[4], s[4] = {1.0, -1.0, 2.0, -2.0};
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsSetValue(NULL, "-convection_form", form));
  PetscCall(SlumpProblemCreate(PETSC_COMM_WORLD, &prob));
  PetscCall(SlumpSceneCreate(PETSC_COMM_WORLD, scenename, prob, &scene));
  PetscCall(SlumpProblemSetFromOptions(prob));
  PetscCall(SlumpProblemSetUp(prob));
  PetscCall(SlumpProblemCreateVector(prob, &X));
  PetscCall(VecDuplicate(X, &Xdot));
  PetscCall(VecDuplicate(X, &F));
  PetscCall(SlumpProblemProjectInitialState(prob, 0.0, X));
  PetscCall(VecZeroEntries(Xdot));
  PetscCall(SlumpProblemGetFieldIS(prob, &isu, &isp));
  if (isp) PetscCall(VecISSet(X, isp, 0.0));
  if (uniform) {
    PetscCall(SlumpProblemGetExtraFieldIS(prob, &isphi));
    PetscCheck(isphi, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-uniform_phase needs a two-phase scene");
    PetscCall(VecISSet(X, isphi, -1.0));
  }
  PetscCall(VecGetSubVector(X, isu, &Xu));
  PetscCall(VecDuplicate(Xu, &U));
  PetscCall(VecRestoreSubVector(X, isu, &Xu));
  PetscCall(PetscRandomCreate(PETSC_COMM_WORLD, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -1.0, 1.0));
  PetscCall(PetscRandomSetSeed(rnd, 7));
  PetscCall(PetscRandomSeed(rnd));
  PetscCall(VecSetRandom(U, rnd));
  for (PetscInt k = 0; k < 4; ++k) PetscCall(Work(prob, X, Xdot, F, isu, U, s[k], &W[k]));
  /* O(1) = (W(1) - W(-1))/2, O(2) = (W(2) - W(-2))/2 */
  *C = (0.5 * (W[2] - W[3]) - (W[0] - W[1])) / 6.0;
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(ISDestroy(&isu));
  PetscCall(ISDestroy(&isp));
  PetscCall(ISDestroy(&isphi));
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&Xdot));
  PetscCall(VecDestroy(&F));
  PetscCall(SlumpSceneDestroy(&scene));
  PetscCall(SlumpProblemDestroy(&prob));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char      name[64] = "dam_break";
  PetscReal tol = 1e-10, Cs, Ca;
  PetscBool uniform = PETSC_FALSE;
  PetscCall(SlepcInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-scene", name, sizeof(name), NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-tol", &tol, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-uniform_phase", &uniform, NULL));
  PetscCall(ConvectiveWork(name, "advective", uniform, &Ca));
  PetscCall(ConvectiveWork(name, "skew", uniform, &Cs));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "scene %s%s: convective work on the discrete velocity: advective %.6e, skew %.6e, ratio %.3e (tolerance %.1e)\n", name, uniform ? " (uniform phase)" : "", (double)Ca, (double)Cs, (double)(PetscAbsReal(Cs) / PetscAbsReal(Ca)), (double)tol));
  if (!(PetscAbsReal(Cs) <= tol * PetscAbsReal(Ca))) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "The skew form does work on the velocity: |C_skew| = %g > %g |C_advective|\n", (double)PetscAbsReal(Cs), (double)tol));
    return 1;
  }
  PetscCall(SlepcFinalize());
  return 0;
}
