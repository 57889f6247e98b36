/* Momentum and continuity pointwise terms of the effects a scene switches on.
 *
 *   momentum:   rho (u_t + u . grad u) - rho g  [f0]   +  tau - p I  [f1, rheology]
 *   continuity: -div u                          [f0]
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

static inline void MomentumF0(PetscInt dim, PetscInt Nf, const PetscInt uOff[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscScalar constants[], PetscBool inertia, PetscBool convection, PetscBool body, PetscBool twophase, PetscScalar f0[])
{
  const PetscReal rho = Density(Nf, uOff, u, constants, twophase, NULL);
  for (PetscInt c = 0; c < dim; ++c) {
    PetscScalar v = 0.0;
    if (inertia) v += rho * u_t[c];
    if (convection)
      for (PetscInt d = 0; d < dim; ++d) v += rho * u[d] * u_x[c * dim + d];
    if (body) v -= rho * constants[SLUMP_C_GX + c];
    f0[c] = v;
  }
}

#define MOMENTUM_F0(NAME, INERTIA, CONV, BODY, TP) \
  static void NAME(SLUMP_PW_ARGS, PetscScalar f0[]) \
  { \
    MomentumF0(dim, Nf, uOff, u, u_t, u_x, constants, INERTIA, CONV, BODY, TP, f0); \
  }
MOMENTUM_F0(f0_u_none, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE)
MOMENTUM_F0(f0_u_I, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE)
MOMENTUM_F0(f0_u_IC, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE)
MOMENTUM_F0(f0_u_B, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE, PETSC_FALSE)
MOMENTUM_F0(f0_u_IB, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE, PETSC_FALSE)
MOMENTUM_F0(f0_u_ICB, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE)
MOMENTUM_F0(f0_u_none_tp, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE)
MOMENTUM_F0(f0_u_I_tp, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE)
MOMENTUM_F0(f0_u_IC_tp, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE)
MOMENTUM_F0(f0_u_B_tp, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE, PETSC_TRUE)
MOMENTUM_F0(f0_u_IB_tp, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE, PETSC_TRUE)
MOMENTUM_F0(f0_u_ICB_tp, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE)

PetscPointFunc SlumpPwSelectMomentumF0(PetscInt e, PetscBool tp)
{
  const PetscBool in = (e & SLUMP_EFFECT_INERTIA) ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool cv = (e & SLUMP_EFFECT_CONVECTION) ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool bf = (e & SLUMP_EFFECT_BODY_FORCE) ? PETSC_TRUE : PETSC_FALSE;
  if (tp) {
    if (in && cv) return bf ? f0_u_ICB_tp : f0_u_IC_tp;
    if (in) return bf ? f0_u_IB_tp : f0_u_I_tp;
    return bf ? f0_u_B_tp : f0_u_none_tp;
  }
  if (in && cv) return bf ? f0_u_ICB : f0_u_IC;
  if (in) return bf ? f0_u_IB : f0_u_I;
  return bf ? f0_u_B : f0_u_none;
}

/* Two-phase: d f0_u / d phi = (d rho / d phi) (u_t + u . grad u - g). */
#define MOMENTUM_G0_PHI(NAME, INERTIA, CONV, BODY) \
  static void NAME(SLUMP_PWJ_ARGS, PetscScalar g0[]) \
  { \
    PetscReal   drho; \
    PetscScalar r[3]; \
    (void)Density(Nf, uOff, u, constants, PETSC_TRUE, &drho); \
    MomentumPerDensity(dim, u, u_t, u_x, constants, INERTIA, CONV, BODY, r); \
    for (PetscInt c = 0; c < dim; ++c) g0[c] = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0 ? drho * r[c] : 0.0; \
  }
MOMENTUM_G0_PHI(g0_uphi_I, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE)
MOMENTUM_G0_PHI(g0_uphi_IC, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE)
MOMENTUM_G0_PHI(g0_uphi_B, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE)
MOMENTUM_G0_PHI(g0_uphi_IB, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE)
MOMENTUM_G0_PHI(g0_uphi_ICB, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE)

PetscPointJac SlumpPwSelectG0Phi(PetscInt e)
{
  const PetscBool in = (e & SLUMP_EFFECT_INERTIA) ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool cv = (e & SLUMP_EFFECT_CONVECTION) ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool bf = (e & SLUMP_EFFECT_BODY_FORCE) ? PETSC_TRUE : PETSC_FALSE;
  if (in && cv) return bf ? g0_uphi_ICB : g0_uphi_IC;
  if (in) return bf ? g0_uphi_IB : g0_uphi_I;
  return bf ? g0_uphi_B : NULL;
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

PetscPointJac SlumpPwSelectG0(PetscInt e, PetscBool tp)
{
  if (!(e & SLUMP_EFFECT_INERTIA)) return NULL;
  if (tp) return (e & SLUMP_EFFECT_CONVECTION) ? g0_uu_IC_tp : g0_uu_I_tp;
  return (e & SLUMP_EFFECT_CONVECTION) ? g0_uu_IC : g0_uu_I;
}

PetscPointJac SlumpPwSelectG1(PetscInt e, PetscBool tp)
{
  if (!(e & SLUMP_EFFECT_CONVECTION)) return NULL;
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
  for (PetscInt c = 0; c < dim; ++c) f0[c] = w.m * w.L * w.ut[c];
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
      g0[c * dim + e] = w.m * v;
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
  for (PetscInt c = 0; c < dim; ++c) g0[c] = w.law == SLUMP_WALL_NAVIER ? 0.0 : w.m * PetscRealPart(constants[SLUMP_C_WALL_COEFF]) * w.dP / w.s * w.ut[c];
}

void SlumpPwWallFrictionG0uphi(PetscInt dim, PetscInt Nf, PetscInt NfAux, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscInt aOff[], const PetscInt aOff_x[], const PetscScalar a[], const PetscScalar a_t[], const PetscScalar a_x[], PetscReal t, PetscReal u_tShift, const PetscReal x[], const PetscReal n[], PetscInt numConstants, const PetscScalar constants[], PetscScalar g0[])
{
  WallState w;
  if (PetscRealPart(constants[SLUMP_C_JACMODE]) == 1) { /* consistent initialisation: [rho M, B^T; B, 0] */
    for (PetscInt c = 0; c < dim; ++c) g0[c] = 0.0;
    return;
  }
  WallEvaluate(dim, Nf, uOff, u, n, constants, &w);
  for (PetscInt c = 0; c < dim; ++c) g0[c] = w.dm * w.L * w.ut[c];
}
