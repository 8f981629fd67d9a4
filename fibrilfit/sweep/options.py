"""The sweep command's own options (the model parameters come from the command line's
add_param_options, the executor's from batch/options.py: both added by the command line)."""
from __future__ import annotations

import argparse

from .gate import FORM, METRICS


def add_arguments(parser: argparse.ArgumentParser) -> None:
    g = parser.add_argument_group("sweep")
    g.add_argument("--seeds", type=int, metavar="N",
                   help="run seeds 0..N-1 at every grid point [default 1]")
    g.add_argument("--seed-list", metavar="LIST",
                   help="the seeds as a list or range, e.g. 0:49 or 3,7,11 (same as --seed)")
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
    g.add_argument("--no-plot", action="store_true", help="do not draw phase.png")
    g.add_argument("--quiet", action="store_true",
                   help="no progress bar and no table: the result lines only (for CI logs)")
