/* Private: inline helpers shared by the pointwise kernels (quadrature-point
 * code only: no allocation, no MPI, no PETSc object calls).
 *
 * Norm convention: gdot = grad u + grad u^T, ||gdot|| = sqrt(1/2 gdot:gdot),
 * tau = eta gdot. u_x[c*dim + d] = d u_c / d x_d. */
#pragma once

#include "slumprheology.h"

#define SLUMP_PW_ARGS \
  PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], \
    const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, const PetscReal x[], \
    PetscInt numConstants, const PetscScalar constants[]
#define SLUMP_PWJ_ARGS \
  PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], \
    const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, PetscReal u_tShift, \
    const PetscReal x[], PetscInt numConstants, const PetscScalar constants[]

/* Below this shear rate the tangent's rank-one term (O(||gdot||)) is dropped. */
#define SLUMP_GDOT_TINY 1e-300

/* gd[dim*dim] = grad u + grad u^T; returns ||gdot||. */
static inline PetscReal SlumpPwStrainRate(PetscInt dim, const PetscScalar u_x[], PetscScalar gd[])
{
  PetscReal s = 0.0;
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt d = 0; d < dim; ++d) {
      gd[c * dim + d] = u_x[c * dim + d] + u_x[d * dim + c];
      s += PetscRealPart(gd[c * dim + d] * gd[c * dim + d]);
    }
  return PetscSqrtReal(0.5 * s);
}

/* Either formulation: plane (u vector, p) or anti-plane (one scalar w with
   ||gdot|| = |grad w|, no pressure). Returns ||gdot|| and the pressure (0). */
static inline PetscReal SlumpPwShearRateAny(PetscInt dim, PetscInt Nf, const PetscInt uOff[], const PetscScalar u[], const PetscScalar u_x[], PetscReal *p)
{
  if (uOff[1] - uOff[0] == 1) { /* anti-plane */
    PetscReal s = 0.0;
    for (PetscInt d = 0; d < dim; ++d) s += PetscRealPart(u_x[d] * u_x[d]);
    *p = 0.0;
    return PetscSqrtReal(s);
  } else {
    PetscScalar gd[9];
    *p = Nf > 1 ? PetscRealPart(u[uOff[1]]) : 0.0;
    return SlumpPwStrainRate(dim, u_x, gd);
  }
}

/* The same with the hoop strain 2 u_r / r of the axisymmetric geometry when
   a kernel is called by PETSc's own loops (projections: dim 2, no hoop
   entry; our cell loop calls with dim 3 and the entry in u_x). */
static inline PetscReal SlumpPwShearRateAxi(PetscInt dim, PetscInt Nf, const PetscInt uOff[], const PetscScalar u[], const PetscScalar u_x[], const PetscReal x[], const PetscScalar constants[], PetscReal *p)
{
  const PetscInt ax = (PetscInt)PetscRealPart(constants[SLUMP_C_AXIS]) - 1;
  PetscReal      g  = SlumpPwShearRateAny(dim, Nf, uOff, u, u_x, p);
  if (ax >= 0 && dim == 2 && x[ax] > 0) {
    const PetscReal h = PetscRealPart(u[uOff[0] + ax]) / x[ax];
    g = PetscSqrtReal(g * g + 2.0 * h * h);
  }
  return g;
}

/* The boundary kernels' weight (PETSc's face loop): the radius, or 1. */
static inline PetscReal SlumpPwBoundaryWeight(const PetscReal x[], const PetscScalar constants[])
{
  const PetscInt ax = (PetscInt)PetscRealPart(constants[SLUMP_C_AXIS]) - 1;
  return ax >= 0 ? x[ax] : 1.0;
}

