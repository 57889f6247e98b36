/* Steady lid-driven cavity of a Bingham fluid (Riber's thesis, section
 * 3.4.1; the benchmark of Mitsoulis & Zisis 2001, Vola, Boscardin & Latche
 * 2003, Syrakos, Georgiou & Alexandrou 2013).
 * Unit square (L = 1), plastic viscosity eta_p = 1, lid speed U = 1 on
 * "top" (uniform, or u = 16 U x^2 (1 - x)^2 with -cavity_lid regularised),
 * no slip on the other walls, pressure fixed at one vertex.
 * Bn = tau0 L / (eta_p U) with the norm of the code, ||gdot|| =
 * sqrt(gdot:gdot/2), gdot = grad u + grad u^T: tau0 is the yield value of
 * the second invariant of the deviatoric stress, the convention of the
 * papers above. Re = rho U L / eta_p (-re; > 0 adds inertia and convection:
 * the steady Navier-Stokes-Bingham problem).
 * Results: the primary vortex, psi_max = max |psi| of the stream function
 * psi(x, y) = int_0^y u(x, s) ds (psi = 0 on the walls), at (psi_x, psi_y);
 * the unyielded area (from the rheology's criterion ||tau|| > tau0, or the
 * exact method's yield surface) and the stagnant area (|u| < 1e-3 U, on
 * the grid: the unyielded zone at the bottom at large Bn, and the corner
 * eddies at small Bn); psi_top = max_x |psi(x, 1)|, which
 * the divergence constraint makes zero (a check of the sampling). The
 * velocity is sampled on a (-cavity_grid + 1)^2 grid, written with psi to
 * <output_dir>/cavity_grid.csv. */
#include "common.h"

typedef struct {
  PetscReal U, L;
  PetscBool regularised;
  PetscInt  ngrid;
} CavityCtx;

static PetscErrorCode LidU(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const CavityCtx *c = (const CavityCtx *)ctx;
  u[0]               = SlumpSceneLidVelocity(x[0], c->U, c->L, c->regularised);
  u[1]               = 0.0;
  return 0;
}

