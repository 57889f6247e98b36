/* The exact Bingham cessation reference (timeint/alg2.c) checks itself:
 *  - convergence in dt (backward Euler: observed order of the stopping time
 *    in [0.8, 1.25]) and in dy (P1: order in [1.8, 2.25]), Couette Bn = 1;
 *  - the extrapolated stopping times respect the energy bound of
 *    REFERENCES.md (Couette Bn 0.1, 1, 10; Poiseuille Bn 0.1, 0.5 from the
 *    Bingham profile, Bn 1 and 10 from the Newtonian one), and the kinetic
 *    energy never increases;
 *  - the mean-shear-rate arrest precedes the stop. */
#include "slumptimeint.h"

static PetscReal Couette(PetscReal y, void *ctx)
{
  return y;
}

/* steady channel flow on y in [-1, 1] (G = eta = 1), shifted to [0, 2] */
static PetscReal Poiseuille(PetscReal yy, void *ctx)
{
  const PetscReal bn = *(PetscReal *)ctx, y = PetscAbsReal(yy - 1.0);
  if (bn < 0) return 0.5 * (1.0 - y * y); /* Newtonian: ctx holds -Bn */
  if (y <= bn) return 0.5 * (1.0 - bn) * (1.0 - bn);
  return 0.5 * (1.0 - y * y) - bn * (1.0 - y);
}

static int failures = 0;

static void Check(PetscBool ok, const char *what, double got, double lo, double hi)
{
  printf("%s %s: %.6g (accepted [%.4g, %.4g])\n", ok ? "ok  " : "FAIL", what, got, lo, hi);
  if (!ok) ++failures;
}

static PetscErrorCode Stop(PetscInt n, PetscReal dt, PetscReal bn, SlumpBinghamStripResult *res)
{
  SlumpBinghamStripSpec s;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&s, sizeof(s)));
  s.L = 1.0; s.rho = 1.0; s.eta = 1.0; s.tau0 = bn; s.ncells = n; s.dt = dt; s.t_max = 1.0; s.threshold = 1e-3; s.u0 = Couette;
  PetscCall(SlumpBinghamStripCessation(&s, res));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  SlumpBinghamStripResult r[3];
  PetscReal               d1, d2, p;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  /* dt: 2e-4, 1e-4, 5e-5 on 200 cells */
  for (int k = 0; k < 3; ++k) PetscCall(Stop(200, 2e-4 / (1 << k), 1.0, &r[k]));
  d1 = r[0].t_stop - r[1].t_stop;
  d2 = r[1].t_stop - r[2].t_stop;
  p  = PetscLog2Real(d1 / d2);
  printf("dt 2e-4, 1e-4, 5e-5: t_stop %.10f %.10f %.10f\n", (double)r[0].t_stop, (double)r[1].t_stop, (double)r[2].t_stop);
  Check(p >= 0.8 && p <= 1.25, "observed order in dt", p, 0.8, 1.25);
  /* dy: 50, 100, 200 cells at dt 5e-5 */
  for (int k = 0; k < 3; ++k) PetscCall(Stop(50 << k, 5e-5, 1.0, &r[k]));
  d1 = r[0].t_stop - r[1].t_stop;
  d2 = r[1].t_stop - r[2].t_stop;
  p  = PetscLog2Real(PetscAbsReal(d1 / d2));
  printf("cells 50, 100, 200: t_stop %.10f %.10f %.10f\n", (double)r[0].t_stop, (double)r[1].t_stop, (double)r[2].t_stop);
  Check(p >= 1.8 && p <= 2.25, "observed order in dy", p, 1.8, 2.25);
  Check(r[2].t_arrest < r[2].t_stop ? PETSC_TRUE : PETSC_FALSE, "arrest (mean shear rate < 1e-3) before the stop, t_stop - t_arrest", (double)(r[2].t_stop - r[2].t_arrest), 0, (double)r[2].t_stop);

  /* the energy bound */
  {
    const PetscReal bns[3] = {0.1, 1.0, 10.0};
    for (int k = 0; k < 3; ++k) {
      SlumpBinghamStripSpec s;
      PetscReal             ts, ta, bound = PetscLogReal(1.0 + PETSC_PI * PETSC_PI / (2.0 * PetscSqrtReal(3.0) * bns[k])) / (PETSC_PI * PETSC_PI);
      char                  what[128];
      PetscCall(PetscMemzero(&s, sizeof(s)));
      s.L = 1.0; s.rho = 1.0; s.eta = 1.0; s.tau0 = bns[k]; s.ncells = 200; s.dt = bound / 500; s.t_max = 2.0 * bound; s.u0 = Couette;
      PetscCall(SlumpBinghamStripCessation(&s, &r[0]));
      PetscCall(SlumpBinghamStripReference(&s, &ts, &ta));
      snprintf(what, sizeof(what), "Couette Bn %g: t_stop / bound (bound %.6g, t_stop %.8g)", (double)bns[k], (double)bound, (double)ts);
      Check(ts > 0 && ts <= bound ? PETSC_TRUE : PETSC_FALSE, what, ts / bound, 0, 1);
      snprintf(what, sizeof(what), "Couette Bn %g: kinetic energy never increases", (double)bns[k]);
      Check(r[0].energy_monotone, what, r[0].energy_monotone, 1, 1);
    }
  }
  {
    const PetscReal bns[4] = {0.1, 0.5, -1.0, -10.0}; /* < 0: Newtonian initial flow */
    for (int k = 0; k < 4; ++k) {
      SlumpBinghamStripSpec s;
      PetscReal             ts, ta, bn = PetscAbsReal(bns[k]), u2 = 0.0, bound;
      const PetscInt        nq = 20000;
      char                  what[160];
      for (PetscInt q = 0; q < nq; ++q) {
        PetscReal y = 2.0 * (q + 0.5) / nq, v = Poiseuille(y, (void *)&bns[k]);
        u2 += v * v * 2.0 / nq;
      }
      bound = 4.0 / (PETSC_PI * PETSC_PI) * PetscLogReal(1.0 + PETSC_PI * PETSC_PI * PetscSqrtReal(u2) / (4.0 * PetscSqrtReal(2.0) * bn));
      PetscCall(PetscMemzero(&s, sizeof(s)));
      s.L = 2.0; s.rho = 1.0; s.eta = 1.0; s.tau0 = bn; s.ncells = 200; s.dt = bound / 500; s.t_max = 2.0 * bound; s.u0 = Poiseuille; s.ctx = (void *)&bns[k];
      PetscCall(SlumpBinghamStripCessation(&s, &r[0]));
      PetscCall(SlumpBinghamStripReference(&s, &ts, &ta));
      snprintf(what, sizeof(what), "Poiseuille Bn %g (%s initial flow): t_stop / bound (bound %.6g, t_stop %.8g)", (double)bn, bns[k] < 0 ? "Newtonian" : "Bingham", (double)bound, (double)ts);
      Check(ts > 0 && ts <= bound ? PETSC_TRUE : PETSC_FALSE, what, ts / bound, 0, 1);
      snprintf(what, sizeof(what), "Poiseuille Bn %g: kinetic energy never increases", (double)bn);
      Check(r[0].energy_monotone, what, r[0].energy_monotone, 1, 1);
    }
  }
  PetscCall(PetscFinalize());
  if (failures) printf("%d check(s) failed\n", failures);
  return failures ? 1 : 0;
}
