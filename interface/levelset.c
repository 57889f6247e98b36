/* The level set phi as the problem's extra field: transport kernels with
 * SUPG, the reinitialisation registry and its hooks, options, the volume
 * record.
 *
 * Transport residual (phi last field, a = velocity):
 *   r = phi_t + a . grad phi,   F = (w, r) + (tau a . grad w, r),
 *   tau = supg h_p / (2 |a|_0),  h_p = h / degree,  |a|_0 = sqrt(|a|^2 + a0^2).
 * Convective reinitialisation (Riber's thesis eq. 2.16, discretised as in
 * its eq. 2.18) on the filtered state phi = E tanh(d/E):
 *   r = phi_t + (a + lambda U^n) . grad phi - lambda s(phi^n) (1 - (phi^n/E)^2),
 *   U^n = s(phi^n) grad phi^n/|grad phi^n|_0.1,  s(p) = p / sqrt(p^2 + h^2),
 *   |g|_0.1 = sqrt(|g|^2 + 0.01) (see Convective()), phi^n the last
 *   accepted step; SUPG along the flow a on r, streamline diffusion along
 *   lambda U^n on the redistancing residual (see Convective()).
 * With the speed floor a0 = 0 (-levelset_supg_speed, the default) the
 * transport Jacobian freezes tau(a), which is singular where a = 0; with
 * a0 > 0 tau is smooth and differentiated in a, and the Jacobian is exact
 * (a quasi-static flow needs it: there the velocity is algebraic and a
 * line-search Newton needs a descent direction). The convective Jacobian is
 * exact (its residual is linear in phi, and tau(a*) is differentiated in a). */
#include "interfaceimpl.h"
#include "slumppointwise.h"

#define LSC(k) PetscRealPart(constants[SLUMP_C_FIELD + (k)])

/* tau and, if dtau is given, d tau / d a_c = -tau a_c / |a|_0^2 with the
   speed floor a0 > 0, 0 without (tau frozen) */
static inline PetscReal Tau(PetscInt dim, const PetscReal a[], const PetscScalar constants[], PetscReal dtau[])
{
  const PetscReal a0 = LSC(SLUMP_LS_SPEED);
  PetscReal       n2 = a0 * a0, tau;
  for (PetscInt d = 0; d < dim; ++d) n2 += a[d] * a[d];
  tau = n2 > 0.0 ? LSC(SLUMP_LS_SUPG) * LSC(SLUMP_LS_H) / LSC(SLUMP_LS_DEG) / (2.0 * PetscSqrtReal(n2)) : 0.0;
  if (dtau)
    for (PetscInt d = 0; d < dim; ++d) dtau[d] = a0 > 0 ? -tau * a[d] / n2 : 0.0;
  return tau;
}

#define LS_SETUP \
  const PetscInt     F_   = Nf - 1; \
  const PetscScalar  phi  = u[uOff[F_]], phi_t = u_t[uOff[F_]]; \
  const PetscScalar *phx  = &u_x[uOff_x[F_]]; \
  PetscReal          vel[3] = {0, 0, 0}; \
  for (PetscInt d = 0; d < dim; ++d) vel[d] = PetscRealPart(u[uOff[0] + d]); \
  (void)phi; \
  (void)phx; \
  (void)vel; \
  (void)phi_t

/* ---- plain transport ---- */
static void f0_phi(SLUMP_PW_ARGS, PetscScalar f0[])
{
  LS_SETUP;
  PetscScalar r = phi_t;
  for (PetscInt d = 0; d < dim; ++d) r += vel[d] * phx[d];
  f0[0] = r;
}
static void f1_phi(SLUMP_PW_ARGS, PetscScalar f1[])
{
  LS_SETUP;
  const PetscReal tau = Tau(dim, vel, constants, NULL);
  PetscScalar     r   = phi_t;
  for (PetscInt d = 0; d < dim; ++d) r += vel[d] * phx[d];
  for (PetscInt d = 0; d < dim; ++d) f1[d] = tau * vel[d] * r;
}
static void g0_phi_phi(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  g0[0] = u_tShift;
}
static void g1_phi_phi(SLUMP_PWJ_ARGS, PetscScalar g1[])
{
  LS_SETUP;
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0;
  for (PetscInt d = 0; d < dim; ++d) g1[d] = full ? vel[d] : 0.0;
}
static void g2_phi_phi(SLUMP_PWJ_ARGS, PetscScalar g2[])
{
  LS_SETUP;
  const PetscReal tau = Tau(dim, vel, constants, NULL);
  for (PetscInt d = 0; d < dim; ++d) g2[d] = tau * vel[d] * u_tShift;
}
static void g3_phi_phi(SLUMP_PWJ_ARGS, PetscScalar g3[])
{
  LS_SETUP;
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0;
  const PetscReal tau  = Tau(dim, vel, constants, NULL);
  for (PetscInt d = 0; d < dim; ++d)
    for (PetscInt e = 0; e < dim; ++e) g3[d * dim + e] = full ? tau * vel[d] * vel[e] : 0.0;
}
/* coupling to the velocity (tau frozen unless the speed floor is set) */
static void g0_phi_u(SLUMP_PWJ_ARGS, PetscScalar g0[])
{
  LS_SETUP;
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0;
  for (PetscInt c = 0; c < dim; ++c) g0[c] = full ? phx[c] : 0.0;
}
static void g2_phi_u(SLUMP_PWJ_ARGS, PetscScalar g2[])
{
  LS_SETUP;
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0;
  PetscReal       dtau[3];
  const PetscReal tau = Tau(dim, vel, constants, dtau);
  PetscScalar     r   = phi_t;
  for (PetscInt d = 0; d < dim; ++d) r += vel[d] * phx[d];
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt d = 0; d < dim; ++d) g2[c * dim + d] = full ? tau * ((c == d ? r : 0.0) + vel[d] * phx[c]) + dtau[c] * vel[d] * r : 0.0;
}

