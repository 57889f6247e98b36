/* slump: viscoplastic and dense granular flows that slow down and stop.
 *
 * Public interface of the core: mesh, fields, effects, boundary conditions,
 * the semi-discrete residual F(t, y, y') and its Jacobian, diagnostics and
 * outputs. Rheology (slumprheology.h), time integration (slumptimeint.h) and
 * scenes (slumpscene.h) build on it. */
#pragma once

#include <petscdmplex.h>
#include <petscds.h>
#include <petscksp.h>

#define SLUMP_VERSION_STRING "0.1.0"

typedef struct _p_SlumpRheology *SlumpRheology;
typedef struct _n_SlumpProblem  *SlumpProblem;

/* ------------------------------------------------------------------ mesh */
/* Rectangle [x0,x1] x [y0,y1], nx x ny squares each cut into two triangles.
   Boundary faces carry the labels "bottom", "right", "top", "left" (value 1)
   and "boundary". On more than one rank the cells are partitioned with METIS
   (-petscpartitioner_type overrides). */
PETSC_EXTERN PetscErrorCode SlumpMeshCreateRectangle(MPI_Comm comm, PetscInt nx, PetscInt ny, const PetscReal lower[2], const PetscReal upper[2], DM *dm);
/* Gmsh .msh file; physical names become labels. Distributed like the rectangle. */
PETSC_EXTERN PetscErrorCode SlumpMeshCreateGmsh(MPI_Comm comm, const char filename[], DM *dm);
/* Partition a mesh held on rank 0 with METIS (k-way on the cell dual graph) and distribute it. */
PETSC_EXTERN PetscErrorCode SlumpMeshDistribute(DM *dm);
/* Smallest edge length over the mesh (collective). */
PETSC_EXTERN PetscErrorCode SlumpMeshGetMinEdgeLength(DM dm, PetscReal *hmin);

/* --------------------------------------------------------------- effects */
/* Each physical effect is switched on by the scene. What is off is neither
   assembled nor stored. Without SLUMP_EFFECT_INERTIA there is no time
   derivative and every unknown is algebraic. */
typedef enum {
  SLUMP_EFFECT_INERTIA    = 1 << 0, /* rho du/dt                          */
  SLUMP_EFFECT_CONVECTION = 1 << 1, /* rho u . grad u (needs inertia)     */
  SLUMP_EFFECT_BODY_FORCE = 1 << 2, /* rho g, or an imposed pressure gradient */
  SLUMP_EFFECT_FREE_SURFACE = 1 << 3 /* a level set phi in the state (interface/) */
} SlumpEffect;
PETSC_EXTERN const char *const SlumpEffectNames[];

/* Point function, PETSc's simple form: u[Nc] = f(t, x). */
typedef PetscErrorCode (*SlumpPointFn)(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx);
/* Boundary pointwise term f0 = -traction (PETSc's PetscBdPointFunc: it
   receives x and the outward normal n, and the kernels' constants). */
typedef PetscBdPointFunc SlumpTractionFn;

/* Constants shared by every pointwise kernel (PetscDSSetConstants). The
   rheology's parameters follow from SLUMP_C_RHEO on. */
enum {
  SLUMP_C_RHO     = 0, /* density                                        */
  SLUMP_C_GX      = 1, /* body force per unit mass, x                    */
  SLUMP_C_GY      = 2, /* body force per unit mass, y                    */
  SLUMP_C_JACMODE = 3, /* 0: full Jacobian; 1: [rho M, B^T; B, 0] only    */
  SLUMP_C_SCENE   = 4, /* four values a scene's own kernels may use       */
  SLUMP_C_RHEO    = 8, /* first rheology parameter                       */
  SLUMP_C_RHEO_MAX = 16,
  SLUMP_C_FIELD   = SLUMP_C_RHEO + SLUMP_C_RHEO_MAX, /* six values of the extra field (level set) */
  SLUMP_C_FIELD_MAX = 6,
  SLUMP_C_MIX_RHO = SLUMP_C_FIELD + SLUMP_C_FIELD_MAX, /* two-phase: ambient density          */
  SLUMP_C_MIX_ETA = SLUMP_C_MIX_RHO + 1,               /* two-phase: ambient viscosity        */
  SLUMP_C_MIX_EPS = SLUMP_C_MIX_RHO + 2,               /* two-phase: Heaviside half-width     */
  SLUMP_C_WALL_LAW   = SLUMP_C_MIX_RHO + 3, /* wall friction: 0 Navier, 1 Coulomb          */
  SLUMP_C_WALL_COEFF = SLUMP_C_MIX_RHO + 4, /* wall friction: beta or mu_w                 */
  SLUMP_C_WALL_REG   = SLUMP_C_MIX_RHO + 5, /* wall friction: Coulomb velocity scale delta */
  SLUMP_C_MIX_SHIFT  = SLUMP_C_MIX_RHO + 6, /* two-phase: viscosity Heaviside shift (x w)  */
  SLUMP_C_SURF_N     = SLUMP_C_MIX_RHO + 7, /* free-surface table: samples (0: none)       */
  SLUMP_C_SURF_X0    = SLUMP_C_MIX_RHO + 8, /* free-surface table: first abscissa          */
  SLUMP_C_SURF_DX    = SLUMP_C_MIX_RHO + 9, /* free-surface table: spacing                 */
  SLUMP_C_MIX_FILTER = SLUMP_C_MIX_RHO + 10, /* two-phase: the level set is E tanh(d/E): E (0: a distance) */
  SLUMP_C_AXIS       = SLUMP_C_MIX_RHO + 11, /* axisymmetric: 1 + the radial coordinate (0: planar) */
  SLUMP_C_NUM        = SLUMP_C_MIX_RHO + 12,
  /* the free-surface heights follow the fixed constants:
     constants[SLUMP_C_NUM + i] = h(x0 + i dx), i < constants[SLUMP_C_SURF_N] */
  SLUMP_C_SURF_MAX = 4096
};

