/* The linear algebra of every Newton step: a direct factorisation (MUMPS
 * LU, the default) or, with -linear_solver iterative, a preconditioned
 * Krylov method whose cost grows linearly with the mesh:
 *
 *   anti-plane (one scalar velocity): GMRES, right-preconditioned (its
 *     residual is the true one), with hypre BoomerAMG;
 *   velocity-pressure: FGMRES with a block upper-triangular Schur
 *     preconditioner (PCFIELDSPLIT), the velocity block by one V-cycle of
 *     BoomerAMG (strong threshold 0.7; GAMG without hypre, the rigid-body
 *     modes as its near null space), the Schur complement by the
 *     viscosity-weighted pressure mass matrix
 *     assembled with every Jacobian (SlumpAssembleSchurMass), or by PETSc's
 *     B diag(A)^-1 B^T (-stokes_schur_pre selfp).
 *
 * Every choice is a PETSc option with the KSP's prefix, set here only when
 * the user has not set it, so -ksp_type, -pc_type, -fieldsplit_u_pc_type
 * hypre ... still override. */
#include "slumpimpl.h"
#include <petscblaslapack.h>

#if defined(PETSC_HAVE_HYPRE)
  #define SLUMP_AMG PCHYPRE
#else
  #define SLUMP_AMG PCGAMG
#endif

PetscErrorCode SlumpProblemLinearSetFromOptions(SlumpProblem prob)
{
  const char *kinds[] = {"direct", "iterative"};
  const char *pres[]  = {"mass", "selfp"};
  const char *forc[]  = {"fixed", "eisenstat_walker"};
  PetscInt    k       = prob->linIterative ? 1 : 0, sp = prob->schurPre, fo = prob->linForcing ? 1 : 0;
  PetscBool   spSet   = PETSC_FALSE, set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(prob->comm, NULL, "Linear solver", "SlumpProblem");
  PetscCall(PetscOptionsEList("-linear_solver", "Linear solves: direct (MUMPS LU) or iterative (GMRES + BoomerAMG for a scalar velocity; FGMRES + Schur fieldsplit with BoomerAMG on the velocity block for velocity-pressure; with a level set, block Gauss-Seidel of the flow and the level set by ILU)", "SlumpProblemConfigureKSP", kinds, 2, kinds[k], &k, NULL));
  PetscCall(PetscOptionsEList("-stokes_schur_pre", "Schur preconditioner of -linear_solver iterative (velocity-pressure): mass (pressure mass weighted by 1/(eta + rho cj |K|); the default without a level set) or selfp (B diag(A)^-1 B^T by BoomerAMG; the default with a level set)", "SlumpProblemConfigureKSP", pres, 2, pres[sp], &sp, &spSet));
  PetscCall(PetscOptionsInt("-linear_escalate_its", "With -linear_solver iterative (velocity-pressure, plane, no level set): a Krylov solve that passes this many iterations is repeated, and every later one made, with the velocity block deflated on the rigid motions of its stiff regions (as -stokes_velocity_deflation 1e-4; skipped when that option is given), and on a second stall with an inner GMRES solve of the velocity block to 1e-2 (0: never; ignored when -fieldsplit_u_ksp_type is given)", "SlumpProblemKSPSolve", prob->linEscalateIts, &prob->linEscalateIts, NULL));
  PetscCheck(prob->linEscalateIts >= 0, prob->comm, PETSC_ERR_USER_INPUT, "-linear_escalate_its must be a non-negative number of iterations (0: never escalate); got %" PetscInt_FMT, prob->linEscalateIts);
  {
    /* the user's own velocity-block solve is not escalated (read before
       SlumpProblemConfigureKSP puts its defaults in the options database) */
    PetscBool u, fu;
    PetscCall(PetscOptionsHasName(NULL, NULL, "-fieldsplit_u_ksp_type", &u));
    PetscCall(PetscOptionsHasName(NULL, NULL, "-fieldsplit_flow_fieldsplit_u_ksp_type", &fu));
    if (!prob->linConfigured && (u || fu)) prob->linEscalateIts = 0;
  }
  PetscCall(PetscOptionsReal("-stokes_velocity_deflation", "With -linear_solver iterative (velocity-pressure, plane, no level set): precondition the velocity block by two sweeps of a coarse correction on the rigid-body modes of each connected stiff region (diagonal above this fraction of the largest; 1e-4 recommended) and a BoomerAMG V-cycle; 0: off (also as the first rung of -linear_escalate_its)", "SlumpProblemKSPSolve", prob->linDeflation, &prob->linDeflation, &set));
  if (set) prob->linDeflationSet = PETSC_TRUE;
  PetscCheck(prob->linDeflation >= 0 && prob->linDeflation < 1, prob->comm, PETSC_ERR_USER_INPUT, "-stokes_velocity_deflation must be a fraction in [0, 1) of the largest diagonal entry (0: off; 1e-4 recommended); got %g", (double)prob->linDeflation);
  PetscCall(PetscOptionsBool("-stokes_schur_pin_correction", "With -linear_solver iterative on enclosed flows (pressure fixed at one vertex; velocity-pressure, no level set): correct the Schur complement's preconditioner on the constant pressure, the pinned system's smallest mode", "SlumpProblemKSPSolve", prob->linPinCorrection, &prob->linPinCorrection, NULL));
  PetscCall(PetscOptionsEList("-linear_forcing", "Krylov tolerance of the steady Newton (KINSOL) with -linear_solver iterative: fixed (-ksp_rtol, default 1e-10) or eisenstat_walker (relative tolerance from the decrease of the residual, 1e-10 ... 1e-4); IDA's stages always solve to -ksp_rtol", "SlumpProblemConfigureKSP", forc, 2, forc[fo], &fo, NULL));
  PetscOptionsEnd();
  prob->linForcing   = fo == 1 ? PETSC_TRUE : PETSC_FALSE;
  prob->linIterative = k == 1 ? PETSC_TRUE : PETSC_FALSE;
  prob->schurPre     = sp;
  prob->schurPreSet  = (PetscBool)(prob->schurPreSet || spSet);
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetLinearForcing(SlumpProblem prob, PetscBool *ew)
{
  PetscFunctionBeginUser;
  *ew = (prob->linIterative && prob->linForcing) ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemLinearDestroy(SlumpProblem prob)
{
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&prob->Sp));
  PetscCall(DMDestroy(&prob->dmP));
  PetscCall(PetscFree(prob->pidx));
  PetscCall(ISDestroy(&prob->isU));
  PetscCall(ISDestroy(&prob->isP));
  PetscCall(ISDestroy(&prob->isF));
  PetscCall(ISDestroy(&prob->isX));
  PetscCall(ISDestroy(&prob->isUF));
  PetscCall(ISDestroy(&prob->isPF));
  PetscCall(MatNullSpaceDestroy(&prob->nearNull));
  PetscCall(KSPDestroy(&prob->linOuter));
  PetscCall(KSPDestroy(&prob->linVel));
  PetscFunctionReturn(0);
}

