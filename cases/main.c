/* slump: viscoplastic and dense granular flows that slow down and stop.
 *   slump -scene list
 *   slump -scene couette_cessation [-options_file FILE] [options]
 *   slump -help */
#include "slumpscene.h"
#include <slepcsys.h>
#include <unistd.h>

static const char help[] = "slump: viscoplastic (Bingham) and granular flows that slow down and stop.\n"
                           "  -scene NAME        scene to run (-scene list lists them)\n"
                           "  -options_file FILE options from a file\n"
                           "  -output_dir DIR    output directory (default out/<scene>)\n"
                           "  -output_fields     write XDMF/HDF5 fields at output times (default true)\n\n";

int main(int argc, char **argv)
{
  PetscErrorCode ierr;
  /* An unreadable options file is refused before PETSc starts, in one sentence. */
  for (int i = 1; i < argc; ++i) {
    if (!strcmp(argv[i], "-options_file")) {
      if (i + 1 >= argc || access(argv[i + 1], R_OK)) {
        fprintf(stderr, "slump: error: cannot read the options file '%s' (-options_file); give the path of a readable file\n", i + 1 < argc ? argv[i + 1] : "");
        return 1;
      }
    }
  }
  ierr = SlepcInitialize(&argc, &argv, NULL, help);
  if (ierr) return 1;
  PetscCall(PetscPushErrorHandler(SlumpErrorHandler, NULL));
  /* after PETSc's own handlers: SIGINT/SIGTERM end the run after its step */
  PetscCall(SlumpInstallInterruptHandlers());
  ierr = SlumpRun(PETSC_COMM_WORLD);
  PetscCall(PetscPopErrorHandler());
  SlumpOutputUnlockAll();
  if (ierr && SlumpHasUnclosableOutput()) {
    /* the error is reported and the other outputs are closed */
    fflush(stdout);
    fflush(stderr);
    _exit(1);
  }
  if (ierr) {
    /* Collective errors reach every rank; finalise cleanly and fail
       (128 + the signal for an interrupted run, as a shell reports it). */
    const int sig = SlumpInterruptSignal();
    SlepcFinalize();
    return ierr == PETSC_ERR_SIG && sig ? 128 + sig : 1;
  }
  PetscCall(SlepcFinalize());
  return 0;
}
