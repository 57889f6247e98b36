/* Creeping flow past a cylinder between two parallel walls (Riber's thesis,
 * section 3.4.3; the confined-cylinder benchmark of the viscoelastic and
 * viscoplastic literature, blockage R/H = 1/2).
 * The upper half of the channel, -15 R <= x <= 15 R, 0 <= y <= H = 2 R,
 * with the cylinder of radius R = 1 at the origin cut out (Gmsh mesh
 * cases/data/cylinder.msh from cylinder.geo; physical names inlet, outlet,
 * wall, symmetry, cylinder); free slip on the symmetry plane y = 0.
 * The inlet carries the fully developed channel profile of mean velocity
 * U = 1 for the material in force (Newtonian parabola, or the Bingham
 * profile with its plug, whose pressure gradient is found by bisection);
 * the outlet has v = 0 and zero normal traction.
 * Bn = tau0 R / (eta_p U) (the norm of the code: ||gdot|| = sqrt(gdot:gdot/2)).
 * Result: the drag coefficient K = F / (eta_p U) of the whole cylinder
 * (twice the half domain's force), from the consistent reaction with a
 * radial cut-off (SlumpProblemComputeBoundaryForce); Newtonian: K = 132.36
 * (Alves, Pinho & Oliveira 2001 and the benchmark papers before them).
 *
 * -cylinder_domain unbounded: the cylinder in a uniform stream U (Tokpavi,
 * Magnin & Jay 2008; the thesis' Fig. 40): the upper half of the box
 * -40 R <= x <= 50 R, 0 <= y <= 30 R (cases/data/cylinder_unbounded.msh),
 * u = (U, 0) on the inlet and the far boundary, v = 0 and zero normal
 * traction on the outlet. It also reports the Oldroyd number
 * Od = tau0 D/(eta_p U) = 2 Bn and the plastic drag coefficient
 * Cd* = F/(tau0 D), whose limit for Od -> infinity is the limit load of a
 * rough cylinder in a perfectly plastic medium, 2 pi + 4 sqrt 2 = 11.94
 * (Randolph & Houlsby 1984). */
#include "common.h"

#ifndef SLUMP_DATA_DIR
  #define SLUMP_DATA_DIR "cases/data"
#endif

typedef struct {
  PetscBool           unbounded;
  PetscReal           R, H, U, tau0, eta, cut;
  SlumpChannelProfile inflow;
} CylinderCtx;

/* 1 on the cylinder, falling linearly to 0 at r = 1.8 R (inside the channel) */
static void Cutoff(const PetscReal x[], void *ctx, PetscReal *phi, PetscReal dphi[])
{
  const CylinderCtx *c = (const CylinderCtx *)ctx;
  const PetscReal    r = PetscSqrtReal(x[0] * x[0] + x[1] * x[1]), r1 = c->cut * c->R;
  dphi[0] = dphi[1] = 0.0;
  if (r >= r1) *phi = 0.0;
  else if (r <= c->R * (1 + 1e-12)) *phi = 1.0;
  else {
    *phi    = (r1 - r) / (r1 - c->R);
    dphi[0] = -x[0] / (r * (r1 - c->R));
    dphi[1] = -x[1] / (r * (r1 - c->R));
  }
}

