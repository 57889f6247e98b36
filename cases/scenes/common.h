/* Private helpers shared by the scene files. */
#pragma once
#include "slumpscene.h"
#include "slumppointwise.h"

static inline PetscErrorCode SlumpZeroVelocity(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  for (PetscInt c = 0; c < Nc; ++c) u[c] = 0.0;
  return 0;
}

/* The scene's mesh (-mesh_file or the rectangle [lower, upper]) handed to the problem. */
static inline PetscErrorCode SlumpSceneSetMesh(SlumpScene scene, SlumpProblem prob, MPI_Comm comm, const PetscReal lower[2], const PetscReal upper[2])
{
  DM dm;
  PetscFunctionBeginUser;
  PetscCall(SlumpSceneCreateMesh(scene, comm, lower, upper, &dm));
  PetscCall(SlumpProblemSetMesh(prob, dm));
  PetscCall(DMDestroy(&dm));
  PetscFunctionReturn(0);
}

/* Fully developed channel flow along x: v = 0 and zero normal traction at
   both ends ("left", "right"). */
static inline PetscErrorCode SlumpSceneChannelEnds(SlumpProblem prob)
{
  const PetscInt compy = 1;
  PetscFunctionBeginUser;
  PetscCall(SlumpProblemAddVelocityBC(prob, "inlet_v", "left", 1, &compy, SlumpZeroVelocity, NULL, NULL));
  PetscCall(SlumpProblemAddVelocityBC(prob, "outlet_v", "right", 1, &compy, SlumpZeroVelocity, NULL, NULL));
  PetscFunctionReturn(0);
}
