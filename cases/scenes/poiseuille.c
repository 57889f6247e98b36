/* Steady Bingham and Herschel-Bulkley plane Poiseuille flow (REFERENCES.md).
 * Channel |y| <= H, driven by a pressure gradient G = -dp/dx applied as a
 * body force; fully developed: no slip on the walls, v = 0 and zero normal
 * traction at inlet/outlet (so p = 0). Plug half-width y0 = tau0/G;
 *   y0 <= |y| <= H: u = G (H^2 - y^2)/(2 eta_p) - tau0 (H - |y|)/eta_p,
 *   plug:           u = G (H - y0)^2 / (2 eta_p).
 * Herschel-Bulkley (tau0 + K ||gdot||^n), |y| >= y0:
 *   u = n/(n+1) / (G K^(1/n)) [(G H - tau0)^((n+1)/n) - (G |y| - tau0)^((n+1)/n)],
 * and the same expression at |y| = y0 in the plug (n = 1 is Bingham).
 * Options: -bn (= y0/H = tau0/(G H), default 0.3), -channel_length,
 * -half_channel (0 <= y <= H with free slip, the symmetry plane, at y = 0).
 * -geometry axisymmetric: the pipe of radius R = H about the axis y = 0
 * (r = y, u_r = 0 on the axis), shear stress G r / 2: Bn = r0/R = 2 tau0/(G R)
 * the plug radius over R, and (Buckingham-Reiner)
 *   r0 <= r <= R: u = G (R^2 - r^2)/(4 eta_p) - tau0 (R - r)/eta_p,
 * the channel's profile with G/2 (likewise for Herschel-Bulkley). Results:
 * plug_radius (from the yielded volume fraction 1 - (r0/R)^2) and the flow
 * rate per radian int u r dr, with their exact values. */
#include "common.h"

typedef struct {
  PetscReal     G, H;
  PetscBool     axi;  /* a pipe of radius H (the shear stress is G r / 2) */
  SlumpRheology rheo; /* the yield stress and viscosity in force after options */
} PoiseuilleCtx;

/* tau0, K (or eta_p) and n (1 for Bingham) of the model in force. */
static PetscErrorCode YieldParameters(SlumpRheology rheo, PetscReal *tau0, PetscReal *K, PetscReal *n)
{
  PetscBool has;
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyHasParameter(rheo, "consistency", &has));
  if (has) {
    PetscCall(SlumpRheologyGetParameter(rheo, "consistency", K));
    PetscCall(SlumpRheologyGetParameter(rheo, "n", n));
  } else {
    PetscCall(SlumpRheologyGetParameter(rheo, "viscosity", K));
    *n = 1.0;
  }
  PetscCall(SlumpRheologyHasParameter(rheo, "yield_stress", &has));
  *tau0 = 0.0;
  if (has) PetscCall(SlumpRheologyGetParameter(rheo, "yield_stress", tau0));
  PetscFunctionReturn(0);
}

static PetscErrorCode ExactU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const PoiseuilleCtx *c = (const PoiseuilleCtx *)ctx;
  PetscReal            tau0, K, n;
  PetscCall(YieldParameters(c->rheo, &tau0, &K, &n));
  /* the pipe's stress G r / 2 is the channel's with G / 2 */
  const PetscReal G = c->axi ? 0.5 * c->G : c->G, y0 = tau0 / G, ay = PetscMax(PetscAbsReal(x[1]), y0), e = (n + 1.0) / n;
  if (y0 >= c->H) u[0] = 0.0;
  else u[0] = n / (n + 1.0) / (G * PetscPowReal(K, 1.0 / n)) * (PetscPowReal(G * c->H - tau0, e) - PetscPowReal(G * ay - tau0, e));
  u[1] = 0.0;
  return 0;
}

