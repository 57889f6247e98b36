/* Herschel-Bulkley fluid (REFERENCES.md): ||tau|| > tau0 => ||tau|| = tau0 + K ||gdot||^n,
 * regularised like Bingham, with the power-law part kept finite at rest:
 *   eta = tau0 R(||gdot||) + K (||gdot||^2 + gdot_min^2)^((n-1)/2),
 * R = 1/(g + eps) (hb_simple), 1/sqrt(g^2 + eps^2) (hb_bercovier),
 *     (1 - exp(-m g))/g (hb_papanastasiou).
 * n = 1 gives Bingham with eta_p = K. Parameters: consistency K, index n,
 * yield_stress tau0, eps or m, gdot_min. */
#include "rheologyimpl.h"

static inline void HBKernel(SlumpRegKind kind, const PetscScalar prm[], PetscReal g, PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty)
{
  const PetscReal K = PetscRealPart(prm[0]), n = PetscRealPart(prm[1]), tau0 = PetscRealPart(prm[2]), r = PetscRealPart(prm[3]), gmin = PetscRealPart(prm[4]);
  const PetscReal q = g * g + gmin * gmin;
  PetscReal       R, dR;
  SlumpYieldShape(kind, r, g, &R, &dR);
  const PetscReal pl = (n == 1.0) ? 1.0 : PetscPowReal(q, 0.5 * (n - 1.0));
  *eta   = tau0 * R + K * pl;
  *de_dg = tau0 * dR + ((n == 1.0) ? 0.0 : K * (n - 1.0) * g * pl / q);
  *de_dp = 0.0;
  *ty    = tau0;
}

#define HB_KERNEL(NAME, KIND) \
  static inline void NAME(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty) \
  { \
    HBKernel(KIND, prm, g, eta, de_dg, de_dp, ty); \
  }
HB_KERNEL(HBSimpleKernel, SLUMP_REG_SIMPLE)
HB_KERNEL(HBBercovierKernel, SLUMP_REG_BERCOVIER)
HB_KERNEL(HBPapanastasiouKernel, SLUMP_REG_PAPANASTASIOU)
/* Plastic parts: tau_y = tau0 and the regularised 1/g of the yield term. */
SLUMP_DEFINE_PLASTIC_CONSTANT(HBSimplePlastic, SLUMP_REG_SIMPLE, 2, 3)
SLUMP_DEFINE_PLASTIC_CONSTANT(HBBercovierPlastic, SLUMP_REG_BERCOVIER, 2, 3)
SLUMP_DEFINE_PLASTIC_CONSTANT(HBPapanastasiouPlastic, SLUMP_REG_PAPANASTASIOU, 2, 3)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(HBSimple, HBSimpleKernel, HBSimplePlastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(HBBercovier, HBBercovierKernel, HBBercovierPlastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(HBPapanastasiou, HBPapanastasiouKernel, HBPapanastasiouPlastic)

static PetscErrorCode HBCheck(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCheck(rheo->param[1].value >= 1.0 || rheo->param[4].value > 0.0, rheo->comm, PETSC_ERR_USER_INPUT, "-rheology_hb_gdot_min must be > 0 when the flow index -rheology_hb_n = %g is below 1 (the viscosity is infinite at rest)", (double)rheo->param[1].value);
  PetscFunctionReturn(0);
}

static PetscErrorCode HBCommon(SlumpRheology rheo, SlumpRegKind kind)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyAddParameter(rheo, "consistency", "-rheology_hb_K", "Consistency K", 1.0, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddParameter(rheo, "n", "-rheology_hb_n", "Flow index n", 0.5, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddParameter(rheo, "yield_stress", "-rheology_yield_stress", "Yield stress tau0", 1.0, 0.0, PETSC_FALSE));
  PetscCall(SlumpRheologyAddRegularisation(rheo, kind));
  PetscCall(SlumpRheologyAddParameter(rheo, "gdot_min", "-rheology_hb_gdot_min", "Shear rate keeping the power-law viscosity finite at rest", 1e-6, 0.0, PETSC_FALSE));
  rheo->ops.check = HBCheck;
  PetscFunctionReturn(0);
}

#define HB_CREATE(NAME, KIND, KERNEL, PLASTIC, PW) \
  static PetscErrorCode NAME(SlumpRheology rheo) \
  { \
    PetscFunctionBeginUser; \
    PetscCall(HBCommon(rheo, KIND)); \
    rheo->kernel    = KERNEL; \
    rheo->plastic   = PLASTIC; \
    rheo->pointwise = PW; \
    PetscFunctionReturn(0); \
  }
HB_CREATE(CreateHBSimple, SLUMP_REG_SIMPLE, HBSimpleKernel, HBSimplePlastic, HBSimple_pointwise)
HB_CREATE(CreateHBBercovier, SLUMP_REG_BERCOVIER, HBBercovierKernel, HBBercovierPlastic, HBBercovier_pointwise)
HB_CREATE(CreateHBPapanastasiou, SLUMP_REG_PAPANASTASIOU, HBPapanastasiouKernel, HBPapanastasiouPlastic, HBPapanastasiou_pointwise)

PetscErrorCode SlumpRheologyRegister_HerschelBulkley(void)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyRegister("hb_papanastasiou", CreateHBPapanastasiou));
  PetscCall(SlumpRheologyRegister("hb_bercovier", CreateHBBercovier));
  PetscCall(SlumpRheologyRegister("hb_simple", CreateHBSimple));
  PetscFunctionReturn(0);
}
