/* The smallest eigenvalue of the viscous operator with the scene's walls, by
 * SLEPc: K x = lambda M x on the velocity unknowns (Dirichlet dofs removed),
 * K the vector Laplacian int grad u : grad v (the scalar one in the
 * anti-plane formulation), M the mass matrix. Shift-and-invert around 0 with
 * a direct factorisation; every -eig_ option applies. It bounds the exact
 * stopping time of a Bingham flow (REFERENCES.md):
 *   T <= rho/(eta_p lambda1) ln(1 + eta_p lambda1 ||u0|| / (tau0 beta)). */
#include "slumpimpl.h"
#include <slepceps.h>

static void g3_laplace(SLUMP_PWJ_ARGS, PetscScalar g3[])
{
  const PetscInt nc = uOff[1] - uOff[0];
  for (PetscInt i = 0; i < nc * nc * dim * dim; ++i) g3[i] = 0.0;
  for (PetscInt c = 0; c < nc; ++c)
    for (PetscInt d = 0; d < dim; ++d) g3[((c * nc + c) * dim + d) * dim + d] = 1.0;
}

static void g0_mass(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  const PetscInt nc = uOff[1] - uOff[0];
  for (PetscInt i = 0; i < nc * nc; ++i) g0[i] = 0.0;
  for (PetscInt c = 0; c < nc; ++c) g0[c * nc + c] = 1.0;
}

PetscErrorCode SlumpProblemComputeViscousEigenvalue(SlumpProblem prob, PetscReal *lambda1)
{
  PetscPointJac g[SLUMP_MAX_FIELDS][SLUMP_MAX_FIELDS][4] = {{{NULL}}};
  Mat           A, K, M;
  Vec           X;
  IS            isu, isp;
  EPS           eps;
  ST            st;
  KSP           ksp;
  PetscInt      nconv;
  PetscScalar   kr, ki;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemCreateVector(prob, &X));
  PetscCall(SlumpProblemCreateMatrix(prob, &A));
  PetscCall(SlumpProblemGetFieldIS(prob, &isu, &isp));
  g[0][0][3] = g3_laplace;
  PetscCall(SlumpAssembleJacobianWith(prob, 0.0, prob->locX, NULL, 0.0, g, A));
  PetscCall(MatCreateSubMatrix(A, isu, isu, MAT_INITIAL_MATRIX, &K));
  g[0][0][3] = NULL;
  g[0][0][0] = g0_mass;
  PetscCall(SlumpAssembleJacobianWith(prob, 0.0, prob->locX, NULL, 0.0, g, A));
  PetscCall(MatCreateSubMatrix(A, isu, isu, MAT_INITIAL_MATRIX, &M));
  PetscCall(EPSCreate(prob->comm, &eps));
  PetscCall(EPSSetOptionsPrefix(eps, "eig_"));
  PetscCall(EPSSetOperators(eps, K, M));
  PetscCall(EPSSetProblemType(eps, EPS_GHEP));
  PetscCall(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  PetscCall(EPSSetTarget(eps, 0.0));
  PetscCall(EPSSetDimensions(eps, 1, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(EPSSetTolerances(eps, 1e-10, 200));
  PetscCall(EPSGetST(eps, &st));
  PetscCall(STSetType(st, STSINVERT));
  PetscCall(STGetKSP(st, &ksp));
  PetscCall(SlumpKSPSetDirect(ksp));
  PetscCall(EPSSetFromOptions(eps));
  PetscCall(EPSSolve(eps));
  PetscCall(EPSGetConverged(eps, &nconv));
  PetscCheck(nconv >= 1, prob->comm, PETSC_ERR_NOT_CONVERGED, "SLEPc found no eigenvalue of the viscous operator (try -eig_ options)");
  PetscCall(EPSGetEigenvalue(eps, 0, &kr, &ki));
  *lambda1 = PetscRealPart(kr);
  PetscCall(EPSDestroy(&eps));
  PetscCall(MatDestroy(&K));
  PetscCall(MatDestroy(&M));
  PetscCall(MatDestroy(&A));
  PetscCall(VecDestroy(&X));
  PetscCall(ISDestroy(&isu));
  PetscCall(ISDestroy(&isp));
  PetscFunctionReturn(0);
}
