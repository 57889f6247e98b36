/* Options given but not read are errors: a misspelt option must not run
 * silently with its default.
 *
 * Before the run (everything is set up, nothing is written) the options
 * database is compared with SlumpOptionTable, the options slump reads, and
 * with the prefixes of the PETSc objects it creates (KSP, PC, Mat, DM, FE,
 * SLEPc's EPS): an unknown name, an option of a PETSc object slump does not
 * create (SNES, TS, ...), an option of the table given without its value,
 * and a non-finite number are refused with one sentence. After the run,
 * an option nothing read (a known option this scene or these settings do
 * not use, a solver option of an unused KSP) is refused the same way.
 * -options_ignore_unused allows options nothing reads. */
#include "slumpscene.h"
#include <ctype.h>
#include <strings.h>

/* PETSc's own options, read at initialisation or at finalisation. */
static const char *const PetscGlobal[] = {"help", "version", "options_", "log_", "malloc", "memory_", "objects_", "info", "on_error_", "no_signal_handler", "fp_trap", "check_pointer", "viewer_", "skip_petscrc", "nox", "display", "saws", "mpi_", "stop_for_debugger", "start_in_debugger", "debugger", "error_output", "use_gpu_aware_mpi", "device_", "checkstack", "sleep", "get_total_flops", "history", "python", "citations", "slepc_", "petsc_", "tmp", "shared_tmp", "not_shared_tmp", "use_", "compare", "vecscatter_", NULL};
/* Prefixes of the PETSc and SLEPc objects slump creates, whose options are
   read when the object is set up (possibly during the run). */
static const char *const Created[] = {"ksp_", "pc_", "mat_", "sub_", "fieldsplit_", "mg_", "dm_", "petscspace_", "petscdualspace_", "petscfe_", "petscpartitioner_", "petscsection_", "vec_", "sf_", "eps_", "st_", "bv_", "ds_", "rg_", "fn_", "is_", "mat_mumps_", "pc_hypre_", "alg2_ksp_", "alg2_pc_", "alg2_mat_", "ic_ksp_", "ic_pc_", "ic_mat_", "ic_sub_", "ic_fieldsplit_", NULL};
/* Objects slump does not create: its nonlinear solvers are KINSOL and IDA. */
static const char *const NotCreated[][2] = {
  {"snes_",           "SNES (slump's Newton solver is KINSOL: -newton_* options)"                    },
  {"ts_",             "TS (slump's time integrators are IDA and its own BDF2: -time_* and -ida_*)"},
  {"tao_",            "Tao"                                                                           },
  {"pep_",            "SLEPc PEP"                                                                     },
  {"nep_",            "SLEPc NEP"                                                                     },
  {"svd_",            "SLEPc SVD"                                                                     },
  {"mfn_",            "SLEPc MFN"                                                                     },
  {"characteristic_", "Characteristic"                                                                },
  {"linesearch_",     "SNESLineSearch (use -newton_linesearch)"                                       },
};
/* PETSc options worth suggesting for a misspelling. */
static const char *const CommonPetsc[] = {"-ksp_type", "-pc_type", "-ksp_rtol", "-ksp_atol", "-ksp_max_it", "-ksp_monitor", "-ksp_view", "-ksp_converged_reason", "-pc_factor_mat_solver_type", "-log_view", "-options_left", "-options_file", "-help", "-info", "-malloc_debug", "-mat_mumps_icntl_14", "-dm_view", "-options_ignore_unused", NULL};

static PetscBool HasPrefix(const char name[], const char *const list[])
{
  for (PetscInt i = 0; list[i]; ++i)
    if (!strncmp(name, list[i], strlen(list[i]))) return PETSC_TRUE;
  return PETSC_FALSE;
}

static const SlumpOptionInfo *Lookup(const char name[])
{
  for (const SlumpOptionInfo *o = SlumpOptionTable; o->name; ++o)
    if (!strcmp(o->name + 1, name)) return o;
  return NULL;
}

PetscBool SlumpOptionKnown(const char name[])
{
  if (name[0] == '-') ++name;
  return Lookup(name) || HasPrefix(name, Created) ? PETSC_TRUE : PETSC_FALSE;
}

/* Levenshtein distance, for "did you mean". */
static int Distance(const char *a, const char *b)
{
  int la = (int)strlen(a), lb = (int)strlen(b), prev[128], cur[128];
  if (la > 126 || lb > 126) return 1000;
  for (int j = 0; j <= lb; ++j) prev[j] = j;
  for (int i = 1; i <= la; ++i) {
    cur[0] = i;
    for (int j = 1; j <= lb; ++j) {
      int c = prev[j - 1] + (a[i - 1] != b[j - 1]);
      c     = PetscMin(c, prev[j] + 1);
      cur[j] = PetscMin(c, cur[j - 1] + 1);
    }
    for (int j = 0; j <= lb; ++j) prev[j] = cur[j];
  }
  return prev[lb];
}

