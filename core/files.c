/* Output integrity: checked text files, the output directory's lock, and
 * the interruption flag set by SIGINT/SIGTERM.
 *
 * Text outputs (series.csv, steps.csv, interface.csv, ...) are line
 * buffered, so every completed row is in the file even if the process is
 * killed, and every write is checked: a full disk or a vanished directory is
 * an error naming the file, not a silently short file. Files that must be
 * whole or absent (summary.csv) are written under a temporary name and
 * renamed when complete. */
#include "slumpimpl.h"
#include <errno.h>
#include <stdarg.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

int SlumpFileOpen(const char path[], FILE **fp)
{
  errno = 0;
  *fp   = fopen(path, "w");
  if (!*fp) return errno ? errno : EIO;
  if (setvbuf(*fp, NULL, _IOLBF, 0)) {
    fclose(*fp);
    *fp = NULL;
    return EIO;
  }
  return 0;
}

int SlumpFilePrintf(FILE *fp, const char fmt[], ...)
{
  va_list ap;
  int     n;
  if (!fp) return 0;
  errno = 0;
  va_start(ap, fmt);
  n = vfprintf(fp, fmt, ap);
  va_end(ap);
  if (n < 0 || ferror(fp)) return errno ? errno : EIO;
  return 0;
}

int SlumpFileClose(FILE **fp)
{
  int err = 0;
  if (!*fp) return 0;
  errno = 0;
  if (fflush(*fp) || ferror(*fp)) err = errno ? errno : EIO;
  if (fclose(*fp) && !err) err = errno ? errno : EIO;
  *fp = NULL;
  return err;
}

PetscErrorCode SlumpFileCheck(MPI_Comm comm, int err, const char path[])
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_INT, MPI_MAX, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "Cannot write %s: %s; free space or choose another -output_dir", path, strerror(err));
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpFileCommit(MPI_Comm comm, int err, const char tmp[], const char path[])
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    if (err) unlink(tmp);
    else if (rename(tmp, path)) {
      err = errno ? errno : EIO;
      unlink(tmp);
    }
  }
  PetscCall(SlumpFileCheck(comm, err, path));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------ lock */
/* DIR/.slump.lock holds "pid host" of the run writing into DIR. A lock whose
   process is gone (same host, kill(pid, 0) fails with ESRCH) is stale and
   taken over; a live one refuses the directory unless overwrite is set. */
#define SLUMP_MAX_LOCKS 8
static char held_lock[SLUMP_MAX_LOCKS][PETSC_MAX_PATH_LEN];

static int TryLock(const char lock[], char owner[], size_t len, PetscBool overwrite)
{
  char host[256] = "", buf[512];
  int  fd;
  gethostname(host, sizeof(host) - 1);
  for (int attempt = 0; attempt < 2; ++attempt) {
    fd = open(lock, O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd >= 0) {
      int n = snprintf(buf, sizeof(buf), "%ld %s\n", (long)getpid(), host);
      int w = (int)write(fd, buf, (size_t)n);
      close(fd);
      return w == n ? 0 : EIO;
    }
    if (errno != EEXIST) return errno;
    {
      long  pid   = -1;
      char  other[256] = "";
      FILE *fp    = fopen(lock, "r");
      if (fp) {
        if (fscanf(fp, "%ld %255s", &pid, other) < 1) pid = -1;
        fclose(fp);
      }
      snprintf(owner, len, "process %ld on %s", pid, other[0] ? other : "an unknown host");
      if (!overwrite && pid > 0 && (strcmp(other, host) || !(kill((pid_t)pid, 0) && errno == ESRCH))) return EBUSY;
      unlink(lock); /* stale, unreadable, or taken over */
    }
  }
  return EBUSY;
}

PetscErrorCode SlumpOutputLock(MPI_Comm comm, const char dir[], PetscBool overwrite)
{
  PetscMPIInt rank;
  int         err = 0;
  char        lock[PETSC_MAX_PATH_LEN], owner[320] = "";
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscSNPrintf(lock, sizeof(lock), "%s/.slump.lock", dir));
  if (!rank) err = TryLock(lock, owner, sizeof(owner), overwrite);
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(owner, sizeof(owner), MPI_CHAR, 0, comm));
  PetscCheck(err != EBUSY, comm, PETSC_ERR_FILE_OPEN, "The output directory %s is in use by another run (%s, lock file %s); give another -output_dir, or -output_overwrite to take it over", dir, owner, lock);
  PetscCheck(!err, comm, PETSC_ERR_FILE_OPEN, "Cannot create the lock file %s: %s; check -output_dir", lock, strerror(err));
  if (!rank)
    for (int k = 0; k < SLUMP_MAX_LOCKS; ++k)
      if (!held_lock[k][0]) {
        PetscCall(PetscStrncpy(held_lock[k], lock, sizeof(held_lock[k])));
        break;
      }
  PetscFunctionReturn(0);
}

PetscErrorCode SlumpOutputUnlock(MPI_Comm comm, const char dir[])
{
  PetscMPIInt rank;
  char        lock[PETSC_MAX_PATH_LEN];
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(lock, sizeof(lock), "%s/.slump.lock", dir));
  for (int k = 0; k < SLUMP_MAX_LOCKS; ++k)
    if (!strcmp(held_lock[k], lock)) {
      unlink(lock);
      held_lock[k][0] = 0;
    }
  PetscFunctionReturn(0);
}

void SlumpOutputUnlockAll(void)
{
  for (int k = 0; k < SLUMP_MAX_LOCKS; ++k)
    if (held_lock[k][0]) {
      unlink(held_lock[k]);
      held_lock[k][0] = 0;
    }
}

/* An HDF5 file whose close failed (its metadata could not be flushed: a full
   disk) stays registered in HDF5 1.10, which then crashes while closing it
   again inside MPI_Finalize; the program ends without finalising instead. */
static PetscBool unclosable = PETSC_FALSE;

void SlumpSetUnclosableOutput(void)
{
  unclosable = PETSC_TRUE;
}

PetscBool SlumpHasUnclosableOutput(void)
{
  return unclosable;
}

/* ------------------------------------------------------------ interrupts */
static volatile sig_atomic_t interrupt_signal = 0;

static void OnSignal(int sig)
{
  /* the second signal ends the process at once */
  if (interrupt_signal) {
    signal(sig, SIG_DFL);
    raise(sig);
    return;
  }
  interrupt_signal = sig;
}

PetscErrorCode SlumpInstallInterruptHandlers(void)
{
  struct sigaction sa;
  PetscFunctionBeginUser;
  memset(&sa, 0, sizeof(sa));
  sa.sa_handler = OnSignal;
  sigemptyset(&sa.sa_mask);
  PetscCheck(!sigaction(SIGINT, &sa, NULL) && !sigaction(SIGTERM, &sa, NULL), PETSC_COMM_SELF, PETSC_ERR_SYS, "Cannot install the SIGINT/SIGTERM handlers");
  PetscFunctionReturn(0);
}

int SlumpInterruptSignal(void)
{
  return (int)interrupt_signal;
}
