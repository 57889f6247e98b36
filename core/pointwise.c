/* Momentum and continuity pointwise terms of the effects a scene switches on.
 *
 *   momentum:   rho (u_t + u . grad u) - rho g  [f0]   +  tau - p I  [f1, rheology]
 *   continuity: -div u                          [f0]
 *
 * One function per combination of effects, so a term that is off costs
 * nothing at the quadrature points (no branch, no assembly). */
#include "slumpimpl.h"

static inline void MomentumF0(PetscInt dim, const PetscScalar u[], const PetscScalar u_t[], const PetscScalar u_x[], const PetscScalar constants[], PetscBool inertia, PetscBool convection, PetscBool body, PetscScalar f0[])
{
  const PetscReal rho = PetscRealPart(constants[SLUMP_C_RHO]);
  for (PetscInt c = 0; c < dim; ++c) {
    PetscScalar v = 0.0;
    if (inertia) v += rho * u_t[c];
    if (convection)
      for (PetscInt d = 0; d < dim; ++d) v += rho * u[d] * u_x[c * dim + d];
    if (body) v -= rho * constants[SLUMP_C_GX + c];
    f0[c] = v;
  }
}

#define MOMENTUM_F0(NAME, INERTIA, CONV, BODY) \
  static void NAME(SLUMP_PW_ARGS, PetscScalar f0[]) \
  { \
    MomentumF0(dim, u, u_t, u_x, constants, INERTIA, CONV, BODY, f0); \
  }
MOMENTUM_F0(f0_u_none, PETSC_FALSE, PETSC_FALSE, PETSC_FALSE)
MOMENTUM_F0(f0_u_I, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE)
MOMENTUM_F0(f0_u_IC, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE)
MOMENTUM_F0(f0_u_B, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE)
MOMENTUM_F0(f0_u_IB, PETSC_TRUE, PETSC_FALSE, PETSC_TRUE)
MOMENTUM_F0(f0_u_ICB, PETSC_TRUE, PETSC_TRUE, PETSC_TRUE)

PetscPointFunc SlumpPwSelectMomentumF0(PetscInt e)
{
  const PetscBool in = (e & SLUMP_EFFECT_INERTIA) ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool cv = (e & SLUMP_EFFECT_CONVECTION) ? PETSC_TRUE : PETSC_FALSE;
  const PetscBool bf = (e & SLUMP_EFFECT_BODY_FORCE) ? PETSC_TRUE : PETSC_FALSE;
  if (in && cv) return bf ? f0_u_ICB : f0_u_IC;
  if (in) return bf ? f0_u_IB : f0_u_I;
  return bf ? f0_u_B : f0_u_none;
}

/* d f0_u / d u = rho shift I + rho grad u (convection). */
static void g0_uu_I(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  const PetscReal rho = PetscRealPart(constants[SLUMP_C_RHO]);
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt e = 0; e < dim; ++e) g0[c * dim + e] = (c == e) ? rho * u_tShift : 0.0;
}
static void g0_uu_IC(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  const PetscReal rho  = PetscRealPart(constants[SLUMP_C_RHO]);
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0;
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt e = 0; e < dim; ++e) g0[c * dim + e] = ((c == e) ? rho * u_tShift : 0.0) + (full ? rho * u_x[c * dim + e] : 0.0);
}
/* d f0_u[c] / d u_x[e,d] = rho u_d delta_ce. */
static void g1_uu_C(SLUMP_PWJ_ARGS, PetscScalar g1[])
{
  const PetscReal rho  = PetscRealPart(constants[SLUMP_C_RHO]);
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0;
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt e = 0; e < dim; ++e)
      for (PetscInt d = 0; d < dim; ++d) g1[(c * dim + e) * dim + d] = (c == e && full) ? rho * u[d] : 0.0;
}

PetscPointJac SlumpPwSelectG0(PetscInt e)
{
  if (!(e & SLUMP_EFFECT_INERTIA)) return NULL;
  return (e & SLUMP_EFFECT_CONVECTION) ? g0_uu_IC : g0_uu_I;
}

PetscPointJac SlumpPwSelectG1(PetscInt e)
{
  return (e & SLUMP_EFFECT_CONVECTION) ? g1_uu_C : NULL;
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
