"""An uncaught exception in a script run on several ranks, reported once.

Under ``mpirun -n P python3 script.py`` an error that every rank meets (a topography of the wrong
shape, a bad keyword) raises the same exception on every rank, and Python prints P tracebacks,
interleaved. adhbem's hook waits briefly for every rank to arrive in it (a non-blocking barrier):
when all do, rank 0 prints the traceback once and every rank exits with status 1, together, with no
MPI_Abort (so no abort banner, and every file adhbem closed stays whole). When some rank does not
arrive within ``ADHBEM_ERROR_WAIT`` seconds (default 5), the exception is that rank's alone: it
prints its traceback with its rank and calls MPI_Abort, since the others would wait for it for ever.

Installed by the solver side on first use when the world has more than one rank, and only over
Python's own hook (a hook of the user's, or mpi4py's ``-m mpi4py`` runner, stays).
"""
import os
import sys
import time
import traceback


def _hook(kind, value, tb, comm, previous):
    if kind is KeyboardInterrupt:
        return previous(kind, value, tb)
    try:
        wait = float(os.environ.get("ADHBEM_ERROR_WAIT", "5"))
    except ValueError:
        wait = 5.0
    request = comm.Ibarrier()
    deadline = time.monotonic() + wait
    everyone = request.Test()
    while not everyone and time.monotonic() < deadline:
        time.sleep(0.01)
        everyone = request.Test()
    if everyone:
        if comm.Get_rank() == 0:
            previous(kind, value, tb)
        sys.stderr.flush()
        return  # every rank leaves with status 1 (Python's for an uncaught exception)
    sys.stderr.write(f"[rank {comm.Get_rank()} of {comm.Get_size()}, alone] " + "".join(traceback.format_exception(kind, value, tb)))
    sys.stderr.flush()
    comm.Abort(1)


def install(comm) -> None:
    """Report uncaught exceptions once on comm (an mpi4py communicator of more than one rank)."""
    if comm.Get_size() < 2 or sys.excepthook is not sys.__excepthook__:
        return
    previous = sys.__excepthook__
    sys.excepthook = lambda kind, value, tb: _hook(kind, value, tb, comm, previous)
