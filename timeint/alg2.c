/* The exact (unregularised) reference for Bingham cessation between two
 * walls: rho u_t = d/dy sigma on 0 < y < L, u = 0 at both walls for t > 0,
 * sigma = eta u_y + tau0 u_y/|u_y| where u_y != 0 and |sigma - eta u_y| <= tau0
 * where u_y = 0. Regularised models creep; this one stops in finite time.
 *
 * Discretisation: P1 elements in y (consistent mass), backward Euler in t.
 * Each step minimises the convex functional
 *   rho/(2 dt) |u - u^n|_M^2 + eta/2 sum h g_e^2 + tau0 sum h |g_e|,  g = D u,
 * by ALG2 (Glowinski, Fortin): gamma stands for g, lambda is its multiplier
 * (the plastic stress), r the augmentation; each iteration solves one
 * tridiagonal system with a fixed matrix (Thomas algorithm), shrinks gamma
 * cell by cell and updates lambda. lambda and gamma carry over between
 * steps.
 *
 * Stopping: u^{n+1} = 0 is the step's exact minimiser if and only if a
 * stress field with |sigma_e| <= tau0 balances the momentum, i.e. (cell
 * balance sigma_{i-1} - sigma_i = (rho/dt)(M u^n)_i) if and only if
 *   Phi(u^n) = rho (max C - min C)/(2 tau0) <= dt,  C_i = sum_{j<=i} (M u^n)_j.
 * Phi(u) is the time the yield stress alone needs to bring u to rest, so
 * the step is tested exactly before it is solved, and the stopping time is
 * estimated as t^n + Phi(u^n) at the last moving state. */
#include "slumptimeint.h"

/* Factor a constant symmetric tridiagonal matrix (diag d, off-diagonal o) of
 * size n for the Thomas algorithm: w holds the modified diagonal. */
static void TridiagFactor(PetscInt n, PetscReal d, PetscReal o, PetscReal *w)
{
  w[0] = d;
  for (PetscInt i = 1; i < n; ++i) w[i] = d - o * o / w[i - 1];
}

static void TridiagSolve(PetscInt n, PetscReal o, const PetscReal *w, PetscReal *x)
{
  for (PetscInt i = 1; i < n; ++i) x[i] -= o / w[i - 1] * x[i - 1];
  x[n - 1] /= w[n - 1];
  for (PetscInt i = n - 2; i >= 0; --i) x[i] = (x[i] - o * x[i + 1]) / w[i];
}

/* (M u)_i at interior node i (u has n + 1 nodal values, u_0 = u_n = 0). */
static inline PetscReal MassApply(const PetscReal *u, PetscInt i, PetscReal h)
{
  return h / 6.0 * (u[i - 1] + 4.0 * u[i] + u[i + 1]);
}

/* Phi(u) = rho (max C - min C) / (2 tau0), C the running sum of M u. */
static PetscReal StopTime(PetscInt n, const PetscReal *u, PetscReal h, PetscReal rho, PetscReal tau0)
{
  PetscReal c = 0.0, cmin = 0.0, cmax = 0.0;
  for (PetscInt i = 1; i < n; ++i) {
    c += MassApply(u, i, h);
    cmin = PetscMin(cmin, c);
    cmax = PetscMax(cmax, c);
  }
  return rho * (cmax - cmin) / (2.0 * tau0);
}

static PetscReal MeanShear(PetscInt n, const PetscReal *u, PetscReal h, PetscReal L)
{
  PetscReal s = 0.0;
  for (PetscInt e = 0; e < n; ++e) s += PetscAbsReal(u[e + 1] - u[e]);
  return s / L; /* sum_e h |g_e| / L */
}

static PetscReal Energy(PetscInt n, const PetscReal *u, PetscReal h, PetscReal rho)
{
  PetscReal e = 0.0;
  for (PetscInt i = 1; i < n; ++i) e += u[i] * MassApply(u, i, h);
  return 0.5 * rho * e;
}

