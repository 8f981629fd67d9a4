"""`--executor slurm`: a batch command's Dask workers as SLURM jobs, through dask-jobqueue's
SLURMCluster.

One job per Dask worker, one core and one thread each; the worker hands its runs, one at a time,
to a bpy process of its own (pool.run_here), exactly as on any Dask cluster. The scheduler runs in
the command's own process; the jobs need the repository, --out and the Python at the same paths
(a shared file system). Options left out fall back to dask-jobqueue's configuration
(~/.config/dask/jobqueue.yaml, section jobqueue.slurm), then to the defaults named in --help.
"""
from __future__ import annotations

import contextlib
import os
import re
import signal
import subprocess
import sys
import threading

from ..plans import PlanError

JOB_LOGS = "slurm"  # under --out: one .out and one .err file per job
MEMORY = "2GB"  # per job: a bpy worker (~0.45 GB at 20-40 layers) plus the Dask worker and nanny
JOB_NAME = "fibrilfit"
MAX_JOBS = 16  # the default --workers: one job per run to do, at most this many

# sbatch --time: minutes, minutes:seconds, hours:minutes:seconds, days-hours,
# days-hours:minutes, days-hours:minutes:seconds
_WALLTIME = re.compile(r"\d+(:\d{1,2}){0,2}|\d+-\d+(:\d{1,2}){0,2}")
_MEMORY = re.compile(r"\d+(\.\d+)?\s*([kmgt]i?b?)?", re.IGNORECASE)
OPTIONS = ("partition", "account", "memory", "walltime", "job_name", "job_directive",
           "job_prologue", "python", "interface", "show_job_script")


@contextlib.contextmanager
def ctrl_c_kept():
    """Importing dask_jobqueue sets SIGINT to sys.exit() (its runner.py), so Ctrl-C would end the
    sweep with exit 0, past the interrupted-sweep handling (exit 130, jobs cancelled). Undo it."""
    main = threading.current_thread() is threading.main_thread()
    previous = signal.getsignal(signal.SIGINT) if main else None
    try:
        yield
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)


def given(values) -> list[str]:
    """The SLURM fields set, in OPTIONS order: of an executor plan (batch/plans.py), or of a
    mapping of the values given for one (api/plans.py's RunPlan.refuse, before it is made)."""
    get = values.get if isinstance(values, dict) else lambda name: getattr(values, name)
    return [name for name in OPTIONS if get(name) not in (None, [], (), False)]


def check(plan) -> None:
    """Usage errors in an executor plan's SLURM fields (before anything is written or
    submitted)."""
    if plan.executor != "slurm":
        named = given(plan)
        if named:
            raise PlanError(named[0], "only with --executor slurm")
        return
    if plan.walltime is not None and not _WALLTIME.fullmatch(plan.walltime):
        raise PlanError("walltime", f"must be a SLURM time such as 30, 04:00:00 or "
                        f"1-12:00:00 (got '{plan.walltime}')")
    if plan.memory is not None and not _MEMORY.fullmatch(plan.memory.strip()):
        raise PlanError("memory", f"must be a size such as 2GB or 1500MB "
                        f"(got '{plan.memory}')")
    if plan.python is not None and not os.access(plan.python, os.X_OK):
        raise PlanError("python", f"'{plan.python}' is not an executable file here "
                        f"(the jobs need it at the same path)")
    for line in plan.job_directive:
        if not line.startswith("-"):
            raise PlanError("job_directive", f"must be an sbatch option such as "
                            f"--qos=short (got '{line}')")


def jobs(plan, runs: int) -> int:
    """How many SLURM jobs (= Dask workers) to keep: --workers, else one per run, at most 16."""
    return plan.workers or max(1, min(runs, MAX_JOBS))


def cluster_options(plan, out) -> dict:
    """SLURMCluster's keyword arguments for these options (--out: where the job logs go)."""
    import dask
    memory = plan.memory or dask.config.get("jobqueue.slurm.memory", None) or MEMORY
    return dict(
        cores=1, processes=1, memory=memory.replace(" ", ""),
        walltime=plan.walltime, queue=plan.partition, account=plan.account,
        job_name=plan.job_name or JOB_NAME,
        python=plan.python or sys.executable,
        job_extra_directives=list(plan.job_directive),
        job_script_prologue=list(plan.job_prologue),
        interface=plan.interface,
        log_directory=str(out / JOB_LOGS),
        scheduler_options={"dashboard": False, "dashboard_address": ":0"},  # no port clash
    )


def job_script(plan, out) -> str:
    """The batch script each job runs (what --show-job-script prints); submits nothing."""
    with ctrl_c_kept():
        from dask_jobqueue import SLURMCluster
    logs = out / JOB_LOGS
    made = [d for d in (logs, *logs.parents) if not d.exists()]  # dask-jobqueue makes the log dir
    try:
        with SLURMCluster(**cluster_options(plan, out)) as cluster:
            return cluster.job_script()
    finally:
        for d in made:  # deepest first: leave no empty folders behind
            if d.is_dir() and not any(d.iterdir()):
                d.rmdir()


def submit_error(exc: BaseException) -> str:
    """The line worth showing from a failed sbatch (dask-jobqueue quotes its whole output)."""
    text = str(exc)
    lines = [line.strip() for line in text.splitlines() if "error" in line.lower()]
    sbatch = [line for line in lines if line.startswith("sbatch:")]
    return (sbatch or lines or [text.strip().splitlines()[0] if text.strip() else repr(exc)])[0]


def alive_jobs(states, *, timeout: float = 30.0) -> set | None:
    """The ids of this user's SLURM jobs in one of `states` (squeue's long state names), or None
    when squeue gives no answer (not on the PATH, a timeout, the controller busy)."""
    import getpass
    try:
        cp = subprocess.run(["squeue", "-h", "-u", getpass.getuser(), "-o", "%i %T"],
                            capture_output=True, text=True, timeout=timeout)
    except (OSError, subprocess.TimeoutExpired):
        return None
    if cp.returncode != 0:
        return None
    alive = set()
    for line in cp.stdout.splitlines():
        parts = line.split()
        if len(parts) == 2 and parts[1] in states:
            alive.add(parts[0])
    return alive
