/* Manufactured Stokes solution on the unit square (eta = 1):
 *   u = ( sin(pi x) cos(pi y), -cos(pi x) sin(pi y) ),  div u = 0,
 *   p = cos(pi x) cos(pi y),
 *   f = -div(eta gdot) + grad p = 2 pi^2 eta u + grad p.
 * Dirichlet u on bottom, top, left; the exact traction (-p I + eta gdot) n on
 * the right, which also fixes the pressure level (-mms_enclosed: Dirichlet
 * everywhere; the pressure is then fixed at one vertex). Taylor-Hood P2/P1 should
 * converge at order 3 (velocity, L2) and 2 (pressure, L2). */
#include "common.h"

static PetscErrorCode ExactU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  u[0] = PetscSinReal(PETSC_PI * x[0]) * PetscCosReal(PETSC_PI * x[1]);
  u[1] = -PetscCosReal(PETSC_PI * x[0]) * PetscSinReal(PETSC_PI * x[1]);
  return 0;
}

static PetscErrorCode ExactP(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar p[], void *ctx)
{
  p[0] = PetscCosReal(PETSC_PI * x[0]) * PetscCosReal(PETSC_PI * x[1]);
  return 0;
}

/* momentum: -f (no inertia) */
static void Source(SLUMP_PW_ARGS, PetscScalar f0[])
{
  const PetscReal eta = PetscRealPart(constants[SLUMP_C_RHEO]), pi = PETSC_PI;
  const PetscReal sx = PetscSinReal(pi * x[0]), cx = PetscCosReal(pi * x[0]), sy = PetscSinReal(pi * x[1]), cy = PetscCosReal(pi * x[1]);
  f0[0] = -(2 * pi * pi * eta * sx * cy - pi * sx * cy);
  f0[1] = -(-2 * pi * pi * eta * cx * sy - pi * cx * sy);
}

/* boundary: -t, t = (-p I + eta gdot) n */
static void Traction(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, const PetscReal x[], const PetscReal n[], PetscInt numConstants, const PetscScalar constants[], PetscScalar f0[])
{
  const PetscReal eta = PetscRealPart(constants[SLUMP_C_RHEO]), pi = PETSC_PI;
  const PetscReal sx = PetscSinReal(pi * x[0]), cx = PetscCosReal(pi * x[0]), sy = PetscSinReal(pi * x[1]), cy = PetscCosReal(pi * x[1]);
  const PetscReal p = cx * cy;
  /* grad u: du/dx, du/dy, dv/dx, dv/dy */
  const PetscReal ux = pi * cx * cy, uy = -pi * sx * sy, vx = pi * sx * sy, vy = -pi * cx * cy;
  const PetscReal s00 = -p + 2 * eta * ux, s01 = eta * (uy + vx), s11 = -p + 2 * eta * vy;
  f0[0] = -(s00 * n[0] + s01 * n[1]);
  f0[1] = -(s01 * n[0] + s11 * n[1]);
}

PetscErrorCode SlumpSceneCreate_MMSStokes(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  SlumpRheology rheo;
  PetscReal     lower[2] = {0.0, 0.0}, upper[2] = {1.0, 1.0};
  PetscBool     enclosed = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Scene mms_stokes", "");
  PetscCall(PetscOptionsBool("-mms_enclosed", "Dirichlet on all four sides (enclosed flow: the pressure level is fixed at one vertex)", "", enclosed, &enclosed, NULL));
  PetscOptionsEnd();
  scene->steady    = PETSC_TRUE;
  scene->mesh_n[0] = 8;
  scene->mesh_n[1] = 8;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, 0));
  PetscCall(SlumpProblemSetMomentumSource(prob, Source));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologySetType(rheo, SLUMP_RHEOLOGY_NEWTONIAN));
  PetscCall(SlumpProblemAddVelocityBC(prob, "bottom", "bottom", 0, NULL, ExactU, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "top", "top", 0, NULL, ExactU, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "left", "left", 0, NULL, ExactU, NULL, NULL));
  if (enclosed) PetscCall(SlumpProblemAddVelocityBC(prob, "right", "right", 0, NULL, ExactU, NULL, NULL));
  else PetscCall(SlumpProblemAddTractionBC(prob, "right", Traction));
  PetscCall(SlumpProblemSetExactSolution(prob, ExactU, ExactP, NULL));
  PetscFunctionReturn(0);
}
