"""Where a command's many runs happen: the executor options, declared once for every command that
runs many models (`run --restarts`, `minimal-linker`, `report`, `sweep`), and checked once.

    --executor processes|dask|slurm  --workers N  --scheduler ADDRESS  --timeout SECONDS
    SLURM: --partition --account --memory --walltime --job-name --job-directive --job-prologue
           --python --interface --show-job-script

executors.make_executor turns the parsed options into the executor; docs/guide/cluster.md#commands
says which command takes what. No bpy, no Dask at import: the parser needs neither.
"""
from __future__ import annotations

import argparse
import pathlib

from .. import exits
from . import outdir, slurm

EXECUTORS = ("processes", "dask", "slurm")
RESTARTS_OUT = "out/restarts"  # `run --restarts` has no --out: its SLURM job logs go under this


def add_executor_options(parser: argparse.ArgumentParser) -> None:
    """The executor's options and the SLURM group, as two argument groups of `parser`."""
    g = parser.add_argument_group(
        "where the runs happen (for run: with --restarts)",
        "Local worker processes, a Dask cluster, or SLURM jobs (dask-jobqueue); the same options "
        "for every command that runs many models (docs/guide/cluster.md).")
    g.add_argument("--executor", choices=EXECUTORS, default="processes",
                   help="local worker processes, Dask, or SLURM jobs (dask-jobqueue) "
                        "[default processes]")
    g.add_argument("--workers", type=int, metavar="N",
                   help="worker processes (local, or a Dask LocalCluster) [default: CPU count]; "
                        "with --executor slurm, SLURM jobs [default: one per run, at most "
                        f"{slurm.MAX_JOBS}]")
    g.add_argument("--scheduler", metavar="ADDRESS",
                   help="with --executor dask: an existing scheduler, e.g. tcp://host:8786 "
                        "[default: start a LocalCluster]")
    g.add_argument("--timeout", type=float, metavar="SECONDS",
                   help="stop a run after this long (recorded as failed, retried once)")

    j = parser.add_argument_group(
        "SLURM (with --executor slurm)",
        "One SLURM job per Dask worker (1 core, 1 thread; it runs the models in a bpy process of "
        "its own). The jobs need this repository, --out and --python at the same paths (a shared "
        f"file system); their logs go to OUT/slurm/ ({RESTARTS_OUT}/slurm/ for run --restarts, "
        "which has no --out). Options left out come from dask-jobqueue's config "
        "(~/.config/dask/jobqueue.yaml, jobqueue.slurm), then the defaults below.")
    j.add_argument("--partition", metavar="NAME", help="sbatch -p [default: SLURM's default]")
    j.add_argument("--account", metavar="NAME", help="sbatch -A [default: none]")
    j.add_argument("--memory", metavar="SIZE",
                   help=f"memory per job, e.g. 2GB (sbatch --mem) [default {slurm.MEMORY}]")
    j.add_argument("--walltime", metavar="TIME",
                   help="per job, e.g. 04:00:00 (sbatch -t); a job that reaches it is replaced "
                        "and its run retried [default 00:30:00]")
    j.add_argument("--job-name", metavar="NAME", help=f"sbatch -J [default {slurm.JOB_NAME}]")
    j.add_argument("--job-directive", action="append", default=[], metavar="OPTION",
                   help="an extra #SBATCH line, e.g. --job-directive=--qos=short; repeatable")
    j.add_argument("--job-prologue", action="append", default=[], metavar="LINE",
                   help="a shell line the job runs before the worker, e.g. "
                        "'module load gcc'; repeatable")
    j.add_argument("--python", metavar="PATH",
                   help="the Python the jobs run, with bpy and distributed "
                        "[default: this Python]")
    j.add_argument("--interface", metavar="NAME",
                   help="network interface for the scheduler and workers, e.g. ib0 "
                        "[default: Dask's choice]")
    j.add_argument("--show-job-script", action="store_true",
                   help="print the batch script each job would run, submit nothing, exit")


def defaults() -> dict:
    """Every executor option at its default, for callers without a command line (the sidebar's
    Report… button)."""
    parser = argparse.ArgumentParser(add_help=False)
    add_executor_options(parser)
    return vars(parser.parse_args([]))


def check(args) -> None:
    """Usage errors in the executor options, one line each, before anything runs or is written."""
    if args.workers is not None and args.workers < 1:
        raise exits.UsageError(f"--workers: must be at least 1 (got {args.workers})")
    if args.timeout is not None and not args.timeout > 0:
        raise exits.UsageError(f"--timeout: must be a positive number of seconds "
                               f"(got {args.timeout:g})")
    if args.scheduler and args.executor != "dask":
        raise exits.UsageError("--scheduler: only with --executor dask")
    slurm.check(args)


def packages(args) -> list[str]:
    """The optional Python packages the executor asked for needs."""
    return {"processes": [], "dask": ["distributed"],
            "slurm": ["distributed", "dask_jobqueue"]}[args.executor]


def need(args) -> None:
    """Refuse in one line when a package the executor needs is missing; dask_jobqueue is imported
    with Ctrl-C kept (slurm.ctrl_c_kept)."""
    with slurm.ctrl_c_kept():
        outdir.need(*packages(args))


def width(args, runs: int) -> int:
    """How many runs are in flight at once: the SLURM jobs, else the workers."""
    from .executors import cpu_count
    if args.executor == "slurm":
        return slurm.jobs(args, runs)
    return args.workers or cpu_count()


def where(args, runs: int, out) -> str:
    """Where `runs` runs will happen, for a command's plan line ('4 local workers')."""
    if args.executor == "slurm":
        return (f"{slurm.jobs(args, runs)} SLURM jobs (one Dask worker each; job logs in "
                f"{out / slurm.JOB_LOGS})")
    if args.scheduler:
        return f"Dask scheduler {args.scheduler}"
    kind = "Dask LocalCluster" if args.executor == "dask" else "local"
    return f"{width(args, runs)} {kind} workers"


def job_script(args, out) -> str | None:
    """With --show-job-script, the batch script a job would run (its logs under `out`), else
    None. Submits nothing, writes nothing."""
    if not getattr(args, "show_job_script", False):
        return None
    need(args)
    return slurm.job_script(args, pathlib.Path(out).resolve())
