"""R independent seeds of one model, run through the sweep's executors and runner.

A restart is the same model with another seed: another random start layout and gravity. What
comes back is how many were accommodated, P(fit) with its 95 % Wilson interval, and which seed
gave the best layout.
"""
from __future__ import annotations

import pathlib
import statistics

from ..sweep import grid, runner
from ..sweep.grid import Point
from ..sweep.stats import wilson


def points(base: dict, seeds) -> list[Point]:
    """One sweep point per seed of the model `base` (a params dict)."""
    return [Point({**base, "seed": int(s)}, {"seed": int(s)}) for s in seeds]


def run_restarts(executor, base: dict, seeds, results_path, *, stop_on_fit: bool = False,
                 width: float | None = None, window: int = 1, force: bool = False,
                 progress: bool = False, version: str = "") -> list[dict]:
    """Run `base` at each seed; return their records (results.jsonl lines), in seed order.

    Seeds go out in order, `window` in flight. With `stop_on_fit`, no more are started once one
    is accommodated; with `width`, none once P(fit)'s 95 % Wilson interval is at most that wide
    (decided). The runs already started still finish and are recorded, and the tally is taken
    from the runs made.
    """
    todo = points(base, seeds)
    skip = None
    if stop_on_fit or width is not None:
        def skip(point, records):
            return decided(records, stop_on_fit=stop_on_fit, width=width) is not None
    runner.run_points(executor, todo, results_path, force=force, progress=progress,
                      version=version, skip=skip, window=window)
    return read(results_path, base)


def up_to_first_fit(records: list[dict]) -> list[dict]:
    """`records` (in seed order) up to and including the first accommodated one. A length that
    stops at its first fit starts its seeds in order, so every seed before that fit has run; a
    later seed already running when the fit came finishes too, and whether it had started
    depends on which worker was faster. Counted up to the first fit, P(fit) there is the same on
    every machine and under any load (docs/model/search.md#decided)."""
    for i, r in enumerate(records):
        if r.get("accommodated"):
            return records[:i + 1]
    return records


def decided(records: list[dict], *, stop_on_fit: bool = False,
            width: float | None = None) -> str | None:
    """Why the restarts still to run cannot change what is reported, or None (run them).

    'a fit found' (stop_on_fit: the question is whether any restart fits, and a fit is a proof by
    example), or 'interval at most W wide' (the user asked for P(fit) to that width: the 95 %
    Wilson interval of the runs made is that narrow)."""
    ok = [r for r in records if r.get("status") == "ok"]
    fits = sum(bool(r.get("accommodated")) for r in ok)
    if stop_on_fit and fits:
        return "a fit found"
    if width is not None and ok:
        low, high = wilson(fits, len(ok))
        if high - low <= width:
            return f"interval at most {width:g} wide"
    return None


def read(results_path, base: dict) -> list[dict]:
    """The records of `base`'s seeds in `results_path`, in seed order (the last of duplicates)."""
    records, _ = runner.read_lines(pathlib.Path(results_path))
    same = {k: v for k, v in grid.with_defaults(base).items() if k != "seed"}
    found = {}
    for r in records:  # as runner.done_keys sees them: a record predating a parameter has its default
        if {k: v for k, v in grid.with_defaults(r["params"]).items() if k != "seed"} == same:
            found[r["params"]["seed"]] = r
    return [found[s] for s in sorted(found)]


def badness(record: dict) -> tuple:
    """Sort key, best first: accommodated, then fewest clashing pairs, shallowest overlap,
    least stretch; failed runs last."""
    if record.get("status") != "ok":
        return (2, 0, 0.0, 0.0)
    return (0 if record["accommodated"] else 1, len(record["clashing_pairs"]),
            record["max_overlap"], record["max_bond_stretch"])


def tally(records: list[dict]) -> dict:
    """How many restarts were accommodated, P(fit) and its Wilson interval, and the best seed."""
    ok = [r for r in records if r.get("status") == "ok"]
    fits = sum(bool(r["accommodated"]) for r in ok)
    low, high = wilson(fits, len(ok)) if ok else (0.0, 1.0)
    best = min(records, key=badness) if records else None
    outer = [r["envelope"]["outer_diameter"] for r in ok
             if (r.get("envelope") or {}).get("outer_diameter") is not None]
    return {
        "restarts": len(ok),
        "failed": len(records) - len(ok),
        "accommodated": fits,
        "p_fit": round(fits / len(ok), 4) if ok else None,
        "p_fit_interval": [round(low, 4), round(high, 4)],
        "best_seed": None if best is None else best["params"]["seed"],
        "runs": [{"seed": r["params"]["seed"], "status": r.get("status"),
                  **({"accommodated": r["accommodated"], "verdict": r["verdict"],
                      "clashing_pairs": len(r["clashing_pairs"]),
                      "max_bond_stretch": r["max_bond_stretch"],
                      "frames_simulated": r["frames_simulated"],
                      "outer_diameter": (r.get("envelope") or {}).get("outer_diameter")}
                     if r.get("status") == "ok" else {"error": r.get("error")})}
                 for r in records],
        # the envelope's outer diameter over the seeds, Å (docs/model/envelope.md#envelope)
        "outer_diameter": ({"median": statistics.median(outer), "min": min(outer),
                            "max": max(outer)} if outer else None),
    }
