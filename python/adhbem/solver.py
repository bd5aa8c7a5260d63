"""The solver: ``Solver``, configured by the options of the executable, on real petsc4py objects
(``import adhbem`` loads this module the first time one of its names is used, so that reading
and plotting results need neither petsc4py nor the C extension)."""
from __future__ import annotations

import math
import os
from typing import Callable, Iterator, Optional, Union

import numpy as np

from ._extension import PETSc, _adhbem
from .grid import _ndim, _shape, gather, grid_shape, local_rows, row_range, set_local_rows
from .options import _option_value
from .topography import from_surface_topography, is_surface_topography


_solver_count = 0


class Solver:
    """The adhesive contact solver, configured by the same options as the executable.

    Every keyword is an ``-adh_`` option of the executable without that prefix; the list below is
    made from the library's own option table (what ``adhbem -help`` prints), with its defaults.
    KSP options go the same way (``ksp_rtol=1e-12``). The options are stored under a prefix of
    this solver's own, so two solvers do not see each other's.

    Examples
    --------
    >>> s = adhbem.Solver(n=128, gamma=2e-3, radius=1.0, path=[0.06, -0.03], steps=45)
    >>> curve = s.solve_path()                      # dict of NumPy arrays, a row per state
    >>> p = s.pressure_array()                      # the last state's pressure, (Ny, Nx)

    A rough surface of your own, as a NumPy height map on a periodic cell:

    >>> s = adhbem.Solver(n=(Nx, Ny), size=(Lx, Ly), boundary="periodic", gamma=1e-3,
    ...                   topography=z, path=[0.0, 0.02, -0.01], steps=40)

    Notes
    -----
    A height map z gives the profile h = max(z) - z (the highest peak touches at d = 0);
    ``topography_kind="gap"`` takes h as it is. An array or Vec topography makes the indenter
    ``"array"``; the results files it writes hold it as ``/topography``. A topography on the
    default free boundary is an isolated body of the grid's size and draws a warning: give
    ``boundary="periodic"`` for a periodic cell, ``boundary="free"`` to keep it.

    The fields are those of the current state, as NumPy arrays (``pressure_array()``,
    ``gap_array()``, ``contact_array()``, ...) or as petsc4py objects (``pressure``, ``gap``,
    ``contact_set``, ...): read them inside ``for state in s.iterate_path():`` or a
    ``monitor(fn)`` to have every state's; after ``solve_path()`` they are the last state's (after
    a pull-off: nothing in contact). ``curve()`` gives the recorded states, from
    ``solve_path()``, ``iterate_path()`` or ``start(d)`` and ``step(d)``; ``pull_off_force`` the
    largest tension the contact carried; ``resolution`` how well the grid resolves the adhesion.

    Errors are Python's exceptions: ``ValueError`` for a bad value (the message names the
    option), ``FileNotFoundError``, ``MemoryError`` (a grid larger than the node), ``TypeError``
    for an unknown keyword, ``KeyboardInterrupt`` when SIGINT or SIGTERM stops a path (its
    results so far are written).
    """

    def __init__(self, comm=None, *, topography=None, topography_kind=None, gamma_field=None, **options):
        self._keys = []
        self._topography = None  # an array or Vec topography, written to results files
        # File names are options read at set-up; arrays and Vecs are handed over after it.
        if topography_kind is not None:
            if topography_kind not in ("height", "gap"):
                raise ValueError(f"topography_kind: 'height' or 'gap', got {topography_kind!r}")
            options["topography_kind"] = topography_kind
        if isinstance(topography, (str, os.PathLike)):
            options["topography"] = os.fspath(topography)
            topography = None
        elif ("n" not in options and topography is not None and not isinstance(topography, PETSc.Vec)
              and not is_surface_topography(topography) and _ndim(topography) == 2):
            shape = _shape(topography)
            options["n"] = (shape[1], shape[0])  # an (Ny, Nx) array gives the grid
        elif is_surface_topography(topography):
            topography = self._take_surface_topography(topography, options)
        if topography is not None:
            indenter = options.pop("indenter", "array")
            if indenter != "array":
                raise ValueError(f"topography: an array or Vec is the indenter; indenter={indenter!r} conflicts with it")
        if isinstance(gamma_field, (str, os.PathLike)):
            options["gamma_field"] = os.fspath(gamma_field)
            gamma_field = None
        self._init(comm, options)
        try:
            if topography is not None:
                self.set_topography(topography, topography_kind or "height")
            if gamma_field is not None:
                self.set_gamma_field(gamma_field)
        except BaseException:
            self._forget_options()
            raise

    @staticmethod
    def _take_surface_topography(t, options):
        """A SurfaceTopography topography: its heights (transposed to (Ny, Nx)), and its grid, sizes
        and periodicity as the options n, size and boundary unless given (then they must agree)."""
        import numpy as np
        z, n, size, periodic = from_surface_topography(t)
        for key, value in (("n", n), ("size", size)):
            given = options.get(key)
            if given is None:
                options[key] = value
                continue
            pair = tuple(given) if isinstance(given, (tuple, list, np.ndarray)) else (given, given)
            if not np.allclose(np.asarray(pair, dtype=float), value, rtol=1e-12):
                raise ValueError(f"{key}={given!r} disagrees with the SurfaceTopography map's {value} "
                                 f"(Nx, Ny / Lx, Ly; its heights() are (nx, ny), adhbem's arrays (Ny, Nx))")
        options.setdefault("boundary", "periodic" if periodic else "free")
        return z

    @staticmethod
    def _check_option_names(options):
        # A misspelled keyword is an error, as for any Python function (the C check would name
        # the option with this solver's internal prefix).
        import difflib
        from .options import solver_options
        # the solver's own options and every registered type's (-help shows them all)
        known = [name[len("adh_"):] for name in _adhbem.option_names()]
        known += [o.name for o in solver_options() if o.name not in known]
        for key in options:
            if key in known or key.startswith(("ksp_", "pc_", "local_ksp_")):
                continue
            near = difflib.get_close_matches(key, known, n=1)
            hint = f" (did you mean {near[0]!r}?)" if near else ""
            raise TypeError(f"Solver: unknown option {key!r}{hint}")

    @staticmethod
    def _check_option_values(options):
        # A value of the wrong kind is refused here, naming the keyword, rather than cast or
        # replaced by a default (or reported by PETSc without the keyword's name).
        import numbers
        from .options import solver_options, _is_sequence
        kinds = {o.name: o.kind for o in solver_options()}

        def number(key, v, integer):
            """v checked; the value to pass (an integral float as an int for an integer option)."""
            if isinstance(v, np.ndarray) and v.ndim == 0:
                v = v.item()
            if isinstance(v, (complex, np.complexfloating)):
                raise TypeError(f"{key}: expected a real number, got the complex {v!r}")
            if isinstance(v, (bool, np.bool_)) and not integer:
                return v  # a real that switches (progress=False: off; _option_value gives 0 or 1)
            if isinstance(v, (bool, np.bool_)):
                raise TypeError(f"{key}: expected {'an integer' if integer else 'a real number'}, got bool {v!r}")
            if isinstance(v, str):
                if v.strip().upper() in ("DEFAULT", "PETSC_DEFAULT", "DECIDE", "PETSC_DECIDE", "DETERMINE", "PETSC_DETERMINE"):
                    return v  # PETSc's own words
                try:
                    x = int(v) if integer else float(v)
                except ValueError:
                    raise ValueError(f"{key}: expected {'an integer' if integer else 'a real number'}, got {v!r}") from None
            else:
                try:
                    x = float(v)  # numbers.Real, NumPy scalars, Decimal, Fraction
                except (TypeError, ValueError):
                    raise TypeError(f"{key}: expected {'an integer' if integer else 'a real number'}, got {type(v).__name__} {v!r}") from None
            if math.isnan(float(x)):
                raise ValueError(f"{key}: NaN is not a value")
            if integer and not float(x).is_integer():
                raise ValueError(f"{key}: expected an integer, got {v!r}")
            return int(x) if integer and not isinstance(v, str) else v

        for key, value in options.items():
            kind = kinds.get(key)
            if kind in ("int", "real"):
                if _is_sequence(value):
                    raise TypeError(f"{key}: expected one number, got a sequence {value!r}")
                options[key] = number(key, value, kind == "int")
            elif kind in ("int list", "real list"):
                if isinstance(value, str):  # the option's own text, "0,0.02,-0.03"
                    values = [v for v in value.split(",") if v.strip()]
                else:
                    values = list(np.asarray(value, dtype=object).ravel()) if _is_sequence(value) else [value]
                if not values:
                    raise ValueError(f"{key}: an empty sequence (give at least one value)")
                checked = [number(key, v, kind == "int list") for v in values]
                if not isinstance(value, str):
                    options[key] = checked if _is_sequence(value) else checked[0]

    def _init(self, comm, options):
        global _solver_count
        self._check_option_names(options)
        self._check_option_values(options)
        _solver_count += 1
        self.prefix = f"adhbem{_solver_count}_"
        comm = PETSc.COMM_WORLD if comm is None else comm
        if not isinstance(comm, PETSc.Comm):
            comm = PETSc.Comm(comm)
        self._options = dict(options)
        opts = PETSc.Options()
        self._keys = []
        for key, value in options.items():
            name = f"{self.prefix}adh_{key}"
            opts[name] = _option_value(value)
            self._keys.append(name)
        try:
            self._petsc = _adhbem.solver_create(comm, self.prefix)
        except BaseException:
            self._forget_options()
            raise

    def _forget_options(self):
        # The options stay while the solver lives: operators made later (bounding-box windows)
        # read the -adh_fftw_* ones.
        try:
            opts = PETSc.Options()
            for name in self._keys:
                opts.delValue(name)
        except Exception:  # PETSc already finalised at interpreter exit
            pass
        self._keys = []

    def __del__(self):
        self._forget_options()

    @property
    def _s(self):
        """The C solver; a destroyed Solver refuses to be used."""
        obj = getattr(self, "_petsc", None)
        if obj is None:
            raise RuntimeError("this Solver was destroyed (Solver.destroy() or the end of its with-block)")
        return obj

    def destroy(self) -> None:
        """Frees the solver and its PETSc objects now. Collective: every rank calls it (as they
        created it), which is why a parallel script should free solvers this way, or with
        ``with adhbem.Solver(...) as s:``, rather than leave them to each rank's garbage collector.
        A destroyed solver can no longer be used; fields and the compliance taken from it stay
        valid (petsc4py holds its own references)."""
        obj, self._petsc = getattr(self, "_petsc", None), None
        if obj is not None:
            obj.destroy()  # PETSc's reference counting: the C solver goes with the last reference
        self._forget_options()

    @property
    def petsc(self) -> PETSc.Object:
        """The C solver as a petsc4py ``PETSc.Object`` (class ``AdhSolver``): name it
        (``setName``), view it (``view()`` prints what ``-adh_view`` prints), compose objects
        with it, hold a reference to it."""
        return self._s

    @property
    def grid(self) -> PETSc.Object:
        """The solver's element grid as a petsc4py ``PETSc.Object`` (class ``AdhGrid``): ``view()``
        prints its elements, element sizes and domain. It holds a reference of its own, so it
        stays valid after the solver is destroyed."""
        return _adhbem.solver_grid(self._s)

    def __enter__(self) -> "Solver":
        return self

    def __exit__(self, *exc) -> None:
        self.destroy()

    def start(self, d: float) -> dict:
        """Computes the starting state and begins a new curve with it.

        Parameters
        ----------
        d : float
            The indentation (a force under ``control="force"``); the state is adhesion-free or
            loaded from first touch as the option ``start`` says.

        Returns
        -------
        dict
            The state: a value per column of ``curve()``.
        """
        return self._derived(_adhbem.solver_start(self._s, float(d)))

    def step(self, d: float) -> dict:
        """One step from the current contact set, appended to the curve.

        Parameters
        ----------
        d : float
            The indentation (a force under ``control="force"``) to step to.

        Returns
        -------
        dict
            The state reached: a value per column of ``curve()``.
        """
        return self._derived(_adhbem.solver_step(self._s, float(d)))

    def state(self) -> dict:
        """The current state, a value per column of ``curve()``, without recording it."""
        return self._derived(_adhbem.solver_state(self._s))

    def _cell_area(self) -> float:
        """The grid's area Lx Ly (fixed at set-up: asked for once), and whether it is a periodic cell."""
        if getattr(self, "_cell", None) is None:
            objects = _adhbem.solver_objects(self._s)
            self._cell = objects["Lx"] * objects["Ly"]
            self._periodic = objects["boundary"] == "periodic"
        return self._cell

    def _derived(self, state: dict) -> dict:
        """A state with the columns the results file derives: area_fraction, and on a periodic
        cell mean_pressure."""
        cell = self._cell_area()
        state["area_fraction"] = state["area"] / cell
        if self._periodic:
            state["mean_pressure"] = state["force"] / cell
        return state

    def solve_path(self, progress: Optional[bool] = None) -> dict:
        """Runs the option ``path`` and returns the curve (see ``curve()``).

        With the option ``output``, writes the results file as it goes (and the fields of its
        states with the option ``fields``); ``checkpoint`` and ``restart`` work as for the
        executable. Before the path it prints a rough surface's stickiness (``stickiness``), at
        the end how well the grid resolves the adhesion (``resolution``).

        Parameters
        ----------
        progress : bool or None, optional
            ``None`` (default): a progress bar with the time left on rank 0 when tqdm is
            installed and the output is a terminal, else the library's progress lines (one after
            ``progress`` seconds, the option, then now and then). ``True``: the bar wherever tqdm
            is installed. ``False``: quiet: no progress, no stickiness and no resolution lines.

        Returns
        -------
        dict of numpy.ndarray
            The curve, a row per recorded state.
        """
        import sys
        use_bar = False
        if progress is not False:
            # rank 0 decides for all: every rank must register the same monitors (each is collective)
            comm = self.compliance.getComm().tompi4py()
            use_bar = comm.bcast(_have_tqdm() and (progress is True or sys.stderr.isatty()), root=0)
        bar = self._progress_bar() if use_bar else None
        before = _adhbem.solver_progress(self._s, 0.0) if (use_bar or progress is False) else None
        if progress is not False:
            _adhbem.solver_stickiness_view(self._s)  # a rough surface's, before the path (as the executable)
        try:
            _adhbem.solver_solve_path(self._s)
        finally:
            if before is not None:
                _adhbem.solver_progress(self._s, before)
            if bar is not None:
                bar.close()
            self._bar = None
        if progress is not False:
            _adhbem.solver_resolution_view(self._s)  # the lines the executable prints at the end
        return self.curve()

    def _progress_bar(self):
        """A tqdm bar over the path's states on rank 0 (None elsewhere), moved by a monitor that
        every rank registers once. The monitor holds the solver weakly: the C solver it is
        registered with is the solver's own, and a strong reference would keep both alive."""
        from tqdm.auto import tqdm
        if not getattr(self, "_bar_monitor", False):
            import weakref
            solver = weakref.ref(self)

            def move(step, state):
                s = solver()
                if s is not None:
                    s._move_bar(step, state)
            self.monitor(move)
            self._bar_monitor = True
        if self.compliance.getComm().getRank() != 0:
            return None
        path, steps, _ = _adhbem.solver_path(self._s)
        self._bar = tqdm(total=1 + (len(path) - 1) * steps, unit="state", desc="adhbem", leave=True)
        return self._bar

    def _move_bar(self, step, state):
        bar = getattr(self, "_bar", None)
        if bar is not None:
            bar.n = step + 1  # a leg that ends by pull-off skips its remaining states
            bar.set_postfix(d=f"{state['d']:.4g}", F=f"{state['force']:.4g}", refresh=False)
            bar.refresh()

    def iterate_path(self) -> Iterator[dict]:
        """Runs the option ``path`` as ``solve_path()`` does, a state at a time.

        Yields
        ------
        dict
            Each state (a value per column of ``curve()``), with the solver's fields current, on
            every rank; it is appended to the curve.

        Notes
        -----
        All ranks must take the same states: a ``break`` on one rank only leaves the others
        waiting. With the option ``output`` the results file is written as it goes, as
        ``solve_path()`` writes it: each state's row, and with ``fields`` its fields, before it is
        yielded; the file gets its name when the loop ends (``complete`` 1 at the path's end, 0
        after a ``break`` or an exception). The options ``checkpoint`` and ``restart`` are
        ``solve_path()``'s. As in ``solve_path()``, a pull-off ends the path unless the option
        ``stop_at_pulloff`` is false (then only its leg ends).

        Examples
        --------
        >>> for state in s.iterate_path():
        ...     p = s.pressure_array()          # this state's pressure, (Ny, Nx)
        """
        for name in ("checkpoint", "restart"):
            if name in self._options:
                raise ValueError(f"iterate_path: option {name!r} is solve_path()'s (a loop of the caller's cannot be "
                                 "restarted from inside)")
        output = self._options.get("output")
        path, steps, stop_at_pulloff = _adhbem.solver_path(self._s)
        state = self.start(path[0])
        complete = False
        if output is not None:
            _adhbem.solver_output_begin(self._s, os.fspath(output))
        try:
            yield self._recorded(state, output)
            for a, b in zip(path[:-1], path[1:]):
                for k in range(1, steps + 1):
                    # the targets of solve_path, to the last bit
                    state = self.step(a + (b - a) * k / steps)
                    yield self._recorded(state, output)
                    if state["pulled_off"]:
                        break  # the rest of this leg has nothing in contact
                if state["pulled_off"] and stop_at_pulloff:
                    break  # and the path ends there unless stop_at_pulloff=False
            complete = True
        finally:  # the loop's end, a break (GeneratorExit) or an exception: the file under its name
            if output is not None:
                _adhbem.solver_output_end(self._s, complete)

    def _recorded(self, state: dict, output) -> dict:
        """state, written into the results file of iterate_path() first when there is one."""
        if output is not None:
            _adhbem.solver_output_record(self._s)
        return state

    def monitor(self, fn: Callable[[int, dict], None]) -> None:
        """Adds a function called on every rank after each recorded state.

        Parameters
        ----------
        fn : callable
            ``fn(step, state)``: ``step`` the curve row, ``state`` a dict of the curve's columns.
            The solver's fields are current inside it, so it can read or save them; an exception
            it raises stops the path and comes out of ``solve_path()``.
        """
        import weakref
        solver = weakref.ref(self)  # the C solver holds the monitor: no cycle back to this object

        def with_derived(step, state):
            s = solver()
            fn(step, s._derived(state) if s is not None else state)
        _adhbem.solver_monitor(self._s, with_derived)

    @property
    def largest_tension(self) -> float:
        """The largest tension the contact carried over the curve, -min(force) (0.0 without
        tension), whether or not the surfaces came apart."""
        F = self.curve()["force"]
        return max(0.0, -float(F.min())) if len(F) else 0.0

    @property
    def pull_off_force(self) -> float:
        """The pull-off force: the largest tension, when the surfaces came apart (a state ended in
        pull-off); NaN when they did not (full contact to the end, or a path that ended in
        contact: ``resolution["apart"]`` is -1), as the results file's ``pull_off_force``."""
        return self.largest_tension if self.resolution["apart"] >= 0 else float("nan")

    @property
    def resolution(self) -> dict:
        """How well the grid resolves the adhesion, as a dict (the lines ``solve_path()`` prints):

        - ``asperity_contact_radius``: the JKR contact radius at pull-off of the sphere or of the
          smallest asperities (from the surface's mean summit curvature), in grid spacings, estimated
          at set-up from the profile (0.0: no estimate: no adhesion, or a shape without one);
        - ``asperity_tabor``: with a finite-range criterion (``dugdale``, ``exponential``), the
          Tabor parameter of the same sphere or asperities (Maugis' lambda, Tabor's mu; 0.0: none);
        - ``touched``: whether any recorded state had a point in contact;
        - ``state``, ``force``: the curve row of the largest tension and its force (-1, 0.0: none);
        - ``small_patch_tension``, ``smallest_tensile_patch``: there, the share of the tension
          carried by contact patches under 314 elements, and the smallest patch with a net tension;
        - ``cohesive_elements``, ``cohesive_width``: with a finite-range criterion, the elements its
          cohesive zone covers there, and how many grid spacings wide the zone is (a sphere's
          annulus; on other profiles the zone's area over the mean of its inner and outer edges,
          ``contact_perimeter`` and ``cohesive_perimeter``; under 10 the
          pull-off force depends on the grid; 0.0: no zone);
        - ``resolved``: the verdict (``None`` before a state carried tension);
        - ``unresolved``: why not, the rule's parts that failed there: ``"patches"`` (a zero-range
          criterion's: more than 10% of the tension on patches under 314 elements), ``"asperities"`` (``asperity_contact_radius``
          under 10), ``"zone"`` (the cohesive zone under 10 spacings wide); empty when resolved;
        - ``apart``: the first curve row where the surfaces came apart (-1: they did not, and the
          largest tension is no pull-off force); ``full_contact``: the first row in full contact,
          every grid point in the set (-1: none); ``last_points``: the points in contact at the
          last row; ``stopped``: the row at which a pull-off ended ``solve_path()`` with legs
          left (the option ``stop_at_pulloff``, true by default; -1: it did not).

        The results file holds the same as ``asperity_contact_radius``, ``adhesion_resolved``,
        ``adhesion_unresolved_by`` (the reasons in words), ...
        """
        r = _adhbem.solver_resolution(self._s)
        r["unresolved"] = [why for why in r["unresolved"] if why]
        return r

    @property
    def stickiness(self) -> Optional[dict]:
        """Whether a rough surface is sticky, estimated at set-up from its heights (the line
        ``solve_path()`` prints first), as a dict; ``None`` without an estimate (it is made for a
        rough surface, a topography file or an array, with adhesion, on either boundary; on the free
        boundary the slope is from forward and the curvature from second differences, as
        SurfaceTopography takes them for a map, and
        U_el is that of the map less its mean plane taken as one periodic cell):

        - ``rms_slope``, ``rms_curvature``: h'_rms (the rms of the gradient's length) and h''_rms
          (the rms of the mean curvature, half the Laplacian), as SurfaceTopography defines them;
        - ``full_contact_energy``: U_el / A0, the elastic energy per area that flattens the surface;
        - ``work_of_adhesion``: dgamma (with a ``gamma_field``, its mean);
        - ``persson_tosatti``: U_el / (dgamma A0) (Persson & Tosatti 2001); below 1 the surface sticks
          everywhere once in contact, and a compressive mean pressure is reached only in full contact;
        - ``range``: the criterion's range Delta r (``dugdale``: dgamma / dugdale_stress;
          ``exponential``: exponential_range; 0.0 for the zero-range criteria);
        - ``pastewka_robbins``: h'_rms E* Delta r / (2 dgamma) (h'_rms^2 / (h''_rms Delta r))^(2/3)
          (Pastewka & Robbins 2014, eq. 10); below 1 sticky (0.0 without a range);
        - ``generalized_tabor``: (R dgamma^2 / (E*^2 Delta r^3))^(1/3) with R = 1 / h''_rms (0.0
          without a range);
        - ``sticks_everywhere``, ``sticky``: the verdicts (Persson-Tosatti below 1; that, or
          Pastewka-Robbins below 1); ``sticky`` is ``None`` when neither says (a zero-range
          criterion on a surface that does not stick everywhere: the run tells).

        The results file holds the same as root attributes ``stickiness_persson_tosatti``,
        ``stickiness_pastewka_robbins``, ``stickiness_tabor`` (this ``generalized_tabor``),
        ``stickiness_range``, ``stickiness_work_of_adhesion``, ``stickiness_rms_slope``, ...,
        ``sticks_everywhere`` and ``sticky`` (absent where it is ``None`` here).
        """
        return _adhbem.solver_stickiness(self._s)

    def contact_mask(self) -> PETSc.Vec:
        """A new Vec on the grid: 1.0 on the points of the contact set, 0.0 elsewhere
        (``contact_array()`` gives it as a NumPy bool array)."""
        v = self.pressure.duplicate()
        v.set(0.0)
        r0, _ = v.getOwnershipRange()
        v.getArray()[self.contact_set.getIndices() - r0] = 1.0
        return v

    def curve(self) -> dict:
        """The recorded states: a dict of NumPy arrays, an entry per state, the columns of the
        results file's ``/curve`` (counts int64):

        - ``d``, ``force``, ``area``, ``contact_points``: the state (indentation, or the force
          target's d under force control; force F = sum p hx hy; contact area);
        - ``outer_iterations``, ``ksp_iterations``, ``compliance_applications``, ``fft_pairs``,
          ``seconds``: its cost (set updates, CG iterations, compliance applications,
          forward+backward FFT pairs, wall time; under a cohesive law the minimisation's Newton
          steps and their CG iterations, or with ``minimize_direction="polak-ribiere"`` one a
          minimisation and its iterations);
        - ``patches``: connected clusters of the contact set; ``mean_gap``: the gap's mean;
        - ``max_tension_ratio``: the largest tension over Sigma; ``detach_ratio``: the
          criterion's largest demand over its limit (1: a point is about to let go);
        - ``area_tension``: area of the contact set carrying tension, p < 0;
        - ``area_compression``: area of the contact set carrying compression, p > 0;
        - ``pulled_off``: 1 on the state where the contact was lost (the leg ends there);
        - ``smallest_tensile_patch``, ``small_patch_tension``: the smallest patch with a net
          tension, and the share of the tension carried by patches under 314 points;
        - ``cohesive_area``, ``cohesive_force``: the cohesive zone, the area off the contact that
          carries a traction (``dugdale``'s, and a law's within its zone gap), and the force of the
          traction off the contact, included in ``force`` (0 in the JKR limit);
        - ``contact_perimeter``: the length of the contact's edge (its element edges facing a point
          off the contact, times pi/4, the mean ratio of a curve's length to its staircase's; exact
          on average for isotropic edges, 4/pi too short along a grid line); ``cohesive_perimeter``:
          the same of the contact with its cohesive zone, the zone's outer edge;
        - ``area_fraction``: the area over the grid's area Lx Ly (on a free boundary the
          fraction of the grid, for a measured map of the scan, in contact); on a periodic cell
          also ``mean_pressure``, the force over the cell's area.

        The states ``start()``, ``step()``, ``state()``, ``iterate_path()`` and the monitors
        give have the same keys.

        ``adhbem.load(FILE).to_pandas()`` gives the same columns of a results file as a DataFrame.
        """
        curve = {k: np.asarray(v) for k, v in _adhbem.solver_curve(self._s).items()}
        cell = self._cell_area()
        curve["area_fraction"] = curve["area"] / cell
        if self._periodic:
            curve["mean_pressure"] = curve["force"] / cell
        return curve

    def write(self, file: Union[str, os.PathLike]) -> None:
        """Writes the curve to a results file and its CSV (with the option ``fields``, the current
        fields too, as those of the last row).

        Parameters
        ----------
        file : str or os.PathLike
            ``FILE.h5``; the curve also goes to ``FILE.csv``.
        """
        _adhbem.solver_write(self._s, str(file))

    def view(self) -> None:
        """Prints the solver's set-up (what ``-adh_view`` prints), on rank 0."""
        _adhbem.solver_view(self._s)

    def set_gamma_field(self, vec) -> None:
        """Sets the work of adhesion as a field dgamma(x, y), in place of the scalar ``gamma``.

        Parameters
        ----------
        vec : numpy.ndarray or petsc4py.PETSc.Vec
            An (Ny, Nx) array (every rank passes the whole of it) or a Vec on the grid
            (``make_field``), >= 0 everywhere.

        Raises
        ------
        ValueError
            For a wrong shape, NaN or Inf, or a negative value.
        """
        if not isinstance(vec, PETSc.Vec):
            vec = self._field_from_array("gamma_field", vec, nonnegative=True)
        _adhbem.solver_set_gamma_field(self._s, vec)

    def set_topography(self, topography, kind: str = "height") -> None:
        """Makes this topography the indenter (indenter ``"array"``) and clears the contact state:
        the next ``start()`` or ``solve_path()`` begins from it.

        Parameters
        ----------
        topography : numpy.ndarray or petsc4py.PETSc.Vec
            An (Ny, Nx) array (every rank passes the whole of it) or a Vec on the grid.
        kind : {'height', 'gap'}, default 'height'
            Heights z (the profile is h = max(z) - z) or the gap h itself.

        Raises
        ------
        ValueError
            For a wrong shape or NaN or Inf values.
        """
        if not isinstance(topography, PETSc.Vec):
            topography = self._field_from_array("topography", topography)
        else:
            topography = topography.copy()  # as it is now: the user may change theirs
        _adhbem.solver_set_topography(self._s, topography, str(kind))
        self._topography = topography  # kept: the solver holds a reference, libadhbem writes it

    def _field_from_array(self, name, array, nonnegative=False):
        Nx, Ny = grid_shape(self.compliance)
        try:
            raw = np.asarray(array)
        except (TypeError, ValueError) as e:  # ragged nested lists
            raise ValueError(f"{name}: expected a NumPy array of shape (Ny, Nx) = {(Ny, Nx)} or a PETSc.Vec ({e})") from None
        if raw.dtype.kind not in "iuf":  # complex, bool, object (ragged), strings: never cast silently
            what = {"c": "complex values (give the real part, np.real, if that is what is meant)", "b": "booleans",
                    "O": "Python objects (a ragged or mixed sequence?)"}.get(raw.dtype.kind, f"dtype {raw.dtype}")
            raise TypeError(f"{name}: expected real numbers, got {what}")
        try:
            a = np.asarray(raw, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ValueError(f"{name}: expected a NumPy array of shape (Ny, Nx) = {(Ny, Nx)} or a PETSc.Vec ({e})") from None
        if a.shape != (Ny, Nx):
            raise ValueError(f"{name}: expected shape (Ny, Nx) = {(Ny, Nx)}, got {a.shape}")
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name}: holds NaN or Inf values")
        if nonnegative and np.any(a < 0):
            raise ValueError(f"{name}: the work of adhesion must be >= 0, the minimum is {a.min()!r}")
        return self.make_field(a)

    def make_field(self, array=None) -> PETSc.Vec:
        """A new Vec on the grid (zero), or set from an array.

        Parameters
        ----------
        array : array_like, optional
            This rank's rows, (j1 - j0, Nx), or the whole field, (Ny, Nx).
        """
        v = self.pressure.duplicate()
        v.set(0.0)
        if array is not None:
            set_local_rows(v, self.compliance, array)
        return v

    # NumPy views of the fields. Grids are distributed by rows: local=False gathers the whole
    # (Ny, Nx) field on every rank (collective: every rank calls it), local=True gives this
    # rank's rows j0:j1 (``rows``) as a (j1 - j0, Nx) array. Copies: the solver's next step does
    # not change them.
    _ARRAYS = ("pressure", "displacement", "gap", "profile", "critical_stress", "contact")

    def array(self, name: str, local: bool = False) -> np.ndarray:
        """The field ``name`` of the current state as a NumPy array (a copy).

        Parameters
        ----------
        name : {'pressure', 'displacement', 'gap', 'profile', 'critical_stress', 'contact'}
            pressure p (tension < 0), surface displacement u = K p, gap g = h - d + u, the
            indenter's profile h, the critical stress Sigma(x, y), or the contact set as a bool
            mask.
        local : bool, default False
            False: the whole field, shape (Ny, Nx), on every rank (collective). True: this
            rank's rows ``rows[0]:rows[1]``, shape (rows[1] - rows[0], Nx).

        Returns
        -------
        numpy.ndarray
            float64, or bool for ``"contact"``; index ``[j, i]`` is the element at
            x_i = (i - Nx/2) hx, y_j = (j - Ny/2) hy.
        """
        if name not in self._ARRAYS:
            raise ValueError(f"array: no field {name!r} (one of {', '.join(self._ARRAYS)})")
        vec = self.contact_mask() if name == "contact" else self._obj(name)
        K = self.compliance
        a = local_rows(vec, K).copy() if local else gather(vec, K)
        return a.astype(bool) if name == "contact" else a

    def pressure_array(self, local: bool = False) -> np.ndarray:
        """The pressure p, a NumPy copy (see ``array``)

        Parameters
        ----------
        local : bool, default False
            False: the whole (Ny, Nx) field on every rank (collective); True: this rank's rows.
        """
        return self.array("pressure", local)

    def displacement_array(self, local: bool = False) -> np.ndarray:
        """The surface displacement u = K p, a NumPy copy (see ``array``)

        Parameters
        ----------
        local : bool, default False
            False: the whole (Ny, Nx) field on every rank (collective); True: this rank's rows.
        """
        return self.array("displacement", local)

    def gap_array(self, local: bool = False) -> np.ndarray:
        """The gap g = h - d + u, a NumPy copy (see ``array``)

        Parameters
        ----------
        local : bool, default False
            False: the whole (Ny, Nx) field on every rank (collective); True: this rank's rows.
        """
        return self.array("gap", local)

    def profile_array(self, local: bool = False) -> np.ndarray:
        """The indenter's profile h, the gap at d = 0 before deformation, a NumPy copy (see
        ``array``); for a height map z given as topography, h = max(z) - z

        Parameters
        ----------
        local : bool, default False
            False: the whole (Ny, Nx) field on every rank (collective); True: this rank's rows.
        """
        return self.array("profile", local)

    def contact_array(self, local: bool = False) -> np.ndarray:
        """The contact set as a NumPy bool mask (see ``array``)

        Parameters
        ----------
        local : bool, default False
            False: the whole (Ny, Nx) field on every rank (collective); True: this rank's rows.
        """
        return self.array("contact", local)

    @property
    def rows(self) -> tuple[int, int]:
        """(j0, j1): the grid rows this rank owns (``array(..., local=True)`` gives them)."""
        return row_range(self.compliance)

    @property
    def critical_stress(self) -> float:
        """The critical stress Sigma of the scalar work of adhesion on this grid
        (``critical_stress_field`` gives Sigma(x, y) of a dgamma field)."""
        return _adhbem.solver_critical_stress(self._s)

    def _obj(self, name):
        return _adhbem.solver_objects(self._s, name)[name]

    # The solver's own petsc4py objects, of the current state (not copies: the next step changes
    # them; the *_array methods give NumPy copies)
    @property
    def pressure(self) -> PETSc.Vec:
        """The pressure p on the grid (compression > 0, tension < 0)."""
        return self._obj("pressure")

    @property
    def displacement(self) -> PETSc.Vec:
        """The surface displacement u = K p."""
        return self._obj("displacement")

    @property
    def gap(self) -> PETSc.Vec:
        """The gap g = h - d + u."""
        return self._obj("gap")

    @property
    def profile(self) -> PETSc.Vec:
        """The indenter's profile h (the gap at d = 0 before deformation)."""
        return self._obj("profile")

    @property
    def critical_stress_field(self) -> PETSc.Vec:
        """The critical stress Sigma(x, y) on the grid."""
        return self._obj("critical_stress")

    @property
    def compliance(self) -> PETSc.Mat:
        """The compliance K (u = K p), a MatShell applied with distributed FFTW."""
        return self._obj("compliance")

    @property
    def contact_set(self) -> PETSc.IS:
        """The contact set: the grid points in contact, as global indices (row-major, j Nx + i)."""
        return self._obj("contact_set")

    @property
    def spacing(self) -> tuple[float, float]:
        """(hx, hy): the grid spacing."""
        return self._obj("hx"), self._obj("hy")


