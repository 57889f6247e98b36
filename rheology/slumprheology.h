/* slump rheology: constitutive models as pluggable, registered callbacks.
 *
 * A model maps the shear-rate magnitude ||gdot|| = sqrt(1/2 gdot:gdot),
 * gdot = grad u + grad u^T, and the pressure p to an effective viscosity
 * eta_eff (tau = eta_eff gdot), returning d eta/d||gdot|| and d eta/dp so the
 * Newton Jacobian is exact, and its yield stress (for yielded/unyielded
 * diagnostics). Parameters are named, read from options, checked, and may
 * change between solves (continuation, sweeps) without rebuilding anything. */
#pragma once

#include "slump.h"

typedef const char *SlumpRheologyType;
#define SLUMP_RHEOLOGY_NEWTONIAN      "newtonian"
#define SLUMP_RHEOLOGY_PAPANASTASIOU  "papanastasiou"
#define SLUMP_RHEOLOGY_BERCOVIER      "bercovier"
#define SLUMP_RHEOLOGY_BINGHAM_SIMPLE "bingham_simple"

/* One point: params[] are the model's parameters in declaration order; x the
   position (lithostatic yield stress). */
typedef void (*SlumpViscosityKernel)(const PetscScalar params[], PetscReal gdot, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *deta_dgdot, PetscReal *deta_dp, PetscReal *yield_stress);

/* The plastic part of a yield-stress law, for the stress-velocity Newton
   (-newton_linearisation stress_velocity, timeint/). A yield-stress model
   writes its viscosity as
     eta(g, p, x) = eta_rest(g, p) + tau_y(p, x) R(g),
   where R is the regularised 1/||gdot|| of its yield term (Papanastasiou
   (1 - exp(-m g))/g, Bercovier-Engelman 1/sqrt(g^2 + eps^2), simple
   1/(g + eps), ...) and tau_y its yield stress (tau0, mu P, the lithostatic
   mu rho g depth ...). The plastic kernel returns tau_y, R and dR/dg at
   (g, p, x), in the same parameter layout as the viscosity kernel; the rest
   of the law is linearised as before. With it the Newton linearisation keeps
   the plastic stress S (||S|| <= tau_y) as an independent variable at every
   quadrature point: the tangent's plastic rank-one term tau_y R'(g)/g
   gdot (x) gdot becomes R'/(R g) sym(S (x) gdot), bounded whatever the
   regularisation, and S is updated from the linearised law after each
   Newton correction (slumppointwise.h, SlumpPwDualUpdate). A model without a
   plastic kernel (NULL: Newtonian) is linearised with the primal tangent. */
typedef void (*SlumpPlasticKernel)(const PetscScalar params[], PetscReal gdot, PetscReal p, const PetscReal x[], PetscReal *tau_y, PetscReal *R, PetscReal *dR);
/* Whether the model has a plastic kernel (the stress-velocity Newton applies). */
PETSC_EXTERN PetscErrorCode SlumpRheologyHasPlasticPart(SlumpRheology rheo, PetscBool *has);
/* Host-side plastic part at (gdot, p, x) (tests). */
PETSC_EXTERN PetscErrorCode SlumpRheologyEvaluatePlastic(SlumpRheology rheo, PetscReal gdot, PetscReal p, const PetscReal x[], PetscReal *tau_y, PetscReal *R, PetscReal *dR);

/* One step of the dual variable at a quadrature point (stress-velocity
   Newton): u, u_x at the linearisation point, du, du_x the Newton correction
   (NULL: initialise S consistently with u), S[dim*dim] (plane; dim in the
   anti-plane formulation) updated in place. Returns whether the point is
   yielded (eta ||gdot|| > tau_y) at u + du: the Newton refreshes its
   Jacobian when the yielded set changes. */
typedef PetscBool (*SlumpDualFn)(PetscInt dim, PetscInt Nf, const PetscInt uOff[], const PetscInt uOff_x[], const PetscScalar u[], const PetscScalar u_x[], const PetscScalar du[], const PetscScalar du_x[], const PetscReal x[], const PetscScalar constants[], PetscScalar S[]);

PETSC_EXTERN PetscErrorCode SlumpRheologyCreate(MPI_Comm comm, SlumpRheology *rheo);
PETSC_EXTERN PetscErrorCode SlumpRheologyDestroy(SlumpRheology *rheo);
PETSC_EXTERN PetscErrorCode SlumpRheologySetType(SlumpRheology rheo, SlumpRheologyType type);
PETSC_EXTERN PetscErrorCode SlumpRheologyGetType(SlumpRheology rheo, SlumpRheologyType *type);
PETSC_EXTERN PetscErrorCode SlumpRheologySetFromOptions(SlumpRheology rheo);
PETSC_EXTERN PetscErrorCode SlumpRheologyView(SlumpRheology rheo, PetscViewer viewer);
PETSC_EXTERN PetscErrorCode SlumpRheologyRegister(const char name[], PetscErrorCode (*create)(SlumpRheology));
PETSC_EXTERN PetscErrorCode SlumpRheologyRegisterAll(void);
PETSC_EXTERN PetscErrorCode SlumpRheologyListTypes(MPI_Comm comm, char list[], size_t len);