static PetscErrorCode ExactP(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar p[], void *ctx)
{
  p[0] = 0.0;
  return 0;
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  PoiseuilleCtx   *c = (PoiseuilleCtx *)scene->ctx;
  SlumpDiagnostics d;
  PetscReal        tau0, K, n;
  PetscFunctionBeginUser;
  PetscCall(YieldParameters(c->rheo, &tau0, &K, &n));
  PetscCall(SlumpProblemComputeDiagnostics(prob, t, X, &d));
  if (c->axi) {
    /* unyielded share of the pipe's volume = (r0 / R)^2, r0 = 2 tau0 / G;
       flow rate per radian int_0^R u r dr (Buckingham-Reiner for Bingham),
       the exact one by Simpson's rule on the exact profile */
    const PetscInt N = 4000;
    PetscReal      q = 0.0;
    for (PetscInt i = 0; i <= N; ++i) {
      const PetscReal r = c->H * i / N, x[2] = {0.0, r};
      PetscScalar     u[2] = {0.0, 0.0};
      PetscCall(ExactU(2, t, x, 2, u, c));
      q += (i == 0 || i == N ? 1.0 : (i % 2 ? 4.0 : 2.0)) * PetscRealPart(u[0]) * r;
    }
    PetscCall(SlumpSceneAddResult(scene, "plug_radius", PetscSqrtReal(PetscMax(1.0 - d.yielded_fraction, 0.0)) * c->H));
    PetscCall(SlumpSceneAddResult(scene, "plug_radius_exact", PetscMin(2.0 * tau0 / c->G, c->H)));
    PetscCall(SlumpSceneAddResult(scene, "flow_rate", d.flow_rate));
    PetscCall(SlumpSceneAddResult(scene, "flow_rate_exact", q * c->H / (3.0 * N)));
  } else {
    /* unyielded share of the channel = y0 / H */
    PetscCall(SlumpSceneAddResult(scene, "plug_half_width", (1.0 - d.yielded_fraction) * c->H));
    PetscCall(SlumpSceneAddResult(scene, "plug_half_width_exact", PetscMin(tau0 / c->G, c->H)));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_Poiseuille(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  PoiseuilleCtx *c;
  SlumpRheology  rheo;
  PetscReal      bn = 0.3, L = 0.5, lower[2], upper[2];
  PetscBool      half = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->G       = 1.0;
  c->H       = 1.0;
  PetscOptionsBegin(comm, NULL, "Scene poiseuille", "");
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0/(G H) = plug half-width / H", "", bn, &bn, NULL));
  PetscCall(PetscOptionsReal("-channel_length", "Channel length", "", L, &L, NULL));
  PetscCall(PetscOptionsBool("-half_channel", "Half channel 0 <= y <= H, free slip on the symmetry plane y = 0", "", half, &half, NULL));
  PetscOptionsEnd();
  PetscCheck(bn >= 0, comm, PETSC_ERR_USER_INPUT, "-bn must be non-negative; got %g", (double)bn);
  PetscCheck(L > 0, comm, PETSC_ERR_USER_INPUT, "-channel_length must be positive; got %g", (double)L);
  /* axisymmetric: a pipe of radius H about the axis y = 0 (r = y) */
  PetscCall(SlumpSceneGeometry(prob, comm, 1, &c->axi));
  if (c->axi) half = PETSC_TRUE;
  scene->steady    = PETSC_TRUE;
  scene->mesh_n[0] = 4;
  scene->mesh_n[1] = half ? 16 : 32;
  lower[0]         = 0.0;
  lower[1]         = half ? 0.0 : -c->H;
  upper[0]         = L;
  upper[1]         = c->H;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_BODY_FORCE));
  PetscCall(SlumpProblemSetBodyForce(prob, c->G, 0.0));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  c->rheo = rheo;
  PetscCall(SlumpSceneSetBinghamDefaults(prob, (c->axi ? 0.5 : 1.0) * bn * c->G * c->H));
  if (half) PetscCall(SlumpProblemAddFreeSlipBC(prob, "bottom"));
  else PetscCall(SlumpProblemAddVelocityBC(prob, "wall_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "wall_top", "top", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpSceneChannelEnds(prob));
  PetscCall(SlumpProblemSetFlowRateBoundary(prob, "right"));
  PetscCall(SlumpProblemSetExactSolution(prob, ExactU, ExactP, c));
  scene->results = Results;
  PetscCall(SlumpSceneAddParameter(scene, "bn", bn));
  PetscCall(SlumpSceneAddParameter(scene, "G", c->G));
  PetscCall(SlumpSceneAddParameter(scene, "H", c->H));
  PetscFunctionReturn(0);
}
