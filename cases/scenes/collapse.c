/* Two-phase collapses of a rectangular column under gravity: the material
 * (phi < 0) fills [0, r_i] x [0, h_i] of a closed box [0, L] x [0, H], the
 * rest is the ambient fluid (air); the left wall x = 0 is the symmetry axis.
 * Density and viscosity are mixed by a smoothed Heaviside of the level set
 * (SlumpProblemSetTwoPhase); the level set is transported by the flow and
 * reinitialised between steps (redistance every 20 steps by default, with
 * the global volume correction: -reinit_volume_correction 0 turns it off).
 *
 * dam_break: the Newtonian benchmark of Riber's thesis (sec. 2.6, after
 *   Cruchaga et al.): box 0.42 x 0.44 m, column 0.114 x 0.114 m, material
 *   rho = 1000 kg/m^3, eta = 1 Pa s, air rho = 1, eta = 1e-3, g = 9.81,
 *   every wall free slip (slip floor as in the thesis).
 * bingham_dam_break: the Bingham column of Liu et al. as in the thesis
 *   (sec. 3.5, its eq. 3.8): lengths in h_i, stresses in rho g h_i, time in
 *   the viscous unit t_c = eta_p/(rho g h_i) (velocity rho g h_i^2/eta_p),
 *   so that Re rho (u_t + u.grad u) = -grad p + div tau + rho e_g with
 *   Re = rho^2 g h_i^3/eta_p^2 = 1e-3 (-re); in slump's terms the density is
 *   Re, gravity 1/Re, eta_p = 1 and tau0 = Bn = tau0/(rho g h_i) (-bn,
 *   default 0.1). Air ratios 1e-3 (density) and 1e-6 (viscosity)
 *   (-ambient_density, -ambient_viscosity); Papanastasiou m = 1e3 t_c by
 *   default; box 4 x 1.5 h_i. The floor is the thesis' no slip under the
 *   material with a slip cell at the contact line: Navier friction
 *   beta m(phi) u with beta = 1e4 eta_p/h_i (slip length 1e-4 h_i under the
 *   fluid, free slip in the air), -floor for others. -re 0 is the
 *   quasi-static limit: no inertia (velocity and pressure algebraic, only
 *   phi differential), density and gravity 1 so that the weight stays 1.
 *
 * column_collapse: the mu(I) columns of Lagree et al. (below).
 *
 * Options: -column_width r_i, -column_height h_i, -box_length L,
 * -box_height H, -floor slip|noslip|navier|coulomb, -floor_friction,
 * -floor_friction_delta. The interface record (interface.csv)
 * logs the front x_max and the material height on the symmetry axis (x = 0)
 * and on the right wall (x = L). Results: the initial and final front and
 * axis height, the volume drift, the potential energy released. */
#include "common.h"
#include "slumpinterface.h"

typedef enum { FLOOR_SLIP, FLOOR_NOSLIP, FLOOR_NAVIER, FLOOR_COULOMB } FloorKind;
static const char *const Floors[] = {"slip", "noslip", "navier", "coulomb"};

typedef struct {
  PetscReal ri, hi, L, H, g;
  FloorKind floor;
  PetscReal fcoeff, freg; /* floor friction: beta or mu_w, Coulomb delta */
  PetscReal runout_fit;   /* column_collapse: the thesis' fit of (r_f - r_i)/r_i (0: none) */
  PetscInt  reinit_every; /* between-step reinitialisation every n steps (0: the level set's default) */
  PetscReal cell;         /* target cell size of the default mesh (0: the scene's mesh_n as set) */
  PetscBool surface_feed; /* hand the current free-surface height to the kernels (lithostatic yield) */
  PetscBool quasistatic;  /* no inertia: velocity and pressure algebraic, only phi differential */
  PetscReal supg_speed;   /* speed floor of the level set's SUPG (0: none) */
  PetscBool axi;          /* -geometry axisymmetric: a cylindrical column about x = 0 */
} ColumnCtx;

/* signed distance to the column [0, ri] x [0, hi] seen from the box: the
   walls x = 0 and y = 0 are not interface */
static PetscErrorCode ColumnPhi(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const ColumnCtx *c  = (const ColumnCtx *)ctx;
  const PetscReal  dx = x[0] - c->ri, dy = x[1] - c->hi;
  if (dx <= 0 && dy <= 0) u[0] = PetscMax(dx, dy);
  else u[0] = PetscSqrtReal(PetscSqr(PetscMax(dx, 0.0)) + PetscSqr(PetscMax(dy, 0.0)));
  return 0;
}

