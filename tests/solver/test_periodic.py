"""The periodic mode (-adh_boundary periodic): Westergaard's wavy surface against the exact
solution under both controls, full contact (force control only), the certified early stop and its
eigenvalue bound on a periodic cell, the JKR sphere on a periodic cell against the free boundary
(with a bound derived from the two operators), and the per-state contact statistics.

The periodic compliance has no mean mode (the displacement has zero mean), so the mean gap is
mean(h) - d exactly and a cell is in full contact exactly at d = mean(h).

Every test prints its key numbers (`pytest -s` shows them). Tests marked `mpi` are collective and
assert only on gathered or all-reduced values, so a failure never leaves a rank in a collective.
"""
import math
import os
import subprocess
import sys
import time

import numpy as np
import pytest

import adhbem
from adhbem import PETSc, theory
from adhbem_build import EXE
from common import _max, _min, assembled, gamma_for, jkr_scales, label_patches, rank0, say  # noqa: E402


R = 1.0   # sphere radius
E = 1.0   # reduced modulus E*


def contact_mask(s, shape):
    """The contact set as a boolean (Ny, Nx) array on every rank (indices gathered over ranks)."""
    mpi = s.pressure.getComm().tompi4py()
    mask = np.zeros(shape[0] * shape[1], dtype=bool)
    mask[np.concatenate(mpi.allgather(np.asarray(s.contact_set.getIndices())))] = True
    return mask.reshape(shape)


# ---- Westergaard's wavy surface --------------------------------------------------------------------

LAM, D_WAVE = 1.0, 0.01
P_STAR = math.pi * E * D_WAVE / LAM       # full-contact mean pressure
WAVE_GRIDS = (64, 128, 256, 512, 1024)


