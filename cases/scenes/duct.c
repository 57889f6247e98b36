/* Anti-plane Bingham flow in a square duct: the Mosolov problem (the classic
 * viscoplastic benchmark; Rheolef ships it as mosolov_*).
 * One out-of-plane velocity w(x, y) on the cross-section [0, L]^2, w = 0 on
 * the walls, driven by a pressure gradient G:  -div(eta(|grad w|) grad w) = G.
 * Scaling: lengths L, stresses G L, velocities G L^2/eta_p; Bn = tau0/(G L).
 * Flow stops exactly when tau0 >= G/h, with h = (2 + sqrt(pi))/L the Cheeger
 * constant of the square: Bn_c = 1/(2 + sqrt(pi)) = 0.265079.
 * Results: flow rate Q = int w, plug (unyielded) area, and for reference the
 * Newtonian flow rate (series) and Bn_c. Options: -bn (default 0.1). */
#include "common.h"

typedef struct {
  PetscReal L, G;
} DuctCtx;

/* Newtonian square duct, eta = 1: Q = 64 G L^4/pi^6 sum_{m,n odd} 1/(m^2 n^2 (m^2 + n^2)) */
static PetscReal NewtonianFlowRate(PetscReal G, PetscReal L)
{
  PetscReal s = 0.0;
  for (PetscInt m = 1; m < 400; m += 2)
    for (PetscInt n = 1; n < 400; n += 2) s += 1.0 / ((PetscReal)m * m * n * n * (m * m + n * n));
  return 64.0 * G * PetscPowReal(L, 4) / PetscPowReal(PETSC_PI, 6) * s;
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  DuctCtx         *c = (DuctCtx *)scene->ctx;
  SlumpDiagnostics d;
  PetscReal        tau0, etap;
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &etap));
  PetscCall(SlumpProblemComputeDiagnostics(prob, t, X, &d));
  PetscCall(SlumpSceneAddResult(scene, "bn", tau0 / (c->G * c->L)));
  PetscCall(SlumpSceneAddResult(scene, "bn_critical", 1.0 / (2.0 + PetscSqrtReal(PETSC_PI))));
  PetscCall(SlumpSceneAddResult(scene, "flow_rate", d.flow_rate));
  PetscCall(SlumpSceneAddResult(scene, "flow_rate_newtonian", NewtonianFlowRate(c->G, c->L) / etap));
  PetscCall(SlumpSceneAddResult(scene, "plug_area", (1.0 - d.yielded_fraction) * c->L * c->L));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_Duct(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  DuctCtx      *c;
  PetscReal     bn = 0.1, lower[2] = {0.0, 0.0}, upper[2];
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->L       = 1.0;
  c->G       = 1.0;
  PetscOptionsBegin(comm, NULL, "Scene duct", "");
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0/(G L)", "", bn, &bn, NULL));
  PetscOptionsEnd();
  PetscCheck(bn >= 0, comm, PETSC_ERR_USER_INPUT, "-bn must be non-negative; got %g", (double)bn);
  scene->steady    = PETSC_TRUE;
  scene->mesh_n[0] = 16;
  scene->mesh_n[1] = 16;
  upper[0]         = c->L;
  upper[1]         = c->L;
  PetscCall(SlumpProblemSetFormulation(prob, SLUMP_FORMULATION_ANTIPLANE));
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_BODY_FORCE));
  PetscCall(SlumpProblemSetBodyForce(prob, c->G, 0.0));
  PetscCall(SlumpSceneSetBinghamDefaults(prob, bn * c->G * c->L));
  PetscCall(SlumpProblemAddVelocityBC(prob, "walls", "boundary", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  scene->results          = Results;
  scene->bound_beta       = 2.0 * PetscSqrtReal(PETSC_PI); /* scalar 2-D: sharp L1-L2 isoperimetric constant */
  scene->bound_norm_scale = 1.0;
  PetscCall(SlumpSceneAddParameter(scene, "bn_option", bn));
  PetscFunctionReturn(0);
}
