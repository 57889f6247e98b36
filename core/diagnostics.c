/* Diagnostics by finite-element quadrature over the domain, in the norm
 * convention ||gdot|| = sqrt(1/2 gdot:gdot), gdot = grad u + grad u^T.
 * They are evaluated on a copy of the solution in an unconstrained layout
 * (dmDiag) so that boundary values at the current time are included. */
#include "slumpimpl.h"

static void KineticEnergy(SLUMP_PW_ARGS, PetscScalar f[])
{
  PetscScalar s = 0.0;
  for (PetscInt d = 0; d < uOff[1] - uOff[0]; ++d) s += u[uOff[0] + d] * u[uOff[0] + d];
  f[0] = 0.5 * PetscRealPart(constants[SLUMP_C_RHO]) * s;
}

static void ShearRate(SLUMP_PW_ARGS, PetscScalar f[])
{
  PetscReal p;
  f[0] = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p);
}

static void ShearRateSquared(SLUMP_PW_ARGS, PetscScalar f[])
{
  PetscReal p, g = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p);
  f[0] = g * g;
}

/* Two-phase: the material's share, weighted by its fraction m(phi). */
static inline PetscReal Fraction(PetscInt Nf, const PetscInt uOff[], const PetscScalar u[], const PetscScalar constants[])
{
  PetscReal m, dm;
  SlumpPwMaterialFraction(u[uOff[Nf - 1]], constants, &m, &dm);
  return m;
}

static void KineticEnergyTP(SLUMP_PW_ARGS, PetscScalar f[])
{
  KineticEnergy(dim, Nf, NfAux, uOff, uOff_x, u, u_t, u_x, aOff, aOff_x, a, a_t, a_x, t, x, numConstants, constants, f);
  f[0] *= Fraction(Nf, uOff, u, constants);
}

static void ShearRateTP(SLUMP_PW_ARGS, PetscScalar f[])
{
  PetscReal p;
  f[0] = Fraction(Nf, uOff, u, constants) * SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p);
}

static void ShearRateSquaredTP(SLUMP_PW_ARGS, PetscScalar f[])
{
  PetscReal p, g = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p);
  f[0] = Fraction(Nf, uOff, u, constants) * g * g;
}

/* -rho g . x */
static void PotentialEnergy(SLUMP_PW_ARGS, PetscScalar f[])
{
  PetscReal gx = 0.0;
  for (PetscInt d = 0; d < dim; ++d) gx += PetscRealPart(constants[SLUMP_C_GX + d]) * x[d];
  f[0] = -PetscRealPart(constants[SLUMP_C_RHO]) * gx;
}

static void PotentialEnergyTP(SLUMP_PW_ARGS, PetscScalar f[])
{
  PotentialEnergy(dim, Nf, NfAux, uOff, uOff_x, u, u_t, u_x, aOff, aOff_x, a, a_t, a_x, t, x, numConstants, constants, f);
  f[0] *= Fraction(Nf, uOff, u, constants);
}

/* the ambient fluid's dissipation, (1 - m_v) eta_ambient ||gdot||^2 (m_v: the viscosity's fraction) */
static void AmbientDissipation(SLUMP_PW_ARGS, PetscScalar f[])
{
  PetscReal m, dm, p, g = SlumpPwShearRateAxi(dim, Nf, uOff, u, u_x, x, constants, &p);
  SlumpPwViscousFraction(u[uOff[Nf - 1]], constants, &m, &dm);
  f[0] = (1.0 - m) * PetscRealPart(constants[SLUMP_C_MIX_ETA]) * g * g;
}

/* The friction walls' dissipation at the local solution prob->locX (filled
   by the caller; collective). */
static PetscErrorCode WallDissipation(SlumpProblem prob, PetscReal *power)
{
  PetscFunctionBeginUser;
  *power = 0.0;
  for (PetscInt b = 0; b < prob->nbc && prob->wallFriction; ++b) {
    PetscReal p;
    if (prob->bc[b].kind != SLUMP_BC_FRICTION) continue;
    PetscCall(SlumpAssembleBoundaryIntegral(prob, prob->locX, prob->bc[b].label, 0, SlumpPwWallFrictionPower, &p, NULL));
    *power += p;
  }
  PetscFunctionReturn(0);
}