/* potential energy density of the material: m(phi) rho g y */
static void PotentialEnergy(SLUMP_PW_ARGS, PetscScalar f[])
{
  PetscReal m, dm;
  SlumpPwMaterialFraction(u[uOff[Nf - 1]], constants, &m, &dm);
  f[0] = m * PetscRealPart(constants[SLUMP_C_RHO]) * (-PetscRealPart(constants[SLUMP_C_GY])) * x[1];
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  ColumnCtx     *c = (ColumnCtx *)scene->ctx;
  SlumpLevelSet  ls;
  PetscReal      box[4], V0, V, drift, h0, hL, ep;
  PetscBool      f0, fL;
  PetscInt       nre;
  PetscPointFunc obj[1] = {PotentialEnergy};
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetLevelSet(prob, &ls));
  PetscCall(SlumpLevelSetComputeExtent(ls, t, X, box));
  PetscCall(SlumpLevelSetComputeHeightAt(ls, t, X, 0.0, &h0, &f0));
  PetscCall(SlumpLevelSetComputeHeightAt(ls, t, X, c->L, &hL, &fL));
  PetscCall(SlumpLevelSetComputeVolume(ls, t, X, &V));
  PetscCall(SlumpLevelSetGetStats(ls, &V0, NULL, &drift, &nre));
  PetscCall(SlumpSceneAddResult(scene, "front", box[1]));
  PetscCall(SlumpSceneAddResult(scene, "front_over_ri", box[1] / c->ri));
  PetscCall(SlumpSceneAddResult(scene, "height_axis", f0 ? h0 : 0.0));
  PetscCall(SlumpSceneAddResult(scene, "height_axis_over_hi", f0 ? h0 / c->hi : 0.0));
  PetscCall(SlumpSceneAddResult(scene, "height_right_wall", fL ? hL : 0.0));
  PetscCall(SlumpSceneAddResult(scene, "volume_error", V / V0 - 1.0));
  PetscCall(SlumpSceneAddResult(scene, "volume_drift_max", drift));
  PetscCall(SlumpSceneAddResult(scene, "reinitialisations", nre));
  PetscCall(SlumpProblemComputeIntegrals(prob, t, X, 1, obj, &ep));
  PetscCall(SlumpSceneAddResult(scene, "potential_energy", ep));
  {
    PetscReal shift;
    PetscCall(SlumpLevelSetGetVolumeShift(ls, &shift));
    PetscCall(SlumpSceneAddResult(scene, "volume_correction_shift", shift));
  }
  {
    PetscReal ereinit, ecorr;
    PetscCall(SlumpLevelSetGetEnergyInput(ls, &ereinit, &ecorr));
    PetscCall(SlumpSceneAddResult(scene, "energy_reinit", ereinit));
    PetscCall(SlumpSceneAddResult(scene, "energy_correction", ecorr));
  }
  {
    /* the front of the layer at least 5 % of h_i thick: the zero contour's
       end includes a film thinner than a cell that creeps on ahead */
    const PetscInt npt = 801;
    PetscReal     *xs, *top, fthick = 0.0;
    PetscCall(PetscMalloc2(npt, &xs, npt, &top));
    for (PetscInt i = 0; i < npt; ++i) xs[i] = c->L * i / (npt - 1.0);
    PetscCall(SlumpLevelSetComputeProfile(ls, t, X, npt, xs, top));
    for (PetscInt i = 0; i < npt; ++i)
      if (top[i] >= 0.05 * c->hi) fthick = xs[i];
    PetscCall(PetscFree2(xs, top));
    PetscCall(SlumpSceneAddResult(scene, "front_thick", fthick));
    if (c->runout_fit > 0) PetscCall(SlumpSceneAddResult(scene, "runout_thick_over_ri", (fthick - c->ri) / c->ri));
  }
  if (c->runout_fit > 0) {
    PetscCall(SlumpSceneAddResult(scene, "runout_over_ri", (box[1] - c->ri) / c->ri));
    PetscCall(SlumpSceneAddResult(scene, "runout_fit_thesis", c->runout_fit));
    /* axisymmetric experiments (Lube et al. 2004; Lajeunesse et al. 2004
       find the same regimes): 1.24 a (a < 1.7), 1.6 a^(1/2) */
    if (c->axi) PetscCall(SlumpSceneAddResult(scene, "runout_fit_lube2004", c->hi / c->ri < 1.7 ? 1.24 * c->hi / c->ri : 1.6 * PetscSqrtReal(c->hi / c->ri)));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ColumnSetUp(SlumpScene scene, SlumpProblem prob, MPI_Comm comm, ColumnCtx *c, PetscReal rho, PetscReal rho_a, PetscReal eta_a)
{
  SlumpLevelSet   ls;
  PetscReal       lower[2] = {0.0, 0.0}, upper[2];
  const PetscInt  cy = 1;
  PetscInt        fl = (PetscInt)c->floor;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Column collapse", "");
  PetscCall(PetscOptionsReal("-column_width", "Initial width r_i of the column", "", c->ri, &c->ri, NULL));
  PetscCall(PetscOptionsReal("-column_height", "Initial height h_i of the column", "", c->hi, &c->hi, NULL));
  PetscCall(PetscOptionsReal("-box_length", "Length L of the box", "", c->L, &c->L, NULL));
  PetscCall(PetscOptionsReal("-box_height", "Height H of the box", "", c->H, &c->H, NULL));
  PetscCall(PetscOptionsEList("-floor", "Floor condition: slip, noslip, navier (friction beta m(phi) u) or coulomb (mu_w m(phi) p u/sqrt(u^2+delta^2))", "", Floors, 4, Floors[fl], &fl, NULL));
  PetscCall(PetscOptionsReal("-floor_friction", "Floor friction coefficient: beta (navier) or mu_w (coulomb)", "", c->fcoeff, &c->fcoeff, NULL));
  PetscCall(PetscOptionsReal("-floor_friction_delta", "Velocity scale delta of the regularised Coulomb floor", "", c->freg, &c->freg, NULL));
  PetscOptionsEnd();
  /* axisymmetric: the column is a cylinder about the left wall x = 0 (r = x) */
  PetscCall(SlumpSceneGeometry(prob, comm, 0, &c->axi));
  c->floor = (FloorKind)fl;
  PetscCheck(c->fcoeff >= 0, comm, PETSC_ERR_USER_INPUT, "-floor_friction must be >= 0; got %g", (double)c->fcoeff);
  PetscCheck(c->floor != FLOOR_COULOMB || c->freg > 0, comm, PETSC_ERR_USER_INPUT, "-floor_friction_delta must be positive for -floor coulomb; got %g", (double)c->freg);
  PetscCheck(c->ri > 0 && c->hi > 0, comm, PETSC_ERR_USER_INPUT, "-column_width and -column_height must be positive; got %g and %g", (double)c->ri, (double)c->hi);
  PetscCheck(c->L > c->ri && c->H > c->hi, comm, PETSC_ERR_USER_INPUT, "The box (-box_length %g, -box_height %g) must be longer and higher than the column (%g x %g)", (double)c->L, (double)c->H, (double)c->ri, (double)c->hi);
  upper[0] = c->L;
  upper[1] = c->H;
  if (c->cell > 0) { /* after -box_length/-box_height: square cells of the target size */
    scene->mesh_n[0] = (PetscInt)PetscMax(1.0, PetscFloorReal(c->L / c->cell + 0.5));
    scene->mesh_n[1] = (PetscInt)PetscMax(1.0, PetscFloorReal(c->H / c->cell + 0.5));
  }
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  if (c->quasistatic) PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_BODY_FORCE | SLUMP_EFFECT_FREE_SURFACE));
  else PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_INERTIA | SLUMP_EFFECT_CONVECTION | SLUMP_EFFECT_BODY_FORCE | SLUMP_EFFECT_FREE_SURFACE));
  PetscCall(SlumpProblemSetDensity(prob, rho));
  PetscCall(SlumpProblemSetBodyForce(prob, 0.0, -c->g));
  /* the box: symmetry axis on the left, free slip on the right and the top;
     the floor last so that it owns the bottom corners */
  PetscCall(SlumpProblemAddFreeSlipBC(prob, "left"));
  PetscCall(SlumpProblemAddFreeSlipBC(prob, "right"));
  PetscCall(SlumpProblemAddFreeSlipBC(prob, "top"));
  switch (c->floor) {
  case FLOOR_SLIP:
    PetscCall(SlumpProblemAddVelocityBC(prob, "floor", "bottom", 1, &cy, SlumpZeroVelocity, NULL, NULL));
    break;
  case FLOOR_NOSLIP:
    PetscCall(SlumpProblemAddVelocityBC(prob, "floor", "bottom", 0, NULL, SlumpZeroVelocity, NULL, NULL));
    break;
  case FLOOR_NAVIER:
    PetscCall(SlumpProblemAddFrictionBC(prob, "bottom", SLUMP_WALL_NAVIER, c->fcoeff, 0.0));
    break;
  case FLOOR_COULOMB:
    PetscCall(SlumpProblemAddFrictionBC(prob, "bottom", SLUMP_WALL_COULOMB, c->fcoeff, c->freg));
    break;
  }
  {
    /* the closed box leaves the pressure to a constant: 0 at the top corner,
       in the air, so that pressure-dependent laws see the right pressure */
    const PetscReal ref[2] = {c->L, c->H};
    PetscCall(SlumpProblemSetPressureReference(prob, ref));
  }
  PetscCall(SlumpProblemSetTwoPhase(prob, rho_a, eta_a, 1.5));
  PetscCall(SlumpLevelSetCreate(prob, ColumnPhi, c, &ls));
  PetscCall(SlumpLevelSetSetReinitType(ls, "redistance"));
  if (c->reinit_every > 0) PetscCall(SlumpLevelSetSetReinitEvery(ls, c->reinit_every));
  /* the transport loses volume at first order in h (42 x 44 cells: -2 % by
     t = 0.2 s in dam_break); restore it after each reinitialisation */
  PetscCall(SlumpLevelSetSetVolumeCorrection(ls, PETSC_TRUE));
  {
    const PetscReal gauges[2] = {0.0, c->L};
    PetscCall(SlumpLevelSetSetGauges(ls, 2, gauges));
  }
  PetscCall(SlumpLevelSetSetSurfaceFeed(ls, c->surface_feed));
  if (c->supg_speed > 0) PetscCall(SlumpLevelSetSetSUPGSpeed(ls, c->supg_speed));
  PetscCall(SlumpLevelSetSetFromOptions(ls));
  scene->steady  = PETSC_FALSE;
  scene->results = Results;
  PetscCall(SlumpSceneAddParameter(scene, "column_width", c->ri));
  PetscCall(SlumpSceneAddParameter(scene, "column_height", c->hi));
  PetscCall(SlumpSceneAddParameter(scene, "aspect_ratio", c->hi / c->ri));
  PetscCall(SlumpSceneAddParameter(scene, "floor", (PetscReal)fl));
  if (c->floor >= FLOOR_NAVIER) PetscCall(SlumpSceneAddParameter(scene, "floor_friction", c->fcoeff));
  if (c->floor == FLOOR_COULOMB) PetscCall(SlumpSceneAddParameter(scene, "floor_friction_delta", c->freg));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_DamBreak(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  ColumnCtx    *c;
  SlumpRheology rheo;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->ri      = 0.114;
  c->hi      = 0.114;
  c->L       = 0.42;
  c->H       = 0.44;
  c->g       = 9.81;
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologySetType(rheo, SLUMP_RHEOLOGY_NEWTONIAN));
  PetscCall(SlumpRheologySetParameter(rheo, "viscosity", 1.0));
  scene->tfinal           = 0.3;
  scene->dtout            = 0.02;
  scene->arrest_threshold = 0.0;
  scene->mesh_n[0]        = 42;
  scene->mesh_n[1]        = 44;
  c->floor           = FLOOR_SLIP;
  PetscCall(ColumnSetUp(scene, prob, comm, c, 1000.0, 1.0, 1e-3));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_BinghamDamBreak(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  ColumnCtx    *c;
  SlumpRheology rheo;
  PetscReal     re = 1e-3, bn = 0.1;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->ri      = 1.0;
  c->hi      = 1.0;
  c->L       = 4.0;
  c->H       = 1.5;
  PetscOptionsBegin(comm, NULL, "Scene bingham_dam_break", "");
  PetscCall(PetscOptionsReal("-re", "Reynolds number rho^2 g h_i^3 / eta_p^2 (the thesis' Re, velocity scale rho g h_i^2/eta_p)", "", re, &re, NULL));
  PetscCall(PetscOptionsReal("-bn", "Bingham number tau0 / (rho g h_i)", "", bn, &bn, NULL));
  PetscOptionsEnd();
  PetscCheck(re >= 0, comm, PETSC_ERR_USER_INPUT, "-re must be >= 0 (0: quasi-static, no inertia); got %g", (double)re);
  PetscCheck(bn >= 0, comm, PETSC_ERR_USER_INPUT, "-bn must be >= 0; got %g", (double)bn);
  /* viscous units: the weight rho g = 1, the inertia Re; at Re = 0 the
     inertia is off and the density only weighs (rho = g = 1) */
  c->quasistatic = re == 0 ? PETSC_TRUE : PETSC_FALSE;
  c->g           = c->quasistatic ? 1.0 : 1.0 / re;
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologySetType(rheo, SLUMP_RHEOLOGY_PAPANASTASIOU));
  PetscCall(SlumpRheologySetParameter(rheo, "viscosity", 1.0));
  PetscCall(SlumpRheologySetParameter(rheo, "yield_stress", bn));
  PetscCall(SlumpRheologySetParameter(rheo, "m", 1e3));
  scene->tfinal           = 2000.0;
  scene->dtout            = 10.0;
  scene->arrest_threshold = 2e-4;
  /* the air's velocity (density 1e-6, viscosity 1e-6) follows the
     reinitialised interface at once; restarting at the last step failed the
     error test ten times (IDA_ERR_FAIL at t = 0.91 on 40 x 15 cells) */
  scene->restart_step     = 1e-2;
  scene->rtol             = 1e-3;
  scene->atol             = 1e-5;
  scene->mesh_n[0]        = 80;
  scene->mesh_n[1]        = 30;
  c->floor                = FLOOR_NAVIER;
  c->fcoeff               = 1e4;
  if (c->quasistatic) {
    /* velocity and pressure algebraic: every stage is a Papanastasiou
       Stokes solve, which IDA's modified Newton did not converge (IDA_CONV_FAIL
       at t = 0.26 on 40 x 15); KINSOL's line search needs the exact Jacobian,
       so the SUPG tau is smoothed below 1e-3 (velocities are ~0.1 at first,
       the arrest threshold's shear rate is 2e-4) */
    scene->linesearch = PETSC_TRUE;
    c->supg_speed     = 1e-3;
  }
  PetscCall(ColumnSetUp(scene, prob, comm, c, c->quasistatic ? 1.0 : re, c->quasistatic ? 1e-3 : 1e-3 * re, 1e-6));
  PetscCall(SlumpSceneAddParameter(scene, "re", re));
  PetscCall(SlumpSceneAddParameter(scene, "bn", bn));
  PetscFunctionReturn(0);
}

