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
  SlumpPlasticKernel     plastic; /* NULL: no yield term */
  SlumpRheologyPointwise pointwise;
  PetscInt               nparam;
  SlumpRheologyParam     param[SLUMP_RHEOLOGY_MAX_PARAM];
  PetscInt               ireg;          /* regularisation parameter, or -1 */
  PetscBool              reg_larger_stiffer;
};

/* Regularised 1/||gdot|| of a yield term and its derivative:
   simple 1/(g + e), Bercovier-Engelman 1/sqrt(g^2 + e^2),
   Papanastasiou (1 - exp(-m g))/g (r = m). */
typedef enum { SLUMP_REG_SIMPLE, SLUMP_REG_BERCOVIER, SLUMP_REG_PAPANASTASIOU } SlumpRegKind;

static inline void SlumpYieldShape(SlumpRegKind kind, PetscReal r, PetscReal g, PetscReal *R, PetscReal *dR)
{
  if (kind == SLUMP_REG_SIMPLE) {
    *R  = 1.0 / (g + r);
    *dR = -(*R) * (*R);
  } else if (kind == SLUMP_REG_BERCOVIER) {
    const PetscReal q = g * g + r * r, sq = PetscSqrtReal(q);
    *R  = 1.0 / sq;
    *dR = -g / (q * sq);
  } else {
    const PetscReal x = r * g;
    PetscReal       f, df;
    if (x < 1e-3) {
      f  = 1.0 - x / 2.0 + x * x / 6.0 - x * x * x / 24.0;
      df = -0.5 + x / 3.0 - x * x / 8.0;
    } else {
      const PetscReal e = PetscExpReal(-x), om = -expm1(-x);
      f  = om / x;
      df = (e * x - om) / (x * x);
    }
    *R  = r * f;
    *dR = r * r * df;
  }
}

/* Smooth positive part of the pressure (Chauchat & Medale eq. 16):
   P = (p + sqrt(p^2 + d^2))/2, or max(p, 0) when d = 0. */
static inline void SlumpPositivePressure(PetscReal p, PetscReal d, PetscReal *P, PetscReal *dP)
{
  if (d > 0) {
    const PetscReal s = PetscSqrtReal(p * p + d * d);
    if (p >= 0) {
      *P  = 0.5 * (p + s);
      *dP = 0.5 * (1.0 + p / s);
    } else { /* rationalised: no cancellation as p -> -infinity */
      *P  = 0.5 * d * d / (s - p);
      *dP = *P / s;
    }
  } else {
    *P  = p > 0 ? p : 0.0;
    *dP = p > 0 ? 1.0 : 0.0;
  }
}

/* A plastic kernel (slumprheology.h) with a constant yield stress
   tau_y = params[ITAU] and the regularisation KIND of parameter params[IREG]. */
#define SLUMP_DEFINE_PLASTIC_CONSTANT(NAME, KIND, ITAU, IREG) \
  static inline void NAME(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *ty, PetscReal *R, PetscReal *dR) \
  { \
    *ty = PetscRealPart(prm[ITAU]); \
    SlumpYieldShape(KIND, PetscRealPart(prm[IREG]), g, R, dR); \
  }

/* Used by implementations: declare a parameter (keeps a value already set by name). */
PETSC_INTERN PetscErrorCode SlumpRheologyAddParameter(SlumpRheology, const char name[], const char option[], const char help[], PetscReal value, PetscReal lower, PetscBool strict);

PETSC_INTERN PetscErrorCode SlumpRheologyAddRegularisation(SlumpRheology, SlumpRegKind);
PETSC_INTERN PetscErrorCode SlumpRheologyCreate_Newtonian(SlumpRheology);
PETSC_INTERN PetscErrorCode SlumpRheologyCreate_Papanastasiou(SlumpRheology);
PETSC_INTERN PetscErrorCode SlumpRheologyCreate_Bercovier(SlumpRheology);
PETSC_INTERN PetscErrorCode SlumpRheologyCreate_BinghamSimple(SlumpRheology);
PETSC_INTERN PetscErrorCode SlumpRheologyRegister_HerschelBulkley(void);
PETSC_INTERN PetscErrorCode SlumpRheologyRegister_DruckerPrager(void);
PETSC_INTERN PetscErrorCode SlumpRheologyRegister_MuI(void);
