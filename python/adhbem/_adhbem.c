/* The C half of the Python layer: turns libadhbem objects into real petsc4py objects.
   PETSc errors become Python's exceptions (SetPythonError). */
#define PY_SSIZE_T_CLEAN
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <Python.h>
#include <petsc4py/petsc4py.h>
#include "adhbem.h"

/* PETSc errors become Python's own exceptions (ValueError, FileNotFoundError, MemoryError, ...)
   with PETSc's one-line message, as the executable prints it; the error code is kept as the
   exception's petsc_error_code. A handler of ours sits on PETSc's stack while libadhbem runs, to
   catch that message. -adh_traceback (an option in PETSc's database: `python job.py -adh_traceback`)
   prints PETSc's traceback of every frame as well, as it does for the executable. */
/* The messages of the errors raised since the outermost call began: the one whose code the call
   returns is the one to tell (a later error in a clean-up on the way out does not replace it). */
#define ADH_ERRORS 8
static char           ErrorTexts[ADH_ERRORS][1024];
static PetscErrorCode ErrorCodes[ADH_ERRORS];
static int            ErrorCount, CatchDepth;
static char           ErrorText[1024]; /* the one chosen */
static PetscErrorCode ErrorCode;

static PetscErrorCode CatchError(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p == PETSC_ERROR_INITIAL) {
    const int k   = ErrorCount < ADH_ERRORS ? ErrorCount++ : ADH_ERRORS - 1;
    ErrorCodes[k] = n;
    if (mess && mess[0]) snprintf(ErrorTexts[k], sizeof(ErrorTexts[k]), "%s", mess);
    else {
      const char *text = NULL;
      (void)PetscErrorMessage(n, &text, NULL);
      snprintf(ErrorTexts[k], sizeof(ErrorTexts[k]), "%s (in %s() at %s:%d)", text ? text : "unknown error", fun ? fun : "?", file ? file : "?", line);
    }
  }
  if (ctx) return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, mess, NULL);
  return n;
}

/* Calls nest (a Python monitor that calls back into the extension): only the outermost starts
   the record. */
static void CatchErrorsBegin(void)
{
  PetscBool traceback = PETSC_FALSE;
  if (CatchDepth++ == 0) ErrorCount = 0;
  (void)PetscOptionsGetBool(NULL, NULL, "-adh_traceback", &traceback, NULL);
  (void)PetscPushErrorHandler(CatchError, traceback ? (void *)1 : NULL);
}

static void CatchErrorsEnd(void)
{
  (void)PetscPopErrorHandler();
  CatchDepth--;
}

/* The message to tell for a call that returned n: the last error raised with that code, else the
   last one raised. */
static void ChooseError(PetscErrorCode n)
{
  int k = ErrorCount - 1;
  while (k >= 0 && ErrorCodes[k] != n) k--;
  if (k < 0) k = ErrorCount - 1;
  ErrorText[0] = 0;
  ErrorCode    = 0;
  if (k >= 0) {
    snprintf(ErrorText, sizeof(ErrorText), "%s", ErrorTexts[k]);
    ErrorCode = ErrorCodes[k];
  }
  if (!CatchDepth) ErrorCount = 0;
}

static PyObject *PythonExceptionType(PetscErrorCode n)
{
  switch (n) {
  case PETSC_ERR_MEM: return PyExc_MemoryError;
  case PETSC_ERR_FILE_OPEN: return PyExc_FileNotFoundError;
  case PETSC_ERR_FILE_READ:
  case PETSC_ERR_FILE_WRITE:
  case PETSC_ERR_SYS: return PyExc_OSError;
  case PETSC_ERR_SUP:
  case PETSC_ERR_SUP_SYS: return PyExc_NotImplementedError;
  case PETSC_ERR_INT_OVERFLOW: return PyExc_OverflowError;
  case PETSC_ERR_SIG: return PyExc_KeyboardInterrupt; /* a stop asked by SIGINT or SIGTERM: the results so far are written */
  case PETSC_ERR_ARG_SIZ:
  case PETSC_ERR_ARG_IDN:
  case PETSC_ERR_ARG_WRONG:
  case PETSC_ERR_ARG_OUTOFRANGE:
  case PETSC_ERR_ARG_NOTSAMETYPE:
  case PETSC_ERR_ARG_INCOMP:
  case PETSC_ERR_ARG_NULL:
  case PETSC_ERR_ARG_UNKNOWN_TYPE:
  case PETSC_ERR_FILE_UNEXPECTED: /* a file of the wrong content, as numpy.load says */
  case PETSC_ERR_USER_INPUT: return PyExc_ValueError;
  default: return PyExc_RuntimeError;
  }
}

/* A Python Solver's options live under a prefix of its own (adhbem7_): the user gave them without,
   so messages name them without (-adh_gamma, not -adhbem7_adh_gamma). */
static void StripSolverPrefix(char *text)
{
  char *p = text;
  while ((p = strstr(p, "-adhbem"))) {
    char *q = p + 7;
    while (*q >= '0' && *q <= '9') q++;
    if (q > p + 7 && *q == '_') memmove(p + 1, q + 1, strlen(q + 1) + 1);
    else p++;
  }
}

/* The Python exception of a failed call: an exception a Python callback raised (a monitor) is
   kept; otherwise the caught message, as the matching Python type. */
