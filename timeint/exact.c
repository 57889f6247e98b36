/* The exact (unregularised) Bingham model on the finite-element mesh: the
 * augmented Lagrangian method ALG2 (Fortin & Glowinski 1983; Glowinski &
 * Wachs 2011 for viscoplastic flows), with the strain rate's auxiliary
 * variable gamma and its multiplier lambda (the plastic stress) at the
 * quadrature points of every cell.
 *
 * With the norm of the code (slumppointwise.h), <A, B> = A:B/2 and
 * ||A|| = <A, A>^(1/2) for the plane formulation (A = grad u + grad u^T),
 * and the Euclidean ones for the anti-plane one (A = grad w), a steady
 * solve or a backward Euler step minimises
 *   int rho alpha/2 |u - u^n|^2 + eta/2 ||D u||^2 + tau0 ||D u|| - f . u
 * over divergence-free u with the boundary values (alpha = 1/dt, or 0 for a
 * steady state). ALG2 replaces the non-smooth ||D u|| by ||gamma|| with the
 * constraint gamma = D u, and iterates on the augmented Lagrangian
 *   ... + tau0 ||gamma|| + <lambda, D u - gamma> + r/2 ||D u - gamma||^2:
 *   1. u: the linear Stokes (or Poisson) problem with viscosity eta + r and
 *      the source -(lambda - r gamma), of fixed matrix: it is the problem's
 *      own Jacobian with the rheology Newtonian (eta + r), factored once per
 *      alpha, and each iteration costs one residual and one back-substitution;
 *   2. gamma = max(0, 1 - tau0/||xi||) xi / r, xi = lambda + r D u, pointwise;
 *   3. lambda += r (D u - gamma).
 * At convergence gamma = D u exactly where the material flows and is zero in
 * the unyielded zones, and ||lambda|| <= tau0 there: the yield surface is
 * where ||lambda + r D u|| = tau0, without a regularisation parameter.
 * Convergence (ADMM's two residuals): ||D u - gamma||_L2 below tol times
 * ||D u|| (or the step's initial one), and r ||gamma_k - gamma_{k-1}||_L2
 * below tol times ||lambda|| + eta ||D u||. */
#include "timeintimpl.h"
#include "slumprheology.h"

/* iterations between refreshed u-step Jacobians when the u-step is
   nonlinear (convection) */
#define SLUMP_ALG2_CHORD 20

struct _n_SlumpExactSolver {
  SlumpProblem prob;
  MPI_Comm     comm;
  PetscInt     npt, ns;
  PetscBool    plane;
  PetscReal    eta, tau0, r, tol, alpha, rcur, rfact;
  PetscBool    adapt;
  PetscInt     maxit;
  PetscScalar *g, *gam, *lam, *T;
  PetscReal   *w;
  Mat          J;
  KSP          ksp;
  Vec          F, Flin, dX, Xdot;
  IS           isu;
  PetscBool    factored, nonlin;
  PetscInt     its, solves, factorisations, lin_its, last_its;
  PetscReal    last_res;
};

static inline PetscReal TensorNorm(const PetscScalar *a, PetscInt ns, PetscBool plane)
{
  PetscReal s = 0.0;
  for (PetscInt k = 0; k < ns; ++k) s += PetscRealPart(a[k] * a[k]);
  return PetscSqrtReal(plane ? 0.5 * s : s);
}

