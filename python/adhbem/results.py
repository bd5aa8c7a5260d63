"""Reading a results file (-adh_output FILE.h5) without PETSc: the curve as NumPy arrays, the
parameters as a dict, the fields by state, read from the file only when asked for.

    r = adhbem.load("results/rough.h5")
    r.curve["force"], r.params["gamma"], r.field("contact", r.states[-1])

A run that was killed (SIGKILL, a node lost) leaves FILE.h5.part and FILE.csv.part, both holding
every state recorded before: load("FILE.h5") reads the .part then (with a warning), and the curve
comes from the CSV journal when the HDF5 file cannot be read or holds fewer states.
"""
import os
import warnings

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
    # integers in the file; earlier files and the CSV journal hold them as floats
    COUNTS = ("contact_points", "outer_iterations", "ksp_iterations", "compliance_applications", "fft_pairs",
              "patches", "pulled_off", "smallest_tensile_patch")

    def __init__(self, path):
        import h5py
        self.path = str(path)
        if not os.path.exists(self.path) and os.path.exists(self.path + ".part"):
            warnings.warn(f"{self.path} is not there but {self.path}.part is: the run was killed before it ended; "
                          "reading its states so far (complete = 0)", stacklevel=3)
            self.path += ".part"
        journal = _journal_name(self.path)
        self._file = None
        try:
            self._file = h5py.File(self.path, "r")
            self.params = {k: _plain(v) for k, v in self._file.attrs.items()}
            self.curve = {k: self._file["curve"][k][()] for k in self._file["curve"]}
            if "path" in self.curve:  # earlier files: /curve/path, of its own length
                self.params.setdefault("path", self.curve.pop("path"))
        except (OSError, KeyError) as e:
            if not os.path.exists(journal):
                raise
            warnings.warn(f"{self.path} cannot be read ({e}): the curve comes from {journal}, "
                          "without fields or parameters", stacklevel=3)
            if self._file is not None:
                self._file.close()
            self._file, self.params, self.curve = None, {"complete": 0}, {}
        if not self.params.get("complete", 0) and os.path.exists(journal):
            # a results file cut short by a kill may hold fewer states than its journal
            rows = _read_journal(journal)
            if len(rows.get("d", ())) > len(self.curve.get("d", ())):
                self.curve = rows
        for k in self.COUNTS:
            if k in self.curve:
                self.curve[k] = self.curve[k].astype(np.int64)
        if self.params.get("boundary") == "periodic" and "mean_pressure" not in self.curve and "force" in self.curve:
            # earlier files: the columns a periodic cell's file now has
            cell = self.params["Lx"] * self.params["Ly"]
            self.curve["mean_pressure"] = self.curve["force"] / cell
            self.curve["area_fraction"] = self.curve["area"] / cell
        group = self._file.get("fields") if self._file is not None else None
        self.field_names = [k for k in self.FIELDS if group is not None and k in group]
        self.states = group["state"][()].astype(np.int64) if group is not None and "state" in group else np.zeros(0, np.int64)
        # frames written after the last state the file knows of (a kill between the two) are not its
        self.states = self.states[self.states < len(self.curve.get("d", ()))]

    def to_pandas(self):
        """The curve as a ``pandas.DataFrame``, a row per recorded state (the index: the state,
        the curve row that ``field(name, state)`` takes). pandas is needed for this call only."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("Results.to_pandas() needs pandas (pip install pandas, or apt install python3-pandas); "
                              "Results.curve holds the same columns as a dict of NumPy arrays") from None
        frame = pd.DataFrame(self.curve)
        frame.index.name = "state"
        return frame

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
        if self._file is not None:
            self._file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _journal_name(path):
    """FILE.csv beside FILE.h5 (FILE.csv.part beside FILE.h5.part): the curve as CSV."""
    part = path.endswith(".part")
    base = path[:-len(".part")] if part else path
    csv = (base[:-3] if base.endswith(".h5") else base) + ".csv"
    return csv + ".part" if part else csv


def _read_journal(name):
    """The curve of a CSV journal, without the step column; a last line cut short is left out."""
    with open(name) as f:
        header = f.readline().rstrip("\n").split(",")
        rows = []
        for line in f:
            fields = line.rstrip("\n").split(",")
            if not line.endswith("\n") or len(fields) != len(header):
                break
            try:
                rows.append([float(x) for x in fields])
            except ValueError:
                break
    data = np.array(rows, dtype=float).reshape(-1, len(header))
    return {k: data[:, j] for j, k in enumerate(header) if k != "step"}


def load(path):
    """The results file at path, as a Results (use it in a with statement, or close() it)."""
    return Results(path)