/* Granular column collapse with the mu(I) rheology (Lagree, Staron & Popinet,
   J. Fluid Mech. 2011, as in Riber's thesis sec. 4.3.1), dimensionless with
   h_i, sqrt(g h_i), sqrt(h_i/g) and the grain density: h_i = 1,
   r_i = 1/a, d = 1/sqrt(a N) for N grains; mu_s = 0.32, delta_mu = 0.28,
   I0 = 0.4; ||gdot||_min = 1e-2, eta_min = 1e-4 (the thesis' choices);
   air density 1e-3, viscosity 1e-4. The friction law holds up to the zero
   contour (viscosity Heaviside shifted by one half-width). The floor is
   rough: regularised Coulomb friction mu_w = mu_s + delta_mu = 0.6 (as
   strong as the material at its most mobile), delta = 1e-2; -floor
   noslip|slip|navier and -floor_friction, -floor_friction_delta for others.
   IDA tolerances rtol 1e-3, atol 1e-4; arrest when the material's mean
   shear rate falls below 0.05 (it creeps at ~2.5 gdot_min once at rest).
   The box is long enough for `margin` times the thesis' run-out fit
   (r_f - r_i)/r_i = 1.72 a^0.97 (a <= 7), 2.96 a^0.69 (a > 7), taken at the
   effective aspect ratio a_eff (a, or (h_i + h_r)/r_i for a chute):
   margin 1.5 for a collapse, 3 for a chute (in 2-D a column dropped from
   h_r = h_i at a = 1 reached the end of a box of margin 1.5). */
