"""Reading a results file (-adh_output FILE.h5) without PETSc: the curve as NumPy arrays, the
parameters as a dict, the fields by state, read from the file only when asked for.

    r = adhbem.load("results/rough.h5")
    r.curve["force"], r.params["gamma"], r.field("contact", r.states[-1])

A run that was killed (SIGKILL, a node lost) leaves FILE.h5.part and FILE.csv.part, both holding
every state recorded before: load("FILE.h5") reads the .part then (with a warning), and the curve
comes from the CSV journal when the HDF5 file cannot be read or holds fewer states.
"""
from __future__ import annotations

import os
import warnings
from typing import TYPE_CHECKING, Union

import numpy as np

if TYPE_CHECKING:  # pandas is optional: to_pandas() imports it
    import pandas


def _plain(value):
    if isinstance(value, bytes):
        return value.decode()
    if isinstance(value, np.generic):
        return value.item()
    return value


class Results:
    """One results file, open for reading (``adhbem.load``).

    Attributes
    ----------
    path : str
        The file read (``FILE.h5.part`` for a run that was killed).
    curve : dict of numpy.ndarray
        The curve: a 1-D array per column, an entry per recorded state (counts as int64).
    params : dict
        The root attributes: grid, material, indenter, control, criterion, ``pull_off_force``,
        the resolution, ``path``, ``complete``, ... (text as str).
    states : numpy.ndarray
        The curve rows whose fields the file holds (empty without ``-adh_fields``).
    field_names : list of str
        The fields it holds, of ``pressure``, ``displacement``, ``gap``, ``contact``.

    Examples
    --------
    >>> with adhbem.load("results/rough.h5") as r:
    ...     df = r.to_pandas()
    ...     mask = r.field("contact", r.states[-1])
    """

    FIELDS = ("pressure", "displacement", "gap", "contact")
    # integers in the file; earlier files and the CSV journal hold them as floats
    COUNTS = ("contact_points", "outer_iterations", "ksp_iterations", "compliance_applications", "fft_pairs",
              "patches", "pulled_off", "smallest_tensile_patch")

    def __init__(self, path: Union[str, os.PathLike]):
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
            # a write that failed on some ranks part-way through a state's row leaves columns of
            # unequal length: the states whole in every column are the file's
            whole = min((len(v) for v in self.curve.values()), default=0)
            self.curve = {k: v[:whole] for k, v in self.curve.items()}
        except (OSError, KeyError) as e:
            if not os.path.exists(journal):
                if self._file is not None:
                    self._file.close()
                if isinstance(e, KeyError):
                    raise ValueError(f"{self.path}: not an adhbem results file (it has no {e} of a curve)") from None
                raise OSError(f"{self.path}: not a readable HDF5 file (truncated or damaged?): {e}") from None
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
        if "area_fraction" not in self.curve and "area" in self.curve and "Lx" in self.params:
            # earlier files: the columns a file now has (area_fraction on every boundary)
            self.curve["area_fraction"] = self.curve["area"] / (self.params["Lx"] * self.params["Ly"])
        if self.params.get("boundary") == "periodic" and "mean_pressure" not in self.curve and "force" in self.curve:
            self.curve["mean_pressure"] = self.curve["force"] / (self.params["Lx"] * self.params["Ly"])
        group = self._file.get("fields") if self._file is not None else None
        self.field_names = [k for k in self.FIELDS if group is not None and k in group]
        self.states = group["state"][()].astype(np.int64) if group is not None and "state" in group else np.zeros(0, np.int64)
        # frames written after the last state the file knows of (a kill between the two) are not its
        self.states = self.states[self.states < len(self.curve.get("d", ()))]

    def to_pandas(self) -> "pandas.DataFrame":
        """The curve as a ``pandas.DataFrame``.

        Returns
        -------
        pandas.DataFrame
            A row per recorded state, indexed by the state (the curve row that
            ``field(name, state)`` takes), a column per column of ``curve``.

        Raises
        ------
        ImportError
            Without pandas (needed for this call only).
        """
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("Results.to_pandas() needs pandas (pip install pandas, or apt install python3-pandas); "
                              "Results.curve holds the same columns as a dict of NumPy arrays") from None
        frame = pd.DataFrame(self.curve)
        frame.index.name = "state"
        return frame

    def field(self, name: str, state: int) -> np.ndarray:
        """A field of one state, read from the file now.

        Parameters
        ----------
        name : {'pressure', 'displacement', 'gap', 'contact'}
            The field (``contact``: uint8, 1 in contact).
        state : int
            The curve row (negative: from the end); it must be one of ``states``.

        Returns
        -------
        numpy.ndarray
            Shape (Ny, Nx).

        Raises
        ------
        KeyError
            When the file does not hold that field, or not for that state.
        """
        if name not in self.field_names:
            raise KeyError(f"{self.path} holds no field {name!r} (it has {self.field_names or 'none'}; write them with -adh_fields)")
        n = len(self.curve["d"])
        row = state + n if state < 0 else state
        frames = np.nonzero(self.states == row)[0]
        if not len(frames):
            raise KeyError(f"{self.path} has no fields of state {state} (it has those of states {self.states.tolist()})")
        return self._file["fields"][name][frames[0]]

    @property
    def came_apart(self) -> bool:
        """Whether the surfaces came apart: a state ended in pull-off (``pulled_off`` in the curve)."""
        return bool(np.any(self.curve.get("pulled_off", np.zeros(0))))

    @property
    def largest_tension(self) -> float:
        """The largest tension the contact carried, -min(force) (0.0: none), apart or not."""
        return max(0.0, -float(self.curve["force"].min())) if len(self.curve["force"]) else 0.0

    @property
    def pull_off_force(self) -> float:
        """The pull-off force: the largest tension the contact carried, when the surfaces came apart;
        NaN when they did not (full contact to the end, or a path that ended in contact), whose
        largest tension is ``largest_tension``."""
        return self.largest_tension if self.came_apart else float("nan")

    @property
    def profile(self) -> np.ndarray:
        """The indenter's profile h, (Ny, Nx)."""
        return self._file["fields"]["profile"][()]

    @property
    def critical_stress(self) -> np.ndarray:
        """The critical stress Sigma(x, y), (Ny, Nx)."""
        return self._file["fields"]["critical_stress"][()]

    def close(self) -> None:
        """Closes the file (a with-block does it at its end)."""
        if self._file is not None:
            self._file.close()

    def __enter__(self) -> "Results":
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


def load(path: Union[str, os.PathLike]) -> Results:
    """Opens a results file (``-adh_output FILE.h5``) for reading; needs only h5py and NumPy.

    Parameters
    ----------
    path : str or os.PathLike
        ``FILE.h5``; if it is missing but ``FILE.h5.part`` is there (a run that was killed),
        that is read, with a warning.

    Returns
    -------
    Results
        Use it in a with-block, or ``close()`` it.
    """
    return Results(path)
