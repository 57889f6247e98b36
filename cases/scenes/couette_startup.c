/* Newtonian plane Couette start-up with a time-dependent wall velocity: the
 * check of time-dependent Dirichlet data and its time derivative (which also
 * enters the consistent initial conditions).
 * Gap 0 <= y <= H = 1, nu = eta/rho; at rest for t <= 0; the top plate
 * accelerates as V(t) = V0 (1 - exp(-t/tau)), the bottom one stays still.
 * Exact solution (separation of variables, w = u - y V(t)):
 *   u(y, t) = y V(t) + sum_n b_n(t) sin(n pi y),
 *   b_n(t)  = -c_n (V0/tau) (exp(-t/tau) - exp(-lambda_n t)) / (lambda_n - 1/tau),
 *   c_n = 2 (-1)^(n+1) / (n pi),  lambda_n = nu n^2 pi^2  (H = 1).
 * The series is summed to 4000 terms (tail below 1e-7).
 * Options: -startup_tau (default 0.05). */
#include "common.h"

typedef struct {
  PetscReal     V0, tau, rho;
  SlumpRheology rheo;
} StartupCtx;

static PetscErrorCode WallU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const StartupCtx *c = (const StartupCtx *)ctx;
  u[0]                = c->V0 * (1.0 - PetscExpReal(-t / c->tau));
  u[1]                = 0.0;
  return 0;
}

static PetscErrorCode WallU_t(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const StartupCtx *c = (const StartupCtx *)ctx;
  u[0]                = c->V0 / c->tau * PetscExpReal(-t / c->tau);
  u[1]                = 0.0;
  return 0;
}

static PetscErrorCode ExactU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const StartupCtx *c = (const StartupCtx *)ctx;
  PetscReal         eta, s = 0.0;
  PetscCall(SlumpRheologyGetParameter(c->rheo, "viscosity", &eta));
  const PetscReal nu = eta / c->rho, et = PetscExpReal(-t / c->tau);
  for (PetscInt n = 1; n <= 4000; ++n) {
    const PetscReal lam = nu * n * n * PETSC_PI * PETSC_PI, cn = 2.0 * ((n % 2) ? 1.0 : -1.0) / (n * PETSC_PI);
    s += -cn * (c->V0 / c->tau) * (et - PetscExpReal(-lam * t)) / (lam - 1.0 / c->tau) * PetscSinReal(n * PETSC_PI * x[1]);
  }
  u[0] = x[1] * c->V0 * (1.0 - et) + s;
  u[1] = 0.0;
  return 0;
}

static PetscErrorCode ExactP(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar p[], void *ctx)
{
  p[0] = 0.0;
  return 0;
}

PetscErrorCode SlumpSceneCreate_CouetteStartup(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  StartupCtx    *c;
  SlumpRheology  rheo;
  PetscReal      lower[2] = {0.0, 0.0}, upper[2] = {0.25, 1.0};
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->V0      = 1.0;
  c->tau     = 0.05;
  c->rho     = 1.0;
  PetscOptionsBegin(comm, NULL, "Scene couette_startup", "");
  PetscCall(PetscOptionsReal("-startup_tau", "Time scale of the plate's acceleration", "", c->tau, &c->tau, NULL));
  PetscCall(PetscOptionsReal("-density", "Density", "", c->rho, &c->rho, NULL));
  PetscOptionsEnd();
  PetscCheck(c->tau > 0, comm, PETSC_ERR_USER_INPUT, "-startup_tau must be positive; got %g", (double)c->tau);
  scene->steady    = PETSC_FALSE;
  scene->tfinal    = 0.2;
  scene->dtout     = 0.01;
  scene->mesh_n[0] = 2;
  scene->mesh_n[1] = 32;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_INERTIA));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  c->rheo = rheo;
  PetscCall(SlumpRheologySetType(rheo, SLUMP_RHEOLOGY_NEWTONIAN));
  PetscCall(SlumpProblemAddVelocityBC(prob, "plate_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "plate_top", "top", 0, NULL, WallU, WallU_t, c));
  PetscCall(SlumpSceneChannelEnds(prob));
  PetscCall(SlumpProblemSetInitialVelocity(prob, SlumpZeroVelocity, NULL));
  PetscCall(SlumpProblemSetExactSolution(prob, ExactU, ExactP, c));
  PetscCall(SlumpSceneAddParameter(scene, "tau", c->tau));
  PetscFunctionReturn(0);
}
