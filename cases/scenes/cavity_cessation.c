/* Cessation of the Bingham lid-driven cavity.
 * Unit square cavity (L = 1), rho = eta_p = 1, lid speed U = 1 on "top",
 * no slip on the other walls. The initial state is the steady creeping
 * (Stokes) flow with the lid moving, computed by KINSOL with continuation in
 * the regularisation; at t = 0 the lid stops and the enclosed flow decays to
 * rest (pressure fixed at one vertex). Bn = tau0 L/(eta_p U); any Bn > 0
 * has a moving initial state. -initial_flow newtonian starts from the
 * Newtonian cavity flow instead.
 * -cavity_lid uniform|regularised: u = U on the whole lid (the classic
 * set-up, corner singularities), or u = 16 U x^2 (1 - x)^2 (smooth, no
 * corner singularity). -cavity_convection: add rho (u . grad) u, Re = rho U
 * L / eta_p (off: the scene asks for inertia only).
 * The energy estimate needs the constant beta of ||u||_2 <= ||grad u||_1 /
 * beta for divergence-free vector fields in the square, which is not known
 * in closed form: no bound is printed (the driver says so). */
#include "common.h"

typedef struct {
  PetscReal U, L, lower[2], upper[2];
  PetscBool regularised, newtonian;
} CavityCtx;

static PetscErrorCode LidU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const CavityCtx *c = (const CavityCtx *)ctx;
  u[0]               = SlumpSceneLidVelocity(x[0], c->U, c->L, c->regularised);
  u[1]               = 0.0;
  return 0;
}

/* the steady creeping flow with the lid moving */
static PetscErrorCode ConfigureDriven(SlumpScene scene, SlumpProblem p0)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemSetEffects(p0, 0));
  PetscCall(SlumpProblemAddVelocityBC(p0, "wall_left", "left", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(p0, "wall_right", "right", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(p0, "wall_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(p0, "lid", "top", 0, NULL, LidU, NULL, scene->ctx)); /* last: the lid owns its corners */
  PetscFunctionReturn(0);
}

static PetscErrorCode InitialState(SlumpScene scene, SlumpProblem prob, Vec X)
{
  CavityCtx       *c = (CavityCtx *)scene->ctx;
  SlumpDiagnostics d;
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)X), "initial state: steady lid-driven flow of %s (KINSOL)\n", c->newtonian ? "a Newtonian fluid" : "the material"));
  PetscCall(SlumpSceneSteadyInitialState(scene, prob, c->lower, c->upper, ConfigureDriven, c->newtonian, X));
  PetscCall(SlumpProblemComputeDiagnostics(prob, 0.0, X, &d));
  PetscCall(SlumpSceneAddResult(scene, "u0_norm", PetscSqrtReal(2.0 * d.kinetic_energy)));
  PetscCall(SlumpSceneAddResult(scene, "yielded_fraction0", d.yielded_fraction));
  PetscFunctionReturn(0);
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  CavityCtx *c = (CavityCtx *)scene->ctx;
  PetscReal  tau0, etap;
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &etap));
  PetscCall(SlumpSceneAddResult(scene, "bn", tau0 * c->L / (etap * c->U)));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_CavityCessation(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  CavityCtx    *c;
  PetscReal     bn   = 1.0;
  PetscBool     conv = PETSC_FALSE;
  const char   *lids[] = {"uniform", "regularised"};
  PetscInt      lid    = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->U       = 1.0;
  c->L       = 1.0;
  PetscOptionsBegin(comm, NULL, "Scene cavity_cessation", "");
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0 L/(eta_p U) of the lid-driven initial flow", "", bn, &bn, NULL));
  PetscCall(PetscOptionsEList("-cavity_lid", "Lid velocity: uniform (u = U) or regularised (u = 16 U x^2 (1 - x)^2)", "", lids, 2, lids[lid], &lid, NULL));
  PetscCall(PetscOptionsBool("-cavity_convection", "Include convection rho (u . grad) u after the lid stops", "", conv, &conv, NULL));
  PetscOptionsEnd();
  PetscCall(SlumpSceneInitialFlowOption(comm, &c->newtonian));
  PetscCheck(bn > 0, comm, PETSC_ERR_USER_INPUT, "-bn must be positive; got %g", (double)bn);
  c->regularised          = lid == 1 ? PETSC_TRUE : PETSC_FALSE;
  SlumpSceneSetCessationDefaults(scene, 0.3, 0.005, 16, 16);
  c->lower[0] = c->lower[1] = 0.0;
  c->upper[0] = c->upper[1] = c->L;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, c->lower, c->upper));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_INERTIA | (conv ? SLUMP_EFFECT_CONVECTION : 0)));
  PetscCall(SlumpSceneSetBinghamDefaults(prob, bn * c->U / c->L));
  /* all walls at rest for t >= 0 */
  PetscCall(SlumpProblemAddVelocityBC(prob, "walls", "boundary", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  scene->initial    = InitialState;
  scene->results    = Results;
  scene->bound_beta = 0.0; /* not known for this geometry */
  PetscCall(SlumpSceneAddParameter(scene, "bn_option", bn));
  PetscCall(SlumpSceneAddParameter(scene, "lid_regularised", (PetscReal)c->regularised));
  PetscFunctionReturn(0);
}
