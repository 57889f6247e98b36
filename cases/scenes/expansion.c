/* Creeping Bingham flow through a planar 1:2 sudden expansion (Riber's
 * thesis, section 3.4.2): the upper half of a channel of half-width h = 1
 * (-10 h <= x <= 0) opening into one of half-width 2 h (0 <= x <= 30 h),
 * Gmsh mesh cases/data/expansion.msh (from expansion.geo; physical names
 * inlet, outlet, wall, symmetry); free slip on the symmetry plane y = 0.
 * The inlet carries the fully developed profile of mean velocity U = 1 of
 * the material in force; the outlet has v = 0 and zero normal traction.
 * Bn = tau0 h/(eta_p U).
 * Results:
 *   - the flow far downstream against the fully developed profile of mean
 *     velocity U/2 in the wide channel (analytic; relative L2 difference
 *     along x = 20 h, sampled), with the plug half-widths tau0/G of the
 *     developed flows up- and downstream for reference;
 *   - the corner's stagnant area: where |u| < 1e-3 U in the step's corner
 *     0 <= x <= 4 h, h <= y <= 2 h (the dead zone; the recirculating eddy of
 *     Newtonian fluid's Moffatt eddies are slower than that too: 0.093 of
 *     the corner's 4 h^2);
 *   - mass conservation: the mean velocity across x = 20 h (U/2). */
#include "common.h"

#ifndef SLUMP_DATA_DIR
  #define SLUMP_DATA_DIR "cases/data"
#endif

typedef struct {
  PetscReal           h, U, eta, tau0;
  SlumpChannelProfile inflow, downstream;
} ExpansionCtx;

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  ExpansionCtx   *c = (ExpansionCtx *)scene->ctx;
  const PetscInt  ny = 401, nx = 81, nyc = 41;
  PetscReal      *u, lo[2], hi[2], num = 0.0, den = 0.0, mean = 0.0, stagnant = 0.0, tau0, etap;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(2 * PetscMax(2 * ny, nx * nyc), &u));
  /* the developed flow across x = 20 h */
  lo[0] = 20.0 * c->h;
  hi[0] = lo[0] + 1e-9;
  lo[1] = 0.0;
  hi[1] = 2.0 * c->h;
  PetscCall(SlumpProblemSampleVelocity(prob, t, X, 2, ny, lo, hi, u, NULL));
  {
    const PetscReal dy = hi[1] / (ny - 1);
    for (PetscInt j = 0; j < ny; ++j) {
      const PetscReal w = (j == 0 || j == ny - 1 ? 0.5 : 1.0) * dy, ue = SlumpChannelProfileValue(&c->downstream, j * dy), uh = u[(j * 2) * 2];
      num += w * PetscSqr(uh - ue);
      den += w * PetscSqr(ue);
      mean += w * uh;
    }
    mean /= hi[1];
  }
  PetscCall(SlumpSceneAddResult(scene, "downstream_profile_error", PetscSqrtReal(num / den)));
  PetscCall(SlumpSceneAddResult(scene, "downstream_mean_velocity", mean));
  PetscCall(SlumpSceneAddResult(scene, "downstream_plug_exact", PetscMin(c->tau0 / c->downstream.G, 2.0 * c->h)));
  PetscCall(SlumpSceneAddResult(scene, "upstream_plug_exact", PetscMin(c->tau0 / c->inflow.G, c->h)));
  /* the corner 0 <= x <= 4 h, h <= y <= 2 h */
  lo[0] = 0.0;
  hi[0] = 4.0 * c->h;
  lo[1] = c->h;
  hi[1] = 2.0 * c->h;
  PetscCall(SlumpProblemSampleVelocity(prob, t, X, nx, nyc, lo, hi, u, NULL));
  {
    const PetscReal dx = (hi[0] - lo[0]) / (nx - 1), dy = (hi[1] - lo[1]) / (nyc - 1);
    for (PetscInt j = 0; j < nyc; ++j)
      for (PetscInt i = 0; i < nx; ++i) {
        const PetscReal w = (i == 0 || i == nx - 1 ? 0.5 : 1.0) * (j == 0 || j == nyc - 1 ? 0.5 : 1.0) * dx * dy;
        if (PetscSqrtReal(PetscSqr(u[(j * nx + i) * 2]) + PetscSqr(u[(j * nx + i) * 2 + 1])) < 1e-3 * c->U) stagnant += w;
      }
  }
  PetscCall(SlumpSceneAddResult(scene, "corner_stagnant_area", stagnant));
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &etap));
  PetscCall(SlumpSceneAddResult(scene, "bn", tau0 * c->h / (etap * c->U)));
  PetscCall(PetscFree(u));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_Expansion(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  ExpansionCtx *c;
  PetscReal     bn = 0.0, lower[2] = {-10.0, 0.0}, upper[2] = {30.0, 2.0};
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->h       = 1.0;
  c->U       = 1.0;
  c->eta     = 1.0;
  PetscOptionsBegin(comm, NULL, "Scene expansion", "");
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0 h/(eta_p U), h the inlet half-width, U its mean velocity", "", bn, &bn, NULL));
  PetscOptionsEnd();
  PetscCheck(bn >= 0, comm, PETSC_ERR_USER_INPUT, "-bn must be non-negative; got %g", (double)bn);
  scene->steady = PETSC_TRUE;
  PetscCall(SlumpSceneSetShippedMesh(scene, prob, comm, SLUMP_DATA_DIR, "expansion", lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, 0));
  c->tau0 = bn * c->eta * c->U / c->h;
  PetscCall(SlumpSceneSetBinghamDefaults(prob, c->tau0));
  /* the inflow (half-width h, mean U) and the developed flow downstream
     (half-width 2 h, mean U/2: the same flux) */
  SlumpChannelProfileSet(&c->inflow, c->h, c->eta, c->tau0, c->U);
  SlumpChannelProfileSet(&c->downstream, 2.0 * c->h, c->eta, c->tau0, 0.5 * c->U);
  {
    const PetscInt compy = 1;
    PetscCall(SlumpProblemAddVelocityBC(prob, "inlet", "inlet", 0, NULL, SlumpChannelProfileU, NULL, &c->inflow));
    PetscCall(SlumpProblemAddVelocityBC(prob, "outlet_v", "outlet", 1, &compy, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddVelocityBC(prob, "wall", "wall", 0, NULL, SlumpZeroVelocity, NULL, NULL));
    PetscCall(SlumpProblemAddFreeSlipBC(prob, "symmetry"));
  }
  scene->results = Results;
  PetscCall(SlumpSceneAddParameter(scene, "bn_option", bn));
  PetscFunctionReturn(0);
}
