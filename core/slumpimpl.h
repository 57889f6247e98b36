/* Private: the problem object. */
#pragma once

#include "slump.h"
#include "slumprheology.h"
#include "slumppointwise.h"

#define SLUMP_MAX_BC 16

typedef struct _n_SlumpAssembly *SlumpAssembly;

typedef enum { SLUMP_BC_DIRICHLET, SLUMP_BC_FREESLIP, SLUMP_BC_TRACTION, SLUMP_BC_FRICTION } SlumpBCKind;

typedef struct {
  SlumpBCKind     kind;
  char            name[64];
  char            label[64];
  PetscInt        ncomp;
  PetscInt        comps[3];
  SlumpPointFn    g, g_t;
  SlumpTractionFn traction;
  void           *ctx;
} SlumpBC;

struct _n_SlumpProblem {
  MPI_Comm      comm;
  DM            dm;       /* solution: u (P2), p (P1), Dirichlet dofs constrained out */
  DM            dmDiag;   /* same fields, no constraints: diagnostics and projections */
  PetscInt      effects;
  SlumpFormulation formulation;
  PetscInt      axis;     /* axisymmetric: the radial coordinate; -1: planar */
  PetscReal     rho, g[2], sceneConst[4];
  PetscInt      velocityDegree, pressureDegree, quadOrder;
  SlumpRheology rheo;
  PetscInt      nbc;
  SlumpBC       bc[SLUMP_MAX_BC];
  PetscPointFunc momentumSource;
  SlumpPointFn  u0, p0, uex, pex;
  void         *u0ctx, *p0ctx, *exctx;
  char          flowRateLabel[64];
  PetscBool     setup, pressurePinned;
  PetscReal     area;
  PetscScalar   constants[SLUMP_C_NUM + SLUMP_C_SURF_MAX]; /* the fixed ones, then the surface table */
  PetscInt      nsurf;
  PetscReal     surfX0, surfDx;
  PetscInt      jacmode;
  /* work */
  Vec           locX, locXdot, locF, diagX;
  /* the state at the last accepted step (SlumpProblemSetLaggedState),
     handed to the kernels as auxiliary fields; lagSet false: not yet taken */
  PetscBool     lagOn, lagSet;
  Vec           locLag;
  PetscInt      nres, njac;
  SlumpAssembly assembly;
  /* boundary values: when no condition depends on time they are projected
     once and copied into the local vectors (projection per call is costly) */
  PetscBool     bcStatic;
  PetscInt      nbcIdx, *bcIdx;
  PetscScalar  *bcVal;
  PetscBool     petscAssembly; /* -assembly petsc: PETSc's DMPlexTSCompute*FEM */
  PetscInt      convForm;      /* -convection_form: SLUMP_CONVECTION_* */
  /* transport formulation: prescribed velocity */
  SlumpPointFn  uPresc, uPresc_t;
  void         *uPrescCtx;
  /* extra field (level set): index, callbacks, context */
  PetscInt      extraField;
  SlumpExtraFieldOps extraOps;
  void         *extraCtx;
  /* two-phase mixing with the level set */
  PetscBool     twoPhase;
  PetscReal     rhoAmbient, etaAmbient, mixWidth, mixEps, mixShift;
  PetscReal     mixFilter; /* E of a filtered level set (0: a distance) */
  PetscReal     materialArea; /* of the last diagnostics pass */
  /* wall friction (SlumpProblemAddFrictionBC) */
  PetscBool     wallFriction;
  PetscReal     yieldedOverride; /* >= 0: the yielded fraction a solver measured (the exact method) */
  PetscScalar  *plasticStress;   /* the exact method's plastic stress per local quadrature point (dim x dim), or NULL */
  PetscReal    *yieldMap;        /* and its map: 1 yielded, 0 not, per local quadrature point (or NULL) */
  SlumpWallLaw  wallLaw;
  PetscReal     wallCoeff, wallReg;
  /* stress-velocity Newton (SlumpProblemSetStressVelocity): the plastic
     stress S at every (local cell, quadrature point), dualNs values each;
     used by the Jacobian between SlumpProblemDualBegin and ...End */
  PetscBool     dualWanted, dualWantedSet; /* -newton_linearisation stress_velocity (SlumpProblemSetFromOptions) */
  PetscBool     dualOn, dualInSolve, dualSaved, dualLinSet;
  PetscInt      dualNs, dualNq;
  PetscScalar  *dual, *dualSave;
  PetscBool    *dualYield, *dualYieldJ; /* yielded at the last update / at the last Jacobian */
  Vec           dualLin, locDual;
  /* pressure reference point (closed boxes) */
  PetscBool     pinSet;
  PetscReal     pinX[3];
  /* linear algebra (core/linear.c): -linear_solver iterative; for the
     velocity-pressure formulation the Schur preconditioner Sp (pressure
     mass weighted by 1 / (eta + m |K|), assembled with every Jacobian) on
     the pressure sub-DM dmP, whose closure indices pidx are cached */
  PetscBool     linIterative;
  PetscInt      schurPre;   /* SLUMP_SCHUR_PRE_* */
  PetscBool     schurPreSet; /* by the user; else mass, selfp with a level set */
  PetscBool     linForcing; /* Eisenstat-Walker tolerances in KINSOL's Newton */
  /* velocity-pressure: a Krylov solve that passes linEscalateIts iterations
     (0: never) switches every later solve of the run, first to the
     deflated velocity block (unless deflation was set by the user), on a
     second stall to an inner GMRES solve of the velocity block
     (SlumpProblemKSPSolve); linEscalated: the rungs taken, 0, 1 or 2 */
  PetscInt      linEscalateIts;
  PetscInt      linEscalated;
  PetscBool     linDeflationSet; /* -stokes_velocity_deflation given */
  KSP           linOuter, linVel; /* the last solve's KSP and its velocity block's (referenced) */
  PetscInt      linJac;        /* the Jacobian count at that solve */
  PetscReal     linDeflation;  /* -stokes_velocity_deflation: stiffness fraction of the deflated regions, 0: off */
  PetscBool     linPinCorrection; /* -stokes_schur_pin_correction: the Schur PC corrected on the constant pressure when it is pinned */
  PetscBool     linConfigured; /* a KSP has been configured (defaults set) */
  SlumpLinearFailures linFail;
  DM            dmP;
  Mat           Sp;
  PetscInt     *pidx;
  IS            isU, isP;
  /* with a level set: the flow unknowns isF and the level set isX (global
     numbering), velocity and pressure numbered within the flow block */
  IS            isF, isX, isUF, isPF;
  MatNullSpace  nearNull;
};