def _have_tqdm():
    try:
        import tqdm  # noqa: F401
        return True
    except ImportError:
        return False


# Solver's keywords, their defaults and their documentation, from the library's option table.
_PYTHON_ONLY = {
    "comm": ("mpi4py.MPI.Comm or petsc4py.PETSc.Comm, optional",
             "The ranks the solver runs on (default: ``PETSc.COMM_WORLD``)."),
    "topography": ("str or os.PathLike or numpy.ndarray or petsc4py.PETSc.Vec or SurfaceTopography, optional",
                   "The indenter's profile: a file (.npy of shape (Ny, Nx), or HDF5), a NumPy array of shape "
                   "(Ny, Nx) (every rank passes the whole array), a Vec on the grid, or a SurfaceTopography "
                   "topography (its grid, sizes and periodicity become ``n``, ``size`` and ``boundary``)."),
    "topography_kind": ("{'height', 'gap'}, default 'height'",
                        "What ``topography`` holds: heights z (profile h = max(z) - z) or the gap h itself."),
    "gamma_field": ("str or os.PathLike or numpy.ndarray or petsc4py.PETSc.Vec, optional",
                    "The work of adhesion as a field dgamma(x, y), (Ny, Nx): a file, an array or a Vec. It "
                    "replaces ``gamma`` in the critical stress."),
}
_OTHER_GROUPS = ("solver tuning", "compliance")  # numpydoc's "Other Parameters"