/* the free stream (U, 0) of the unbounded domain */
static PetscErrorCode UniformStream(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const CylinderCtx *c = (const CylinderCtx *)ctx;
  u[0]                 = c->U;
  for (PetscInt k = 1; k < Nc; ++k) u[k] = 0.0;
  return 0;
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  CylinderCtx *c = (CylinderCtx *)scene->ctx;
  PetscReal    Fx, tau0, etap;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemComputeBoundaryForce(prob, t, X, Cutoff, c, 0, &Fx));
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &etap));
  PetscCall(SlumpSceneAddResult(scene, "bn", tau0 * c->R / (etap * c->U)));
  PetscCall(SlumpSceneAddResult(scene, "drag_coefficient", 2.0 * Fx / (etap * c->U)));
  if (c->unbounded) {
    PetscCall(SlumpSceneAddResult(scene, "oldroyd", 2.0 * tau0 * c->R / (etap * c->U)));
    if (tau0 > 0) PetscCall(SlumpSceneAddResult(scene, "drag_plastic", Fx / (tau0 * c->R)));
    PetscCall(SlumpSceneAddResult(scene, "drag_plastic_limit", 2.0 * PETSC_PI + 4.0 * PetscSqrtReal(2.0)));
    PetscFunctionReturn(0);
  }
  PetscCall(SlumpSceneAddResult(scene, "pressure_gradient_inlet", c->inflow.G));
  {
    /* the mean velocity across the outlet and across the cylinder's section
       x = 0 (mass conservation checks; both U), by sampling */
    const PetscInt n = 401;
    PetscReal      u[2 * 2 * 401], lo[2], hi[2], m[2] = {0, 0};
    for (PetscInt k = 0; k < 2; ++k) {
      lo[0] = k ? 0.0 : 15.0;
      hi[0] = lo[0] + 1e-9;
      lo[1] = k ? c->R : 0.0;
      hi[1] = c->H;
      PetscCall(SlumpProblemSampleVelocity(prob, t, X, 2, n, lo, hi, u, NULL));
      for (PetscInt j = 0; j < n; ++j) m[k] += (j == 0 || j == n - 1 ? 0.5 : 1.0) * u[(j * 2) * 2] * (hi[1] - lo[1]) / (n - 1);
      m[k] /= c->H;
    }
    PetscCall(SlumpSceneAddResult(scene, "outlet_mean_velocity", m[0]));
    PetscCall(SlumpSceneAddResult(scene, "gap_mean_velocity", m[1]));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_Cylinder(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  CylinderCtx *c;
  PetscReal    bn = 0.0, lower[2] = {-15.0, 0.0}, upper[2] = {15.0, 2.0};
  const char  *domains[] = {"confined", "unbounded"};
  PetscInt     domain    = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->R       = 1.0;
  c->H       = 2.0;
  c->U       = 1.0;
  c->eta     = 1.0;
  c->cut     = 1.8;
  PetscOptionsBegin(comm, NULL, "Scene cylinder", "");
  PetscCall(PetscOptionsReal("-cylinder_cutoff", "Outer radius of the drag's cut-off function, in R (in (1, 2))", "", c->cut, &c->cut, NULL));
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0 R/(eta_p U), U the mean inlet velocity (the free stream's, unbounded)", "", bn, &bn, NULL));
  PetscCall(PetscOptionsEList("-cylinder_domain", "confined (between walls, blockage 1/2) or unbounded (in a uniform stream, box of 90 R x 60 R)", "", domains, 2, domains[domain], &domain, NULL));
  PetscOptionsEnd();
  PetscCheck(bn >= 0, comm, PETSC_ERR_USER_INPUT, "-bn must be non-negative; got %g", (double)bn);
  c->unbounded = domain == 1 ? PETSC_TRUE : PETSC_FALSE;
  PetscCheck(c->cut > 1 && c->cut < 2, comm, PETSC_ERR_USER_INPUT, "-cylinder_cutoff must lie in (1, 2) (radii R, inside the walls at 2 R); got %g", (double)c->cut);
  scene->steady = PETSC_TRUE;
  if (c->unbounded) {
    lower[0] = -40.0;
    upper[0] = 50.0;
    upper[1] = 30.0;
  }
  PetscCall(SlumpSceneSetShippedMesh(scene, prob, comm, SLUMP_DATA_DIR, c->unbounded ? "cylinder_unbounded" : "cylinder", lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, 0));
  PetscCall(SlumpSceneSetBinghamDefaults(prob, bn * c->eta * c->U / c->R));
  c->tau0 = bn * c->eta * c->U / c->R;
  if (c->unbounded) {
    const PetscInt compy = 1;
    PetscCall(SlumpProblemAddVelocityBC(prob, "inlet", "inlet", 0, NULL, UniformStream, NULL, c));
    PetscCall(SlumpProblemAddVelocityBC(prob, "far", "far", 0, NULL, UniformStream, NULL, c));
    PetscCall(SlumpProblemAddVelocityBC(prob, "outlet_v", "outlet", 1, &compy, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddVelocityBC(prob, "cylinder", "cylinder", 0, NULL, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddFreeSlipBC(prob, "symmetry"));
  } else {
    /* the inlet's profile: mean velocity U */
    SlumpChannelProfileSet(&c->inflow, c->H, c->eta, c->tau0, c->U);
    const PetscInt compy = 1;
    PetscCall(SlumpProblemAddVelocityBC(prob, "inlet", "inlet", 0, NULL, SlumpChannelProfileU, NULL, &c->inflow));
    PetscCall(SlumpProblemAddVelocityBC(prob, "outlet_v", "outlet", 1, &compy, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddVelocityBC(prob, "wall", "wall", 0, NULL, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddVelocityBC(prob, "cylinder", "cylinder", 0, NULL, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddFreeSlipBC(prob, "symmetry"));
  }
  scene->results = Results;
  PetscCall(SlumpSceneAddParameter(scene, "unbounded", c->unbounded ? 1.0 : 0.0));
  PetscCall(SlumpSceneAddParameter(scene, "bn_option", bn));
  PetscFunctionReturn(0);
}
