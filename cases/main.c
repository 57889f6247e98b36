/* slump: viscoplastic and dense granular flows that slow down and stop.
 *   slump -scene list
 *   slump -scene couette_cessation [-options_file FILE] [options]
 *   slump -help [petsc] */
#include "slumpscene.h"
#include <slepcsys.h>
#include <unistd.h>
#include <ctype.h>
#include <sys/stat.h>

static const char help_text[] = "slump: viscoplastic (Bingham) and granular flows that slow down and stop.\n"
                           "  -scene NAME        scene to run (-scene list lists them)\n"
                           "  -options_file FILE options from a file\n"
                           "  -output_dir DIR    output directory (default out/<scene>)\n"
                           "  -output_fields     write XDMF/HDF5 fields at output times (default true)\n\n";

/* An options file must be text of "-name [value]" lines ('#' comments). */
static int CheckOptionsFile(const char *path)
{
  struct stat st;
  FILE       *fp;
  char        line[4096];
  int         n = 0;
  if (stat(path, &st) || !S_ISREG(st.st_mode) || access(path, R_OK)) {
    fprintf(stderr, "slump: error: cannot read the options file '%s' (-options_file); give the path of a readable file\n", path);
    return 1;
  }
  fp = fopen(path, "r");
  if (!fp) {
    fprintf(stderr, "slump: error: cannot read the options file '%s' (-options_file); give the path of a readable file\n", path);
    return 1;
  }
  while (fgets(line, sizeof(line), fp)) {
    char *c = line;
    ++n;
    for (char *q = line; *q; ++q)
      if ((unsigned char)*q < 0x20 && *q != '\n' && *q != '\r' && *q != '\t') {
        fprintf(stderr, "slump: error: the options file '%s' (-options_file) is not text (line %d holds control bytes); give a file of '-name value' lines\n", path, n);
        fclose(fp);
        return 1;
      }
    while (*c == ' ' || *c == '\t') ++c;
    if (*c == '#' || *c == '\n' || *c == '\r' || !*c) continue;
    if (*c != '-') {
      c[strcspn(c, "\r\n")] = 0;
      fprintf(stderr, "slump: error: line %d of the options file '%s' (-options_file) is not an option ('%.40s'); each line holds -name [value], '#' starts a comment\n", n, path, c);
      fclose(fp);
      return 1;
    }
  }
  fclose(fp);
  return 0;
}

static int IsNumber(const char *s)
{
  if (*s == '-' || *s == '+') ++s;
  return isdigit((unsigned char)*s) || *s == '.';
}

int main(int argc, char **argv)
{
  PetscErrorCode ierr;
  int            help = 0; /* -help: slump's options; -help petsc: PETSc's too */
  for (int i = 1; i < argc; ++i) {
    if (!strcmp(argv[i], "-help") || !strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      if (i + 1 < argc && !strcmp(argv[i + 1], "petsc")) {
        argv[i]     = (char *)"-help";
        argv[i + 1] = (char *)"-options_ignore_unused"; /* PETSc lists what it reads */
        ++i;
      } else {
        help = 1;
        for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
        --argc;
        --i;
      }
    }
  }
  /* Positional arguments are refused: PETSc would ignore them. A token not
     starting with a dash (or a negative number) is the value of the option
     before it. An unreadable options file is refused before PETSc starts. */
  for (int i = 1; i < argc; ++i) {
    const int isopt = argv[i][0] == '-' && !IsNumber(argv[i]);
    if (!isopt && (i == 1 || argv[i - 1][0] != '-' || IsNumber(argv[i - 1]))) {
      fprintf(stderr, "slump: error: unexpected argument '%s'; options start with a dash (a scene is given as -scene %s)\n", argv[i], argv[i]);
      return 1;
    }
    if (!strcmp(argv[i], "-options_file")) {
      if (i + 1 >= argc) {
        fprintf(stderr, "slump: error: -options_file needs the path of a readable file\n");
        return 1;
      }
      if (CheckOptionsFile(argv[i + 1])) return 1;
    }
  }
  ierr = SlepcInitialize(&argc, &argv, NULL, help_text);
  if (ierr) return 1;
  PetscCall(PetscPushErrorHandler(SlumpErrorHandler, NULL));
  if (help) {
    PetscCall(SlumpPrintHelp(PETSC_COMM_WORLD));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "\nScenes:\n"));
    PetscCall(SlumpSceneView(PETSC_COMM_WORLD));
    PetscCall(SlepcFinalize());
    return 0;
  }
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
