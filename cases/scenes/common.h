/* Private helpers shared by the scene files. */
#pragma once
#include "slumpscene.h"
#include <unistd.h>
#include "slumppointwise.h"

static inline PetscErrorCode SlumpZeroVelocity(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  for (PetscInt c = 0; c < Nc; ++c) u[c] = 0.0;
  return 0;
}

/* -geometry axisymmetric: the scene's domain is the meridian half-plane of
   a solid of revolution with r = x[radial] (SlumpProblemSetAxisymmetric);
   scenes that offer it call this before building their mesh (scene.c
   refuses the option for the others). */
static inline PetscErrorCode SlumpSceneGeometry(SlumpProblem prob, MPI_Comm comm, PetscInt radial, PetscBool *axi)
{
  const char *geoms[] = {"planar", "axisymmetric"};
  PetscInt    g       = 0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Scene geometry", "");
  PetscCall(PetscOptionsEList("-geometry", "planar (2-D) or axisymmetric (r-z meridian plane, integrals per radian)", "SlumpProblemSetAxisymmetric", geoms, 2, geoms[0], &g, NULL));
  PetscOptionsEnd();
  *axi = g == 1 ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(SlumpProblemSetAxisymmetric(prob, *axi ? radial : -1));
  PetscFunctionReturn(0);
}

/* The scene's mesh (-mesh_file or the rectangle [lower, upper]) handed to the problem. */
static inline PetscErrorCode SlumpSceneSetMesh(SlumpScene scene, SlumpProblem prob, MPI_Comm comm, const PetscReal lower[2], const PetscReal upper[2])
{
  DM dm;
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneCreateMesh(scene, comm, lower, upper, &dm));
  PetscCall(SlumpProblemSetMesh(prob, dm));
  PetscCall(DMDestroy(&dm));
  PetscFunctionReturn(0);
}

/* Fully developed channel flow along x: v = 0 and zero normal traction at
   both ends ("left", "right"). */
static inline PetscErrorCode SlumpSceneChannelEnds(SlumpProblem prob)
{
  const PetscInt compy = 1;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemAddVelocityBC(prob, "inlet_v", "left", 1, &compy, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "outlet_v", "right", 1, &compy, SlumpZeroVelocity, NULL, NULL));
  PetscFunctionReturn(0);
}

/* tau0 (0 without a yield stress) and eta_p (1 without a "viscosity") of the model in force. */
static inline PetscErrorCode SlumpSceneYieldParameters(SlumpProblem prob, PetscReal *tau0, PetscReal *etap)
{
  SlumpRheology rheo;
  PetscBool     has;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  *tau0 = 0.0;
  *etap = 1.0;
  PetscCall(SlumpRheologyHasParameter(rheo, "yield_stress", &has));
  if (has) PetscCall(SlumpRheologyGetParameter(rheo, "yield_stress", tau0));
  PetscCall(SlumpRheologyHasParameter(rheo, "viscosity", &has));
  if (has) PetscCall(SlumpRheologyGetParameter(rheo, "viscosity", etap));
  PetscFunctionReturn(0);
}

/* A steady state on the scene's mesh, by KINSOL, as the initial state X of a
   run: a helper problem with the run's rheology (scene defaults included),
   made by `configure` (effects, body force, boundary conditions); its
   unknowns have the layout of X. With `newtonian`, the fluid of the helper
   problem is Newtonian with the run's plastic viscosity eta_p instead. */
