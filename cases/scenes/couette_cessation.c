/* Bingham plane Couette cessation (the demo; REFERENCES.md).
 * Gap 0 <= y <= H = 1, plate speed V = 1, eta_p = rho = 1: for t < 0 the top
 * plate moves and the steady profile is u = V y / H (uniform shear, fully
 * yielded whatever the yield stress); at t = 0 it stops. Bn = tau0 H/(eta_p V).
 * The flow stops in finite time; the energy estimate bounds the exact
 * stopping time: T_stop <= ln(1 + pi^2 / (2 sqrt(3) Bn)) / pi^2.
 * Regularised models creep instead; the arrest time is where the mean shear
 * rate falls below -arrest_mean_shear_rate (root-found by the integrator). */
#include "common.h"

typedef struct {
  PetscReal V, H;
} CouetteCtx;

static PetscErrorCode InitialU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const CouetteCtx *c = (const CouetteCtx *)ctx;
  u[0]                = c->V * x[1] / c->H;
  u[1]                = 0.0;
  return 0;
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  SlumpRheology rheo;
  PetscReal     tau0 = 0.0, etap, rho = 1.0;
  PetscBool     has;
  CouetteCtx   *c = (CouetteCtx *)scene->ctx;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologyGetParameter(rheo, "viscosity", &etap));
  PetscCall(SlumpRheologyHasParameter(rheo, "yield_stress", &has));
  if (has) PetscCall(SlumpRheologyGetParameter(rheo, "yield_stress", &tau0));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-density", &rho, NULL));
  if (tau0 > 0) {
    /* energy bound in the scene's units: time scale rho H^2 / eta_p */
    const PetscReal bn = tau0 * c->H / (etap * c->V);
    PetscCall(SlumpSceneAddResult(scene, "bn", bn));
    PetscCall(SlumpSceneAddResult(scene, "t_stop_bound", rho * c->H * c->H / etap * PetscLogReal(1.0 + PETSC_PI * PETSC_PI / (2.0 * PetscSqrtReal(3.0) * bn)) / (PETSC_PI * PETSC_PI)));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_CouetteCessation(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  CouetteCtx    *c;
  SlumpRheology  rheo;
  PetscReal      bn = 1.0, lower[2] = {0.0, 0.0}, upper[2];
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->V       = 1.0;
  c->H       = 1.0;
  PetscOptionsBegin(comm, NULL, "Scene couette_cessation", "");
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0 H / (eta_p V)", "", bn, &bn, NULL));
  PetscOptionsEnd();
  PetscCheck(bn >= 0, comm, PETSC_ERR_USER_INPUT, "-bn must be non-negative; got %g", (double)bn);
  scene->steady           = PETSC_FALSE;
  scene->tfinal           = 0.3;
  scene->dtout            = 0.01;
  scene->arrest_threshold = 1e-3;
  scene->mesh_n[0]        = 2;
  scene->mesh_n[1]        = 32;
  upper[0]                = 0.25 * c->H;
  upper[1]                = c->H;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_INERTIA));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologySetType(rheo, SLUMP_RHEOLOGY_PAPANASTASIOU));
  PetscCall(SlumpRheologySetParameter(rheo, "viscosity", 1.0));
  PetscCall(SlumpRheologySetParameter(rheo, "yield_stress", bn * 1.0 * c->V / c->H));
  PetscCall(SlumpRheologySetParameter(rheo, "m", 1e4));
  /* both plates at rest for t >= 0 */
  PetscCall(SlumpProblemAddVelocityBC(prob, "plate_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "plate_top", "top", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpSceneChannelEnds(prob));
  PetscCall(SlumpProblemSetInitialVelocity(prob, InitialU, c));
  scene->results = Results;
  PetscCall(SlumpSceneAddParameter(scene, "bn_option", bn));
  PetscFunctionReturn(0);
}