/* The thesis' fits of the run-out (r_f - r_i)/r_i: 2-D (sec. 4.3.1, with
   Lagree et al.'s parameters) 1.72 a^0.97 (a <= 7), 2.96 a^0.69; 3-D
   (eq. 4.20, with Jop et al.'s mu_s = 0.38, I0 = 0.279) 1.2 a (a < 2.7),
   1.93 a^0.54. */
static PetscReal RunoutFit(PetscBool axi, PetscReal a)
{
  if (axi) return a < 2.7 ? 1.2 * a : 1.93 * PetscPowReal(a, 0.54);
  return a <= 7 ? 1.72 * PetscPowReal(a, 0.97) : 2.96 * PetscPowReal(a, 0.69);
}

static PetscErrorCode MuIColumn(SlumpScene scene, SlumpProblem prob, MPI_Comm comm, ColumnCtx *c, PetscReal a, PetscReal grains, PetscReal h, PetscReal a_eff, PetscReal margin)
{
  SlumpRheology rheo;
  PetscFunctionBeginUser;
  PetscCheck(a > 0, comm, PETSC_ERR_USER_INPUT, "-aspect_ratio must be positive; got %g", (double)a);
  PetscCheck(grains >= 0, comm, PETSC_ERR_USER_INPUT, "-grains must be positive; got %g", (double)grains);
  PetscCheck(h > 0, comm, PETSC_ERR_USER_INPUT, "-cell_size must be positive; got %g", (double)h);
  if (grains == 0) {
    if (PetscAbsReal(a - 0.5) < 1e-12) grains = 3407;
    else if (PetscAbsReal(a - 1.42) < 1e-12) grains = 6041;
    else if (PetscAbsReal(a - 6.26) < 1e-12) grains = 6036;
    else grains = 6000;
  }
  c->hi         = 1.0;
  c->ri         = 1.0 / a;
  c->g          = 1.0;
  PetscCall(SlumpSceneGeometry(prob, comm, 0, &c->axi));
  {
    const PetscReal fit_eff = RunoutFit(c->axi, a_eff);
    c->runout_fit           = RunoutFit(c->axi, a);
    c->L                    = PetscCeilReal((c->ri * (1.0 + margin * fit_eff) + 0.5) / h) * h;
  }
  c->H      = PetscCeilReal(1.25 / h) * h;
  c->floor  = FLOOR_COULOMB;
  c->fcoeff = 0.6;
  c->freg   = 1e-2;
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologySetType(rheo, "mui_thesis"));
  PetscCall(SlumpRheologySetParameter(rheo, "mu_s", 0.32));
  PetscCall(SlumpRheologySetParameter(rheo, "delta_mu", 0.28));
  PetscCall(SlumpRheologySetParameter(rheo, "I0", 0.4));
  PetscCall(SlumpRheologySetParameter(rheo, "d", 1.0 / PetscSqrtReal(a * grains)));
  PetscCall(SlumpRheologySetParameter(rheo, "rho", 1.0));
  PetscCall(SlumpRheologySetParameter(rheo, "gdot_min", 1e-2));
  PetscCall(SlumpRheologySetParameter(rheo, "eta_min", 1e-4));
  scene->tfinal           = scene->t0 + 8.0;
  scene->dtout            = 0.25;
  scene->arrest_threshold = 5e-2; /* mean |gdot| peaks at ~0.7 and creeps at ~2.5 gdot_min once arrested */
  scene->rtol             = 1e-3;
  scene->atol             = 1e-4;
  c->cell                 = h;
  /* the friction law holds up to the zero contour (see SlumpProblemSetTwoPhaseViscosityShift) */
  PetscCall(SlumpProblemSetTwoPhaseViscosityShift(prob, 1.0));
  PetscCall(ColumnSetUp(scene, prob, comm, c, 1.0, 1e-3, 1e-4));
  PetscCall(SlumpSceneAddParameter(scene, "grains", grains));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_ColumnCollapse(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  ColumnCtx *c;
  PetscReal  a = 0.5, grains = 0.0, h = 0.05;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  PetscOptionsBegin(comm, NULL, "Scene column_collapse", "");
  PetscCall(PetscOptionsReal("-aspect_ratio", "Aspect ratio a = h_i/r_i of the column", "", a, &a, NULL));
  PetscCall(PetscOptionsReal("-grains", "Number of grains N of the discrete reference (grain diameter 1/sqrt(a N); default: 3407, 6041, 6036 for a = 0.5, 1.42, 6.26, else 6000)", "", grains, &grains, NULL));
  PetscCall(PetscOptionsReal("-cell_size", "Target cell size of the default mesh, in units of h_i", "", h, &h, NULL));
  PetscOptionsEnd();
  PetscCall(MuIColumn(scene, prob, comm, c, a, grains, h, a, 1.5));
  PetscFunctionReturn(0);
}