def westergaard_exact(pbar, M=2 ** 20):
    """(a, d, spread, mean error) of Westergaard's solution at mean pressure pbar (adhbem.theory's,
    sampled on M points): spread is max - min of h + u over the contact, mean error the sampled
    pressure's mean / pbar - 1 (both measure the reference's own sampling)."""
    a, d, spread = theory.westergaard_wave(pbar, LAM, D_WAVE, E, samples=M)
    x = (np.arange(M) - M // 2) * LAM / M
    return a, d, spread, theory.westergaard_pressure(x, pbar, LAM, D_WAVE, E).mean() / pbar - 1


def wave_gap(N):
    """The (4, N) gap array h = D (1 - cos(2 pi x/lam)), x_i = (i - N//2) lam/N, uniform in y."""
    x = (np.arange(N) - N // 2) * LAM / N
    return x, np.tile(D_WAVE * (1 - np.cos(2 * np.pi * x / LAM)), (4, 1))


def wave_solver(N, **options):
    _, h = wave_gap(N)
    options.setdefault("steps", 1)
    return adhbem.Solver(n=(N, 4), size=(LAM, 4 * LAM / N), E_star=E, gamma=0.0, boundary="periodic",
                         start="hertz", topography=h, topography_kind="gap", **options)


@pytest.mark.parametrize("fraction", [0.3, 0.6])
def test_westergaard_wavy_surface(fraction):
    """Force control at F = pbar x cell area gives d, displacement control at the exact d gives
    pbar; both errors shrink with the grid (max over N = 64, 128 at least 4x the max over
    N = 512, 1024) and are below 5e-6 (of D, of p*) at N = 1024; the contact half-width is within
    one element of the exact a."""
    pbar = fraction * P_STAR
    t0 = time.perf_counter()
    a, d_exact, spread, mean_err = westergaard_exact(pbar)
    say(f"\nWestergaard pbar = {fraction} p*: a/lam = {a:.6f}, d_exact/D = {d_exact / D_WAVE:.9f};"
        f" spread of h + u over the exact contact {spread:.1e} ({spread / D_WAVE:.1e} D),"
        f" sampled mean pressure / pbar - 1 = {mean_err:.1e}")
    # The reference itself: h + u constant over the contact, the sampled pressure has mean pbar.
    assert spread < 1e-8 * D_WAVE
    assert abs(mean_err) < 1e-8
    d_err, p_err = [], []
    for N in WAVE_GRIDS:
        cell = LAM * 4 * LAM / N
        cf = wave_solver(N, control="force", path=[pbar * cell] * 2).solve_path()
        cd = wave_solver(N, path=[d_exact] * 2).solve_path()
        d_err.append(abs(cf["d"][-1] - d_exact) / D_WAVE)
        p_err.append(abs(cd["force"][-1] / cell - pbar) / P_STAR)
        half = cf["contact_points"][-1] / 4 / 2 * LAM / N
        say(f"  N = {N:5d}: |d - d_exact|/D = {d_err[-1]:.2e}, |pbar - pbar_exact|/p* = {p_err[-1]:.2e},"
            f" half-width - a = {(half - a) * N / LAM:+.3f} elements"
            f" ({cf['contact_points'][-1]} / {cd['contact_points'][-1]} points)")
        assert abs(cf["force"][-1] / (pbar * cell) - 1) < 1e-10
        assert abs(half - a) <= LAM / N
        # mean gap = mean(h) - d, exactly in the periodic mode
        assert abs(cf["mean_gap"][-1] - (D_WAVE - cf["d"][-1])) < 1e-10 * D_WAVE
    d_err, p_err = np.array(d_err), np.array(p_err)
    say(f"  envelope coarse/fine: d {d_err[:2].max() / d_err[3:].max():.1f}x,"
        f" pbar {p_err[:2].max() / p_err[3:].max():.1f}x; {time.perf_counter() - t0:.2f} s")
    for err in (d_err, p_err):
        assert err[:2].max() >= 4 * err[3:].max()
        assert err[-1] < 5e-6


def test_full_contact(tmp_path):
    """Force control beyond full contact (pbar = 1.5 p*): every point in contact, d = mean(h) = D,
    and the pressure is the exact discrete p_i = pbar + p* cos(2 pi x_i/lam). Displacement control
    up to d >= D is refused before any work (Python: ValueError; executable: non-zero exit, the
    message says "full contact" and "-adh_control force", no results file)."""
    N = 64
    cell = LAM * 4 * LAM / N
    pbar = 1.5 * P_STAR
    s = wave_solver(N, control="force", path=[0.5 * P_STAR * cell, pbar * cell])
    c = s.solve_path()
    x, _ = wave_gap(N)
    p = adhbem.gather(s.pressure, s.compliance)
    p_exact = np.tile(pbar + P_STAR * np.cos(2 * np.pi * x / LAM), (4, 1))
    p_rel = np.max(np.abs(p - p_exact)) / pbar
    say(f"\nfull contact at pbar = 1.5 p*: {c['contact_points'][-1]} of {4 * N} points,"
        f" d/D - 1 = {c['d'][-1] / D_WAVE - 1:.1e}, max |p - p_exact| / pbar = {p_rel:.1e},"
        f" mean gap {c['mean_gap'][-1]:.1e}")
    assert c["contact_points"][-1] == 4 * N
    assert abs(c["d"][-1] / D_WAVE - 1) < 1e-12
    assert p_rel < 1e-8
    assert abs(c["force"][-1] / (pbar * cell) - 1) < 1e-10

    with pytest.raises(ValueError) as e:
        wave_solver(N, path=[0.5 * D_WAVE, 1.2 * D_WAVE], steps=4).solve_path()
    msg = str(e.value).splitlines()[-1]
    say(f"displacement control to d = 1.2 D: {msg}")
    # Refused before the solve, at the first d >= mean(h) = D (0.01025), naming mean(h) = D.
    assert "presses the periodic cell into full contact" in msg and "mean(h) = 0.01)" in msg

    out = tmp_path / "full.h5"
    # A sphere on a periodic 16 x 16 cell: mean(h) ~ 0.08, below the path's end.
    r = subprocess.run([EXE, "-adh_n", "16", "-adh_boundary", "periodic", "-adh_path", "0.01,0.2",
                        "-adh_steps", "4", "-adh_output", str(out)], capture_output=True, text=True, timeout=60)
    msg = r.stdout + r.stderr
    lines = [ln for ln in msg.splitlines() if "full contact" in ln and "-adh_control force" in ln]
    say(f"executable: exit {r.returncode}: {lines[0].strip() if lines else '(no message)'}")
    assert r.returncode != 0
    assert lines, msg[-2000:]
    # refused before any work: no results file
    assert not any(p.name.startswith("full.") for p in tmp_path.iterdir())


# ---- Certified early stop ---------------------------------------------------------------------------

def random_heights(N, L=1.0, modes=6, seed=7):
    """A smooth periodic random height map: a sum of a few cosines with random integer wave
    vectors, amplitudes and phases (the same on every rank)."""
    rng = np.random.default_rng(seed)
    x = np.arange(N) * L / N
    X, Y = np.meshgrid(x, x)
    z = np.zeros((N, N))
    for _ in range(modes):
        kx, ky = rng.integers(-4, 5, size=2)
        if kx == 0 and ky == 0:
            kx = 1
        z += rng.uniform(0.5, 1.0) / math.hypot(kx, ky) * np.cos(2 * np.pi * (kx * X + ky * Y) / L + rng.uniform(0, 2 * np.pi))
    return 0.01 * z / np.abs(z).max()


@pytest.mark.parametrize("criterion", ["pohrt-popov", "crack-closure"])
def test_certified_stop_periodic(criterion):
    """Displacement control with adhesion on a rough periodic surface: certify on and off give the
    same contact sets and forces, with fewer KSP iterations when on (pohrt-popov decides by p
    alone; crack-closure, with -adh_criterion_certify, bounds its openings' error too, through K's
    row norms)."""
    N = 64
    z = random_heights(N)
    h = z.max() - z
    opts = dict(n=N, size=1.0, E_star=E, gamma=2e-4, boundary="periodic", start="hertz", criterion=criterion,
                criterion_certify=criterion == "crack-closure", cascade_local=0,  # the exact cascade's sets
                topography=z, topography_kind="height", path=[0.25 * h.mean(), 0.6 * h.mean(), -0.02 * h.mean()], steps=8)
    t0 = time.perf_counter()
    on = adhbem.Solver(certify=True, **opts).solve_path()
    off = adhbem.Solver(certify=False, **opts).solve_path()
    Frel = np.max(np.abs(on["force"] - off["force"])) / np.max(np.abs(off["force"]))
    k_on, k_off = int(on["ksp_iterations"].sum()), int(off["ksp_iterations"].sum())
    say(f"\ncertified stop, {criterion}, periodic N={N}: {len(on['d'])} states, points {on['contact_points'].min()}"
        f" .. {on['contact_points'].max()}, largest tension/Sigma {on['max_tension_ratio'].max():.4f};"
        f" KSP iterations {k_on} (certify) vs {k_off}; max |dF| / max|F| = {Frel:.1e};"
        f" {time.perf_counter() - t0:.2f} s")
    assert np.array_equal(on["contact_points"], off["contact_points"])
    assert np.array_equal(on["patches"], off["patches"])
    assert Frel < 1e-8
    assert on["max_tension_ratio"].max() > 0.5          # the path detaches under tension
    assert k_on < k_off


@pytest.mark.parametrize("criterion", ["pohrt-popov", "crack-closure"])
def test_certified_attach_same_sets(tmp_path, criterion):
    """The attach test decided before the solve has converged (the gaps' error bounded through
    K's row norm): on a rough periodic cell with adhesion and reach attach, loading then unloading,
    it fires, and every state has the same contact set (mask), the same number of set updates and
    the same force as with -adh_certify 0, with fewer KSP iterations."""
    import h5py
    base = [EXE, "-adh_n", "64", "-adh_size", "64", "-adh_indenter", "rough", "-adh_hurst", "0.8",
            "-adh_rms_slope", "0.1", "-adh_seed", "3", "-adh_boundary", "periodic", "-adh_gamma", "0.004",
            "-adh_start", "adhesive", "-adh_attach", "reach", "-adh_path", "0,0.6,-0.4", "-adh_steps", "8",
            "-adh_fields", "contact", "-adh_criterion", criterion, "-adh_cascade_local", "0"] + (["-adh_criterion_certify"] if criterion == "crack-closure" else [])
    runs = {}
    for certify in (1, 0):
        out = tmp_path / f"c{certify}.h5"
        r = subprocess.run(base + ["-adh_certify", str(certify), "-adh_output", str(out), "-info", ":adhsolver"],
                           capture_output=True, text=True, timeout=300)
        assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
        with h5py.File(out, "r") as f:
            c = {k: f["curve"][k][()] for k in ("force", "contact_points", "outer_iterations", "ksp_iterations")}
            c["masks"] = f["fields/contact"][()]
        c["attach"] = r.stdout.count("(certified attach)")
        c["stop"] = r.stdout.count("(certified stop)")
        runs[certify] = c
    on, off = runs[1], runs[0]
    Frel = np.max(np.abs(on["force"] - off["force"])) / np.max(np.abs(off["force"]))
    say(f"\ncertified attach, {criterion}, rough 64^2: {on['attach']} certified attach stops, {on['stop']} certified stops; KSP {int(on['ksp_iterations'].sum())}"
        f" vs {int(off['ksp_iterations'].sum())} without certification; set updates {int(on['outer_iterations'].sum())};"
        f" max |dF|/max|F| = {Frel:.1e}")
    assert on["attach"] > 0 and off["attach"] == 0
    assert on["stop"] > 0 and off["stop"] == 0
    assert np.array_equal(on["masks"], off["masks"])
    assert np.array_equal(on["contact_points"], off["contact_points"])
    assert np.array_equal(on["outer_iterations"], off["outer_iterations"])
    assert Frel < 1e-8
    assert on["ksp_iterations"].sum() < off["ksp_iterations"].sum()


def test_periodic_set_eigenvalue_bound():
    """lambda_min(K_CC) >= lambda_meanfree (1 - m/N) for subsets C of m of N points of a 9 x 7
    periodic cell, lambda_meanfree = 2/(E* q_max) from the symbol."""
    Nx, Ny, Lx, Ly = 9, 7, 1.0, 7.0 / 9.0
    n = Nx * Ny
    K = adhbem.compliance((Nx, Ny), (Lx, Ly), E, "periodic", comm=PETSc.COMM_SELF)
    M = assembled(K)
    M = 0.5 * (M + M.T)
    qx = 2 * np.pi * np.fft.fftfreq(Nx, Lx / Nx)
    qy = 2 * np.pi * np.fft.fftfreq(Ny, Ly / Ny)
    lam_mf = 2 / (E * np.hypot(qx[None, :], qy[:, None]).max())
    w = np.linalg.eigvalsh(M)
    assert abs(w[0]) < 1e-14 and abs(w[1] / lam_mf - 1) < 1e-10
    rng = np.random.default_rng(3)
    worst = np.inf
    lines = []
    for m in (1, 5, 20, 40, 55, 60, 61, 62):
        margins = []
        for _ in range(20):
            C = rng.choice(n, size=m, replace=False)
            lmin = np.linalg.eigvalsh(M[np.ix_(C, C)])[0]
            bound = lam_mf * (1 - m / n)
            margins.append(lmin / bound if bound > 0 else np.inf)
            assert lmin >= bound * (1 - 1e-12)
        worst = min(worst, min(margins))
        lines.append(f"m={m}: min lambda/bound {min(margins):.3f}")
    say(f"\nperiodic K_CC bound on {Nx}x{Ny}: lambda_meanfree = {lam_mf:.6f}; " + ", ".join(lines))


# ---- JKR on a periodic cell against the free boundary ------------------------------------------------

def test_jkr_periodic_against_free():
    """Force-controlled JKR (N = 96, a_c/h = 20) on a periodic cell and with a free boundary, in
    lockstep. The images act as an extra displacement U = K_per p - K_free p (p the free pressure)
    on the contact. To first order, for the same contact set, d_per - d_free is a weighted mean of
    U over the set (weights: the flat-punch pressure K_CC^-1 1, positive), so
    |(d_per - d_free) - mean_C(U)| <= dU = max_C U - min_C U; asserted on every state before the
    pull-off where the two sets are identical (printed for all). The pull-off force changes by no
    more than U's curvature as a change of the sphere's 1/(2R): |F_per/F_free - 1| <= 2 R dU / a^2."""
    N, ratio = 96, 20.0
    ac = ratio / N
    gamma = gamma_for(ac)
    ac, dc, Fadh = jkr_scales(gamma)
    F0 = 4.0 / 3.0 * E * (1.3 * ac) ** 3 / R
    targets = np.linspace(F0, -1.2 * Fadh, 21)
    opts = dict(n=N, size=1.0, E_star=E, gamma=gamma, radius=R, start="hertz", control="force",
                path=[F0, -1.2 * Fadh], steps=20, criterion="pohrt-popov", attach="penetration")
    t0 = time.perf_counter()
    sf = adhbem.Solver(**opts)
    sp = adhbem.Solver(boundary="periodic", **opts)
    Kp = adhbem.compliance(N, 1.0, E, "periodic")
    up = Kp.createVecLeft()
    checked, rows = 0, []
    for k, F in enumerate(targets):
        a = sf.start(F) if k == 0 else sf.step(F)
        b = sp.start(F) if k == 0 else sp.step(F)
        Kp.mult(sf.pressure, up)
        U = adhbem.gather(up, Kp) - adhbem.gather(sf.displacement, sf.compliance)
        mf, mp = contact_mask(sf, (N, N)), contact_mask(sp, (N, N))
        off_f = abs(a["force"] - F) > 1e-9 * Fadh        # the force control's pull-off state
        off_p = abs(b["force"] - F) > 1e-9 * Fadh
        mean_U, dU = U[mf].mean(), U[mf].max() - U[mf].min()
        resid = (b["d"] - a["d"]) - mean_U
        same = bool(np.array_equal(mf, mp))
        rows.append(f"  {k:2d}: F~ {F / Fadh:+.3f} points {a['contact_points']}/{b['contact_points']}"
                    f" (differ {int(np.count_nonzero(mf != mp))}), d_per - d_free = {(b['d'] - a['d']) / (F / E):+.4f} F/(E* L),"
                    f" mean U {mean_U:+.3e}, residual {resid:+.2e}, dU {dU:.2e}")
        if off_f or off_p:
            break
        if same:
            checked += 1
            assert abs(resid) <= dU
    assert off_f and off_p, "a run did not come off on the path"
    Ff, Fp = a["force"], b["force"]
    an = math.sqrt(a["area"] / math.pi)
    bound = 2 * R * dU / an ** 2
    say(f"\nJKR periodic vs free (N={N}, a_c/h={ratio}), {time.perf_counter() - t0:.2f} s:")
    say("\n".join(rows))
    say(f"  pull-off {-Ff / Fadh:.4f} F_adh free vs {-Fp / Fadh:.4f} periodic ({Fp / Ff - 1:+.3%});"
        f" dU at the free pull-off {dU:.3e}, bound 2 R dU / a^2 = {bound:.2%};"
        f" identical sets checked on {checked} states")
    assert checked >= 1
    assert abs(Fp / Ff - 1) <= bound


# ---- Contact statistics ---------------------------------------------------------------------------------

def count_patches(mask, wrap):
    """Connected clusters of mask with 4-neighbours; wrap: periodic in both directions."""
    return label_patches(np.asarray(mask, bool), wrap)[1]


@pytest.mark.mpi
@pytest.mark.ranks3
@pytest.mark.parametrize("boundary", ["periodic", "free"])
def test_contact_statistics(boundary):
    """patches, mean_gap, area_tension/compression and max_tension_ratio of the last state of a
    path against the gathered fields, for a few paths (loading, unloading under tension)."""
    N = 48
    z = random_heights(N, seed=15)
    h_mean = float(np.mean(z.max() - z))
    breakpoints = [0.3 * h_mean, 0.55 * h_mean, 0.3 * h_mean, 0.05 * h_mean]
    mpi = PETSc.COMM_WORLD.tompi4py()
    ok, rows, patches_seen, crossings, seam = 1, [], [], set(), 0
    worst = dict(mean_gap=0.0, identity=0.0, ratio=0.0)
    for n in range(2, len(breakpoints) + 1):
        s = adhbem.Solver(n=N, size=1.0, E_star=E, gamma=2e-4, boundary=boundary, start="hertz",
                          topography=z, topography_kind="height", path=breakpoints[:n], steps=3)
        c = s.solve_path()
        K = s.compliance
        hx, hy = s.spacing
        mask = contact_mask(s, (N, N))
        p = adhbem.gather(s.pressure, K)
        g = adhbem.gather(s.gap, K)
        Sigma = adhbem.gather(s.critical_stress_field, K)
        prof = adhbem.gather(s.profile, K)
        ref_patches = count_patches(mask, wrap=boundary == "periodic")
        ratio = float(np.max(-p[mask] / Sigma[mask])) if mask.any() else 0.0
        ratio = max(ratio, 0.0)
        st = {k: v[-1] for k, v in c.items()}
        e_mean = abs(st["mean_gap"] - g.mean()) / h_mean
        e_id = abs(st["mean_gap"] - (prof.mean() - st["d"])) / prof.mean()
        worst["mean_gap"] = max(worst["mean_gap"], e_mean)
        worst["identity"] = max(worst["identity"], e_id)
        worst["ratio"] = max(worst["ratio"], abs(st["max_tension_ratio"] - ratio))
        checks = [
            st["contact_points"] == mask.sum(),
            st["patches"] == ref_patches,
            e_mean < 1e-12,
            math.isclose(st["area_tension"], np.count_nonzero(p[mask] < 0) * hx * hy, rel_tol=1e-12, abs_tol=0),
            math.isclose(st["area_compression"], np.count_nonzero(p[mask] > 0) * hx * hy, rel_tol=1e-12, abs_tol=0),
            abs(st["max_tension_ratio"] - ratio) <= 1e-12 * max(ratio, 1.0),
            st["max_tension_ratio"] <= 1 + 1e-9,
        ]
        if boundary == "periodic":
            checks.append(e_id < 1e-10)
        ok = min(ok, int(all(checks)))
        patches_seen.append(ref_patches)
        # Does the set cross the row blocks of 2 and 3 ranks, and the periodic seam?
        crossings.update(j for j in (N // 3, N // 2, 2 * N // 3) if np.any(mask[j - 1] & mask[j]))
        seam = max(seam, int(np.any(mask[-1] & mask[0]) or np.any(mask[:, -1] & mask[:, 0])))
        rows.append(f"  d = {st['d']:.3e}: {int(mask.sum())} points, patches {st['patches']} (reference {ref_patches}),"
                    f" tension/compression area {st['area_tension']:.4f}/{st['area_compression']:.4f},"
                    f" max tension/Sigma {st['max_tension_ratio']:.4f} (reference {ratio:.4f}), checks {checks}")
    say(f"\ncontact statistics ({boundary}, N={N}, {PETSc.COMM_WORLD.getSize()} ranks):\n" + "\n".join(rows))
    say(f"  worst |mean_gap - mean(g)|/mean(h) {worst['mean_gap']:.1e}, |mean_gap - (mean(h) - d)|/mean(h)"
        f" {worst['identity']:.1e} (asserted only periodic), |max_tension_ratio - reference| {worst['ratio']:.1e}")
    say(f"  the set crosses the rank boundaries before rows {sorted(crossings)} (2 ranks: {N // 2},"
        f" 3 ranks: {N // 3}, {2 * N // 3}); touches itself across the cell edge: {bool(seam)}")
    ok = mpi.allreduce(ok, op=_min())
    assert ok == 1
    # The paths exercise several patches, clusters across the rank boundaries and (periodic) the seam.
    assert max(patches_seen) >= 2
    assert crossings == {N // 3, N // 2, 2 * N // 3}
    if boundary == "periodic":
        assert seam == 1