/* Height of the free surface above abscissa x from the table in the kernels'
   constants (SlumpProblemSetSurfaceHeight): linear between the samples,
   constant beyond the ends. False when no table is set. */
static inline PetscBool SlumpSurfaceHeight(const PetscScalar constants[], PetscReal x, PetscReal *h)
{
  const PetscInt n = (PetscInt)PetscRealPart(constants[SLUMP_C_SURF_N]);
  PetscReal      s;
  PetscInt       i;
  if (n < 1) return PETSC_FALSE;
  s = (x - PetscRealPart(constants[SLUMP_C_SURF_X0])) / PetscRealPart(constants[SLUMP_C_SURF_DX]);
  if (n == 1 || s <= 0) {
    *h = PetscRealPart(constants[SLUMP_C_NUM]);
    return PETSC_TRUE;
  }
  if (s >= n - 1) {
    *h = PetscRealPart(constants[SLUMP_C_NUM + n - 1]);
    return PETSC_TRUE;
  }
  i  = (PetscInt)s;
  s -= i;
  *h = (1 - s) * PetscRealPart(constants[SLUMP_C_NUM + i]) + s * PetscRealPart(constants[SLUMP_C_NUM + i + 1]);
  return PETSC_TRUE;
}
#define SLUMP_MAX_FIELDS 3

/* ----------------------------------------------------------- formulation */
/* plane: velocity u (P2, dim components) and pressure p (P1);
   antiplane: one out-of-plane velocity w(x, y) (P2), u = (0, 0, w), with
   ||gdot|| = |grad w| and no pressure (ducts: the Mosolov problem). The body
   force's x component drives w. */
/* transport: the velocity is prescribed everywhere (SlumpProblemSetPrescribedVelocity)
   and is not an unknown; only the extra field (a level set) is solved for. */
typedef enum { SLUMP_FORMULATION_PLANE, SLUMP_FORMULATION_ANTIPLANE, SLUMP_FORMULATION_TRANSPORT } SlumpFormulation;

/* An extra scalar field carried in the state after velocity and pressure:
   the level set of interface/. Core knows it only through these callbacks
   (core does not include interface/). */
typedef struct {
  /* create the field's PetscFE (DMSetField at index `field`) */
  PetscErrorCode (*create_field)(void *ctx, SlumpProblem prob, DM dm, PetscInt field);
  /* register its residual and Jacobian kernels (and may replace the momentum
     ones, e.g. two-phase mixing) */
  PetscErrorCode (*set_pointwise)(void *ctx, SlumpProblem prob, PetscDS ds, PetscInt field);
  /* its values into the kernels' constants[SLUMP_C_FIELD ...] */
  PetscErrorCode (*set_constants)(void *ctx, SlumpProblem prob, PetscScalar constants[]);
  /* initial values */
  SlumpPointFn init;
  /* action between two accepted steps (reinitialisation); *changed tells the
     integrator to restart from the modified state */
  PetscErrorCode (*post_step)(void *ctx, SlumpProblem prob, PetscInt step, PetscReal t, Vec X, PetscBool *changed);
  PetscErrorCode (*view)(void *ctx, SlumpProblem prob, PetscViewer viewer);
  PetscErrorCode (*destroy)(void *ctx);
  const char *name;
} SlumpExtraFieldOps;