/* column_chute: the mu(I) column of column_collapse released from a height
   h_r above the floor (Riber's thesis sec. 4.3.3, in 2-D). The free fall is
   not simulated: the run starts at the impact, t0 = sqrt(2 h_r/g), with the
   column on the floor and the material moving down at the impact velocity
   v = sqrt(2 g h_r) (the air at rest). The consistent initialisation
   projects that velocity onto the divergence-free fields that respect the
   walls, with the density as weight: this is the impulsive pressure of the
   impact, and the kinetic energy it removes is the energy lost at impact.
   Options: -release_height h_r (in h_i; default 0.5), -aspect_ratio (1),
   -grains, -cell_size as column_collapse. Results add the impact velocity,
   the impact time and the kinetic energy just before and just after the
   impact; run-out_fit_thesis is the collapse fit at a (not a_r). */
typedef struct {
  ColumnCtx c; /* first: the collapse routines see a ColumnCtx */
  PetscReal hr, v;
} ChuteCtx;

static PetscErrorCode ChuteVelocity(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const ChuteCtx *ch = (const ChuteCtx *)ctx;
  PetscScalar     phi;
  PetscCall(ColumnPhi(dim, t, x, 1, &phi, (void *)&ch->c));
  u[0] = 0.0;
  u[1] = PetscRealPart(phi) < 0 ? -ch->v : 0.0;
  return 0;
}