/* the maximum of a parabola through (-1, a), (0, b), (1, c): offset in [-1, 1] */
static PetscReal ParabolaPeak(PetscReal a, PetscReal b, PetscReal c)
{
  const PetscReal d = a - 2.0 * b + c;
  if (d >= 0) return 0.0;
  return PetscMax(-1.0, PetscMin(1.0, 0.5 * (a - c) / d));
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  CavityCtx       *c = (CavityCtx *)scene->ctx;
  const PetscInt   n = c->ngrid + 1;
  const PetscReal  lower[2] = {0.0, 0.0}, upper[2] = {c->L, c->L}, h = c->L / c->ngrid;
  PetscReal       *u, *psi, best = -1.0, top = 0.0, stagnant = 0.0, tau0, etap, area = 0.0;
  PetscInt         bi = 0, bj = 0;
  SlumpDiagnostics d;
  MPI_Comm         comm;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)X, &comm));
  PetscCall(PetscMalloc2(2 * n * n, &u, n * n, &psi));
  PetscCall(SlumpProblemSampleVelocity(prob, t, X, n, n, lower, upper, u, NULL));
  for (PetscInt i = 0; i < n; ++i) {
    psi[i] = 0.0;
    for (PetscInt j = 1; j < n; ++j) psi[j * n + i] = psi[(j - 1) * n + i] + 0.5 * h * (u[(j * n + i) * 2] + u[((j - 1) * n + i) * 2]);
    top = PetscMax(top, PetscAbsReal(psi[(n - 1) * n + i]));
  }
  for (PetscInt j = 0; j < n; ++j)
    for (PetscInt i = 0; i < n; ++i) {
      const PetscReal w = (i == 0 || i == n - 1 ? 0.5 : 1.0) * (j == 0 || j == n - 1 ? 0.5 : 1.0) * h * h;
      const PetscReal s = PetscSqrtReal(PetscSqr(u[(j * n + i) * 2]) + PetscSqr(u[(j * n + i) * 2 + 1]));
      area += w;
      if (s < 1e-3 * c->U) stagnant += w;
      if (PetscAbsReal(psi[j * n + i]) > best) {
        best = PetscAbsReal(psi[j * n + i]);
        bi   = i;
        bj   = j;
      }
    }
  {
    /* the peak refined by a parabola in each direction */
    PetscReal dx = 0.0, dy = 0.0;
    if (bi > 0 && bi < n - 1) dx = ParabolaPeak(PetscAbsReal(psi[bj * n + bi - 1]), best, PetscAbsReal(psi[bj * n + bi + 1]));
    if (bj > 0 && bj < n - 1) dy = ParabolaPeak(PetscAbsReal(psi[(bj - 1) * n + bi]), best, PetscAbsReal(psi[(bj + 1) * n + bi]));
    PetscCall(SlumpSceneAddResult(scene, "psi_x", (bi + dx) * h));
    PetscCall(SlumpSceneAddResult(scene, "psi_y", (bj + dy) * h));
  }
  PetscCall(SlumpSceneAddResult(scene, "psi_max", best));
  PetscCall(SlumpSceneAddResult(scene, "psi_top", top));
  PetscCall(SlumpSceneYieldParameters(prob, &tau0, &etap));
  PetscCall(SlumpProblemComputeDiagnostics(prob, t, X, &d));
  PetscCall(SlumpSceneAddResult(scene, "bn", tau0 * c->L / (etap * c->U)));
  PetscCall(SlumpSceneAddResult(scene, "unyielded_area", (1.0 - d.yielded_fraction) * c->L * c->L));
  PetscCall(SlumpSceneAddResult(scene, "stagnant_area", stagnant));
  PetscCall(SlumpSceneAddResult(scene, "kinetic_energy", d.kinetic_energy));
  if (scene->dir[0]) {
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (!rank) {
      char  path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN + 8];
      FILE *fp  = NULL;
      int   err = 0;
      PetscCall(PetscSNPrintf(path, sizeof(path), "%s/cavity_grid.csv", scene->dir));
      PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.part", path));
      err = SlumpFileOpen(tmp, &fp);
      if (!err) err = SlumpFilePrintf(fp, "x,y,u,v,psi\n");
      for (PetscInt j = 0; j < n && !err; ++j)
        for (PetscInt i = 0; i < n && !err; ++i) err = SlumpFilePrintf(fp, "%.6g,%.6g,%.8e,%.8e,%.8e\n", (double)(i * h), (double)(j * h), (double)u[(j * n + i) * 2], (double)u[(j * n + i) * 2 + 1], (double)psi[j * n + i]);
      if (fp) {
        int e2 = SlumpFileClose(&fp);
        if (!err) err = e2;
      }
      PetscCall(SlumpFileCommit(PETSC_COMM_SELF, err, tmp, path));
    }
  }
  PetscCall(PetscFree2(u, psi));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_Cavity(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  CavityCtx   *c;
  PetscReal    bn = 2.0, re = 0.0, lower[2] = {0.0, 0.0}, upper[2];
  const char  *lids[] = {"uniform", "regularised"};
  PetscInt     lid    = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->U       = 1.0;
  c->L       = 1.0;
  c->ngrid   = 200;
  PetscOptionsBegin(comm, NULL, "Scene cavity", "");
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0 L/(eta_p U)", "", bn, &bn, NULL));
  PetscCall(PetscOptionsReal("-re", "Reynolds number rho U L/eta_p (> 0: inertia and convection)", "", re, &re, NULL));
  PetscCall(PetscOptionsEList("-cavity_lid", "Lid velocity: uniform (u = U) or regularised (u = 16 U x^2 (1 - x)^2)", "", lids, 2, lids[lid], &lid, NULL));
  PetscCall(PetscOptionsInt("-cavity_grid", "Intervals of the grid the velocity and stream function are sampled on", "", c->ngrid, &c->ngrid, NULL));
  PetscOptionsEnd();
  PetscCheck(bn >= 0, comm, PETSC_ERR_USER_INPUT, "-bn must be non-negative; got %g", (double)bn);
  PetscCheck(re >= 0, comm, PETSC_ERR_USER_INPUT, "-re must be non-negative; got %g", (double)re);
  PetscCheck(c->ngrid >= 10 && c->ngrid <= 4000, comm, PETSC_ERR_USER_INPUT, "-cavity_grid must lie in [10, 4000]; got %d", (int)c->ngrid);
  c->regularised   = lid == 1 ? PETSC_TRUE : PETSC_FALSE;
  scene->steady    = PETSC_TRUE;
  scene->mesh_n[0] = 32;
  scene->mesh_n[1] = 32;
  upper[0] = upper[1] = c->L;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscCall(SlumpProblemSetEffects(prob, re > 0 ? SLUMP_EFFECT_INERTIA | SLUMP_EFFECT_CONVECTION : 0));
  if (re > 0) PetscCall(SlumpProblemSetDensity(prob, re * 1.0 / (c->U * c->L)));
  PetscCall(SlumpSceneSetBinghamDefaults(prob, bn * c->U / c->L));
  /* the walls come last and own the lid's two corners: no flux leaks through
     the side walls' top cells (a lid owning them lets O(h) through, and
     psi = 0 on the walls would fail by that much) */
  PetscCall(SlumpProblemAddVelocityBC(prob, "lid", "top", 0, NULL, LidU, NULL, c));
  PetscCall(SlumpProblemAddVelocityBC(prob, "wall_left", "left", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "wall_right", "right", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "wall_bottom", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
  scene->results = Results;
  PetscCall(SlumpSceneAddParameter(scene, "bn_option", bn));
  PetscCall(SlumpSceneAddParameter(scene, "re", re));
  PetscCall(SlumpSceneAddParameter(scene, "lid_regularised", (PetscReal)c->regularised));
  PetscFunctionReturn(0);
}
