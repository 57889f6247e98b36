/* Cessation of anti-plane Bingham flow in a square duct.
 * Cross-section [0, L]^2 (L = 1), w = 0 on the walls, rho = eta_p = 1. The
 * initial state is the steady flow driven by the pressure gradient G = 1
 * (the Mosolov problem of the duct scene, computed by KINSOL); at t = 0 the
 * gradient is removed and the flow stops in finite time.
 * Bn = tau0/(G L) < Bn_c = 1/(2 + sqrt(pi)) (above it the initial flow is at
 * rest); with -initial_flow newtonian the initial state is the Newtonian
 * flow under G and any Bn > 0 is accepted. Reported: bn_mean = tau0 L/(eta_p
 * W0), W0 the initial mean velocity.
 * Energy bound (scalar 2-D problem: beta = 2 sqrt(pi), the sharp L1-L2
 * isoperimetric constant; lambda1 = 2 pi^2/L^2):
 *   T_stop <= rho/(eta_p lambda1) ln(1 + eta_p lambda1 ||w0|| / (tau0 beta)). */
#include "common.h"

typedef struct {
  PetscReal L, G, lower[2], upper[2];
  PetscBool newtonian;
} DuctCessationCtx;

/* the steady flow driven by G (no inertia) */
static PetscErrorCode ConfigureDriven(SlumpScene scene, SlumpProblem p0)
{
  DuctCessationCtx *c = (DuctCessationCtx *)scene->ctx;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemSetFormulation(p0, SLUMP_FORMULATION_ANTIPLANE));
  PetscCall(SlumpProblemSetEffects(p0, SLUMP_EFFECT_BODY_FORCE));
  PetscCall(SlumpProblemSetBodyForce(p0, c->G, 0.0));
  PetscCall(SlumpProblemAddVelocityBC(p0, "walls", "boundary", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode InitialAndNorm(SlumpScene scene, SlumpProblem prob, Vec X)
{
  DuctCessationCtx *c = (DuctCessationCtx *)scene->ctx;
  SlumpDiagnostics  d;
  PetscReal         tau0, etap, area = c->L * c->L;
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)X), "initial state: steady duct flow of %s driven by G = %g (KINSOL)\n", c->newtonian ? "a Newtonian fluid" : "the material", (double)c->G));
  PetscCall(SlumpSceneSteadyInitialState(scene, prob, c->lower, c->upper, ConfigureDriven, c->newtonian, X));
  PetscCall(SlumpProblemComputeDiagnostics(prob, 0.0, X, &d));
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &etap));
  PetscCall(SlumpSceneAddResult(scene, "u0_norm", PetscSqrtReal(2.0 * d.kinetic_energy)));
  PetscCall(SlumpSceneAddResult(scene, "u0_mean", d.flow_rate / area));
  if (d.flow_rate > 0) PetscCall(SlumpSceneAddResult(scene, "bn_mean", tau0 * c->L / (etap * d.flow_rate / area)));
  PetscFunctionReturn(0);
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  DuctCessationCtx *c = (DuctCessationCtx *)scene->ctx;
  PetscReal         tau0, etap, u0 = 0.0, rho = 1.0;
  PetscBool         found;
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &etap));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-density", &rho, NULL));
  PetscCall(SlumpSceneAddResult(scene, "bn", tau0 / (c->G * c->L)));
  PetscCall(SlumpSceneGetResult(scene, "u0_norm", &u0, &found));
  if (tau0 > 0 && found && u0 > 0) {
    const PetscReal l1 = 2.0 * PETSC_PI * PETSC_PI / (c->L * c->L);
    PetscCall(SlumpSceneAddResult(scene, "t_stop_bound", rho / (etap * l1) * PetscLogReal(1.0 + etap * l1 * u0 / (tau0 * scene->bound_beta))));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_DuctCessation(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  DuctCessationCtx *c;
  PetscReal         bn = 0.1;
  const PetscReal   bnc = 1.0 / (2.0 + PetscSqrtReal(PETSC_PI));
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->L       = 1.0;
  c->G       = 1.0;
  PetscOptionsBegin(comm, NULL, "Scene duct_cessation", "");
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0/(G L) of the removed pressure gradient G", "", bn, &bn, NULL));
  PetscOptionsEnd();
  PetscCall(SlumpSceneInitialFlowOption(comm, &c->newtonian));
  if (c->newtonian) PetscCheck(bn > 0, comm, PETSC_ERR_USER_INPUT, "-bn must be positive; got %g", (double)bn);
  else PetscCheck(bn > 0 && bn < bnc, comm, PETSC_ERR_USER_INPUT, "-bn must lie in (0, %.6f) (at Bn >= 1/(2 + sqrt(pi)) the initial flow is at rest; -initial_flow newtonian allows any Bn > 0); got %g", (double)bnc, (double)bn);
  SlumpSceneSetCessationDefaults(scene, 0.3, 0.005, 16, 16);
  c->lower[0] = c->lower[1] = 0.0;
  c->upper[0] = c->upper[1] = c->L;
  PetscCall(SlumpProblemSetFormulation(prob, SLUMP_FORMULATION_ANTIPLANE));
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, c->lower, c->upper));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_INERTIA)); /* gradient removed */
  PetscCall(SlumpSceneSetBinghamDefaults(prob, bn * c->G * c->L));
  PetscCall(SlumpProblemAddVelocityBC(prob, "walls", "boundary", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  scene->initial          = InitialAndNorm;
  scene->results          = Results;
  scene->bound_beta       = 2.0 * PetscSqrtReal(PETSC_PI);
  scene->bound_norm_scale = 1.0;
  PetscCall(SlumpSceneAddParameter(scene, "bn_option", bn));
  PetscFunctionReturn(0);
}
