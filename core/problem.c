/* The problem: fields (Taylor-Hood P2/P1), the effects a scene switches on,
 * boundary conditions, and the constants handed to the pointwise kernels. */
#include "slumpimpl.h"

const char *const SlumpEffectNames[] = {"inertia", "convection", "body_force", "free_surface"};
const char *const SlumpWallLaws[]    = {"navier", "coulomb", "SlumpWallLaw", "SLUMP_WALL_", NULL};

static PetscErrorCode ZeroFn(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx);

PetscErrorCode SlumpProblemCreate(MPI_Comm comm, SlumpProblem *prob)
{
  SlumpProblem p;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&p));
  p->comm           = comm;
  p->rho            = 1.0;
  p->velocityDegree = 2;
  p->pressureDegree = 1;
  p->quadOrder      = 3; /* (3+1)^2 = 16 points: exact to degree 7 */
  p->convForm       = SLUMP_CONVECTION_ADVECTIVE;
  p->extraField     = -1;
  p->axis           = -1;
  p->yieldedOverride = -1.0;
  p->linForcing     = PETSC_FALSE;
  p->linEscalateIts = 1000;
  p->linPinCorrection = PETSC_TRUE;
  PetscCall(SlumpRheologyCreate(comm, &p->rheo));
  *prob = p;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemDestroy(SlumpProblem *prob)
{
  SlumpProblem p = *prob;
  PetscFunctionBeginUser;
  if (!p) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&p->locX));
  PetscCall(VecDestroy(&p->locXdot));
  PetscCall(VecDestroy(&p->locLag));
  PetscCall(VecDestroy(&p->locF));
  PetscCall(VecDestroy(&p->diagX));
  PetscCall(SlumpAssemblyDestroy(&p->assembly));
  PetscCall(SlumpProblemLinearDestroy(p));
  PetscCall(PetscFree2(p->dual, p->dualSave));
  PetscCall(PetscFree2(p->dualYield, p->dualYieldJ));
  PetscCall(PetscFree(p->yieldMap));
  PetscCall(PetscFree(p->plasticStress));
  PetscCall(VecDestroy(&p->dualLin));
  PetscCall(VecDestroy(&p->locDual));
  PetscCall(PetscFree2(p->bcIdx, p->bcVal));
  PetscCall(DMDestroy(&p->dmDiag));
  PetscCall(DMDestroy(&p->dm));
  PetscCall(SlumpRheologyDestroy(&p->rheo));
  if (p->extraOps.destroy) PetscCall(p->extraOps.destroy(p->extraCtx));
  PetscCall(PetscFree(*prob));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetMesh(SlumpProblem prob, DM mesh)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectReference((PetscObject)mesh));
  PetscCall(DMDestroy(&prob->dm));
  prob->dm = mesh;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetFormulation(SlumpProblem prob, SlumpFormulation f)
{
  PetscFunctionBeginUser;
  prob->formulation = f;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetAxisymmetric(SlumpProblem prob, PetscInt radial)
{
  PetscFunctionBeginUser;
  PetscCheck(!prob->setup, prob->comm, PETSC_ERR_ORDER, "Set the geometry before SlumpProblemSetUp()");
  PetscCheck(radial < 2, prob->comm, PETSC_ERR_ARG_OUTOFRANGE, "The radial coordinate is 0 (x) or 1 (y); got %d", (int)radial);
  prob->axis = radial < 0 ? -1 : radial;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetAxisymmetric(SlumpProblem prob, PetscInt *radial)
{
  PetscFunctionBeginUser;
  *radial = prob->axis;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetFormulation(SlumpProblem prob, SlumpFormulation *f)
{
  PetscFunctionBeginUser;
  *f = prob->formulation;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetEffects(SlumpProblem prob, PetscInt effects)
{
  PetscFunctionBeginUser;
  PetscCheck(!(effects & SLUMP_EFFECT_CONVECTION) || (effects & SLUMP_EFFECT_INERTIA), prob->comm, PETSC_ERR_USER_INPUT, "Convection needs inertia: switch on inertia too");
  prob->effects = effects;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetEffects(SlumpProblem prob, PetscInt *effects)
{
  PetscFunctionBeginUser;
  *effects = prob->effects;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetDensity(SlumpProblem prob, PetscReal rho)
{
  PetscFunctionBeginUser;
  PetscCheck(rho > 0.0, prob->comm, PETSC_ERR_USER_INPUT, "-density must be positive; got %g", (double)rho);
  prob->rho = rho;
  if (prob->setup) PetscCall(SlumpProblemSetConstantsAll(prob)); /* a continuation in the Reynolds number */
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetDensity(SlumpProblem prob, PetscReal *rho)
{
  PetscFunctionBeginUser;
  *rho = prob->rho;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetBodyForce(SlumpProblem prob, PetscReal gx, PetscReal gy)
{
  PetscFunctionBeginUser;
  prob->g[0] = gx;
  prob->g[1] = gy;
  if (prob->setup) PetscCall(SlumpProblemSetConstantsAll(prob)); /* a continuation in the load */
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetRheology(SlumpProblem prob, SlumpRheology *rheo)
{
  PetscFunctionBeginUser;
  *rheo = prob->rheo;
  PetscFunctionReturn(0);
}

static PetscErrorCode AddBC(SlumpProblem prob, SlumpBC **bc)
{
  PetscFunctionBeginUser;
  PetscCheck(prob->nbc < SLUMP_MAX_BC, prob->comm, PETSC_ERR_SUP, "At most %d boundary conditions", SLUMP_MAX_BC);
  *bc = &prob->bc[prob->nbc++];
  PetscCall(PetscMemzero(*bc, sizeof(**bc)));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemAddVelocityBC(SlumpProblem prob, const char name[], const char label[], PetscInt ncomp, const PetscInt comps[], SlumpPointFn g, SlumpPointFn g_t, void *ctx)
{
  SlumpBC *bc = NULL;
  PetscFunctionBeginUser;
  PetscCall(AddBC(prob, &bc));
  bc->kind = SLUMP_BC_DIRICHLET;
  PetscCall(PetscStrncpy(bc->name, name, sizeof(bc->name)));
  PetscCall(PetscStrncpy(bc->label, label, sizeof(bc->label)));
  bc->ncomp = comps ? ncomp : 0;
  for (PetscInt c = 0; c < bc->ncomp; ++c) bc->comps[c] = comps[c];
  bc->g   = g;
  bc->g_t = g_t;
  bc->ctx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemAddFreeSlipBC(SlumpProblem prob, const char label[])
{
  SlumpBC *bc = NULL;
  PetscFunctionBeginUser;
  PetscCall(AddBC(prob, &bc));
  bc->kind = SLUMP_BC_FREESLIP;
  PetscCall(PetscSNPrintf(bc->name, sizeof(bc->name), "freeslip_%s", label));
  PetscCall(PetscStrncpy(bc->label, label, sizeof(bc->label)));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemAddFrictionBC(SlumpProblem prob, const char label[], SlumpWallLaw law, PetscReal coeff, PetscReal reg)
{
  SlumpBC *bc = NULL;
  PetscFunctionBeginUser;
  PetscCheck(coeff >= 0, prob->comm, PETSC_ERR_USER_INPUT, "The wall friction coefficient must be >= 0; got %g", (double)coeff);
  PetscCheck(law == SLUMP_WALL_NAVIER || reg > 0, prob->comm, PETSC_ERR_USER_INPUT, "The Coulomb wall law needs a velocity scale delta > 0; got %g", (double)reg);
  PetscCheck(!prob->wallFriction || (prob->wallLaw == law && prob->wallCoeff == coeff && prob->wallReg == reg), prob->comm, PETSC_ERR_SUP, "One wall friction law per problem: %s was already set", SlumpWallLaws[prob->wallLaw]);
  PetscCall(AddBC(prob, &bc));
  bc->kind = SLUMP_BC_FRICTION;
  PetscCall(PetscSNPrintf(bc->name, sizeof(bc->name), "friction_%s", label));
  PetscCall(PetscStrncpy(bc->label, label, sizeof(bc->label)));
  prob->wallFriction = PETSC_TRUE;
  prob->wallLaw      = law;
  prob->wallCoeff    = coeff;
  prob->wallReg      = reg;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetYieldedFraction(SlumpProblem prob, PetscReal fraction)
{
  PetscFunctionBeginUser;
  prob->yieldedOverride = fraction;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemHasWallFriction(SlumpProblem prob, PetscBool *has)
{
  PetscFunctionBeginUser;
  *has = prob->wallFriction;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetPressureReference(SlumpProblem prob, const PetscReal x[])
{
  PetscFunctionBeginUser;
  prob->pinSet = PETSC_TRUE;
  for (PetscInt d = 0; d < 3; ++d) prob->pinX[d] = 0.0;
  for (PetscInt d = 0; d < 2; ++d) prob->pinX[d] = x[d];
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemAddTractionBC(SlumpProblem prob, const char label[], SlumpTractionFn traction)
{
  SlumpBC *bc = NULL;
  PetscFunctionBeginUser;
  PetscCall(AddBC(prob, &bc));
  bc->kind = SLUMP_BC_TRACTION;
  PetscCall(PetscSNPrintf(bc->name, sizeof(bc->name), "traction_%s", label));
  PetscCall(PetscStrncpy(bc->label, label, sizeof(bc->label)));
  bc->traction = traction;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetMomentumSource(SlumpProblem prob, PetscPointFunc f0_u)
{
  PetscFunctionBeginUser;
  prob->momentumSource = f0_u;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetSceneConstant(SlumpProblem prob, PetscInt i, PetscReal value)
{
  PetscFunctionBeginUser;
  PetscCheck(i >= 0 && i < 4, prob->comm, PETSC_ERR_ARG_OUTOFRANGE, "Scene constant index %" PetscInt_FMT " must lie in [0, 3]", i);
  prob->sceneConst[i] = value;
  if (prob->setup) PetscCall(SlumpProblemSetConstantsAll(prob));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetInitialVelocity(SlumpProblem prob, SlumpPointFn u0, void *ctx)
{
  PetscFunctionBeginUser;
  prob->u0    = u0;
  prob->u0ctx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetPrescribedVelocity(SlumpProblem prob, SlumpPointFn u, SlumpPointFn u_t, void *ctx)
{
  PetscFunctionBeginUser;
  prob->uPresc    = u;
  prob->uPresc_t  = u_t;
  prob->uPrescCtx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetExtraField(SlumpProblem prob, const SlumpExtraFieldOps *ops, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCheck(!prob->setup, prob->comm, PETSC_ERR_ORDER, "Attach the extra field before SlumpProblemSetUp()");
  PetscCheck(prob->formulation != SLUMP_FORMULATION_ANTIPLANE, prob->comm, PETSC_ERR_SUP, "An anti-plane flow carries no extra field");
  if (prob->extraOps.destroy) PetscCall(prob->extraOps.destroy(prob->extraCtx));
  prob->extraOps   = *ops;
  prob->extraCtx   = ctx;
  prob->extraField = prob->formulation == SLUMP_FORMULATION_PLANE ? 2 : 1;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetExtraField(SlumpProblem prob, PetscInt *field, void **ctx)
{
  PetscFunctionBeginUser;
  if (field) *field = prob->extraField;
  if (ctx) *ctx = prob->extraCtx;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetExtraFieldIS(SlumpProblem prob, IS *isx)
{
  IS      *is;
  PetscInt nf;
  PetscFunctionBeginUser;
  *isx = NULL;
  if (prob->extraField < 0) PetscFunctionReturn(0);
  PetscCall(DMCreateFieldIS(prob->dm, &nf, NULL, &is));
  for (PetscInt f = 0; f < nf; ++f) {
    if (f == prob->extraField) *isx = is[f];
    else PetscCall(ISDestroy(&is[f]));
  }
  PetscCall(PetscFree(is));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemPostStep(SlumpProblem prob, PetscInt step, PetscReal t, Vec X, PetscBool *changed)
{
  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (prob->extraOps.post_step) PetscCall(prob->extraOps.post_step(prob->extraCtx, prob, step, t, X, changed));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetLocalSolution(SlumpProblem prob, PetscReal t, Vec X, Vec *locX)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  *locX = prob->locX;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemComputeIntegrals(SlumpProblem prob, PetscReal t, Vec X, PetscInt n, PetscPointFunc obj[], PetscReal result[])
{
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemFillLocal(prob, t, X));
  PetscCall(SlumpAssembleIntegrals(prob, t, prob->locX, n, obj, result));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetInitialPressure(SlumpProblem prob, SlumpPointFn p0, void *ctx)
{
  PetscFunctionBeginUser;
  prob->p0    = p0;
  prob->p0ctx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetExactSolution(SlumpProblem prob, SlumpPointFn u, SlumpPointFn p, void *ctx)
{
  PetscFunctionBeginUser;
  prob->uex   = u;
  prob->pex   = p;
  prob->exctx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetExactSolution(SlumpProblem prob, SlumpPointFn *u, SlumpPointFn *p, void **ctx)
{
  PetscFunctionBeginUser;
  if (u) *u = prob->uex;
  if (p) *p = prob->pex;
  if (ctx) *ctx = prob->exctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetFlowRateBoundary(SlumpProblem prob, const char label[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(prob->flowRateLabel, label, sizeof(prob->flowRateLabel)));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetTwoPhase(SlumpProblem prob, PetscReal rho_ambient, PetscReal eta_ambient, PetscReal width)
{
  PetscFunctionBeginUser;
  PetscCheck(!prob->setup, prob->comm, PETSC_ERR_ORDER, "Set the two-phase mixing before SlumpProblemSetUp()");
  PetscCheck(rho_ambient > 0.0, prob->comm, PETSC_ERR_USER_INPUT, "-ambient_density must be positive; got %g", (double)rho_ambient);
  PetscCheck(eta_ambient > 0.0, prob->comm, PETSC_ERR_USER_INPUT, "-ambient_viscosity must be positive; got %g", (double)eta_ambient);
  PetscCheck(width > 0.0, prob->comm, PETSC_ERR_USER_INPUT, "-mixing_width must be positive (a number of mesh cells); got %g", (double)width);
  prob->twoPhase   = PETSC_TRUE;
  prob->rhoAmbient = rho_ambient;
  prob->etaAmbient = eta_ambient;
  prob->mixWidth   = width;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetTwoPhaseFilter(SlumpProblem prob, PetscReal E)
{
  PetscFunctionBeginUser;
  PetscCheck(E >= 0.0, prob->comm, PETSC_ERR_ARG_OUTOFRANGE, "The level set's filter width must be >= 0; got %g", (double)E);
  prob->mixFilter = E;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetConvectionForm(SlumpProblem prob, SlumpConvectionForm form)
{
  PetscFunctionBeginUser;
  PetscCheck(!prob->setup, prob->comm, PETSC_ERR_ORDER, "Set the convection form before SlumpProblemSetUp()");
  PetscCheck(form >= SLUMP_CONVECTION_ADVECTIVE && form <= SLUMP_CONVECTION_SKEW, prob->comm, PETSC_ERR_ARG_OUTOFRANGE, "Unknown convection form %d", (int)form);
  prob->convForm = (PetscInt)form;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetTwoPhaseViscosityShift(SlumpProblem prob, PetscReal shift)
{
  PetscFunctionBeginUser;
  PetscCheck(!prob->setup, prob->comm, PETSC_ERR_ORDER, "Set the two-phase mixing before SlumpProblemSetUp()");
  PetscCheck(shift >= 0.0 && shift <= 1.0, prob->comm, PETSC_ERR_USER_INPUT, "-mixing_viscosity_shift must lie in [0, 1] (a fraction of the mixing half-width); got %g", (double)shift);
  prob->mixShift = shift;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetTwoPhase(SlumpProblem prob, PetscBool *on, PetscReal *rho_ambient, PetscReal *eta_ambient, PetscReal *width)
{
  PetscFunctionBeginUser;
  if (on) *on = prob->twoPhase;
  if (rho_ambient) *rho_ambient = prob->rhoAmbient;
  if (eta_ambient) *eta_ambient = prob->etaAmbient;
  if (width) *width = prob->mixWidth;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetFromOptions(SlumpProblem prob)
{
  PetscReal rho = prob->rho;
  PetscFunctionBeginUser;
  PetscOptionsBegin(prob->comm, NULL, "Problem", "SlumpProblem");
  PetscCall(PetscOptionsReal("-density", "Density rho", "SlumpProblemSetDensity", rho, &rho, NULL));
  if (prob->twoPhase) {
    PetscReal ra = prob->rhoAmbient, ea = prob->etaAmbient, w = prob->mixWidth;
    PetscCall(PetscOptionsReal("-ambient_density", "Density of the ambient fluid (two-phase)", "SlumpProblemSetTwoPhase", ra, &ra, NULL));
    PetscCall(PetscOptionsReal("-ambient_viscosity", "Viscosity of the ambient fluid (two-phase)", "SlumpProblemSetTwoPhase", ea, &ea, NULL));
    PetscCall(PetscOptionsReal("-mixing_width", "Half-width of the smoothed Heaviside, in mesh cells (two-phase)", "SlumpProblemSetTwoPhase", w, &w, NULL));
    PetscCall(SlumpProblemSetTwoPhase(prob, ra, ea, w));
    {
      PetscReal sh = prob->mixShift;
      PetscCall(PetscOptionsReal("-mixing_viscosity_shift", "Shift of the viscosity's Heaviside into the ambient fluid, as a fraction of the half-width (1: the material law holds up to the zero contour)", "SlumpProblemSetTwoPhaseViscosityShift", sh, &sh, NULL));
      PetscCall(SlumpProblemSetTwoPhaseViscosityShift(prob, sh));
    }
  }
  PetscCall(PetscOptionsRangeInt("-velocity_degree", "Polynomial degree of the velocity", "", prob->velocityDegree, &prob->velocityDegree, NULL, 2, 4));
  {
    const char *kinds[] = {"slump", "petsc"};
    PetscInt    k       = prob->petscAssembly ? 1 : 0;
    PetscCall(PetscOptionsEList("-assembly", "Cell loop: slump (ours, fast) or petsc (DMPlexTSComputeIFunctionFEM/IJacobianFEM)", "", kinds, 2, kinds[k], &k, NULL));
    prob->petscAssembly = k == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  if (prob->effects & SLUMP_EFFECT_CONVECTION) {
    const char *forms[] = {"advective", "temam", "skew"};
    PetscCall(PetscOptionsEList("-convection_form", "Convective terms: advective (rho u.grad u), temam (+ 1/2 rho (div u) u) or skew (+ 1/2 (rho_t + div(rho u)) u; with it the inertial terms do no work on the discrete velocity)", "", forms, 3, forms[prob->convForm], &prob->convForm, NULL));
  }
  PetscCall(PetscOptionsRangeInt("-quadrature_order", "Quadrature: q+1 Gauss-Jacobi points per direction, exact for polynomials of degree 2q+1", "", prob->quadOrder, &prob->quadOrder, NULL, 1, 6));
  PetscOptionsEnd();
  prob->pressureDegree = prob->velocityDegree - 1;
  PetscCall(SlumpProblemSetDensity(prob, rho));
  PetscCall(SlumpRheologySetFromOptions(prob->rheo));
  {
    /* the Newton linearisation of the yield term (timeint/ applies it at
       every nonlinear solve): stress-velocity by default for a yield law */
    const char *kinds[] = {"primal", "stress_velocity"};
    PetscBool   plastic;
    PetscInt    k;
    PetscCall(SlumpRheologyHasPlasticPart(prob->rheo, &plastic));
    k = (plastic && !prob->petscAssembly) ? 1 : 0; /* PETSc's cell loop cannot hand S to the kernels */
    PetscOptionsBegin(prob->comm, NULL, "Newton linearisation", "SlumpProblem");
    PetscCall(PetscOptionsEList("-newton_linearisation", "Newton's tangent for yield-stress laws: primal, or stress_velocity (the plastic stress as a quadrature-point variable; the default for models with a yield term, with -assembly slump)", "SlumpProblemSetStressVelocity", kinds, 2, kinds[k], &k, NULL));
    PetscOptionsEnd();
    prob->dualWanted    = k == 1 ? PETSC_TRUE : PETSC_FALSE;
    prob->dualWantedSet = PETSC_TRUE;
  }
  PetscCall(SlumpProblemLinearSetFromOptions(prob));
  PetscFunctionReturn(0);
}

/* Label values present anywhere (collective), so every rank passes the same ids. */
static PetscErrorCode GetLabelIds(SlumpProblem prob, const char name[], DMLabel *label, PetscInt *nids, PetscInt **ids)
{
  IS       valueIS;
  PetscInt n = 0, gn, has;
  PetscFunctionBeginUser;
  PetscCall(DMGetLabel(prob->dm, name, label));
  has = *label ? 1 : 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &has, 1, MPIU_INT, MPI_MAX, prob->comm));
  PetscCheck(has, prob->comm, PETSC_ERR_USER_INPUT, "The mesh has no boundary labelled '%s' (a Gmsh mesh needs a physical group of that name)", name);
  if (!*label) {
    PetscCall(DMCreateLabel(prob->dm, name));
    PetscCall(DMGetLabel(prob->dm, name, label));
  }
  PetscCall(DMLabelGetValueIS(*label, &valueIS));
  PetscCall(ISGetLocalSize(valueIS, &n));
  {
    PetscInt        maxv = -1, gmaxv;
    const PetscInt *v;
    PetscCall(ISGetIndices(valueIS, &v));
    for (PetscInt i = 0; i < n; ++i) maxv = PetscMax(maxv, v[i]);
    PetscCall(ISRestoreIndices(valueIS, &v));
    PetscCall(MPIU_Allreduce(&maxv, &gmaxv, 1, MPIU_INT, MPI_MAX, prob->comm));
    /* every value up to the max that any rank has */
    PetscInt *flag;
    PetscCall(PetscCalloc1(gmaxv + 2, &flag));
    PetscCall(ISGetIndices(valueIS, &v));
    for (PetscInt i = 0; i < n; ++i)
      if (v[i] >= 0) flag[v[i]] = 1;
    PetscCall(ISRestoreIndices(valueIS, &v));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, flag, gmaxv + 1, MPIU_INT, MPI_MAX, prob->comm));
    gn = 0;
    for (PetscInt i = 0; i <= gmaxv; ++i) gn += flag[i];
    PetscCall(PetscMalloc1(PetscMax(gn, 1), ids));
    gn = 0;
    for (PetscInt i = 0; i <= gmaxv; ++i)
      if (flag[i]) (*ids)[gn++] = i;
    PetscCall(PetscFree(flag));
  }
  PetscCall(ISDestroy(&valueIS));
  *nids = gn;
  PetscFunctionReturn(0);
}

/* The velocity component normal to an axis-aligned boundary (free slip). */
static PetscErrorCode FreeSlipComponent(SlumpProblem prob, DMLabel label, PetscInt nids, const PetscInt ids[], PetscInt *comp)
{
  PetscInt fStart, fEnd, votes[2] = {0, 0}, bad = 0;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(prob->dm, 1, &fStart, &fEnd));
  for (PetscInt k = 0; k < nids; ++k) {
    IS pts;
    PetscCall(DMLabelGetStratumIS(label, ids[k], &pts));
    if (!pts) continue;
    const PetscInt *p;
    PetscInt        n;
    PetscCall(ISGetLocalSize(pts, &n));
    PetscCall(ISGetIndices(pts, &p));
    for (PetscInt i = 0; i < n; ++i) {
      PetscReal area, c[3], nrm[3];
      if (p[i] < fStart || p[i] >= fEnd) continue;
      PetscCall(DMPlexComputeCellGeometryFVM(prob->dm, p[i], &area, c, nrm));
      if (PetscAbsReal(nrm[1]) < 1e-8 * PetscAbsReal(nrm[0])) votes[0]++;
      else if (PetscAbsReal(nrm[0]) < 1e-8 * PetscAbsReal(nrm[1])) votes[1]++;
      else bad++;
    }
    PetscCall(ISRestoreIndices(pts, &p));
    PetscCall(ISDestroy(&pts));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, votes, 2, MPIU_INT, MPI_SUM, prob->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_SUM, prob->comm));
  PetscCheck(!bad && !(votes[0] && votes[1]), prob->comm, PETSC_ERR_SUP, "Free slip is supported on straight boundaries parallel to an axis only");
  *comp = votes[0] ? 0 : 1;
  PetscFunctionReturn(0);
}

/* Does any boundary face leave its normal velocity free (traction or partial
   Dirichlet)? If none does the flow is enclosed and the pressure level is free. */
static PetscErrorCode PressureDetermined(SlumpProblem prob, PetscBool *determined)
{
  DMLabel  bnd;
  IS       faceIS;
  PetscInt fStart, fEnd, found = 0;
  PetscFunctionBeginUser;
  PetscCall(DMGetLabel(prob->dm, "boundary", &bnd));
  PetscCall(DMPlexGetHeightStratum(prob->dm, 1, &fStart, &fEnd));
  PetscCall(DMLabelGetStratumIS(bnd, 1, &faceIS));
  if (faceIS) {
    const PetscInt *faces;
    PetscInt        n;
    PetscCall(ISGetLocalSize(faceIS, &n));
    PetscCall(ISGetIndices(faceIS, &faces));
    for (PetscInt i = 0; i < n && !found; ++i) {
      PetscBool fixed[3] = {PETSC_FALSE, PETSC_FALSE, PETSC_FALSE};
      PetscReal area, c[3], nrm[3];
      PetscInt  dim;
      if (faces[i] < fStart || faces[i] >= fEnd) continue;
      PetscCall(DMGetDimension(prob->dm, &dim));
      PetscCall(DMPlexComputeCellGeometryFVM(prob->dm, faces[i], &area, c, nrm));
      for (PetscInt b = 0; b < prob->nbc; ++b) {
        DMLabel  label;
        PetscInt val;
        PetscCall(DMGetLabel(prob->dm, prob->bc[b].label, &label));
        if (!label) continue;
        PetscCall(DMLabelGetValue(label, faces[i], &val));
        if (val < 0) continue;
        if (prob->bc[b].kind == SLUMP_BC_DIRICHLET) {
          if (!prob->bc[b].ncomp)
            for (PetscInt d = 0; d < dim; ++d) fixed[d] = PETSC_TRUE;
          for (PetscInt k = 0; k < prob->bc[b].ncomp; ++k) fixed[prob->bc[b].comps[k]] = PETSC_TRUE;
        } else if (prob->bc[b].kind == SLUMP_BC_FREESLIP || prob->bc[b].kind == SLUMP_BC_FRICTION) {
          for (PetscInt d = 0; d < dim; ++d)
            if (PetscAbsReal(nrm[d]) > 1e-8 * PetscSqrtReal(area)) fixed[d] = PETSC_TRUE;
        }
      }
      for (PetscInt d = 0; d < dim; ++d)
        if (!fixed[d] && PetscAbsReal(nrm[d]) > 1e-12) found = 1;
    }
    PetscCall(ISRestoreIndices(faceIS, &faces));
    PetscCall(ISDestroy(&faceIS));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &found, 1, MPIU_INT, MPI_MAX, prob->comm));
  *determined = found ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Enclosed flow: fix the pressure at the vertex with the smallest x + y (ties:
   smallest x), to the scene's reference pressure there, or 0. */
static PetscErrorCode PinPressure(SlumpProblem prob)
{
  DM                 cdm;
  Vec                coords;
  const PetscScalar *xa;
  PetscInt           vStart, vEnd, best = -1, dim;
  PetscReal          key[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, gkey[2];
  DMLabel            label;
  const PetscInt     one = 1;
  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(prob->dm, &dim));
  PetscCall(DMPlexGetDepthStratum(prob->dm, 0, &vStart, &vEnd));
  PetscCall(DMGetCoordinateDM(prob->dm, &cdm));
  PetscCall(DMGetCoordinatesLocal(prob->dm, &coords));
  PetscCall(VecGetArrayRead(coords, &xa));
  for (PetscInt v = vStart; v < vEnd; ++v) {
    PetscSection cs;
    PetscInt     off;
    PetscCall(DMGetLocalSection(cdm, &cs));
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    PetscReal k0 = PetscRealPart(xa[off] + xa[off + 1]), k1 = PetscRealPart(xa[off]);
    if (prob->pinSet) { /* nearest to the reference point */
      k0 = PetscSqr(PetscRealPart(xa[off]) - prob->pinX[0]) + PetscSqr(PetscRealPart(xa[off + 1]) - prob->pinX[1]);
      k1 = PetscRealPart(xa[off]);
    }
    if (k0 < key[0] - 1e-12 || (PetscAbsReal(k0 - key[0]) <= 1e-12 && k1 < key[1])) {
      key[0] = k0;
      key[1] = k1;
      best   = v;
    }
  }
  PetscCall(VecRestoreArrayRead(coords, &xa));
  gkey[0] = key[0];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, gkey, 1, MPIU_REAL, MPIU_MIN, prob->comm));
  PetscCall(DMCreateLabel(prob->dm, "pressure_pin"));
  PetscCall(DMGetLabel(prob->dm, "pressure_pin", &label));
  if (best >= 0 && PetscAbsReal(key[0] - gkey[0]) <= 1e-12) PetscCall(DMLabelSetValue(label, best, 1));
  PetscCall(DMAddBoundary(prob->dm, DM_BC_ESSENTIAL, "pressure_pin", label, 1, &one, 1, 0, NULL, (void (*)(void))(prob->pex ? prob->pex : ZeroFn), NULL, prob->exctx, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode ZeroFn(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  for (PetscInt c = 0; c < Nc; ++c) u[c] = 0.0;
  return 0;
}

PetscErrorCode SlumpProblemSetPointwise(SlumpProblem prob, PetscDS ds)
{
  SlumpRheologyPointwise pw;
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyGetPointwise(prob->rheo, &pw));
  if (prob->formulation == SLUMP_FORMULATION_TRANSPORT) {
    /* the velocity is constrained everywhere: no momentum equation */
    if (prob->extraField >= 0) PetscCall(prob->extraOps.set_pointwise(prob->extraCtx, prob, ds, prob->extraField));
    PetscFunctionReturn(0);
  }
  if (prob->formulation == SLUMP_FORMULATION_ANTIPLANE) {
    PetscCheck(!(prob->effects & SLUMP_EFFECT_CONVECTION), prob->comm, PETSC_ERR_SUP, "Convection does not act on an anti-plane flow");
    PetscCall(PetscDSSetResidual(ds, 0, prob->momentumSource ? prob->momentumSource : SlumpPwSelectAntiPlaneF0(prob->effects), pw.ap_f1_u));
    PetscCall(PetscDSSetJacobian(ds, 0, 0, SlumpPwSelectAntiPlaneG0(prob->effects), NULL, NULL, pw.ap_g3_uu));
    PetscFunctionReturn(0);
  }
  {
    const PetscBool tp = prob->twoPhase;
    PetscCheck(!tp || !prob->momentumSource, prob->comm, PETSC_ERR_SUP, "A scene's own momentum source cannot be mixed by two-phase density");
    PetscCall(PetscDSSetResidual(ds, 0, prob->momentumSource ? prob->momentumSource : SlumpPwSelectMomentumF0(prob->effects, tp, prob->convForm), tp ? pw.tp_f1_u : pw.f1_u));
    PetscCall(PetscDSSetResidual(ds, 1, SlumpPwContinuityF0, NULL));
    PetscCall(PetscDSSetJacobian(ds, 0, 0, SlumpPwSelectG0(prob->effects, tp, prob->convForm), SlumpPwSelectG1(prob->effects, tp, prob->convForm), NULL, tp ? pw.tp_g3_uu : pw.g3_uu));
    PetscCall(PetscDSSetJacobian(ds, 0, 1, NULL, NULL, tp ? pw.tp_g2_up : pw.g2_up, NULL));
    PetscCall(PetscDSSetJacobian(ds, 1, 0, NULL, SlumpPwContinuityG1, NULL, NULL));
    if (prob->extraField >= 0) PetscCall(prob->extraOps.set_pointwise(prob->extraCtx, prob, ds, prob->extraField));
    /* the momentum equation's dependence on phi through rho and eta */
    if (tp) PetscCall(PetscDSSetJacobian(ds, 0, prob->extraField, SlumpPwSelectG0Phi(prob->effects, prob->convForm), SlumpPwSelectG1Phi(prob->effects, prob->convForm), pw.tp_g2_uphi, NULL));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode CreateFields(SlumpProblem prob, DM dm)
{
  PetscFE  fe[2];
  PetscInt dim;
  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(PetscFECreateLagrange(PETSC_COMM_SELF, dim, prob->formulation == SLUMP_FORMULATION_ANTIPLANE ? 1 : dim, PETSC_TRUE, prob->velocityDegree, prob->quadOrder, &fe[0]));
  PetscCall(PetscObjectSetName((PetscObject)fe[0], "velocity"));
  if (prob->formulation == SLUMP_FORMULATION_TRANSPORT) {
    PetscCheck(prob->extraField >= 0, prob->comm, PETSC_ERR_ORDER, "The transport formulation needs an extra field (a level set) to transport");
    PetscCall(DMSetField(dm, 0, NULL, (PetscObject)fe[0]));
    PetscCall(prob->extraOps.create_field(prob->extraCtx, prob, dm, 1));
    PetscCall(DMCreateDS(dm));
    PetscCall(PetscFEDestroy(&fe[0]));
    PetscFunctionReturn(0);
  }
  if (prob->formulation == SLUMP_FORMULATION_ANTIPLANE) {
    PetscCall(DMSetField(dm, 0, NULL, (PetscObject)fe[0]));
    PetscCall(DMCreateDS(dm));
    PetscCall(PetscFEDestroy(&fe[0]));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscFECreateLagrange(PETSC_COMM_SELF, dim, 1, PETSC_TRUE, prob->pressureDegree, prob->quadOrder, &fe[1]));
  PetscCall(PetscFECopyQuadrature(fe[0], fe[1]));
  PetscCall(PetscObjectSetName((PetscObject)fe[1], "pressure"));
  PetscCall(DMSetField(dm, 0, NULL, (PetscObject)fe[0]));
  PetscCall(DMSetField(dm, 1, NULL, (PetscObject)fe[1]));
  if (prob->extraField >= 0) PetscCall(prob->extraOps.create_field(prob->extraCtx, prob, dm, 2));
  PetscCall(DMCreateDS(dm));
  PetscCall(PetscFEDestroy(&fe[0]));
  PetscCall(PetscFEDestroy(&fe[1]));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetConstantsAll(SlumpProblem prob)
{
  PetscDS  ds;
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(prob->constants, SLUMP_C_NUM));
  prob->constants[SLUMP_C_RHO]     = prob->rho;
  prob->constants[SLUMP_C_GX]      = prob->g[0];
  prob->constants[SLUMP_C_GY]      = prob->g[1];
  prob->constants[SLUMP_C_JACMODE] = prob->jacmode;
  prob->constants[SLUMP_C_AXIS]    = prob->axis + 1;
  for (PetscInt i = 0; i < 4; ++i) prob->constants[SLUMP_C_SCENE + i] = prob->sceneConst[i];
  PetscCall(SlumpRheologyGetConstants(prob->rheo, &n, &prob->constants[SLUMP_C_RHEO]));
  if (prob->extraOps.set_constants) PetscCall(prob->extraOps.set_constants(prob->extraCtx, prob, &prob->constants[SLUMP_C_FIELD]));
  if (prob->twoPhase) {
    prob->constants[SLUMP_C_MIX_RHO] = prob->rhoAmbient;
    prob->constants[SLUMP_C_MIX_ETA] = prob->etaAmbient;
    prob->constants[SLUMP_C_MIX_EPS]   = prob->mixEps;
    prob->constants[SLUMP_C_MIX_SHIFT] = prob->mixShift * prob->mixEps;
    prob->constants[SLUMP_C_MIX_FILTER] = prob->mixFilter;
  }
  if (prob->wallFriction) {
    prob->constants[SLUMP_C_WALL_LAW]   = prob->wallLaw;
    prob->constants[SLUMP_C_WALL_COEFF] = prob->wallCoeff;
    prob->constants[SLUMP_C_WALL_REG]   = prob->wallReg;
  }
  /* the table itself, after SLUMP_C_NUM, is kept */
  prob->constants[SLUMP_C_SURF_N]  = prob->nsurf;
  prob->constants[SLUMP_C_SURF_X0] = prob->surfX0;
  prob->constants[SLUMP_C_SURF_DX] = prob->surfDx;
  PetscCall(DMGetDS(prob->dm, &ds));
  PetscCall(PetscDSSetConstants(ds, SLUMP_C_NUM + prob->nsurf, prob->constants));
  PetscCall(DMGetDS(prob->dmDiag, &ds));
  PetscCall(PetscDSSetConstants(ds, SLUMP_C_NUM + prob->nsurf, prob->constants));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetSurfaceHeight(SlumpProblem prob, PetscInt n, PetscReal x0, PetscReal dx, const PetscReal h[])
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 0 && n <= SLUMP_C_SURF_MAX, prob->comm, PETSC_ERR_ARG_OUTOFRANGE, "The free-surface table takes 0 to %d samples; got %" PetscInt_FMT, (int)SLUMP_C_SURF_MAX, n);
  PetscCheck(n < 2 || dx > 0, prob->comm, PETSC_ERR_ARG_OUTOFRANGE, "The free-surface table needs a positive spacing; got %g", (double)dx);
  prob->nsurf  = n;
  prob->surfX0 = x0;
  prob->surfDx = dx;
  for (PetscInt i = 0; i < n; ++i) prob->constants[SLUMP_C_NUM + i] = h[i];
  if (prob->setup) PetscCall(SlumpProblemSetConstantsAll(prob));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemUpdateConstants(SlumpProblem prob)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyCheck(prob->rheo));
  PetscCall(SlumpProblemSetConstantsAll(prob));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemSetRheologyParameter(SlumpProblem prob, const char name[], PetscReal value)
{
  PetscFunctionBeginUser;
  PetscCheck(prob->rheo, prob->comm, PETSC_ERR_ORDER, "Set a rheology before setting its parameter %s", name);
  PetscCall(SlumpRheologySetParameter(prob->rheo, name, value));
  PetscCall(SlumpProblemUpdateConstants(prob));
  PetscFunctionReturn(0);
}

static void AreaObjective(SLUMP_PW_ARGS, PetscScalar f[])
{
  f[0] = 1.0;
}

PetscErrorCode SlumpProblemSetUp(SlumpProblem prob)
{
  PetscDS ds;
  PetscFunctionBeginUser;
  PetscCheck(prob->dm, prob->comm, PETSC_ERR_ORDER, "Set a mesh before SlumpProblemSetUp()");
  if (prob->setup) PetscFunctionReturn(0);
  /* with a level set the time steps follow the interface and inertia rules
     the Schur complement (a Laplacian weighted by 1/(rho cj)): the weighted
     mass needed 500 Krylov iterations per solve on dam_break, selfp 21 */
  if (!prob->schurPreSet && prob->extraField >= 0) prob->schurPre = SLUMP_SCHUR_PRE_SELFP;
  PetscCheck(!prob->linIterative || !prob->petscAssembly || prob->formulation != SLUMP_FORMULATION_PLANE || prob->schurPre == SLUMP_SCHUR_PRE_SELFP, prob->comm, PETSC_ERR_USER_INPUT, "-stokes_schur_pre mass is assembled by our cell loop; with -assembly petsc use -stokes_schur_pre selfp");
  PetscCall(SlumpRheologyCheck(prob->rheo));
  if (prob->axis >= 0) {
    PetscInt dim;
    PetscCall(DMGetDimension(prob->dm, &dim));
    PetscCheck(dim == 2 && prob->formulation == SLUMP_FORMULATION_PLANE, prob->comm, PETSC_ERR_SUP, "The axisymmetric geometry needs a 2-D mesh and the plane (velocity-pressure) formulation");
    PetscCheck(!prob->petscAssembly, prob->comm, PETSC_ERR_USER_INPUT, "-assembly petsc is planar only; the axisymmetric geometry needs -assembly slump");
    for (PetscInt b = 0; b < prob->nbc; ++b) PetscCheck(prob->bc[b].kind != SLUMP_BC_TRACTION, prob->comm, PETSC_ERR_SUP, "Traction conditions (%s) are planar only; the axisymmetric geometry does not take them", prob->bc[b].label);
    {
      PetscReal lo[3], hi[3];
      PetscCall(DMGetBoundingBox(prob->dm, lo, hi));
      PetscCheck(lo[prob->axis] >= -1e-12 * (hi[prob->axis] - lo[prob->axis]), prob->comm, PETSC_ERR_USER_INPUT, "The axisymmetric mesh must lie in r = %s >= 0; it reaches %g", prob->axis ? "y" : "x", (double)lo[prob->axis]);
    }
  }
  if (prob->twoPhase) {
    PetscReal h;
    PetscCheck(prob->extraField >= 0 && prob->formulation == SLUMP_FORMULATION_PLANE, prob->comm, PETSC_ERR_ORDER, "Two-phase mixing needs a level set (an extra field) and the plane formulation");
    PetscCall(SlumpMeshGetMinEdgeLength(prob->dm, &h));
    prob->mixEps = prob->mixWidth * h;
  }
  PetscCall(DMClone(prob->dm, &prob->dmDiag));
  PetscCall(CreateFields(prob, prob->dm));
  PetscCall(CreateFields(prob, prob->dmDiag));
  PetscCall(DMGetDS(prob->dm, &ds));
  PetscCall(SlumpProblemSetPointwise(prob, ds));
  if (prob->formulation == SLUMP_FORMULATION_TRANSPORT) {
    /* the prescribed velocity: a condition on every point of the mesh */
    DMLabel        all;
    PetscInt       pStart, pEnd;
    const PetscInt one = 1;
    PetscCheck(prob->uPresc, prob->comm, PETSC_ERR_ORDER, "The transport formulation needs a prescribed velocity (SlumpProblemSetPrescribedVelocity)");
    PetscCall(DMCreateLabel(prob->dm, "slump_everywhere"));
    PetscCall(DMGetLabel(prob->dm, "slump_everywhere", &all));
    PetscCall(DMPlexGetChart(prob->dm, &pStart, &pEnd));
    for (PetscInt pt = pStart; pt < pEnd; ++pt) PetscCall(DMLabelSetValue(all, pt, 1));
    PetscCall(DMAddBoundary(prob->dm, DM_BC_ESSENTIAL, "prescribed_velocity", all, 1, &one, 0, 0, NULL, (void (*)(void))prob->uPresc, (void (*)(void))(prob->uPresc_t ? prob->uPresc_t : ZeroFn), prob->uPrescCtx, NULL));
    if (prob->uPresc_t) prob->bcStatic = PETSC_FALSE;
  }
  for (PetscInt b = 0; b < prob->nbc; ++b) {
    SlumpBC  *bc = &prob->bc[b];
    DMLabel   label;
    PetscInt  nids, *ids;
    PetscCall(GetLabelIds(prob, bc->label, &label, &nids, &ids));
    switch (bc->kind) {
    case SLUMP_BC_DIRICHLET:
      PetscCall(DMAddBoundary(prob->dm, DM_BC_ESSENTIAL, bc->name, label, nids, ids, 0, bc->ncomp, bc->ncomp ? bc->comps : NULL, (void (*)(void))(bc->g ? bc->g : ZeroFn), (void (*)(void))(bc->g_t ? bc->g_t : ZeroFn), bc->ctx, NULL));
      break;
    case SLUMP_BC_FREESLIP: {
      PetscInt comp;
      PetscCall(FreeSlipComponent(prob, label, nids, ids, &comp));
      PetscCall(DMAddBoundary(prob->dm, DM_BC_ESSENTIAL, bc->name, label, nids, ids, 0, 1, &comp, (void (*)(void))ZeroFn, (void (*)(void))ZeroFn, NULL, NULL));
    } break;
    case SLUMP_BC_FRICTION: {
      PetscInt      comp, bd;
      char          name[80];
      PetscWeakForm wf;
      PetscCheck(prob->formulation == SLUMP_FORMULATION_PLANE, prob->comm, PETSC_ERR_SUP, "Wall friction needs the plane formulation");
      PetscCall(FreeSlipComponent(prob, label, nids, ids, &comp));
      PetscCall(DMAddBoundary(prob->dm, DM_BC_ESSENTIAL, bc->name, label, nids, ids, 0, 1, &comp, (void (*)(void))ZeroFn, (void (*)(void))ZeroFn, NULL, NULL));
      PetscCall(PetscSNPrintf(name, sizeof(name), "%s_traction", bc->name));
      PetscCall(DMAddBoundary(prob->dm, DM_BC_NATURAL, name, label, nids, ids, 0, 0, NULL, NULL, NULL, NULL, &bd));
      PetscCall(PetscDSGetBoundary(ds, bd, &wf, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL));
      for (PetscInt k = 0; k < nids; ++k) {
        PetscCall(PetscWeakFormSetIndexBdResidual(wf, label, ids[k], 0, 0, 0, SlumpPwWallFrictionF0, 0, NULL));
        PetscCall(PetscWeakFormSetIndexBdJacobian(wf, label, ids[k], 0, 0, 0, 0, SlumpPwWallFrictionG0uu, 0, NULL, 0, NULL, 0, NULL));
        if (prob->wallLaw == SLUMP_WALL_COULOMB) PetscCall(PetscWeakFormSetIndexBdJacobian(wf, label, ids[k], 0, 1, 0, 0, SlumpPwWallFrictionG0up, 0, NULL, 0, NULL, 0, NULL));
        if (prob->twoPhase) PetscCall(PetscWeakFormSetIndexBdJacobian(wf, label, ids[k], 0, prob->extraField, 0, 0, SlumpPwWallFrictionG0uphi, 0, NULL, 0, NULL, 0, NULL));
      }
    } break;
    case SLUMP_BC_TRACTION: {
      PetscInt     bd;
      PetscWeakForm wf;
      PetscCall(DMAddBoundary(prob->dm, DM_BC_NATURAL, bc->name, label, nids, ids, 0, 0, NULL, NULL, NULL, NULL, &bd));
      PetscCall(PetscDSGetBoundary(ds, bd, &wf, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL));
      for (PetscInt k = 0; k < nids; ++k) PetscCall(PetscWeakFormSetIndexBdResidual(wf, label, ids[k], 0, 0, 0, bc->traction, 0, NULL));
    } break;
    }
    PetscCall(PetscFree(ids));
  }
  {
    PetscBool determined = PETSC_TRUE;
    if (prob->formulation == SLUMP_FORMULATION_PLANE) PetscCall(PressureDetermined(prob, &determined));
    prob->pressurePinned = determined ? PETSC_FALSE : PETSC_TRUE;
    if (prob->pressurePinned) PetscCall(PinPressure(prob));
  }
  PetscCall(SlumpProblemSetConstantsAll(prob));
  PetscCall(SlumpAssemblyCreate(prob));
  PetscCall(DMCreateLocalVector(prob->dm, &prob->locX));
  PetscCall(VecDuplicate(prob->locX, &prob->locXdot));
  PetscCall(VecDuplicate(prob->locX, &prob->locF));
  PetscCall(DMCreateGlobalVector(prob->dmDiag, &prob->diagX));
  /* static boundary values: locate the constrained local entries by inserting
     into a vector of zeros and one of ones */
  prob->bcStatic = (prob->formulation == SLUMP_FORMULATION_TRANSPORT && prob->uPresc_t) ? PETSC_FALSE : PETSC_TRUE;
  for (PetscInt b = 0; b < prob->nbc; ++b)
    if (prob->bc[b].kind == SLUMP_BC_DIRICHLET && prob->bc[b].g_t) prob->bcStatic = PETSC_FALSE;
  if (prob->bcStatic) {
    Vec                z, o;
    const PetscScalar *az, *ao;
    PetscInt           n, k = 0;
    PetscCall(VecDuplicate(prob->locX, &z));
    PetscCall(VecDuplicate(prob->locX, &o));
    PetscCall(VecZeroEntries(z));
    PetscCall(VecSet(o, 1.0));
    PetscCall(DMPlexInsertBoundaryValues(prob->dm, PETSC_TRUE, z, 0.0, NULL, NULL, NULL));
    PetscCall(DMPlexInsertBoundaryValues(prob->dm, PETSC_TRUE, o, 0.0, NULL, NULL, NULL));
    PetscCall(VecGetLocalSize(z, &n));
    PetscCall(VecGetArrayRead(z, &az));
    PetscCall(VecGetArrayRead(o, &ao));
    for (PetscInt i = 0; i < n; ++i)
      if (az[i] != 0.0 || ao[i] != 1.0) k++;
    PetscCall(PetscMalloc2(k, &prob->bcIdx, k, &prob->bcVal));
    k = 0;
    for (PetscInt i = 0; i < n; ++i)
      if (az[i] != 0.0 || ao[i] != 1.0) {
        prob->bcIdx[k]   = i;
        prob->bcVal[k++] = az[i];
      }
    prob->nbcIdx = k;
    PetscCall(VecRestoreArrayRead(z, &az));
    PetscCall(VecRestoreArrayRead(o, &ao));
    PetscCall(VecDestroy(&z));
    PetscCall(VecDestroy(&o));
  }
  {
    Vec       tmp;
    PetscInt  n1, n2;
    PetscCall(DMGetLocalVector(prob->dmDiag, &tmp));
    PetscCall(VecGetSize(tmp, &n1));
    PetscCall(VecGetSize(prob->locX, &n2));
    PetscCall(DMRestoreLocalVector(prob->dmDiag, &tmp));
    PetscCheck(n1 == n2, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Local layouts of the solution and diagnostic DMs differ");
  }
  {
    PetscPointFunc obj[1] = {AreaObjective};
    PetscCall(VecZeroEntries(prob->locX));
    PetscCall(SlumpAssembleIntegrals(prob, 0.0, prob->locX, 1, obj, &prob->area));
  }
  prob->setup = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemView(SlumpProblem prob, PetscViewer viewer)
{
  PetscInt N, Nu, nc, cStart, cEnd;
  IS       isu, isp;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetFieldIS(prob, &isu, &isp));
  PetscCall(ISGetSize(isu, &Nu));
  N = 0;
  if (isp) PetscCall(ISGetSize(isp, &N));
  PetscCall(ISDestroy(&isu));
  PetscCall(ISDestroy(&isp));
  PetscCall(DMPlexGetHeightStratum(prob->dm, 0, &cStart, &cEnd));
  nc = cEnd - cStart;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nc, 1, MPIU_INT, MPI_SUM, prob->comm));
  if (prob->formulation == SLUMP_FORMULATION_TRANSPORT) PetscCall(PetscViewerASCIIPrintf(viewer, "mesh: %" PetscInt_FMT " triangles; transport by a prescribed velocity (not an unknown)\n", nc));
  else if (prob->formulation == SLUMP_FORMULATION_ANTIPLANE) PetscCall(PetscViewerASCIIPrintf(viewer, "mesh: %" PetscInt_FMT " triangles; anti-plane P%" PetscInt_FMT " unknowns: %" PetscInt_FMT " out-of-plane velocity\n", nc, prob->velocityDegree, Nu));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "mesh: %" PetscInt_FMT " triangles; P%" PetscInt_FMT "/P%" PetscInt_FMT " unknowns: %" PetscInt_FMT " velocity, %" PetscInt_FMT " pressure\n", nc, prob->velocityDegree, prob->pressureDegree, Nu, N));
  if (prob->axis >= 0) PetscCall(PetscViewerASCIIPrintf(viewer, "geometry: axisymmetric, r = %s, axis %s = 0 (integrals per radian)\n", prob->axis ? "y" : "x", prob->axis ? "y" : "x"));
  PetscCall(PetscViewerASCIIPrintf(viewer, "effects:"));
  if (!prob->effects) PetscCall(PetscViewerASCIIPrintf(viewer, " none (steady Stokes: no differential unknowns)"));
  for (PetscInt e = 0; e < 4; ++e)
    if (prob->effects & (1 << e)) PetscCall(PetscViewerASCIIPrintf(viewer, " %s", SlumpEffectNames[e]));
  if (prob->momentumSource) PetscCall(PetscViewerASCIIPrintf(viewer, " scene_source"));
  else if (prob->effects & SLUMP_EFFECT_CONVECTION) PetscCall(PetscViewerASCIIPrintf(viewer, " (convection form: %s)", prob->convForm == SLUMP_CONVECTION_SKEW ? "skew" : (prob->convForm == SLUMP_CONVECTION_TEMAM ? "temam" : "advective")));
  PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  if (prob->pressurePinned) PetscCall(PetscViewerASCIIPrintf(viewer, "enclosed flow: pressure fixed at one vertex\n"));
  if (prob->extraField >= 0) {
    IS       isx;
    PetscInt Nx;
    PetscCall(SlumpProblemGetExtraFieldIS(prob, &isx));
    PetscCall(ISGetSize(isx, &Nx));
    PetscCall(ISDestroy(&isx));
    PetscCall(PetscViewerASCIIPrintf(viewer, "%s unknowns: %" PetscInt_FMT "\n", prob->extraOps.name ? prob->extraOps.name : "extra field", Nx));
    if (prob->extraOps.view) PetscCall(prob->extraOps.view(prob->extraCtx, prob, viewer));
  }
  PetscCall(SlumpRheologyView(prob->rheo, viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetDM(SlumpProblem prob, DM *dm)
{
  PetscFunctionBeginUser;
  *dm = prob->dm;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemCreateVector(SlumpProblem prob, Vec *X)
{
  PetscFunctionBeginUser;
  PetscCall(DMCreateGlobalVector(prob->dm, X));
  PetscCall(VecZeroEntries(*X));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemCreateMatrix(SlumpProblem prob, Mat *J)
{
  PetscFunctionBeginUser;
  PetscCall(DMSetMatType(prob->dm, MATAIJ));
  PetscCall(DMCreateMatrix(prob->dm, J));
  PetscCall(MatSetOption(*J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetFieldIS(SlumpProblem prob, IS *isu, IS *isp)
{
  IS      *is;
  PetscInt nf;
  PetscFunctionBeginUser;
  PetscCall(DMCreateFieldIS(prob->dm, &nf, NULL, &is));
  *isu = is[0];
  *isp = prob->formulation == SLUMP_FORMULATION_PLANE ? is[1] : NULL;
  for (PetscInt f = 1; f < nf; ++f)
    if (is[f] != *isp) PetscCall(ISDestroy(&is[f]));
  PetscCall(PetscFree(is));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetDifferentialMarker(SlumpProblem prob, Vec id)
{
  IS isu, isp;
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(id));
  if (prob->effects & SLUMP_EFFECT_INERTIA) {
    Vec sub;
    PetscCall(SlumpProblemGetFieldIS(prob, &isu, &isp));
    PetscCall(VecGetSubVector(id, isu, &sub));
    PetscCall(VecSet(sub, 1.0));
    PetscCall(VecRestoreSubVector(id, isu, &sub));
    PetscCall(ISDestroy(&isu));
    PetscCall(ISDestroy(&isp));
  }
  if (prob->extraField >= 0) {
    IS  isx;
    Vec sub;
    PetscCall(SlumpProblemGetExtraFieldIS(prob, &isx));
    PetscCall(VecGetSubVector(id, isx, &sub));
    PetscCall(VecSet(sub, 1.0));
    PetscCall(VecRestoreSubVector(id, isx, &sub));
    PetscCall(ISDestroy(&isx));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemProjectInitialState(SlumpProblem prob, PetscReal t, Vec X)
{
  SlumpPointFn funcs[3] = {prob->u0 ? prob->u0 : ZeroFn, prob->p0 ? prob->p0 : ZeroFn, ZeroFn};
  /* anti-plane: one field; DMProjectFunction reads funcs[0] only */
  void        *ctxs[3]  = {prob->u0ctx, prob->p0ctx, NULL};
  PetscFunctionBeginUser;
  if (prob->formulation == SLUMP_FORMULATION_TRANSPORT) {
    funcs[0] = prob->uPresc;
    ctxs[0]  = prob->uPrescCtx;
  }
  if (prob->extraField >= 0) {
    funcs[prob->extraField] = prob->extraOps.init ? prob->extraOps.init : ZeroFn;
    ctxs[prob->extraField]  = prob->extraCtx;
  }
  PetscCall(DMProjectFunction(prob->dm, t, funcs, ctxs, INSERT_ALL_VALUES, X));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetCounters(SlumpProblem prob, PetscInt *nres, PetscInt *njac)
{
  PetscFunctionBeginUser;
  if (nres) *nres = prob->nres;
  if (njac) *njac = prob->njac;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetArea(SlumpProblem prob, PetscReal *area)
{
  PetscFunctionBeginUser;
  *area = prob->area;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpKSPSetDirect(KSP ksp)
{
  PC pc;
  PetscFunctionBeginUser;
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
#if defined(PETSC_HAVE_MUMPS)
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  {
    /* MUMPS's workspace +1000 % (ICNTL(14), its default is +20 %) unless
       the user sets it: with density ratios of 1e-3 the delayed pivots
       overflow the default estimate (INFOG(1) = -9); +200 % was still short
       for column_collapse's consistent initialisation on 8e3 cells. Where
       that allocation fails (1e6 Taylor-Hood unknowns: 31 GB asked for
       2.7 GB of factors), SlumpProblemKSPSolve lowers it again */
    const char *prefix;
    char        name[256];
    PetscBool   has;
    PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%smat_mumps_icntl_14", prefix ? prefix : ""));
    PetscCall(PetscOptionsHasName(NULL, NULL, name, &has));
    if (!has) {
      PetscContainer mark; /* the value is ours: SlumpProblemKSPSolve may change it */
      PetscCall(PetscOptionsSetValue(NULL, name, "1000"));
      PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)ksp), &mark));
      PetscCall(PetscObjectCompose((PetscObject)ksp, "slump_mumps_relax_default", (PetscObject)mark));
      PetscCall(PetscContainerDestroy(&mark));
    }
  }
#endif
  PetscCall(KSPSetFromOptions(ksp));
  PetscFunctionReturn(0);
}