static void SetPythonError(PetscErrorCode n)
{
  PyObject *type, *value, *tb, *code;
  ChooseError(n);
  if (PyErr_Occurred()) return;
  if (!ErrorText[0]) {
    const char *text = NULL;
    (void)PetscErrorMessage(n, &text, NULL);
    snprintf(ErrorText, sizeof(ErrorText), "%s", text ? text : "unknown PETSc error");
  }
  StripSolverPrefix(ErrorText);
  /* PETSc refuses a value outside an enumeration's choices with PETSC_ERR_USER, the code of any
     user's error: the text tells it, and it is bad input */
  if ((ErrorCode ? ErrorCode : n) == PETSC_ERR_USER && !strncmp(ErrorText, "Unknown option ", 15) && strstr(ErrorText, "Available options")) PyErr_SetString(PyExc_ValueError, ErrorText);
  else PyErr_SetString(PythonExceptionType(ErrorCode ? ErrorCode : n), ErrorText);
  PyErr_Fetch(&type, &value, &tb);
  PyErr_NormalizeException(&type, &value, &tb);
  code = PyLong_FromLong((long)(ErrorCode ? ErrorCode : n));
  if (value && code) (void)PyObject_SetAttrString(value, "petsc_error_code", code);
  Py_XDECREF(code);
  PyErr_Restore(type, value, tb);
}

/* After CatchErrorsBegin, a call, CatchErrorsEnd: on error set the Python exception and return NULL. */
#define PyPetscRaise(ierr) \
  do { \
    if (ierr) { \
      SetPythonError(ierr); \
      return NULL; \
    } \
  } while (0)

/* Run a libadhbem call; on error set the Python exception and return NULL from the wrapper. */
#define PyPetscCall(...) \
  do { \
    PetscErrorCode ierr_; \
    CatchErrorsBegin(); \
    ierr_ = (__VA_ARGS__); \
    CatchErrorsEnd(); \
    if (ierr_) { \
      SetPythonError(ierr_); \
      return NULL; \
    } \
  } while (0)

static PyObject *py_compliance(PyObject *self, PyObject *args)
{
  PyObject   *pycomm;
  Py_ssize_t  Nx, Ny;
  double      Lx, Ly, Estar;
  const char *bname;
  AdhGrid     grid;
  AdhBoundary boundary;
  Mat         K;
  PyObject   *result;
  PetscBool   found = PETSC_FALSE;
  PetscInt    b;

  if (!PyArg_ParseTuple(args, "Onnddds", &pycomm, &Nx, &Ny, &Lx, &Ly, &Estar, &bname)) return NULL;
  for (b = 0; b < 2; b++)
    if (!strcmp(bname, AdhBoundaries[b])) { found = PETSC_TRUE; boundary = (AdhBoundary)b; }
  if (!found) {
    PyErr_Format(PyExc_ValueError, "boundary: unknown boundary mode '%s' (free or periodic)", bname);
    return NULL;
  }
  PyPetscCall(AdhGridCreate(PyPetscComm_Get(pycomm), &grid));
  {
    PetscErrorCode ierr;
    CatchErrorsBegin();
    ierr = AdhGridSetFromOptions(grid); /* the FFTW options; the sizes are the call's */
    if (!ierr) ierr = AdhGridSetSizes(grid, (PetscInt)Nx, (PetscInt)Ny, Lx, Ly);
    if (!ierr) ierr = MatCreateAdhCompliance(grid, Estar, boundary, &K);
    CatchErrorsEnd();
    (void)AdhGridDestroy(&grid); /* also on error: no grid leaks on bad input */
    PyPetscRaise(ierr);
  }
  result = PyPetscMat_New(K);
  PyPetscCall(MatDestroy(&K));
  return result;
}

/* A rough surface on a fresh Nx x Ny grid, from the options under prefix (set by __init__.py).
   The Vec has the grid's layout and block size Nx, so adhbem.gather(z, z) works; the grid itself is
   freed. */
static PyObject *py_rough_surface(PyObject *self, PyObject *args)
{
  PyObject      *pycomm, *result;
  Py_ssize_t     Nx, Ny;
  double         Lx, Ly;
  const char    *prefix;
  AdhGrid        grid;
  AdhSurface     s;
  Vec            z = NULL;
  PetscErrorCode ierr;

  if (!PyArg_ParseTuple(args, "Onndds", &pycomm, &Nx, &Ny, &Lx, &Ly, &prefix)) return NULL;
  PyPetscCall(AdhGridCreate(PyPetscComm_Get(pycomm), &grid));
  CatchErrorsBegin();
  ierr = AdhGridSetSizes(grid, (PetscInt)Nx, (PetscInt)Ny, Lx, Ly);
  if (!ierr) ierr = AdhSurfaceSetFromOptions(grid, prefix, &s);
  if (!ierr) ierr = AdhGridSetUp(grid);
  if (!ierr) ierr = AdhGridCreateVector(grid, &z);
  if (!ierr) ierr = AdhSurfaceGenerate(grid, &s, z);
  CatchErrorsEnd();
  if (ierr) { /* no grid or Vec leaks on bad input */
    (void)VecDestroy(&z);
    (void)AdhGridDestroy(&grid);
    PyPetscRaise(ierr);
  }
  PyPetscCall(AdhGridDestroy(&grid));
  result = Py_BuildValue("N{s:d,s:d,s:d,s:n,s:s,s:d,s:d,s:d,s:d,s:d,s:d,s:n}", PyPetscVec_New(z), "hurst", (double)s.hurst, "rolloff_wavelength", (double)s.used_rolloff_wavelength, "cutoff_wavelength", (double)s.used_cutoff_wavelength, "seed", (Py_ssize_t)s.seed,
                         "requested", s.rms_height != PETSC_DEFAULT ? "rms_height" : "rms_slope", "requested_value", (double)(s.rms_height != PETSC_DEFAULT ? s.rms_height : s.rms_slope != PETSC_DEFAULT ? s.rms_slope : 0.1),
                         "realised_rms_height", (double)s.realised_rms_height, "realised_rms_slope", (double)s.realised_rms_slope, "realised_mean", (double)s.realised_mean, "min_height", (double)s.min_height, "max_height", (double)s.max_height, "modes", (Py_ssize_t)s.modes);
  PyPetscCall(VecDestroy(&z));
  return result;
}

