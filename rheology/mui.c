/* mu(I) rheology of dense granular flows (Jop, Forterre & Pouliquen 2006):
 *   ||tau|| = mu(I) p,  mu(I) = mu_s + dmu / (I0/I + 1),
 * regularised as in Chauchat & Medale (J. Comput. Phys. 256, 2014), with
 * I = ||gdot|| / sqrt(phi P) in their scaling and lambda_r > 0:
 *   mui_simple        (9)  eta = mu_s P/(g + lr) + dmu P/(I0 sqrt(phi P) + g + lr)
 *   mui_bercovier    (10)  first term mu_s P/sqrt(g^2 + lr^2)
 *   mui_papanastasiou (11) first term mu_s P (1 - exp(-g/lr))/g
 *   mui_cm           (12)  eta = [mu_s + dmu g/(I0 sqrt(phi P) + g)] P/sqrt(g^2 + lr^2)
 * and P = (p + sqrt(p^2 + d^2))/2, their pressure regularisation (16)
 * (d = -rheology_pressure_reg; 0 gives max(p, 0)).
 * mui_thesis (Riber 2017, eqs. 4.13-4.14):
 *   eta = dmu P/(sqrt(P/rho) I0/d + g) + mu_s P/sqrt(g^2 + gdot_min^2) + eta_min.
 * The yield stress (for yielded/unyielded diagnostics) is mu_s P. */
#include "rheologyimpl.h"

static inline void CMKernel(SlumpRegKind kind, const PetscScalar prm[], PetscReal g, PetscReal p, PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty)
{
  const PetscReal mus = PetscRealPart(prm[0]), dmu = PetscRealPart(prm[1]), I0 = PetscRealPart(prm[2]), phi = PetscRealPart(prm[3]), lr = PetscRealPart(prm[4]), d = PetscRealPart(prm[5]);
  PetscReal       P, dP, R, dR;
  SlumpPositivePressure(p, d, &P, &dP);
  const PetscReal s = PetscSqrtReal(phi * P);
  SlumpYieldShape(kind, kind == SLUMP_REG_PAPANASTASIOU ? 1.0 / lr : lr, g, &R, &dR);
  const PetscReal D = I0 * s + g + lr;
  *eta   = mus * P * R + dmu * P / D;
  *de_dg = mus * P * dR - dmu * P / (D * D);
  /* P d s/dP = s/2 keeps the derivative finite as P -> 0 */
  *de_dp = (mus * R + dmu / D - dmu * I0 * 0.5 * s / (D * D)) * dP;
  *ty    = mus * P;
}

static inline void CM12Kernel(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty)
{
  const PetscReal mus = PetscRealPart(prm[0]), dmu = PetscRealPart(prm[1]), I0 = PetscRealPart(prm[2]), phi = PetscRealPart(prm[3]), lr = PetscRealPart(prm[4]), d = PetscRealPart(prm[5]);
  PetscReal       P, dP;
  SlumpPositivePressure(p, d, &P, &dP);
  const PetscReal s = PetscSqrtReal(phi * P), Ds = I0 * s + g;
  const PetscReal M = Ds > 0 ? mus + dmu * g / Ds : mus, dMdg = Ds > 0 ? dmu * I0 * s / (Ds * Ds) : 0.0, PdMdP = Ds > 0 ? -dmu * g * I0 * 0.5 * s / (Ds * Ds) : 0.0;
  const PetscReal E = 1.0 / PetscSqrtReal(g * g + lr * lr), dE = -g * E * E * E;
  *eta   = M * P * E;
  *de_dg = P * (dMdg * E + M * dE);
  *de_dp = E * (M + PdMdP) * dP;
  *ty    = mus * P;
}

