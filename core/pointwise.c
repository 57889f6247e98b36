/* Momentum and continuity pointwise terms of the effects a scene switches on.
 *
 *   momentum:   rho (u_t + u . grad u) - rho g  [f0]   +  tau - p I  [f1, rheology]
 *               + 1/2 (rho_t + div(rho u)) u    [f0, -convection_form skew]
 *               + 1/2 rho (div u) u             [f0, -convection_form temam]
 *   continuity: -div u                          [f0]
 *
 * The skew term vanishes for the exact solution (mass conservation). With it,
 * testing with the discrete velocity gives int rho u_t.u + 1/2 rho_t |u|^2 =
 * d/dt int rho |u|^2/2 and int rho (u.grad u).u + 1/2 div(rho u) |u|^2 = 0
 * (u.n = 0 on the walls): the inertial terms do no work, whatever the
 * discrete divergence of u and the level set's transport error. Without it
 * (advective), a Taylor-Hood velocity that is only weakly divergence-free
 * can feed energy into a nearly inviscid ambient fluid.
 *
 * One function per combination of effects, so a term that is off costs
 * nothing at the quadrature points (no branch, no assembly). */
#include "slumpimpl.h"

/* Density at a point: the material's, or (two-phase) mixed with the ambient
   fluid's by the level set phi, the last field; drho: d rho / d phi. */
static inline PetscReal Density(PetscInt Nf, const PetscInt uOff[], const PetscScalar u[], const PetscScalar constants[], PetscBool twophase, PetscReal *drho)
{
  const PetscReal rm = PetscRealPart(constants[SLUMP_C_RHO]), ra = PetscRealPart(constants[SLUMP_C_MIX_RHO]);
  PetscReal       m, dm;
  if (!twophase) {
    if (drho) *drho = 0.0;
    return rm;
  }
  SlumpPwMaterialFraction(u[uOff[Nf - 1]], constants, &m, &dm);
  if (drho) *drho = dm * (rm - ra);
  return m * rm + (1.0 - m) * ra;
}

/* The skew term's factor s, the term being s u:
   s = 1/2 (rho div u + rho'(phi) (phi_t + u . grad phi)) (rho' = 0 in one
   phase; mass false drops the rho' part: Temam's 1/2 rho (div u) u).
   Optionally rho, rho' and ds/dphi at fixed phi_t and grad phi. */
static inline PetscReal SkewFactor(PetscInt dim, PetscInt Nf, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscScalar constants[], PetscBool twophase, PetscBool mass, PetscReal *rho_, PetscReal *drho_, PetscReal *ds_dphi)
{
  PetscReal rho, drho, div = 0.0, adv = 0.0;
  rho = Density(Nf, uOff, u, constants, twophase, &drho);
  for (PetscInt d = 0; d < dim; ++d) div += PetscRealPart(u_x[d * dim + d]);
  if (twophase && mass) {
    adv = PetscRealPart(u_t[uOff[Nf - 1]]);
    for (PetscInt d = 0; d < dim; ++d) adv += PetscRealPart(u[d] * u_x[uOff_x[Nf - 1] + d]);
  }
  if (rho_) *rho_ = rho;
  if (drho_) *drho_ = drho;
  if (ds_dphi) {
    PetscReal d2m = 0.0;
    if (twophase && mass) SlumpPwMaterialFractionCurvature(u[uOff[Nf - 1]], constants, &d2m);
    *ds_dphi = 0.5 * (drho * div + d2m * (PetscRealPart(constants[SLUMP_C_RHO]) - PetscRealPart(constants[SLUMP_C_MIX_RHO])) * adv);
  }
  return 0.5 * (rho * div + drho * adv);
}

/* the momentum equation's f0 per unit density: u_t + u . grad u - g */
static inline void MomentumPerDensity(PetscInt dim, const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscScalar constants[], PetscBool inertia, PetscBool convection, PetscBool body, PetscScalar f0[])
{
  for (PetscInt c = 0; c < dim; ++c) {
    PetscScalar v = 0.0;
    if (inertia) v += u_t[c];
    if (convection)
      for (PetscInt d = 0; d < dim; ++d) v += u[d] * u_x[c * dim + d];
    if (body) v -= constants[SLUMP_C_GX + c];
    f0[c] = v;
  }
}

