/* The values given to adhbem's numeric options, checked before PETSc reads them: PETSc's own
   message for a value that is not a number ("Input string abc has no numeric value") names no
   option, it reads NaN as a real, and it casts an integer beyond PetscInt's range (99999999999)
   to another integer without a word. adhbem reads its numeric options through AdhOptionsReal(),
   AdhOptionsInt() and their arrays (sysimpl.h), which check first; what range the option's meaning allows is checked after
   the read, where the meaning is. */
#include <errno.h>
#include <math.h>
#include "sys/sysimpl.h"

/* PETSc's words for its defaults, which its readers take for a number (-2 or -1). */
static PetscBool PETScWord(const char *s)
{
  const char *const words[] = {"DEFAULT", "PETSC_DEFAULT", "DECIDE", "PETSC_DECIDE", "DETERMINE", "PETSC_DETERMINE", "UNLIMITED", "PETSC_UNLIMITED"};

  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(words); k++)
    if (!strcasecmp(s, words[k])) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* One item of the value: NULL when it is a number of the kind, else why not. */
static const char *Refused(const char *item, AdhNumberKind kind)
{
  char *end;

  if (!item[0]) return "an empty value";
  if (PETScWord(item)) return NULL;
  errno = 0;
  if (kind == ADH_NUMBER_INT) {
    const long long v = strtoll(item, &end, 10);
    if (*end) return "not an integer";
    if (errno == ERANGE || v > PETSC_MAX_INT || v < -PETSC_MAX_INT) return sizeof(PetscInt) == 8 ? "beyond the 64-bit integers" : "beyond the integers of this PETSc build (32-bit indices: at most 2147483647)";
  } else {
    const double v = strtod(item, &end);
    if (*end && strcmp(end, ".")) return "not a real number"; /* PETSc prints reals as "1." and "inf." */
    if (isnan(v)) return "NaN, not a value";
    if (errno == ERANGE && isfinite(v) && v != 0) return "not a real number";
    if (errno == ERANGE && !isfinite(v)) return "beyond the largest double (write inf for an infinite value)";
  }
  return NULL;
}

/*
  AdhOptionsCheckNumber_Private - an error naming the option, unless the value given to name (under
  prefix), each item of a comma-separated list, is a number of the kind; nothing when the option is
  not given.
*/
PetscErrorCode AdhOptionsCheckNumber_Private(MPI_Comm comm, PetscOptions options, const char prefix[], const char name[], AdhNumberKind kind)
{
  char        value[PETSC_MAX_PATH_LEN] = "", item[PETSC_MAX_PATH_LEN];
  PetscBool   set;
  const char *p;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetString(options, prefix, name, value, sizeof(value), &set));
  if (!set) PetscFunctionReturn(0);
  PetscCheck(value[0], comm, PETSC_ERR_ARG_WRONG, "-%s%s needs a value (%s)", prefix ? prefix : "", name + 1, kind == ADH_NUMBER_INT ? "an integer" : "a real number");
  p = value;
  while (1) {
    size_t      n = strcspn(p, ",");
    const char *why;
    char       *s = item, *e;
    PetscCall(PetscStrncpy(item, p, PetscMin(n + 1, sizeof(item))));
    while (*s == ' ') s++;
    for (e = s + strlen(s); e > s && e[-1] == ' '; e--) e[-1] = 0;
    why = Refused(s, kind);
    PetscCheck(!why, comm, PETSC_ERR_ARG_WRONG, "-%s%s: expected %s, got '%s' (%s)", prefix ? prefix : "", name + 1, kind == ADH_NUMBER_INT ? "an integer" : "a real number", s, why);
    if (!p[n]) break;
    p += n + 1;
  }
  PetscFunctionReturn(0);
}
