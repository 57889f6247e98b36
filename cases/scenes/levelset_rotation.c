/* A circle or Zalesak's slotted disc carried by a solid-body rotation of the
 * unit square, u = 2 pi (0.5 - y, x - 0.5): after one revolution (t = 1)
 * the shape is back where it started. The verification of level-set
 * transport and reinitialisation: the velocity is prescribed (transport
 * formulation), only phi is solved for.
 *   -shape circle|slotted_disc   (centre (0.5, 0.75), radius 0.15; slot 0.05 wide, 0.25 deep)
 *   -revolutions r               (t_final = r)
 * Results: area drift, |grad phi| deviation in a 3-cell band (after a final
 * reinitialisation for the between-step methods), reinitialisations. */
#include "common.h"
#include "slumpinterface.h"

typedef struct {
  PetscInt  shape; /* 0 circle, 1 slotted disc */
  PetscReal xc, yc, R, slot_w, slot_top;
} RotCtx;

/* Solid-body rotation inside r = 0.42 (the shapes stay within r = 0.4),
   brought to rest smoothly by r = 0.5: purely azimuthal, so divergence
   free, and no inflow through the walls (an inflow boundary without a
   condition on phi lets spurious zero contours in at the corners). */
static PetscErrorCode Rotation(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const PetscReal dx = x[0] - 0.5, dy = x[1] - 0.5, r = PetscSqrtReal(dx * dx + dy * dy), r0 = 0.42, r1 = 0.5;
  PetscReal       c = 1.0;
  if (r >= r1) c = 0.0;
  else if (r > r0) {
    const PetscReal s = (r - r0) / (r1 - r0);
    c                 = 1.0 - s * s * (3.0 - 2.0 * s);
  }
  u[0] = -2.0 * PETSC_PI * c * dy;
  u[1] = 2.0 * PETSC_PI * c * dx;
  return 0;
}

/* signed distance to the axis-aligned box [x0, x1] x [y0, y1] (negative inside) */
static PetscReal BoxDistance(PetscReal x, PetscReal y, PetscReal x0, PetscReal x1, PetscReal y0, PetscReal y1)
{
  const PetscReal dx = PetscMax(x0 - x, x - x1), dy = PetscMax(y0 - y, y - y1);
  if (dx <= 0 && dy <= 0) return PetscMax(dx, dy);
  return PetscSqrtReal(PetscSqr(PetscMax(dx, 0.0)) + PetscSqr(PetscMax(dy, 0.0)));
}

static PetscErrorCode Phi0(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  const RotCtx   *c = (const RotCtx *)ctx;
  const PetscReal d = PetscSqrtReal(PetscSqr(x[0] - c->xc) + PetscSqr(x[1] - c->yc)) - c->R;
  if (c->shape == 0) u[0] = d;
  else u[0] = PetscMax(d, -BoxDistance(x[0], x[1], c->xc - 0.5 * c->slot_w, c->xc + 0.5 * c->slot_w, c->yc - 2.0 * c->R, c->slot_top));
  return 0;
}

static PetscErrorCode Results(SlumpScene scene, SlumpProblem prob, PetscReal t, Vec X)
{
  SlumpLevelSet ls;
  PetscReal     V0, V, drift, mean, max;
  PetscInt      nre;
  PetscBool     changed;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemGetLevelSet(prob, &ls));
  PetscCall(SlumpLevelSetComputeVolume(ls, t, X, &V));
  PetscCall(SlumpLevelSetGetStats(ls, &V0, NULL, &drift, &nre));
  PetscCall(SlumpSceneAddResult(scene, "area0", V0));
  PetscCall(SlumpSceneAddResult(scene, "area_error", V / V0 - 1.0));
  PetscCall(SlumpSceneAddResult(scene, "area_drift_max", drift));
  PetscCall(SlumpLevelSetComputeGradientDeviation(ls, t, X, 3.0, &mean, &max));
  PetscCall(SlumpSceneAddResult(scene, "grad_dev_mean", mean));
  PetscCall(SlumpSceneAddResult(scene, "grad_dev_max", max));
  /* the same in a band of one cell (a filtered level set is a distance
     only well inside its width E) */
  PetscCall(SlumpLevelSetComputeGradientDeviation(ls, t, X, 1.0, &mean, &max));
  PetscCall(SlumpSceneAddResult(scene, "grad_dev_mean_1cell", mean));
  PetscCall(SlumpSceneAddResult(scene, "grad_dev_max_1cell", max));
  /* the band after one more application of the between-step method (the
     state itself is left as it ends) */
  {
    Vec Y;
    PetscCall(VecDuplicate(X, &Y));
    PetscCall(VecCopy(X, Y));
    PetscCall(SlumpLevelSetReinitialise(ls, t, Y, &changed));
    PetscCall(SlumpLevelSetComputeGradientDeviation(ls, t, Y, 3.0, &mean, &max));
    PetscCall(SlumpSceneAddResult(scene, "grad_dev_mean_reinit", mean));
    PetscCall(SlumpSceneAddResult(scene, "grad_dev_max_reinit", max));
    PetscCall(SlumpLevelSetComputeVolume(ls, t, Y, &V));
    PetscCall(SlumpSceneAddResult(scene, "area_error_reinit", V / V0 - 1.0));
    PetscCall(VecDestroy(&Y));
  }
  PetscCall(SlumpLevelSetGetStats(ls, NULL, NULL, NULL, &nre));
  PetscCall(SlumpSceneAddResult(scene, "reinitialisations", nre));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpSceneCreate_LevelSetRotation(SlumpScene scene, SlumpProblem prob, MPI_Comm comm)
{
  RotCtx       *c;
  SlumpLevelSet ls;
  PetscReal     lower[2] = {0.0, 0.0}, upper[2] = {1.0, 1.0}, rev = 1.0;
  const char   *shapes[] = {"circle", "slotted_disc"};
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&c));
  scene->ctx = c;
  c->xc      = 0.5;
  c->yc      = 0.75;
  c->R       = 0.15;
  c->slot_w  = 0.05;
  c->slot_top = 0.85;
  PetscOptionsBegin(comm, NULL, "Scene levelset_rotation", "");
  PetscCall(PetscOptionsEList("-shape", "Shape carried by the rotation", "", shapes, 2, shapes[0], &c->shape, NULL));
  PetscCall(PetscOptionsReal("-revolutions", "Number of revolutions (t_final)", "", rev, &rev, NULL));
  PetscOptionsEnd();
  PetscCheck(rev > 0, comm, PETSC_ERR_USER_INPUT, "-revolutions must be positive; got %g", (double)rev);
  scene->steady    = PETSC_FALSE;
  scene->tfinal    = rev;
  scene->dtout     = 0.25;
  scene->mesh_n[0] = 64;
  scene->mesh_n[1] = 64;
  scene->results   = Results;
  PetscCall(SlumpSceneSetMesh(scene, prob, comm, lower, upper));
  PetscCall(SlumpProblemSetFormulation(prob, SLUMP_FORMULATION_TRANSPORT));
  PetscCall(SlumpProblemSetEffects(prob, SLUMP_EFFECT_FREE_SURFACE));
  PetscCall(SlumpProblemSetPrescribedVelocity(prob, Rotation, NULL, NULL));
  PetscCall(SlumpLevelSetCreate(prob, Phi0, c, &ls));
  PetscCall(SlumpLevelSetSetFromOptions(ls));
  PetscCall(SlumpSceneAddParameter(scene, "shape", (PetscReal)c->shape));
  PetscCall(SlumpSceneAddParameter(scene, "revolutions", rev));
  PetscFunctionReturn(0);
}