/* -alg2_* (read and checked before anything is written, and again by the solver) */
static PetscErrorCode ReadOptions(MPI_Comm comm, PetscReal *r, PetscReal *tol, PetscInt *maxit, PetscBool *adapt)
{
  PetscFunctionBeginUser;
  *r     = 0.0;
  *tol   = 0.0;
  *maxit = 20000;
  *adapt = PETSC_TRUE;
  PetscOptionsBegin(comm, NULL, "Exact method (ALG2)", "");
  PetscCall(PetscOptionsReal("-alg2_r", "ALG2 augmentation r (0: eta_p for a steady state, eta_p + rho L^2/(10 dt) for a step; L the domain's size)", "", *r, r, NULL));
  PetscCall(PetscOptionsReal("-alg2_tol", "ALG2 tolerance on its primal and dual residuals, relative to the state's strain rate and stress (0: 1e-6 for a steady state, 1e-4 for a time step)", "", *tol, tol, NULL));
  PetscCall(PetscOptionsBool("-alg2_adapt", "Adapt r to balance ALG2's primal and dual residuals (a factorisation per change)", "", *adapt, adapt, NULL));
  PetscCall(PetscOptionsInt("-alg2_max_it", "ALG2 iterations per steady solve or time step", "", *maxit, maxit, NULL));
  PetscOptionsEnd();
  PetscCheck(*r >= 0, comm, PETSC_ERR_USER_INPUT, "-alg2_r must be non-negative (0: the default); got %g", (double)*r);
  PetscCheck(*tol >= 0 && *tol < 1, comm, PETSC_ERR_USER_INPUT, "-alg2_tol must lie in [0, 1) (0: the default); got %g", (double)*tol);
  PetscCheck(*maxit > 0, comm, PETSC_ERR_USER_INPUT, "-alg2_max_it must be a positive integer; got %d", (int)*maxit);
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpExactCheckProblem(SlumpProblem prob)
{
  SlumpRheology     rheo;
  SlumpRheologyType type;
  SlumpFormulation  form;
  PetscInt          effects;
  PetscBool         ok = PETSC_FALSE, tp, fr;
  MPI_Comm          comm;
  DM                dm;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetDM(prob, &dm));
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologyGetType(rheo, &type));
  {
    const char *bingham[] = {SLUMP_RHEOLOGY_PAPANASTASIOU, SLUMP_RHEOLOGY_BERCOVIER, SLUMP_RHEOLOGY_BINGHAM_SIMPLE, SLUMP_RHEOLOGY_NEWTONIAN};
    for (PetscInt i = 0; i < 4; ++i) {
      PetscBool eq;
      PetscCall(PetscStrcmp(type, bingham[i], &eq));
      ok = ok || eq;
    }
  }
  PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "-method exact solves the unregularised Bingham model; -rheology_type %s is not one (give papanastasiou, bercovier or bingham_simple: their viscosity and yield stress are used, the regularisation is not)", type);
  PetscCall(SlumpProblemGetFormulation(prob, &form));
  PetscCheck(form == SLUMP_FORMULATION_PLANE || form == SLUMP_FORMULATION_ANTIPLANE, comm, PETSC_ERR_USER_INPUT, "-method exact needs a flow problem (plane or anti-plane), not a transport one");
  PetscCall(SlumpProblemGetEffects(prob, &effects));
  PetscCheck(!(effects & SLUMP_EFFECT_FREE_SURFACE), comm, PETSC_ERR_USER_INPUT, "-method exact is implemented for flows of one material (inertia, convection, body force); this scene has a free surface");
  PetscCall(SlumpProblemGetTwoPhase(prob, &tp, NULL, NULL, NULL));
  PetscCall(SlumpProblemHasWallFriction(prob, &fr));
  PetscCheck(!tp && !fr, comm, PETSC_ERR_USER_INPUT, "-method exact is implemented for one material with no-slip or free-slip walls; this scene has %s", tp ? "two phases" : "wall friction");
  {
    PetscReal r, tol;
    PetscInt  maxit;
    PetscBool adapt;
    PetscCall(ReadOptions(comm, &r, &tol, &maxit, &adapt));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpExactSolverCreate(SlumpProblem prob, Vec X, SlumpExactSolver *solver)
{
  SlumpExactSolver  s;
  SlumpRheology     rheo;
  SlumpFormulation  form;
  PetscFunctionBeginUser;
  PetscCall(SlumpExactCheckProblem(prob));
  PetscCall(PetscNew(&s));
  s->prob = prob;
  PetscCall(PetscObjectGetComm((PetscObject)X, &s->comm));
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpProblemGetFormulation(prob, &form));
  s->plane = form == SLUMP_FORMULATION_PLANE ? PETSC_TRUE : PETSC_FALSE;
  {
    PetscInt effects;
    PetscCall(SlumpProblemGetEffects(prob, &effects));
    s->nonlin = (effects & SLUMP_EFFECT_CONVECTION) ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(SlumpRheologyGetParameter(rheo, "viscosity", &s->eta));
  {
    PetscBool has;
    PetscCall(SlumpRheologyHasParameter(rheo, "yield_stress", &has));
    s->tau0 = 0.0;
    if (has) PetscCall(SlumpRheologyGetParameter(rheo, "yield_stress", &s->tau0));
  }
  PetscCall(ReadOptions(s->comm, &s->r, &s->tol, &s->maxit, &s->adapt));
  PetscCall(SlumpProblemSetStressVelocity(prob, PETSC_FALSE));
  PetscCall(SlumpProblemGetQuadratureLayout(prob, &s->npt, &s->ns));
  PetscCall(PetscCalloc5(s->npt * s->ns, &s->g, s->npt * s->ns, &s->gam, s->npt * s->ns, &s->lam, s->npt * s->ns, &s->T, s->npt, &s->w));
  PetscCall(SlumpProblemGetQuadratureWeights(prob, s->w));
  PetscCall(SlumpProblemCreateMatrix(prob, &s->J));
  PetscCall(KSPCreate(s->comm, &s->ksp));
  PetscCall(KSPSetOptionsPrefix(s->ksp, "alg2_"));
  PetscCall(SlumpKSPSetDirect(s->ksp));
  PetscCall(KSPSetFromOptions(s->ksp));
  PetscCall(VecDuplicate(X, &s->F));
  PetscCall(VecDuplicate(X, &s->Flin));
  PetscCall(VecDuplicate(X, &s->dX));
  PetscCall(VecDuplicate(X, &s->Xdot));
  {
    IS isp;
    PetscCall(SlumpProblemGetFieldIS(prob, &s->isu, &isp));
    PetscCall(ISDestroy(&isp));
  }
  s->alpha = -1.0;
  *solver  = s;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpExactSolverDestroy(SlumpExactSolver *solver)
{
  SlumpExactSolver s = *solver;
  PetscFunctionBeginUser;
  if (!s) PetscFunctionReturn(0);
  PetscCall(PetscFree5(s->g, s->gam, s->lam, s->T, s->w));
  PetscCall(MatDestroy(&s->J));
  PetscCall(KSPDestroy(&s->ksp));
  PetscCall(VecDestroy(&s->F));
  PetscCall(VecDestroy(&s->Flin));
  PetscCall(VecDestroy(&s->dX));
  PetscCall(VecDestroy(&s->Xdot));
  PetscCall(ISDestroy(&s->isu));
  PetscCall(PetscFree(*solver));
  PetscFunctionReturn(0);
}

/* ||u||_2 over the velocity unknowns */
PetscErrorCode SlumpExactSolverVelocityNorm(SlumpExactSolver s, Vec X, PetscReal *nrm)
{
  Vec U;
  PetscFunctionBeginUser;
  PetscCall(VecGetSubVector(X, s->isu, &U));
  PetscCall(VecNorm(U, NORM_2, nrm));
  PetscCall(VecRestoreSubVector(X, s->isu, &U));
  PetscFunctionReturn(0);
}

/* sqrt(int ||a||^2) over the mesh */
static PetscErrorCode L2Norm(SlumpExactSolver s, const PetscScalar *a, PetscReal *nrm)
{
  PetscReal sum = 0.0;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < s->npt; ++i) sum += s->w[i] * PetscSqr(TensorNorm(&a[i * s->ns], s->ns, s->plane));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sum, 1, MPIU_REAL, MPIU_SUM, s->comm));
  *nrm = PetscSqrtReal(sum);
  PetscFunctionReturn(0);
}