/* Set -<prefix>name value unless the user has. */
static PetscErrorCode SetDefault(KSP ksp, const char name[], const char value[])
{
  const char *prefix;
  char        full[256];
  PetscBool   has;
  PetscFunctionBeginUser;
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  PetscCall(PetscSNPrintf(full, sizeof(full), "-%s%s", prefix ? prefix : "", name));
  PetscCall(PetscOptionsHasName(NULL, NULL, full, &has));
  if (!has) PetscCall(PetscOptionsSetValue(NULL, full, value));
  PetscFunctionReturn(0);
}

/* The split's index sets, the velocity's rigid-body modes and the Schur
   preconditioner's matrix, made once per problem. */
static PetscErrorCode StokesSetUp(SlumpProblem prob, PetscInt schurPre)
{
  PetscInt f;
  DM       dmU;
  PetscFunctionBeginUser;
  if (!prob->isU) {
    f = 0;
    PetscCall(DMCreateSubDM(prob->dm, 1, &f, &prob->isU, &dmU));
    PetscCall(DMPlexCreateRigidBody(dmU, 0, &prob->nearNull));
    PetscCall(PetscObjectCompose((PetscObject)prob->isU, "nearnullspace", (PetscObject)prob->nearNull));
    PetscCall(DMDestroy(&dmU));
    f = 1;
    PetscCall(DMCreateSubDM(prob->dm, 1, &f, &prob->isP, &prob->dmP));
  }
  /* the consistent initialisation (selfp) may have come first */
  if (schurPre == SLUMP_SCHUR_PRE_MASS && !prob->Sp) {
    PetscCall(DMSetMatType(prob->dmP, MATAIJ));
    PetscCall(DMCreateMatrix(prob->dmP, &prob->Sp));
    PetscCall(MatSetOption(prob->Sp, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  }
  PetscFunctionReturn(0);
}

/* The positions of a's indices within b, numbered globally in the space b
   spans (each rank's part of b follows the previous ranks'). */
static PetscErrorCode EmbedGlobal(IS a, IS b, IS *ab)
{
  IS              loc;
  const PetscInt *ix;
  PetscInt        n, nb, off = 0, *gx;
  MPI_Comm        comm;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)b, &comm));
  PetscCall(ISEmbed(a, b, PETSC_TRUE, &loc));
  PetscCall(ISGetLocalSize(b, &nb));
  PetscCallMPI(MPI_Exscan(&nb, &off, 1, MPIU_INT, MPI_SUM, comm));
  {
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (!rank) off = 0; /* MPI_Exscan leaves rank 0's result undefined */
  }
  PetscCall(ISGetLocalSize(loc, &n));
  PetscCall(ISGetIndices(loc, &ix));
  PetscCall(PetscMalloc1(n, &gx));
  for (PetscInt i = 0; i < n; ++i) gx[i] = ix[i] + off;
  PetscCall(ISRestoreIndices(loc, &ix));
  PetscCall(ISDestroy(&loc));
  PetscCall(ISCreateGeneral(comm, n, gx, PETSC_OWN_POINTER, ab));
  PetscFunctionReturn(0);
}

/* With a level set: the flow block (every field but the level set) and the
   level set's unknowns; velocity and pressure numbered within the flow. */
static PetscErrorCode LevelSetSetUp(SlumpProblem prob)
{
  PetscInt flow[2] = {0, 1}, nflow = prob->formulation == SLUMP_FORMULATION_PLANE ? 2 : 1, x = prob->extraField;
  PetscFunctionBeginUser;
  if (prob->isF) PetscFunctionReturn(0);
  PetscCall(DMCreateSubDM(prob->dm, nflow, flow, &prob->isF, NULL));
  PetscCall(DMCreateSubDM(prob->dm, 1, &x, &prob->isX, NULL));
  if (prob->formulation == SLUMP_FORMULATION_PLANE) {
    PetscCall(EmbedGlobal(prob->isU, prob->isF, &prob->isUF));
    PetscCall(EmbedGlobal(prob->isP, prob->isF, &prob->isPF));
    PetscCall(PetscObjectCompose((PetscObject)prob->isUF, "nearnullspace", (PetscObject)prob->nearNull));
  }
  PetscFunctionReturn(0);
}

/* The flow's preconditioner on ksp's PC: BoomerAMG for one scalar velocity;
   the Schur fieldsplit over the velocity isU and the pressure isP (numbered
   in ksp's operator) for velocity-pressure. Defaults use ksp's prefix. */
