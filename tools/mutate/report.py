"""One module's mutation result from a cosmic-ray session (`make mutate`, docs/contributing/
mutation.md): mutants run, killed, surviving, the kill rate, and every survivor as its line of
the diff. Run with the cosmic-ray venv's python: `python tools/mutate/report.py SESSION`."""
from __future__ import annotations

import sys

from cosmic_ray.work_db import WorkDB, use_db
from cosmic_ray.work_item import TestOutcome, WorkerOutcome


def survivors_and_counts(session: str) -> tuple[dict, list[str]]:
    counts = {"mutants": 0, "skipped": 0, "pending": 0, "killed": 0, "incompetent": 0,
              "survived": 0}
    lines = []
    with use_db(session, WorkDB.Mode.open) as db:
        items = {item.job_id: item for item in db.work_items}
        results = dict(db.results)
    counts["mutants"] = len(items)
    for job, item in sorted(items.items(), key=lambda kv: (kv[1].mutations[0].start_pos,
                                                            kv[1].mutations[0].operator_name)):
        r = results.get(job)
        if r is None:
            counts["pending"] += 1
        elif r.worker_outcome == WorkerOutcome.SKIPPED:
            counts["skipped"] += 1
        elif r.test_outcome == TestOutcome.SURVIVED:
            counts["survived"] += 1
            m = item.mutations[0]
            changed = [ln[1:].strip() for ln in (r.diff or "").splitlines()
                       if ln.startswith("+") and not ln.startswith("+++")]
            lines.append(f"{m.module_path}:{m.start_pos[0]} {m.operator_name} "
                         f"({m.definition_name}): {' | '.join(changed)}")
        elif r.test_outcome == TestOutcome.INCOMPETENT:
            counts["incompetent"] += 1  # the mutant does not run (a timeout, an import error)
        else:
            counts["killed"] += 1
    return counts, lines


def main(argv: list[str]) -> int:
    counts, lines = survivors_and_counts(argv[0])
    run = counts["killed"] + counts["incompetent"] + counts["survived"]
    rate = (counts["killed"] + counts["incompetent"]) / run if run else float("nan")
    print(f"{argv[0]}: {counts['mutants']} mutants, {run} run ({counts['skipped']} left out of "
          f"the sample, {counts['pending']} pending): {counts['killed']} killed, "
          f"{counts['incompetent']} incompetent, {counts['survived']} survived; "
          f"kill rate {rate:.1%}")
    for line in lines:
        print("  survived:", line)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