/* The augmentation: r = eta for a steady state (Stokes with viscosity 2 eta
   in the u-step); for a step the mass term rho/dt is balanced by r over the
   domain's size L (measured on poiseuille_cessation and cavity_cessation,
   docs/exact.md). */
static PetscReal DefaultR(SlumpExactSolver s, PetscReal alpha, PetscReal rho, PetscReal L)
{
  if (s->r > 0) return s->r;
  return s->eta + (alpha > 0 ? rho * alpha * L * L / 10.0 : 0.0);
}

PetscErrorCode SlumpExactSolverGetYieldedFraction(SlumpExactSolver s, PetscReal *fraction)
{
  PetscReal v[2] = {0.0, 0.0};
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < s->npt; ++i) {
    v[1] += s->w[i];
    if (TensorNorm(&s->gam[i * s->ns], s->ns, s->plane) > 0) v[0] += s->w[i];
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, v, 2, MPIU_REAL, MPIU_SUM, s->comm));
  *fraction = v[1] > 0 ? v[0] / v[1] : 0.0;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpExactSolverGetStats(SlumpExactSolver s, PetscInt *its, PetscInt *solves, PetscInt *factorisations, PetscInt *lin_its)
{
  PetscFunctionBeginUser;
  if (its) *its = s->its;
  if (solves) *solves = s->solves;
  if (factorisations) *factorisations = s->factorisations;
  if (lin_its) *lin_its = s->lin_its;
  PetscFunctionReturn(0);
}