static PetscErrorCode ConfigureFlowPC(SlumpProblem prob, PetscInt schurPre, KSP ksp, IS isU, IS isP)
{
  PC pc;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp, &pc));
  if (prob->formulation == SLUMP_FORMULATION_ANTIPLANE) {
#if defined(PETSC_HAVE_HYPRE)
    PetscCall(PCSetType(pc, PCHYPRE));
#else
    PetscCall(PCSetType(pc, PCGAMG));
#endif
    PetscFunctionReturn(0);
  }
  PetscCall(PCSetType(pc, PCFIELDSPLIT));
  PetscCall(PCFieldSplitSetIS(pc, "u", isU));
  PetscCall(PCFieldSplitSetIS(pc, "p", isP));
  PetscCall(PCFieldSplitSetType(pc, PC_COMPOSITE_SCHUR));
  PetscCall(PCFieldSplitSetSchurFactType(pc, PC_FIELDSPLIT_SCHUR_FACT_UPPER));
  if (schurPre == SLUMP_SCHUR_PRE_MASS) PetscCall(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_USER, prob->Sp));
  else PetscCall(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_SELFP, NULL));
  PetscCall(SetDefault(ksp, "fieldsplit_u_ksp_type", "preonly"));
#if defined(PETSC_HAVE_HYPRE)
  /* BoomerAMG with a strong threshold of 0.7 (the default 0.25 suits
     scalar 2-D Laplacians; measured on poiseuille with m 1e4, 36-45
     Krylov iterations per Newton step from 2e3 to 4e4 unknowns against
     88-195 with GAMG) */
  {
    const char *prefix;
    char        name[256], type[64] = "hypre";
    PetscBool   set;
    PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%sfieldsplit_u_pc_type", prefix ? prefix : ""));
    PetscCall(PetscOptionsGetString(NULL, NULL, name, type, sizeof(type), &set));
    PetscCall(SetDefault(ksp, "fieldsplit_u_pc_type", "hypre"));
    /* not with a level set: dam_break (density and viscosity ratios 1e-3,
       24k unknowns) took 28 Krylov iterations per solve with 0.7, 21 with
       BoomerAMG's default 0.25 */
    if (!strcmp(type, "hypre") && prob->extraField < 0) PetscCall(SetDefault(ksp, "fieldsplit_u_pc_hypre_boomeramg_strong_threshold", "0.7"));
  }
#else
  PetscCall(SetDefault(ksp, "fieldsplit_u_pc_type", "gamg"));
#endif
  PetscCall(SetDefault(ksp, "fieldsplit_p_ksp_type", "preonly"));
  /* the weighted mass is spectrally a diagonal; B diag(A)^-1 B^T is a
     Laplacian (weighted by 1/(rho cj + eta h^-2)) */
  PetscCall(SetDefault(ksp, "fieldsplit_p_pc_type", schurPre == SLUMP_SCHUR_PRE_MASS ? "jacobi" : SLUMP_AMG));
  PetscFunctionReturn(0);
}

/* ksp as the problem's iterative solver, with the Schur preconditioner
   schurPre (SLUMP_SCHUR_PRE_*) for velocity-pressure */
static PetscErrorCode ConfigureIterative(SlumpProblem prob, PetscInt schurPre, KSP ksp)
{
  PC pc;
  PetscFunctionBeginUser;
  PetscCheck(!prob->petscAssembly || prob->formulation != SLUMP_FORMULATION_PLANE || schurPre == SLUMP_SCHUR_PRE_SELFP, prob->comm, PETSC_ERR_USER_INPUT, "-stokes_schur_pre mass is assembled by our cell loop; with -assembly petsc use -stokes_schur_pre selfp");
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(SetDefault(ksp, "ksp_rtol", "1e-10"));
  /* no cap below PETSc's 10000: with 1000 one solve of the steady Bingham
     cavity on 128 x 128 cells (147k unknowns, m 1e4) ran out and KINSOL failed */
  PetscCall(SetDefault(ksp, "ksp_max_it", "10000"));
  if (prob->formulation == SLUMP_FORMULATION_TRANSPORT) {
    /* only the level set: cj M + advection (SUPG), nonsymmetric and
       diagonally dominant at the integrator's steps: GMRES with ILU(0)
       (block Jacobi across ranks) */
    PetscCall(KSPSetType(ksp, KSPGMRES));
    PetscCall(KSPSetPCSide(ksp, PC_RIGHT));
    PetscCall(PCSetType(pc, PCBJACOBI));
  } else if (prob->extraField >= 0) {
    /* flow and level set: block Gauss-Seidel (the flow, then the level set
       with the flow's correction), the flow by its own preconditioner, the
       level set by ILU(0); FGMRES outside */
    KSP     *sub;
    PetscInt ns;
    if (prob->formulation == SLUMP_FORMULATION_PLANE) PetscCall(StokesSetUp(prob, schurPre));
    PetscCall(LevelSetSetUp(prob));
    PetscCall(KSPSetType(ksp, KSPFGMRES));
    PetscCall(PCSetType(pc, PCFIELDSPLIT));
    PetscCall(PCFieldSplitSetType(pc, PC_COMPOSITE_MULTIPLICATIVE));
    PetscCall(PCFieldSplitSetIS(pc, "flow", prob->isF));
    PetscCall(PCFieldSplitSetIS(pc, "levelset", prob->isX));
    PetscCall(PCFieldSplitGetSubKSP(pc, &ns, &sub));
    PetscCall(ConfigureFlowPC(prob, schurPre, sub[0], prob->isUF, prob->isPF));
    {
      PC pcx;
      PetscCall(KSPGetPC(sub[1], &pcx));
      PetscCall(PCSetType(pcx, PCBJACOBI));
    }
    PetscCall(PetscFree(sub));
  } else {
    if (prob->formulation == SLUMP_FORMULATION_ANTIPLANE) {
      PetscCall(KSPSetType(ksp, KSPGMRES));
      PetscCall(KSPSetPCSide(ksp, PC_RIGHT));
    } else {
      PetscCall(StokesSetUp(prob, schurPre));
      PetscCall(KSPSetType(ksp, KSPFGMRES));
    }
    PetscCall(ConfigureFlowPC(prob, schurPre, ksp, prob->isU, prob->isP));
  }
  PetscCall(KSPGMRESSetRestart(ksp, 100));
  PetscCall(KSPSetFromOptions(ksp));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemConfigureKSP(SlumpProblem prob, KSP ksp)
{
  PetscFunctionBeginUser;
  prob->linConfigured = PETSC_TRUE;
  if (prob->linIterative) PetscCall(ConfigureIterative(prob, prob->schurPre, ksp));
  else PetscCall(SlumpKSPSetDirect(ksp));
  PetscFunctionReturn(0);
}

/* The KSP of the consistent initialisation (SlumpConsistentInitialConditions:
   the mass matrix, or [rho M, B^T; B, 0] with the pressure): LU with
   -linear_solver direct; with iterative the problem's iterative solver,
   its Schur complement preconditioned by selfp whatever -stokes_schur_pre
   says: B diag(rho M)^-1 B^T is spectrally equivalent to this Schur
   complement, the viscosity-weighted pressure mass is not. Options take
   ksp's prefix (ic_). */
PetscErrorCode SlumpProblemConfigureInitKSP(SlumpProblem prob, KSP ksp)
{
  PetscFunctionBeginUser;
  if (prob->linIterative) PetscCall(ConfigureIterative(prob, SLUMP_SCHUR_PRE_SELFP, ksp));
  else PetscCall(SlumpKSPSetDirect(ksp));
  PetscFunctionReturn(0);
}

/* The velocity block's KSP ku and the Schur complement's kp of ksp's Schur
   fieldsplit (inside the flow block with a level set), NULL if there is
   none; kp may be NULL. ksp is set up. */
static PetscErrorCode SplitKSPs(SlumpProblem prob, KSP ksp, KSP *ku, KSP *kp)
{
  PC        pc;
  PetscBool isfs;
  KSP      *sub;
  PetscInt  ns;
  PetscFunctionBeginUser;
  *ku = NULL;
  if (kp) *kp = NULL;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &isfs));
  if (!isfs) PetscFunctionReturn(0);
  PetscCall(KSPSetUp(ksp));
  PetscCall(PCFieldSplitGetSubKSP(pc, &ns, &sub));
  if (prob->extraField >= 0) {
    KSP flow = sub[0];
    PetscCall(PetscFree(sub));
    PetscCall(KSPGetPC(flow, &pc));
    PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &isfs));
    if (!isfs) PetscFunctionReturn(0);
    PetscCall(KSPSetUp(flow));
    PetscCall(PCFieldSplitGetSubKSP(pc, &ns, &sub));
  }
  *ku = sub[0];
  if (kp) *kp = sub[ns - 1];
  PetscCall(PetscFree(sub));
  PetscFunctionReturn(0);
}

