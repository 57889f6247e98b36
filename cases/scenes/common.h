/* Private helpers shared by the scene files. */
#pragma once
#include "slumpscene.h"
#include "slumppointwise.h"

static inline PetscErrorCode SlumpZeroVelocity(PetscInt dim, PetscReal t, const PetscReal x[], PetscInt Nc, PetscScalar u[], void *ctx)
{
  for (PetscInt c = 0; c < Nc; ++c) u[c] = 0.0;
  return 0;
}