/* One steady solve (alpha = 0, beta NULL) or backward Euler step (X' =
   alpha X + beta) at time t; X: initial iterate and result. gref: a scale
   of D u (L2) the tolerance is relative to besides the iterate's own (the
   step's initial state; 0: none). */
PetscErrorCode SlumpExactSolverSolve(SlumpExactSolver s, PetscReal t, PetscReal alpha, Vec beta, PetscReal gref, Vec X, PetscBool *converged, PetscInt *its)
{
  SlumpProblem prob = s->prob;
  PetscReal    rho = 1.0, L = 1.0, r;
  PetscReal    tol;
  PetscInt     k, klast = 0, klin = 0, kfact = 0;
  PetscReal    dxprev = 1.0, rmin = 0.0;
  PetscBool    fresh = PETSC_TRUE;
  PetscBool    monitor = PETSC_FALSE;
  PetscFunctionBeginUser;
  /* option -alg2_monitor late: print ALG2's primal and dual residuals at every iteration */
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-alg2_monitor", &monitor, NULL));
  PetscCall(SlumpProblemGetDensity(prob, &rho));
  {
    PetscReal area;
    PetscCall(SlumpProblemGetArea(prob, &area));
    L = PetscSqrtReal(area);
  }
  /* r carries over between steps with the same alpha (adapted) */
  if (alpha != s->alpha || s->rcur <= 0) s->rcur = DefaultR(s, alpha, rho, L);
  tol = s->tol > 0 ? s->tol : (alpha > 0 ? 1e-4 : 1e-6);
  r = s->rcur;
  if (s->tau0 > 0) PetscCall(SlumpProblemSetRheologyParameter(prob, "yield_stress", 0.0));
  *converged = PETSC_FALSE;
  for (k = 1; k <= s->maxit; ++k) {
    PetscReal gn, ln, res, dual, gsc, ssc, dxrel = 0.0;
    PetscInt  lits;
    /* with convection the u-step is nonlinear: one Newton step per
       iteration, with a fresh Jacobian while the velocity still moves by
       more than 1 % per iteration, then a chord step with the Jacobian
       refreshed every SLUMP_ALG2_CHORD iterations */
    if (!s->factored || alpha != s->alpha || r != s->rfact || (s->nonlin && (dxprev > 1e-2 || k - kfact >= SLUMP_ALG2_CHORD))) {
      /* the u-step's matrix: the problem's Jacobian, Newtonian with eta + r */
      PetscCall(SlumpProblemSetRheologyParameter(prob, "viscosity", s->eta + r));
      if (beta) PetscCall(VecAXPBYPCZ(s->Xdot, alpha, 1.0, 0.0, X, beta));
      PetscCall(SlumpProblemJacobian(prob, t, X, beta ? s->Xdot : NULL, alpha, s->J));
      PetscCall(KSPSetOperators(s->ksp, s->J, s->J));
      PetscCall(KSPSetUp(s->ksp));
      s->factored = PETSC_TRUE;
      s->alpha    = alpha;
      s->rfact    = r;
      s->factorisations++;
      kfact = k;
      fresh = PETSC_TRUE;
    }
    /* the u-step's residual is affine in u with the factored matrix as its
       derivative: assembled afresh after a factorisation and every 50
       iterations (round-off), updated by J dX in between (the assembly was
       half of an iteration's time) */
    /* time steps assemble at every iteration: with the update the
       Poiseuille cessation stopped at 0.168 instead of 0.148 (CI, not yet
       understood) */
    if (fresh || beta || s->nonlin || (k - klin) >= 50) {
      if (beta) PetscCall(VecAXPBYPCZ(s->Xdot, alpha, 1.0, 0.0, X, beta));
      PetscCall(SlumpProblemResidual(prob, t, X, beta ? s->Xdot : NULL, s->Flin));
      klin  = k;
      fresh = PETSC_FALSE;
    }
    PetscCall(VecCopy(s->Flin, s->F));
    for (PetscInt i = 0; i < s->npt * s->ns; ++i) s->T[i] = s->lam[i] - r * s->gam[i];
    PetscCall(SlumpProblemAddQuadratureFlux(prob, s->T, s->F));
    PetscCall(KSPSolve(s->ksp, s->F, s->dX));
    PetscCall(KSPGetIterationNumber(s->ksp, &lits));
    s->lin_its += lits;
    s->solves++;
    PetscCall(VecAXPY(X, -1.0, s->dX));
    if (s->nonlin) {
      PetscReal dxn, xn;
      PetscCall(VecNorm(s->dX, NORM_2, &dxn));
      PetscCall(VecNorm(X, NORM_2, &xn));
      dxrel = dxn / PetscMax(xn, PETSC_SMALL);
    }
    PetscCall(MatMult(s->J, s->dX, s->F));
    PetscCall(VecAXPY(s->Flin, -1.0, s->F));
    PetscCall(SlumpProblemComputeQuadratureStrainRate(prob, t, X, s->g));
    dual = 0.0;
    for (PetscInt i = 0; i < s->npt; ++i) {
      PetscScalar *g = &s->g[i * s->ns], *gm = &s->gam[i * s->ns], *lm = &s->lam[i * s->ns], xi[9], dg[9];
      PetscReal    nx, f;
      for (PetscInt c = 0; c < s->ns; ++c) xi[c] = lm[c] + r * g[c];
      nx = TensorNorm(xi, s->ns, s->plane);
      f  = nx > s->tau0 ? (1.0 - s->tau0 / nx) / r : 0.0;
      for (PetscInt c = 0; c < s->ns; ++c) {
        dg[c] = f * xi[c] - gm[c];
        gm[c] = f * xi[c];
        lm[c] += r * (g[c] - gm[c]);
        s->T[i * s->ns + c] = g[c] - gm[c];
      }
      dual += s->w[i] * PetscSqr(r * TensorNorm(dg, s->ns, s->plane));
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &dual, 1, MPIU_REAL, MPIU_SUM, s->comm));
    dual = PetscSqrtReal(dual);
    PetscCall(L2Norm(s, s->T, &res));
    PetscCall(L2Norm(s, s->g, &gn));
    PetscCall(L2Norm(s, s->lam, &ln));
    s->its++;
    /* ADMM's primal residual (the constraint D u = gamma) against the
       strain rate, and its dual residual r |gamma_k - gamma_{k-1}| (the
       stationarity of u) against the stress */
    gsc         = PetscMax(PetscMax(gn, gref), PETSC_SMALL);
    ssc         = PetscMax(ln + s->eta * gsc, PETSC_SMALL);
    s->last_res = PetscMax(res / gsc, dual / ssc);
    if (s->nonlin) s->last_res = PetscMax(s->last_res, dxrel);
    if (PetscIsInfOrNanReal(s->last_res)) break;
    dxprev = dxrel;
    /* with convection the u-step's Reynolds number rho U L/(eta + r) is
       kept at most 50 (U the largest velocity after the first u-step):
       Newton's method from the previous iterate diverged above it (the
       cavity at Re 1000, Bn 14 with r = 1) */
    if (s->nonlin && k == 1 && s->r <= 0) {
      Vec       U;
      PetscReal umax;
      PetscCall(VecGetSubVector(X, s->isu, &U));
      PetscCall(VecNorm(U, NORM_INFINITY, &umax));
      PetscCall(VecRestoreSubVector(X, s->isu, &U));
      rmin = rho * umax * L / 50.0 - s->eta;
      if (r < rmin) r = rmin;
    }
    if (monitor && s->nonlin) PetscCall(PetscPrintf(s->comm, "  alg2 %5" PetscInt_FMT " r %.3e primal %.3e dual %.3e u-step update %.3e\n", k, (double)r, (double)(res / gsc), (double)(dual / ssc), (double)dxrel));
    else if (monitor) PetscCall(PetscPrintf(s->comm, "  alg2 %5" PetscInt_FMT " r %.3e primal %.3e dual %.3e\n", k, (double)r, (double)(res / gsc), (double)(dual / ssc)));
    /* with convection the u-step's chord iteration must have converged too:
       its last update below tol relative to the state */
    if (res <= tol * gsc && dual <= tol * ssc && dxrel <= tol) {
      *converged = PETSC_TRUE;
      break;
    }
    /* residual balancing (Boyd et al. 2011, section 3.4.1): r up when the
       constraint lags, down when the stationarity does; at most every 10
       iterations, as each change costs a factorisation */
    if (s->adapt && k - klast >= 10 && dxrel <= PetscMax(res / gsc, dual / ssc)) {
      const PetscReal p = res / gsc, d = dual / ssc;
      if (p > 10.0 * d || d > 10.0 * p) {
        r     = p > d ? 2.0 * r : PetscMax(0.5 * r, rmin);
        klast = k;
      }
    }
  }
  s->rcur = r;
  s->last_its = PetscMin(k, s->maxit);
  *its        = s->last_its;
  PetscCall(SlumpProblemSetRheologyParameter(prob, "viscosity", s->eta));
  if (s->tau0 > 0) PetscCall(SlumpProblemSetRheologyParameter(prob, "yield_stress", s->tau0));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSteadySolveExact(SlumpProblem prob, Vec X, SlumpStats *stats, PetscReal *yielded_fraction)
{
  SlumpExactSolver s;
  PetscBool        conv;
  PetscInt         its;
  MPI_Comm         comm;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)X, &comm));
  PetscCall(SlumpExactSolverCreate(prob, X, &s));
  PetscCall(SlumpExactSolverSolve(s, 0.0, 0.0, NULL, 0.0, X, &conv, &its));
  PetscCall(PetscPrintf(comm, "steady (exact, ALG2): %" PetscInt_FMT " iterations, relative residual %.3e%s\n", its, (double)s->last_res, conv ? "" : "  (not converged)"));
  PetscCheck(conv, comm, PETSC_ERR_NOT_CONVERGED, "ALG2 did not converge in %d iterations (-alg2_max_it); raise it, or loosen -alg2_tol", (int)s->maxit);
  PetscCall(PetscMemzero(stats, sizeof(*stats)));
  stats->newton_its = s->its;
  stats->lin_solves = s->solves;
  stats->lin_its    = s->lin_its;
  {
    PetscReal yf;
    PetscReal *map;
    PetscCall(SlumpExactSolverGetYieldedFraction(s, &yf));
    PetscCall(SlumpProblemSetYieldedFraction(prob, yf));
    PetscCall(PetscMalloc1(PetscMax(s->npt, 1), &map));
    for (PetscInt i = 0; i < s->npt; ++i) map[i] = TensorNorm(&s->gam[i * s->ns], s->ns, s->plane) > 0 ? 1.0 : 0.0;
    PetscCall(SlumpProblemSetYieldMap(prob, s->npt, map));
    if (s->plane) PetscCall(SlumpProblemSetPlasticStress(prob, s->npt * s->ns, s->lam));
    PetscCall(PetscFree(map));
    if (yielded_fraction) *yielded_fraction = yf;
  }
  PetscCall(SlumpProblemGetCounters(prob, &stats->res_evals, &stats->jac_evals));
  PetscCall(SlumpExactSolverDestroy(&s));
  PetscFunctionReturn(0);
}