/* --------------------------------------------------------------- problem */
PETSC_EXTERN PetscErrorCode SlumpProblemCreate(MPI_Comm comm, SlumpProblem *prob);
PETSC_EXTERN PetscErrorCode SlumpProblemDestroy(SlumpProblem *prob);
PETSC_EXTERN PetscErrorCode SlumpProblemSetMesh(SlumpProblem prob, DM mesh);
PETSC_EXTERN PetscErrorCode SlumpProblemSetFormulation(SlumpProblem prob, SlumpFormulation f);
/* Axisymmetric geometry (before SlumpProblemSetUp): the mesh is a meridian
   half-plane of a solid of revolution, x[radial] = r >= 0 (radial 0 or 1,
   the other coordinate the axial one z), without swirl. The velocity
   (u_r, u_z) gains the hoop strain rate u_r / r in ||gdot|| and in the
   stress (tau_tt = 2 eta u_r / r), div u gains u_r / r, and every integral
   (residual, Jacobian, diagnostics, fluxes, forces) carries the weight r:
   volumes, energies, flow rates and forces are per radian (multiply by
   2 pi for the whole solid). The axis r = 0 needs u_r = 0 (a free-slip
   condition there). radial < 0: planar (the default). Plane formulation
   only; not with traction conditions or -assembly petsc. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetAxisymmetric(SlumpProblem prob, PetscInt radial);
PETSC_EXTERN PetscErrorCode SlumpProblemGetAxisymmetric(SlumpProblem prob, PetscInt *radial);
PETSC_EXTERN PetscErrorCode SlumpProblemGetFormulation(SlumpProblem prob, SlumpFormulation *f);
PETSC_EXTERN PetscErrorCode SlumpProblemSetEffects(SlumpProblem prob, PetscInt effects);
PETSC_EXTERN PetscErrorCode SlumpProblemGetEffects(SlumpProblem prob, PetscInt *effects);
PETSC_EXTERN PetscErrorCode SlumpProblemSetDensity(SlumpProblem prob, PetscReal rho);
PETSC_EXTERN PetscErrorCode SlumpProblemGetDensity(SlumpProblem prob, PetscReal *rho);
PETSC_EXTERN PetscErrorCode SlumpProblemSetBodyForce(SlumpProblem prob, PetscReal gx, PetscReal gy);
PETSC_EXTERN PetscErrorCode SlumpProblemGetRheology(SlumpProblem prob, SlumpRheology *rheo);
/* Dirichlet velocity on every face of label `label`: components comps[ncomp]
   (NULL: all) take g(t, x); g_t is its time derivative (NULL: zero). */
PETSC_EXTERN PetscErrorCode SlumpProblemAddVelocityBC(SlumpProblem prob, const char name[], const char label[], PetscInt ncomp, const PetscInt comps[], SlumpPointFn g, SlumpPointFn g_t, void *ctx);
/* Zero normal velocity, tangential traction free (axis-aligned boundaries). */
PETSC_EXTERN PetscErrorCode SlumpProblemAddFreeSlipBC(SlumpProblem prob, const char label[]);
/* Wall friction on an axis-aligned wall: zero normal velocity (essential)
   and a tangential traction opposing the wall velocity u_t (natural, with
   its exact Jacobian):
     navier:  t = -beta m u_t                                  (coeff = beta)
     coulomb: t = -mu_w m P(p) u_t / sqrt(|u_t|^2 + delta^2)    (coeff = mu_w, reg = delta)
   with P(p) = max(p, 0) and m = 1, or in two-phase flows the material
   fraction m(phi): the ambient fluid slips, and across the contact line the
   friction fades over the mixing width (the slip cell of Riber's thesis,
   sec. 4.3.1.1, in a smooth form). A large beta is no slip under the
   material by penalty. One friction law per problem (any number of labels). */
typedef enum { SLUMP_WALL_NAVIER, SLUMP_WALL_COULOMB } SlumpWallLaw;
PETSC_EXTERN const char *const SlumpWallLaws[];
PETSC_EXTERN PetscErrorCode SlumpProblemAddFrictionBC(SlumpProblem prob, const char label[], SlumpWallLaw law, PetscReal coeff, PetscReal reg);
PETSC_EXTERN PetscErrorCode SlumpProblemHasWallFriction(SlumpProblem prob, PetscBool *has);
/* The yielded fraction the diagnostics report from now on, measured by a
   solver that knows the yield surface (the exact method's steady state;
   < 0: the rheology's criterion ||tau|| > tau_y, the default). */
PETSC_EXTERN PetscErrorCode SlumpProblemSetYieldedFraction(SlumpProblem prob, PetscReal fraction);
/* ... and the map behind it: 1 (yielded) or 0 at each local quadrature point
   (the layout of SlumpProblemGetQuadratureLayout; NULL: none). */
PETSC_EXTERN PetscErrorCode SlumpProblemSetYieldMap(SlumpProblem prob, PetscInt n, const PetscReal yielded[]);
/* x,y,yielded at every quadrature point into a CSV file (rank 0 writes):
   the map set above, or the rheology's criterion ||tau|| > tau_y at X. */
/* The force of the fluid on a boundary (component comp), as the consistent
   reaction -R(phi e_comp) of the steady residual with a cut-off phi equal to
   1 on that boundary and 0 on the other no-slip and open boundaries. */