/* Anti-plane: f1 = eta grad w; g3 = eta I + eta' grad w grad w^T / |grad w|. */
static inline void SlumpPwF1AntiPlane(PetscInt dim, const PetscScalar w_x[], const PetscReal x[], const PetscScalar prm[], SlumpViscosityKernel k, PetscScalar f1[])
{
  PetscReal s = 0.0, eta, de_dg, de_dp, ty;
  for (PetscInt d = 0; d < dim; ++d) s += PetscRealPart(w_x[d] * w_x[d]);
  k(prm, PetscSqrtReal(s), 0.0, x, &eta, &de_dg, &de_dp, &ty);
  for (PetscInt d = 0; d < dim; ++d) f1[d] = eta * w_x[d];
}

/* Stress-velocity Newton: the plastic part of the tangent's rank-one term.
   The primal tangent carries m tau_y R'(g)/g gdot (x) gdot (m: the material
   fraction); with the plastic stress S held as its own variable it becomes
   m R'/(R g) sym(S (x) gdot). Returns rp, the primal coefficient to remove,
   and cS, the coefficient of sym(S (x) gdot). Both 0 without S or a plastic
   kernel, or at rest. */
static inline void SlumpPwPlasticTangent(SlumpPlasticKernel pk, const PetscScalar *S, const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal m, PetscReal *rp, PetscReal *cS)
{
  PetscReal ty, R, dR;
  *rp = *cS = 0.0;
  if (!pk || !S || !(g > SLUMP_GDOT_TINY)) return;
  pk(prm, g, p, x, &ty, &R, &dR);
  *rp = m * ty * dR / g;
  *cS = R > 0 ? m * dR / (R * g) : 0.0;
}

static inline void SlumpPwG3AntiPlane(PetscInt dim, const PetscScalar w_x[], const PetscReal x[], const PetscScalar prm[], PetscInt jacmode, SlumpViscosityKernel k, SlumpPlasticKernel pk, const PetscScalar *S, PetscScalar g3[])
{
  PetscReal s = 0.0, g, eta, de_dg, de_dp, ty, rp, cS;
  for (PetscInt d = 0; d < dim * dim; ++d) g3[d] = 0.0;
  if (jacmode == 1) return;
  for (PetscInt d = 0; d < dim; ++d) s += PetscRealPart(w_x[d] * w_x[d]);
  g = PetscSqrtReal(s);
  k(prm, g, 0.0, x, &eta, &de_dg, &de_dp, &ty);
  SlumpPwPlasticTangent(pk, S, prm, g, 0.0, x, 1.0, &rp, &cS);
  const PetscReal r = g > SLUMP_GDOT_TINY ? de_dg / g - rp : 0.0;
  for (PetscInt d = 0; d < dim; ++d)
    for (PetscInt e = 0; e < dim; ++e) g3[d * dim + e] = r * w_x[d] * w_x[e] + (d == e ? eta : 0.0) + (cS != 0.0 ? 0.5 * cS * (S[d] * w_x[e] + w_x[d] * S[e]) : 0.0);
}

/* The dual variable's update at one quadrature point (stress-velocity
   Newton). The plastic law multiplied through, S / R(g) = tau_y gdot, is
   linearised in (gdot, S) at the linearisation point; after the Newton
   correction dgdot it gives
     S <- tau_y R(g) (gdot + dgdot) + R'/(R g) S (1/2 gdot : dgdot)
   (the anti-plane form with grad w and grad w . grad dw), then S is scaled
   back into ||S|| <= tau_y, tau_y taken at the corrected pressure. Without
   a correction (dgrad NULL) S = tau_y R(g) gdot, the consistent value.
   grad: u_x (plane, dim x dim) or grad w (anti-plane, dim). */
