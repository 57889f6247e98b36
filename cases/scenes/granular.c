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

#ifndef SLUMP_DATA_DIR
  #define SLUMP_DATA_DIR "cases/data"
#endif

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

/* granular_cylinder: the dry granular chute flow over a cylinder of Chauchat &
 * Medale (2014, section 4.2) in the plane, in the units above (d, phi rho g0
 * d, sqrt(d/g0)). A vertical channel W = 20 D wide and L = 30 D long between
 * rough walls, the cylinder of diameter D = 10 d (their d/D = 0.1) at its
 * centre, the flow along -x; the half 0 <= y <= W/2 with the symmetry plane
 * y = 0 (cases/data/granular_cylinder.msh). Both ends carry the confining
 * pressure p_ext (zero tangential velocity, normal stress -p_ext); the body
 * force per unit volume is G = F p_ext / D along -x, F = phi rho G D / p_ext
 * their dimensionless load (their F_adim; the factor D, not their L_x, makes
 * the walls alone hold the material for F < 2 mu_s D/W = mu_s/10, as it must
 * by the balance of forces). Inertia and convection are on: the steady
 * momentum equation is theirs (eq. 7).
 * Results: the flow rate Q of the whole channel, its mean velocity U = Q/W,
 * the Froude numbers U/sqrt(G D) and U/sqrt(G (D + d)), the drag F_D of the
 * cylinder (force along the flow per unit span), F_D/(p_ext D), the drag
 * coefficient C_D = F_D/(rho U^2 D/2) and the share of the weight the
 * cylinder carries (the walls carry the rest). */
typedef struct {
  PetscReal D, W, L, p, F, G, cut, dF, lr_load;
} GranularCylinderCtx;

static void GranularCylinderCutoff(const PetscReal x[], void *ctx, PetscReal *phi, PetscReal dphi[])
{
  const GranularCylinderCtx *c = (const GranularCylinderCtx *)ctx;
  const PetscReal            R = 0.5 * c->D, r = PetscSqrtReal(x[0] * x[0] + x[1] * x[1]), r1 = c->cut * R;
  dphi[0] = dphi[1] = 0.0;
  if (r >= r1) *phi = 0.0;
  else if (r <= R * (1 + 1e-12)) *phi = 1.0;
  else {
    *phi    = (r1 - r) / (r1 - R);
    dphi[0] = -x[0] / (r * (r1 - R));
    dphi[1] = -x[1] / (r * (r1 - R));
  }
}

static PetscErrorCode GranularCylinderPressure(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar p[], void *ctx)
{
  p[0] = ((const GranularCylinderCtx *)ctx)->p;
  return 0;
}

static PetscErrorCode GranularCylinderResults(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  GranularCylinderCtx *c = (GranularCylinderCtx *)scene->ctx;
  const PetscReal      rho = 1.0; /* phi rho: the unit of density */
  PetscReal            Fx, um[2], Q, U, weight;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemComputeBoundaryForce(prob, t, X, GranularCylinderCutoff, c, 0, &Fx));
  /* the flow rate through both ends (the same for an incompressible flow) */
  PetscCall(SlumpProblemComputeBoundaryMean(prob, t, X, "bottom_end", 0, &um[0]));
  PetscCall(SlumpProblemComputeBoundaryMean(prob, t, X, "top_end", 0, &um[1]));
  Q = -0.5 * (um[0] + um[1]) * c->W;
  U = Q / c->W;
  weight = rho * c->G * (c->W * c->L - 0.25 * PETSC_PI * c->D * c->D);
  PetscCall(SlumpSceneAddResult(scene, "flow_rate", Q));
  PetscCall(SlumpSceneAddResult(scene, "flow_rate_ends_difference", PetscAbsReal(um[0] - um[1]) * 0.5 * c->W));
  PetscCall(SlumpSceneAddResult(scene, "mean_velocity", U));
  PetscCall(SlumpSceneAddResult(scene, "froude", U / PetscSqrtReal(c->G * c->D)));
  PetscCall(SlumpSceneAddResult(scene, "froude_effective", U / PetscSqrtReal(c->G * (c->D + 1.0))));
  /* the fluid's force on the cylinder along the flow (-x), both halves */
  PetscCall(SlumpSceneAddResult(scene, "drag", -2.0 * Fx));
  PetscCall(SlumpSceneAddResult(scene, "drag_over_pressure", -2.0 * Fx / (c->p * c->D)));
  if (U > 0) PetscCall(SlumpSceneAddResult(scene, "drag_coefficient", -2.0 * Fx / (0.5 * rho * U * U * c->D)));
  PetscCall(SlumpSceneAddResult(scene, "drag_weight_fraction", -2.0 * Fx / weight));
  PetscFunctionReturn(0);
}

static PetscErrorCode AddStats(SlumpStats *sum, const SlumpStats *st)
{
  PetscFunctionBeginUser;
  sum->newton_its += st->newton_its;
  sum->lin_its += st->lin_its;
  sum->lin_solves += st->lin_solves;
  sum->conv_fails += st->conv_fails;
  PetscFunctionReturn(0);
}