/* Named parameters ("viscosity", "yield_stress", "m", "eps", ...). */
PETSC_EXTERN PetscErrorCode SlumpRheologySetParameter(SlumpRheology rheo, const char name[], PetscReal value);
PETSC_EXTERN PetscErrorCode SlumpRheologyGetParameter(SlumpRheology rheo, const char name[], PetscReal *value);
PETSC_EXTERN PetscErrorCode SlumpRheologyHasParameter(SlumpRheology rheo, const char name[], PetscBool *has);
/* Check every parameter against its bounds; one clear sentence if invalid. */
/* dst takes src's type and every parameter value. */
PETSC_EXTERN PetscErrorCode SlumpRheologyCopy(SlumpRheology src, SlumpRheology dst);
PETSC_EXTERN PetscErrorCode SlumpRheologyCheck(SlumpRheology rheo);
/* Packed parameters for the pointwise kernels' constants. */
PETSC_EXTERN PetscErrorCode SlumpRheologyGetConstants(SlumpRheology rheo, PetscInt *n, PetscScalar params[]);

/* Host-side evaluation (tests, diagnostics). */
PETSC_EXTERN PetscErrorCode SlumpRheologyEvaluate(SlumpRheology rheo, PetscReal gdot, PetscReal p, PetscReal *eta, PetscReal *deta_dgdot, PetscReal *deta_dp);
/* The same at a position x[dim] (models whose law depends on position). */
PETSC_EXTERN PetscErrorCode SlumpRheologyEvaluateAt(SlumpRheology rheo, PetscReal gdot, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *deta_dgdot, PetscReal *deta_dp, PetscReal *yield_stress);
PETSC_EXTERN PetscErrorCode SlumpRheologyGetYieldStress(SlumpRheology rheo, PetscReal p, PetscReal *tau_y);
/* Viscosity of the (regularised) unyielded material, ||gdot|| -> 0. */
PETSC_EXTERN PetscErrorCode SlumpRheologyGetPlugViscosity(SlumpRheology rheo, PetscReal p, PetscReal *eta_plug);

/* The regularisation parameter (if any), for continuation: name, value, and
   whether larger values are stiffer (m) or softer (eps). */
PETSC_EXTERN PetscErrorCode SlumpRheologyGetRegularisation(SlumpRheology rheo, const char **name, PetscReal *value, PetscBool *stiffer_when_larger);

/* Pointwise residual/Jacobian kernels of this model (see slumppointwise.h). */
typedef struct {
  PetscPointFunc f1_u;        /* tau(u, p) - p I                    */
  PetscPointJac  g2_up;       /* d f1_u / d p                       */
  PetscPointJac  g3_uu;       /* d f1_u / d grad u                  */
  PetscPointFunc eta;         /* effective viscosity (projection)   */
  PetscPointFunc shear_rate;  /* ||gdot|| (projection)              */
  PetscPointFunc diss_yield;  /* objective pair, see diagnostics.c  */
  PetscPointFunc yielded;     /* 1 where ||tau|| > tau_y            */
  PetscPointFunc ap_f1_u;     /* anti-plane: eta grad w             */
  PetscPointJac  ap_g3_uu;    /* anti-plane: d f1 / d grad w        */
  /* two-phase (SlumpProblemSetTwoPhase): mixed with the ambient fluid by the
     level set, the last field */
  PetscPointFunc tp_f1_u;
  PetscPointJac  tp_g2_up;
  PetscPointJac  tp_g3_uu;
  PetscPointJac  tp_g2_uphi;  /* d f1_u / d phi                     */
  PetscPointFunc tp_eta;      /* mixed viscosity                    */
  PetscPointFunc tp_diss;     /* material dissipation m eta ||gdot||^2 */
  PetscPointFunc tp_yielded;  /* material fraction where yielded    */
  /* stress-velocity Newton: the g3 kernels above take the plastic stress S
     at the quadrature point through their a_t argument (the assembly's
     aux time derivative, otherwise unused; NULL: the primal tangent) */
  SlumpDualFn    dual;        /* S update (S = 0 without a plastic kernel) */
} SlumpRheologyPointwise;
PETSC_EXTERN PetscErrorCode SlumpRheologyGetPointwise(SlumpRheology rheo, SlumpRheologyPointwise *pw);