static inline void SlumpPwDualUpdate(PetscInt dim, PetscBool antiplane, const PetscScalar grad[], PetscReal p, const PetscScalar dgrad[], PetscReal dp, const PetscReal x[], const PetscScalar prm[], SlumpPlasticKernel pk, PetscScalar S[])
{
  PetscScalar gd[9], dgd[9];
  PetscReal   g, ty, R, dR, ty1, R1, dR1, c = 0.0, gdg = 0.0, nS = 0.0;
  const PetscInt n = antiplane ? dim : dim * dim;
  const PetscReal half = antiplane ? 1.0 : 0.5;
  if (!pk) {
    for (PetscInt i = 0; i < n; ++i) S[i] = 0.0;
    return;
  }
  if (antiplane) {
    PetscReal s = 0.0;
    for (PetscInt d = 0; d < dim; ++d) {
      gd[d]  = grad[d];
      dgd[d] = dgrad ? dgrad[d] : 0.0;
      s += PetscRealPart(gd[d] * gd[d]);
    }
    g = PetscSqrtReal(s);
  } else {
    g = SlumpPwStrainRate(dim, grad, gd);
    if (dgrad) (void)SlumpPwStrainRate(dim, dgrad, dgd);
    else
      for (PetscInt i = 0; i < n; ++i) dgd[i] = 0.0;
  }
  pk(prm, g, p, x, &ty, &R, &dR);
  if (dgrad) {
    pk(prm, g, p + dp, x, &ty1, &R1, &dR1);
    if (g > SLUMP_GDOT_TINY && R > 0) c = dR / (R * g);
    for (PetscInt i = 0; i < n; ++i) gdg += half * PetscRealPart(gd[i] * dgd[i]);
    for (PetscInt i = 0; i < n; ++i) S[i] = ty1 * R * (gd[i] + dgd[i]) + c * S[i] * gdg;
  } else {
    ty1 = ty;
    for (PetscInt i = 0; i < n; ++i) S[i] = ty * R * gd[i];
  }
  for (PetscInt i = 0; i < n; ++i) nS += half * PetscRealPart(S[i] * S[i]);
  nS = PetscSqrtReal(nS);
  if (nS > ty1) {
    const PetscReal f = ty1 > 0 ? ty1 / nS : 0.0;
    for (PetscInt i = 0; i < n; ++i) S[i] *= f;
  }
}

/* Two-phase mixing: the material fraction m = 1 - H(d - shift) of the
   smoothed Heaviside of half-width w = constants[SLUMP_C_MIX_EPS] (d < 0:
   material), and dm/dphi. d is the distance: phi itself, or
   E atanh(phi/E) for a filtered level set (E = constants[SLUMP_C_MIX_FILTER]
   > 0, the convective reinitialisation), whose phi never exceeds E and
   would leave a band wider than E mixed for ever. */
static inline void SlumpPwMaterialFractionShifted(PetscScalar phi, PetscReal shift, const PetscScalar constants[], PetscReal *m, PetscReal *dm)
{
  const PetscReal w = PetscRealPart(constants[SLUMP_C_MIX_EPS]), E = PetscRealPart(constants[SLUMP_C_MIX_FILTER]);
  PetscReal       p = PetscRealPart(phi), dd = 1.0;
  if (E > 0) {
    const PetscReal r = PetscMax(-1.0 + 1e-12, PetscMin(1.0 - 1e-12, p / E));
    p                 = 0.5 * E * PetscLogReal((1.0 + r) / (1.0 - r));
    dd                = 1.0 / (1.0 - r * r);
  }
  p -= shift;
  if (p <= -w) {
    *m  = 1.0;
    *dm = 0.0;
  } else if (p >= w) {
    *m  = 0.0;
    *dm = 0.0;
  } else {
    *m  = 0.5 * (1.0 - p / w - PetscSinReal(PETSC_PI * p / w) / PETSC_PI);
    *dm = -0.5 * (1.0 + PetscCosReal(PETSC_PI * p / w)) / w * dd;
  }
}
static inline void SlumpPwMaterialFraction(PetscScalar phi, const PetscScalar constants[], PetscReal *m, PetscReal *dm)
{
  SlumpPwMaterialFractionShifted(phi, 0.0, constants, m, dm);
}
/* d^2 m / d phi^2 of the unshifted fraction (the skew term's Jacobian) */
static inline void SlumpPwMaterialFractionCurvature(PetscScalar phi, const PetscScalar constants[], PetscReal *d2m)
{
  const PetscReal w = PetscRealPart(constants[SLUMP_C_MIX_EPS]), E = PetscRealPart(constants[SLUMP_C_MIX_FILTER]);
  PetscReal       p = PetscRealPart(phi), dd = 1.0, ddd = 0.0;
  if (E > 0) {
    const PetscReal r = p / E;
    if (r <= -1.0 + 1e-12 || r >= 1.0 - 1e-12) {
      *d2m = 0.0;
      return;
    }
    p   = 0.5 * E * PetscLogReal((1.0 + r) / (1.0 - r));
    dd  = 1.0 / (1.0 - r * r);
    ddd = 2.0 * r * dd * dd / E;
  }
  if (p <= -w || p >= w) *d2m = 0.0;
  else *d2m = 0.5 * PETSC_PI * PetscSinReal(PETSC_PI * p / w) / (w * w) * dd * dd - 0.5 * (1.0 + PetscCosReal(PETSC_PI * p / w)) / w * ddd;
}