enum { SLUMP_SCHUR_PRE_MASS, SLUMP_SCHUR_PRE_SELFP };
PETSC_INTERN PetscErrorCode SlumpProblemLinearDestroy(SlumpProblem);
PETSC_INTERN PetscErrorCode SlumpProblemLinearSetFromOptions(SlumpProblem);
/* the viscosity-weighted pressure mass matrix (assembly.c) */
PETSC_INTERN PetscErrorCode SlumpAssembleSchurMass(SlumpProblem, PetscReal t, Vec locX, Vec locXdot, PetscReal shift, Mat Sp);

PETSC_INTERN PetscErrorCode SlumpProblemSetConstantsAll(SlumpProblem);
/* assembly.c */
PETSC_INTERN PetscErrorCode SlumpAssemblyCreate(SlumpProblem);
PETSC_INTERN PetscErrorCode SlumpAssemblyDestroy(SlumpAssembly *);
PETSC_INTERN PetscErrorCode SlumpAssembleResidual(SlumpProblem, PetscReal t, Vec locX, Vec locXdot, Vec locF);
PETSC_INTERN PetscErrorCode SlumpAssembleJacobian(SlumpProblem, PetscReal t, Vec locX, Vec locXdot, PetscReal shift, Mat J);
PETSC_INTERN PetscErrorCode SlumpAssembleJacobianWith(SlumpProblem, PetscReal t, Vec locX, Vec locXdot, PetscReal shift, PetscPointJac g[SLUMP_MAX_FIELDS][SLUMP_MAX_FIELDS][4], Mat J);
/* int over the faces labelled `label` of u . n (comp < 0), u_comp, or, if
   func is given, of func (every field's values, no gradients, at t = 0);
   length: the faces' total length */
