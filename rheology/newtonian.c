/* Newtonian fluid: tau = eta gdot, eta constant (-rheology_viscosity). */
#include "rheologyimpl.h"

static inline void NewtonianKernel(const PetscScalar prm[], PetscReal g, PetscReal p, const PetscReal x[], PetscReal *eta, PetscReal *de_dg, PetscReal *de_dp, PetscReal *ty)
{
  *eta   = PetscRealPart(prm[0]);
  *de_dg = 0.0;
  *de_dp = 0.0;
  *ty    = 0.0;
}

SLUMP_RHEOLOGY_DEFINE_POINTWISE(Newtonian, NewtonianKernel, NULL)

PetscErrorCode SlumpRheologyCreate_Newtonian(SlumpRheology rheo)
{
  PetscFunctionBeginUser;
  PetscCall(SlumpRheologyAddParameter(rheo, "viscosity", "-rheology_viscosity", "Dynamic viscosity eta", 1.0, 0.0, PETSC_TRUE));
  rheo->kernel    = NewtonianKernel;
  rheo->pointwise = Newtonian_pointwise;
  PetscFunctionReturn(0);
}