static PetscErrorCode ChuteResults(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  ChuteCtx *ch = (ChuteCtx *)scene->ctx;
  PetscFunctionBeginUser;
  PetscCall(Results(scene, prob, t, X));
  PetscCall(SlumpSceneAddResult(scene, "impact_velocity", ch->v));
  PetscCall(SlumpSceneAddResult(scene, "t_impact", scene->t0));
  PetscCall(SlumpSceneAddResult(scene, "kinetic_energy_before_impact", 0.5 * ch->c.ri * ch->c.hi * ch->v * ch->v));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_ColumnChute(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  ChuteCtx *ch;
  PetscReal a = 1.0, grains = 0.0, h = 0.05, hr = 0.5;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&ch));
  scene->ctx = ch;
  PetscOptionsBegin(comm, NULL, "Scene column_chute", "");
  PetscCall(PetscOptionsReal("-aspect_ratio", "Aspect ratio a = h_i/r_i of the column", "", a, &a, NULL));
  PetscCall(PetscOptionsReal("-release_height", "Release height h_r of the column's base above the floor, in units of h_i", "", hr, &hr, NULL));
  PetscCall(PetscOptionsReal("-grains", "Number of grains N (grain diameter 1/sqrt(a N); default 6000)", "", grains, &grains, NULL));
  PetscCall(PetscOptionsReal("-cell_size", "Target cell size of the default mesh, in units of h_i", "", h, &h, NULL));
  PetscOptionsEnd();
  PetscCheck(hr >= 0, comm, PETSC_ERR_USER_INPUT, "-release_height must be >= 0; got %g", (double)hr);
  ch->hr    = hr;
  ch->v     = PetscSqrtReal(2.0 * hr); /* g = 1 */
  scene->t0 = PetscSqrtReal(2.0 * hr);
  /* the spreading film thins fast after the impact: every 20 steps the
     volume drifted by 2.1 % (a = 1, h_r = 0.25, cells of about 0.1), every
     10 by 1.7 % */
  ch->c.reinit_every = 10;
  PetscCall(MuIColumn(scene, prob, comm, &ch->c, a, grains, h, (1.0 + hr) * a, 3.0));
  if (hr > 0) PetscCall(SlumpProblemSetInitialVelocity(prob, ChuteVelocity, ch));
  scene->results = ChuteResults;
  PetscCall(SlumpSceneAddParameter(scene, "release_height", hr));
  PetscCall(SlumpSceneAddParameter(scene, "aspect_ratio_release", (1.0 + hr) * a));
  PetscFunctionReturn(0);
}

