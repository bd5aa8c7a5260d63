"""The contact-set predictor (-adh_predictor): without adhesion, Polonsky & Keer's conjugate
gradient guesses the contact set of a step (at a force or at an indentation) and the set-update
loop certifies it. The answer must be the loop's alone (-adh_predictor none): the same contact
sets in every state, the same d and forces to the solver's tolerance, for both boundaries, both
controls, and on 1 and 2 ranks; the predictor must take fewer FFT pairs, and must stay out of
adhesive runs.

Tests marked `mpi` assert only on all-reduced values."""
import numpy as np
import pytest

import adhbem
from adhbem import PETSc
from common import _max, _min, say

N = 64
# A rough periodic cell loaded, partly unloaded and loaded again (mean pressures 0.002 to 0.01 E*)
ROUGH = dict(n=N, size=float(N), boundary="periodic", indenter="rough", hurst=0.8, rms_slope=0.1, seed=3,
             gamma=0.0, start="hertz", control="force", path=[0.0, 0.01 * N * N, 0.002 * N * N, 0.006 * N * N],
             steps=3)
# The same under displacement control (d from first touch to about 6% of the cell in contact)
ROUGH_D = dict(ROUGH, control="displacement", path=[0.2, 1.0, 0.4, 0.8])
# A sphere on a free boundary, contact radius up to about 12 elements, unloaded into tension: without
# adhesion it comes off at F = 0 (the leg ends there)
HERTZ = dict(n=N, size=1.0, boundary="free", radius=1.0, gamma=0.0, start="hertz", control="force", path=[0.0, 2.5e-3, 1e-3, -1.5e-3],
             steps=3)
HERTZ_D = dict(HERTZ, control="displacement", path=[0.005, 0.02, 0.01, -0.002])
CASES = {"rough": ROUGH, "hertz": HERTZ, "rough-displacement": ROUGH_D, "hertz-displacement": HERTZ_D}


def same_states(a, b):
    """Both curves' states agree: contact counts and patches exactly, d and force to 1e-9."""
    Fs, ds = np.max(np.abs(a["force"])), np.max(np.abs(a["d"]))
    return dict(points=bool(np.array_equal(a["contact_points"], b["contact_points"])),
                patches=bool(np.array_equal(a["patches"], b["patches"])),
                F=float(np.max(np.abs(a["force"] - b["force"])) / Fs),
                d=float(np.max(np.abs(a["d"] - b["d"])) / ds))


@pytest.mark.parametrize("case", list(CASES))
def test_predictor_gives_the_loops_states_with_fewer_ffts(case):
    opts = CASES[case]
    loop = adhbem.Solver(comm=PETSc.COMM_SELF, predictor="none", **opts)
    pk = adhbem.Solver(comm=PETSc.COMM_SELF, predictor="polonsky-keer", **opts)
    masks = {"loop": [], "pk": []}
    loop.monitor(lambda k, state: masks["loop"].append(loop.contact_mask().getArray().copy()))
    pk.monitor(lambda k, state: masks["pk"].append(pk.contact_mask().getArray().copy()))
    a, b = loop.solve_path(), pk.solve_path()
    diff = same_states(a, b)
    masks_equal = all(np.array_equal(x, y) for x, y in zip(masks["loop"], masks["pk"]))
    ffts_loop, ffts_pk = int(a["fft_pairs"].sum()), int(b["fft_pairs"].sum())
    say(f"\npredictor, {case}: {len(a['d'])} states, contact points {list(b['contact_points'])},"
        f" masks equal {masks_equal}, F {diff['F']:.1e}, d {diff['d']:.1e};"
        f" FFT pairs {ffts_loop} (loop) -> {ffts_pk} (polonsky-keer),"
        f" set updates {int(a['outer_iterations'].sum())} -> {int(b['outer_iterations'].sum())}")
    assert len(masks["loop"]) == len(a["d"]) == len(b["d"]) and masks_equal
    assert diff["points"] and diff["patches"] and diff["F"] < 1e-9 and diff["d"] < 1e-9
    assert np.min(b["contact_points"][1:-1]) > 0
    if opts["boundary"] == "periodic":
        # where it is the default: on a free boundary the loop's bounding-box windows are cheaper
        assert ffts_pk < ffts_loop


@pytest.mark.parametrize("case, default", [("rough", "polonsky-keer"), ("hertz-displacement", "none")])
def test_default_predictor_follows_the_boundary(case, default):
    """polonsky-keer on a periodic cell, none on a free boundary (the same counts to the bit)."""
    a = adhbem.Solver(comm=PETSc.COMM_SELF, **CASES[case]).solve_path()
    b = adhbem.Solver(comm=PETSc.COMM_SELF, predictor=default, **CASES[case]).solve_path()
    assert np.array_equal(a["fft_pairs"], b["fft_pairs"]) and np.array_equal(a["force"], b["force"])


def test_predictor_stays_out_of_adhesive_runs():
    """With adhesion the state depends on the path: the predictor must not run (same counts)."""
    opts = dict(ROUGH, gamma=0.004, start="adhesive", attach="reach", path=[0.004 * N * N, -0.001 * N * N])
    a = adhbem.Solver(comm=PETSc.COMM_SELF, predictor="none", **opts).solve_path()
    b = adhbem.Solver(comm=PETSc.COMM_SELF, predictor="polonsky-keer", **opts).solve_path()
    assert np.array_equal(a["fft_pairs"], b["fft_pairs"]) and np.array_equal(a["force"], b["force"])


def test_unknown_predictor_is_refused():
    with pytest.raises(ValueError) as e:
        adhbem.Solver(predictor="newton", **HERTZ).solve_path()
    assert "-adh_predictor" in str(e.value) or "predictor" in str(e.value)


@pytest.mark.mpi
@pytest.mark.parametrize("case", ["rough", "rough-displacement"])
def test_predictor_on_ranks_gives_the_same_curve(case):
    world = adhbem.Solver(predictor="polonsky-keer", **CASES[case]).solve_path()
    alone = adhbem.Solver(comm=PETSc.COMM_SELF, predictor="polonsky-keer", **CASES[case]).solve_path()
    mpi = PETSc.COMM_WORLD.tompi4py()
    diff = same_states(alone, world)
    ok = mpi.allreduce(int(diff["points"] and diff["patches"]), op=_min())
    F = mpi.allreduce(diff["F"], op=_max())
    d = mpi.allreduce(diff["d"], op=_max())
    say(f"\npredictor on {PETSc.COMM_WORLD.getSize()} ranks vs 1: F {F:.1e}, d {d:.1e}")
    assert ok == 1 and F < 1e-9 and d < 1e-9
