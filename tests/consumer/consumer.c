/* A program outside the project linking the installed libslump through
 * pkg-config: evaluates the Papanastasiou viscosity at ||gdot|| = 1
 * (eta_p = 1, tau0 = 2, m = 10: eta = 1 + 2 (1 - e^-10)) and checks it. */
#include <slumprheology.h>

int main(int argc, char **argv)
{
  SlumpRheology r;
  PetscReal     eta;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(SlumpRheologyCreate(PETSC_COMM_WORLD, &r));
  PetscCall(SlumpRheologySetType(r, "papanastasiou"));
  PetscCall(SlumpRheologySetParameter(r, "yield_stress", 2.0));
  PetscCall(SlumpRheologySetParameter(r, "m", 10.0));
  PetscCall(SlumpRheologyEvaluate(r, 1.0, 0.0, &eta, NULL, NULL));
  PetscCall(SlumpRheologyDestroy(&r));
  PetscCall(PetscFinalize());
  if (PetscAbsReal(eta - (1.0 + 2.0 * (1.0 - PetscExpReal(-10.0)))) > 1e-14) {
    printf("consumer: eta expected %.15g, got %.15g\n", 1.0 + 2.0 * (1.0 - PetscExpReal(-10.0)), (double)eta);
    return 1;
  }
  return 0;
}
