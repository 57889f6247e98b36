/* Unit test: for every registered model, three values of its regularisation
 * parameter and every regime (plug, yielded, ||gdot|| -> 0, p -> 0, p < 0,
 * below and above a free surface), d eta/d||gdot|| and d eta/dp match
 * centred finite differences to 1e-6 relative (or to the round-off level
 * 1e-9 eta/h of the difference quotient), and eta is finite and positive.
 * Also checks that invalid parameters are refused, and that the lithostatic
 * laws take the depth below a free-surface table when the kernels' constants
 * carry one. Prints nothing on success. */
#include "slumprheology.h"

static int failures = 0;

static PetscErrorCode Check(SlumpRheology r, const char *model, PetscReal g, PetscReal p, const PetscReal x[])
{
  PetscReal eta, dg, dp, ep, em, h;
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyEvaluateAt(r, g, p, x, &eta, &dg, &dp, NULL));
  if (!(eta > 0) || PetscIsInfOrNanReal(eta)) {
    printf("%s: eta(%g, %g) = %g, expected finite and positive\n", model, (double)g, (double)p, (double)eta);
    failures++;
  }
  /* d/dg: relative step, one-sided near g = 0 (the law is defined for g >= 0) */
  h = PetscMax(1e-6 * g, 1e-12);
  if (g > h) {
    PetscCall(SlumpRheologyEvaluateAt(r, g + h, p, x, &ep, NULL, NULL, NULL));
    PetscCall(SlumpRheologyEvaluateAt(r, g - h, p, x, &em, NULL, NULL, NULL));
    const PetscReal fd = (ep - em) / (2 * h), scale = PetscMax(PetscAbsReal(dg), PetscAbsReal(eta) / PetscMax(g, 1e-300) * 1e-6);
    if (PetscAbsReal(fd - dg) > 1e-6 * PetscMax(scale, 1e-300) && PetscAbsReal(fd - dg) > 1e-9 * PetscAbsReal(eta) / h) {
      printf("%s: d eta/d gdot at (%g, %g): analytic %.10e, centred FD %.10e\n", model, (double)g, (double)p, (double)dg, (double)fd);
      failures++;
    }
  }
  h = PetscMax(1e-6 * PetscAbsReal(p), 1e-8);
  PetscCall(SlumpRheologyEvaluateAt(r, g, p + h, x, &ep, NULL, NULL, NULL));
  PetscCall(SlumpRheologyEvaluateAt(r, g, p - h, x, &em, NULL, NULL, NULL));
  {
    const PetscReal fd = (ep - em) / (2 * h);
    if (PetscAbsReal(fd - dp) > 1e-6 * PetscMax(PetscAbsReal(dp), PetscAbsReal(fd)) && PetscAbsReal(fd - dp) > 1e-9 * PetscAbsReal(eta) / h) {
      printf("%s: d eta/dp at (%g, %g): analytic %.10e, centred FD %.10e\n", model, (double)g, (double)p, (double)dp, (double)fd);
      failures++;
    }
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char        list[1024], *models[64], *tok;
  size_t      nmodels = 0;
  const PetscReal xs[2][2] = {{0.0, 0.3}, {0.0, 2.0}};
  const PetscReal gs[] = {1e-9, 1e-6, 1e-4, 1e-3, 1e-2, 0.1, 1.0, 10.0, 1e3};
  const PetscReal ps[] = {-1.0, 0.0, 1e-8, 1.0, 100.0};
  const PetscReal regs[] = {1e2, 1e4, 1e6};
  SlumpRheology r;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(SlumpRheologyCreate(PETSC_COMM_WORLD, &r));
  PetscCall(SlumpRheologyListTypes(PETSC_COMM_WORLD, list, sizeof(list)));
  for (tok = strtok(list, ", "); tok; tok = strtok(NULL, ", ")) models[nmodels++] = tok;
  if (nmodels < 18) {
    printf("expected at least 18 registered models, got %d\n", (int)nmodels);
    failures++;
  }
  for (size_t m = 0; m < nmodels; ++m) {
    PetscCall(SlumpRheologySetType(r, models[m]));
    const char *regname;
    PetscReal   regval;
    PetscBool   larger;
    PetscCall(SlumpRheologyGetRegularisation(r, &regname, &regval, &larger));
    for (size_t k = 0; k < (regname ? 3 : 1); ++k) {
      if (regname) PetscCall(SlumpRheologySetParameter(r, regname, larger ? regs[k] : 1.0 / regs[k]));
      for (size_t i = 0; i < sizeof(gs) / sizeof(gs[0]); ++i)
        for (size_t j = 0; j < sizeof(ps) / sizeof(ps[0]); ++j)
          for (size_t k2 = 0; k2 < 2; ++k2) PetscCall(Check(r, models[m], gs[i], ps[j], xs[k2]));
    }
    /* plug viscosity of Papanastasiou: eta_p + tau0 m */
    if (!strcmp(models[m], SLUMP_RHEOLOGY_PAPANASTASIOU)) {
      PetscReal eta0;
      PetscCall(SlumpRheologySetParameter(r, "m", 1e4));
      PetscCall(SlumpRheologyGetPlugViscosity(r, 0.0, &eta0));
      if (PetscAbsReal(eta0 - (1.0 + 1.0 * 1e4)) > 1e-10 * eta0) {
        printf("papanastasiou plug viscosity: expected %g, got %g\n", 1.0 + 1e4, (double)eta0);
        failures++;
      }
    }
  }
  /* lithostatic yield below a surface table h = 1, 0.5, 0 at x = 0, 1, 2:
     at x = 0.5 the surface is at 0.75, so eta there equals the fixed-height
     law's (H = 2) at y + 2 - 0.75; beyond the table's ends h is constant */
  {
    SlumpRheologyPointwise pw;
    PetscScalar            c[SLUMP_C_NUM + 3] = {0}, u[3] = {0.0, 0.0, 0.3}, u_x[6] = {0.2, 1.5, -0.4, -0.2, 0.0, 0.0};
    const PetscInt         uOff[2] = {0, 2}, uOff_x[2] = {0, 4};
    const PetscReal        pts[3][2] = {{0.5, 0.2}, {1.5, 0.1}, {-1.0, 0.4}}, hs[3] = {0.75, 0.25, 1.0};
    PetscInt               n;
    PetscCall(SlumpRheologySetType(r, "litho_bercovier"));
    PetscCall(SlumpRheologySetParameter(r, "density", 3.0));
    PetscCall(SlumpRheologySetParameter(r, "gravity", 2.0));
    PetscCall(SlumpRheologySetParameter(r, "height", 2.0));
    PetscCall(SlumpRheologySetParameter(r, "eps", 0.05));
    PetscCall(SlumpRheologyGetConstants(r, &n, &c[SLUMP_C_RHEO]));
    c[SLUMP_C_SURF_N]  = 3;
    c[SLUMP_C_SURF_X0] = 0.0;
    c[SLUMP_C_SURF_DX] = 1.0;
    c[SLUMP_C_NUM]     = 1.0;
    c[SLUMP_C_NUM + 1] = 0.5;
    c[SLUMP_C_NUM + 2] = 0.0;
    PetscCall(SlumpRheologyGetPointwise(r, &pw));
    for (PetscInt k = 0; k < 3; ++k) {
      PetscScalar     eta, g;
      PetscReal       ref, hk;
      const PetscReal xs2[2] = {pts[k][0], pts[k][1] + 2.0 - hs[k]};
      pw.eta(2, 2, 0, uOff, uOff_x, u, NULL, u_x, NULL, NULL, NULL, NULL, NULL, 0.0, pts[k], SLUMP_C_NUM + 3, c, &eta);
      pw.shear_rate(2, 2, 0, uOff, uOff_x, u, NULL, u_x, NULL, NULL, NULL, NULL, NULL, 0.0, pts[k], SLUMP_C_NUM + 3, c, &g);
      PetscCall(SlumpRheologyEvaluateAt(r, PetscRealPart(g), 0.3, xs2, &ref, NULL, NULL, NULL));
      if (!SlumpSurfaceHeight(c, pts[k][0], &hk) || PetscAbsReal(hk - hs[k]) > 1e-14 || PetscAbsReal(PetscRealPart(eta) - ref) > 1e-12 * ref) {
        printf("litho_bercovier below the surface table at x = %g: h %g (expected %g), eta %.12g (expected %.12g)\n", (double)pts[k][0], (double)hk, (double)hs[k], (double)PetscRealPart(eta), (double)ref);
        failures++;
      }
    }
  }
  /* lithostatic depth with a smoothed Heaviside of half-width w = 0.2: the
     yield stress is mu rho g times the weight above, int_{-d}^{w} m(s) ds for
     a point at depth d below the surface (Simpson's rule here): d itself
     for d >= w, positive in the band above the contour, 0 above it */
  {
    SlumpRheologyPointwise pw;
    PetscScalar            c[SLUMP_C_NUM + 1] = {0}, u[3] = {0.0, 0.0, 0.3}, u_x[6] = {0.2, 1.5, -0.4, -0.2, 0.0, 0.0};
    const PetscInt         uOff[2] = {0, 2}, uOff_x[2] = {0, 4};
    const PetscReal        w = 0.2, H = 2.0, ds[5] = {0.5, 0.2, 0.05, -0.1, -0.25};
    PetscReal              eta_ref = 0.0;
    PetscInt               n;
    PetscCall(SlumpRheologySetType(r, "litho_bercovier"));
    PetscCall(SlumpRheologySetParameter(r, "viscosity", 1.0));
    PetscCall(SlumpRheologySetParameter(r, "height", H));
    PetscCall(SlumpRheologyGetConstants(r, &n, &c[SLUMP_C_RHEO]));
    c[SLUMP_C_MIX_EPS] = w;
    PetscCall(SlumpRheologyGetPointwise(r, &pw));
    for (PetscInt k = 0; k < 5; ++k) {
      const PetscReal xk[2] = {0.0, H - ds[k]}, a = -ds[k], b = w;
      PetscReal       D = 0.0;
      PetscScalar     eta;
      if (a < b) {
        const PetscInt N = 2000;
        for (PetscInt i = 0; i <= N; ++i) {
          const PetscReal sv = a + (b - a) * i / N, m = sv <= -w ? 1.0 : 0.5 * (1.0 - sv / w - PetscSinReal(PETSC_PI * sv / w) / PETSC_PI);
          D += (i == 0 || i == N ? 1.0 : (i % 2 ? 4.0 : 2.0)) * m;
        }
        D *= (b - a) / (3.0 * N);
      }
      pw.eta(2, 2, 0, uOff, uOff_x, u, NULL, u_x, NULL, NULL, NULL, NULL, NULL, 0.0, xk, SLUMP_C_NUM + 1, c, &eta);
      if (k == 0) eta_ref = PetscRealPart(eta) - 1.0; /* d = 0.5 >= w: weight 0.5 */
      else if (PetscAbsReal((PetscRealPart(eta) - 1.0) - eta_ref * D / 0.5) > 1e-9 * eta_ref) {
        printf("litho_bercovier in the mixing band, depth %g: yield part of eta %.12g, expected %.12g (weight above %.12g)\n", (double)ds[k], (double)(PetscRealPart(eta) - 1.0), (double)(eta_ref * D / 0.5), (double)D);
        failures++;
      }
    }
  }
  /* invalid parameters are refused */
  PetscCall(SlumpRheologySetType(r, SLUMP_RHEOLOGY_PAPANASTASIOU));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  PetscCall(SlumpRheologySetParameter(r, "yield_stress", -1.0));
  if (!SlumpRheologyCheck(r)) {
    printf("a negative yield stress was accepted\n");
    failures++;
  }
  PetscCall(SlumpRheologySetParameter(r, "yield_stress", 1.0));
  PetscCall(SlumpRheologySetParameter(r, "m", 0.0));
  if (!SlumpRheologyCheck(r)) {
    printf("m = 0 was accepted\n");
    failures++;
  }
  PetscCall(SlumpRheologySetType(r, "mui_cm"));
  PetscCall(SlumpRheologySetParameter(r, "I0", 0.0));
  if (!SlumpRheologyCheck(r)) {
    printf("I0 = 0 was accepted\n");
    failures++;
  }
  PetscCall(SlumpRheologySetParameter(r, "I0", 0.279));
  PetscCall(SlumpRheologySetParameter(r, "delta_mu", 0.0));
  if (!SlumpRheologyCheck(r)) {
    printf("mu_2 = mu_s (delta_mu = 0) was accepted\n");
    failures++;
  }
  PetscCall(SlumpRheologySetType(r, "hb_simple"));
  PetscCall(SlumpRheologySetParameter(r, "n", 0.5));
  PetscCall(SlumpRheologySetParameter(r, "gdot_min", 0.0));
  if (!SlumpRheologyCheck(r)) {
    printf("n < 1 with gdot_min = 0 was accepted\n");
    failures++;
  }
  PetscCall(PetscPopErrorHandler());
  PetscCall(SlumpRheologyDestroy(&r));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
