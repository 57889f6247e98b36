/* Bingham fluid, regularised (REFERENCES.md; Frigaard & Nouar 2005 review):
 *   exact:              ||tau|| > tau0 => tau = (eta_p + tau0/||gdot||) gdot, else gdot = 0
 *   Papanastasiou:      eta = eta_p + tau0 (1 - exp(-m ||gdot||)) / ||gdot||   (-> eta_p + tau0 m)
 *   Bercovier-Engelman: eta = eta_p + tau0 / sqrt(||gdot||^2 + eps^2)
 *   simple:             eta = eta_p + tau0 / (||gdot|| + eps)
 * Parameters: viscosity eta_p, yield_stress tau0, then m or eps. */
#include "rheologyimpl.h"

/* (1 - exp(-x))/x and its derivative, accurate for small x. */
static inline void PapanastasiouShape(PetscReal x, PetscReal *f, PetscReal *df)
{
  if (x < 1e-3) {
    /* series: 1 - x/2 + x^2/6 - x^3/24 */
    *f  = 1.0 - x / 2.0 + x * x / 6.0 - x * x * x / 24.0;
    *df = -0.5 + x / 3.0 - x * x / 8.0;
  } else {
    const PetscReal e = PetscExpReal(-x), om = -expm1(-x);
    *f  = om / x;
    *df = (e * x - om) / (x * x);
  }
}

static inline void PapanastasiouKernel(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty)
{
  const PetscReal etap = PetscRealPart(prm[0]), tau0 = PetscRealPart(prm[1]), m = PetscRealPart(prm[2]);
  PetscReal       f, df;
  PapanastasiouShape(m * g, &f, &df);
  *eta   = etap + tau0 * m * f;
  *de_dg = tau0 * m * m * df;
  *de_dp = 0.0;
  *ty    = tau0;
}

static inline void BercovierKernel(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty)
{
  const PetscReal etap = PetscRealPart(prm[0]), tau0 = PetscRealPart(prm[1]), eps = PetscRealPart(prm[2]);
  const PetscReal s    = PetscSqrtReal(g * g + eps * eps);
  *eta   = etap + tau0 / s;
  *de_dg = -tau0 * g / (s * s * s);
  *de_dp = 0.0;
  *ty    = tau0;
}

static inline void SimpleKernel(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty)
{
  const PetscReal etap = PetscRealPart(prm[0]), tau0 = PetscRealPart(prm[1]), eps = PetscRealPart(prm[2]);
  *eta   = etap + tau0 / (g + eps);
  *de_dg = -tau0 / ((g + eps) * (g + eps));
  *de_dp = 0.0;
  *ty    = tau0;
}

/* Plastic parts (slumprheology.h): tau_y = tau0, R the regularised 1/g. */
SLUMP_DEFINE_PLASTIC_CONSTANT(PapanastasiouPlastic, SLUMP_REG_PAPANASTASIOU, 1, 2)
SLUMP_DEFINE_PLASTIC_CONSTANT(BercovierPlastic, SLUMP_REG_BERCOVIER, 1, 2)
SLUMP_DEFINE_PLASTIC_CONSTANT(SimplePlastic, SLUMP_REG_SIMPLE, 1, 2)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(Papanastasiou, PapanastasiouKernel, PapanastasiouPlastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(Bercovier, BercovierKernel, BercovierPlastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(BinghamSimple, SimpleKernel, SimplePlastic)

static PetscErrorCode BinghamCommon(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyAddParameter(rheo, "viscosity", "-rheology_viscosity", "Plastic viscosity eta_p", 1.0, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddParameter(rheo, "yield_stress", "-rheology_yield_stress", "Yield stress tau0", 1.0, 0.0, PETSC_FALSE));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyCreate_Papanastasiou(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCall(BinghamCommon(rheo));
  PetscCall(SlumpRheologyAddParameter(rheo, "m", "-rheology_papanastasiou_m", "Papanastasiou exponent m (plug viscosity eta_p + tau0 m)", 1e3, 0.0, PETSC_TRUE));
  rheo->ireg               = 2;
  rheo->reg_larger_stiffer = PETSC_TRUE;
  rheo->kernel             = PapanastasiouKernel;
  rheo->plastic            = PapanastasiouPlastic;
  rheo->pointwise          = Papanastasiou_pointwise;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyCreate_Bercovier(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCall(BinghamCommon(rheo));
  PetscCall(SlumpRheologyAddParameter(rheo, "eps", "-rheology_bercovier_eps", "Bercovier-Engelman epsilon (plug viscosity eta_p + tau0/eps)", 1e-3, 0.0, PETSC_TRUE));
  rheo->ireg               = 2;
  rheo->reg_larger_stiffer = PETSC_FALSE;
  rheo->kernel             = BercovierKernel;
  rheo->plastic            = BercovierPlastic;
  rheo->pointwise          = Bercovier_pointwise;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyCreate_BinghamSimple(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCall(BinghamCommon(rheo));
  PetscCall(SlumpRheologyAddParameter(rheo, "eps", "-rheology_simple_eps", "Simple regularisation epsilon (plug viscosity eta_p + tau0/eps)", 1e-3, 0.0, PETSC_TRUE));
  rheo->ireg               = 2;
  rheo->reg_larger_stiffer = PETSC_FALSE;
  rheo->kernel             = SimpleKernel;
  rheo->plastic            = SimplePlastic;
  rheo->pointwise          = BinghamSimple_pointwise;
  PetscFunctionReturn(0);
}