static inline void MomentumF0(PetscInt dim, PetscInt Nf, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscScalar constants[], PetscBool inertia, PetscBool convection, PetscBool body, PetscBool twophase, PetscInt skew, PetscScalar f0[])
{
  const PetscReal rho = Density(Nf, uOff, u, constants, twophase, NULL);
  const PetscReal s   = skew ? SkewFactor(dim, Nf, uOff, uOff_x, u, u_t, u_x, constants, twophase, skew == SLUMP_CONVECTION_SKEW ? PETSC_TRUE : PETSC_FALSE, NULL, NULL, NULL) : 0.0;
  for (PetscInt c = 0; c < dim; ++c) {
    PetscScalar v = 0.0;
    if (inertia) v += rho * u_t[c];
    if (convection)
      for (PetscInt d = 0; d < dim; ++d) v += rho * u[d] * u_x[c * dim + d];
    if (skew) v += s * u[c];
    if (body) v -= rho * constants[SLUMP_C_GX + c];
    f0[c] = v;
  }
}

#define MOMENTUM_F0(NAME, INERTIA, CONV, BODY, TP, SKEW) \
  static void NAME(SLUMP_PW_ARGS, PetscScalar f0[]) \
  { \
    MomentumF0(dim, Nf, uOff, uOff_x, u, u_t, u_x, constants, INERTIA, CONV, BODY, TP, SKEW, f0); \
  }
MOMENTUM_F0(f0_u_none, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE, 0)
MOMENTUM_F0(f0_u_I, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE, 0)
MOMENTUM_F0(f0_u_IC, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, 0)
MOMENTUM_F0(f0_u_B, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE, PETSC_FALSE, 0)
MOMENTUM_F0(f0_u_IB, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE, PETSC_FALSE, 0)
MOMENTUM_F0(f0_u_ICB, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, 0)
MOMENTUM_F0(f0_u_none_tp, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE, 0)
MOMENTUM_F0(f0_u_I_tp, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE, 0)
MOMENTUM_F0(f0_u_IC_tp, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE, 0)
MOMENTUM_F0(f0_u_B_tp, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE, PETSC_TRUE, 0)
MOMENTUM_F0(f0_u_IB_tp, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE, PETSC_TRUE, 0)
MOMENTUM_F0(f0_u_ICB_tp, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, 0)
MOMENTUM_F0(f0_u_ICS, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, SLUMP_CONVECTION_SKEW)
MOMENTUM_F0(f0_u_ICBS, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, SLUMP_CONVECTION_SKEW)
MOMENTUM_F0(f0_u_ICS_tp, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE, SLUMP_CONVECTION_SKEW)
MOMENTUM_F0(f0_u_ICT_tp, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE, SLUMP_CONVECTION_TEMAM)
MOMENTUM_F0(f0_u_ICBS_tp, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, SLUMP_CONVECTION_SKEW)
MOMENTUM_F0(f0_u_ICBT_tp, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, SLUMP_CONVECTION_TEMAM)

PetscPointFunc SlumpPwSelectMomentumF0(PetscInt e, PetscBool tp, PetscInt skew)
{
  const PetscBool in = (e & SLUMP_EFFECT_INERTIA) ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool cv = (e & SLUMP_EFFECT_CONVECTION) ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool bf = (e & SLUMP_EFFECT_BODY_FORCE) ? PETSC_TRUE : PETSC_FALSE;
  if (tp) {
    if (in && cv && skew == SLUMP_CONVECTION_SKEW) return bf ? f0_u_ICBS_tp : f0_u_ICS_tp;
    if (in && cv && skew == SLUMP_CONVECTION_TEMAM) return bf ? f0_u_ICBT_tp : f0_u_ICT_tp;
    if (in && cv) return bf ? f0_u_ICB_tp : f0_u_IC_tp;
    if (in) return bf ? f0_u_IB_tp : f0_u_I_tp;
    return bf ? f0_u_B_tp : f0_u_none_tp;
  }
  if (in && cv && skew) return bf ? f0_u_ICBS : f0_u_ICS;
  if (in && cv) return bf ? f0_u_ICB : f0_u_IC;
  if (in) return bf ? f0_u_IB : f0_u_I;
  return bf ? f0_u_B : f0_u_none;
}

/* Two-phase: d f0_u / d phi = (d rho / d phi) (u_t + u . grad u - g), and
   with the skew term (ds/dphi + shift rho'/2) u. */
