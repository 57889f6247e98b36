/* Bingham plane Poiseuille cessation (REFERENCES.md).
 * Channel -H <= y <= H (H = 1), rho = eta_p = 1: the steady Bingham flow
 * driven by G = 1 (computed by KINSOL, with continuation in the
 * regularisation from -steady_continuation_start, default 1e2) is the
 * initial state; at t = 0 the driving force is removed and the flow stops in
 * finite time. Bn = tau0/(G H) = plug half-width of the initial flow, so
 * Bn < 1. With -initial_flow newtonian the initial state is the Newtonian
 * flow under G (any Bn > 0). Reported: bn_mean = tau0 H/(eta_p U0), U0 the
 * initial mean velocity (flux through "right" / 2H). Energy bound:
 *   T_stop <= (1/l1) ln(1 + l1 ||u0|| / (tau0 beta)),  l1 = pi^2/(2H)^2,
 *   beta = 2/sqrt(2H), ||u0|| the L2 norm across the channel
 * (= (4/pi^2) ln(1 + pi^2 ||u0|| / (4 sqrt(2) Bn)) for H = G = 1).
 * -geometry axisymmetric: the pipe of radius R = H about the axis y = 0
 * (r = y, u_r = 0 on the axis); Bn = 2 tau0/(G R), the plug radius of the
 * initial flow over R; u0_mean = 2 Q/R^2 (Q per radian). Energy bound
 * with the pipe's l1 = j1^2/R^2 (j1 = 2.40483) and beta = 2 sqrt(pi) (the
 * sharp L1 Sobolev inequality on the disc), ||u0|| over the cross-section.
 * The 1-D exact reference is planar: -method exact gives the pipe's
 * stopping time. */
#include "common.h"

typedef struct {
  PetscReal H, G, lower[2], upper[2];
  PetscBool axi;       /* a pipe of radius H */
  PetscBool newtonian; /* initial flow of a Newtonian fluid */
  PetscReal tau0, eta; /* for the exact profile */
} CessationCtx;

/* The steady flow driven by G (no inertia). */
static PetscErrorCode ConfigureDriven(SlumpScene scene, SlumpProblem p0)
{
  CessationCtx *c = (CessationCtx *)scene->ctx;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemSetEffects(p0, SLUMP_EFFECT_BODY_FORCE));
  PetscCall(SlumpProblemSetBodyForce(p0, c->G, 0.0));
  if (c->axi) PetscCall(SlumpProblemAddFreeSlipBC(p0, "bottom")); /* the axis */
  else PetscCall(SlumpProblemAddVelocityBC(p0, "wall_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(p0, "wall_top", "top", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpSceneChannelEnds(p0));
  PetscFunctionReturn(0);
}

static PetscErrorCode SteadyInitial(SlumpScene scene, SlumpProblem prob, Vec X)
{
  CessationCtx *c = (CessationCtx *)scene->ctx;
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)X), "initial state: steady driven flow of %s (KINSOL)\n", c->newtonian ? "a Newtonian fluid" : "the material"));
  PetscCall(SlumpSceneSteadyInitialState(scene, prob, c->lower, c->upper, ConfigureDriven, c->newtonian, X));
  PetscFunctionReturn(0);
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  CessationCtx *c = (CessationCtx *)scene->ctx;
  PetscReal     tau0, etap;
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &etap));
  PetscCall(SlumpSceneAddResult(scene, "bn", (c->axi ? 2.0 : 1.0) * tau0 / (c->G * c->H)));
  if (tau0 > 0 && scene->nresult && c->H > 0 && !c->axi) {
    /* analytic bound with the initial state's norm across the channel */
    const PetscReal L = 2.0 * c->H, l1 = PETSC_PI * PETSC_PI / (L * L), beta = 2.0 / PetscSqrtReal(L);
    PetscReal       u0 = 0.0;
    PetscBool       found;
    PetscCall(SlumpSceneGetResult(scene, "u0_norm", &u0, &found));
    if (found && u0 > 0) PetscCall(SlumpSceneAddResult(scene, "t_stop_bound", 1.0 / (etap * l1) * PetscLogReal(1.0 + etap * l1 * u0 / (tau0 * beta))));
  }
  if (tau0 > 0 && scene->nresult && c->axi) {
    /* the pipe: l1 = j1^2/R^2 (J0's first zero), beta = 2 sqrt(pi) (the
       sharp L1 Sobolev inequality on the cross-section), ||u0|| the L2 norm
       over the disc, sqrt(2 pi) x the per-radian norm u0_norm */
    const PetscReal j1 = 2.404825557695773, l1 = j1 * j1 / (c->H * c->H), beta = 2.0 * PetscSqrtReal(PETSC_PI);
    PetscReal       u0 = 0.0;
    PetscBool       found;
    PetscCall(SlumpSceneGetResult(scene, "u0_norm", &u0, &found));
    u0 *= PetscSqrtReal(2.0 * PETSC_PI);
    if (found && u0 > 0) PetscCall(SlumpSceneAddResult(scene, "t_stop_bound", 1.0 / (etap * l1) * PetscLogReal(1.0 + etap * l1 * u0 / (tau0 * beta))));
  }
  PetscFunctionReturn(0);
}