/* chupin_column: the Drucker-Prager collapses of Chupin, Dubois & Phan
   (2019 slides; REFERENCES.md), in SI units: a column 0.20 m wide of height
   0.14 m (-column_height 0.40 for the tall one), grains rho = 1500 kg/m^3
   with a viscous part eta = 0.5 Pa s and friction mu_f = tan 24 deg
   (-friction_angle 28 for the other material), yield stress mu_f p
   (dp_bercovier, eps = 1e-2 1/s); air rho = 1, eta = 1e-5; g = 9.81.
   Floor: Coulomb friction tan 24 deg (-wall rough, default) or tan 17 deg
   (-wall smooth), delta = 1e-3 m/s. Box r_i + 4 h_i long, 1.25 h_i high,
   cells of h_i/10 (-cell_size in metres). Arrest when the material's mean
   shear rate falls below 0.2 1/s (it peaks at ~10 1/s; eps sets the creep).
   -plasticity pl: the slides' lithostatic model (PL), yield stress
   mu_f p_L with p_L = rho_s g (H - y) instead of mu_f p (litho_bercovier).
   The slides do not say what H is once the column deforms. With pl, H is
   the current height h(x) of the free surface above the point (from the
   level set, updated after every step): p_L is the weight of the material
   column above, the shallow-layer reading. With pl_fixed, H is the
   column's initial height h_i everywhere and at all times. */
typedef enum { WALL_ROUGH, WALL_SMOOTH } WallKind;
static const char *const Walls[] = {"rough", "smooth"};
typedef enum { PLASTICITY_DP, PLASTICITY_PL, PLASTICITY_PL_FIXED } PlasticityKind;
static const char *const Plasticities[] = {"dp", "pl", "pl_fixed"};