/* ---- convective reinitialisation ---- */
/* Riber's eq. 2.18: the direction U and the source are taken from the state
   of the last accepted step phi^n (the auxiliary fields, see
   SlumpProblemSetLaggedState), the transport along a* = a + lambda U^n is
   implicit:
     r = phi_t + a* . grad phi - lambda s(phi^n) (1 - (phi^n/E)^2),
   so the level-set equation is linear in phi within a step.
   Stabilisation: F = (w, r) + (tau a . grad w, r) + (tau lambda U^n . grad w, rho),
   rho = lambda U^n . grad phi - lambda s (1 - (phi^n/E)^2) the redistancing
   residual: SUPG along the flow a, and streamline diffusion along lambda U^n
   on rho, which vanishes on a transported filtered distance (diffusing the
   steady residual r - phi_t instead shrank the circle by 1.5 % a turn with
   lambda = 0.3 on 64^2: it is the transport's residual across a curved
   interface). SUPG along a* on the
   whole residual made the stabilised mass matrix nearly singular where U^n
   turns over a cell (IDA's steps fell to 1e-10); taking U, s and tau from
   the current iterate instead of phi^n (fully implicit) failed in the same
   way (docs/free-surface.md). */
typedef struct {
  PetscReal astar[3], lamU[3], src, tau, dtau_dv[3];
} ConvTerms;

static inline void Convective(PetscInt dim, PetscScalar phin, const PetscScalar gn_[], const PetscReal vel[], const PetscScalar constants[], ConvTerms *ct)
{
  const PetscReal h = LSC(SLUMP_LS_H), lam = LSC(SLUMP_LS_LAMBDA), E = LSC(SLUMP_LS_E), p = PetscRealPart(phin);
  PetscReal       gn[3] = {0, 0, 0}, n2 = 0.0, A2 = 0.01 * lam * lam;
  for (PetscInt d = 0; d < dim; ++d) {
    gn[d] = PetscRealPart(gn_[d]);
    n2 += gn[d] * gn[d];
  }
  /* U = s grad phi / |grad phi|_delta, |g|_delta = sqrt(|g|^2 + delta^2),
     delta = 0.1: where the filter saturates grad phi -> 0 and the direction
     is undefined; U then fades out instead. At steady state the slope is
     |g|^2/|g|_delta = 1 - (phi/E)^2, 0.5 % steeper at the interface. */
  const PetscReal delta = 0.1, nd = PetscSqrtReal(n2 + delta * delta), s = p / PetscSqrtReal(p * p + h * h);
  for (PetscInt d = 0; d < 3; ++d) ct->astar[d] = ct->lamU[d] = ct->dtau_dv[d] = 0.0;
  for (PetscInt d = 0; d < dim; ++d) {
    ct->lamU[d]  = lam * s * gn[d] / nd;
    ct->astar[d] = vel[d] + ct->lamU[d];
    A2 += ct->astar[d] * ct->astar[d];
  }
  ct->src = lam * s * (1.0 - (p / E) * (p / E));
  /* tau with |a*| floored smoothly at lambda/10: a* vanishes on curves,
     where tau a* = (h/2) a* / abs(a*) would jump; d tau/d a = -tau a* / A2 */
  ct->tau = A2 > 0 ? LSC(SLUMP_LS_SUPG) * h / LSC(SLUMP_LS_DEG) / (2.0 * PetscSqrtReal(A2)) : 0.0;
  if (A2 > 0)
    for (PetscInt d = 0; d < dim; ++d) ct->dtau_dv[d] = -ct->tau * ct->astar[d] / A2;
}

/* phi^n and grad phi^n from the auxiliary fields (the current state if the
   lag has not been taken, e.g. in a diagnostic pass); r the residual, rho
   the redistancing residual, sd[d] = a_d r + lambda U_d rho the
   stabilisation's flux over tau */