#define MOMENTUM_G0_PHI(NAME, INERTIA, CONV, BODY, SKEW) \
  static void NAME(SLUMP_PWJ_ARGS, PetscScalar g0[]) \
  { \
    PetscReal   drho, ds = 0.0; \
    PetscScalar r[3]; \
    if (SKEW) (void)SkewFactor(dim, Nf, uOff, uOff_x, u, u_t, u_x, constants, PETSC_TRUE, SKEW == SLUMP_CONVECTION_SKEW ? PETSC_TRUE : PETSC_FALSE, NULL, &drho, &ds); \
    else (void)Density(Nf, uOff, u, constants, PETSC_TRUE, &drho); \
    MomentumPerDensity(dim, u, u_t, u_x, constants, INERTIA, CONV, BODY, r); \
    for (PetscInt c = 0; c < dim; ++c) g0[c] = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0 ? drho * r[c] + (SKEW ? (ds + (SKEW == SLUMP_CONVECTION_SKEW ? 0.5 * u_tShift * drho : 0.0)) * u[c] : 0.0) : 0.0; \
  }
MOMENTUM_G0_PHI(g0_uphi_I, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, 0)
MOMENTUM_G0_PHI(g0_uphi_IC, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, 0)
MOMENTUM_G0_PHI(g0_uphi_B, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE, 0)
MOMENTUM_G0_PHI(g0_uphi_IB, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE, 0)
MOMENTUM_G0_PHI(g0_uphi_ICB, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, 0)
MOMENTUM_G0_PHI(g0_uphi_ICS, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, SLUMP_CONVECTION_SKEW)
MOMENTUM_G0_PHI(g0_uphi_ICT, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, SLUMP_CONVECTION_TEMAM)
MOMENTUM_G0_PHI(g0_uphi_ICBS, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, SLUMP_CONVECTION_SKEW)
MOMENTUM_G0_PHI(g0_uphi_ICBT, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, SLUMP_CONVECTION_TEMAM)

PetscPointJac SlumpPwSelectG0Phi(PetscInt e, PetscInt skew)
{
  const PetscBool in = (e & SLUMP_EFFECT_INERTIA) ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool cv = (e & SLUMP_EFFECT_CONVECTION) ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool bf = (e & SLUMP_EFFECT_BODY_FORCE) ? PETSC_TRUE : PETSC_FALSE;
  if (in && cv && skew == SLUMP_CONVECTION_SKEW) return bf ? g0_uphi_ICBS : g0_uphi_ICS;
  if (in && cv && skew == SLUMP_CONVECTION_TEMAM) return bf ? g0_uphi_ICBT : g0_uphi_ICT;
  if (in && cv) return bf ? g0_uphi_ICB : g0_uphi_IC;
  if (in) return bf ? g0_uphi_IB : g0_uphi_I;
  return bf ? g0_uphi_B : NULL;
}

/* skew term, two-phase: d f0_u[c] / d phi_x[d] = rho'/2 u_d u_c */
static void g1_uphi_S(SLUMP_PWJ_ARGS, PetscScalar g1[])
{
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0;
  PetscReal       drho;
  (void)Density(Nf, uOff, u, constants, PETSC_TRUE, &drho);
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt d = 0; d < dim; ++d) g1[c * dim + d] = full ? 0.5 * drho * u[d] * u[c] : 0.0;
}

PetscPointJac SlumpPwSelectG1Phi(PetscInt e, PetscInt skew)
{
  const PetscBool cv = (e & SLUMP_EFFECT_CONVECTION) && (e & SLUMP_EFFECT_INERTIA) ? PETSC_TRUE : PETSC_FALSE;
  return cv && skew == SLUMP_CONVECTION_SKEW ? g1_uphi_S : NULL;
}

/* d f0_u / d u = rho shift I + rho grad u (convection). */
static inline void G0uuI(PetscInt dim, PetscReal rho, PetscReal u_tShift, PetscScalar g0[])
{
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt e = 0; e < dim; ++e) g0[c * dim + e] = (c == e) ? rho * u_tShift : 0.0;
}
static inline void G0uuIC(PetscInt dim, PetscReal rho, PetscReal u_tShift, const PetscScalar u_x[], const PetscScalar constants[], PetscScalar g0[])
{
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0;
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt e = 0; e < dim; ++e) g0[c * dim + e] = ((c == e) ? rho * u_tShift : 0.0) + (full ? rho * u_x[c * dim + e] : 0.0);
}
/* d f0_u[c] / d u_x[e,d] = rho u_d delta_ce. */
static inline void G1uuC(PetscInt dim, PetscReal rho, const PetscScalar u[], const PetscScalar constants[], PetscScalar g1[])
{
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0;
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt e = 0; e < dim; ++e)
      for (PetscInt d = 0; d < dim; ++d) g1[(c * dim + e) * dim + d] = (c == e && full) ? rho * u[d] : 0.0;
}
/* With the skew term s u added: d/d u_e gains s delta_ce + rho'/2 phi_x[e] u_c
   and d/d u_x[e,d] gains rho/2 delta_ed u_c (G1uuCSkew). rho and s come from
   one evaluation of the mixture. */
