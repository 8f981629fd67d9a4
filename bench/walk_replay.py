"""This checkout's minimal-linker walk replayed on the runs of an earlier report or map (its
results.jsonl): runs are deterministic for a seed, so the walk here asks for a subset of them,
answered from the file without simulating anything. Prints the answer and the runs made, with
their run time (build + bake + check, from the file) against all the file's runs.

    .venv/bin/python bench/walk_replay.py RESULTS.jsonl [--restarts 8] [--all-restarts]
                                          [--diameter D] [--floor N] [--workers 2]

A run the walk asks for that is not in the file stops the replay with its name (the earlier
walk did not need it).
"""
import argparse
import json
import pathlib
import tempfile

from fibrilfit.api.plans import MinimalLinkerPlan
from fibrilfit.batch.plans import ExecutorPlan
from fibrilfit.model import params as P
from fibrilfit.search import linker_map, minimal
from fibrilfit.search.plans import BatchOutput, SearchPlan


class Answering:
    """The executor interface (submit, pending, wait) without Blender: each job, in the order
    submitted, is answered by `answer(params)` -> the run's record (its params become the
    job's), and `ran` lists `noted(params, record)` for each (default: the record). Here it
    replays a file's runs (replay); the unit tests answer from a table
    (tests/unit/test_search_walk.py, tests/unit/test_fraction_search.py)."""

    def __init__(self, answer, noted=lambda params, record: record):
        self.answer, self.noted, self.queue, self.ran = answer, noted, [], []

    def submit(self, job):
        self.queue.append(job)

    def pending(self):
        return len(self.queue)

    def wait(self):
        job = self.queue.pop(0)
        p = job["params"]
        r = self.answer(p)
        self.ran.append(self.noted(p, r))
        return job, {"id": job["id"], "ok": True, "result": {**r, "params": p}}


def replay(records: dict) -> Answering:
    """An executor answering from the file's records by (linker, seed); `ran`: the records."""
    def answer(p):
        key = (int(p["linker"]), int(p["seed"]))
        if key not in records:
            raise SystemExit(f"the walk asks for linker {key[0]}, seed {key[1]}: not in the file")
        return records[key]
    return Answering(answer)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("results", type=pathlib.Path)
    ap.add_argument("--restarts", type=int, default=8)
    ap.add_argument("--all-restarts", action="store_true")
    ap.add_argument("--floor", type=int, default=None, help="the bound (default: the model's)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--max-linker", type=int, default=30)
    args = ap.parse_args()
    lines = [json.loads(x) for x in args.results.read_text().splitlines() if x.strip()]
    ok = [r for r in lines if r.get("status") == "ok"]
    params = dict(ok[0]["params"])
    records = {(int(r["params"]["linker"]), int(r["params"]["seed"])): r for r in ok}
    seeds = range(min(s for _, s in records), min(s for _, s in records) + args.restarts)
    plan = MinimalLinkerPlan(
        search=SearchPlan(restarts=args.restarts, max_linker=args.max_linker,
                          all_restarts=args.all_restarts),
        output=BatchOutput(quiet=True),
        executor=ExecutorPlan(executor="processes", workers=args.workers), force=True)
    values = {k: v for k, v in params.items() if k not in ("linker", "seed", "globule_diameter")}
    base = P.make_params(force=True, **{**params, "linker": 1})
    walk = linker_map.new_walk(plan.search, base, len(seeds))
    if args.floor is not None:
        walk = minimal.Walk(walk.diameter, walk.start, walk.max_linker, restarts=walk.restarts,
                            stop_at_fit=walk.stop_at_fit, floor=args.floor)
    replayed = replay(records)
    with tempfile.TemporaryDirectory() as tmp:
        linker_map.step_walks(values, seeds, [walk], pathlib.Path(tmp), plan, lambda: replayed)
    row = walk.row()

    def cost(rs):
        return sum(sum(r["timings_s"].get(k, 0.0) for k in ("build", "bake", "check")) for r in rs)

    walk_lengths = {int(L) for L in row["tried"]}
    before = [r for r in ok if int(r["params"]["linker"]) in walk_lengths]
    print(f"answer: minimal linker {row['minimal_linker']} (P(fit) {row['fits']}/"
          f"{row['restarts']}{', stopped at the first fit' if row['stopped_at_fit'] else ''}), "
          f"one below {row['linker_below']}: "
          + ("0, proven by the bound" if row["below_settled_by_bound"] else
             f"0/{row['restarts_below']}") + f"; tried {row['tried']}")
    print(f"runs: {len(replayed.ran)} of the file's {len(before)} at those lengths; run time "
          f"{cost(replayed.ran):.0f} s of {cost(before):.0f} s (summed over workers, as recorded)")


if __name__ == "__main__":
    main()
