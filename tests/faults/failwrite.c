/* A disk that fills up or fails, for the fault tests (LD_PRELOAD=failwrite.so): the writes to a
   file whose path contains $ADHBEM_FAULT_PATH fail with $ADHBEM_FAULT_ERRNO (ENOSPC, EIO) once
   $ADHBEM_FAULT_AFTER bytes have gone to such files (0: the first write fails). With ENOSPC a
   reservation (fallocate) that would go beyond those bytes fails too, as a full disk's does; with
   EIO it succeeds. With $ADHBEM_FAULT_OP=rename only a rename onto such a path fails (ENOSPC: a
   full directory). With $ADHBEM_FAULT_OP=stall the first write to such a file after
   $ADHBEM_FAULT_RENAMES renames onto such a path (checkpoints replaced) does not return: the
   process creates the file $ADHBEM_FAULT_MARK and waits to be killed, mid-write. Every other file
   is written as usual. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

static long long written; /* bytes written to matching files by this process */

static int Matches(int fd)
{
  const char *pattern = getenv("ADHBEM_FAULT_PATH");
  char        link[64], path[4096];
  ssize_t     n;

  if (!pattern || !pattern[0]) return 0;
  snprintf(link, sizeof(link), "/proc/self/fd/%d", fd);
  n = readlink(link, path, sizeof(path) - 1);
  if (n <= 0) return 0;
  path[n] = 0;
  return strstr(path, pattern) != NULL;
}

static int Errno(void)
{
  const char *e = getenv("ADHBEM_FAULT_ERRNO");
  return e && !strcmp(e, "EIO") ? EIO : ENOSPC;
}

static int RenameOnly(void)
{
  const char *op = getenv("ADHBEM_FAULT_OP");
  return op && !strcmp(op, "rename");
}

static int renames; /* renames onto matching paths by this process */

/* A write that never ends, once enough renames have happened: say so through the mark, then wait. */
static void Stall(int fd)
{
  const char *op = getenv("ADHBEM_FAULT_OP"), *after = getenv("ADHBEM_FAULT_RENAMES"), *mark = getenv("ADHBEM_FAULT_MARK");

  if (!op || strcmp(op, "stall") || !Matches(fd) || renames < (after ? atoi(after) : 0)) return;
  if (mark) close(open(mark, O_CREAT | O_WRONLY, 0644));
  for (;;) pause();
}

/* Whether `bytes` more to fd fail (setting errno); counted (count) when they do not. */
static int Fails(int fd, size_t bytes, int count)
{
  const char *after = getenv("ADHBEM_FAULT_AFTER");
  const char *op = getenv("ADHBEM_FAULT_OP");

  Stall(fd);
  if (RenameOnly() || (op && !strcmp(op, "stall")) || !Matches(fd)) return 0;
  if (written + (long long)bytes > (after ? atoll(after) : 0)) {
    errno = Errno();
    return 1;
  }
  if (count) written += (long long)bytes;
  return 0;
}

#define NEXT(name) static __typeof__(name) *next_##name; if (!next_##name) next_##name = (__typeof__(name) *)dlsym(RTLD_NEXT, #name)

ssize_t write(int fd, const void *buf, size_t n)
{
  NEXT(write);
  if (Fails(fd, n, 1)) return -1;
  return next_write(fd, buf, n);
}

ssize_t pwrite(int fd, const void *buf, size_t n, off_t off)
{
  NEXT(pwrite);
  if (Fails(fd, n, 1)) return -1;
  return next_pwrite(fd, buf, n, off);
}

ssize_t pwrite64(int fd, const void *buf, size_t n, off64_t off)
{
  NEXT(pwrite64);
  if (Fails(fd, n, 1)) return -1;
  return next_pwrite64(fd, buf, n, off);
}

static size_t Bytes(const struct iovec *iov, int cnt)
{
  size_t n = 0;
  for (int k = 0; k < cnt; k++) n += iov[k].iov_len;
  return n;
}

ssize_t writev(int fd, const struct iovec *iov, int cnt)
{
  NEXT(writev);
  if (Fails(fd, Bytes(iov, cnt), 1)) return -1;
  return next_writev(fd, iov, cnt);
}

ssize_t pwritev(int fd, const struct iovec *iov, int cnt, off_t off)
{
  NEXT(pwritev);
  if (Fails(fd, Bytes(iov, cnt), 1)) return -1;
  return next_pwritev(fd, iov, cnt, off);
}

/* A reservation on a full disk fails; on a failing one it does not (EIO comes with the write). */
int fallocate(int fd, int mode, off_t off, off_t len)
{
  NEXT(fallocate);
  if (Errno() == ENOSPC && Fails(fd, (size_t)len, 0)) return -1;
  return next_fallocate(fd, mode, off, len);
}

int fallocate64(int fd, int mode, off64_t off, off64_t len)
{
  NEXT(fallocate64);
  if (Errno() == ENOSPC && Fails(fd, (size_t)len, 0)) return -1;
  return next_fallocate64(fd, mode, off, len);
}

/* A full disk may have no room for a directory entry either. */
int rename(const char *from, const char *to)
{
  const char *pattern = getenv("ADHBEM_FAULT_PATH");
  NEXT(rename);
  if (pattern && pattern[0] && strstr(to, pattern)) renames++;
  if (RenameOnly() && pattern && pattern[0] && strstr(to, pattern)) {
    errno = ENOSPC;
    return -1;
  }
  return next_rename(from, to);
}