static inline void G0uuICSkew(PetscInt dim, PetscInt Nf, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscScalar constants[], PetscBool tp, PetscBool mass, PetscReal u_tShift, PetscScalar g0[])
{
  PetscReal       rho, drho, s;
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0;
  s = SkewFactor(dim, Nf, uOff, uOff_x, u, u_t, u_x, constants, tp, mass, &rho, &drho, NULL);
  G0uuIC(dim, rho, u_tShift, u_x, constants, g0);
  if (!full) return;
  for (PetscInt c = 0; c < dim; ++c) {
    g0[c * dim + c] += s;
    if (tp && mass)
      for (PetscInt e = 0; e < dim; ++e) g0[c * dim + e] += 0.5 * drho * u_x[uOff_x[Nf - 1] + e] * u[c];
  }
}
static inline void G1uuCSkew(PetscInt dim, PetscReal rho, const PetscScalar u[], const PetscScalar constants[], PetscScalar g1[])
{
  G1uuC(dim, rho, u, constants, g1);
  if (PetscRealPart(constants[SLUMP_C_JACMODE]) != 0.0) return;
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt e = 0; e < dim; ++e) g1[(c * dim + e) * dim + e] += 0.5 * rho * u[c];
}
#define RHO_(TP) Density(Nf, uOff, u, constants, TP, NULL)
static void g0_uu_I(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  G0uuI(dim, RHO_(PETSC_FALSE), u_tShift, g0);
}
static void g0_uu_IC(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  G0uuIC(dim, RHO_(PETSC_FALSE), u_tShift, u_x, constants, g0);
}
static void g1_uu_C(SLUMP_PWJ_ARGS, PetscScalar g1[])
{
  G1uuC(dim, RHO_(PETSC_FALSE), u, constants, g1);
}
static void g0_uu_I_tp(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  G0uuI(dim, RHO_(PETSC_TRUE), u_tShift, g0);
}
static void g0_uu_IC_tp(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  G0uuIC(dim, RHO_(PETSC_TRUE), u_tShift, u_x, constants, g0);
}
static void g1_uu_C_tp(SLUMP_PWJ_ARGS, PetscScalar g1[])
{
  G1uuC(dim, RHO_(PETSC_TRUE), u, constants, g1);
}
static void g0_uu_ICS(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  G0uuICSkew(dim, Nf, uOff, uOff_x, u, u_t, u_x, constants, PETSC_FALSE, PETSC_FALSE, u_tShift, g0);
}
static void g1_uu_CS(SLUMP_PWJ_ARGS, PetscScalar g1[])
{
  G1uuCSkew(dim, RHO_(PETSC_FALSE), u, constants, g1);
}
static void g0_uu_ICS_tp(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  G0uuICSkew(dim, Nf, uOff, uOff_x, u, u_t, u_x, constants, PETSC_TRUE, PETSC_TRUE, u_tShift, g0);
}
static void g0_uu_ICT_tp(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  G0uuICSkew(dim, Nf, uOff, uOff_x, u, u_t, u_x, constants, PETSC_TRUE, PETSC_FALSE, u_tShift, g0);
}
static void g1_uu_CS_tp(SLUMP_PWJ_ARGS, PetscScalar g1[])
{
  G1uuCSkew(dim, RHO_(PETSC_TRUE), u, constants, g1);
}

PetscPointJac SlumpPwSelectG0(PetscInt e, PetscBool tp, PetscInt skew)
{
  if (!(e & SLUMP_EFFECT_INERTIA)) return NULL;
  if (!(e & SLUMP_EFFECT_CONVECTION)) return tp ? g0_uu_I_tp : g0_uu_I;
  if (skew == SLUMP_CONVECTION_SKEW) return tp ? g0_uu_ICS_tp : g0_uu_ICS;
  if (skew == SLUMP_CONVECTION_TEMAM) return tp ? g0_uu_ICT_tp : g0_uu_ICS;
  return tp ? g0_uu_IC_tp : g0_uu_IC;
}