/* The viscosity at a point: the model's, mixed with the ambient fluid's
   (m = 1, eta_a = 0: the model alone, bit for bit). eta_m: the model's own. */
static inline void SlumpPwViscosity(SlumpViscosityKernel k, const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal m, PetscReal eta_a, PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty, PetscReal *eta_m)
{
  PetscReal e;
  k(prm, g, p, x, &e, de_dg, de_dp, ty);
  *eta_m = e;
  *eta   = m * e + (1.0 - m) * eta_a;
  *de_dg *= m;
  *de_dp *= m;
}

static inline void SlumpPwF1(PetscInt dim, const PetscScalar u_x[], PetscScalar p, const PetscReal x[], const PetscScalar prm[], PetscReal m, PetscReal eta_a, SlumpViscosityKernel k, PetscScalar f1[])
{
  PetscScalar gd[9];
  PetscReal   g = SlumpPwStrainRate(dim, u_x, gd), eta, de_dg, de_dp, ty, em;
  SlumpPwViscosity(k, prm, g, PetscRealPart(p), x, m, eta_a, &eta, &de_dg, &de_dp, &ty, &em);
  for (PetscInt c = 0; c < dim; ++c) {
    for (PetscInt d = 0; d < dim; ++d) f1[c * dim + d] = eta * gd[c * dim + d];
    f1[c * dim + c] -= p;
  }
}

/* d f1[c,d] / d u_x[e,f] = eta (delta_ce delta_df + delta_de delta_cf) + eta' gd_cd gd_ef / ||gdot||.
   jacmode 1 (consistent initialisation) drops the viscous block. With the
   plastic stress S (stress-velocity Newton) the plastic share of the
   rank-one term is m R'/(R g) sym(S (x) gdot) instead (SlumpPwPlasticTangent). */
static inline void SlumpPwG3(PetscInt dim, const PetscScalar u_x[], PetscScalar p, const PetscReal x[], const PetscScalar prm[], PetscReal m, PetscReal eta_a, PetscInt jacmode, SlumpViscosityKernel k, SlumpPlasticKernel pk, const PetscScalar *S, PetscScalar g3[])
{
  PetscScalar gd[9];
  PetscReal   g = SlumpPwStrainRate(dim, u_x, gd), eta, de_dg, de_dp, ty, em, rp, cS;
  const PetscInt n = dim * dim;
  if (jacmode == 1) {
    for (PetscInt i = 0; i < n * n; ++i) g3[i] = 0.0;
    return;
  }
  SlumpPwViscosity(k, prm, g, PetscRealPart(p), x, m, eta_a, &eta, &de_dg, &de_dp, &ty, &em);
  SlumpPwPlasticTangent(pk, S, prm, g, PetscRealPart(p), x, m, &rp, &cS);
  const PetscReal r = g > SLUMP_GDOT_TINY ? de_dg / g - rp : 0.0;
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt d = 0; d < dim; ++d)
      for (PetscInt e = 0; e < dim; ++e)
        for (PetscInt f = 0; f < dim; ++f) {
          PetscScalar v = r * gd[c * dim + d] * gd[e * dim + f];
          if (cS != 0.0) v += 0.5 * cS * (S[c * dim + d] * gd[e * dim + f] + gd[c * dim + d] * S[e * dim + f]);
          if (c == e && d == f) v += eta;
          if (d == e && c == f) v += eta;
          g3[((c * dim + e) * dim + d) * dim + f] = v;
        }
}

