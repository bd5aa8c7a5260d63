"""Reading a results file (-adh_output FILE.h5) without PETSc: the curve as NumPy arrays, the
parameters as a dict, the fields by state, read from the file only when asked for.

    r = adhbem.load("results/rough.h5")
    r.curve["force"], r.params["gamma"], r.field("contact", r.states[-1])
"""
import numpy as np


def _plain(value):
    if isinstance(value, bytes):
        return value.decode()
    if isinstance(value, np.generic):
        return value.item()
    return value


class Results:
    """One results file. curve: dict of 1-D arrays, one entry per recorded state; params: the
    root attributes (grid, material, indenter, control, criterion, pull_off_force, complete...);
    pull_off_force: the largest tension carried;
    states: the curve rows that have fields (empty without -adh_fields); field(name, state): the
    (Ny, Nx) array of pressure, displacement, gap or contact of curve row `state`; profile and
    critical_stress: the (Ny, Nx) arrays written once."""

    FIELDS = ("pressure", "displacement", "gap", "contact")

    def __init__(self, path):
        import h5py
        self.path = str(path)
        self._file = h5py.File(self.path, "r")
        self.params = {k: _plain(v) for k, v in self._file.attrs.items()}
        self.curve = {k: self._file["curve"][k][()] for k in self._file["curve"]}
        for k in ("contact_points", "outer_iterations", "ksp_iterations", "compliance_applications",
                  "fft_pairs", "patches", "pulled_off"):
            if k in self.curve:
                self.curve[k] = self.curve[k].astype(np.int64)
        group = self._file.get("fields")
        self.field_names = [k for k in self.FIELDS if group is not None and k in group]
        self.states = group["state"][()].astype(np.int64) if group is not None and "state" in group else np.zeros(0, np.int64)

    def field(self, name, state):
        """The field `name` of curve row `state` (negative: from the end), read from the file."""
        if name not in self.field_names:
            raise KeyError(f"{self.path} holds no field {name!r} (it has {self.field_names or 'none'}; write them with -adh_fields)")
        n = len(self.curve["d"])
        row = state + n if state < 0 else state
        frames = np.nonzero(self.states == row)[0]
        if not len(frames):
            raise KeyError(f"{self.path} has no fields of state {state} (it has those of states {self.states.tolist()})")
        return self._file["fields"][name][frames[0]]

    @property
    def pull_off_force(self):
        """The largest tension carried over the run, -min(force) (0: none)."""
        return self.params.get("pull_off_force", max(0.0, -float(self.curve["force"].min())))

    @property
    def profile(self):
        return self._file["fields"]["profile"][()]

    @property
    def critical_stress(self):
        return self._file["fields"]["critical_stress"][()]

    def close(self):
        self._file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def load(path):
    """The results file at path, as a Results (use it in a with statement, or close() it)."""
    return Results(path)
