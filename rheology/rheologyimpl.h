/* Private: the rheology object. */
#pragma once

#include "slumprheology.h"
#include "slumppointwise.h"

#define SLUMP_RHEOLOGY_MAX_PARAM 12

typedef struct {
  const char *name;   /* "viscosity"                               */
  const char *option; /* "-rheology_viscosity"                     */
  const char *help;
  PetscReal   value;
  PetscReal   lower;  /* value must be > lower (strict) or >= lower */
  PetscBool   strict;
} SlumpRheologyParam;

typedef struct {
  PetscErrorCode (*check)(SlumpRheology);   /* cross-parameter checks, optional */
  PetscErrorCode (*plugviscosity)(SlumpRheology, PetscReal p, PetscReal *eta);
} SlumpRheologyOps;

struct _p_SlumpRheology {
  MPI_Comm               comm;
  char                   type[64];
  SlumpRheologyOps       ops;
  SlumpViscosityKernel   kernel;
  SlumpRheologyPointwise pointwise;
  PetscInt               nparam;
  SlumpRheologyParam     param[SLUMP_RHEOLOGY_MAX_PARAM];
  PetscInt               ireg;          /* regularisation parameter, or -1 */
  PetscBool              reg_larger_stiffer;
};

/* Used by implementations: declare a parameter (keeps a value already set by name). */
PETSC_INTERN PetscErrorCode SlumpRheologyAddParameter(SlumpRheology, const char name[], const char option[], const char help[], PetscReal value, PetscReal lower, PetscBool strict);

PETSC_INTERN PetscErrorCode SlumpRheologyCreate_Newtonian(SlumpRheology);
PETSC_INTERN PetscErrorCode SlumpRheologyCreate_Papanastasiou(SlumpRheology);
PETSC_INTERN PetscErrorCode SlumpRheologyCreate_Bercovier(SlumpRheology);
PETSC_INTERN PetscErrorCode SlumpRheologyCreate_BinghamSimple(SlumpRheology);
