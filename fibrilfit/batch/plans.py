"""Where a command's many runs happen: the executor plan, declared once for every command that
runs many models (`run --restarts`, `minimal-linker`, `report`, `sweep`, and the API's
functions of the same names), and checked once.

    --executor processes|dask|slurm  --workers N  --scheduler ADDRESS  --timeout SECONDS
    SLURM: --partition --account --memory --walltime --job-name --job-directive --job-prologue
           --python --interface --show-job-script

executors.make_executor turns the plan into the executor; docs/guide/cluster.md#commands says
which command takes what. No bpy, no Dask at import: the command line's parser needs neither.
"""
from __future__ import annotations

import dataclasses
import pathlib

from ..plans import Plan, PlanError, option
from . import outdir, slurm

EXECUTORS = ("processes", "dask", "slurm")
RESTARTS_OUT = "out/restarts"  # `run --restarts` has no --out: its SLURM job logs go under this
WHERE = "where the runs happen (for run: with --restarts)"
SLURM = "SLURM (with --executor slurm)"
GROUPS = {
    WHERE: "Local worker processes, a Dask cluster, or SLURM jobs (dask-jobqueue); the same "
           "options for every command that runs many models (docs/guide/cluster.md).",
    SLURM: "One SLURM job per Dask worker (1 core, 1 thread; it runs the models in a bpy "
           "process of its own). The jobs need this repository, --out and --python at the same "
           f"paths (a shared file system); their logs go to OUT/slurm/ ({RESTARTS_OUT}/slurm/ "
           "for run --restarts, which has no --out). Options left out come from "
           "dask-jobqueue's config (~/.config/dask/jobqueue.yaml, jobqueue.slurm), then the "
           "defaults below."}


def _positive_seconds(value: float) -> str | None:
    return None if value > 0 else f"must be a positive number of seconds (got {value:g})"


@dataclasses.dataclass(frozen=True)
class ExecutorPlan(Plan):
    """Where the runs happen: local worker processes, a Dask cluster, or SLURM jobs."""

    executor: str = option("processes", "local worker processes, Dask, or SLURM jobs "
                                        "(dask-jobqueue)", choices=EXECUTORS, group=WHERE)
    workers: int | None = option(None, "worker processes (local, or a Dask LocalCluster) "
                                       "[default: CPU count]; with --executor slurm, SLURM jobs "
                                       f"[default: one per run, at most {slurm.MAX_JOBS}]",
                                 kind=int, lo=1, metavar="N", group=WHERE)
    scheduler: str | None = option(None, "with --executor dask: an existing scheduler, e.g. "
                                         "tcp://host:8786 [default: start a LocalCluster]",
                                   metavar="ADDRESS", group=WHERE)
    timeout: float | None = option(None, "stop a run after this long (recorded as failed, "
                                         "retried once)", kind=float, metavar="SECONDS",
                                   check=_positive_seconds, group=WHERE)
    partition: str | None = option(None, "sbatch -p [default: SLURM's default]", metavar="NAME",
                                   group=SLURM)
    account: str | None = option(None, "sbatch -A [default: none]", metavar="NAME", group=SLURM)
    memory: str | None = option(None, f"memory per job, e.g. 2GB (sbatch --mem) "
                                      f"[default {slurm.MEMORY}]", metavar="SIZE", group=SLURM)
    walltime: str | None = option(None, "per job, e.g. 04:00:00 (sbatch -t); a job that reaches "
                                        "it is replaced and its run retried [default 00:30:00]",
                                  metavar="TIME", group=SLURM)
    job_name: str | None = option(None, f"sbatch -J [default {slurm.JOB_NAME}]", metavar="NAME",
                                  group=SLURM)
    job_directive: tuple = option((), "an extra #SBATCH line, e.g. --job-directive=--qos=short; "
                                      "repeatable", kind=str, repeat=True, metavar="OPTION",
                                  group=SLURM)
    job_prologue: tuple = option((), "a shell line the job runs before the worker, e.g. "
                                     "'module load gcc'; repeatable", kind=str, repeat=True,
                                 metavar="LINE", group=SLURM)
    python: str | None = option(None, "the Python the jobs run, with bpy and distributed "
                                      "[default: this Python]", metavar="PATH", group=SLURM)
    interface: str | None = option(None, "network interface for the scheduler and workers, e.g. "
                                         "ib0 [default: Dask's choice]", metavar="NAME",
                                   group=SLURM)
    show_job_script: bool = option(False, "print the batch script each job would run, submit "
                                          "nothing, exit", group=SLURM)

    def check(self) -> None:
        """The combinations refused, one line each, before anything runs or is written."""
        if self.scheduler and self.executor != "dask":
            raise PlanError("scheduler", "only with --executor dask")
        slurm.check(self)

    def packages(self) -> list[str]:
        """The optional Python packages this executor needs."""
        return {"processes": [], "dask": ["distributed"],
                "slurm": ["distributed", "dask_jobqueue"]}[self.executor]

    def need(self) -> None:
        """Refuse in one line when a package the executor needs is missing; dask_jobqueue is
        imported with Ctrl-C kept (slurm.ctrl_c_kept)."""
        with slurm.ctrl_c_kept():
            outdir.need(*self.packages())

    def width(self, runs: int) -> int:
        """How many runs are in flight at once: the SLURM jobs, else the workers."""
        from .executors import cpu_count
        if self.executor == "slurm":
            return slurm.jobs(self, runs)
        return self.workers or cpu_count()

    def where(self, runs: int, out) -> str:
        """Where `runs` runs will happen, for a command's plan line ('4 local workers')."""
        if self.executor == "slurm":
            return (f"{slurm.jobs(self, runs)} SLURM jobs (one Dask worker each; job logs in "
                    f"{pathlib.Path(out) / slurm.JOB_LOGS})")
        if self.scheduler:
            return f"Dask scheduler {self.scheduler}"
        kind = "Dask LocalCluster" if self.executor == "dask" else "local"
        return f"{self.width(runs)} {kind} workers"

    def job_script(self, out) -> str | None:
        """With show_job_script, the batch script a job would run (its logs under `out`), else
        None. Submits nothing, writes nothing."""
        if not self.show_job_script:
            return None
        self.need()
        return slurm.job_script(self, pathlib.Path(out).resolve())