static PyObject *py_compliance_info(PyObject *self, PyObject *args)
{
  PyObject *pymat;
  PetscReal lmin, rho;
  PetscInt  count, single, Nx, Ny;
  Mat       K;

  if (!PyArg_ParseTuple(args, "O", &pymat)) return NULL;
  K = PyPetscMat_Get(pymat);
  if (!K) return NULL;
  PyPetscCall(MatAdhComplianceGetLambdaMin(K, &lmin));
  PyPetscCall(MatAdhComplianceGetRowNormBound(K, &rho));
  PyPetscCall(MatAdhComplianceGetMultCount(K, &count));
  PyPetscCall(MatAdhComplianceGetSingleMultCount(K, &single));
  PyPetscCall(MatAdhComplianceGetGridSize(K, &Nx, &Ny));
  return Py_BuildValue("{s:d,s:d,s:n,s:n,s:n,s:n}", "lambda_min", (double)lmin, "row_norm_bound", (double)rho, "mult_count", (Py_ssize_t)count, "single_mult_count", (Py_ssize_t)single, "Nx", (Py_ssize_t)Nx, "Ny", (Py_ssize_t)Ny);
}

/* y = R K R^T x for the set of x's nonzero local points, through MatAdhComplianceMultOnSet, in
   single precision or double (for the tests of the single-precision transforms). */
static PetscErrorCode MultOnNonzeros(Mat K, Vec x, PetscBool single, Vec *y)
{
  const PetscScalar *xa, *ca;
  PetscScalar       *ya, *xc;
  PetscInt           n, m = 0, k, *local;
  PetscBool          direct;
  Vec                xC, yC;
  PetscErrorCode     ierr;

  PetscFunctionBegin;
  PetscCall(MatAdhComplianceHasDirectLayout(K, &direct));
  PetscCheck(direct, PetscObjectComm((PetscObject)K), PETSC_ERR_ARG_WRONG, "compliance_mult_on_set needs a periodic compliance");
  PetscCall(VecGetLocalSize(x, &n));
  PetscCall(PetscMalloc1(n + 1, &local));
  PetscCall(VecGetArrayRead(x, &xa));
  for (k = 0; k < n; k++)
    if (xa[k] != 0.0) local[m++] = k;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, m, &xC));
  PetscCall(VecDuplicate(xC, &yC));
  PetscCall(VecGetArrayWrite(xC, &xc));
  for (k = 0; k < m; k++) xc[k] = xa[local[k]];
  PetscCall(VecRestoreArrayWrite(xC, &xc));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(MatAdhComplianceSetSinglePrecision(K, single));
  ierr = MatAdhComplianceMultOnSet(K, m, local, xC, yC);
  PetscCall(MatAdhComplianceSetSinglePrecision(K, PETSC_FALSE));
  PetscCall(ierr);
  PetscCall(VecDuplicate(x, y));
  PetscCall(VecSet(*y, 0.0));
  PetscCall(VecGetArray(*y, &ya));
  PetscCall(VecGetArrayRead(yC, &ca));
  for (k = 0; k < m; k++) ya[local[k]] = ca[k];
  PetscCall(VecRestoreArrayRead(yC, &ca));
  PetscCall(VecRestoreArray(*y, &ya));
  PetscCall(VecDestroy(&xC));
  PetscCall(VecDestroy(&yC));
  PetscCall(PetscFree(local));
  PetscFunctionReturn(0);
}

static PyObject *py_compliance_mult_on_set(PyObject *self, PyObject *args)
{
  PyObject *pymat, *pyx, *result;
  int       single;
  Mat       K;
  Vec       x, y = NULL;

  if (!PyArg_ParseTuple(args, "OOp", &pymat, &pyx, &single)) return NULL;
  K = PyPetscMat_Get(pymat);
  x = PyPetscVec_Get(pyx);
  if (!K || !x) return NULL;
  PyPetscCall(MultOnNonzeros(K, x, single ? PETSC_TRUE : PETSC_FALSE, &y));
  result = PyPetscVec_New(y);
  PyPetscCall(VecDestroy(&y));
  return result;
}