typedef void (*SlumpCutoffFn)(const PetscReal x[], void *ctx, PetscReal *phi, PetscReal dphi[]);
PETSC_EXTERN PetscErrorCode SlumpProblemComputeBoundaryForce(SlumpProblem prob, PetscReal t, Vec X, SlumpCutoffFn cutoff, void *ctx, PetscInt comp, PetscReal *force);
/* The exact method's plastic stress at the quadrature points (plane: dim x
   dim per point; NULL: none): the force above then uses it with the
   viscous stress in place of the rheology's law. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetPlasticStress(SlumpProblem prob, PetscInt n, const PetscScalar S[]);
PETSC_EXTERN PetscErrorCode SlumpProblemWriteYieldMap(SlumpProblem prob, PetscReal t, Vec X, const char path[]);
/* Imposed traction (natural condition); a label without a condition is traction free. */
PETSC_EXTERN PetscErrorCode SlumpProblemAddTractionBC(SlumpProblem prob, const char label[], SlumpTractionFn traction);
/* Replace the momentum source (body force) by a scene's own pointwise term f0_u. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetMomentumSource(SlumpProblem prob, PetscPointFunc f0_u);
/* Scene constant i (0..3), read by a scene's kernels as constants[SLUMP_C_SCENE + i]. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetSceneConstant(SlumpProblem prob, PetscInt i, PetscReal value);
PETSC_EXTERN PetscErrorCode SlumpProblemSetInitialVelocity(SlumpProblem prob, SlumpPointFn u0, void *ctx);
/* Transport formulation: the velocity u(t, x) everywhere (u_t: its time
   derivative, NULL if steady). */
PETSC_EXTERN PetscErrorCode SlumpProblemSetPrescribedVelocity(SlumpProblem prob, SlumpPointFn u, SlumpPointFn u_t, void *ctx);
/* The pressure is fixed to 0 at the mesh vertex nearest to x when no
   boundary determines it (closed boxes). Default: the vertex of least x + y,
   which suits a Newtonian law; pressure-dependent laws (mu(I),
   Drucker-Prager) need the reference where the pressure is truly 0 (the top
   of a box of air). */
PETSC_EXTERN PetscErrorCode SlumpProblemSetPressureReference(SlumpProblem prob, const PetscReal x[]);
/* Two-phase mixing (needs the extra field, a level set phi, negative in the
   material): density and viscosity are mixed with the smoothed Heaviside
   H(phi) = 0 (phi < -w), 1 (phi > w), (1 + phi/w + sin(pi phi/w)/pi)/2
   between, the material fraction being 1 - H. The rheology acts in the
   material, a Newtonian law of viscosity eta_ambient in the ambient fluid:
     rho = (1-H) rho + H rho_ambient,   eta = (1-H) eta_model(gdot, p) + H eta_ambient.
   width: the half-width w in units of the smallest mesh edge (e.g. 1.5).
   Options -ambient_density, -ambient_viscosity, -mixing_width. The
   diagnostics then measure the material: kinetic energy and dissipation of
   the material, shear rates and yielded fraction averaged over its area. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetTwoPhase(SlumpProblem prob, PetscReal rho_ambient, PetscReal eta_ambient, PetscReal width);
/* Shift the Heaviside that weighs the material's viscosity by shift * w into
   the ambient fluid (0 <= shift <= 1; default 0: the density's): with 1 the
   material law holds in the whole band up to the zero contour, as
   pressure-dependent laws need (a fraction m < 1 of a friction law would
   scale its friction coefficient by m in the band). Wall friction uses the
   same fraction. Option -mixing_viscosity_shift. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetTwoPhaseViscosityShift(SlumpProblem prob, PetscReal shift);
/* The convective terms (option -convection_form): rho u.grad u (advective,
   the default), + 1/2 rho (div u) u (temam), or + 1/2 (rho_t + div(rho u)) u
   (skew: tested with the discrete velocity, the inertial terms then give
   exactly d/dt int rho |u|^2/2, whatever the discrete divergence and the
   level set's transport error). */
typedef enum { SLUMP_CONVECTION_ADVECTIVE = 0, SLUMP_CONVECTION_TEMAM = 1, SLUMP_CONVECTION_SKEW = 2 } SlumpConvectionForm;
PETSC_EXTERN PetscErrorCode SlumpProblemSetConvectionForm(SlumpProblem prob, SlumpConvectionForm form);
/* The extra field is a filtered distance E tanh(d/E) (E > 0; 0: a distance):
   the mixing then takes d = E atanh(phi/E). The level set sets it for the
   convective reinitialisation. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetTwoPhaseFilter(SlumpProblem prob, PetscReal E);
PETSC_EXTERN PetscErrorCode SlumpProblemGetTwoPhase(SlumpProblem prob, PetscBool *on, PetscReal *rho_ambient, PetscReal *eta_ambient, PetscReal *width);
/* Attach the extra field (before SlumpProblemSetUp); the problem owns ctx
   and calls ops->destroy. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetExtraField(SlumpProblem prob, const SlumpExtraFieldOps *ops, void *ctx);
PETSC_EXTERN PetscErrorCode SlumpProblemGetExtraField(SlumpProblem prob, PetscInt *field, void **ctx);
/* Index set of the extra field's unknowns (NULL if none). */
PETSC_EXTERN PetscErrorCode SlumpProblemGetExtraFieldIS(SlumpProblem prob, IS *is);
/* Call the extra field's between-step action (collective). */
PETSC_EXTERN PetscErrorCode SlumpProblemPostStep(SlumpProblem prob, PetscInt step, PetscReal t, Vec X, PetscBool *changed);
/* The current free-surface height h(x) on n uniform samples from x0 with
   spacing dx (n <= SLUMP_C_SURF_MAX; n = 0 removes it), handed to the
   kernels after their constants: the lithostatic yield stress then uses
   the depth h(x) - y below the surface instead of a fixed height. The level
   set sets it between steps (SlumpLevelSetSetSurfaceFeed). */
