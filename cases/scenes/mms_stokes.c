/* Manufactured Stokes solution on the unit square (eta = 1):
 *   u = ( sin(pi x) cos(pi y), -cos(pi x) sin(pi y) ),  div u = 0,
 *   p = cos(pi x) cos(pi y),
 *   f = -div(eta gdot) + grad p = 2 pi^2 eta u + grad p.
 * Dirichlet u on bottom, top, left; the exact traction (-p I + eta gdot) n on
 * the right, which also fixes the pressure level (-mms_enclosed: Dirichlet
 * everywhere; the pressure is then fixed at one vertex). Taylor-Hood P2/P1 should
 * converge at order 3 (velocity, L2) and 2 (pressure, L2).
 *
 * -geometry axisymmetric (r = x, z = y, axis x = 0): the axisymmetric Stokes
 * flow of stream function psi = r^2 cos(pi r) sin(pi z),
 *   u_r = -pi r cos(pi r) cos(pi z),  u_z = (2 cos(pi r) - pi r sin(pi r)) sin(pi z),
 *   p = cos(pi r) cos(pi z),  f = -eta (vector Laplacian of u) + grad p,
 * divergence-free with the hoop term (div u = (1/r) d(r u_r)/dr + du_z/dz),
 * with u_r/r and the hoop stress 2 eta u_r/r non-zero everywhere; Dirichlet
 * on the bottom, top and right, u_r = 0 on the axis (the pressure fixed at
 * one vertex). Errors are in the r-weighted norm. */
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

static PetscErrorCode ExactUAxi(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const PetscReal r = x[0], z = x[1], pi = PETSC_PI;
  u[0] = -pi * r * PetscCosReal(pi * r) * PetscCosReal(pi * z);
  u[1] = (2.0 * PetscCosReal(pi * r) - pi * r * PetscSinReal(pi * r)) * PetscSinReal(pi * z);
  return 0;
}

/* momentum: -f, the source of the axisymmetric solution (r > 0 at the
   quadrature points; sin(pi r)/r is regular on the axis) */
static void SourceAxi(SLUMP_PW_ARGS, PetscScalar f0[])
{
  const PetscReal eta = PetscRealPart(constants[SLUMP_C_RHEO]), pi = PETSC_PI, r = x[0], z = x[1];
  const PetscReal sr = PetscSinReal(pi * r), cr = PetscCosReal(pi * r), sz = PetscSinReal(pi * z), cz = PetscCosReal(pi * z);
  f0[0] = pi * (2.0 * pi * pi * eta * r * cr + 3.0 * pi * eta * sr + sr) * cz;
  f0[1] = -pi * (3.0 * eta * sr / r + (-2.0 * pi * pi * eta * r * sr + 7.0 * pi * eta * cr - cr)) * sz;
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
  PetscBool     enclosed = PETSC_FALSE, axi = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Scene mms_stokes", "");
  PetscCall(PetscOptionsBool("-mms_enclosed", "Dirichlet on all four sides (enclosed flow: the pressure level is fixed at one vertex)", "", enclosed, &enclosed, NULL));
  PetscOptionsEnd();
  PetscCall(SlumpSceneGeometry(prob, comm, 0, &axi));
  scene->steady    = PETSC_TRUE;
  scene->mesh_n[0] = 8;
  scene->mesh_n[1] = 8;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, 0));
  if (axi) {
    PetscCall(SlumpProblemSetMomentumSource(prob, SourceAxi));
    PetscCall(SlumpProblemGetRheology(prob, &rheo));
    PetscCall(SlumpRheologySetType(rheo, SLUMP_RHEOLOGY_NEWTONIAN));
    PetscCall(SlumpProblemAddVelocityBC(prob, "bottom", "bottom", 0, NULL, ExactUAxi, NULL, NULL));
    PetscCall(SlumpProblemAddVelocityBC(prob, "top", "top", 0, NULL, ExactUAxi, NULL, NULL));
    PetscCall(SlumpProblemAddVelocityBC(prob, "right", "right", 0, NULL, ExactUAxi, NULL, NULL));
    PetscCall(SlumpProblemAddFreeSlipBC(prob, "left")); /* the axis */
    PetscCall(SlumpProblemSetExactSolution(prob, ExactUAxi, ExactP, NULL));
    PetscFunctionReturn(0);
  }
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