static PyObject *py_love(PyObject *self, PyObject *args)
{
  double x, y, hx, hy, Estar;
  if (!PyArg_ParseTuple(args, "ddddd", &x, &y, &hx, &hy, &Estar)) return NULL;
  return PyFloat_FromDouble(AdhLoveCoefficient(x, y, hx, hy, Estar));
}

/* The solver's option table as -help prints it: a fresh solver on this process reads its options
   with -help set, PETSc's help printer writing into a buffer. The Python layer builds Solver's
   keywords and their documentation from it, so they cannot drift from the C options. */
static char  *HelpText;
static size_t HelpLength, HelpCapacity;

static PetscErrorCode (*PrintTo)(FILE *, const char[], va_list);

/* PETSc prints help through PetscHelpPrintf and, for lists of types, straight to stdout: both
   pass through PetscVFPrintf, which this replaces for the call. */
static PetscErrorCode CaptureHelp(FILE *fd, const char format[], va_list given)
{
  char    line[16384]; /* PETSc's formatting (a real always shows a '.'), as -help prints it */
  size_t  n = 0;
  va_list args;
  if (fd != stdout && fd != PETSC_STDOUT) return PrintTo(fd, format, given);
  va_copy(args, given);
  (void)PetscVSNPrintf(line, sizeof(line), format, &n, args);
  va_end(args);
  n = strlen(line);
  if (HelpLength + n + 1 > HelpCapacity) {
    size_t capacity = 2 * (HelpLength + n + 1);
    char  *grown    = (char *)realloc(HelpText, capacity);
    if (!grown) return PETSC_ERR_MEM;
    HelpText     = grown;
    HelpCapacity = capacity;
  }
  memcpy(HelpText + HelpLength, line, n + 1);
  HelpLength += n;
  return 0;
}

static PyObject *py_option_help(PyObject *self, PyObject *args)
{
  PetscBool      had_help = PETSC_FALSE;
  AdhSolver      s        = NULL;
  PetscErrorCode ierr;
  PyObject      *text;
  const char    *prefix;

  if (!PyArg_ParseTuple(args, "s", &prefix)) return NULL;
  HelpLength = 0;
  if (HelpText) HelpText[0] = 0;
  CatchErrorsBegin();
  ierr = PetscOptionsHasName(NULL, NULL, "-help", &had_help);
  if (!ierr && !had_help) ierr = PetscOptionsSetValue(NULL, "-help", NULL);
  if (!ierr) {
    PrintTo         = PetscVFPrintf;
    PetscVFPrintf   = CaptureHelp;
    ierr            = AdhSolverCreate(PETSC_COMM_SELF, &s);
    if (!ierr) ierr = AdhSolverSetOptionsPrefix(s, prefix);
    if (!ierr) ierr = AdhSolverSetFromOptions(s);
    if (!ierr) ierr = AdhSolverSetUp(s); /* the compliance's options (-adh_fftw_*) are read here */
    PetscVFPrintf   = PrintTo;
    (void)AdhSolverDestroy(&s);
    if (!had_help) (void)PetscOptionsClearValue(NULL, "-help");
  }
  CatchErrorsEnd();
  PyPetscRaise(ierr);
  text = PyUnicode_FromString(HelpText ? HelpText : "");
  return text;
}

static PyObject *py_option_names(PyObject *self, PyObject *args)
{
  PetscInt           n;
  const char *const *names;
  PyObject          *l;
  if (AdhGetOptionNames(&n, &names)) return NULL;
  l = PyList_New(n);
  for (PetscInt k = 0; k < n; k++) PyList_SET_ITEM(l, k, PyUnicode_FromString(names[k]));
  return l;
}

static PyObject *py_chi(PyObject *self, PyObject *args)
{
  double hx, hy;
  if (!PyArg_ParseTuple(args, "dd", &hx, &hy)) return NULL;
  return PyFloat_FromDouble(AdhChi(hx, hy));
}

static PyObject *py_chi_square(PyObject *self, PyObject *args)
{
  double h;
  if (!PyArg_ParseTuple(args, "d", &h)) return NULL;
  return PyFloat_FromDouble(AdhChiSquare(h));
}

static PyObject *py_critical_stress(PyObject *self, PyObject *args)
{
  double hx, hy, Estar, dgamma;
  if (!PyArg_ParseTuple(args, "dddd", &hx, &hy, &Estar, &dgamma)) return NULL;
  return PyFloat_FromDouble(AdhCriticalStress(hx, hy, Estar, dgamma));
}

/* ---- the solver: a PETSc object, handed to Python as a petsc4py PETSc.Object (named, viewed,
   reference counted and destroyed like any); the class Solver in solver.py wraps it ---- */

static AdhSolver solver_get(PyObject *obj);

/* PyArg_ParseTuple's "O&" converter of a solver argument (a TypeError for anything else). */
static int solver_arg(PyObject *obj, void *out)
{
  *(AdhSolver *)out = solver_get(obj);
  return *(AdhSolver *)out != NULL;
}

static AdhSolver solver_get(PyObject *obj)
{
  PetscObject  o = PyPetscObject_Get(obj);
  PetscClassId id;
  if (!o) return NULL;
  if (PetscObjectGetClassId(o, &id) || id != ADH_CLASSID) {
    PyErr_SetString(PyExc_TypeError, "not an adhbem solver");
    return NULL;
  }
  return (AdhSolver)o;
}