static const char *Closest(const char name[])
{
  const char *best = NULL;
  int         dbest = 1000, limit = PetscMax(2, (int)strlen(name) / 4);
  for (const SlumpOptionInfo *o = SlumpOptionTable; o->name; ++o) {
    int d = Distance(name, o->name + 1);
    if (d < dbest) dbest = d, best = o->name;
  }
  for (PetscInt i = 0; CommonPetsc[i]; ++i) {
    int d = Distance(name, CommonPetsc[i] + 1);
    if (d < dbest) dbest = d, best = CommonPetsc[i];
  }
  return dbest <= limit ? best : NULL;
}

static PetscBool IsNumber(const char *s)
{
  if (!s || !*s) return PETSC_FALSE;
  if (*s == '-' || *s == '+') ++s;
  return isdigit((unsigned char)*s) || *s == '.' ? PETSC_TRUE : PETSC_FALSE;
}

/* Every value in the database: non-finite numbers and table options of a
   kind that needs a value given without one. PetscOptionsGetAll lists the
   options as "-name [value] -name [value] ..." without marking them used. */
static PetscErrorCode CheckValues(MPI_Comm comm)
{
  char *all, *tok, *save = NULL, name[256] = "";
  PetscBool pending = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  for (tok = strtok_r(all, " ", &save);; tok = strtok_r(NULL, " ", &save)) {
    const PetscBool isname = tok && tok[0] == '-' && !IsNumber(tok) ? PETSC_TRUE : PETSC_FALSE;
    if (pending && (!tok || isname)) {
      /* the previous option had no value */
      const SlumpOptionInfo *o = Lookup(name + 1);
      if (o && strcmp(o->kind, "bool") && strcmp(o->kind, "flag")) {
        const char *what = !strcmp(o->kind, "real") ? "a number" : !strcmp(o->kind, "int") ? "an integer" : !strcmp(o->kind, "choice") ? "one of its choices (slump -help lists them)" : "a value";
        PetscCall(PetscFree(all));
        SETERRQ(comm, PETSC_ERR_USER_INPUT, "Option %s needs %s", name, what);
      }
    }
    if (!tok) break;
    if (isname) {
      PetscCall(PetscStrncpy(name, tok, sizeof(name)));
      pending = PETSC_TRUE;
      continue;
    }
    pending = PETSC_FALSE;
    {
      /* a logical option's value: what PetscOptionsStringToBool takes (its
         own error does not name the option) */
      const SlumpOptionInfo *o = Lookup(name + 1);
      if (o && !strcmp(o->kind, "bool")) {
        static const char *const words[] = {"true", "false", "yes", "no", "on", "off", "1", "0"};
        PetscBool                ok      = PETSC_FALSE;
        for (size_t k = 0; k < sizeof(words) / sizeof(words[0]) && !ok; ++k) ok = strcasecmp(tok, words[k]) ? PETSC_FALSE : PETSC_TRUE;
        if (!ok) {
          char msg[1200];
          PetscCall(PetscSNPrintf(msg, sizeof(msg), "Option %s must be true or false (also yes/no, on/off, 1/0); got %s", name, tok));
          PetscCall(PetscFree(all));
          SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s", msg);
        }
      }
    }
    {
      /* a value: each of its comma-, colon- or space-separated numbers */
      char  buf[1024], *piece, *s2 = NULL;
      PetscCall(PetscStrncpy(buf, tok, sizeof(buf)));
      for (piece = strtok_r(buf, ",:", &s2); piece; piece = strtok_r(NULL, ",:", &s2)) {
        char  *end;
        double v = strtod(piece, &end);
        if (end != piece && !*end && !isfinite(v)) {
          char msg[1200];
          PetscCall(PetscSNPrintf(msg, sizeof(msg), "Option %s must be a finite number; got %s", name, tok));
          PetscCall(PetscFree(all));
          SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s", msg);
        }
        /* products and squares of larger numbers overflow in the kernels */
        if (end != piece && !*end && (fabs(v) > 1e100 || (v != 0 && fabs(v) < 1e-100))) {
          char msg[1200];
          PetscCall(PetscSNPrintf(msg, sizeof(msg), "Option %s = %s is outside the magnitudes slump computes with (0 or 1e-100 to 1e100)", name, tok));
          PetscCall(PetscFree(all));
          SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s", msg);
        }
      }
    }
  }
  PetscCall(PetscFree(all));
  PetscFunctionReturn(0);
}