/* Backward Euler with an ALG2 solve per step. The flow has stopped when a
   step's velocity vanishes: |u^{n+1}| <= max(1e-3, 30 tol) |u^n| is far
   below the decay of a moving step (exp(-lambda1 eta dt/rho)), and ALG2's
   own tolerance leaves u = O(tol |u^n|) there (measured 2e-4 |u^n| at the
   default tol 1e-4 on poiseuille_cessation); the stopping time then lies in
   (t_n, t_{n+1}]. Output times and arrest times use the linear interpolant
   of the step. */
PetscErrorCode SlumpIntegratorSolve_Exact(SlumpIntegrator ti, Vec X)
{
  MPI_Comm         comm;
  SlumpExactSolver s;
  Vec              Yn, beta, Y;
  PetscInt         N, kout = 1;
  PetscReal        dt, next_out, gprev[16], g1[16], u0;
  PetscBool        stop = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)X, &comm));
  PetscCheck(!ti->restarted, comm, PETSC_ERR_USER_INPUT, "-restart is not available with -method exact");
  N  = (PetscInt)PetscCeilReal((ti->tfinal - ti->t0) / ti->dt - 1e-9);
  dt = (ti->tfinal - ti->t0) / N;
  PetscCall(SlumpExactSolverCreate(ti->prob, X, &s));
  PetscCall(VecDuplicate(X, &Yn));
  PetscCall(VecDuplicate(X, &beta));
  PetscCall(VecDuplicate(X, &Y));
  if (ti->outmon) PetscCall(ti->outmon(ti, ti->t0, X, ti->outctx));
  PetscCall(SlumpIntegratorResolveArrest(ti, ti->t0, X));
  if (ti->narrest) PetscCall(SlumpIntegratorArrestFunctions(ti, ti->t0, X, gprev));
  PetscCall(SlumpExactSolverVelocityNorm(s, X, &u0));
  ti->t_stop[0] = ti->t_stop[1] = -1.0;
  next_out                      = ti->t0 + kout * ti->dtout;
  for (PetscInt n = 0; n < N && u0 > 0; ++n) {
    const PetscReal tn = ti->t0 + n * dt, tn1 = ti->t0 + (n + 1) * dt;
    PetscReal       un, un1, gref;
    PetscBool       conv;
    PetscInt        its;
    PetscCall(VecCopy(X, Yn));
    PetscCall(VecAXPBY(beta, -1.0 / dt, 0.0, Yn));
    PetscCall(SlumpExactSolverVelocityNorm(s, Yn, &un));
    PetscCall(SlumpProblemComputeQuadratureStrainRate(ti->prob, tn, Yn, s->g));
    PetscCall(L2Norm(s, s->g, &gref));
    PetscCall(SlumpExactSolverSolve(s, tn1, 1.0 / dt, beta, gref, X, &conv, &its));
    PetscCheck(conv, comm, PETSC_ERR_NOT_CONVERGED, "ALG2 did not converge in %d iterations at t = %g (-alg2_max_it); raise it, loosen -alg2_tol or change -alg2_r", (int)s->maxit, (double)tn1);
    PetscCall(SlumpExactSolverVelocityNorm(s, X, &un1));
    {
      SlumpStepRecord rec = {tn1, dt, 1, its, 0, 0, 0, X};
      ti->stats.steps++;
      ti->stats.h_min = dt;
      ti->stats.h_max = dt;
      ti->h_last      = dt;
      ti->order_last  = 1;
      ti->t           = tn1;
      if (ti->stepmon) PetscCall(ti->stepmon(ti, &rec, ti->stepctx));
    }
    if (ti->narrest) {
      PetscCall(SlumpIntegratorArrestFunctions(ti, tn1, X, g1));
      for (PetscInt k = 0; k < ti->narrest; ++k) {
        if (ti->arrest[k].t_arrest < 0 && gprev[k] > 0 && g1[k] <= 0) {
          PetscReal c;
          PetscCall(SlumpIntegratorLocateArrest(ti, k, tn, gprev[k], tn1, g1[k], dt, NULL, Yn, X, Y, &c));
          if (SlumpIntegratorArrestRecord(ti, k, c)) stop = PETSC_TRUE;
        }
        gprev[k] = g1[k];
      }
    }
    PetscCall(SlumpIntegratorOutputsUpTo(ti, tn, tn1, dt, &next_out, &kout, NULL, Yn, X, Y));
    if (un1 <= PetscMax(1e-3, 30.0 * (s->tol > 0 ? s->tol : 1e-4)) * un) {
      ti->t_stop[0] = tn;
      ti->t_stop[1] = tn1;
      PetscCall(PetscPrintf(comm, "exact method: the flow stopped in (%g, %g] (|u| %.3e -> %.3e)\n", (double)tn, (double)tn1, (double)un, (double)un1));
      break;
    }
    if (stop || ti->stop_requested) break;
  }
  ti->stats.newton_its = s->its;
  ti->stats.lin_solves = s->solves;
  ti->stats.lin_its    = s->lin_its;
  PetscCall(SlumpExactSolverDestroy(&s));
  PetscCall(VecDestroy(&Yn));
  PetscCall(VecDestroy(&beta));
  PetscCall(VecDestroy(&Y));
  PetscFunctionReturn(0);
}