def _entry(name, kind, text):
    import textwrap
    body = textwrap.fill(text, width=88, initial_indent="    ", subsequent_indent="    ")
    return f"{name} : {kind}\n{body}"


def _option_entry(o):
    from .options import python_text
    if o.default is None:
        kind = f"{o.python_type}, optional"
    elif o.kind == "choice" or o.kind == "str":
        kind = f"{o.python_type}, default {o.default!r}"
    else:
        kind = f"{o.python_type}, default {o.default!r}"
    return _entry(o.name, kind, f"{python_text(o.text)} (``-adh_{o.name}``)")


def _document_solver():
    """Solver's signature and the Parameters of its docstring, from the option table."""
    import inspect
    from .options import solver_options
    table = [o for o in solver_options() if o.name not in _PYTHON_ONLY]
    main = [o for o in table if o.group not in _OTHER_GROUPS]
    other = [o for o in table if o.group in _OTHER_GROUPS]
    lines = ["Parameters", "----------"]
    lines += [_entry(k, *v) for k, v in _PYTHON_ONLY.items()]
    lines += [_option_entry(o) for o in main]
    lines += ["", "Other Parameters", "----------------"]
    lines += [_option_entry(o) for o in other]
    lines += [_entry("**petsc_options", "optional", "PETSc's options of the solver's KSPs, without ``-adh_``: "
                     "``ksp_type``, ``ksp_rtol``, ``pc_type``, ``local_ksp_rtol``, ... (a misspelled one is "
                     "refused at set-up).")]
    doc = inspect.cleandoc(Solver.__doc__)
    head, _, tail = doc.partition("\nExamples\n--------\n")
    Solver.__doc__ = head + "\n" + "\n".join(lines) + "\n\nExamples\n--------\n" + tail
    P = inspect.Parameter
    params = [P("comm", P.POSITIONAL_OR_KEYWORD, default=None)]
    params += [P(k, P.KEYWORD_ONLY, default=None) for k in ("topography", "topography_kind", "gamma_field")]
    params += [P(o.name, P.KEYWORD_ONLY, default=o.default) for o in table]
    params += [P("petsc_options", P.VAR_KEYWORD)]
    Solver.__signature__ = inspect.Signature(params)


_document_solver()