/* Groups of options read only when the run's solvers are created. */
PetscBool SlumpOptionReadLate(const char name[])
{
  PetscBool early = PETSC_FALSE;
  if (HasPrefix(name, Created)) return PETSC_TRUE;
  for (const SlumpOptionInfo *o = SlumpOptionTable; o->name; ++o)
    if (!strcmp(o->name + 1, name)) {
      if (o->late || !strcmp(o->group, "Newton (KINSOL)") || !strcmp(o->group, "Steady solve") || !strcmp(o->group, "Exact method (ALG2)")) return PETSC_TRUE;
      early = PETSC_TRUE;
    }
  return !early;
}

PetscErrorCode SlumpOptionsCheck(MPI_Comm comm, SlumpOptionsStage stage)
{
  PetscInt  n;
  char    **names, **values;
  PetscBool ignore = PETSC_FALSE;
  char      msg[1024] = "";
  PetscFunctionBeginUser;
  /* option -options_ignore_unused: allow options nothing reads (a shared options file, say) */
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-options_ignore_unused", &ignore, NULL));
  if (stage == SLUMP_OPTIONS_START) PetscCall(CheckValues(comm));
  if (ignore) PetscFunctionReturn(0);
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n && !msg[0]; ++i) {
    const char *nm = names[i];
    if (HasPrefix(nm, PetscGlobal)) continue;
    if (stage == SLUMP_OPTIONS_END) {
      PetscCall(PetscSNPrintf(msg, sizeof(msg), "Option -%s was given but not read by this run (this scene and these settings do not use it); the results are written, but remove it or give -options_ignore_unused", nm));
      break;
    }
    if (stage == SLUMP_OPTIONS_SETUP) {
      /* set up, nothing written: a known option of the scene, the mesh, the
         rheology, the problem or the integrator is read by now */
      if (!SlumpOptionReadLate(nm)) PetscCall(PetscSNPrintf(msg, sizeof(msg), "Option -%s is not read by this run (this scene and these settings do not use it); remove it or give -options_ignore_unused", nm));
      continue;
    }
    if (SlumpOptionKnown(nm)) continue; /* read when its object is set up */
    for (size_t k = 0; k < sizeof(NotCreated) / sizeof(NotCreated[0]); ++k)
      if (!strncmp(nm, NotCreated[k][0], strlen(NotCreated[k][0]))) {
        PetscCall(PetscSNPrintf(msg, sizeof(msg), "Option -%s is an option of a PETSc %s, which slump does not create; remove it or give -options_ignore_unused", nm, NotCreated[k][1]));
        break;
      }
    if (!msg[0]) {
      const char *close = Closest(nm);
      if (close) PetscCall(PetscSNPrintf(msg, sizeof(msg), "Unknown option -%s (did you mean %s?); slump -help lists the options, -options_ignore_unused allows unknown ones", nm, close));
      else PetscCall(PetscSNPrintf(msg, sizeof(msg), "Unknown option -%s; slump -help lists the options, -options_ignore_unused allows unknown ones", nm));
    }
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscCheck(!msg[0], comm, PETSC_ERR_USER_INPUT, "%s", msg);
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpOptionsCheckName(MPI_Comm comm, const char what[], const char name[])
{
  const char *close;
  PetscFunctionBeginUser;
  if (name[0] == '-') ++name;
  if (SlumpOptionKnown(name)) PetscFunctionReturn(0);
  close = Closest(name);
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s: unknown option -%s%s%s%s; slump -help lists the options", what, name, close ? " (did you mean " : "", close ? close : "", close ? "?)" : "");
}

PetscErrorCode SlumpPrintHelp(MPI_Comm comm)
{
  const char *group = NULL;
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(comm, "slump %s: viscoplastic (Bingham, Herschel-Bulkley) and dense granular flows that slow down and stop.\n\n", SLUMP_VERSION_STRING));
  PetscCall(PetscPrintf(comm, "usage: slump -scene NAME [-options_file FILE] [-OPTION VALUE ...]\n       slump -scene list      the scenes\n       slump -help petsc      PETSc's and SLEPc's own options as well\n       slump -scene NAME -help petsc   every option the run would read, with its value\n"));
  PetscCall(PetscPrintf(comm, "Options nobody reads are errors unless -options_ignore_unused is given.\n"));
  for (const SlumpOptionInfo *o = SlumpOptionTable; o->name; ++o) {
    if (!group || strcmp(group, o->group)) {
      group = o->group;
      PetscCall(PetscPrintf(comm, "\n%s:\n", group));
    }
    PetscCall(PetscPrintf(comm, "  %-32s <%s> %s\n", o->name, o->kind, o->help));
  }
  PetscCall(PetscPrintf(comm, "\nLinear algebra: the PETSc options of the KSP, PC and Mat slump creates (-ksp_type, -pc_type, -pc_factor_mat_solver_type, -mat_mumps_icntl_14, ...).\n"));
  PetscFunctionReturn(0);
}