/* d f1[c,d] / d p = -delta_cd + (d eta/dp) gd_cd. */
static inline void SlumpPwG2(PetscInt dim, const PetscScalar u_x[], PetscScalar p, const PetscReal x[], const PetscScalar prm[], PetscReal m, PetscReal eta_a, PetscInt jacmode, SlumpViscosityKernel k, PetscScalar g2[])
{
  PetscScalar gd[9];
  PetscReal   g = SlumpPwStrainRate(dim, u_x, gd), eta, de_dg, de_dp = 0.0, ty, em;
  if (jacmode != 1) SlumpPwViscosity(k, prm, g, PetscRealPart(p), x, m, eta_a, &eta, &de_dg, &de_dp, &ty, &em);
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt d = 0; d < dim; ++d) g2[c * dim + d] = de_dp * gd[c * dim + d] - (c == d ? 1.0 : 0.0);
}

/* The fraction that weighs the material's viscosity: the material fraction
   of phi - s, s = constants[SLUMP_C_MIX_SHIFT] >= 0 (0: the density's). With
   s = w the material law holds in the whole band up to the zero contour:
   pressure-dependent laws (mu(I), Drucker-Prager, Coulomb walls) would
   otherwise see their friction multiplied by m < 1 there while the weight
   and the pressure are m's too, and the band would slide below the angle
   of repose. */
static inline void SlumpPwViscousFraction(PetscScalar phi, const PetscScalar constants[], PetscReal *m, PetscReal *dm)
{
  SlumpPwMaterialFractionShifted(phi, PetscRealPart(constants[SLUMP_C_MIX_SHIFT]), constants, m, dm);
}

/* Two-phase: d f1[c,d] / d phi = dm/dphi (eta_model - eta_ambient) gd_cd. */
static inline void SlumpPwG2Phi(PetscInt dim, const PetscScalar u_x[], PetscScalar p, PetscScalar phi, const PetscReal x[], const PetscScalar constants[], PetscInt jacmode, SlumpViscosityKernel k, PetscScalar g2[])
{
  PetscScalar gd[9];
  PetscReal   g = SlumpPwStrainRate(dim, u_x, gd), eta, de_dg, de_dp, ty, m, dm;
  for (PetscInt i = 0; i < dim * dim; ++i) g2[i] = 0.0;
  if (jacmode == 1) return;
  SlumpPwViscousFraction(phi, constants, &m, &dm);
  if (dm == 0.0) return;
  k(&constants[SLUMP_C_RHEO], g, PetscRealPart(p), x, &eta, &de_dg, &de_dp, &ty);
  for (PetscInt i = 0; i < dim * dim; ++i) g2[i] = dm * (eta - PetscRealPart(constants[SLUMP_C_MIX_ETA])) * gd[i];
}

/* Every model file instantiates its pointwise set from its kernel: the
   single-phase set, and the two-phase set (tp_) that reads the level set
   phi (the last field) and mixes with the ambient Newtonian fluid. */
#define SLUMP_PW_JACMODE (PetscInt)PetscRealPart(constants[SLUMP_C_JACMODE])
#define SLUMP_PW_MIX \
  PetscReal m_, dm_; \
  SlumpPwViscousFraction(u[uOff[Nf - 1]], constants, &m_, &dm_); \
  const PetscReal ea_ = PetscRealPart(constants[SLUMP_C_MIX_ETA]); \
  (void)ea_
