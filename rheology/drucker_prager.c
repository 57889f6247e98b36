/* Frictional yield stresses with a viscous part (Chupin, Dubois & Phan 2019;
 * REFERENCES.md):
 *   Drucker-Prager:  tau_y = mu P(p),  P = (p + sqrt(p^2 + d^2))/2 (eq. 16 of
 *                    Chauchat & Medale; max(p, 0) when d = 0),
 *   lithostatic:     tau_y = mu rho g (H - y)_+  (independent of p; H the
 *                    fixed height, or the current free-surface height h(x)
 *                    when the problem hands the kernels a surface table),
 *   eta = eta_p + tau_y R(||gdot||),
 * R = 1/(g + eps) (_simple), 1/sqrt(g^2 + eps^2) (_bercovier),
 *     (1 - exp(-m g))/g (_papanastasiou).
 * Types dp_* and litho_*. */
#include "rheologyimpl.h"

static inline void DPKernel(SlumpRegKind kind, const PetscScalar prm[], PetscReal g, PetscReal p, PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty)
{
  const PetscReal etap = PetscRealPart(prm[0]), mu = PetscRealPart(prm[1]), r = PetscRealPart(prm[2]), d = PetscRealPart(prm[3]);
  PetscReal       R, dR, P, dP;
  SlumpYieldShape(kind, r, g, &R, &dR);
  SlumpPositivePressure(p, d, &P, &dP);
  *eta   = etap + mu * P * R;
  *de_dg = mu * P * dR;
  *de_dp = mu * R * dP;
  *ty    = mu * P;
}

/* The weight above a point at depth d below a flat surface, per unit rho g.
   In one phase (w = 0) it is max(d, 0). With a smoothed Heaviside of
   half-width w, the density is rho m(phi), phi = -d, and the weight above is
   int_{-d}^{w} m(s) ds: d itself once d >= w (the band's excess above the
   contour and its deficit below cancel), and positive in the band above the
   contour, whose material would otherwise carry no yield stress at all and
   flow down any slope. (A filtered level set, E > 0, is treated as a
   distance here.) */
static inline PetscReal LithoDepth(PetscReal d, PetscReal w)
{
  const PetscReal s = -d;
  if (w <= 0) return d > 0 ? d : 0.0;
  if (d >= w) return d;
  if (d <= -w) return 0.0;
  /* int_s^w m = M(w) - M(s), M(s) = (s - s^2/(2w) + w cos(pi s/w)/pi^2)/2 */
  return 0.5 * (0.5 * w - w / (PETSC_PI * PETSC_PI)) - 0.5 * (s - s * s / (2.0 * w) + w * PetscCosReal(PETSC_PI * s / w) / (PETSC_PI * PETSC_PI));
}

/* prm is constants + SLUMP_C_RHEO (the kernels' layout): when the problem
   carries a free-surface table, H is the current surface height h(x). */
static inline PetscReal LithoYieldStress(const PetscScalar prm[], const PetscReal x[])
{
  const PetscReal mu = PetscRealPart(prm[1]), rho = PetscRealPart(prm[2]), grav = PetscRealPart(prm[3]);
  PetscReal       H  = PetscRealPart(prm[4]);
  if (x) (void)SlumpSurfaceHeight(prm - SLUMP_C_RHEO, x[0], &H);
  return mu * rho * grav * LithoDepth(H - (x ? x[1] : 0.0), PetscRealPart(prm[SLUMP_C_MIX_EPS - SLUMP_C_RHEO]));
}
static inline void LithoKernel(SlumpRegKind kind, const PetscScalar prm[], PetscReal g, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty)
{
  const PetscReal etap = PetscRealPart(prm[0]), r = PetscRealPart(prm[5]), tauy = LithoYieldStress(prm, x);
  PetscReal       R, dR;
  SlumpYieldShape(kind, r, g, &R, &dR);
  *eta   = etap + tauy * R;
  *de_dg = tauy * dR;
  *de_dp = 0.0;
  *ty    = tauy;
}