PETSC_EXTERN PetscErrorCode SlumpProblemSetSurfaceHeight(SlumpProblem prob, PetscInt n, PetscReal x0, PetscReal dx, const PetscReal h[]);
/* The state at the last accepted step as the kernels' auxiliary fields:
   a[aOff[f]] and a_x[aOff_x[f]] hold field f of it with the same layout as
   u and u_x (NfAux = Nf), for terms a scheme lags by one step (the
   convective reinitialisation's direction and source, Riber eq. 2.18).
   SlumpProblemSetLagged(prob, PETSC_TRUE) switches it on (the kernels
   then get NfAux = Nf); until SlumpProblemSetLaggedState is first called,
   the first state the residual or Jacobian is evaluated at is taken. The
   integrators' between-step action (SlumpProblemPostStep) is where an
   extra field updates it. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetLagged(SlumpProblem prob, PetscBool on);
PETSC_EXTERN PetscErrorCode SlumpProblemSetLaggedState(SlumpProblem prob, PetscReal t, Vec X);
/* Local solution at t with boundary values (read only; valid until the next call). */
PETSC_EXTERN PetscErrorCode SlumpProblemGetLocalSolution(SlumpProblem prob, PetscReal t, Vec X, Vec *locX);
/* Local indices of a field's dofs in the closure of every local cell
   (ncell x nb, row-major; PetscFree(idx) afterwards); cStart: first cell. */
PETSC_EXTERN PetscErrorCode SlumpProblemGetFieldClosure(SlumpProblem prob, PetscInt field, PetscInt *ncell, PetscInt *nb, PetscInt **idx, PetscInt *cStart);
/* Fields at the quadrature points of the local cells (the exact method's
   plastic stress and strain rate): value k of point q of cell c at
   (c * nq + q) * ns + k, ns = dim*dim (plane: tensors) or dim (anti-plane:
   vectors). The strain rate is grad u + grad u^T (plane) or grad w; the
   flux adds int T : grad v over the velocity test functions into F. */
PETSC_EXTERN PetscErrorCode SlumpProblemGetQuadratureLayout(SlumpProblem prob, PetscInt *npoints, PetscInt *ns);
PETSC_EXTERN PetscErrorCode SlumpProblemGetQuadratureWeights(SlumpProblem prob, PetscReal w[]);
PETSC_EXTERN PetscErrorCode SlumpProblemComputeQuadratureStrainRate(SlumpProblem prob, PetscReal t, Vec X, PetscScalar g[]);
PETSC_EXTERN PetscErrorCode SlumpProblemAddQuadratureFlux(SlumpProblem prob, const PetscScalar T[], Vec F);
/* The velocity at the points of an nx x ny grid spanning [lower, upper]
   (value c of point (i, j) at (j nx + i) Nc + c; found[p] = 0 outside the
   mesh; collective, every rank gets every value). */
PETSC_EXTERN PetscErrorCode SlumpProblemSampleVelocity(SlumpProblem prob, PetscReal t, Vec X, PetscInt nx, PetscInt ny, const PetscReal lower[2], const PetscReal upper[2], PetscReal u[], PetscReal found[]);
/* Integrals over the domain of n pointwise functions (one value each) at (t, X). */
PETSC_EXTERN PetscErrorCode SlumpProblemComputeIntegrals(SlumpProblem prob, PetscReal t, Vec X, PetscInt n, PetscPointFunc obj[], PetscReal result[]);
/* Initial pressure (initial guess of steady solves; e.g. lithostatic). */
PETSC_EXTERN PetscErrorCode SlumpProblemSetInitialPressure(SlumpProblem prob, SlumpPointFn p0, void *ctx);
PETSC_EXTERN PetscErrorCode SlumpProblemSetExactSolution(SlumpProblem prob, SlumpPointFn u, SlumpPointFn p, void *ctx);
PETSC_EXTERN PetscErrorCode SlumpProblemGetExactSolution(SlumpProblem prob, SlumpPointFn *u, SlumpPointFn *p, void **ctx);
PETSC_EXTERN PetscErrorCode SlumpProblemSetFromOptions(SlumpProblem prob);
PETSC_EXTERN PetscErrorCode SlumpProblemSetUp(SlumpProblem prob);
PETSC_EXTERN PetscErrorCode SlumpProblemView(SlumpProblem prob, PetscViewer viewer);
/* Push the current physical and rheological parameters into the kernels'
   constants (call after changing them between solves). */
PETSC_EXTERN PetscErrorCode SlumpProblemUpdateConstants(SlumpProblem prob);
/* sets a rheology parameter and pushes the new constants to the assembly */
PETSC_EXTERN PetscErrorCode SlumpProblemSetRheologyParameter(SlumpProblem prob, const char name[], PetscReal value);
PETSC_EXTERN PetscErrorCode SlumpProblemGetDM(SlumpProblem prob, DM *dm);
PETSC_EXTERN PetscErrorCode SlumpProblemCreateVector(SlumpProblem prob, Vec *X);
PETSC_EXTERN PetscErrorCode SlumpProblemCreateMatrix(SlumpProblem prob, Mat *J);
/* Index sets of the velocity and pressure unknowns in the global vector
   (isp = NULL in the anti-plane formulation). */