#define CONV_SETUP \
  LS_SETUP; \
  ConvTerms ct; \
  Convective(dim, NfAux ? a[aOff[F_]] : phi, NfAux ? &a_x[aOff_x[F_]] : phx, vel, constants, &ct); \
  PetscScalar r = phi_t - ct.src, rho = -ct.src, sd[3]; \
  for (PetscInt d = 0; d < dim; ++d) { \
    r += ct.astar[d] * phx[d]; \
    rho += ct.lamU[d] * phx[d]; \
  } \
  for (PetscInt d = 0; d < dim; ++d) sd[d] = vel[d] * r + ct.lamU[d] * rho; \
  const PetscBool full = PetscRealPart(constants[SLUMP_C_JACMODE]) == 0.0; \
  (void)full; \
  (void)sd; \
  (void)rho

static void f0_phi_conv(SLUMP_PW_ARGS, PetscScalar f0[])
{
  CONV_SETUP;
  f0[0] = r;
}
static void f1_phi_conv(SLUMP_PW_ARGS, PetscScalar f1[])
{
  CONV_SETUP;
  for (PetscInt d = 0; d < dim; ++d) f1[d] = ct.tau * sd[d];
}
static void g1_phi_phi_conv(SLUMP_PWJ_ARGS, PetscScalar g1[])
{
  CONV_SETUP;
  for (PetscInt d = 0; d < dim; ++d) g1[d] = full ? ct.astar[d] : 0.0;
}
/* d f1_d / d phi: through phi_t only */
static void g2_phi_phi_conv(SLUMP_PWJ_ARGS, PetscScalar g2[])
{
  CONV_SETUP;
  for (PetscInt d = 0; d < dim; ++d) g2[d] = ct.tau * vel[d] * u_tShift;
}
static void g3_phi_phi_conv(SLUMP_PWJ_ARGS, PetscScalar g3[])
{
  CONV_SETUP;
  for (PetscInt d = 0; d < dim; ++d)
    for (PetscInt e = 0; e < dim; ++e) g3[d * dim + e] = full ? ct.tau * (vel[d] * ct.astar[e] + ct.lamU[d] * ct.lamU[e]) : 0.0;
}
/* d f1_d / d u_c: r and a* are linear in u, tau depends on it through |a*| */
static void g2_phi_u_conv(SLUMP_PWJ_ARGS, PetscScalar g2[])
{
  CONV_SETUP;
  for (PetscInt c = 0; c < dim; ++c)
    for (PetscInt d = 0; d < dim; ++d) g2[c * dim + d] = full ? ct.tau * ((c == d ? r : 0.0) + vel[d] * phx[c]) + ct.dtau_dv[c] * sd[d] : 0.0;
}