static PyObject *py_solver_create(PyObject *self, PyObject *args)
{
  PyObject   *pycomm;
  const char *prefix;
  AdhSolver   s;
  PetscErrorCode ierr;

  if (!PyArg_ParseTuple(args, "Os", &pycomm, &prefix)) return NULL;
  PyPetscCall(AdhSolverCreate(PyPetscComm_Get(pycomm), &s));
  CatchErrorsBegin();
  ierr = AdhSolverSetOptionsPrefix(s, prefix);
  if (!ierr) ierr = AdhSolverSetFromOptions(s);
  if (!ierr) ierr = AdhSolverSetUp(s);
  CatchErrorsEnd();
  if (ierr) {
    (void)AdhSolverDestroy(&s);
    PyPetscRaise(ierr);
  }
  {
    PyObject *obj = PyPetscObject_New((PetscObject)s); /* petsc4py takes a reference of its own */
    PyPetscCall(AdhSolverDestroy(&s));
    return obj;
  }
}

/* The solver's grid as a petsc4py PETSc.Object (class AdhGrid), which takes a reference of its own. */
static PyObject *py_solver_grid(PyObject *self, PyObject *args)
{
  AdhSolver s;
  AdhGrid   grid;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &s)) return NULL;
  PyPetscCall(AdhSolverGetGrid(s, &grid));
  return PyPetscObject_New((PetscObject)grid);
}

static PyObject *state_columns(const AdhState *);

/* The current state as a dict of the curve's columns (statistics included). */
static PyObject *state_dict(AdhSolver s)
{
  AdhState st;
  PyPetscCall(AdhSolverComputeState(s, &st));
  return state_columns(&st);
}

/* Records the state a step just reached, as a path records its states: appended to the curve
   (so curve() and write() have the states of manual start() and step()) with the time since t0,
   and the monitors called. */
static PetscErrorCode RecordState(AdhSolver s, PetscLogDouble t0, AdhState *st)
{
  const AdhCurve *c;

  PetscFunctionBegin;
  PetscCall(AdhSolverRecordState(s, t0, st));
  PetscCall(AdhSolverGetCurve(s, &c));
  PetscCall(AdhSolverMonitor(s, c->n - 1, st));
  PetscFunctionReturn(0);
}

/* start(d) begins a new curve, as a path does; step(d) adds to it. */
static PyObject *start_or_step(PyObject *args, PetscBool start)
{
  double         d;
  AdhSolver      s;
  AdhState       st;
  PetscLogDouble t0;
  if (!PyArg_ParseTuple(args, "O&d", solver_arg, &s, &d)) return NULL;
  PyPetscCall(PetscTime(&t0));
  if (start) PyPetscCall(AdhSolverStart(s, d));
  else PyPetscCall(AdhSolverStep(s, d));
  PyPetscCall(RecordState(s, t0, &st));
  return state_columns(&st);
}

static PyObject *py_solver_start(PyObject *self, PyObject *args)
{
  return start_or_step(args, PETSC_TRUE);
}

static PyObject *py_solver_step(PyObject *self, PyObject *args)
{
  return start_or_step(args, PETSC_FALSE);
}

/* The option path: its points and the steps per leg. */
static PyObject *py_solver_path(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  PyObject        *list;
  PetscInt         n, steps;
  const PetscReal *path;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  PetscBool        stop;
  PyPetscCall(AdhSolverGetPath(solver, &n, &path, &steps));
  PyPetscCall(AdhSolverGetStopAtPullOff(solver, &stop));
  list = PyList_New(n);
  for (PetscInt k = 0; k < n; k++) PyList_SET_ITEM(list, k, PyFloat_FromDouble((double)path[k]));
  return Py_BuildValue("NnO", list, (Py_ssize_t)steps, stop ? Py_True : Py_False);
}

static PyObject *py_solver_state(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  return state_dict(solver);
}

static PyObject *py_solver_solve_path(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  PyPetscCall(AdhSolverSolvePath(solver));
  Py_RETURN_NONE;
}

static PyObject *state_columns(const AdhState *st)
{
  /* every column of the curve, by name */
  PyObject *dict = PyDict_New();
  for (PetscInt j = 0; j < AdhCurveNumColumns; j++) {
    const PetscReal v = AdhStateValue(st, j);
    PyObject       *o = AdhCurveColumns[j].integer ? PyLong_FromLong((long)v) : PyFloat_FromDouble((double)v);
    PyDict_SetItemString(dict, AdhCurveColumns[j].name, o);
    Py_DECREF(o);
  }
  return dict;
}

/* A Python callable as an AdhSolver monitor: fn(step, state_dict). An exception in it stops the
   path, and the call that ran the path raises it. */
static PetscErrorCode PythonMonitor(AdhSolver s, PetscInt step, const AdhState *st, void *ctx)
{
  PyObject *state = state_columns(st), *r;
  r = PyObject_CallFunction((PyObject *)ctx, "nO", (Py_ssize_t)step, state);
  Py_DECREF(state);
  if (!r) return PETSC_ERR_USER; /* the exception stays set: the call that ran the path raises it */
  Py_DECREF(r);
  return 0;
}

/* The solver may be destroyed by petsc4py's clean-up at interpreter exit, when Python no longer
   runs: the callable is then left to the exiting interpreter. */