PETSC_EXTERN PetscErrorCode SlumpProblemGetFieldIS(SlumpProblem prob, IS *isu, IS *isp);
/* Differential (1) / algebraic (0) marker of every unknown. */
PETSC_EXTERN PetscErrorCode SlumpProblemGetDifferentialMarker(SlumpProblem prob, Vec id);
PETSC_EXTERN PetscErrorCode SlumpProblemProjectInitialState(SlumpProblem prob, PetscReal t, Vec X);

/* The DAE: F(t, X, Xdot) = 0 on the free (non-Dirichlet) unknowns. */
PETSC_EXTERN PetscErrorCode SlumpProblemResidual(SlumpProblem prob, PetscReal t, Vec X, Vec Xdot, Vec F);
/* J = dF/dX + shift dF/dXdot. */
PETSC_EXTERN PetscErrorCode SlumpProblemJacobian(SlumpProblem prob, PetscReal t, Vec X, Vec Xdot, PetscReal shift, Mat J);
/* Jacobian of the consistent-initialisation system [rho M, B^T; B, 0]. */
PETSC_EXTERN PetscErrorCode SlumpProblemInitJacobian(SlumpProblem prob, PetscReal t, Vec X, Mat J);
PETSC_EXTERN PetscErrorCode SlumpProblemGetCounters(SlumpProblem prob, PetscInt *nres, PetscInt *njac);

/* Stress-velocity Newton (Rudi, Shih & Stadler 2020; Chan, Golub & Mulet
   1999 for TV): the plastic stress S of the rheology's yield term is kept
   as an independent variable at every quadrature point while the Newton
   systems stay velocity-pressure ones (slumprheology.h, SlumpPlasticKernel).
   A nonlinear solve brackets its iterations with Begin/End:
     Begin: S = the value carried from the last converged solve (the first
            time, or after Reset: consistent with X);
     Linearise(X): before each Jacobian at the iterate X: S is updated with
            the step X - X_previous from the linearised plastic law, then
            projected into ||S|| <= tau_y; the Jacobian then uses S;
     End(X, converged): the last update, and S is kept for the next solve
            if converged.
   Outside a Begin/End bracket, and for a model without a plastic part, the
   Jacobian is the primal one. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetStressVelocity(SlumpProblem prob, PetscBool on);
PETSC_EXTERN PetscErrorCode SlumpProblemGetStressVelocity(SlumpProblem prob, PetscBool *on);
/* The linearisation asked for by -newton_linearisation (read by
   SlumpProblemSetFromOptions; default stress_velocity for a model with a
   plastic part, primal otherwise); the integrators apply it. */
PETSC_EXTERN PetscErrorCode SlumpProblemGetStressVelocityOption(SlumpProblem prob, PetscBool *wanted);
PETSC_EXTERN PetscErrorCode SlumpProblemDualBegin(SlumpProblem prob, PetscReal t, Vec X);
PETSC_EXTERN PetscErrorCode SlumpProblemDualLinearise(SlumpProblem prob, PetscReal t, Vec X);
PETSC_EXTERN PetscErrorCode SlumpProblemDualEnd(SlumpProblem prob, PetscReal t, Vec X, PetscBool converged);
/* Quadrature points whose yielded state (eta ||gdot|| > tau_y) changed since
   the last Jacobian was assembled with S (collective): a Newton reusing its
   Jacobian refreshes it when this is not 0. */
PETSC_EXTERN PetscErrorCode SlumpProblemDualYieldChanges(SlumpProblem prob, PetscInt *nchanged);
/* Forget the carried S (the state was changed between steps). */
PETSC_EXTERN PetscErrorCode SlumpProblemDualReset(SlumpProblem prob);
/* The plastic stress carried to the next solve (the state a checkpoint
   keeps): n local values (0 and NULL when the stress-velocity Newton is
   off), and whether it is set (otherwise the next solve starts from the
   state's own stress). */
PETSC_EXTERN PetscErrorCode SlumpProblemDualGetState(SlumpProblem prob, PetscInt *n, PetscBool *saved, PetscScalar **S);
PETSC_EXTERN PetscErrorCode SlumpProblemDualSetState(SlumpProblem prob, PetscInt n, PetscBool saved, const PetscScalar S[]);
/* The S array: n quadrature points (local cells x points per cell), ns
   values each (read only; tests). */
PETSC_EXTERN PetscErrorCode SlumpProblemDualGetArray(SlumpProblem prob, PetscInt *n, PetscInt *ns, const PetscScalar **S);