/* An inner GMRES solve of the velocity block to 1e-2 instead of one
   V-cycle (FGMRES outside accepts the varying preconditioner): robust where
   the V-cycle alone stalls, at several V-cycles per outer iteration. */
static PetscErrorCode Escalate(SlumpProblem prob, KSP ksp, PetscBool *done)
{
  KSP       ku;
  KSPType   type;
  PetscBool pre;
  PetscFunctionBeginUser;
  *done = PETSC_FALSE;
  PetscCall(SplitKSPs(prob, ksp, &ku, NULL));
  if (!ku) PetscFunctionReturn(0);
  PetscCall(KSPGetType(ku, &type));
  PetscCall(PetscStrcmp(type, KSPPREONLY, &pre));
  if (!pre) PetscFunctionReturn(0);
  PetscCall(KSPSetType(ku, KSPGMRES));
  PetscCall(KSPSetTolerances(ku, 1e-2, PETSC_DEFAULT, PETSC_DEFAULT, 1000));
  PetscCall(KSPSetNormType(ku, KSP_NORM_UNPRECONDITIONED));
  PetscCall(KSPSetPCSide(ku, PC_RIGHT));
  *done = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Deflation of the stiff regions' rigid motions (-stokes_velocity_deflation
   delta). A regularised plug has a viscosity ~ tau_y m beside sheared fluid
   of viscosity ~ eta: a nearly rigid inclusion, whose rigid motions are the
   low-energy modes one V-cycle does not reduce. The velocity block's
   preconditioner is two sweeps of (a Galerkin correction in the span Z of
   the rigid-body modes restricted to each connected region whose diagonal
   exceeds delta times the largest; one BoomerAMG V-cycle). The regions are
   found anew at each Jacobian, per rank (a region cut by a partition
   boundary gives one set of modes per rank). */
typedef struct {
  SlumpProblem  prob;
  PetscInt      njac, k; /* the Jacobian count Z was built for; columns of Z */
  Vec          *Z, *AZ, t, s;
  PC            amg;
  PetscScalar  *E, *w; /* Z^T A Z, LU-factored; a k-vector */
  PetscBLASInt *piv;
} Deflation;

#define DEFLATION_MAX_REGIONS 16 /* per rank, the largest */
#define DEFLATION_MIN_DOFS    6
#define DEFLATION_RECOMMENDED 1e-4 /* delta of the escalation's first rung */

static PetscInt RootOf(PetscInt *parent, PetscInt i)
{
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i         = parent[i];
  }
  return i;
}