static PetscErrorCode PythonMonitorDestroy(void **ctx)
{
  if (*ctx && Py_IsInitialized() && !_Py_IsFinalizing()) {
    PyGILState_STATE gil = PyGILState_Ensure();
    Py_DECREF((PyObject *)*ctx);
    PyGILState_Release(gil);
  }
  *ctx = NULL;
  return 0;
}

static PyObject *py_solver_monitor(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  PyObject *fn;
  if (!PyArg_ParseTuple(args, "O&O", solver_arg, &solver, &fn)) return NULL;
  if (!PyCallable_Check(fn)) {
    PyErr_SetString(PyExc_TypeError, "monitor: expected a callable fn(step, state)");
    return NULL;
  }
  Py_INCREF(fn);
  {
    PetscErrorCode ierr;
    CatchErrorsBegin();
    ierr = AdhSolverMonitorSet(solver, PythonMonitor, fn, PythonMonitorDestroy);
    CatchErrorsEnd();
    if (ierr) Py_DECREF(fn); /* not kept */
    PyPetscRaise(ierr);
  }
  Py_RETURN_NONE;
}

static PyObject *py_solver_curve(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  PyObject       *dict;
  const AdhCurve *c;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  PyPetscCall(AdhSolverGetCurve(solver, &c));
  dict = PyDict_New();
  for (PetscInt j = 0; j < AdhCurveNumColumns; j++) {
    PyObject *l = PyList_New(c->n);
    for (PetscInt k = 0; k < c->n; k++) {
      const PetscReal v = AdhStateValue(&c->state[k], j);
      PyList_SET_ITEM(l, k, AdhCurveColumns[j].integer ? PyLong_FromLong((long)v) : PyFloat_FromDouble((double)v));
    }
    PyDict_SetItemString(dict, AdhCurveColumns[j].name, l);
    Py_DECREF(l);
  }
  return dict;
}

static PyObject *py_solver_objects(PyObject *self, PyObject *args)
{
  AdhSolver s;
  Vec         p, u = NULL, g, h, Sigma = NULL;
  Mat         K;
  IS          is;
  AdhGrid     grid;
  AdhBoundary boundary;
  PetscReal   hx, hy, Lx, Ly;
  const char *name = "";
  if (!PyArg_ParseTuple(args, "O&|s", solver_arg, &s, &name)) return NULL;
  /* the displacement and a uniform critical stress are made into vectors only when asked for */
  PyPetscCall(AdhSolverGetFields(s, &p, strcmp(name, "displacement") ? NULL : &u, &g, &h, strcmp(name, "critical_stress") ? NULL : &Sigma));
  PyPetscCall(AdhSolverGetCompliance(s, &K));
  PyPetscCall(AdhSolverGetContactSet(s, &is));
  PyPetscCall(AdhSolverGetGrid(s, &grid));
  PyPetscCall(AdhGridGetSizes(grid, NULL, NULL, &Lx, &Ly));
  PyPetscCall(AdhGridGetSpacing(grid, &hx, &hy));
  PyPetscCall(AdhSolverGetBoundary(s, &boundary));
  return Py_BuildValue("{s:N,s:N,s:N,s:N,s:N,s:N,s:N,s:d,s:d,s:d,s:d,s:s}", "pressure", PyPetscVec_New(p), "displacement", u ? PyPetscVec_New(u) : (Py_INCREF(Py_None), Py_None), "gap", PyPetscVec_New(g), "profile", PyPetscVec_New(h), "critical_stress", Sigma ? PyPetscVec_New(Sigma) : (Py_INCREF(Py_None), Py_None), "compliance", PyPetscMat_New(K), "contact_set", PyPetscIS_New(is), "hx", (double)hx, "hy", (double)hy, "Lx", (double)Lx, "Ly", (double)Ly, "boundary", AdhBoundaries[boundary]);
}

static PyObject *py_solver_sigma(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  PetscReal Sigma;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  PyPetscCall(AdhSolverGetCriticalStress(solver, &Sigma));
  return PyFloat_FromDouble((double)Sigma);
}

static PyObject *py_solver_set_gamma_field(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  PyObject *pyvec;
  Vec       v;
  if (!PyArg_ParseTuple(args, "O&O", solver_arg, &solver, &pyvec)) return NULL;
  v = PyPetscVec_Get(pyvec);
  if (!v) return NULL;
  PyPetscCall(AdhSolverSetWorkOfAdhesionField(solver, v));
  Py_RETURN_NONE;
}

static PyObject *py_solver_set_topography(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  PyObject         *pyvec;
  const char       *kname;
  Vec               v;
  AdhTopographyKind kind = ADH_TOPOGRAPHY_HEIGHT;
  PetscBool         found = PETSC_FALSE;

  if (!PyArg_ParseTuple(args, "O&Os", solver_arg, &solver, &pyvec, &kname)) return NULL;

  for (int k = 0; k < 2; k++)
    if (!strcmp(kname, AdhTopographyKinds[k])) { found = PETSC_TRUE; kind = (AdhTopographyKind)k; }
  if (!found) {
    PyErr_Format(PyExc_ValueError, "topography_kind: '%s' is not height or gap", kname);
    return NULL;
  }
  v = PyPetscVec_Get(pyvec);
  if (!v) return NULL;
  PyPetscCall(AdhSolverSetTopography(solver, v, kind));
  Py_RETURN_NONE;
}

