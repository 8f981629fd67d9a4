"""The search's plans: restarts of one model (`run --restarts`), the restarts and the
minimal-linker walk (`minimal-linker`, `largest-fraction`, `report`, the sidebar's Minimal linker… and Report…,
the Python API), and the folder a batch of runs writes into. Declared once: the command line's
options and the sidebar's properties are generated from these fields (plans.py).
"""
from __future__ import annotations

import dataclasses

from ..model import params as P
from ..model.searches import DEFAULT_RESTARTS
from ..plans import Plan, PlanError, option

RESTARTS = "restarts (independent seeds of this one model)"
SEARCH = "the search: restarts and the minimal-linker walk"
OUTPUT = "where the results go"
LINKER_MAX = P.field_spec("linker")["max"]


def _width(value: float) -> str | None:
    return None if 0.0 < value < 1.0 else (f"must be between 0 and 1, exclusive "
                                           f"(got {value:g})")


@dataclasses.dataclass(frozen=True)
class RestartPlan(Plan):
    """`run --restarts R`: R seeds of the one model on the executor, the best kept."""

    restarts: int | None = option(None, "run seeds SEED..SEED+R-1 in parallel; report how many "
                                        "were accommodated, P(fit) with its 95 % Wilson "
                                        "interval, and keep the best layout (its "
                                        "--json/--blend/--pdb)", kind=int, lo=1,
                                  metavar="R", group=RESTARTS)
    stop_on_fit: bool = option(False, "with --restarts: start no more seeds once one is "
                                      "accommodated", group=RESTARTS)
    interval_width: float | None = option(None, "with --restarts: start no more seeds once "
                                                "P(fit)'s 95 % Wilson interval is at most W "
                                                "wide (0 < W < 1); P(fit) is reported from the "
                                                "runs made [default: all R]", kind=float,
                                          metavar="W", check=_width, group=RESTARTS)

    def check(self) -> None:
        if self.restarts is None:
            for name in ("stop_on_fit", "interval_width"):
                if getattr(self, name) not in (None, False):
                    raise PlanError(name, "only with --restarts")


def plot_fractions(text: str) -> tuple[float, ...]:
    """--fraction-plot's fractions, "0.25,0.5,1" -> (0.25, 0.5, 1.0); () for none. Raises
    ValueError saying what is wrong."""
    words = [w.strip() for w in str(text or "").split(",") if w.strip()]
    try:
        values = tuple(float(w) for w in words)
    except ValueError:
        raise ValueError(f"must be fractions separated by commas, e.g. 0.25,0.5,1 "
                         f"(got {text!r})") from None
    bad = [w for w, v in zip(words, values) if not 0.0 < v <= 1.0]
    if bad:
        raise ValueError(f"each fraction must be above 0 and at most 1 (got {', '.join(bad)})")
    if len(set(values)) < len(values):
        raise ValueError(f"names a fraction twice (got {text!r})")
    return values


def _fractions(text: str) -> str | None:
    try:
        plot_fractions(text)
    except ValueError as exc:
        return str(exc)
    return None


@dataclasses.dataclass(frozen=True)
class SearchPlan(Plan):
    """Restarts at every linker length the minimal-linker walk tries (and, for the report, at
    the asked linker)."""

    restarts: int = option(DEFAULT_RESTARTS, "seeds run at every linker length tried "
                                             "(SEED..SEED+R-1)",
                           lo=1, metavar="R", group=SEARCH, label="Restarts")
    max_linker: int = option(30, "the walk gives up on a diameter when no length up to N fits",
                             lo=1, hi=LINKER_MAX, unit="", metavar="N", group=SEARCH,
                             label="Longest linker")
    known_fit: int | None = option(None, "a linker length at which a layout is known (e.g. a "
                                         "case's seeds fitted at its real linker): the walk "
                                         "brackets the minimum below L, from the guess in "
                                         "doubling steps, and bisects; the minimum and one "
                                         "residue below are measured as always [default: none; "
                                         "the walk brackets from the guess alone]", kind=int,
                                   lo=1, hi=LINKER_MAX, metavar="L", group=SEARCH)
    all_restarts: bool = option(False, "run all R restarts at the minimal linker too, for P(fit) "
                                       "there from R runs [default: a length's restarts stop at "
                                       "its first fit, which decides that it fits; the row says "
                                       "how many ran]", group=SEARCH)
    interval_width: float | None = option(None, "report: start no more restarts at the linker "
                                                "once P(fit)'s 95 % Wilson interval there is at "
                                                "most W wide (0 < W < 1) [default: all R]",
                                          kind=float, metavar="W", check=_width, group=SEARCH)
    fraction_plot: str = option("", "report: P(fit) also at these fractions of subunits carrying "
                                    "the domain (pattern random), at the report's linker with "
                                    "its seeds and restarts: a plot against the fraction with "
                                    "95 % Wilson intervals (fraction_plot.png) and its table on "
                                    "the page [default: none]", metavar="F1,F2,...",
                                check=_fractions, group=SEARCH, label="Fraction plot")


# The report's search: the same defaults as every search's (DEFAULT_RESTARTS)
REPORT_SEARCH = SearchPlan()
# What each command offers of the search plan
MINIMAL_FIELDS = ("restarts", "max_linker", "known_fit", "all_restarts")
REPORT_FIELDS = ("restarts", "interval_width", "all_restarts", "max_linker", "fraction_plot")
FRACTION_FIELDS = ("restarts", "all_restarts")


@dataclasses.dataclass(frozen=True)
class BatchOutput(Plan):
    """The folder a batch of runs (minimal-linker, report, sweep) writes into, and what it
    prints."""

    out: str = option("out/batch", "every run (results.jsonl) and the command's tables, pictures "
                                   "and pages go here", kind="path", metavar="DIR", group=OUTPUT)
    resume: bool = option(False, "continue in --out: runs already in results.jsonl are reused",
                          group=OUTPUT)
    no_plot: bool = option(False, "draw no plot", group=OUTPUT)
    quiet: bool = option(False, "no progress bar", group=OUTPUT)


MINIMAL_OUTPUT = BatchOutput(out="out/minimal_linker")
REPORT_OUTPUT = BatchOutput(out="out/report")
FRACTION_OUTPUT = BatchOutput(out="out/largest_fraction")


def seed_range(first: int, count: int) -> range:
    """Seeds first .. first + count - 1, refused in one line when the last passes the seed's
    range (the one check of every command that runs restarts)."""
    seeds = range(first, first + count)
    top = P.field_spec("seed")["max"]
    if seeds[-1] > top:
        raise P.ParamError("seed", f"seed + restarts - 1 must be at most {top} "
                                   f"(got {seeds[-1]})")
    return seeds