PetscErrorCode SlumpBinghamStripCessation(const SlumpBinghamStripSpec *spec, SlumpBinghamStripResult *res)
{
  const PetscInt  n = spec->ncells;
  const PetscReal L = spec->L, h = L / n, rho = spec->rho, eta = spec->eta, tau0 = spec->tau0, dt = spec->dt;
  const PetscReal tol = spec->tol > 0 ? spec->tol : 1e-9;
  const PetscInt  maxit = spec->max_iter > 0 ? spec->max_iter : 100000;
  PetscReal      *u, *un, *uk, *lam, *gam, *w, *rhs, diag, off, t = 0.0, s_prev, e_prev;

  PetscFunctionBegin;
  PetscCheck(n >= 2 && L > 0 && rho > 0 && eta > 0 && tau0 > 0 && dt > 0 && spec->u0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Bingham strip reference: needs ncells >= 2, and positive L, rho, eta, tau0, dt, and an initial profile");
  PetscCall(PetscMemzero(res, sizeof(*res)));
  res->t_stop   = -1.0;
  res->t_arrest = -1.0;
  res->energy_monotone = PETSC_TRUE;
  PetscCall(PetscCalloc7(n + 1, &u, n + 1, &un, n + 1, &uk, n, &lam, n, &gam, n - 1, &w, n - 1, &rhs));
  for (PetscInt i = 1; i < n; ++i) u[i] = spec->u0(i * h, spec->ctx);
  {
    /* warm start: lambda = the plastic part of the stress, gamma = g */
    for (PetscInt e = 0; e < n; ++e) {
      const PetscReal g = (u[e + 1] - u[e]) / h;
      gam[e]            = g;
      lam[e]            = g > 0 ? tau0 : (g < 0 ? -tau0 : 0.0);
    }
  }
  {
    /* ALG2 converges fastest for r near 0.3 sqrt(rho eta L^2 / dt) (measured
       for n = 100..400, dt = 2.5e-5..1e-4, tau0 = 0.1..10; docs/sweeps.md) */
    const PetscReal ra = spec->r > 0 ? spec->r : PetscMax(eta, 0.3 * L * PetscSqrtReal(rho * eta / dt));
    res->r = ra;
    /* A = (rho/dt) M + (eta + r) K on the n - 1 interior nodes */
    diag = rho / dt * 4.0 * h / 6.0 + (eta + ra) * 2.0 / h;
    off  = rho / dt * h / 6.0 - (eta + ra) / h;
    TridiagFactor(n - 1, diag, off, w);
    s_prev        = MeanShear(n, u, h, L);
    e_prev        = Energy(n, u, h, rho);
    res->energy0  = e_prev;
    res->shear0   = s_prev;
    while (t < spec->t_max) {
      const PetscReal phi = StopTime(n, u, h, rho, tau0);
      PetscReal       s, e, unorm = 0.0;
      PetscInt        k;
      if (phi <= dt) {
        /* the next step is at rest: the flow stops within (t, t + phi] */
        res->t_stop = t + phi;
        if (spec->threshold > 0 && res->t_arrest < 0) res->t_arrest = s_prev <= spec->threshold ? t : t + phi * (s_prev - spec->threshold) / s_prev;
        res->steps++;
        break;
      }
      for (PetscInt i = 0; i <= n; ++i) un[i] = u[i];
      for (PetscInt i = 1; i < n; ++i) unorm = PetscMax(unorm, PetscAbsReal(un[i]));
      for (k = 0; k < maxit; ++k) {
        PetscReal du = 0.0, res_g = 0.0, gmax = 0.0;
        for (PetscInt i = 0; i <= n; ++i) uk[i] = u[i];
        /* u: A u = (rho/dt) M u^n - G^T (lambda - r gamma), (G^T q)_i = q_{i-1} - q_i */
        for (PetscInt i = 1; i < n; ++i) rhs[i - 1] = rho / dt * MassApply(un, i, h) - ((lam[i - 1] - ra * gam[i - 1]) - (lam[i] - ra * gam[i]));
        TridiagSolve(n - 1, off, w, rhs);
        for (PetscInt i = 1; i < n; ++i) u[i] = rhs[i - 1];
        /* gamma: shrink; lambda: multiplier update */
        for (PetscInt e = 0; e < n; ++e) {
          const PetscReal g = (u[e + 1] - u[e]) / h, th = lam[e] + ra * g, a = PetscAbsReal(th);
          gam[e] = a > tau0 ? (a - tau0) / ra * (th > 0 ? 1.0 : -1.0) : 0.0;
          lam[e] += ra * (g - gam[e]);
          res_g = PetscMax(res_g, PetscAbsReal(g - gam[e]));
          gmax  = PetscMax(gmax, PetscAbsReal(g));
        }
        for (PetscInt i = 1; i < n; ++i) du = PetscMax(du, PetscAbsReal(u[i] - uk[i]));
        if (du <= tol * unorm && res_g * L <= tol * unorm) break;
      }
      res->iterations += k + 1;
      res->max_iterations = PetscMax(res->max_iterations, k + 1);
      if (k == maxit) res->unconverged_steps++;
      t += dt;
      res->steps++;
      s = MeanShear(n, u, h, L);
      e = Energy(n, u, h, rho);
      if (e > e_prev * (1.0 + 1e-12)) res->energy_monotone = PETSC_FALSE;
      if (spec->threshold > 0 && res->t_arrest < 0 && s < spec->threshold) res->t_arrest = t - dt + dt * (s_prev - spec->threshold) / (s_prev - s);
      s_prev = s;
      e_prev = e;
    }
  }
  PetscCall(PetscFree7(u, un, uk, lam, gam, w, rhs));
  PetscFunctionReturn(0);
}

/* Both times extrapolated to dt -> 0 from the steps dt and dt/2 (backward
 * Euler: first order, so T = 2 T(dt/2) - T(dt)). */
PetscErrorCode SlumpBinghamStripReference(const SlumpBinghamStripSpec *spec, PetscReal *t_stop, PetscReal *t_arrest)
{
  SlumpBinghamStripSpec   half = *spec;
  SlumpBinghamStripResult a, b;
  PetscFunctionBegin;
  half.dt = 0.5 * spec->dt;
  PetscCall(SlumpBinghamStripCessation(spec, &a));
  PetscCall(SlumpBinghamStripCessation(&half, &b));
  *t_stop   = a.t_stop >= 0 && b.t_stop >= 0 ? 2.0 * b.t_stop - a.t_stop : -1.0;
  *t_arrest = a.t_arrest >= 0 && b.t_arrest >= 0 ? 2.0 * b.t_arrest - a.t_arrest : -1.0;
  PetscFunctionReturn(0);
}
