"""The sweep's own plan (the model's values come as lists from the parameter definition, the
executor's plan from batch/plans.py): the seeds, the folder, the gates, what it prints."""
from __future__ import annotations

import dataclasses

from ..plans import Plan, PlanError, option
from .gate import FORM, METRICS

SWEEP = "sweep"


def _fraction(value: float) -> str | None:
    return None if 0 < value <= 1 else f"must be a fraction above 0 and at most 1 (got {value:g})"


@dataclasses.dataclass(frozen=True)
class SweepOptions(Plan):
    """How a grid of runs is seeded, kept, summarised and gated."""

    seeds: int | None = option(None, "run seeds 0..N-1 at every grid point [default 1]",
                               kind=int, metavar="N", group=SWEEP)
    seed_list: str | None = option(None, "the seeds as a list or range, e.g. 0:49 or 3,7,11 "
                                         "(same as --seed)", metavar="LIST", group=SWEEP)
    out: str = option("out/sweep", "results.jsonl, summary.csv, phase.png and workers.log go "
                                   "here", kind="path", metavar="DIR", group=SWEEP)
    resume: bool = option(False, "continue the sweep in --out: skip points already in "
                                 "results.jsonl", group=SWEEP)
    retry_failed: bool = option(False, "with --resume: run the points recorded as failed again",
                                group=SWEEP)
    target: float = option(0.95, "accommodated fraction for the minimal-linker table",
                           metavar="F", check=_fraction, group=SWEEP)
    require: tuple = option((), f"exit 1 unless it holds, {FORM}; repeatable. "
                                f"Metrics: {', '.join(METRICS)}", kind=str, repeat=True,
                            metavar="SPEC", group=SWEEP)
    no_plot: bool = option(False, "do not draw phase.png", group=SWEEP)
    quiet: bool = option(False, "no progress bar and no table: the result lines only (for CI "
                                "logs)", group=SWEEP)

    def check(self) -> None:
        if self.retry_failed and not self.resume:
            raise PlanError("retry_failed", "only with --resume")
