/* The C half of the Python layer: turns libadhbem objects into real petsc4py objects.
   PETSc errors become petsc4py's PETSc.Error. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <petsc4py/petsc4py.h>
#include "adhbem.h"

/* Run a PETSc call; on error set the Python exception and return NULL from the wrapper. */
#define PyPetscCall(...) \
  do { \
    PetscErrorCode ierr_ = (__VA_ARGS__); \
    if (ierr_) { PyPetscError_Set((int)ierr_); return NULL; } \
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
  PyPetscCall(AdhGridSetSizes(grid, (PetscInt)Nx, (PetscInt)Ny, Lx, Ly));
  PyPetscCall(MatCreateAdhCompliance(grid, Estar, boundary, &K));
  PyPetscCall(AdhGridDestroy(&grid));
  result = PyPetscMat_New(K);
  PyPetscCall(MatDestroy(&K));
  return result;
}

static PyObject *py_compliance_info(PyObject *self, PyObject *args)
{
  PyObject *pymat;
  PetscReal lmin;
  PetscInt  count;
  Mat       K;

  if (!PyArg_ParseTuple(args, "O", &pymat)) return NULL;
  K = PyPetscMat_Get(pymat);
  if (!K) return NULL;
  PyPetscCall(MatAdhComplianceGetLambdaMin(K, &lmin));
  PyPetscCall(MatAdhComplianceGetMultCount(K, &count));
  return Py_BuildValue("{s:d,s:n}", "lambda_min", (double)lmin, "mult_count", (Py_ssize_t)count);
}

static PyObject *py_love(PyObject *self, PyObject *args)
{
  double x, y, hx, hy, Estar;
  if (!PyArg_ParseTuple(args, "ddddd", &x, &y, &hx, &hy, &Estar)) return NULL;
  return PyFloat_FromDouble(AdhLoveCoefficient(x, y, hx, hy, Estar));
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

static PyMethodDef methods[] = {
  {"compliance", py_compliance, METH_VARARGS, "compliance(comm, Nx, Ny, Lx, Ly, Estar, boundary) -> PETSc.Mat"},
  {"compliance_info", py_compliance_info, METH_VARARGS, "compliance_info(K) -> dict(lambda_min, mult_count)"},
  {"love_coefficient", py_love, METH_VARARGS, "love_coefficient(x, y, hx, hy, Estar) -> displacement per unit pressure"},
  {"chi", py_chi, METH_VARARGS, "chi(hx, hy) -> element self-energy factor"},
  {"chi_square", py_chi_square, METH_VARARGS, "chi_square(h) -> 0.473201 h^3"},
  {"critical_stress", py_critical_stress, METH_VARARGS, "critical_stress(hx, hy, Estar, dgamma) -> Sigma"},
  {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_adhbem", "adhbem C extension", -1, methods};

PyMODINIT_FUNC PyInit__adhbem(void)
{
  if (import_petsc4py() < 0) return NULL;
  return PyModule_Create(&module);
}
