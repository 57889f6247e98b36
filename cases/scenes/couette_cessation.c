/* Bingham plane Couette cessation (the demo; REFERENCES.md).
 * Gap 0 <= y <= H = 1, plate speed V = 1, eta_p = rho = 1: for t < 0 the top
 * plate moves and the steady profile is u = V y / H (uniform shear, fully
 * yielded whatever the yield stress); at t = 0 it stops. Bn = tau0 H/(eta_p V).
 * The flow stops in finite time; the energy estimate bounds the exact
 * stopping time: T_stop <= ln(1 + pi^2 / (2 sqrt(3) Bn)) / pi^2.
 * Regularised models creep instead; the arrest time is where the mean shear
 * rate falls below -arrest_mean_shear_rate (root-found by the integrator).
 * -couette_initial analytic|steady: the initial profile u = V y/H, or the
 * steady flow with the plate moving computed by KINSOL (same mesh, same
 * rheology, no inertia); both must give the same run. */
#include "common.h"

typedef struct {
  PetscReal V, H;
  PetscReal lower[2], upper[2];
} CouetteCtx;

static PetscErrorCode PlateU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  u[0] = ((const CouetteCtx *)ctx)->V;
  u[1] = 0.0;
  return 0;
}

/* The steady flow with the top plate moving (no inertia). */
static PetscErrorCode ConfigureDriven(SlumpScene scene, SlumpProblem p0)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemSetEffects(p0, 0));
  PetscCall(SlumpProblemAddVelocityBC(p0, "plate_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(p0, "plate_top", "top", 0, NULL, PlateU, NULL, scene->ctx));
  PetscCall(SlumpSceneChannelEnds(p0));
  PetscFunctionReturn(0);
}

static PetscErrorCode SteadyInitial(SlumpScene scene, SlumpProblem prob, Vec X)
{
  CouetteCtx *c = (CouetteCtx *)scene->ctx;
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)X), "initial state: steady flow with the plate moving (KINSOL)\n"));
  PetscCall(SlumpSceneSteadyInitialState(scene, prob, c->lower, c->upper, ConfigureDriven, PETSC_FALSE, X));
  PetscFunctionReturn(0);
}

static PetscErrorCode InitialU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const CouetteCtx *c = (const CouetteCtx *)ctx;
  u[0]                = c->V * x[1] / c->H;
  u[1]                = 0.0;
  return 0;
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  PetscReal   tau0, etap, rho = 1.0;
  CouetteCtx *c = (CouetteCtx *)scene->ctx;
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &etap));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-density", &rho, NULL));
  if (tau0 > 0) {
    /* energy bound in the scene's units: time scale rho H^2 / eta_p */
    const PetscReal bn = tau0 * c->H / (etap * c->V);
    PetscCall(SlumpSceneAddResult(scene, "bn", bn));
    PetscCall(SlumpSceneAddResult(scene, "t_stop_bound", rho * c->H * c->H / etap * PetscLogReal(1.0 + PETSC_PI * PETSC_PI / (2.0 * PetscSqrtReal(3.0) * bn)) / (PETSC_PI * PETSC_PI)));
  }
  PetscFunctionReturn(0);
}

/* the exact model's profile at t = 0 */
static PetscReal ExactU0(PetscReal y, void *ctx)
{
  const CouetteCtx *c = (const CouetteCtx *)ctx;
  return c->V * y / c->H;
}

static PetscErrorCode ExactArrest(SlumpScene scene, SlumpProblem prob, SlumpDiagnosticKind diag, PetscReal threshold, PetscReal *t_stop, PetscReal *t_arrest)
{
  CouetteCtx *c = (CouetteCtx *)scene->ctx;
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneStripExact(scene, prob, c->H, ExactU0, c, 0.0, diag, threshold, t_stop, t_arrest));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_CouetteCessation(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  CouetteCtx    *c;
  PetscReal      bn = 1.0, lower[2] = {0.0, 0.0}, upper[2];
  const char    *kinds[] = {"analytic", "steady"};
  PetscInt       kind    = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->V       = 1.0;
  c->H       = 1.0;
  PetscOptionsBegin(comm, NULL, "Scene couette_cessation", "");
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0 H / (eta_p V)", "", bn, &bn, NULL));
  PetscCall(PetscOptionsEList("-couette_initial", "Initial state: analytic (u = V y/H) or steady (KINSOL, plate moving)", "", kinds, 2, kinds[kind], &kind, NULL));
  PetscOptionsEnd();
  PetscCheck(bn >= 0, comm, PETSC_ERR_USER_INPUT, "-bn must be non-negative; got %g", (double)bn);
  SlumpSceneSetCessationDefaults(scene, 0.3, 0.01, 2, 32);
  upper[0]                = 0.25 * c->H;
  upper[1]                = c->H;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  c->lower[0] = lower[0];
  c->lower[1] = lower[1];
  c->upper[0] = upper[0];
  c->upper[1] = upper[1];
  if (kind == 1) scene->initial = SteadyInitial;
  /* 1-D strip: beta = 2/sqrt(H), norms per unit length along the strip */
  scene->bound_beta       = 2.0 / PetscSqrtReal(c->H);
  scene->bound_norm_scale = 1.0 / PetscSqrtReal(upper[0] - lower[0]);
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_INERTIA));
  PetscCall(SlumpSceneSetBinghamDefaults(prob, bn * 1.0 * c->V / c->H));
  /* both plates at rest for t >= 0 */
  PetscCall(SlumpProblemAddVelocityBC(prob, "plate_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "plate_top", "top", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpSceneChannelEnds(prob));
  PetscCall(SlumpProblemSetInitialVelocity(prob, InitialU, c));
  scene->results      = Results;
  scene->exact_arrest = ExactArrest;
  PetscCall(SlumpSceneAddParameter(scene, "bn_option", bn));
  PetscFunctionReturn(0);
}