static PetscErrorCode DeflationFree(Deflation *c)
{
  PetscFunctionBeginUser;
  if (c->Z) PetscCall(VecDestroyVecs(c->k, &c->Z));
  if (c->AZ) PetscCall(VecDestroyVecs(c->k, &c->AZ));
  PetscCall(PetscFree3(c->E, c->w, c->piv));
  c->k = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode DeflationBuild(Deflation *c, Mat A)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)A);
  Vec                d;
  PetscReal          dmax;
  PetscInt           rs, re, n, nnv, *parent, *size, *col, nreg = 0, kloc, off = 0;
  const PetscScalar *da;
  const Vec         *nv;
  PetscBool          hasc;
  PetscFunctionBeginUser;
  PetscCall(DeflationFree(c));
  PetscCall(MatCreateVecs(A, &d, NULL));
  PetscCall(MatGetDiagonal(A, d));
  PetscCall(VecMax(d, NULL, &dmax));
  PetscCall(MatGetOwnershipRange(A, &rs, &re));
  n = re - rs;
  PetscCall(PetscMalloc3(n, &parent, n, &size, n, &col));
  PetscCall(VecGetArrayRead(d, &da));
  for (PetscInt i = 0; i < n; ++i) parent[i] = PetscRealPart(da[i]) > c->prob->linDeflation * dmax ? i : -1;
  PetscCall(VecRestoreArrayRead(d, &da));
  for (PetscInt i = 0; i < n; ++i) {
    PetscInt        nc;
    const PetscInt *cols;
    if (parent[i] < 0) continue;
    PetscCall(MatGetRow(A, rs + i, &nc, &cols, NULL));
    for (PetscInt j = 0; j < nc; ++j) {
      PetscInt q = cols[j] - rs, a, b;
      if (q < 0 || q >= n || parent[q] < 0) continue;
      a = RootOf(parent, i);
      b = RootOf(parent, q);
      if (a != b) parent[a] = b;
    }
    PetscCall(MatRestoreRow(A, rs + i, &nc, &cols, NULL));
  }
  /* the regions of at least DEFLATION_MIN_DOFS unknowns, the largest
     DEFLATION_MAX_REGIONS of them, numbered 0.. in col[root] */
  for (PetscInt i = 0; i < n; ++i) size[i] = 0, col[i] = -1;
  for (PetscInt i = 0; i < n; ++i)
    if (parent[i] >= 0) size[RootOf(parent, i)]++;
  for (PetscInt r = 0; r < DEFLATION_MAX_REGIONS; ++r) {
    PetscInt best = -1;
    for (PetscInt i = 0; i < n; ++i)
      if (parent[i] == i && col[i] < 0 && size[i] >= DEFLATION_MIN_DOFS && (best < 0 || size[i] > size[best])) best = i;
    if (best < 0) break;
    col[best] = nreg++;
  }
  PetscCall(MatNullSpaceGetVecs(c->prob->nearNull, &hasc, &nnv, &nv));
  kloc = nreg * nnv;
  PetscCallMPI(MPI_Exscan(&kloc, &off, 1, MPIU_INT, MPI_SUM, comm));
  {
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (!rank) off = 0; /* MPI_Exscan leaves the first rank's result undefined */
  }
  PetscCallMPI(MPI_Allreduce(&kloc, &c->k, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(PetscInfo(NULL, "deflation: %" PetscInt_FMT " stiff regions on this rank, %" PetscInt_FMT " vectors in all\n", nreg, c->k));
  if (c->k) {
    PetscBLASInt bk, info;
    PetscCall(VecDuplicateVecs(d, c->k, &c->Z));
    PetscCall(VecDuplicateVecs(d, c->k, &c->AZ));
    {
      PetscScalar **za;
      for (PetscInt j = 0; j < c->k; ++j) PetscCall(VecSet(c->Z[j], 0.0));
      PetscCall(VecGetArrays(c->Z, c->k, &za));
      for (PetscInt m = 0; m < nnv; ++m) {
        const PetscScalar *ra;
        PetscCall(VecGetArrayRead(nv[m], &ra));
        for (PetscInt i = 0; i < n; ++i) {
          PetscInt r;
          if (parent[i] >= 0 && col[r = RootOf(parent, i)] >= 0) za[off + col[r] * nnv + m][i] = ra[i];
        }
        PetscCall(VecRestoreArrayRead(nv[m], &ra));
      }
      PetscCall(VecRestoreArrays(c->Z, c->k, &za));
    }
    PetscCall(PetscMalloc3(c->k * c->k, &c->E, c->k, &c->w, c->k, &c->piv));
    for (PetscInt j = 0; j < c->k; ++j) {
      PetscCall(MatMult(A, c->Z[j], c->AZ[j]));
      PetscCall(VecMDot(c->AZ[j], c->k, c->Z, &c->E[j * c->k]));
    }
    PetscCall(PetscBLASIntCast(c->k, &bk));
    PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bk, &bk, c->E, &bk, c->piv, &info));
    PetscCheck(!info, comm, PETSC_ERR_LIB, "-stokes_velocity_deflation: the coarse matrix Z^T A Z is singular (LAPACK getrf %d)", (int)info);
  }
  PetscCall(VecDestroy(&d));
  PetscCall(PetscFree3(parent, size, col));
  PetscFunctionReturn(0);
}

static PetscErrorCode DeflationApply(PC pc, Vec r, Vec y)
{
  Deflation   *c;
  Mat          A;
  PetscBLASInt bk, one = 1, info;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &c));
  PetscCall(PCGetOperators(pc, &A, NULL));
  if (c->njac != c->prob->njac || !c->t) {
    PetscCall(DeflationBuild(c, A));
    PetscCall(PCSetOperators(c->amg, A, A));
    c->njac = c->prob->njac;
    if (!c->t) {
      PetscCall(VecDuplicate(r, &c->t));
      PetscCall(VecDuplicate(r, &c->s));
    }
  }
  PetscCall(PetscBLASIntCast(c->k, &bk));
  PetscCall(VecSet(y, 0.0));
  PetscCall(VecCopy(r, c->t)); /* t = r - A y */
  for (PetscInt sweep = 0; sweep < 2; ++sweep) {
    if (c->k) {
      PetscCall(VecMDot(c->t, c->k, c->Z, c->w));
      PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bk, &one, c->E, &bk, c->piv, c->w, &bk, &info));
      PetscCall(VecMAXPY(y, c->k, c->w, c->Z));
      for (PetscInt i = 0; i < c->k; ++i) c->w[i] = -c->w[i];
      PetscCall(VecMAXPY(c->t, c->k, c->w, c->AZ));
    }
    PetscCall(PCApply(c->amg, c->t, c->s));
    PetscCall(VecAXPY(y, 1.0, c->s));
    if (sweep == 0) {
      PetscCall(MatMult(A, y, c->t));
      PetscCall(VecAYPX(c->t, -1.0, r));
    }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode DeflationDestroy(PC pc)
{
  Deflation *c;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &c));
  PetscCall(DeflationFree(c));
  PetscCall(VecDestroy(&c->t));
  PetscCall(VecDestroy(&c->s));
  PetscCall(PCDestroy(&c->amg));
  PetscCall(PetscFree(c));
  PetscFunctionReturn(0);
}

