"""The sweep command's own options (the model parameters come from cli.add_param_options)."""
from __future__ import annotations

import argparse

from ..batch import slurm
from .gate import FORM, METRICS


def add_arguments(parser: argparse.ArgumentParser) -> None:
    g = parser.add_argument_group("sweep")
    g.add_argument("--seeds", type=int, metavar="N",
                   help="run seeds 0..N-1 at every grid point [default 1]")
    g.add_argument("--seed-list", metavar="LIST",
                   help="the seeds as a list or range, e.g. 0:49 or 3,7,11 (same as --seed)")
    g.add_argument("--executor", choices=("processes", "dask", "slurm"), default="processes",
                   help="local worker processes, Dask, or SLURM jobs (dask-jobqueue) "
                        "[default processes]")
    g.add_argument("--workers", type=int, metavar="N",
                   help="worker processes (local, or a Dask LocalCluster) [default: CPU count]; "
                        "with --executor slurm, SLURM jobs [default: one per run, at most "
                        f"{slurm.MAX_JOBS}]")
    g.add_argument("--scheduler", metavar="ADDRESS",
                   help="with --executor dask: an existing scheduler, e.g. tcp://host:8786 "
                        "[default: start a LocalCluster]")
    g.add_argument("--out", metavar="DIR", default="out/sweep",
                   help="results.jsonl, summary.csv, phase.png and workers.log go here "
                        "[default out/sweep]")
    g.add_argument("--resume", action="store_true",
                   help="continue the sweep in --out: skip points already in results.jsonl")
    g.add_argument("--retry-failed", action="store_true",
                   help="with --resume: run the points recorded as failed again")
    g.add_argument("--target", type=float, default=0.95, metavar="F",
                   help="accommodated fraction for the minimal-linker table [default 0.95]")
    g.add_argument("--require", action="append", default=[], metavar="SPEC",
                   help=f"exit 1 unless it holds, {FORM}; repeatable. "
                        f"Metrics: {', '.join(METRICS)}")
    g.add_argument("--timeout", type=float, metavar="SECONDS",
                   help="stop a run after this long (recorded as failed, retried once)")
    g.add_argument("--no-plot", action="store_true", help="do not draw phase.png")
    g.add_argument("--quiet", action="store_true",
                   help="no progress bar and no table: the result lines only (for CI logs)")

    j = parser.add_argument_group(
        "SLURM (with --executor slurm)",
        "One SLURM job per Dask worker (1 core, 1 thread; it runs the models in a bpy process of "
        "its own). The jobs need this repository, --out and --python at the same paths (a shared "
        "file system); their logs go to OUT/slurm/. Options left out come from dask-jobqueue's "
        "config (~/.config/dask/jobqueue.yaml, jobqueue.slurm), then the defaults below.")
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