PetscPointJac SlumpPwSelectG1(PetscInt e, PetscBool tp, PetscInt skew)
{
  if (!(e & SLUMP_EFFECT_CONVECTION)) return NULL;
  if (skew) return tp ? g1_uu_CS_tp : g1_uu_CS;
  return tp ? g1_uu_C_tp : g1_uu_C;
}

void SlumpPwContinuityF0(SLUMP_PW_ARGS, PetscScalar f0[])
{
  f0[0] = 0.0;
  for (PetscInt d = 0; d < dim; ++d) f0[0] -= u_x[d * dim + d];
}

void SlumpPwContinuityG1(SLUMP_PWJ_ARGS, PetscScalar g1[])
{
  for (PetscInt e = 0; e < dim; ++e)
    for (PetscInt d = 0; d < dim; ++d) g1[e * dim + d] = (e == d) ? -1.0 : 0.0;
}

/* Anti-plane momentum: rho w_t - rho G (G: the body force's x component). */
static void f0_w_none(SLUMP_PW_ARGS, PetscScalar f0[])
{
  f0[0] = 0.0;
}
static void f0_w_I(SLUMP_PW_ARGS, PetscScalar f0[])
{
  f0[0] = PetscRealPart(constants[SLUMP_C_RHO]) * u_t[0];
}
static void f0_w_B(SLUMP_PW_ARGS, PetscScalar f0[])
{
  f0[0] = -PetscRealPart(constants[SLUMP_C_RHO]) * constants[SLUMP_C_GX];
}
static void f0_w_IB(SLUMP_PW_ARGS, PetscScalar f0[])
{
  f0[0] = PetscRealPart(constants[SLUMP_C_RHO]) * (u_t[0] - constants[SLUMP_C_GX]);
}
static void g0_ww_I(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  g0[0] = PetscRealPart(constants[SLUMP_C_RHO]) * u_tShift;
}

PetscPointFunc SlumpPwSelectAntiPlaneF0(PetscInt e)
{
  const PetscBool in = (e & SLUMP_EFFECT_INERTIA) ? PETSC_TRUE : PETSC_FALSE, bf = (e & SLUMP_EFFECT_BODY_FORCE) ? PETSC_TRUE : PETSC_FALSE;
  if (in) return bf ? f0_w_IB : f0_w_I;
  return bf ? f0_w_B : f0_w_none;
}

PetscPointJac SlumpPwSelectAntiPlaneG0(PetscInt e)
{
  return (e & SLUMP_EFFECT_INERTIA) ? g0_ww_I : NULL;
}

/* Wall friction (SlumpProblemAddFrictionBC): f0 = m L u_t on the wall, with
   u_t = (I - n n^T) u and L = beta (Navier) or mu_w P(p)/s, s = sqrt(|u_t|^2
   + delta^2) (regularised Coulomb); m is the material fraction in two-phase
   flows, 1 otherwise. */
typedef struct {
  PetscReal ut[3], T[9], m, dm, L, P, dP, s;
  PetscInt  law;
} WallState;

static inline void WallEvaluate(PetscInt dim, PetscInt Nf, const PetscInt uOff[], const PetscScalar u[], const PetscReal n[], const PetscScalar constants[], WallState *w)
{
  PetscReal un = 0.0, s2 = 0.0;
  for (PetscInt d = 0; d < dim; ++d) un += PetscRealPart(u[uOff[0] + d]) * n[d];
  for (PetscInt c = 0; c < dim; ++c) {
    w->ut[c] = PetscRealPart(u[uOff[0] + c]) - un * n[c];
    s2 += w->ut[c] * w->ut[c];
    for (PetscInt e = 0; e < dim; ++e) w->T[c * dim + e] = (c == e ? 1.0 : 0.0) - n[c] * n[e];
  }
  w->m  = 1.0;
  w->dm = 0.0;
  w->law = (PetscInt)PetscRealPart(constants[SLUMP_C_WALL_LAW]);
  /* two-phase: Navier slip, a no-slip penalty under the material, acts on
     the material fraction, so that the band at the contact line slips (the
     thesis' slip cell); Coulomb friction, proportional to the pressure,
     acts like the material law, up to the zero contour */
  if (Nf > 2 && PetscRealPart(constants[SLUMP_C_MIX_EPS]) > 0) {
    if (w->law == SLUMP_WALL_NAVIER) SlumpPwMaterialFraction(u[uOff[Nf - 1]], constants, &w->m, &w->dm);
    else SlumpPwViscousFraction(u[uOff[Nf - 1]], constants, &w->m, &w->dm);
  }
  if (w->law == SLUMP_WALL_NAVIER) {
    w->L = PetscRealPart(constants[SLUMP_C_WALL_COEFF]);
    w->P = w->dP = 0.0;
    w->s = 1.0;
  } else {
    const PetscReal p = Nf > 1 ? PetscRealPart(u[uOff[1]]) : 0.0, dl = PetscRealPart(constants[SLUMP_C_WALL_REG]);
    w->P = p > 0 ? p : 0.0;
    w->dP = p > 0 ? 1.0 : 0.0;
    w->s  = PetscSqrtReal(s2 + dl * dl);
    w->L  = PetscRealPart(constants[SLUMP_C_WALL_COEFF]) * w->P / w->s;
  }
}