/* pc made a shell (ctx, apply, setup if not NULL, destroy, name) around a
   new PC *inner of the given type, which takes pc's options prefix. */
static PetscErrorCode WrapInShell(PC pc, PCType type, void *ctx, PetscErrorCode (*apply)(PC, Vec, Vec), PetscErrorCode (*setup)(PC), PetscErrorCode (*destroy)(PC), const char name[], PC *inner)
{
  const char *prefix;
  PetscFunctionBeginUser;
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(PCCreate(PetscObjectComm((PetscObject)pc), inner));
  PetscCall(PCSetOptionsPrefix(*inner, prefix));
  PetscCall(PCSetType(*inner, type));
  PetscCall(PCSetFromOptions(*inner));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, ctx));
  if (setup) PetscCall(PCShellSetSetUp(pc, setup));
  PetscCall(PCShellSetApply(pc, apply));
  PetscCall(PCShellSetDestroy(pc, destroy));
  PetscCall(PCShellSetName(pc, name));
  PetscFunctionReturn(0);
}

/* The velocity block's PC (BoomerAMG, its options under its prefix) made the
   deflated preconditioner, unless it already is. */
static PetscErrorCode DeflationAttach(SlumpProblem prob, KSP ku, PetscBool *attached)
{
  PC          pc;
  PetscBool   hyp;
  Deflation  *c;
  PetscFunctionBeginUser;
  if (attached) *attached = PETSC_FALSE;
  PetscCall(KSPGetPC(ku, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCHYPRE, &hyp));
  if (!hyp) PetscFunctionReturn(0);
  if (attached) *attached = PETSC_TRUE;
  PetscCall(PetscNew(&c));
  c->prob = prob;
  c->njac = -1;
  PetscCall(WrapInShell(pc, PCHYPRE, c, DeflationApply, NULL, DeflationDestroy, "two sweeps of (rigid-mode deflation of the stiff regions, BoomerAMG V-cycle)", &c->amg));
  PetscFunctionReturn(0);
}

/* Enclosed flows fix the pressure at one vertex. The Schur complement S of
   the pinned system then has one eigenvalue far below the others, on a
   nearly constant pressure v (S 1 is only the pinned vertex's column,
   of size h^2 against the spectrum's O(1)), which the weighted mass does
   not see: GMRES stalls on it for a dozen iterations per solve (the
   Newtonian cavity with an exact velocity solve: 38 iterations, 12 of
   them on a plateau). The Schur complement's PC P is corrected on v,
     y = P^-1 x + v (v^T x) / (v^T S v),
   v^T S v computed once per Jacobian through the Schur complement's own
   velocity solve. Not with a level set (no scene with one is enclosed). */
typedef struct {
  PC          inner;
  Vec         v, w;
  PetscScalar sigma; /* v^T S v */
} PinCorrection;

/* at each new operator (PCSetUp calls it when the Schur complement's
   preconditioning matrix has changed) */
static PetscErrorCode PinCorrectionSetUp(PC pc)
{
  PinCorrection *c;
  Mat            S, Sp;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &c));
  PetscCall(PCGetOperators(pc, &S, &Sp));
  PetscCall(PCSetOperators(c->inner, S, Sp));
  PetscCall(PCSetUp(c->inner));
  if (!c->v) PetscCall(MatCreateVecs(Sp, &c->v, &c->w));
  PetscCall(VecSet(c->v, 1.0));
  PetscCall(MatMult(S, c->v, c->w));
  PetscCall(VecDot(c->v, c->w, &c->sigma));
  PetscFunctionReturn(0);
}

static PetscErrorCode PinCorrectionApply(PC pc, Vec x, Vec y)
{
  PinCorrection *c;
  PetscScalar    a;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &c));
  PetscCall(PCApply(c->inner, x, y));
  if (c->sigma != 0.0) {
    PetscCall(VecDot(c->v, x, &a));
    PetscCall(VecAXPY(y, a / c->sigma, c->v));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode PinCorrectionDestroy(PC pc)
{
  PinCorrection *c;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &c));
  PetscCall(PCDestroy(&c->inner));
  PetscCall(VecDestroy(&c->v));
  PetscCall(VecDestroy(&c->w));
  PetscCall(PetscFree(c));
  PetscFunctionReturn(0);
}

/* The Schur complement's PC (of its KSP kp) wrapped in the correction on
   the constant pressure, unless it already is. */
static PetscErrorCode PinCorrectionAttach(KSP kp)
{
  PC             ps;
  PetscBool      shell;
  PCType         type;
  char           tname[64];
  PinCorrection *c;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(kp, &ps));
  PetscCall(PetscObjectTypeCompare((PetscObject)ps, PCSHELL, &shell));
  if (shell) PetscFunctionReturn(0);
  PetscCall(PetscNew(&c));
  PetscCall(PCGetType(ps, &type));
  PetscCall(PetscStrncpy(tname, type, sizeof(tname))); /* type is freed when ps becomes the shell */
  PetscCall(WrapInShell(ps, tname, c, PinCorrectionApply, PinCorrectionSetUp, PinCorrectionDestroy, "the Schur preconditioner corrected on the constant pressure (pinned pressure)", &c->inner));
  PetscFunctionReturn(0);
}

/* hypre's BoomerAMG set up again on a new matrix does not free what its
   Schwarz smoothers allocated (about 9 MB per Jacobian on poiseuille 16 x 64,
   hypre 2.26): on each new Jacobian the velocity block's hypre PC is made
   anew, which frees the old hierarchy. The hierarchy is rebuilt at every new
   Jacobian anyway; iterates are unchanged. */