PetscErrorCode SlumpSceneCreate_ChupinColumn(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  ColumnCtx    *c;
  SlumpRheology rheo;
  PetscReal     hi = 0.14, angle = 24.0, cell = 0.0;
  PetscInt      wall = WALL_ROUGH, plast = PLASTICITY_DP;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  PetscOptionsBegin(comm, NULL, "Scene chupin_column", "");
  PetscCall(PetscOptionsEList("-plasticity", "Yield stress: dp (Drucker-Prager, mu_f p), pl (lithostatic, mu_f rho g (h(x) - y) below the current surface h) or pl_fixed (mu_f rho g (h_i - y))", "", Plasticities, 3, Plasticities[plast], &plast, NULL));
  PetscCall(PetscOptionsReal("-column_height", "Initial height h_i of the column, m (0.14 or 0.40 in the slides)", "", hi, &hi, NULL));
  PetscCall(PetscOptionsReal("-friction_angle", "Internal friction angle of the grains, degrees (24 or 28)", "", angle, &angle, NULL));
  PetscCall(PetscOptionsEList("-wall", "Floor: rough (Coulomb tan 24 deg) or smooth (tan 17 deg)", "", Walls, 2, Walls[wall], &wall, NULL));
  PetscCall(PetscOptionsReal("-cell_size", "Target cell size of the default mesh, m (default h_i/10)", "", cell, &cell, NULL));
  PetscOptionsEnd();
  PetscCheck(hi > 0, comm, PETSC_ERR_USER_INPUT, "-column_height must be positive; got %g", (double)hi);
  PetscCheck(angle > 0 && angle < 90, comm, PETSC_ERR_USER_INPUT, "-friction_angle must lie in (0, 90) degrees; got %g", (double)angle);
  PetscCheck(cell >= 0, comm, PETSC_ERR_USER_INPUT, "-cell_size must be positive; got %g", (double)cell);
  c->ri     = 0.20;
  c->hi     = hi;
  c->g      = 9.81;
  c->L      = c->ri + 4.0 * hi;
  c->H      = 1.25 * hi;
  c->cell   = cell > 0 ? cell : hi / 10.0;
  c->floor  = FLOOR_COULOMB;
  c->fcoeff = PetscTanReal((wall == WALL_ROUGH ? 24.0 : 17.0) * PETSC_PI / 180.0);
  c->freg   = 1e-3;
  PetscCall(SlumpProblemGetRheology(prob, &rheo));
  PetscCall(SlumpRheologySetType(rheo, plast == PLASTICITY_DP ? "dp_bercovier" : "litho_bercovier"));
  c->surface_feed = plast == PLASTICITY_PL ? PETSC_TRUE : PETSC_FALSE;
  if (plast != PLASTICITY_DP) {
    PetscCall(SlumpRheologySetParameter(rheo, "density", 1500.0));
    PetscCall(SlumpRheologySetParameter(rheo, "gravity", 9.81));
    PetscCall(SlumpRheologySetParameter(rheo, "height", hi));
  }
  PetscCall(SlumpRheologySetParameter(rheo, "viscosity", 0.5));
  PetscCall(SlumpRheologySetParameter(rheo, "mu", PetscTanReal(angle * PETSC_PI / 180.0)));
  PetscCall(SlumpRheologySetParameter(rheo, "eps", 1e-2));
  scene->tfinal           = 2.0;
  scene->dtout            = 0.05;
  scene->arrest_threshold = 0.2;
  scene->rtol             = 1e-3;
  scene->atol             = 1e-4;
  PetscCall(SlumpProblemSetTwoPhaseViscosityShift(prob, 1.0));
  /* the air (rho 1, eta 1e-5) is nearly inviscid: with rho u.grad u alone a
     weakly divergence-free velocity fed it energy until IDA failed (pl, at
     t = 0.85 s on cells of 0.028 m) */
  PetscCall(SlumpProblemSetConvectionForm(prob, SLUMP_CONVECTION_SKEW));
  PetscCall(ColumnSetUp(scene, prob, comm, c, 1500.0, 1.0, 1e-5));
  PetscCall(SlumpSceneAddParameter(scene, "friction_angle", angle));
  PetscCall(SlumpSceneAddParameter(scene, "wall_friction", c->fcoeff));
  PetscCall(SlumpSceneAddParameter(scene, "plasticity", (PetscReal)plast));
  PetscFunctionReturn(0);
}
