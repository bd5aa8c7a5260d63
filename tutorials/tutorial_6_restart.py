"""
A long job stopped and restarted
================================

Batch jobs have time limits and get killed. adhbem writes its results state by state, so a job
that is stopped keeps every state it recorded, and with a checkpoint it goes on where it stopped,
giving the curve the uninterrupted run would have given. This tutorial starts a run, stops it as a
batch system's time limit does (SIGTERM), restarts it from its checkpoint, and compares the
result with a run that was never stopped. ``tutorials/jobs/rough.slurm`` is a Slurm job script
built on the same options, to copy.

Run it yourself from a clone (after ``./run build``)::

    PYTHONPATH=python /usr/bin/python3 tutorials/tutorial_6_restart.py
"""
# %%
# The job
# -------
# A rough periodic cell pressed in and pulled off, run by the executable under ``mpirun`` as a
# batch script would run it, with its results file (``-adh_output``) and a checkpoint after every
# state (``-adh_checkpoint``). ``-adh_fftw_planner estimate`` makes the FFTs the same from run to
# run, so that a restarted curve can be compared bit for bit.
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import matplotlib.pyplot as plt
import numpy as np

import adhbem

try:  # in a clone: the executable of the build ./run made
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(adhbem.__file__)), ".."))
    from adhbem_build import EXE
except ImportError:  # installed: the one on PATH
    EXE = shutil.which("adhbem")

QUICK = os.environ.get("ADHBEM_TUTORIAL_QUICK") == "1"   # the test suite runs it small
N = 64 if QUICK else 128
job = ["-adh_n", str(N), "-adh_size", str(N), "-adh_indenter", "rough", "-adh_hurst", "0.8",
       "-adh_rms_slope", "0.1", "-adh_cutoff_wavelength", str(N / 4), "-adh_seed", "2",
       "-adh_boundary", "periodic", "-adh_gamma", "0.05", "-adh_start", "adhesive",
       "-adh_path", "0,1.0,-1.0", "-adh_steps", "15" if QUICK else "30", "-adh_fftw_planner", "estimate",
       "-adh_progress", "0"]
work = tempfile.mkdtemp()
mpirun = ["mpirun", "--oversubscribe", "-n", "2", EXE]
# A Python process that started MPI itself (petsc4py: any use of adhbem's solver side) carries
# Open MPI's and PMIx's variables of its own job, which would confuse mpirun started from it: the
# jobs get the environment without them (the user's settings of running as root kept).
env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_")) or k.startswith("OMPI_ALLOW_RUN_AS_ROOT")}


def records(path):
    """The states a running job has recorded so far (the lines of its CSV journal)."""
    try:
        with open(path) as f:
            return max(sum(1 for _ in f) - 1, 0)
    except FileNotFoundError:
        return 0


# %%
# Stopped by the time limit
# -------------------------
# The job is started and sent SIGTERM after a few states, as Slurm does at its time limit (with
# ``--signal=TERM@120``, two minutes before) or on ``scancel``. adhbem abandons the step in
# progress, closes the results up to the last state (marked ``complete = 0``) and prints one line
# saying how to go on.
p = subprocess.Popen(mpirun + job + ["-adh_output", "run.h5", "-adh_checkpoint", "run.ck.h5"],
                     cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env)
while records(os.path.join(work, "run.csv.part")) < (5 if QUICK else 12) and p.poll() is None:
    time.sleep(0.05)
p.send_signal(signal.SIGTERM)
print(p.communicate()[1].strip())
with adhbem.load(os.path.join(work, "run.h5")) as r:
    stopped = r.curve
    print(f"results file: {len(stopped['d'])} states, complete = {r.params['complete']}")

# %%
# Restarted from the checkpoint
# -----------------------------
# The same command with ``-adh_restart`` goes on from the checkpoint, in the same results file.
r = subprocess.run(mpirun + job + ["-adh_output", "run.h5", "-adh_checkpoint", "run.ck.h5",
                                   "-adh_restart", "run.ck.h5"], cwd=work, capture_output=True, text=True, check=True, env=env)
print("\n".join(line for line in (r.stdout + r.stderr).splitlines() if "restart" in line))
subprocess.run(mpirun + job + ["-adh_output", "whole.h5"], cwd=work, capture_output=True, check=True, env=env)
with adhbem.load(os.path.join(work, "run.h5")) as r, adhbem.load(os.path.join(work, "whole.h5")) as w:
    restarted, whole = r.curve, w.curve
    print(f"restarted: {len(restarted['d'])} states, complete = {r.params['complete']}; "
          f"uninterrupted: {len(whole['d'])} states")
    same = len(restarted["d"]) == len(whole["d"]) and np.array_equal(restarted["force"], whole["force"])
    print(f"the restarted curve is the uninterrupted one, bit for bit: {same}")

# %%
# The curve
# ---------
# The states before the stop, those after the restart, and the uninterrupted run under them.
k = len(stopped["d"])
fig, ax = plt.subplots(figsize=(5.5, 3.6), layout="constrained")
ax.plot(whole["d"], whole["force"], color="0.6", lw=4, label="uninterrupted run")
ax.plot(restarted["d"][:k], restarted["force"][:k], "o", ms=4, label="before the stop")
ax.plot(restarted["d"][k:], restarted["force"][k:], "s", ms=4, label="after the restart")
ax.set_xlabel("indentation $d$")
ax.set_ylabel("force $F$")
ax.legend(fontsize=8)

# %%
# On a cluster
# ------------
# ``tutorials/jobs/rough.slurm`` runs the same way: Slurm sends SIGTERM ``--signal=TERM@120``
# seconds before the limit, ``srun`` passes it to every rank, and the script restarts from the
# checkpoint when one is there, so the same script is simply submitted again until the results
# file says ``complete = 1``. A job killed outright (a lost node, SIGKILL) keeps its results up to
# the last recorded state too (in ``FILE.h5.part``), and its last checkpoint is whole.
