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

PetscErrorCode SlumpProblemLinearSetFromOptions(SlumpProblem prob)
{
  const char *kinds[] = {"direct", "iterative"};
  const char *pres[]  = {"mass", "selfp"};
  const char *forc[]  = {"fixed", "eisenstat_walker"};
  PetscInt    k       = prob->linIterative ? 1 : 0, sp = prob->schurPre, fo = prob->linForcing ? 1 : 0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(prob->comm, NULL, "Linear solver", "SlumpProblem");
  PetscCall(PetscOptionsEList("-linear_solver", "Linear solves: direct (MUMPS LU) or iterative (GMRES + BoomerAMG for a scalar velocity; FGMRES + Schur fieldsplit with BoomerAMG on the velocity block for velocity-pressure)", "SlumpProblemConfigureKSP", kinds, 2, kinds[k], &k, NULL));
  PetscCall(PetscOptionsEList("-stokes_schur_pre", "Schur preconditioner of -linear_solver iterative (velocity-pressure): mass (pressure mass weighted by 1/(eta + rho cj |K|)) or selfp (B diag(A)^-1 B^T)", "SlumpProblemConfigureKSP", pres, 2, pres[sp], &sp, NULL));
  PetscCall(PetscOptionsEList("-linear_forcing", "Krylov tolerance of the steady Newton (KINSOL) with -linear_solver iterative: fixed (-ksp_rtol, default 1e-10) or eisenstat_walker (relative tolerance from the decrease of the residual, 1e-10 ... 1e-4); IDA's stages always solve to -ksp_rtol", "SlumpProblemConfigureKSP", forc, 2, forc[fo], &fo, NULL));
  PetscOptionsEnd();
  prob->linForcing   = fo == 1 ? PETSC_TRUE : PETSC_FALSE;
  prob->linIterative = k == 1 ? PETSC_TRUE : PETSC_FALSE;
  prob->schurPre     = sp;
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
  PetscCall(MatNullSpaceDestroy(&prob->nearNull));
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
static PetscErrorCode StokesSetUp(SlumpProblem prob)
{
  PetscInt f;
  DM       dmU;
  PetscFunctionBeginUser;
  if (prob->isU) PetscFunctionReturn(0);
  f = 0;
  PetscCall(DMCreateSubDM(prob->dm, 1, &f, &prob->isU, &dmU));
  PetscCall(DMPlexCreateRigidBody(dmU, 0, &prob->nearNull));
  PetscCall(PetscObjectCompose((PetscObject)prob->isU, "nearnullspace", (PetscObject)prob->nearNull));
  PetscCall(DMDestroy(&dmU));
  f = 1;
  PetscCall(DMCreateSubDM(prob->dm, 1, &f, &prob->isP, &prob->dmP));
  if (prob->schurPre == SLUMP_SCHUR_PRE_MASS) {
    PetscCall(DMSetMatType(prob->dmP, MATAIJ));
    PetscCall(DMCreateMatrix(prob->dmP, &prob->Sp));
    PetscCall(MatSetOption(prob->Sp, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpProblemConfigureKSP(SlumpProblem prob, KSP ksp)
{
  PC pc;
  PetscFunctionBeginUser;
  if (!prob->linIterative) {
    PetscCall(SlumpKSPSetDirect(ksp));
    PetscFunctionReturn(0);
  }
  PetscCheck(prob->extraField < 0 && prob->formulation != SLUMP_FORMULATION_TRANSPORT, prob->comm, PETSC_ERR_USER_INPUT, "-linear_solver iterative is for the single-phase velocity-pressure and anti-plane scenes; scenes with a level set need -linear_solver direct");
  PetscCheck(!prob->petscAssembly || prob->formulation != SLUMP_FORMULATION_PLANE || prob->schurPre == SLUMP_SCHUR_PRE_SELFP, prob->comm, PETSC_ERR_USER_INPUT, "-stokes_schur_pre mass is assembled by our cell loop; with -assembly petsc use -stokes_schur_pre selfp");
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(SetDefault(ksp, "ksp_rtol", "1e-10"));
  /* no cap below PETSc's 10000: with 1000 one solve of the steady Bingham
     cavity on 128 x 128 cells (147k unknowns, m 1e4) ran out and KINSOL failed */
  PetscCall(SetDefault(ksp, "ksp_max_it", "10000"));
  if (prob->formulation == SLUMP_FORMULATION_ANTIPLANE) {
    PetscCall(KSPSetType(ksp, KSPGMRES));
    PetscCall(KSPSetPCSide(ksp, PC_RIGHT));
    PetscCall(KSPGMRESSetRestart(ksp, 100));
#if defined(PETSC_HAVE_HYPRE)
    PetscCall(PCSetType(pc, PCHYPRE));
#else
    PetscCall(PCSetType(pc, PCGAMG));
#endif
  } else {
    PetscCall(StokesSetUp(prob));
    PetscCall(KSPSetType(ksp, KSPFGMRES));
    PetscCall(KSPGMRESSetRestart(ksp, 100));
    PetscCall(PCSetType(pc, PCFIELDSPLIT));
    PetscCall(PCFieldSplitSetIS(pc, "u", prob->isU));
    PetscCall(PCFieldSplitSetIS(pc, "p", prob->isP));
    PetscCall(PCFieldSplitSetType(pc, PC_COMPOSITE_SCHUR));
    PetscCall(PCFieldSplitSetSchurFactType(pc, PC_FIELDSPLIT_SCHUR_FACT_UPPER));
    if (prob->schurPre == SLUMP_SCHUR_PRE_MASS) PetscCall(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_USER, prob->Sp));
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
      if (!strcmp(type, "hypre")) PetscCall(SetDefault(ksp, "fieldsplit_u_pc_hypre_boomeramg_strong_threshold", "0.7"));
    }
#else
    PetscCall(SetDefault(ksp, "fieldsplit_u_pc_type", "gamg"));
#endif
    PetscCall(SetDefault(ksp, "fieldsplit_p_ksp_type", "preonly"));
    PetscCall(SetDefault(ksp, "fieldsplit_p_pc_type", "jacobi"));
  }
  PetscCall(KSPSetFromOptions(ksp));
  PetscFunctionReturn(0);
}