static PetscErrorCode SetCoupling(SlumpLevelSet ls, PetscDS ds, PetscInt field, PetscPointJac g2u)
{
  PetscFunctionBeginUser;
  /* in the transport formulation the velocity is constrained: no coupling */
  if (field == 2) PetscCall(PetscDSSetJacobian(ds, field, 0, g0_phi_u, NULL, g2u, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpReinitSetPointwise_Transport(SlumpLevelSet ls, PetscDS ds, PetscInt field)
{
  PetscFunctionBeginUser;
  PetscCall(PetscDSSetResidual(ds, field, f0_phi, f1_phi));
  PetscCall(PetscDSSetJacobian(ds, field, field, g0_phi_phi, g1_phi_phi, g2_phi_phi, g3_phi_phi));
  PetscCall(SetCoupling(ls, ds, field, g2_phi_u));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpReinitSetPointwise_Convective(SlumpLevelSet ls, PetscDS ds, PetscInt field)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemSetLagged(ls->prob, PETSC_TRUE));
  /* the two-phase mixing reads the distance out of the filtered state */
  PetscCall(SlumpProblemSetTwoPhaseFilter(ls->prob, ls->E_cells * ls->h));
  PetscCall(PetscDSSetResidual(ds, field, f0_phi_conv, f1_phi_conv));
  PetscCall(PetscDSSetJacobian(ds, field, field, g0_phi_phi, g1_phi_phi_conv, g2_phi_phi_conv, g3_phi_phi_conv));
  PetscCall(SetCoupling(ls, ds, field, g2_phi_u_conv));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------- registry */
#define MAX_REINIT 16
static struct {
  char           name[64], description[128];
  SlumpReinitOps ops;
} Registry[MAX_REINIT];
static PetscInt NRegistry = 0;

PetscErrorCode SlumpReinitRegister(const char name[], const char description[], const SlumpReinitOps *ops)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < NRegistry; ++i) {
    PetscBool same;
    PetscCall(PetscStrcmp(Registry[i].name, name, &same));
    if (same) {
      Registry[i].ops = *ops;
      PetscFunctionReturn(0);
    }
  }
  PetscCheck(NRegistry < MAX_REINIT, PETSC_COMM_SELF, PETSC_ERR_SUP, "At most %d reinitialisation methods", MAX_REINIT);
  PetscCall(PetscStrncpy(Registry[NRegistry].name, name, sizeof(Registry[0].name)));
  PetscCall(PetscStrncpy(Registry[NRegistry].description, description, sizeof(Registry[0].description)));
  Registry[NRegistry++].ops = *ops;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpReinitRegisterAll(void)
{
  static PetscBool done = PETSC_FALSE;
  SlumpReinitOps   none = {NULL, NULL, PETSC_FALSE, PETSC_FALSE}, conv = {SlumpReinitSetPointwise_Convective, NULL, PETSC_TRUE, PETSC_TRUE};
  SlumpReinitOps   geo = {NULL, SlumpReinitApply_Redistance, PETSC_FALSE, PETSC_FALSE}, hj = {NULL, SlumpReinitApply_HamiltonJacobi, PETSC_FALSE, PETSC_FALSE};
  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = PETSC_TRUE;
  PetscCall(SlumpReinitRegister("none", "transport only", &none));
  PetscCall(SlumpReinitRegister("convective", "coupled transport-redistancing of E tanh(d/E) (Riber eq. 2.16)", &conv));
  PetscCall(SlumpReinitRegister("redistance", "signed distance to the reconstructed zero contour, between steps", &geo));
  PetscCall(SlumpReinitRegister("hamilton_jacobi", "pseudo-time phi_tau + s(phi0)(|grad phi| - 1) = 0, upwind, between steps", &hj));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetSetReinitEvery(SlumpLevelSet ls, PetscInt n)
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 1, ls->comm, PETSC_ERR_USER_INPUT, "-reinit_every must be >= 1 (steps); got %" PetscInt_FMT, n);
  ls->reinit_every = n;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetSetReinitType(SlumpLevelSet ls, const char name[])
{
  PetscFunctionBeginUser;
  PetscCall(SlumpReinitRegisterAll());
  for (PetscInt i = 0; i < NRegistry; ++i) {
    PetscBool same;
    PetscCall(PetscStrcmp(Registry[i].name, name, &same));
    if (same) {
      PetscCall(PetscStrncpy(ls->reinit_name, name, sizeof(ls->reinit_name)));
      ls->reinit = Registry[i].ops;
      PetscFunctionReturn(0);
    }
  }
  {
    char list[512] = "";
    for (PetscInt i = 0; i < NRegistry; ++i) {
      PetscCall(PetscStrlcat(list, i ? ", " : "", sizeof(list)));
      PetscCall(PetscStrlcat(list, Registry[i].name, sizeof(list)));
    }
    SETERRQ(ls->comm, PETSC_ERR_USER_INPUT, "-reinit must be one of %s; got '%s'", list, name);
  }
}

PetscErrorCode SlumpLevelSetGetReinitType(SlumpLevelSet ls, const char **name)
{
  PetscFunctionBeginUser;
  *name = ls->reinit_name;
  PetscFunctionReturn(0);
}

/* ------------------------------------------------ extra-field callbacks */
static PetscErrorCode CreateField(void *ctx, SlumpProblem prob, DM dm, PetscInt field)
{
  SlumpLevelSet ls = (SlumpLevelSet)ctx;
  PetscFE       fe, fe0;
  PetscInt      dim;
  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(PetscFECreateLagrange(PETSC_COMM_SELF, dim, 1, PETSC_TRUE, ls->degree, PETSC_DETERMINE, &fe));
  PetscCall(DMGetField(dm, 0, NULL, (PetscObject *)&fe0));
  PetscCall(PetscFECopyQuadrature(fe0, fe));
  PetscCall(PetscObjectSetName((PetscObject)fe, "levelset"));
  PetscCall(DMSetField(dm, field, NULL, (PetscObject)fe));
  PetscCall(PetscFEDestroy(&fe));
  ls->field = field;
  PetscFunctionReturn(0);
}

static PetscErrorCode SetPointwise(void *ctx, SlumpProblem prob, PetscDS ds, PetscInt field)
{
  SlumpLevelSet ls = (SlumpLevelSet)ctx;
  PetscFunctionBeginUser;
  if (ls->reinit.set_pointwise) PetscCall(ls->reinit.set_pointwise(ls, ds, field));
  else PetscCall(SlumpReinitSetPointwise_Transport(ls, ds, field));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetConstants(void *ctx, SlumpProblem prob, PetscScalar c[])
{
  SlumpLevelSet ls = (SlumpLevelSet)ctx;
  PetscFunctionBeginUser;
  c[SLUMP_LS_H]      = ls->h;
  c[SLUMP_LS_SUPG]   = ls->supg;
  c[SLUMP_LS_LAMBDA] = ls->reinit.filtered ? ls->lambda : 0.0;
  c[SLUMP_LS_E]      = ls->E_cells * ls->h;
  c[SLUMP_LS_DEG]    = (PetscReal)ls->degree;
  c[SLUMP_LS_SPEED]  = ls->supg_speed;
  PetscFunctionReturn(0);
}

static PetscErrorCode InitialPhi(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  SlumpLevelSet ls = (SlumpLevelSet)ctx;
  PetscFunctionBeginUser;
  PetscCall(ls->phi0(dim, t, x, Nc, u, ls->phi0ctx));
  if (ls->reinit.filtered) {
    const PetscReal E = ls->E_cells * ls->h;
    u[0]              = E * PetscTanhReal(PetscRealPart(u[0]) / E);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetRecordVolume(SlumpLevelSet ls, PetscReal t, Vec X)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpLevelSetComputeVolume(ls, t, X, &ls->volume));
  if (!ls->have_volume0) {
    ls->volume0      = ls->volume;
    ls->have_volume0 = PETSC_TRUE;
  }
  if (ls->volume0 > 0) ls->max_drift = PetscMax(ls->max_drift, PetscAbsReal(ls->volume / ls->volume0 - 1.0));
  {
    PetscReal box[4], hg[4];
    PetscBool found[4];
    /* collective: every rank measures, rank 0 writes */
    PetscCall(SlumpLevelSetComputeExtent(ls, t, X, box));
    for (PetscInt g = 0; g < ls->ngauge; ++g) PetscCall(SlumpLevelSetComputeHeightAt(ls, t, X, ls->gauge[g], &hg[g], &found[g]));
    {
      int err = SlumpFilePrintf(ls->log, "%.10g,%.12g,%.6e,%" PetscInt_FMT ",%.8g,%.8g,%.8g,%.8e,%.8e", (double)t, (double)ls->volume, (double)(ls->volume0 > 0 ? ls->volume / ls->volume0 - 1.0 : 0.0), ls->nreinit, (double)box[0], (double)box[1], (double)box[3], (double)ls->energy_reinit, (double)ls->energy_correction);
      for (PetscInt g = 0; g < ls->ngauge && !err; ++g) err = found[g] ? SlumpFilePrintf(ls->log, ",%.8g", (double)hg[g]) : SlumpFilePrintf(ls->log, ",nan");
      if (!err) err = SlumpFilePrintf(ls->log, "\n");
      if (ls->haslog) PetscCall(SlumpFileCheck(ls->comm, err, ls->logpath));
    }
  }
  PetscFunctionReturn(0);
}

/* Global volume correction: phi <- phi - delta with delta such that the
   material volume is back to its initial value (secant iterations on the
   exact volume of the linear interpolant). e0: the potential energy of X on
   entry, for the tally of what the correction adds. */
static PetscErrorCode CorrectVolume(SlumpLevelSet ls, PetscReal t, Vec X, PetscReal e0)
{
  IS              is;
  const PetscInt *idx;
  PetscInt        n, rStart;
  PetscScalar    *x;
  PetscReal       d0 = 0.0, d1, f0, f1, V, applied = 0.0, e1;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetExtraFieldIS(ls->prob, &is));
  PetscCall(ISGetLocalSize(is, &n));
  PetscCall(ISGetIndices(is, &idx));
  PetscCall(VecGetOwnershipRange(X, &rStart, NULL));
  PetscCall(SlumpLevelSetComputeVolume(ls, t, X, &V));
  f0 = V - ls->volume0;
  d1 = 1e-3 * ls->h;
  for (PetscInt it = 0; it < 20 && PetscAbsReal(f0) > 1e-12 * ls->volume0; ++it) {
    /* shift by d1 (from the applied d0) and measure */
    PetscCall(VecGetArray(X, &x));
    for (PetscInt i = 0; i < n; ++i) x[idx[i] - rStart] -= d1 - applied;
    PetscCall(VecRestoreArray(X, &x));
    applied = d1;
    PetscCall(SlumpLevelSetComputeVolume(ls, t, X, &V));
    f1 = V - ls->volume0;
    if (f1 == f0) break;
    {
      const PetscReal d2 = d1 - f1 * (d1 - d0) / (f1 - f0);
      d0                 = d1;
      f0                 = f1;
      d1                 = d2;
    }
  }
  PetscCall(ISRestoreIndices(is, &idx));
  PetscCall(ISDestroy(&is));
  ls->volume_shift += applied;
  PetscCall(SlumpProblemComputePotentialEnergy(ls->prob, t, X, &e1));
  ls->energy_correction += e1 - e0;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetReinitialise(SlumpLevelSet ls, PetscReal t, Vec X, PetscBool *changed)
{
  PetscReal e0, e1;
  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (!ls->reinit.apply) PetscFunctionReturn(0);
  PetscCall(SlumpProblemComputePotentialEnergy(ls->prob, t, X, &e0));
  PetscCall(ls->reinit.apply(ls, ls->prob, t, X, changed));
  if (*changed) {
    ls->nreinit++;
    PetscCall(SlumpProblemComputePotentialEnergy(ls->prob, t, X, &e1));
    ls->energy_reinit += e1 - e0;
    if (ls->volume_correction && ls->have_volume0) PetscCall(CorrectVolume(ls, t, X, e1));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode PostStep(void *ctx, SlumpProblem prob, PetscInt step, PetscReal t, Vec X, PetscBool *changed)
{
  SlumpLevelSet ls = (SlumpLevelSet)ctx;
  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (ls->reinit_every > 0 && step > 0 && step % ls->reinit_every == 0) {
    if (ls->reinit.apply) PetscCall(SlumpLevelSetReinitialise(ls, t, X, changed));
    else if (ls->volume_correction && ls->have_volume0) {
      /* a method without a between-step action (none, convective): the
         global volume correction alone, every reinit_every steps */
      PetscReal e0;
      PetscCall(SlumpProblemComputePotentialEnergy(prob, t, X, &e0));
      PetscCall(CorrectVolume(ls, t, X, e0));
      *changed = PETSC_TRUE;
    }
  }
  PetscCall(SlumpLevelSetRecordVolume(ls, t, X));
  /* every step: a lag of 5 or 20 steps let the front run on ahead of its
     own lagged surface, with little yield stress (chupin_column -plasticity pl) */
  PetscCall(SlumpLevelSetUpdateSurface(ls, t, X));
  /* the lagged terms of the next step (convective) */
  if (ls->reinit.lagged) PetscCall(SlumpProblemSetLaggedState(prob, t, X));
  PetscFunctionReturn(0);
}

static PetscErrorCode View(void *ctx, SlumpProblem prob, PetscViewer viewer)
{
  SlumpLevelSet ls = (SlumpLevelSet)ctx;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "level set: P%" PetscInt_FMT ", SUPG %g, h %g, reinitialisation %s", ls->degree, (double)ls->supg, (double)ls->h, ls->reinit_name));
  if (ls->reinit.filtered) PetscCall(PetscViewerASCIIPrintf(viewer, " (lambda %g, E %g)", (double)ls->lambda, (double)(ls->E_cells * ls->h)));
  if (ls->reinit.apply) PetscCall(PetscViewerASCIIPrintf(viewer, " every %" PetscInt_FMT " steps%s", ls->reinit_every, ls->volume_correction ? ", volume corrected" : ""));
  else if (ls->volume_correction) PetscCall(PetscViewerASCIIPrintf(viewer, ", volume corrected every %" PetscInt_FMT " steps", ls->reinit_every));
  if (ls->surface_feed) PetscCall(PetscViewerASCIIPrintf(viewer, ", surface height fed to the kernels"));
  PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy(void *ctx)
{
  SlumpLevelSet ls = (SlumpLevelSet)ctx;
  PetscFunctionBeginUser;
  (void)SlumpFileClose(&ls->log); /* checked by SlumpLevelSetSetLog(ls, NULL) */
  PetscCall(PetscFree2(ls->surf_x, ls->surf_h));
  PetscCall(SlumpLSNodesDestroy(&ls->nodes));
  PetscCall(PetscFree(ls));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetCreate(SlumpProblem prob, SlumpPointFn phi0, void *ctx, SlumpLevelSet *out)
{
  SlumpLevelSet      ls;
  SlumpExtraFieldOps ops;
  DM                 dm;
  PetscFunctionBeginUser;
  PetscCall(SlumpReinitRegisterAll());
  PetscCall(PetscNew(&ls));
  ls->prob            = prob;
  ls->phi0            = phi0;
  ls->phi0ctx         = ctx;
  ls->degree          = 2;
  ls->supg            = 1.0;
  ls->reinit_every    = 20;
  ls->lambda          = 1.0;
  ls->E_cells         = 2.0;
  ls->hj_iterations   = 30;
  ls->hj_cfl          = 0.8;
  PetscCall(SlumpProblemGetDM(prob, &dm));
  PetscCheck(dm, PETSC_COMM_SELF, PETSC_ERR_ORDER, "Set the mesh before creating the level set");
  PetscCall(PetscObjectGetComm((PetscObject)dm, &ls->comm));
  PetscCall(SlumpMeshGetMinEdgeLength(dm, &ls->h));
  PetscCall(SlumpLevelSetSetReinitType(ls, "none"));
  PetscCall(PetscMemzero(&ops, sizeof(ops)));
  ops.create_field  = CreateField;
  ops.set_pointwise = SetPointwise;
  ops.set_constants = SetConstants;
  ops.init          = InitialPhi;
  ops.post_step     = PostStep;
  ops.view          = View;
  ops.destroy       = Destroy;
  ops.name          = "level set";
  PetscCall(SlumpProblemSetExtraField(prob, &ops, ls));
  *out = ls;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetLevelSet(SlumpProblem prob, SlumpLevelSet *ls)
{
  PetscInt field;
  void    *ctx;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetExtraField(prob, &field, &ctx));
  *ls = field >= 0 ? (SlumpLevelSet)ctx : NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetSetFromOptions(SlumpLevelSet ls)
{
  char      name[64];
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(name, ls->reinit_name, sizeof(name)));
  PetscOptionsBegin(ls->comm, NULL, "Level set", "SlumpLevelSet");
  PetscCall(PetscOptionsInt("-levelset_degree", "Polynomial degree of the level set (1 or 2)", "", ls->degree, &ls->degree, NULL));
  PetscCall(PetscOptionsReal("-levelset_supg", "SUPG factor (0: Galerkin)", "", ls->supg, &ls->supg, NULL));
  PetscCall(PetscOptionsReal("-levelset_supg_speed", "Speed floor a0 in the SUPG tau = h/(2 sqrt(|a|^2 + a0^2)); a0 > 0 makes tau smooth and the Jacobian exact (0: tau(a) frozen in the Jacobian)", "SlumpLevelSetSetSUPGSpeed", ls->supg_speed, &ls->supg_speed, NULL));
  PetscCall(PetscOptionsString("-reinit", "Reinitialisation: none, convective, redistance, hamilton_jacobi", "", name, name, sizeof(name), &set));
  PetscCall(PetscOptionsInt("-reinit_every", "Between-step reinitialisation every n accepted steps", "", ls->reinit_every, &ls->reinit_every, NULL));
  PetscCall(PetscOptionsReal("-reinit_convective_lambda", "Redistancing speed lambda of the convective method", "", ls->lambda, &ls->lambda, NULL));
  PetscCall(PetscOptionsReal("-reinit_convective_width", "Filter width E of the convective method, in cells", "", ls->E_cells, &ls->E_cells, NULL));
  PetscCall(PetscOptionsInt("-reinit_hj_iterations", "Pseudo-time iterations of the Hamilton-Jacobi method", "", ls->hj_iterations, &ls->hj_iterations, NULL));
  PetscCall(PetscOptionsBool("-reinit_volume_correction", "After each between-step reinitialisation (every -reinit_every steps for none and convective), shift phi so that the material volume is the initial one", "", ls->volume_correction, &ls->volume_correction, NULL));
  PetscCall(PetscOptionsBool("-levelset_surface_feed", "Hand the current free-surface height to the kernels after every step (lithostatic yield stress below the current surface)", "SlumpLevelSetSetSurfaceFeed", ls->surface_feed, &ls->surface_feed, NULL));
  PetscCall(PetscOptionsReal("-reinit_hj_cfl", "Pseudo-time step of the Hamilton-Jacobi method over the local mesh size", "", ls->hj_cfl, &ls->hj_cfl, NULL));
  PetscOptionsEnd();
  PetscCheck(ls->degree == 1 || ls->degree == 2, ls->comm, PETSC_ERR_USER_INPUT, "-levelset_degree must be 1 or 2; got %" PetscInt_FMT, ls->degree);
  PetscCheck(ls->supg >= 0, ls->comm, PETSC_ERR_USER_INPUT, "-levelset_supg must be >= 0; got %g", (double)ls->supg);
  PetscCheck(ls->supg_speed >= 0, ls->comm, PETSC_ERR_USER_INPUT, "-levelset_supg_speed must be >= 0 (0: no floor); got %g", (double)ls->supg_speed);
  PetscCheck(ls->reinit_every >= 1, ls->comm, PETSC_ERR_USER_INPUT, "-reinit_every must be >= 1 (steps); got %" PetscInt_FMT, ls->reinit_every);
  PetscCheck(ls->lambda >= 0, ls->comm, PETSC_ERR_USER_INPUT, "-reinit_convective_lambda must be >= 0; got %g", (double)ls->lambda);
  PetscCheck(ls->E_cells > 0, ls->comm, PETSC_ERR_USER_INPUT, "-reinit_convective_width must be > 0 (cells); got %g", (double)ls->E_cells);
  PetscCheck(ls->hj_iterations >= 1, ls->comm, PETSC_ERR_USER_INPUT, "-reinit_hj_iterations must be >= 1; got %" PetscInt_FMT, ls->hj_iterations);
  PetscCheck(ls->hj_cfl > 0 && ls->hj_cfl <= 1, ls->comm, PETSC_ERR_USER_INPUT, "-reinit_hj_cfl must lie in (0, 1]; got %g", (double)ls->hj_cfl);
  if (set) PetscCall(SlumpLevelSetSetReinitType(ls, name));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetSetLog(SlumpLevelSet ls, const char path[])
{
  PetscMPIInt rank;
  int         err = 0;
  PetscFunctionBeginUser;
  if (ls->haslog) PetscCall(SlumpFileCheck(ls->comm, SlumpFileClose(&ls->log), ls->logpath));
  ls->haslog = PETSC_FALSE;
  if (!path) PetscFunctionReturn(0);
  PetscCall(PetscStrncpy(ls->logpath, path, sizeof(ls->logpath)));
  PetscCallMPI(MPI_Comm_rank(ls->comm, &rank));
  if (rank == 0) {
    err = SlumpFileOpen(path, &ls->log);
    if (!err) err = SlumpFilePrintf(ls->log, "t,volume,drift,reinitialisations,x_min,x_max,y_max,energy_reinit,energy_correction");
    for (PetscInt g = 0; g < ls->ngauge && !err; ++g) err = SlumpFilePrintf(ls->log, ",height_at_%g", (double)ls->gauge[g]);
    if (!err) err = SlumpFilePrintf(ls->log, "\n");
  }
  ls->haslog = PETSC_TRUE;
  PetscCall(SlumpFileCheck(ls->comm, err, path));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetSetVolumeCorrection(SlumpLevelSet ls, PetscBool on)
{
  PetscFunctionBeginUser;
  ls->volume_correction = on;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetGetVolumeShift(SlumpLevelSet ls, PetscReal *shift)
{
  PetscFunctionBeginUser;
  *shift = ls->volume_shift;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetGetEnergyInput(SlumpLevelSet ls, PetscReal *reinit, PetscReal *correction)
{
  PetscFunctionBeginUser;
  if (reinit) *reinit = ls->energy_reinit;
  if (correction) *correction = ls->energy_correction;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetSetSurfaceFeed(SlumpLevelSet ls, PetscBool on)
{
  PetscFunctionBeginUser;
  ls->surface_feed = on;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetSetSUPGSpeed(SlumpLevelSet ls, PetscReal a0)
{
  PetscFunctionBeginUser;
  PetscCheck(a0 >= 0, ls->comm, PETSC_ERR_USER_INPUT, "The SUPG speed floor must be >= 0 (0: no floor); got %g", (double)a0);
  ls->supg_speed = a0;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetUpdateSurface(SlumpLevelSet ls, PetscReal t, Vec X)
{
  PetscFunctionBeginUser;
  if (!ls->surface_feed) PetscFunctionReturn(0);
  if (!ls->nsurf) {
    DM        dm;
    PetscReal lo[3], hi[3];
    PetscCall(SlumpProblemGetDM(ls->prob, &dm));
    PetscCall(DMGetBoundingBox(dm, lo, hi));
    /* four samples per smallest edge, as the deposit profile */
    ls->nsurf = PetscMin((PetscInt)PetscCeilReal(4.0 * (hi[0] - lo[0]) / ls->h) + 1, (PetscInt)SLUMP_C_SURF_MAX);
    ls->nsurf = PetscMax(ls->nsurf, 2);
    PetscCall(PetscMalloc2(ls->nsurf, &ls->surf_x, ls->nsurf, &ls->surf_h));
    for (PetscInt i = 0; i < ls->nsurf; ++i) ls->surf_x[i] = lo[0] + (hi[0] - lo[0]) * i / (ls->nsurf - 1);
  }
  PetscCall(SlumpLevelSetComputeProfile(ls, t, X, ls->nsurf, ls->surf_x, ls->surf_h));
  PetscCall(SlumpProblemSetSurfaceHeight(ls->prob, ls->nsurf, ls->surf_x[0], ls->surf_x[1] - ls->surf_x[0], ls->surf_h));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetSetGauges(SlumpLevelSet ls, PetscInt n, const PetscReal x[])
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 0 && n <= 4, ls->comm, PETSC_ERR_ARG_OUTOFRANGE, "At most 4 gauges; got %" PetscInt_FMT, n);
  PetscCheck(!ls->haslog, ls->comm, PETSC_ERR_ORDER, "Set the gauges before opening the log");
  ls->ngauge = n;
  for (PetscInt g = 0; g < n; ++g) ls->gauge[g] = x[g];
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetGetStats(SlumpLevelSet ls, PetscReal *volume0, PetscReal *volume, PetscReal *max_drift, PetscInt *nreinit)
{
  PetscFunctionBeginUser;
  if (volume0) *volume0 = ls->volume0;
  if (volume) *volume = ls->volume;
  if (max_drift) *max_drift = ls->max_drift;
  if (nreinit) *nreinit = ls->nreinit;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetGetMeshSize(SlumpLevelSet ls, PetscReal *h)
{
  PetscFunctionBeginUser;
  *h = ls->h;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetGetState(SlumpLevelSet ls, PetscReal v[])
{
  PetscFunctionBeginUser;
  v[0] = ls->nreinit;
  v[1] = ls->volume0;
  v[2] = ls->have_volume0;
  v[3] = ls->volume;
  v[4] = ls->max_drift;
  v[5] = ls->volume_shift;
  v[6] = ls->energy_reinit;
  v[7] = ls->energy_correction;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpLevelSetSetState(SlumpLevelSet ls, const PetscReal v[])
{
  PetscFunctionBeginUser;
  ls->nreinit           = (PetscInt)v[0];
  ls->volume0           = v[1];
  ls->have_volume0      = v[2] != 0 ? PETSC_TRUE : PETSC_FALSE;
  ls->volume            = v[3];
  ls->max_drift         = v[4];
  ls->volume_shift      = v[5];
  ls->energy_reinit     = v[6];
  ls->energy_correction = v[7];
  PetscFunctionReturn(0);
}