static inline PetscErrorCode SlumpSceneSteadyInitialState(SlumpScene scene, SlumpProblem prob, const PetscReal lower[2], const PetscReal upper[2], PetscErrorCode (*configure)(SlumpScene, SlumpProblem), PetscBool newtonian, Vec X)
{
  SlumpProblem  p0;
  SlumpStats    st;
  SlumpRheology r0, r;
  Vec           X0;
  MPI_Comm      comm;
  PetscInt      n0, n;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)X, &comm));
  PetscCall(SlumpProblemCreate(comm, &p0));
  {
    /* the run's own (distributed) mesh: a second mesh could be partitioned
       differently, and then X0 and X would not match rank by rank (seen on
       2 ranks with 64 x 64 cells) */
    DM dm, dm0;
    PetscCall(SlumpProblemGetDM(prob, &dm));
    PetscCall(DMClone(dm, &dm0));
    PetscCall(SlumpProblemSetMesh(p0, dm0));
    PetscCall(DMDestroy(&dm0));
  }
  {
    PetscInt axis; /* the run's geometry */
    PetscCall(SlumpProblemGetAxisymmetric(prob, &axis));
    PetscCall(SlumpProblemSetAxisymmetric(p0, axis));
  }
  PetscCall(configure(scene, p0));
  PetscCall(SlumpProblemSetFromOptions(p0));
  PetscCall(SlumpProblemGetRheology(prob, &r));
  PetscCall(SlumpProblemGetRheology(p0, &r0));
  PetscCall(SlumpRheologyCopy(r, r0));
  if (newtonian) PetscCall(SlumpRheologySetType(r0, SLUMP_RHEOLOGY_NEWTONIAN)); /* keeps "viscosity" */
  PetscCall(SlumpProblemSetUp(p0));
  PetscCall(SlumpProblemCreateVector(p0, &X0));
  PetscCall(VecGetSize(X0, &n0));
  PetscCall(VecGetSize(X, &n));
  PetscCheck(n0 == n, comm, PETSC_ERR_PLIB, "Steady and transient problems have different layouts");
  {
    /* scene default: continuation from m = 1e2 for models stiffer when their
       parameter grows (Papanastasiou m, ...), unless the user chose a start */
    const char *regname;
    PetscReal   target;
    PetscBool   larger, set;
    char        method[32] = "";
    PetscBool   exact;
    PetscCall(SlumpRheologyGetRegularisation(r0, &regname, &target, &larger));
    PetscCall(PetscOptionsHasName(NULL, NULL, "-steady_continuation_start", &set));
    /* the driver's -method (listed in its group): the exact method's initial
       state is its own steady state */
    const char *method_opt = "-method";
    PetscCall(PetscOptionsGetString(NULL, NULL, method_opt, method, sizeof(method), NULL));
    PetscCall(PetscStrcmp(method, "exact", &exact));
    if (exact && !newtonian) PetscCall(SlumpSteadySolveExact(p0, X0, &st, NULL));
    else if (regname && larger && target > 1e2 && !set) {
      PetscCall(PetscOptionsSetValue(NULL, "-steady_continuation_start", "1e2"));
      PetscCall(SlumpSteadySolve(p0, X0, &st));
      PetscCall(PetscOptionsClearValue(NULL, "-steady_continuation_start"));
    } else PetscCall(SlumpSteadySolve(p0, X0, &st));
  }
  PetscCall(VecCopy(X0, X));
  PetscCall(VecDestroy(&X0));
  PetscCall(SlumpProblemDestroy(&p0));
  PetscFunctionReturn(0);
}

/* -initial_flow material|newtonian: the steady flow before t = 0 in the
   cessation scenes is that of the scene's material (default) or of a
   Newtonian fluid with its plastic viscosity (then any Bingham number has
   a moving initial state). */
static inline PetscErrorCode SlumpSceneInitialFlowOption(MPI_Comm comm, PetscBool *newtonian)
{
  const char *kinds[] = {"material", "newtonian"};
  PetscInt    kind    = 0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Initial flow of the cessation scenes", "");
  PetscCall(PetscOptionsEList("-initial_flow", "Steady flow before t = 0: of the material, or of a Newtonian fluid with its plastic viscosity", "", kinds, 2, kinds[kind], &kind, NULL));
  PetscOptionsEnd();
  *newtonian = kind == 1 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The value of a result already added (found = PETSC_FALSE if there is none). */
static inline PetscErrorCode SlumpSceneGetResult(SlumpScene scene, const char name[], PetscReal *value, PetscBool *found)
{
  PetscFunctionBeginUser;
  *found = PETSC_FALSE;
  for (PetscInt i = 0; i < scene->nresult; ++i) {
    PetscBool same;
    PetscCall(PetscStrcmp(scene->rname[i], name, &same));
    if (same) {
      *value = scene->rvalue[i];
      *found = PETSC_TRUE;
    }
  }
  PetscFunctionReturn(0);
}

/* The scenes' default material: Papanastasiou-regularised Bingham fluid,
   eta_p = 1, yield stress tau0, m = 1e4 (-rheology_* options override). */
static inline PetscErrorCode SlumpSceneSetBinghamDefaults(SlumpProblem prob, PetscReal tau0)
{
  SlumpRheology rheo;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologySetType(rheo, SLUMP_RHEOLOGY_PAPANASTASIOU));
  PetscCall(SlumpRheologySetParameter(rheo, "viscosity", 1.0));
  PetscCall(SlumpRheologySetParameter(rheo, "yield_stress", tau0));
  PetscCall(SlumpRheologySetParameter(rheo, "m", 1e4));
  PetscFunctionReturn(0);
}