/* The steady state, by continuation (the driver reports it without solving
   again). First in the load, as Chauchat & Medale apply theirs: from half
   the walls' onset mu_s D/W (the static regime, where Newton converges from
   rest) up to F by steps of at most dF, halved (down to dF/64) when a solve
   fails and grown by 1.5 after a success. A direct solve from rest fails
   above the onset (F 0.045: no decrease of max|F| in 14 Newton iterations),
   and so does a step across the onset of the flow at lambda_r = 1e-4 (the
   continuation stalls at F = 0.0485). So the load continuation runs at the
   softer lr_load (1e-3 at p_ext = 100, scaled as the shear-rate unit
   sqrt(p_ext)), and the regularisation is then halved down to the model's at
   the final load. */
static PetscErrorCode GranularCylinderInitial(SlumpScene scene, SlumpProblem prob, Vec X)
{
  GranularCylinderCtx *c = (GranularCylinderCtx *)scene->ctx;
  SlumpRheology        rheo;
  SlumpStats           st;
  PetscReal            mus, F, Fok = 0.0, step = c->dF, target;
  const char          *regname;
  PetscBool            larger_stiffer, soft;
  PetscInt             nsolve = 0, nfail = 0;
  Vec                  Xok;
  MPI_Comm             comm;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)X, &comm));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologyGetParameter(rheo, "mu_s", &mus));
  PetscCall(SlumpRheologyGetRegularisation(rheo, &regname, &target, &larger_stiffer));
  soft = regname && !larger_stiffer && target < c->lr_load;
  if (soft) {
    PetscCall(PetscPrintf(comm, "load continuation at %s = %g (the model's %g: the driver's solve ends there)\n", regname, (double)c->lr_load, (double)target));
    PetscCall(SlumpProblemSetRheologyParameter(prob, regname, c->lr_load));
  }
  PetscCall(VecDuplicate(X, &Xok));
  F = PetscMin(mus * c->D / c->W, c->F);
  for (;;) {
    PetscErrorCode ierr;
    PetscCall(VecCopy(X, Xok));
    PetscCall(PetscPrintf(comm, "load continuation: F = %.6g\n", (double)F));
    PetscCall(SlumpProblemSetBodyForce(prob, -F * c->p / c->D, 0.0));
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = SlumpSteadySolveNoRetry(prob, X, &st);
    PetscCall(PetscPopErrorHandler());
    ++nsolve;
    if (ierr == PETSC_ERR_NOT_CONVERGED) {
      scene->initial_stats.conv_fails++;
      /* the first load (walls alone hold the column) must converge */
      PetscCheck(nsolve > 1, comm, PETSC_ERR_NOT_CONVERGED, "The steady solve of granular_cylinder failed at the first load F = %g", (double)F);
      ++nfail;
      PetscCall(VecCopy(Xok, X));
      step = 0.5 * PetscMin(step, F - Fok);
      PetscCheck(step >= c->dF / 64, comm, PETSC_ERR_NOT_CONVERGED, "The load continuation of granular_cylinder stalled at F = %g (last converged load %g); try a smaller -granular_cylinder_load_step or a larger -granular_cylinder_load_lambda_r (with inertia, no steady state was found above F = 0.0559 at p_ext = 100)", (double)F, (double)Fok);
      F = Fok + step;
      continue;
    }
    PetscCall(ierr);
    PetscCall(AddStats(&scene->initial_stats, &st));
    Fok = F;
    if (F >= c->F) break;
    step = PetscMin(1.5 * step, c->dF);
    F    = PetscMin(F + step, c->F);
  }
  /* then down to the model's regularisation at the final load, halving it
     (F 0.054: a direct step from 1e-3 to 1e-4 fails; halving takes 4 solves
     of 8 to 16 Newton iterations) */
  for (PetscReal v = soft ? c->lr_load : target; v > target;) {
    PetscErrorCode ierr;
    v = PetscMax(0.5 * v, target);
    if (v < 1.0001 * target) v = target;
    PetscCall(PetscPrintf(comm, "regularisation continuation: %s = %.6g\n", regname, (double)v));
    PetscCall(SlumpProblemSetRheologyParameter(prob, regname, v));
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = SlumpSteadySolveNoRetry(prob, X, &st);
    PetscCall(PetscPopErrorHandler());
    if (ierr == PETSC_ERR_NOT_CONVERGED) PetscCall(SlumpProblemSetRheologyParameter(prob, regname, target));
    PetscCheck(ierr != PETSC_ERR_NOT_CONVERGED, comm, PETSC_ERR_NOT_CONVERGED, "The continuation of granular_cylinder in %s from %g down to the model's %g failed at %g (load F = %g); try a larger %s for the model", regname, (double)c->lr_load, (double)target, (double)v, (double)c->F, regname);
    PetscCall(ierr);
    PetscCall(AddStats(&scene->initial_stats, &st));
  }
  PetscCall(VecDestroy(&Xok));
  scene->initial_solved = PETSC_TRUE;
  PetscCall(PetscPrintf(comm, "load continuation: %" PetscInt_FMT " steady solves (%" PetscInt_FMT " failed and retried with half the step) up to F = %g\n", nsolve, nfail, (double)c->F));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_GranularCylinder(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  GranularCylinderCtx *c;
  SlumpRheology        rheo;
  PetscReal            lower[2], upper[2];
  PetscBool            inertia = PETSC_TRUE;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->D       = 10.0;
  c->W       = 20.0 * c->D;
  c->L       = 30.0 * c->D;
  c->p       = 10.0 * c->D;
  c->F       = 0.054;
  c->cut     = 1.8;
  c->dF      = 0.005;
  PetscOptionsBegin(comm, NULL, "Scene granular_cylinder", "");
  PetscCall(PetscOptionsReal("-granular_cylinder_pressure", "Confining pressure p_ext at both ends (units phi rho g0 d; 100 = 10 phi rho g0 D)", "", c->p, &c->p, NULL));
  PetscCall(PetscOptionsReal("-granular_cylinder_load", "Dimensionless load F = phi rho G D/p_ext (body force G = F p_ext/D along the flow)", "", c->F, &c->F, NULL));
  PetscCall(PetscOptionsReal("-granular_cylinder_load_step", "Step of the continuation in the load, from mu_s D/W (the initial state)", "", c->dF, &c->dF, NULL));
  c->lr_load = 1e-3 * PetscSqrtReal(c->p / 100.0);
  PetscCall(PetscOptionsReal("-granular_cylinder_load_lambda_r", "Shear-rate regularisation of the load continuation, when the model's is smaller (then halved down to the model's); default 1e-3 sqrt(p_ext/100)", "", c->lr_load, &c->lr_load, NULL));
  PetscCall(PetscOptionsBool("-granular_cylinder_inertia", "Inertia and convection (their steady momentum equation); false: quasi-static", "", inertia, &inertia, NULL));
  PetscOptionsEnd();
  PetscCheck(c->p > 0, comm, PETSC_ERR_USER_INPUT, "-granular_cylinder_pressure must be positive; got %g", (double)c->p);
  PetscCheck(c->F > 0, comm, PETSC_ERR_USER_INPUT, "-granular_cylinder_load must be positive; got %g", (double)c->F);
  PetscCheck(c->lr_load > 0, comm, PETSC_ERR_USER_INPUT, "-granular_cylinder_load_lambda_r must be positive; got %g", (double)c->lr_load);
  PetscCheck(c->dF > 0, comm, PETSC_ERR_USER_INPUT, "-granular_cylinder_load_step must be positive; got %g", (double)c->dF);
  c->G          = c->F * c->p / c->D;
  scene->steady = PETSC_TRUE;
  lower[0]      = -0.5 * c->L;
  lower[1]      = 0.0;
  upper[0]      = 0.5 * c->L;
  upper[1]      = 0.5 * c->W;
  PetscCall(SlumpSceneSetShippedMesh(scene, prob, comm, SLUMP_DATA_DIR, "granular_cylinder", lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_BODY_FORCE | (inertia ? SLUMP_EFFECT_INERTIA | SLUMP_EFFECT_CONVECTION : 0)));
  PetscCall(SlumpProblemSetDensity(prob, 1.0));
  PetscCall(SlumpProblemSetBodyForce(prob, -c->G, 0.0));
  PetscCall(SlumpProblemSetSceneConstant(prob, 0, c->p));
  {
    const PetscInt compy = 1;
    PetscCall(SlumpProblemAddVelocityBC(prob, "wall", "wall", 0, NULL, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddVelocityBC(prob, "cylinder", "cylinder", 0, NULL, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddFreeSlipBC(prob, "symmetry"));
    PetscCall(SlumpProblemAddVelocityBC(prob, "top_end_v", "top_end", 1, &compy, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddVelocityBC(prob, "bottom_end_v", "bottom_end", 1, &compy, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddTractionBC(prob, "top_end", EndTraction));
    PetscCall(SlumpProblemAddTractionBC(prob, "bottom_end", EndTraction));
  }
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologySetType(rheo, "mui_cm"));
  PetscCall(SlumpRheologySetParameter(rheo, "mu_s", 0.4));
  PetscCall(SlumpRheologySetParameter(rheo, "delta_mu", 0.25));
  PetscCall(SlumpRheologySetParameter(rheo, "I0", 0.3));
  PetscCall(SlumpProblemSetInitialPressure(prob, GranularCylinderPressure, c));
  scene->results = GranularCylinderResults;
  scene->initial = GranularCylinderInitial;
  PetscCall(SlumpSceneAddParameter(scene, "pressure", c->p));
  PetscCall(SlumpSceneAddParameter(scene, "load", c->F));
  PetscCall(SlumpSceneAddParameter(scene, "body_force", c->G));
  PetscFunctionReturn(0);
}