#define SLUMP_RHEOLOGY_DEFINE_POINTWISE(NAME, KERNEL, PLASTIC) \
  static void NAME##_f1_u(SLUMP_PW_ARGS, PetscScalar f1[]) \
  { \
    SlumpPwF1(dim, u_x, u[uOff[1]], x, &constants[SLUMP_C_RHEO], 1.0, 0.0, KERNEL, f1); \
  } \
  static void NAME##_g3_uu(SLUMP_PWJ_ARGS, PetscScalar g3[]) \
  { \
    SlumpPwG3(dim, u_x, u[uOff[1]], x, &constants[SLUMP_C_RHEO], 1.0, 0.0, SLUMP_PW_JACMODE, KERNEL, PLASTIC, a_t, g3); \
  } \
  static void NAME##_g2_up(SLUMP_PWJ_ARGS, PetscScalar g2[]) \
  { \
    SlumpPwG2(dim, u_x, u[uOff[1]], x, &constants[SLUMP_C_RHEO], 1.0, 0.0, SLUMP_PW_JACMODE, KERNEL, g2); \
  } \
  static void NAME##_ap_f1_u(SLUMP_PW_ARGS, PetscScalar f1[]) \
  { \
    SlumpPwF1AntiPlane(dim, u_x, x, &constants[SLUMP_C_RHEO], KERNEL, f1); \
  } \
  static void NAME##_ap_g3_uu(SLUMP_PWJ_ARGS, PetscScalar g3[]) \
  { \
    SlumpPwG3AntiPlane(dim, u_x, x, &constants[SLUMP_C_RHEO], SLUMP_PW_JACMODE, KERNEL, PLASTIC, a_t, g3); \
  } \
  static void NAME##_eta(SLUMP_PW_ARGS, PetscScalar f[]) \
  { \
    PetscReal eta, d1_, d2_, ty, p, g = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p); \
    KERNEL(&constants[SLUMP_C_RHEO], g, p, x, &eta, &d1_, &d2_, &ty); \
    f[0] = eta; \
  } \
  static void NAME##_shear_rate(SLUMP_PW_ARGS, PetscScalar f[]) \
  { \
    PetscReal p; \
    f[0] = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p); \
  } \
  static void NAME##_dissipation(SLUMP_PW_ARGS, PetscScalar f[]) \
  { \
    PetscReal eta, d1_, d2_, ty, p, g = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p); \
    KERNEL(&constants[SLUMP_C_RHEO], g, p, x, &eta, &d1_, &d2_, &ty); \
    f[0] = eta * g * g; \
  } \
  static void NAME##_yielded(SLUMP_PW_ARGS, PetscScalar f[]) \
  { \
    PetscReal eta, d1_, d2_, ty, p, g = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p); \
    KERNEL(&constants[SLUMP_C_RHEO], g, p, x, &eta, &d1_, &d2_, &ty); \
    f[0] = (eta * g > ty) ? 1.0 : 0.0; \
  } \
  static void NAME##_tp_f1_u(SLUMP_PW_ARGS, PetscScalar f1[]) \
  { \
    SLUMP_PW_MIX; \
    SlumpPwF1(dim, u_x, u[uOff[1]], x, &constants[SLUMP_C_RHEO], m_, ea_, KERNEL, f1); \
  } \
  static void NAME##_tp_g3_uu(SLUMP_PWJ_ARGS, PetscScalar g3[]) \
  { \
    SLUMP_PW_MIX; \
    SlumpPwG3(dim, u_x, u[uOff[1]], x, &constants[SLUMP_C_RHEO], m_, ea_, SLUMP_PW_JACMODE, KERNEL, PLASTIC, a_t, g3); \
  } \
  static void NAME##_tp_g2_up(SLUMP_PWJ_ARGS, PetscScalar g2[]) \
  { \
    SLUMP_PW_MIX; \
    SlumpPwG2(dim, u_x, u[uOff[1]], x, &constants[SLUMP_C_RHEO], m_, ea_, SLUMP_PW_JACMODE, KERNEL, g2); \
  } \
  static void NAME##_tp_g2_uphi(SLUMP_PWJ_ARGS, PetscScalar g2[]) \
  { \
    SlumpPwG2Phi(dim, u_x, u[uOff[1]], u[uOff[Nf - 1]], x, constants, SLUMP_PW_JACMODE, KERNEL, g2); \
  } \
  static void NAME##_tp_eta(SLUMP_PW_ARGS, PetscScalar f[]) \
  { \
    SLUMP_PW_MIX; \
    PetscReal eta, d1_, d2_, ty, em, p, g = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p); \
    SlumpPwViscosity(KERNEL, &constants[SLUMP_C_RHEO], g, p, x, m_, ea_, &eta, &d1_, &d2_, &ty, &em); \
    f[0] = eta; \
  } \
  static void NAME##_tp_dissipation(SLUMP_PW_ARGS, PetscScalar f[]) \
  { \
    SLUMP_PW_MIX; \
    PetscReal eta, d1_, d2_, ty, p, g = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p); \
    KERNEL(&constants[SLUMP_C_RHEO], g, p, x, &eta, &d1_, &d2_, &ty); \
    f[0] = m_ * eta * g * g; \
  } \
  static void NAME##_tp_yielded(SLUMP_PW_ARGS, PetscScalar f[]) \
  { \
    SLUMP_PW_MIX; \
    PetscReal eta, d1_, d2_, ty, p, g = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p); \
    KERNEL(&constants[SLUMP_C_RHEO], g, p, x, &eta, &d1_, &d2_, &ty); \
    SlumpPwMaterialFraction(u[uOff[Nf - 1]], constants, &m_, &dm_); /* an area share, like the other averages */ \
    f[0] = (eta * g > ty) ? m_ : 0.0; \
  } \
  static PetscBool NAME##_dual(PetscInt dim, PetscInt Nf, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_x[], const PetscScalar du[], const PetscScalar du_x[], const PetscReal x[], const PetscScalar constants[], PetscScalar S[]) \
  { \
    const PetscBool ap_ = (uOff[1] - uOff[0] == 1) ? PETSC_TRUE : PETSC_FALSE; \
    const PetscReal p_  = (!ap_ && Nf > 1) ? PetscRealPart(u[uOff[1]]) : 0.0, dp_ = (!ap_ && Nf > 1 && du) ? PetscRealPart(du[uOff[1]]) : 0.0; \
    PetscScalar     gx_[9]; \
    PetscReal       g_, eta_, d1_, d2_, ty_; \
    SlumpPwDualUpdate(dim, ap_, u_x, p_, du_x, dp_, x, &constants[SLUMP_C_RHEO], PLASTIC, S); \
    /* yielded at the corrected state */ \
    for (PetscInt i_ = 0; i_ < (ap_ ? dim : dim * dim); ++i_) gx_[i_] = u_x[i_] + (du_x ? du_x[i_] : 0.0); \
    if (ap_) { \
      g_ = 0.0; \
      for (PetscInt d_ = 0; d_ < dim; ++d_) g_ += PetscRealPart(gx_[d_] * gx_[d_]); \
      g_ = PetscSqrtReal(g_); \
    } else { \
      PetscScalar gs_[9]; \
      g_ = SlumpPwStrainRate(dim, gx_, gs_); \
    } \
    KERNEL(&constants[SLUMP_C_RHEO], g_, p_ + dp_, x, &eta_, &d1_, &d2_, &ty_); \
    return (eta_ * g_ > ty_) ? PETSC_TRUE : PETSC_FALSE; \
  } \
  static const SlumpRheologyPointwise NAME##_pointwise = {NAME##_f1_u, NAME##_g2_up, NAME##_g3_uu, NAME##_eta, NAME##_shear_rate, NAME##_dissipation, NAME##_yielded, NAME##_ap_f1_u, NAME##_ap_g3_uu, \
                                                          NAME##_tp_f1_u, NAME##_tp_g2_up, NAME##_tp_g3_uu, NAME##_tp_g2_uphi, NAME##_tp_eta, NAME##_tp_dissipation, NAME##_tp_yielded, NAME##_dual};