PETSC_INTERN PetscErrorCode SlumpAssembleBoundaryIntegral(SlumpProblem, Vec locX, const char label[], PetscInt comp, PetscBdPointFunc func, PetscReal *integral, PetscReal *length);
/* S at every quadrature point: initialised from locX (locdX NULL) or
   updated with the correction locdX (SlumpDualFn of the rheology) */
PETSC_INTERN PetscErrorCode SlumpAssembleDual(SlumpProblem, PetscReal t, Vec locX, Vec locdX, PetscScalar *S, PetscBool *yielded);
PETSC_INTERN PetscErrorCode SlumpAssemblyGetSizes(SlumpProblem, PetscInt *ncell, PetscInt *nq, PetscInt *dim);
PETSC_INTERN PetscErrorCode SlumpAssembleL2Diff(SlumpProblem, PetscReal t, Vec locX, SlumpPointFn fn[2], void *ctx, PetscReal err[2]);
PETSC_INTERN PetscErrorCode SlumpAssembleIntegrals(SlumpProblem, PetscReal t, Vec locX, PetscInt n, PetscPointFunc obj[], PetscReal result[]);
/* Fill prob->locX with X and the boundary values at t. */
PETSC_INTERN PetscErrorCode SlumpProblemFillLocal(SlumpProblem, PetscReal t, Vec X);
/* Local solution with boundary values at time t, copied into dmDiag's global layout. */
PETSC_INTERN PetscErrorCode SlumpProblemFillDiagVector(SlumpProblem, PetscReal t, Vec X, Vec Xdiag);
PETSC_INTERN PetscErrorCode SlumpProblemSetPointwise(SlumpProblem, PetscDS ds);

/* core pointwise (pointwise.c) */
PETSC_INTERN PetscPointFunc SlumpPwSelectMomentumF0(PetscInt effects, PetscBool twophase, PetscInt form);
PETSC_INTERN PetscPointJac  SlumpPwSelectG0(PetscInt effects, PetscBool twophase, PetscInt form);
PETSC_INTERN PetscPointJac  SlumpPwSelectG1(PetscInt effects, PetscBool twophase, PetscInt form);
PETSC_INTERN PetscPointJac  SlumpPwSelectG0Phi(PetscInt effects, PetscInt form);
PETSC_INTERN PetscPointJac  SlumpPwSelectG1Phi(PetscInt effects, PetscInt form);
PETSC_INTERN PetscPointFunc SlumpPwSelectAntiPlaneF0(PetscInt effects);
PETSC_INTERN PetscPointJac  SlumpPwSelectAntiPlaneG0(PetscInt effects);
PETSC_INTERN void           SlumpPwWallFrictionPower(PetscInt, PetscInt, PetscInt, const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[], const PetscScalar[], const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[], const PetscScalar[], PetscReal, const PetscReal[], const PetscReal[], PetscInt, const PetscScalar[], PetscScalar[]);
PETSC_INTERN void           SlumpPwWallFrictionF0(PetscInt, PetscInt, PetscInt, const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[], const PetscScalar[], const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[], const PetscScalar[], PetscReal, const PetscReal[], const PetscReal[], PetscInt, const PetscScalar[], PetscScalar[]);
PETSC_INTERN void           SlumpPwWallFrictionG0uu(PetscInt, PetscInt, PetscInt, const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[], const PetscScalar[], const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[], const PetscScalar[], PetscReal, PetscReal, const PetscReal[], const PetscReal[], PetscInt, const PetscScalar[], PetscScalar[]);
PETSC_INTERN void           SlumpPwWallFrictionG0up(PetscInt, PetscInt, PetscInt, const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[], const PetscScalar[], const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[], const PetscScalar[], PetscReal, PetscReal, const PetscReal[], const PetscReal[], PetscInt, const PetscScalar[], PetscScalar[]);
PETSC_INTERN void           SlumpPwWallFrictionG0uphi(PetscInt, PetscInt, PetscInt, const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[], const PetscScalar[], const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[], const PetscScalar[], PetscReal, PetscReal, const PetscReal[], const PetscReal[], PetscInt, const PetscScalar[], PetscScalar[]);
PETSC_INTERN void           SlumpPwContinuityF0(SLUMP_PW_ARGS, PetscScalar f0[]);
PETSC_INTERN void           SlumpPwContinuityG1(SLUMP_PWJ_ARGS, PetscScalar g1[]);