static inline void ThesisKernel(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty)
{
  const PetscReal mus = PetscRealPart(prm[0]), dmu = PetscRealPart(prm[1]), I0 = PetscRealPart(prm[2]), dg = PetscRealPart(prm[3]), rho = PetscRealPart(prm[4]);
  const PetscReal gmin = PetscRealPart(prm[5]), etamin = PetscRealPart(prm[6]), d = PetscRealPart(prm[7]);
  PetscReal       P, dP;
  SlumpPositivePressure(p, d, &P, &dP);
  const PetscReal q = PetscSqrtReal(P / rho), D = q * I0 / dg + g, w = g * g + gmin * gmin, sw = PetscSqrtReal(w);
  const PetscReal f = D > 0 ? dmu * P / D : 0.0;
  *eta   = f + mus * P / sw + etamin;
  *de_dg = (D > 0 ? -dmu * P / (D * D) : 0.0) - mus * P * g / (w * sw);
  *de_dp = ((D > 0 ? dmu / D - dmu * (I0 / dg) * 0.5 * q / (D * D) : 0.0) + mus / sw) * dP;
  *ty    = mus * P;
}

#define CM_KERNEL(NAME, KIND) \
  static inline void NAME(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty) \
  { \
    CMKernel(KIND, prm, g, p, eta, de_dg, de_dp, ty); \
  }
CM_KERNEL(CM9Kernel, SLUMP_REG_SIMPLE)
CM_KERNEL(CM10Kernel, SLUMP_REG_BERCOVIER)
CM_KERNEL(CM11Kernel, SLUMP_REG_PAPANASTASIOU)
/* Plastic parts (slumprheology.h): tau_y = mu_s P, R the static term's
   regularised 1/g (eqs. 9-11: the regularisation's own; eq. 12 and the
   thesis: 1/sqrt(g^2 + lr^2), lr = lambda_r or gdot_min). The rate-dependent
   part dmu ... stays in the primal tangent. */
static inline void CMPlastic(SlumpRegKind kind, const PetscScalar prm[], PetscReal g, PetscReal p, PetscReal *ty, PetscReal *R, PetscReal *dR)
{
  const PetscReal mus = PetscRealPart(prm[0]), lr = PetscRealPart(prm[4]), d = PetscRealPart(prm[5]);
  PetscReal       P, dP;
  SlumpPositivePressure(p, d, &P, &dP);
  *ty = mus * P;
  SlumpYieldShape(kind, kind == SLUMP_REG_PAPANASTASIOU ? 1.0 / lr : lr, g, R, dR);
}
#define CM_PLASTIC(NAME, KIND) \
  static inline void NAME(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *ty, PetscReal *R, PetscReal *dR) \
  { \
    CMPlastic(KIND, prm, g, p, ty, R, dR); \
  }