static PyObject *py_solver_write(PyObject *self, PyObject *args)
{
  AdhSolver   solver;
  const char *file;
  if (!PyArg_ParseTuple(args, "O&s", solver_arg, &solver, &file)) return NULL;
  PyPetscCall(AdhSolverWriteOutput(solver, file));
  Py_RETURN_NONE;
}

static PyObject *py_solver_output_begin(PyObject *self, PyObject *args)
{
  AdhSolver   solver;
  const char *file;
  if (!PyArg_ParseTuple(args, "O&s", solver_arg, &solver, &file)) return NULL;
  PyPetscCall(AdhSolverOutputBegin(solver, file));
  Py_RETURN_NONE;
}

static PyObject *py_solver_output_record(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  PyPetscCall(AdhSolverOutputRecord(solver));
  Py_RETURN_NONE;
}

static PyObject *py_solver_output_end(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  int       complete;
  if (!PyArg_ParseTuple(args, "O&p", solver_arg, &solver, &complete)) return NULL;
  PyPetscCall(AdhSolverOutputEnd(solver, complete ? PETSC_TRUE : PETSC_FALSE));
  Py_RETURN_NONE;
}

/* -adh_progress of a solver: set it when a value is given, and return the one before. */
static PyObject *py_solver_progress(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  double    seconds = -1;
  PetscReal before;
  if (!PyArg_ParseTuple(args, "O&|d", solver_arg, &solver, &seconds)) return NULL;
  PyPetscCall(AdhSolverGetProgress(solver, &before));
  if (seconds >= 0) PyPetscCall(AdhSolverSetProgress(solver, (PetscReal)seconds));
  return PyFloat_FromDouble((double)before);
}

/* How well the grid resolves the adhesion (the results file's attributes hold the same under their own names). */
static PyObject *py_solver_resolution(PyObject *self, PyObject *args)
{
  AdhSolver     solver;
  AdhResolution r;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  PyPetscCall(AdhSolverGetResolution(solver, &r));
  return Py_BuildValue("{s:d,s:d,s:O,s:n,s:d,s:d,s:n,s:O,s:d,s:d,s:n,s:n,s:n,s:n,s:[sss]}", "asperity_contact_radius", (double)r.asperity_contact_radius, "asperity_tabor", (double)r.asperity_tabor, "touched", r.touched ? Py_True : Py_False, "state", (Py_ssize_t)r.state, "force", (double)r.force, "small_patch_tension", (double)r.small_patch_tension, "smallest_tensile_patch", (Py_ssize_t)r.smallest_tensile_patch, "resolved", r.state < 0 ? Py_None : r.resolved ? Py_True : Py_False, "cohesive_elements", (double)r.cohesive_elements, "cohesive_width", (double)r.cohesive_width, "apart", (Py_ssize_t)r.apart, "full_contact", (Py_ssize_t)r.full_contact, "last_points", (Py_ssize_t)r.last_points, "stopped", (Py_ssize_t)r.stopped, "unresolved", r.unresolved & ADH_UNRESOLVED_PATCHES ? "patches" : NULL, r.unresolved & ADH_UNRESOLVED_ASPERITIES ? "asperities" : NULL, r.unresolved & ADH_UNRESOLVED_ZONE ? "zone" : NULL);
}

/* Whether a rough surface is sticky (None: no estimate; sticky None: the run tells, a zero-range criterion on a
   partial contact). The results file's stickiness_* attributes hold the same. */
static PyObject *py_solver_stickiness(PyObject *self, PyObject *args)
{
  AdhSolver     solver;
  AdhStickiness st;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  PyPetscCall(AdhSolverGetStickiness(solver, &st));
  if (!st.estimated) Py_RETURN_NONE;
  return Py_BuildValue("{s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:O,s:O}", "rms_slope", (double)st.rms_slope, "rms_curvature", (double)st.rms_curvature, "full_contact_energy", (double)st.full_contact_energy, "work_of_adhesion", (double)st.work_of_adhesion, "persson_tosatti", (double)st.persson_tosatti, "range", (double)st.range, "pastewka_robbins", (double)st.pastewka_robbins, "generalized_tabor", (double)st.tabor, "sticks_everywhere", st.sticks_everywhere ? Py_True : Py_False, "sticky", !(st.sticks_everywhere || st.range > 0) ? Py_None : st.sticky ? Py_True : Py_False);
}

static PyObject *py_solver_stickiness_view(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  PyPetscCall(AdhSolverStickinessView(solver, NULL));
  Py_RETURN_NONE;
}

static PyObject *py_solver_resolution_view(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  PyPetscCall(AdhSolverResolutionView(solver, NULL));
  Py_RETURN_NONE;
}

static PyObject *py_solver_view(PyObject *self, PyObject *args)
{
  AdhSolver solver;
  if (!PyArg_ParseTuple(args, "O&", solver_arg, &solver)) return NULL;
  PyPetscCall(AdhSolverView(solver, NULL));
  Py_RETURN_NONE;
}