/* ----------------------------------------------------------- diagnostics */
typedef struct {
  PetscReal t;
  PetscReal kinetic_energy;     /* 1/2 int rho |u|^2                          */
  PetscReal mean_shear_rate;    /* (1/|Omega|) int ||gdot||                  */
  PetscReal max_shear_rate;     /* max ||gdot|| (exact for P2: cell vertices) */
  PetscReal l2_shear_rate;      /* (int ||gdot||^2)^(1/2)                     */
  PetscReal dissipation;        /* int tau : D = int eta ||gdot||^2           */
  PetscReal yielded_fraction;   /* |{||tau|| > tau_y}| / |Omega| (1 if no yield stress) */
  PetscReal flow_rate;          /* int u . n over the flow-rate boundary, if any; anti-plane: int w */
  PetscReal potential_energy;   /* -int rho g . x, the body force's potential (0 without body force) */
  PetscReal dissipation_ambient; /* two-phase: int (1 - m) eta_ambient ||gdot||^2, the ambient fluid's share (0 in one phase) */
  PetscReal dissipation_wall;   /* int over the friction walls of the traction's power (0 without wall friction) */
} SlumpDiagnostics;

/* Two-phase (SlumpProblemSetTwoPhase): every quantity is the material's,
   weighted by its fraction m(phi): kinetic, potential energy and dissipation
   of the material, mean shear rate and yielded fraction over its area. */
/* Single diagnostics, for arrest criteria (root functions). */
typedef enum {
  SLUMP_DIAG_MEAN_SHEAR_RATE,
  SLUMP_DIAG_MAX_SHEAR_RATE,
  SLUMP_DIAG_L2_SHEAR_RATE,
  SLUMP_DIAG_KINETIC_ENERGY,
  SLUMP_DIAG_YIELDED_FRACTION,
  SLUMP_DIAG_NUM
} SlumpDiagnosticKind;
PETSC_EXTERN const char *const SlumpDiagnosticNames[];
/* values[k] = diagnostic kinds[k] at (t, X); one quadrature pass for all the
   integrals, one projection if the maximum is asked for (collective). */
PETSC_EXTERN PetscErrorCode SlumpProblemComputeDiagnosticList(SlumpProblem prob, PetscReal t, Vec X, PetscInt n, const SlumpDiagnosticKind kinds[], PetscReal values[]);
PETSC_EXTERN PetscErrorCode SlumpProblemComputeDiagnostics(SlumpProblem prob, PetscReal t, Vec X, SlumpDiagnostics *d);
/* In one quadrature pass, the kinetic energy (the diagnostics') and the
   rate at which the flow dissipates energy, in its three parts: rate[0] the
   material's (the diagnostics' dissipation), rate[1] the ambient fluid's,
   rate[2] the friction walls' (collective). The rates' sum is what the
   kinetic and potential energy lose, up to the discretisation. */
PETSC_EXTERN PetscErrorCode SlumpProblemComputeEnergyRates(SlumpProblem prob, PetscReal t, Vec X, PetscReal *kinetic, PetscReal rate[3]);
PETSC_EXTERN PetscErrorCode SlumpProblemComputeMeanShearRate(SlumpProblem prob, PetscReal t, Vec X, PetscReal *mean);
/* potential energy of the material, -int m rho g.x (0 without gravity or
   outside the plane formulation): the potential_energy of the diagnostics */
PETSC_EXTERN PetscErrorCode SlumpProblemComputePotentialEnergy(SlumpProblem prob, PetscReal t, Vec X, PetscReal *ep);
/* Boundary over which the flow rate diagnostic integrates u . n. */
PETSC_EXTERN PetscErrorCode SlumpProblemSetFlowRateBoundary(SlumpProblem prob, const char label[]);
/* Mean of velocity component comp over the boundary `label` (collective). */
PETSC_EXTERN PetscErrorCode SlumpProblemComputeBoundaryMean(SlumpProblem prob, PetscReal t, Vec X, const char label[], PetscInt comp, PetscReal *mean);
/* Smallest eigenvalue of the viscous operator (vector or scalar Laplacian)
   with the problem's Dirichlet walls, by SLEPc (collective). */
PETSC_EXTERN PetscErrorCode SlumpProblemComputeViscousEigenvalue(SlumpProblem prob, PetscReal *lambda1);
PETSC_EXTERN PetscErrorCode SlumpProblemGetArea(SlumpProblem prob, PetscReal *area);
/* L2 errors of velocity and pressure against the exact solution (if any). */
PETSC_EXTERN PetscErrorCode SlumpProblemComputeErrors(SlumpProblem prob, PetscReal t, Vec X, PetscReal err[2], PetscReal norm[2]);

/* ---------------------------------------------------------------- output */
/* Fields (velocity, pressure, shear rate, effective viscosity, on P1) at
   time t into dir/fields.h5, and dir/fields.xmf listing every time written. */
typedef struct _n_SlumpFieldWriter *SlumpFieldWriter;
PETSC_EXTERN PetscErrorCode SlumpFieldWriterCreate(SlumpProblem prob, const char dir[], SlumpFieldWriter *w);
PETSC_EXTERN PetscErrorCode SlumpFieldWriterWrite(SlumpFieldWriter w, PetscReal t, Vec X);
PETSC_EXTERN PetscErrorCode SlumpFieldWriterDestroy(SlumpFieldWriter *w);