#define DP_KERNEL(NAME, KIND) \
  static inline void NAME(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty) \
  { \
    DPKernel(KIND, prm, g, p, eta, de_dg, de_dp, ty); \
  }
#define LITHO_KERNEL(NAME, KIND) \
  static inline void NAME(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty) \
  { \
    LithoKernel(KIND, prm, g, x, eta, de_dg, de_dp, ty); \
  }
/* Plastic parts (slumprheology.h): tau_y = mu P or the lithostatic
   mu rho g depth, R the regularised 1/g. */
#define DP_PLASTIC(NAME, KIND) \
  static inline void NAME(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *ty, PetscReal *R, PetscReal *dR) \
  { \
    PetscReal P, dP; \
    SlumpPositivePressure(p, PetscRealPart(prm[3]), &P, &dP); \
    *ty = PetscRealPart(prm[1]) * P; \
    SlumpYieldShape(KIND, PetscRealPart(prm[2]), g, R, dR); \
  }
#define LITHO_PLASTIC(NAME, KIND) \
  static inline void NAME(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *ty, PetscReal *R, PetscReal *dR) \
  { \
    *ty = LithoYieldStress(prm, x); \
    SlumpYieldShape(KIND, PetscRealPart(prm[5]), g, R, dR); \
  }