static PyMethodDef methods[] = {
  {"compliance_mult_on_set", py_compliance_mult_on_set, METH_VARARGS, "compliance_mult_on_set(K, x, single) -> y = R K R^T x on x's nonzero points (a periodic compliance)"},
  {"solver_create", py_solver_create, METH_VARARGS, "solver_create(comm, prefix) -> the solver as a PETSc.Object (options read with the prefix)"},
  {"solver_start", py_solver_start, METH_VARARGS, "solver_start(s, d) -> state, the first row of a new curve"},
  {"solver_step", py_solver_step, METH_VARARGS, "solver_step(s, d) -> state, appended to the curve"},
  {"solver_path", py_solver_path, METH_VARARGS, "solver_path(s) -> (path points, steps per leg, a pull-off ends the path)"},
  {"solver_state", py_solver_state, METH_VARARGS, "solver_state(s) -> state"},
  {"solver_solve_path", py_solver_solve_path, METH_VARARGS, "solver_solve_path(s)"},
  {"solver_monitor", py_solver_monitor, METH_VARARGS, "solver_monitor(s, fn): fn(step, state) after every recorded state"},
  {"solver_curve", py_solver_curve, METH_VARARGS, "solver_curve(s) -> dict of lists"},
  {"solver_objects", py_solver_objects, METH_VARARGS, "solver_objects(s) -> dict of petsc4py objects"},
  {"solver_critical_stress", py_solver_sigma, METH_VARARGS, "solver_critical_stress(s) -> Sigma"},
  {"solver_set_gamma_field", py_solver_set_gamma_field, METH_VARARGS, "solver_set_gamma_field(s, vec)"},
  {"solver_set_topography", py_solver_set_topography, METH_VARARGS, "solver_set_topography(s, vec, kind): indenter profile from a height map or gap (kind 'height' or 'gap')"},
  {"solver_write", py_solver_write, METH_VARARGS, "solver_write(s, file)"},
  {"solver_view", py_solver_view, METH_VARARGS, "solver_view(s)"},
  {"solver_progress", py_solver_progress, METH_VARARGS, "solver_progress(s[, seconds]) -> the -adh_progress before (set when given)"},
  {"solver_grid", py_solver_grid, METH_VARARGS, "solver_grid(s) -> PETSc.Object: the solver's grid (class AdhGrid)"},
  {"solver_resolution", py_solver_resolution, METH_VARARGS, "solver_resolution(s) -> dict: how well the grid resolves the adhesion"},
  {"solver_resolution_view", py_solver_resolution_view, METH_VARARGS, "solver_resolution_view(s): prints the resolution lines (rank 0)"},
  {"solver_output_begin", py_solver_output_begin, METH_VARARGS, "solver_output_begin(s, file): opens a results file written state by state"},
  {"solver_output_record", py_solver_output_record, METH_VARARGS, "solver_output_record(s): writes the states recorded since the last call (the last one's fields too)"},
  {"solver_output_end", py_solver_output_end, METH_VARARGS, "solver_output_end(s, complete): closes it under its name"},
  {"solver_stickiness", py_solver_stickiness, METH_VARARGS, "solver_stickiness(s) -> dict of the stickiness estimate, or None"},
  {"solver_stickiness_view", py_solver_stickiness_view, METH_VARARGS, "solver_stickiness_view(s): prints the stickiness line (rank 0)"},
  {"compliance", py_compliance, METH_VARARGS, "compliance(comm, Nx, Ny, Lx, Ly, Estar, boundary) -> PETSc.Mat"},
  {"rough_surface", py_rough_surface, METH_VARARGS, "rough_surface(comm, Nx, Ny, Lx, Ly, prefix) -> (PETSc.Vec, dict); options read with the prefix"},
  {"option_help", py_option_help, METH_VARARGS, "option_help(prefix) -> the -help text of a solver's options under prefix"},
  {"option_names", py_option_names, METH_NOARGS, "option_names() -> adhbem's own option names (adh_gamma, ...)"},
  {"compliance_info", py_compliance_info, METH_VARARGS, "compliance_info(K) -> dict(lambda_min, row_norm_bound, mult_count, Nx, Ny)"},
  {"love_coefficient", py_love, METH_VARARGS, "love_coefficient(x, y, hx, hy, Estar) -> displacement per unit pressure"},
  {"chi", py_chi, METH_VARARGS, "chi(hx, hy) -> element self-energy factor"},
  {"chi_square", py_chi_square, METH_VARARGS, "chi_square(h) -> 0.473201 h^3"},
  {"critical_stress", py_critical_stress, METH_VARARGS, "critical_stress(hx, hy, Estar, dgamma) -> Sigma"},
  {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_adhbem", "adhbem C extension", -1, methods};

PyMODINIT_FUNC PyInit__adhbem(void)
{
  PyObject *m;

  if (import_petsc4py() < 0) return NULL;
  m = PyModule_Create(&module);
  /* The package compares it with petsc4py's PetscInt: both must come from the same PETSc. */
  if (m && PyModule_AddIntConstant(m, "petsc_int_size", (long)sizeof(PetscInt)) < 0) Py_CLEAR(m);
  /* ... and the PETSc it was built against with petsc4py's (major.minor), its own version with the package's */
  if (m && PyModule_AddObject(m, "petsc_version", Py_BuildValue("(iii)", PETSC_VERSION_MAJOR, PETSC_VERSION_MINOR, PETSC_VERSION_SUBMINOR)) < 0) Py_CLEAR(m);
  if (m && PyModule_AddStringConstant(m, "version", ADHBEM_VERSION) < 0) Py_CLEAR(m);
  return m;
}