static void MaterialFraction(SLUMP_PW_ARGS, PetscScalar f[])
{
  f[0] = Fraction(Nf, uOff, u, constants);
}

/* anti-plane flow rate: int w */
static void OutOfPlaneVelocity(SLUMP_PW_ARGS, PetscScalar f[])
{
  f[0] = u[uOff[0]];
}



/* ||gdot|| of a P2 velocity is the norm of a linear field on each triangle,
   a convex function, so its maximum over a cell sits at a vertex: the
   maximum over a discontinuous P1 interpolant is exact. */
static PetscErrorCode MaxShearRate(SlumpProblem prob, PetscReal *gmax)
{
  DM             dmMax;
  Vec            v;
  PetscPointFunc funcs[1] = {prob->twoPhase ? ShearRateTP : ShearRate};
  PetscReal      m;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQuery((PetscObject)prob->dmDiag, "slump_dg1", (PetscObject *)&dmMax));
  if (!dmMax) {
    PetscSpace     P;
    PetscDualSpace Q;
    PetscFE        fe, feu;
    DM             K;
    PetscInt       dim;
    PetscCall(DMGetDimension(prob->dm, &dim));
    PetscCall(PetscSpaceCreate(PETSC_COMM_SELF, &P));
    PetscCall(PetscSpaceSetType(P, PETSCSPACEPOLYNOMIAL));
    PetscCall(PetscSpaceSetNumComponents(P, 1));
    PetscCall(PetscSpaceSetNumVariables(P, dim));
    PetscCall(PetscSpaceSetDegree(P, 1, PETSC_DETERMINE));
    PetscCall(PetscSpaceSetUp(P));
    PetscCall(PetscDualSpaceCreate(PETSC_COMM_SELF, &Q));
    PetscCall(PetscDualSpaceSetType(Q, PETSCDUALSPACELAGRANGE));
    PetscCall(DMPlexCreateReferenceCell(PETSC_COMM_SELF, DM_POLYTOPE_TRIANGLE, &K));
    PetscCall(PetscDualSpaceSetDM(Q, K));
    PetscCall(DMDestroy(&K));
    PetscCall(PetscDualSpaceSetNumComponents(Q, 1));
    PetscCall(PetscDualSpaceSetOrder(Q, 1));
    PetscCall(PetscDualSpaceLagrangeSetContinuity(Q, PETSC_FALSE));
    PetscCall(PetscDualSpaceSetUp(Q));
    PetscCall(PetscFECreate(PETSC_COMM_SELF, &fe));
    PetscCall(PetscFESetType(fe, PETSCFEBASIC));
    PetscCall(PetscFESetBasisSpace(fe, P));
    PetscCall(PetscFESetDualSpace(fe, Q));
    PetscCall(PetscFESetNumComponents(fe, 1));
    PetscCall(PetscFESetUp(fe));
    PetscCall(DMGetField(prob->dmDiag, 0, NULL, (PetscObject *)&feu));
    PetscCall(PetscFECopyQuadrature(feu, fe));
    PetscCall(PetscSpaceDestroy(&P));
    PetscCall(PetscDualSpaceDestroy(&Q));
    PetscCall(DMClone(prob->dm, &dmMax));
    PetscCall(DMSetField(dmMax, 0, NULL, (PetscObject)fe));
    PetscCall(DMCreateDS(dmMax));
    PetscCall(PetscFEDestroy(&fe));
    PetscCall(PetscObjectCompose((PetscObject)prob->dmDiag, "slump_dg1", (PetscObject)dmMax));
    PetscCall(DMDestroy(&dmMax));
    PetscCall(PetscObjectQuery((PetscObject)prob->dmDiag, "slump_dg1", (PetscObject *)&dmMax));
  }
  PetscCall(DMGetGlobalVector(dmMax, &v));
  PetscCall(DMProjectField(dmMax, 0.0, prob->diagX, funcs, INSERT_VALUES, v));
  PetscCall(VecMax(v, NULL, &m));
  PetscCall(DMRestoreGlobalVector(dmMax, &v));
  *gmax = m;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemComputeMeanShearRate(SlumpProblem prob, PetscReal t, Vec X, PetscReal *mean)
{
  SlumpDiagnosticKind k = SLUMP_DIAG_MEAN_SHEAR_RATE;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemComputeDiagnosticList(prob, t, X, 1, &k, mean));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemComputePotentialEnergy(SlumpProblem prob, PetscReal t, Vec X, PetscReal *ep)
{
  PetscPointFunc obj[1] = {prob->twoPhase ? PotentialEnergyTP : PotentialEnergy};
  PetscFunctionBeginUser;
  *ep = 0.0;
  if (!(prob->effects & SLUMP_EFFECT_BODY_FORCE) || prob->formulation != SLUMP_FORMULATION_PLANE) PetscFunctionReturn(0);
  PetscCall(SlumpProblemComputeIntegrals(prob, t, X, 1, obj, ep));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemComputeDiagnostics(SlumpProblem prob, PetscReal t, Vec X, SlumpDiagnostics *d)
{
  SlumpRheologyPointwise pw;
  PetscReal              r[8], area = prob->area;
  const PetscBool        body = (prob->effects & SLUMP_EFFECT_BODY_FORCE) && prob->formulation == SLUMP_FORMULATION_PLANE ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyGetPointwise(prob->rheo, &pw));
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  r[6] = r[7] = 0.0;
  if (prob->twoPhase) {
    PetscPointFunc obj[8] = {KineticEnergyTP, ShearRateTP, ShearRateSquaredTP, pw.tp_diss, pw.tp_yielded, MaterialFraction, AmbientDissipation, PotentialEnergyTP};
    PetscCall(SlumpAssembleIntegrals(prob, t, prob->locX, body ? 8 : 7, obj, r));
    area = prob->materialArea = r[5];
    d->dissipation_ambient = r[6];
    r[6]                   = r[7];
  } else {
    d->dissipation_ambient = 0.0;
    PetscPointFunc obj[7] = {KineticEnergy, ShearRate, ShearRateSquared, pw.diss_yield, pw.yielded, NULL, PotentialEnergy};
    if (body) {
      obj[5] = PotentialEnergy;
      PetscCall(SlumpAssembleIntegrals(prob, t, prob->locX, 6, obj, r));
      r[6] = r[5];
    } else PetscCall(SlumpAssembleIntegrals(prob, t, prob->locX, 5, obj, r));
  }
  d->potential_energy = r[6];
  d->t                = t;
  d->kinetic_energy   = r[0];
  d->mean_shear_rate  = r[1] / area;
  d->l2_shear_rate    = PetscSqrtReal(r[2]);
  d->dissipation      = r[3];
  d->yielded_fraction = prob->yieldedOverride >= 0 ? prob->yieldedOverride : r[4] / area;
  PetscCall(SlumpProblemFillDiagVector(prob, t, X, prob->diagX));
  PetscCall(MaxShearRate(prob, &d->max_shear_rate));
  PetscCall(WallDissipation(prob, &d->dissipation_wall)); /* prob->locX: filled with diagX */
  d->flow_rate = 0.0;
  if (prob->formulation == SLUMP_FORMULATION_ANTIPLANE) {
    PetscPointFunc obj[1] = {OutOfPlaneVelocity};
    PetscCall(SlumpProblemFillLocal(prob, t, X));
    PetscCall(SlumpAssembleIntegrals(prob, t, prob->locX, 1, obj, &d->flow_rate));
  } else if (prob->flowRateLabel[0]) {
    PetscCall(SlumpProblemFillLocal(prob, t, X));
    PetscCall(SlumpAssembleBoundaryIntegral(prob, prob->locX, prob->flowRateLabel, -1, NULL, &d->flow_rate, NULL));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemComputeEnergyRates(SlumpProblem prob, PetscReal t, Vec X, PetscReal *kinetic, PetscReal rate[3])
{
  SlumpRheologyPointwise pw;
  PetscReal              r[3] = {0.0, 0.0, 0.0};
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyGetPointwise(prob->rheo, &pw));
  rate[0] = rate[1] = rate[2] = 0.0;
  if (prob->formulation == SLUMP_FORMULATION_TRANSPORT) { /* a prescribed velocity: nothing dissipates */
    const SlumpDiagnosticKind ke = SLUMP_DIAG_KINETIC_ENERGY;
    PetscCall(SlumpProblemComputeDiagnosticList(prob, t, X, 1, &ke, kinetic));
    PetscFunctionReturn(0);
  }
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  if (prob->twoPhase) {
    PetscPointFunc obj[3] = {KineticEnergyTP, pw.tp_diss, AmbientDissipation};
    PetscCall(SlumpAssembleIntegrals(prob, t, prob->locX, 3, obj, r));
  } else {
    PetscPointFunc obj[2] = {KineticEnergy, pw.diss_yield};
    PetscCall(SlumpAssembleIntegrals(prob, t, prob->locX, 2, obj, r));
  }
  *kinetic = r[0];
  rate[0]  = r[1];
  rate[1]  = r[2];
  if (prob->wallFriction) PetscCall(WallDissipation(prob, &rate[2]));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemComputeErrors(SlumpProblem prob, PetscReal t, Vec X, PetscReal err[2], PetscReal norm[2])
{
  SlumpPointFn zero[2], ex[2];
  void        *ctxs[2] = {prob->exctx, prob->exctx};
  Vec          Z;
  PetscFunctionBeginUser;
  err[0] = err[1] = norm[0] = norm[1] = -1.0;
  if (!prob->uex) PetscFunctionReturn(0);
  if (prob->axis >= 0) {
    /* axisymmetric: the norm of the solid, weighted by r (our cell loop) */
    PetscCall(SlumpProblemFillLocal(prob, t, X));
    ex[0] = prob->uex;
    ex[1] = prob->pex;
    PetscCall(SlumpAssembleL2Diff(prob, t, prob->locX, ex, prob->exctx, err));
    /* the exact solution's norm: the distance of zero from it */
    {
      PetscReal nz[2];
      PetscCall(VecZeroEntries(prob->locX));
      PetscCall(SlumpAssembleL2Diff(prob, t, prob->locX, ex, prob->exctx, nz));
      norm[0] = nz[0];
      norm[1] = nz[1];
    }
    PetscFunctionReturn(0);
  }
  PetscCall(SlumpProblemFillDiagVector(prob, t, X, prob->diagX));
  ex[0] = prob->uex;
  ex[1] = prob->pex;
  if (prob->formulation == SLUMP_FORMULATION_ANTIPLANE) {
    PetscCall(DMComputeL2FieldDiff(prob->dmDiag, t, ex, ctxs, prob->diagX, err));
    err[1] = -1.0;
  } else if (!ex[1]) {
    /* no pressure reference: compare pressure with itself */
    PetscReal e2[2];
    SlumpPointFn f2[2] = {prob->uex, prob->uex};
    PetscCall(DMComputeL2FieldDiff(prob->dmDiag, t, f2, ctxs, prob->diagX, e2));
    err[0] = e2[0];
  } else {
    PetscCall(DMComputeL2FieldDiff(prob->dmDiag, t, ex, ctxs, prob->diagX, err));
  }
  /* norms of the exact solution: distance from zero */
  PetscCall(DMGetGlobalVector(prob->dmDiag, &Z));
  PetscCall(VecZeroEntries(Z));
  zero[0] = ex[0];
  zero[1] = ex[1] ? ex[1] : ex[0];
  PetscCall(DMComputeL2FieldDiff(prob->dmDiag, t, zero, ctxs, Z, norm));
  PetscCall(DMRestoreGlobalVector(prob->dmDiag, &Z));
  if (!ex[1] || prob->formulation == SLUMP_FORMULATION_ANTIPLANE) err[1] = norm[1] = -1.0;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemComputeBoundaryMean(SlumpProblem prob, PetscReal t, Vec X, const char label[], PetscInt comp, PetscReal *mean)
{
  PetscReal integral, length;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  PetscCall(SlumpAssembleBoundaryIntegral(prob, prob->locX, label, comp, NULL, &integral, &length));
  *mean = length > 0 ? integral / length : 0.0;
  PetscFunctionReturn(0);
}

const char *const SlumpDiagnosticNames[] = {"mean_shear_rate", "max_shear_rate", "l2_shear_rate", "kinetic_energy", "yielded_fraction"};

PetscErrorCode SlumpProblemComputeDiagnosticList(SlumpProblem prob, PetscReal t, Vec X, PetscInt n, const SlumpDiagnosticKind kinds[], PetscReal values[])
{
  SlumpRheologyPointwise pw;
  PetscPointFunc         obj[SLUMP_DIAG_NUM + 1];
  PetscReal              r[SLUMP_DIAG_NUM + 1], area = prob->area;
  PetscInt               slot[SLUMP_DIAG_NUM], nobj = 0;
  const PetscBool        tp = prob->twoPhase;
  PetscBool              want[SLUMP_DIAG_NUM] = {PETSC_FALSE};
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyGetPointwise(prob->rheo, &pw));
  for (PetscInt k = 0; k < n; ++k) want[kinds[k]] = PETSC_TRUE;
  for (PetscInt d = 0; d < SLUMP_DIAG_NUM; ++d) {
    slot[d] = -1;
    if (!want[d] || d == SLUMP_DIAG_MAX_SHEAR_RATE) continue;
    slot[d]     = nobj;
    if (tp) obj[nobj++] = d == SLUMP_DIAG_MEAN_SHEAR_RATE ? ShearRateTP : d == SLUMP_DIAG_L2_SHEAR_RATE ? ShearRateSquaredTP : d == SLUMP_DIAG_KINETIC_ENERGY ? KineticEnergyTP : pw.tp_yielded;
    else obj[nobj++] = d == SLUMP_DIAG_MEAN_SHEAR_RATE ? ShearRate : d == SLUMP_DIAG_L2_SHEAR_RATE ? ShearRateSquared : d == SLUMP_DIAG_KINETIC_ENERGY ? KineticEnergy : pw.yielded;
  }
  /* two-phase: means over the material's area, measured in the same pass */
  if (tp && nobj) obj[nobj++] = MaterialFraction;
  if (nobj) {
    PetscCall(SlumpProblemFillLocal(prob, t, X));
    PetscCall(SlumpAssembleIntegrals(prob, t, prob->locX, nobj, obj, r));
    if (tp) area = prob->materialArea = r[nobj - 1];
  }
  for (PetscInt k = 0; k < n; ++k) {
    switch (kinds[k]) {
    case SLUMP_DIAG_MEAN_SHEAR_RATE:
      values[k] = r[slot[kinds[k]]] / area;
      break;
    case SLUMP_DIAG_L2_SHEAR_RATE:
      values[k] = PetscSqrtReal(r[slot[kinds[k]]]);
      break;
    case SLUMP_DIAG_KINETIC_ENERGY:
      values[k] = r[slot[kinds[k]]];
      break;
    case SLUMP_DIAG_YIELDED_FRACTION:
      values[k] = r[slot[kinds[k]]] / area;
      break;
    case SLUMP_DIAG_MAX_SHEAR_RATE:
      PetscCall(SlumpProblemFillDiagVector(prob, t, X, prob->diagX));
      PetscCall(MaxShearRate(prob, &values[k]));
      break;
    default:
      SETERRQ(prob->comm, PETSC_ERR_ARG_OUTOFRANGE, "Unknown diagnostic");
    }
  }
  PetscFunctionReturn(0);
}
