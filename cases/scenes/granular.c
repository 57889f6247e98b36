/* Steady mu(I) verification scenes (REFERENCES.md; Chauchat & Medale 2014),
 * in their dimensionless units (lengths d, pressure phi rho g d, so the body
 * force per unit volume has magnitude 1 and I = ||gdot||/sqrt(phi p)).
 *
 * vertical_chute: flow down between rough walls y = +-b/2 at uniform
 *   pressure p (imposed as the normal stress at both ends), gravity along -x.
 *   Plug |y| <= y0 = mu_s p; for y0 <= |y| <= b/2, with c = I0 sqrt(phi p),
 *   A = dmu p:  w(y) = -c [(|y| - b/2) + A ln((A - (|y| - y0))/(A - (b/2 - y0)))].
 *   Defaults p = 28, b = 28.
 *
 * bagnold: a layer 0 <= z <= H on a rough plane inclined at alpha, free
 *   surface on top (zero traction), lithostatic pressure p = (H - z) cos(alpha)
 *   as the normal stress at both ends:
 *   u(z) = (2/3) I_a sqrt(phi cos a) [H^(3/2) - (H - z)^(3/2)],
 *   I_a = I0 (tan a - mu_s)/(mu_s + dmu - tan a). Defaults alpha = 0.406, H = 14.
 *
 * Both are fully developed flows in a strip: v = 0 at the ends. The rheology
 * defaults to mui_cm (their eq. 12) with lambda_r = 1e-4; any mu(I) type works. */
#include "common.h"

typedef struct {
  PetscInt      kind; /* 0 chute, 1 bagnold */
  PetscReal     p, b, alpha, H;
  SlumpRheology rheo;
} GranularCtx;

static PetscErrorCode MuIParameters(SlumpRheology rheo, PetscReal *mus, PetscReal *dmu, PetscReal *I0, PetscReal *phi)
{
  PetscBool has;
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyGetParameter(rheo, "mu_s", mus));
  PetscCall(SlumpRheologyGetParameter(rheo, "delta_mu", dmu));
  PetscCall(SlumpRheologyGetParameter(rheo, "I0", I0));
  PetscCall(SlumpRheologyHasParameter(rheo, "phi", &has));
  *phi = 1.0;
  if (has) PetscCall(SlumpRheologyGetParameter(rheo, "phi", phi));
  PetscFunctionReturn(0);
}

static PetscErrorCode ExactU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const GranularCtx *g = (const GranularCtx *)ctx;
  PetscReal          mus, dmu, I0, phi;
  PetscCall(MuIParameters(g->rheo, &mus, &dmu, &I0, &phi));
  u[0] = u[1] = 0.0;
  if (g->kind == 0) {
    const PetscReal y0 = mus * g->p, A = dmu * g->p, c = I0 * PetscSqrtReal(phi * g->p), yy = PetscMax(PetscAbsReal(x[1]), y0);
    if (y0 < 0.5 * g->b && A > 0.5 * g->b - y0) u[0] = -c * ((yy - 0.5 * g->b) + A * PetscLogReal((A - (yy - y0)) / (A - (0.5 * g->b - y0))));
  } else {
    const PetscReal ta = PetscTanReal(g->alpha), ca = PetscCosReal(g->alpha);
    if (ta > mus && ta < mus + dmu) {
      const PetscReal Ia = I0 * (ta - mus) / (mus + dmu - ta), dz = PetscMax(g->H - x[1], 0.0);
      u[0] = 2.0 / 3.0 * Ia * PetscSqrtReal(phi * ca) * (PetscPowReal(g->H, 1.5) - PetscPowReal(dz, 1.5));
    }
  }
  return 0;
}

static PetscErrorCode ExactP(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar p[], void *ctx)
{
  const GranularCtx *g = (const GranularCtx *)ctx;
  p[0]                 = g->kind == 0 ? g->p : (g->H - x[1]) * PetscCosReal(g->alpha);
  return 0;
}