static PetscErrorCode FreshVelocityPC(SlumpProblem prob, KSP ksp)
{
  PC        pc;
  PetscBool hyp;
  PetscFunctionBeginUser;
  if (ksp == prob->linOuter && prob->linVel && prob->njac != prob->linJac) {
    PetscCall(KSPGetPC(prob->linVel, &pc));
    PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCHYPRE, &hyp));
    if (hyp) {
      PetscCall(PCSetType(pc, PCNONE));
      PetscCall(PCSetType(pc, PCHYPRE));
      PetscCall(PCSetFromOptions(pc));
    }
  }
  if (ksp != prob->linOuter) {
    KSP ku, kp;
    PetscCall(SplitKSPs(prob, ksp, &ku, &kp));
    PetscCall(PetscObjectReference((PetscObject)ksp));
    PetscCall(KSPDestroy(&prob->linOuter));
    prob->linOuter = ksp;
    if (ku) PetscCall(PetscObjectReference((PetscObject)ku));
    PetscCall(KSPDestroy(&prob->linVel));
    prob->linVel = ku;
    if (prob->linPinCorrection && prob->pressurePinned && prob->formulation == SLUMP_FORMULATION_PLANE && prob->extraField < 0 && kp) PetscCall(PinCorrectionAttach(kp));
  }
  if (prob->linVel && prob->linDeflation > 0 && prob->formulation == SLUMP_FORMULATION_PLANE && prob->extraField < 0) PetscCall(DeflationAttach(prob, prob->linVel, NULL));
  prob->linJac = prob->njac;
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve(KSP ksp, Vec b, Vec x, KSPConvergedReason *reason, PetscInt *its)
{
  PetscFunctionBeginUser;
  PetscCall(KSPSolve(ksp, b, x));
  PetscCall(KSPGetConvergedReason(ksp, reason));
  PetscCall(KSPGetIterationNumber(ksp, its));
  PetscFunctionReturn(0);
}

/* MUMPS's LU of a -linear_solver direct solve stopped on its workspace
   (ksp's PC failed): INFOG(1) = -8 or -9, too small: the relaxation
   ICNTL(14) raised 4-fold; -13, its allocation failed: lowered 10-fold,
   down to MUMPS's own +20 % (our +1000 % asked 31 GB for the 2.7 GB of
   factors of poiseuille on 1.0e6 unknowns). Only where the value is ours
   (SlumpKSPSetDirect's default), kept for the later factorisations under
   ksp's prefix. retry: factorise again (the PC is reset); what: why it
   failed, the end of a sentence, whatever ksp's PC. */
static PetscErrorCode DirectFailure(KSP ksp, KSPConvergedReason reason, char what[], size_t len, PetscBool *retry)
{
  PC        pc;
  PetscBool lu;
  PetscFunctionBeginUser;
  *retry = PETSC_FALSE;
  PetscCall(PetscSNPrintf(what, len, "the direct solve failed (%s)", KSPConvergedReasons[reason]));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &lu));
  if (!lu) PetscFunctionReturn(0);
#if defined(PETSC_HAVE_MUMPS)
  {
    Mat           F, A, P;
    MatSolverType type;
    PetscBool     mumps;
    PetscInt      info1, info2, relax, next = -1;
    PetscObject   ours;
    const char   *prefix;
    char          name[256], value[32], icntl23[256];
    PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%smat_mumps_icntl_14", prefix ? prefix : ""));
    PetscCall(PetscSNPrintf(icntl23, sizeof(icntl23), "-%smat_mumps_icntl_23", prefix ? prefix : ""));
    PetscCall(PCFactorGetMatrix(pc, &F));
    PetscCall(MatFactorGetSolverType(F, &type));
    PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
    if (!mumps) PetscFunctionReturn(0);
    PetscCall(MatMumpsGetInfog(F, 1, &info1));
    PetscCall(MatMumpsGetInfog(F, 2, &info2));
    PetscCall(MatMumpsGetIcntl(F, 14, &relax));
    PetscCall(PetscObjectQuery((PetscObject)ksp, "slump_mumps_relax_default", &ours));
    if (info1 == -13) {
      /* INFOG(2): the size asked, in entries (in millions if negative) */
      const double gb = (info2 < 0 ? -1e6 * info2 : (double)info2) * sizeof(PetscScalar) / 1e9;
      PetscCall(PetscSNPrintf(what, len, "the LU factorisation (MUMPS) could not allocate its workspace of %.1f GB (INFOG(1) = -13 with %s %" PetscInt_FMT "); use -linear_solver iterative (see docs/performance.md), more ranks or a coarser mesh", gb, name, relax));
      if (ours && relax > 20) next = PetscMax(20, relax / 10);
    } else if (info1 == -8 || info1 == -9) {
      PetscCall(PetscSNPrintf(what, len, "the LU factorisation (MUMPS) ran out of workspace (INFOG(1) = %" PetscInt_FMT " with %s %" PetscInt_FMT "); raise %s or use -linear_solver iterative", info1, name, relax, name));
      if (ours && relax < 100000) next = PetscMin(100000, 4 * relax);
    } else if (info1 == -19) {
      PetscCall(PetscSNPrintf(what, len, "the LU factorisation (MUMPS) needs more memory than %s allows (INFOG(1) = -19)", icntl23));
    } else if (info1 == -10) {
      PetscCall(PetscSNPrintf(what, len, "the LU factorisation (MUMPS) found the matrix numerically singular (INFOG(1) = -10)"));
    } else {
      PetscCall(PetscSNPrintf(what, len, "the LU factorisation (MUMPS) failed with INFOG(1) = %" PetscInt_FMT ", INFOG(2) = %" PetscInt_FMT " (the codes are in MUMPS's manual)", info1, info2));
    }
    if (next < 0) PetscFunctionReturn(0);
    PetscCall(PetscSNPrintf(value, sizeof(value), "%" PetscInt_FMT, next));
    PetscCall(PetscOptionsSetValue(NULL, name, value));
    PetscCall(PetscPrintf(PetscObjectComm((PetscObject)ksp), "linear: MUMPS's LU %s (INFOG(1) = %" PetscInt_FMT "); factorising again with its workspace relaxed by %" PetscInt_FMT " %% instead of %" PetscInt_FMT " %% (%s)\n", info1 == -13 ? "could not allocate its workspace" : "ran out of workspace", info1, next, relax, name));
    /* a new factorisation: the PC forgets its factors, the KSP keeps its operators */
    PetscCall(KSPGetOperators(ksp, &A, &P));
    PetscCall(PetscObjectReference((PetscObject)A));
    PetscCall(PetscObjectReference((PetscObject)P));
    PetscCall(PCReset(pc));
    PetscCall(KSPSetOperators(ksp, A, P));
    PetscCall(MatDestroy(&A));
    PetscCall(MatDestroy(&P));
    *retry = PETSC_TRUE;
  }