/* A KSP as a direct solver: preonly + LU (MUMPS when PETSc has it), then
   the options database under the KSP's prefix. */
PETSC_EXTERN PetscErrorCode SlumpKSPSetDirect(KSP ksp);
/* The KSP of the problem's Newton steps: direct (SlumpKSPSetDirect) or, with
   -linear_solver iterative, Krylov + multigrid (core/linear.c) */
PETSC_EXTERN PetscErrorCode SlumpProblemConfigureKSP(SlumpProblem prob, KSP ksp);
/* The KSP of the consistent initialisation: as SlumpProblemConfigureKSP,
   with the Schur complement by selfp (core/linear.c) */
PETSC_EXTERN PetscErrorCode SlumpProblemConfigureInitKSP(SlumpProblem prob, KSP ksp);
/* KSPSolve with the problem's escalation (core/linear.c): with -linear_solver
   iterative on velocity-pressure, a solve that passes -linear_escalate_its
   iterations is repeated, and every later solve made, with an inner GMRES
   solve of the velocity block. its: the outer iterations of all attempts.
   With -linear_solver direct, a MUMPS factorisation that stops on its
   workspace is done again with the relaxation -mat_mumps_icntl_14 lowered
   (allocation failed) or raised (workspace too small), where it is ours. */
PETSC_EXTERN PetscErrorCode SlumpProblemKSPSolve(SlumpProblem prob, KSP ksp, Vec b, Vec x, KSPConvergedReason *reason, PetscInt *its);
/* Krylov solves of SlumpProblemKSPSolve that did not converge: how many
   (over the run), and the last one's iterations and reason; direct: the last
   one was -linear_solver direct, whose LU factorisation failed, what: why
   and what to do, as the end of a sentence */
typedef struct {
  PetscInt           n, its;
  KSPConvergedReason reason;
  PetscBool          direct;
  char               what[320];
} SlumpLinearFailures;
PETSC_EXTERN PetscErrorCode SlumpProblemGetLinearFailures(SlumpProblem prob, SlumpLinearFailures *f);
/* KSPSolve of a direct ksp (LU; SlumpKSPSetDirect): a MUMPS factorisation
   that stops on its workspace is done again, up to 3 times, with the
   relaxation -mat_mumps_icntl_14 lowered (allocation failed) or raised
   (workspace too small), where it is SlumpKSPSetDirect's default; one line
   says so. what: empty, or why the solve failed, the end of a sentence. */
PETSC_EXTERN PetscErrorCode SlumpKSPSolveDirect(KSP ksp, Vec b, Vec x, KSPConvergedReason *reason, char what[], size_t len);
/* true with -linear_solver iterative and -linear_forcing eisenstat_walker */
PETSC_EXTERN PetscErrorCode SlumpProblemGetLinearForcing(SlumpProblem prob, PetscBool *ew);

/* Make a directory and its parents (rank 0; collective). */
PETSC_EXTERN PetscErrorCode SlumpMakeDirectory(MPI_Comm comm, const char dir[]);

/* Checked text outputs (core/files.c). SlumpFileOpen opens for writing,
   line buffered (a killed run keeps every completed row); it, SlumpFilePrintf
   and SlumpFileClose return 0 or the errno of the failure (NULL file: 0);
   SlumpFileCheck makes a rank's errno collective and raises it as an error
   naming the file; SlumpFileCommit renames a complete temporary file to its
   name (rank 0), or removes it if err is set. */
PETSC_EXTERN int            SlumpFileOpen(const char path[], FILE **fp);
PETSC_EXTERN int            SlumpFilePrintf(FILE *fp, const char fmt[], ...) PETSC_ATTRIBUTE_FORMAT(2, 3);
PETSC_EXTERN int            SlumpFileClose(FILE **fp);
PETSC_EXTERN PetscErrorCode SlumpFileCheck(MPI_Comm comm, int err, const char path[]);
PETSC_EXTERN PetscErrorCode SlumpFileCommit(MPI_Comm comm, int err, const char tmp[], const char path[]);
/* The output directory's lock (dir/.slump.lock, collective): refused while
   another live run holds it unless overwrite; released by Unlock, and by
   UnlockAll at exit (any path). */
PETSC_EXTERN PetscErrorCode SlumpOutputLock(MPI_Comm comm, const char dir[], PetscBool overwrite);
PETSC_EXTERN PetscErrorCode SlumpOutputUnlock(MPI_Comm comm, const char dir[]);
PETSC_EXTERN void           SlumpOutputUnlockAll(void);
/* An output file HDF5 could not close (a failed write): the program must end
   without PetscFinalize/MPI_Finalize, where HDF5 1.10 would crash on it. */
PETSC_EXTERN void      SlumpSetUnclosableOutput(void);
PETSC_EXTERN PetscBool SlumpHasUnclosableOutput(void);
/* SIGINT/SIGTERM set a flag (the second one ends the process); the step
   loop reads it with SlumpInterruptSignal (0: none, else the signal). */
PETSC_EXTERN PetscErrorCode SlumpInstallInterruptHandlers(void);
PETSC_EXTERN int            SlumpInterruptSignal(void);