/* Defaults of a cessation scene: time integration to tfinal with outputs
   every dtout, mean-shear-rate arrest below 1e-3, nx x ny cells. */
static inline void SlumpSceneSetCessationDefaults(SlumpScene scene, PetscReal tfinal, PetscReal dtout, PetscInt nx, PetscInt ny)
{
  scene->steady           = PETSC_FALSE;
  scene->tfinal           = tfinal;
  scene->dtout            = dtout;
  scene->arrest_threshold = 1e-3;
  scene->mesh_n[0]        = nx;
  scene->mesh_n[1]        = ny;
}

/* The exact (unregularised) cessation of a 1-D strip of width L as the
 * scene's reference (timeint/alg2.c, ALG2, extrapolated in dt), for the
 * Bingham models (papanastasiou, bercovier, bingham_simple) with a yield
 * stress. u0(y, ctx) is the initial profile for 0 < y < L; the scene's result
 * t_stop_bound (the energy bound) sets dt = t_stop_bound / -exact_steps. The arrest
 * time is computed for the mean shear rate only. Options: -exact_reference
 * (default true), -exact_cells (400), -exact_steps (1000). The last result
 * is kept, so the runs of a sweep over a regularisation parameter compute
 * it once per process. */
static inline PetscErrorCode SlumpSceneStripExact(SlumpScene scene, SlumpProblem prob, PetscReal L, PetscReal (*u0)(PetscReal, void *), void *ctx, PetscReal key, SlumpDiagnosticKind diag, PetscReal threshold, PetscReal *t_stop, PetscReal *t_arrest)
{
  static PetscReal      cache[9] = {-1, -1, -1, -1, -1, -1, -1, -1, -1}, cached[2];
  SlumpRheology         rheo;
  SlumpRheologyType     type;
  SlumpBinghamStripSpec s;
  PetscReal             tau0, eta, rho = 1.0;
  PetscBool             on = PETSC_TRUE, bingham = PETSC_FALSE, same;
  PetscInt              cells = 400, steps = 1000;
  PetscReal             t_scale = 0.0;
  MPI_Comm              comm;
  PetscFunctionBeginUser;
  *t_stop = *t_arrest = -1.0;
  PetscCall(SlumpSceneGetResult(scene, "t_stop_bound", &t_scale, &same));
  if (!same) t_scale = 0.0;
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologyGetType(rheo, &type));
  for (int k = 0; k < 3; ++k) {
    const char *names[] = {SLUMP_RHEOLOGY_PAPANASTASIOU, SLUMP_RHEOLOGY_BERCOVIER, SLUMP_RHEOLOGY_BINGHAM_SIMPLE};
    PetscCall(PetscStrcmp(type, names[k], &same));
    if (same) bingham = PETSC_TRUE;
  }
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &eta));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-density", &rho, NULL));
  /* option -exact_reference late: compute the exact (1-D ALG2) arrest and stopping times after the run (default true) */
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-exact_reference", &on, NULL));
  /* option -exact_cells late: cells of the exact reference */
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-exact_cells", &cells, NULL));
  /* option -exact_steps late: time steps of the exact reference's coarser run (the finer one has twice as many) */
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-exact_steps", &steps, NULL));
  if (!on || !bingham || tau0 <= 0 || t_scale <= 0) PetscFunctionReturn(0);
  {
    DM dm;
    PetscCall(SlumpProblemGetDM(prob, &dm));
    PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  }
  PetscCheck(cells >= 2 && steps >= 10, comm, PETSC_ERR_USER_INPUT, "-exact_cells must be >= 2 and -exact_steps >= 10; got %d and %d", (int)cells, (int)steps);
  if (diag != SLUMP_DIAG_MEAN_SHEAR_RATE) threshold = 0.0;
  {
    const PetscReal now[9] = {L, rho, eta, tau0, key, t_scale, threshold, (PetscReal)cells, (PetscReal)steps};
    same = PETSC_TRUE;
    for (int k = 0; k < 9; ++k)
      if (now[k] != cache[k]) same = PETSC_FALSE;
    if (!same) {
      PetscCall(PetscMemzero(&s, sizeof(s)));
      s.L = L; s.rho = rho; s.eta = eta; s.tau0 = tau0; s.ncells = cells;
      s.dt = t_scale / steps; s.t_max = 4.0 * t_scale; s.threshold = threshold;
      s.u0 = u0; s.ctx = ctx;
      PetscCall(SlumpBinghamStripReference(&s, &cached[0], &cached[1]));
      for (int k = 0; k < 9; ++k) cache[k] = now[k];
      PetscCall(PetscPrintf(comm, "exact reference (ALG2, %d cells, dt %.3g and %.3g, extrapolated): t_stop = %.8g", (int)cells, (double)s.dt, (double)(0.5 * s.dt), (double)cached[0]));
      if (threshold > 0) PetscCall(PetscPrintf(comm, ", mean shear rate < %.4g at t = %.8g", (double)threshold, (double)cached[1]));
      PetscCall(PetscPrintf(comm, "\n"));
    }
  }
  *t_stop   = cached[0];
  *t_arrest = cached[1];
  PetscFunctionReturn(0);
}

