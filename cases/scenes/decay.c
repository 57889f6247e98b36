/* Newtonian flow between plates y = 0 and y = L decaying from u = sin(pi y/L):
 *   u(y, t) = sin(pi y / L) exp(-pi^2 nu t / L^2),  nu = eta / rho,  p = 0.
 * Fully developed (v = 0, zero normal traction at the ends). The order-of-
 * accuracy check in time for fixed-step BDF2 and adaptive IDA.
 * -geometry axisymmetric: the pipe of radius L about the axis y = 0 (r = y),
 *   u(r, t) = J0(j1 r / L) exp(-j1^2 nu t / L^2),  j1 = 2.40483 (J0's first zero). */
#include "common.h"
#include <math.h> /* j0: POSIX Bessel function */

typedef struct {
  PetscReal     L, rho;
  PetscBool     axi; /* a pipe of radius L decaying from J0(j1 r / L) */
  SlumpRheology rheo;
} DecayCtx;

#define J0_FIRST_ZERO 2.404825557695773

static PetscErrorCode ExactU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const DecayCtx *c = (const DecayCtx *)ctx;
  PetscReal       eta;
  PetscCall(SlumpRheologyGetParameter(c->rheo, "viscosity", &eta));
  if (c->axi) u[0] = j0(J0_FIRST_ZERO * x[1] / c->L) * PetscExpReal(-J0_FIRST_ZERO * J0_FIRST_ZERO * eta / c->rho * t / (c->L * c->L));
  else u[0] = PetscSinReal(PETSC_PI * x[1] / c->L) * PetscExpReal(-PETSC_PI * PETSC_PI * eta / c->rho * t / (c->L * c->L));
  u[1] = 0.0;
  return 0;
}

static PetscErrorCode ExactP(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar p[], void *ctx)
{
  p[0] = 0.0;
  return 0;
}

PetscErrorCode SlumpSceneCreate_Decay(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  DecayCtx      *c;
  SlumpRheology  rheo;
  PetscReal      lower[2] = {0.0, 0.0}, upper[2];
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->L       = 1.0;
  c->rho     = 1.0;
  PetscOptionsBegin(comm, NULL, "Scene decay", "");
  PetscCall(PetscOptionsReal("-density", "Density", "", c->rho, &c->rho, NULL));
  PetscOptionsEnd();
  PetscCall(SlumpSceneGeometry(prob, comm, 1, &c->axi));
  scene->steady    = PETSC_FALSE;
  scene->tfinal    = 0.1;
  scene->dtout     = 0.01;
  scene->mesh_n[0] = 2;
  scene->mesh_n[1] = 32;
  upper[0]         = 0.25 * c->L;
  upper[1]         = c->L;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_INERTIA));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  c->rheo = rheo;
  PetscCall(SlumpRheologySetType(rheo, SLUMP_RHEOLOGY_NEWTONIAN));
  if (c->axi) PetscCall(SlumpProblemAddFreeSlipBC(prob, "bottom")); /* the axis: u_r = 0 */
  else PetscCall(SlumpProblemAddVelocityBC(prob, "wall_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "wall_top", "top", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpSceneChannelEnds(prob));
  PetscCall(SlumpProblemSetInitialVelocity(prob, ExactU, c));
  PetscCall(SlumpProblemSetExactSolution(prob, ExactU, ExactP, c));
  PetscCall(SlumpSceneAddParameter(scene, "L", c->L));
  PetscFunctionReturn(0);
}