CM_PLASTIC(CM9Plastic, SLUMP_REG_SIMPLE)
CM_PLASTIC(CM10Plastic, SLUMP_REG_BERCOVIER)
CM_PLASTIC(CM11Plastic, SLUMP_REG_PAPANASTASIOU)
CM_PLASTIC(CM12Plastic, SLUMP_REG_BERCOVIER)
static inline void ThesisPlastic(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *ty, PetscReal *R, PetscReal *dR)
{
  PetscReal P, dP;
  SlumpPositivePressure(p, PetscRealPart(prm[7]), &P, &dP);
  *ty = PetscRealPart(prm[0]) * P;
  SlumpYieldShape(SLUMP_REG_BERCOVIER, PetscRealPart(prm[5]), g, R, dR);
}
SLUMP_RHEOLOGY_DEFINE_POINTWISE(CM9, CM9Kernel, CM9Plastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(CM10, CM10Kernel, CM10Plastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(CM11, CM11Kernel, CM11Plastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(CM12, CM12Kernel, CM12Plastic)
SLUMP_RHEOLOGY_DEFINE_POINTWISE(Thesis, ThesisKernel, ThesisPlastic)

/* Chauchat & Medale's glass beads as defaults. */
static PetscErrorCode Friction(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyAddParameter(rheo, "mu_s", "-rheology_mui_mu_s", "Static friction coefficient mu_s", 0.383, 0.0, PETSC_FALSE));
  PetscCall(SlumpRheologyAddParameter(rheo, "delta_mu", "-rheology_mui_delta_mu", "mu_2 - mu_s (must be > 0)", 0.26, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddParameter(rheo, "I0", "-rheology_mui_I0", "Inertial number scale I0", 0.279, 0.0, PETSC_TRUE));
  PetscFunctionReturn(0);
}

static PetscErrorCode CMCommon(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCall(Friction(rheo));
  PetscCall(SlumpRheologyAddParameter(rheo, "phi", "-rheology_mui_phi", "Solid volume fraction phi in I = ||gdot||/sqrt(phi p)", 0.6, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddParameter(rheo, "lambda_r", "-rheology_mui_lambda_r", "Regularisation lambda_r (shear rate)", 1e-4, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddParameter(rheo, "p_reg", "-rheology_pressure_reg", "Pressure regularisation d of (p + sqrt(p^2 + d^2))/2 (0: max(p, 0))", 1e-4, 0.0, PETSC_FALSE));
  rheo->ireg               = 4;
  rheo->reg_larger_stiffer = PETSC_FALSE;
  PetscFunctionReturn(0);
}

#define CM_CREATE(NAME, KERNEL, PLASTIC, PW) \
  static PetscErrorCode NAME(SlumpRheology rheo) \
  { \
    PetscFunctionBeginUser; \
    PetscCall(CMCommon(rheo)); \
    rheo->kernel    = KERNEL; \
    rheo->plastic   = PLASTIC; \
    rheo->pointwise = PW; \
    PetscFunctionReturn(0); \
  }
CM_CREATE(CreateCM9, CM9Kernel, CM9Plastic, CM9_pointwise)
CM_CREATE(CreateCM10, CM10Kernel, CM10Plastic, CM10_pointwise)
CM_CREATE(CreateCM11, CM11Kernel, CM11Plastic, CM11_pointwise)
CM_CREATE(CreateCM12, CM12Kernel, CM12Plastic, CM12_pointwise)

static PetscErrorCode CreateThesis(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCall(Friction(rheo));
  PetscCall(SlumpRheologyAddParameter(rheo, "d", "-rheology_mui_d", "Grain diameter d", 1.0, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddParameter(rheo, "rho", "-rheology_mui_rho", "Grain (bulk) density in I = d ||gdot||/sqrt(p/rho)", 1.0, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddParameter(rheo, "gdot_min", "-rheology_mui_gdot_min", "Regularisation ||gdot||_min", 1e-2, 0.0, PETSC_TRUE));
  PetscCall(SlumpRheologyAddParameter(rheo, "eta_min", "-rheology_mui_eta_min", "Lower viscosity bound eta_min (about the ambient viscosity)", 1e-4, 0.0, PETSC_FALSE));
  PetscCall(SlumpRheologyAddParameter(rheo, "p_reg", "-rheology_pressure_reg", "Pressure regularisation d of (p + sqrt(p^2 + d^2))/2 (0: max(p, 0))", 1e-4, 0.0, PETSC_FALSE));
  rheo->ireg               = 5;
  rheo->reg_larger_stiffer = PETSC_FALSE;
  rheo->kernel             = ThesisKernel;
  rheo->plastic            = ThesisPlastic;
  rheo->pointwise          = Thesis_pointwise;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpRheologyRegister_MuI(void)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyRegister("mui_simple", CreateCM9));
  PetscCall(SlumpRheologyRegister("mui_bercovier", CreateCM10));
  PetscCall(SlumpRheologyRegister("mui_papanastasiou", CreateCM11));
  PetscCall(SlumpRheologyRegister("mui_cm", CreateCM12));
  PetscCall(SlumpRheologyRegister("mui_thesis", CreateThesis));
  PetscFunctionReturn(0);
}