void SlumpPwWallFrictionF0(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, const PetscReal x[], const PetscReal n[], PetscInt numConstants, const PetscScalar constants[], PetscScalar f0[])
{
  WallState w;
  WallEvaluate(dim, Nf, uOff, u, n, constants, &w);
  const PetscReal wr = SlumpPwBoundaryWeight(x, constants); /* axisymmetric: the radius */
  for (PetscInt c = 0; c < dim; ++c) f0[c] = wr * w.m * w.L * w.ut[c];
}

/* The power the friction takes from the flow, f0 . u = m L |u_t|^2 >= 0 (the
   wall's share of the dissipation; PetscBdPointFunc). */
void SlumpPwWallFrictionPower(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, const PetscReal x[], const PetscReal n[], PetscInt numConstants, const PetscScalar constants[], PetscScalar f[])
{
  WallState w;
  PetscReal s2 = 0.0;
  WallEvaluate(dim, Nf, uOff, u, n, constants, &w);
  for (PetscInt c = 0; c < dim; ++c) s2 += w.ut[c] * w.ut[c];
  f[0] = w.m * w.L * s2;
}

void SlumpPwWallFrictionG0uu(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, PetscReal u_tShift, const PetscReal x[], const PetscReal n[], PetscInt numConstants, const PetscScalar constants[], PetscScalar g0[])
{
  WallState w;
  if (PetscRealPart(constants[SLUMP_C_JACMODE]) == 1) { /* consistent initialisation: [rho M, B^T; B, 0] */
    for (PetscInt c = 0; c < dim * dim; ++c) g0[c] = 0.0;
    return;
  }
  WallEvaluate(dim, Nf, uOff, u, n, constants, &w);
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt e = 0; e < dim; ++e) {
      PetscReal v = w.L * w.T[c * dim + e];
      /* Coulomb: d(1/s)/du_e = -ut_e / s^3 (T ut = ut) */
      if (w.law != SLUMP_WALL_NAVIER) v -= w.L * w.ut[c] * w.ut[e] / (w.s * w.s);
      g0[c * dim + e] = SlumpPwBoundaryWeight(x, constants) * w.m * v;
    }
}

void SlumpPwWallFrictionG0up(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, PetscReal u_tShift, const PetscReal x[], const PetscReal n[], PetscInt numConstants, const PetscScalar constants[], PetscScalar g0[])
{
  WallState w;
  if (PetscRealPart(constants[SLUMP_C_JACMODE]) == 1) { /* consistent initialisation: [rho M, B^T; B, 0] */
    for (PetscInt c = 0; c < dim; ++c) g0[c] = 0.0;
    return;
  }
  WallEvaluate(dim, Nf, uOff, u, n, constants, &w);
  for (PetscInt c = 0; c < dim; ++c) g0[c] = w.law == SLUMP_WALL_NAVIER ? 0.0 : SlumpPwBoundaryWeight(x, constants) * w.m * PetscRealPart(constants[SLUMP_C_WALL_COEFF]) * w.dP / w.s * w.ut[c];
}

void SlumpPwWallFrictionG0uphi(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, PetscReal u_tShift, const PetscReal x[], const PetscReal n[], PetscInt numConstants, const PetscScalar constants[], PetscScalar g0[])
{
  WallState w;
  if (PetscRealPart(constants[SLUMP_C_JACMODE]) == 1) { /* consistent initialisation: [rho M, B^T; B, 0] */
    for (PetscInt c = 0; c < dim; ++c) g0[c] = 0.0;
    return;
  }
  WallEvaluate(dim, Nf, uOff, u, n, constants, &w);
  for (PetscInt c = 0; c < dim; ++c) g0[c] = SlumpPwBoundaryWeight(x, constants) * w.dm * w.L * w.ut[c];
}