#endif
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpKSPSolveDirect(KSP ksp, Vec b, Vec x, KSPConvergedReason *reason, char what[], size_t len)
{
  PetscBool retry = PETSC_TRUE;
  PetscFunctionBeginUser;
  what[0] = 0;
  for (PetscInt k = 0; retry && k < 4; ++k) {
    PetscCall(KSPSolve(ksp, b, x));
    PetscCall(KSPGetConvergedReason(ksp, reason));
    retry = PETSC_FALSE;
    if (*reason == KSP_DIVERGED_PC_FAILED) PetscCall(DirectFailure(ksp, *reason, what, len, &retry));
  }
  if (*reason > 0) what[0] = 0;
  else if (!what[0]) PetscCall(PetscSNPrintf(what, len, "the direct solve failed (%s)", KSPConvergedReasons[*reason]));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemKSPSolve(SlumpProblem prob, KSP ksp, Vec b, Vec x, KSPConvergedReason *reason, PetscInt *its)
{
  PetscInt  maxit, its1 = 0;
  PetscReal rtol, abstol, dtol;
  /* not with a level set: on bingham_dam_break the velocity block is not
     what stalls, and after the switch the solves took 3000 to > 10000
     iterations instead of ~1300 */
  PetscBool can = (PetscBool)(prob->linIterative && prob->formulation == SLUMP_FORMULATION_PLANE && prob->extraField < 0 && prob->linEscalateIts > 0), done;
  PetscFunctionBeginUser;
  if (prob->linIterative) PetscCall(FreshVelocityPC(prob, ksp));
  if (can && prob->linEscalated == 2) PetscCall(Escalate(prob, ksp, &done)); /* a KSP not yet switched */
  if (!prob->linIterative) {
    char what[sizeof(prob->linFail.what)];
    PetscCall(SlumpKSPSolveDirect(ksp, b, x, reason, what, sizeof(what)));
    PetscCall(KSPGetIterationNumber(ksp, its));
    if (*reason <= 0) {
      prob->linFail.n++;
      prob->linFail.its    = *its;
      prob->linFail.reason = *reason;
      prob->linFail.direct = PETSC_TRUE;
      PetscCall(PetscStrncpy(prob->linFail.what, what, sizeof(prob->linFail.what)));
    }
    PetscFunctionReturn(0);
  }
  if (!can || prob->linEscalated == 2) PetscCall(Solve(ksp, b, x, reason, its));
  else {
    PetscCall(KSPGetTolerances(ksp, &rtol, &abstol, &dtol, &maxit));
    PetscCall(KSPSetTolerances(ksp, rtol, abstol, dtol, PetscMin(maxit, prob->linEscalateIts)));
    PetscCall(Solve(ksp, b, x, reason, its));
    /* first rung: the plugs' rigid motions deflated (two V-cycles per
       application), unless the user chose the deflation */
    if (*reason <= 0 && prob->linEscalated == 0) {
      done               = PETSC_FALSE;
      prob->linEscalated = 1; /* the first rung is tried once */
      if (!prob->linDeflationSet && prob->linVel) PetscCall(DeflationAttach(prob, prob->linVel, &done));
      if (done) {
        prob->linDeflation = DEFLATION_RECOMMENDED;
        PetscCall(PetscPrintf(prob->comm, "linear: a Krylov solve stopped (%s after %" PetscInt_FMT " iterations); from now on the velocity block is deflated on the rigid motions of its stiff regions (-stokes_velocity_deflation %g; -linear_escalate_its)\n", KSPConvergedReasons[*reason], *its, DEFLATION_RECOMMENDED));
        its1 = *its;
        PetscCall(Solve(ksp, b, x, reason, its));
        *its += its1;
      }
    }
    PetscCall(KSPSetTolerances(ksp, rtol, abstol, dtol, maxit));
    if (*reason <= 0) PetscCall(Escalate(prob, ksp, &done));
    if (*reason <= 0 && done) {
      PetscInt its2 = *its - its1;
      prob->linEscalated = 2;
      its1               = *its;
      PetscCall(PetscPrintf(prob->comm, "linear: a Krylov solve stopped (%s after %" PetscInt_FMT " iterations); from now on the velocity block is solved by GMRES to 1e-2 in each application (-linear_escalate_its)\n", KSPConvergedReasons[*reason], its2));
      PetscCall(Solve(ksp, b, x, reason, its));
      *its += its1;
    }
  }
  if (*reason <= 0) {
    prob->linFail.n++;
    prob->linFail.its    = *its - its1;
    prob->linFail.reason = *reason;
    prob->linFail.direct = PETSC_FALSE;
    prob->linFail.what[0] = 0;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemGetLinearFailures(SlumpProblem prob, SlumpLinearFailures *f)
{
  PetscFunctionBeginUser;
  *f = prob->linFail;
  PetscFunctionReturn(0);
}