DP_PLASTIC(DPSimplePlastic, SLUMP_REG_SIMPLE)
DP_PLASTIC(DPBercovierPlastic, SLUMP_REG_BERCOVIER)
DP_PLASTIC(DPPapanastasiouPlastic, SLUMP_REG_PAPANASTASIOU)
LITHO_PLASTIC(LithoSimplePlastic, SLUMP_REG_SIMPLE)
LITHO_PLASTIC(LithoBercovierPlastic, SLUMP_REG_BERCOVIER)
LITHO_PLASTIC(LithoPapanastasiouPlastic, SLUMP_REG_PAPANASTASIOU)
DP_KERNEL(DPSimpleKernel, SLUMP_REG_SIMPLE)
DP_KERNEL(DPBercovierKernel, SLUMP_REG_BERCOVIER)
DP_KERNEL(DPPapanastasiouKernel, SLUMP_REG_PAPANASTASIOU)
LITHO_KERNEL(LithoSimpleKernel, SLUMP_REG_SIMPLE)
LITHO_KERNEL(LithoBercovierKernel, SLUMP_REG_BERCOVIER)
LITHO_KERNEL(LithoPapanastasiouKernel, SLUMP_REG_PAPANASTASIOU)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(DPSimple, DPSimpleKernel, DPSimplePlastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(DPBercovier, DPBercovierKernel, DPBercovierPlastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(DPPapanastasiou, DPPapanastasiouKernel, DPPapanastasiouPlastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(LithoSimple, LithoSimpleKernel, LithoSimplePlastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(LithoBercovier, LithoBercovierKernel, LithoBercovierPlastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(LithoPapanastasiou, LithoPapanastasiouKernel, LithoPapanastasiouPlastic)

static PetscErrorCode DPCommon(SlumpRheology rheo, SlumpRegKind kind)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyAddParameter(rheo, "viscosity", "-rheology_viscosity", "Viscous part eta_p", 1.0, 0.0, PETSC_FALSE));
  PetscCall(SlumpRheologyAddParameter(rheo, "mu", "-rheology_dp_mu", "Friction coefficient mu (tan of the friction angle)", 0.5, 0.0, PETSC_FALSE));
  PetscCall(SlumpRheologyAddRegularisation(rheo, kind));
  PetscCall(SlumpRheologyAddParameter(rheo, "p_reg", "-rheology_pressure_reg", "Pressure regularisation d of (p + sqrt(p^2 + d^2))/2 (0: max(p, 0))", 1e-4, 0.0, PETSC_FALSE));
  PetscFunctionReturn(0);
}

static PetscErrorCode LithoCommon(SlumpRheology rheo, SlumpRegKind kind)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyAddParameter(rheo, "viscosity", "-rheology_viscosity", "Viscous part eta_p", 1.0, 0.0, PETSC_FALSE));
  PetscCall(SlumpRheologyAddParameter(rheo, "mu", "-rheology_dp_mu", "Friction coefficient mu", 0.5, 0.0, PETSC_FALSE));
  PetscCall(SlumpRheologyAddParameter(rheo, "density", "-rheology_litho_density", "Density in the lithostatic yield stress", 1.0, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddParameter(rheo, "gravity", "-rheology_litho_gravity", "Gravity in the lithostatic yield stress", 1.0, 0.0, PETSC_FALSE));
  PetscCall(SlumpRheologyAddParameter(rheo, "height", "-rheology_litho_height", "Height H of the free surface (yield stress mu rho g (H - y))", 1.0, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddRegularisation(rheo, kind));
  PetscFunctionReturn(0);
}

/* The viscosity must stay positive: eta_p > 0 or a yield term everywhere. */
static PetscErrorCode DPCheck(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCheck(rheo->param[0].value > 0 || rheo->param[3].value > 0, rheo->comm, PETSC_ERR_USER_INPUT, "-rheology_viscosity must be positive when -rheology_pressure_reg is 0 (the viscosity would vanish where p <= 0)");
  PetscFunctionReturn(0);
}

static PetscErrorCode LithoCheck(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCheck(rheo->param[0].value > 0, rheo->comm, PETSC_ERR_USER_INPUT, "-rheology_viscosity must be positive for the lithostatic model (its yield stress vanishes above the free surface)");
  PetscFunctionReturn(0);
}

#define CREATE(NAME, COMMON, KIND, KERNEL, PLASTIC, PW, CHECK) \
  static PetscErrorCode NAME(SlumpRheology rheo) \
  { \
    PetscFunctionBeginUser; \
    PetscCall(COMMON(rheo, KIND)); \
    rheo->kernel    = KERNEL; \
    rheo->plastic   = PLASTIC; \
    rheo->pointwise = PW; \
    rheo->ops.check = CHECK; \
    PetscFunctionReturn(0); \
  }
CREATE(CreateDPSimple, DPCommon, SLUMP_REG_SIMPLE, DPSimpleKernel, DPSimplePlastic, DPSimple_pointwise, DPCheck)
CREATE(CreateDPBercovier, DPCommon, SLUMP_REG_BERCOVIER, DPBercovierKernel, DPBercovierPlastic, DPBercovier_pointwise, DPCheck)
CREATE(CreateDPPapanastasiou, DPCommon, SLUMP_REG_PAPANASTASIOU, DPPapanastasiouKernel, DPPapanastasiouPlastic, DPPapanastasiou_pointwise, DPCheck)
CREATE(CreateLithoSimple, LithoCommon, SLUMP_REG_SIMPLE, LithoSimpleKernel, LithoSimplePlastic, LithoSimple_pointwise, LithoCheck)
CREATE(CreateLithoBercovier, LithoCommon, SLUMP_REG_BERCOVIER, LithoBercovierKernel, LithoBercovierPlastic, LithoBercovier_pointwise, LithoCheck)
CREATE(CreateLithoPapanastasiou, LithoCommon, SLUMP_REG_PAPANASTASIOU, LithoPapanastasiouKernel, LithoPapanastasiouPlastic, LithoPapanastasiou_pointwise, LithoCheck)

PetscErrorCode SlumpRheologyRegister_DruckerPrager(void)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyRegister("dp_papanastasiou", CreateDPPapanastasiou));
  PetscCall(SlumpRheologyRegister("dp_bercovier", CreateDPBercovier));
  PetscCall(SlumpRheologyRegister("dp_simple", CreateDPSimple));
  PetscCall(SlumpRheologyRegister("litho_papanastasiou", CreateLithoPapanastasiou));
  PetscCall(SlumpRheologyRegister("litho_bercovier", CreateLithoBercovier));
  PetscCall(SlumpRheologyRegister("litho_simple", CreateLithoSimple));
  PetscFunctionReturn(0);
}