/* the initial norm, recorded before the run (the estimate needs ||u0||) */
static PetscErrorCode InitialAndNorm(SlumpScene scene, SlumpProblem prob, Vec X)
{
  CessationCtx    *c = (CessationCtx *)scene->ctx;
  SlumpDiagnostics d;
  PetscReal        tau0, etap;
  PetscFunctionBeginUser;
  PetscCall(SteadyInitial(scene, prob, X));
  PetscCall(SlumpProblemComputeDiagnostics(prob, 0.0, X, &d));
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &etap));
  {
    /* the mean velocity over the section: Q/(2H), or (pipe, Q per radian) 2Q/R^2 */
    const PetscReal umean = c->axi ? 2.0 * d.flow_rate / (c->H * c->H) : d.flow_rate / (2.0 * c->H);
    PetscCall(SlumpSceneAddResult(scene, "u0_norm", PetscSqrtReal(2.0 * d.kinetic_energy) / PetscSqrtReal(c->upper[0] - c->lower[0])));
    PetscCall(SlumpSceneAddResult(scene, "u0_mean", umean));
    if (d.flow_rate > 0) PetscCall(SlumpSceneAddResult(scene, "bn_mean", tau0 * c->H / (etap * umean)));
  }
  PetscFunctionReturn(0);
}

/* the exact model's initial profile (steady Bingham or Newtonian flow under
   G, REFERENCES.md) on 0 < y' < 2H, y = y' - H */
static PetscReal ExactU0(PetscReal yy, void *ctx)
{
  const CessationCtx *c = (const CessationCtx *)ctx;
  const PetscReal     y = PetscAbsReal(yy - c->H), y0 = c->newtonian ? 0.0 : c->tau0 / c->G;
  if (y <= y0) return c->G * (c->H - y0) * (c->H - y0) / (2.0 * c->eta);
  return c->G * (c->H * c->H - y * y) / (2.0 * c->eta) - (c->newtonian ? 0.0 : c->tau0 * (c->H - y) / c->eta);
}

static PetscErrorCode ExactArrest(SlumpScene scene, SlumpProblem prob, SlumpDiagnosticKind diag, PetscReal threshold, PetscReal *t_stop, PetscReal *t_arrest)
{
  CessationCtx *c = (CessationCtx *)scene->ctx;
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneYieldParameters(prob, &c->tau0, &c->eta));
  PetscCall(SlumpSceneStripExact(scene, prob, 2.0 * c->H, ExactU0, c, c->newtonian ? 1.0 : 0.0, diag, threshold, t_stop, t_arrest));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_PoiseuilleCessation(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  CessationCtx *c;
  PetscReal     bn = 0.5;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->H       = 1.0;
  c->G       = 1.0;
  PetscOptionsBegin(comm, NULL, "Scene poiseuille_cessation", "");
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0/(G H) (plug half-width of the initial flow)", "", bn, &bn, NULL));
  PetscOptionsEnd();
  PetscCall(SlumpSceneInitialFlowOption(comm, &c->newtonian));
  if (c->newtonian) PetscCheck(bn > 0, comm, PETSC_ERR_USER_INPUT, "-bn must be positive; got %g", (double)bn);
  else PetscCheck(bn > 0 && bn < 1, comm, PETSC_ERR_USER_INPUT, "-bn must lie in (0, 1) (at Bn >= 1 the initial flow is at rest; -initial_flow newtonian allows any Bn > 0); got %g", (double)bn);
  PetscCall(SlumpSceneGeometry(prob, comm, 1, &c->axi));
  SlumpSceneSetCessationDefaults(scene, 0.5, 0.01, 2, c->axi ? 16 : 32);
  c->lower[0]             = 0.0;
  c->lower[1]             = c->axi ? 0.0 : -c->H;
  c->upper[0]             = 0.25;
  c->upper[1]             = c->H;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, c->lower, c->upper));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_INERTIA)); /* driving removed */
  PetscCall(SlumpSceneSetBinghamDefaults(prob, (c->axi ? 0.5 : 1.0) * bn * c->G * c->H));
  if (c->axi) PetscCall(SlumpProblemAddFreeSlipBC(prob, "bottom"));
  else PetscCall(SlumpProblemAddVelocityBC(prob, "wall_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "wall_top", "top", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpSceneChannelEnds(prob));
  PetscCall(SlumpProblemSetFlowRateBoundary(prob, "right"));
  scene->initial          = InitialAndNorm;
  scene->results          = Results;
  scene->exact_arrest     = c->axi ? NULL : ExactArrest;
  scene->bound_beta       = c->axi ? 2.0 * PetscSqrtReal(PETSC_PI) : 2.0 / PetscSqrtReal(2.0 * c->H);
  scene->bound_norm_scale = (c->axi ? PetscSqrtReal(2.0 * PETSC_PI) : 1.0) / PetscSqrtReal(c->upper[0] - c->lower[0]);
  PetscCall(SlumpSceneAddParameter(scene, "bn_option", bn));
  PetscFunctionReturn(0);
}