/* f0 = -t, t = -p n with p = c0 + c1 (c2 - y) (scene constants 0..2) */
static void EndTraction(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, const PetscReal x[], const PetscReal n[], PetscInt numConstants, const PetscScalar constants[], PetscScalar f0[])
{
  const PetscScalar p = constants[SLUMP_C_SCENE] + constants[SLUMP_C_SCENE + 1] * (constants[SLUMP_C_SCENE + 2] - x[1]);
  for (PetscInt d = 0; d < dim; ++d) f0[d] = p * n[d];
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  GranularCtx     *g = (GranularCtx *)scene->ctx;
  SlumpDiagnostics d;
  PetscReal        mus, dmu, I0, phi;
  PetscFunctionBeginUser;
  PetscCall(MuIParameters(g->rheo, &mus, &dmu, &I0, &phi));
  PetscCall(SlumpProblemComputeDiagnostics(prob, t, X, &d));
  if (g->kind == 0) {
    PetscCall(SlumpSceneAddResult(scene, "plug_half_width", (1.0 - d.yielded_fraction) * 0.5 * g->b));
    PetscCall(SlumpSceneAddResult(scene, "plug_half_width_exact", PetscMin(mus * g->p, 0.5 * g->b)));
  } else {
    PetscReal us, ue[2], xs[2] = {0.0, g->H};
    PetscCall(SlumpProblemComputeBoundaryMean(prob, t, X, "top", 0, &us));
    PetscCall(ExactU(2, t, xs, 2, ue, g));
    PetscCall(SlumpSceneAddResult(scene, "surface_velocity", us));
    PetscCall(SlumpSceneAddResult(scene, "surface_velocity_exact", ue[0]));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateGranular(SlumpScene scene, SlumpProblem prob, MPI_Comm comm, PetscInt kind)
{
  GranularCtx  *g;
  SlumpRheology rheo;
  PetscReal     lower[2], upper[2], L;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&g));
  scene->ctx = g;
  g->kind    = kind;
  g->p       = 28.0;
  g->b       = 28.0;
  g->alpha   = 0.406;
  g->H       = 14.0;
  PetscOptionsBegin(comm, NULL, kind ? "Scene bagnold" : "Scene vertical_chute", "");
  if (kind == 0) {
    PetscCall(PetscOptionsReal("-chute_pressure", "Uniform pressure p", "", g->p, &g->p, NULL));
    PetscCall(PetscOptionsReal("-chute_width", "Distance b between the walls", "", g->b, &g->b, NULL));
  } else {
    PetscCall(PetscOptionsReal("-incline_angle", "Inclination alpha (rad)", "", g->alpha, &g->alpha, NULL));
    PetscCall(PetscOptionsReal("-layer_height", "Layer thickness H", "", g->H, &g->H, NULL));
  }
  PetscOptionsEnd();
  PetscCheck(g->p > 0 && g->b > 0 && g->H > 0, comm, PETSC_ERR_USER_INPUT, "-chute_pressure, -chute_width and -layer_height must be positive");
  PetscCheck(g->alpha > 0 && g->alpha < PETSC_PI / 2, comm, PETSC_ERR_USER_INPUT, "-incline_angle must lie in (0, pi/2); got %g", (double)g->alpha);
  scene->steady = PETSC_TRUE;
  if (kind == 0) {
    L                = 0.25 * g->b;
    lower[0]         = 0.0;
    lower[1]         = -0.5 * g->b;
    upper[0]         = L;
    upper[1]         = 0.5 * g->b;
    scene->mesh_n[0] = 2;
    scene->mesh_n[1] = 16;
  } else {
    L                = 0.25 * g->H;
    lower[0]         = 0.0;
    lower[1]         = 0.0;
    upper[0]         = L;
    upper[1]         = g->H;
    scene->mesh_n[0] = 2;
    scene->mesh_n[1] = 8;
  }
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_BODY_FORCE));
  if (kind == 0) {
    PetscCall(SlumpProblemSetBodyForce(prob, -1.0, 0.0));
    PetscCall(SlumpProblemSetSceneConstant(prob, 0, g->p));
    PetscCall(SlumpProblemAddVelocityBC(prob, "wall_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddVelocityBC(prob, "wall_top", "top", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  } else {
    PetscCall(SlumpProblemSetBodyForce(prob, PetscSinReal(g->alpha), -PetscCosReal(g->alpha)));
    PetscCall(SlumpProblemSetSceneConstant(prob, 1, PetscCosReal(g->alpha)));
    PetscCall(SlumpProblemSetSceneConstant(prob, 2, g->H));
    PetscCall(SlumpProblemAddVelocityBC(prob, "bed", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  }
  PetscCall(SlumpSceneChannelEnds(prob));
  PetscCall(SlumpProblemAddTractionBC(prob, "left", EndTraction));
  PetscCall(SlumpProblemAddTractionBC(prob, "right", EndTraction));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  g->rheo = rheo;
  PetscCall(SlumpRheologySetType(rheo, "mui_cm"));
  PetscCall(SlumpProblemSetExactSolution(prob, ExactU, ExactP, g));
  PetscCall(SlumpProblemSetInitialPressure(prob, ExactP, g)); /* lithostatic / uniform: the usual first guess */
  scene->results = Results;
  if (kind == 0) {
    PetscCall(SlumpSceneAddParameter(scene, "pressure", g->p));
    PetscCall(SlumpSceneAddParameter(scene, "width", g->b));
  } else {
    PetscCall(SlumpSceneAddParameter(scene, "alpha", g->alpha));
    PetscCall(SlumpSceneAddParameter(scene, "H", g->H));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_VerticalChute(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  PetscFunctionBeginUser;
  PetscCall(CreateGranular(scene, prob, comm, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_Bagnold(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  PetscFunctionBeginUser;
  PetscCall(CreateGranular(scene, prob, comm, 1));
  PetscFunctionReturn(0);
}