/* The fully developed Bingham flow in a channel |y| <= H (plane
   Poiseuille) driven by the pressure gradient G: plug |y| <= y0 = tau0/G,
   u = G/(2 eta) ((H - y0)^2 - (|y| - y0)^2) outside it (Newtonian: tau0 = 0).
   SlumpChannelProfileSet finds G for a given mean velocity U by bisection
   (the mean grows monotonically with G); SlumpChannelProfileU is the inflow
   condition (a SlumpPointFn with the profile as its context). */
typedef struct {
  PetscReal H, eta, tau0, G;
} SlumpChannelProfile;

static inline PetscReal SlumpChannelProfileValue(const SlumpChannelProfile *c, PetscReal y)
{
  const PetscReal y0 = c->tau0 / c->G, ay = PetscMax(PetscAbsReal(y), y0);
  return ay >= c->H ? 0.0 : c->G / (2.0 * c->eta) * (PetscSqr(c->H - y0) - PetscSqr(ay - y0));
}

static inline PetscReal SlumpChannelMeanVelocity(PetscReal G, PetscReal H, PetscReal eta, PetscReal tau0)
{
  const PetscReal y0 = tau0 / G;
  if (y0 >= H) return 0.0;
  return G / (2.0 * eta * H) * (PetscSqr(H - y0) * H - PetscPowReal(H - y0, 3) / 3.0);
}

static inline void SlumpChannelProfileSet(SlumpChannelProfile *c, PetscReal H, PetscReal eta, PetscReal tau0, PetscReal U)
{
  PetscReal lo = tau0 / H, hi = PetscMax(1.0, 2.0 * lo);
  c->H = H;
  c->eta = eta;
  c->tau0 = tau0;
  while (SlumpChannelMeanVelocity(hi, H, eta, tau0) < U) hi *= 2.0;
  for (PetscInt it = 0; it < 200; ++it) {
    const PetscReal mid = 0.5 * (lo + hi);
    if (SlumpChannelMeanVelocity(mid, H, eta, tau0) < U) lo = mid;
    else hi = mid;
  }
  c->G = 0.5 * (lo + hi);
}

static inline PetscErrorCode SlumpChannelProfileU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  u[0] = SlumpChannelProfileValue((const SlumpChannelProfile *)ctx, x[1]);
  u[1] = 0.0;
  return 0;
}

/* The mesh of a scene on a non-rectangular domain: -mesh_file, or the Gmsh
   file `name` shipped in cases/data (SLUMP_DATA_DIR, the source tree's, set
   by the build for the scenes that have one) made from its .geo. */
static inline PetscErrorCode SlumpSceneSetShippedMesh(SlumpScene scene, SlumpProblem prob, MPI_Comm comm, const char dir[], const char name[], const PetscReal lower[2], const PetscReal upper[2])
{
  PetscBool has;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-mesh_file", &has));
  if (!has) {
    char path[PETSC_MAX_PATH_LEN];
    int  ok;
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s.msh", dir, name));
    ok = access(path, R_OK) == 0;
    PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "The %s scene's mesh %s is missing; give -mesh_file (a Gmsh mesh made from cases/data/%s.geo)", scene->name, path, name);
    PetscCall(PetscOptionsSetValue(NULL, "-mesh_file", path));
    PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
    PetscCall(PetscOptionsClearValue(NULL, "-mesh_file"));
  } else PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscFunctionReturn(0);
}

/* The lid of a cavity of side L moving at U: uniform, or 16 U s^2 (1 - s)^2
   (s = x/L: no corner singularity). */
static inline PetscReal SlumpSceneLidVelocity(PetscReal x, PetscReal U, PetscReal L, PetscBool regularised)
{
  const PetscReal s = x / L;
  return regularised ? 16.0 * U * s * s * (1.0 - s) * (1.0 - s) : U;
}
