"""Keep a seeded random sample of a cosmic-ray session's pending mutants, mark the rest skipped
(`make mutate SAMPLE=N`): a module of thousands of mutants is measured on a sample whose size the
docs state (docs/contributing/mutation.md). Run with the cosmic-ray venv's python:
`python tools/mutate/sample.py SESSION N [SEED]`."""
from __future__ import annotations

import random
import sys

from cosmic_ray.work_db import WorkDB, use_db
from cosmic_ray.work_item import WorkerOutcome, WorkResult


def main(argv: list[str]) -> int:
    session, n = argv[0], int(argv[1])
    seed = int(argv[2]) if len(argv) > 2 else 0
    with use_db(session, WorkDB.Mode.open) as db:
        pending = sorted(item.job_id for item in db.pending_work_items)
        keep = set(random.Random(seed).sample(pending, min(n, len(pending))))
        for job in pending:
            if job not in keep:
                db.set_result(job, WorkResult(worker_outcome=WorkerOutcome.SKIPPED))
    print(f"{session}: {len(keep)} of {len(pending)} mutants kept (seed {seed})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
