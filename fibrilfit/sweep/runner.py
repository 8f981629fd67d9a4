"""Run grid points on an executor: one line per point in results.jsonl, written as it finishes;
a failed or killed run is retried once and then recorded with its error."""
from __future__ import annotations

import json
import pathlib
import sys
from typing import Callable

from .. import files
from ..model.version import MODEL_VERSION
from .grid import Point, point_key

ATTEMPTS = 2  # the first try and one retry


def read_lines(path) -> tuple[list[dict], int]:
    """The records in a results.jsonl, and how many lines could not be read."""
    path = pathlib.Path(path)
    if not path.exists():
        return [], 0
    records, bad = [], 0
    for line in path.read_text(encoding="utf-8").splitlines():
        if not line.strip():
            continue
        try:
            record = json.loads(line)
        except json.JSONDecodeError:
            bad += 1
            continue
        if isinstance(record, dict) and isinstance(record.get("params"), dict):
            records.append(record)
        else:
            bad += 1
    return records, bad


def repair_tail(path) -> bool:
    """Drop a last line cut short by a crash mid-write, so the next record starts on its own line."""
    path = pathlib.Path(path)
    if not path.exists():
        return False
    data = path.read_bytes()
    if not data or data.endswith(b"\n"):
        return False
    files.write_text(path, data[:data.rfind(b"\n") + 1].decode("utf-8", errors="replace"))
    return True


def drop_failed(path) -> int:
    """Remove the records of failed runs (so --retry-failed runs them again, without duplicates)."""
    path = pathlib.Path(path)
    if not path.exists():
        return 0
    kept, dropped = [], 0
    for line in path.read_text(encoding="utf-8").splitlines(keepends=True):
        try:
            failed = json.loads(line).get("status") == "failed"
        except (json.JSONDecodeError, AttributeError):
            failed = False
        dropped += failed
        if not failed:
            kept.append(line)
    if dropped:
        files.write_text(path, "".join(kept))
    return dropped


def done_keys(records: list[dict]) -> set[str]:
    return {point_key(r["params"]) for r in records}


def _record(point: Point, job: dict, reply: dict, errors: list[str], version: str,
            extra: dict | None = None, case: dict | None = None) -> dict:
    if reply["ok"]:
        record = dict(reply["result"])
        record.update(point=point.point, status="ok", attempts=job["attempt"],
                      worker=reply.get("worker"))
    else:
        record = {"fibrilfit_version": version, "model_version": MODEL_VERSION,
                  "params": point.params,
                  "seed": point.params["seed"], "point": point.point, "status": "failed",
                  "error": errors[-1], "attempts": job["attempt"]}
    if errors:
        record["errors"] = errors  # every failed attempt, oldest first
    record.update(extra or {})
    if case is not None:  # the --case, resolved for this point
        record["case"] = {**case, "params": point.params}
    return record


class Counts:
    def __init__(self):
        self.ok = self.failed = self.accommodated = self.retried = self.skipped = 0

    def __str__(self):
        return (f"accommodated {self.accommodated}/{self.ok}"
                + (f", retried {self.retried}" if self.retried else "")
                + (f", {self.skipped} not needed" if self.skipped else "")
                + (f", failed {self.failed}" if self.failed else ""))


def run_points(executor, points: list[Point], results_path, *, force: bool = False,
               progress: bool = True, version: str = "", extra: dict | None = None,
               case: dict | None = None, skip: Callable | None = None,
               window: int = 1) -> Counts:
    """Run every point on `executor` (already entered); append each record as it finishes,
    with `extra` (e.g. the structure block) in every record, and `case` (the --case,
    Case.resolved) with the point's params.

    With `skip(point, records)` (records: this call's, so far), points go out in order with at
    most `window` in flight, and a point for which skip says True when its turn comes is not
    run (counted in Counts.skipped): what a run that cannot change the answer costs is nothing
    (docs/model/search.md#decided). The runs already in flight finish and are recorded."""
    counts = Counts()
    errors: dict[int, list[str]] = {i: [] for i in range(len(points))}
    records: list[dict] = []
    queue = list(range(len(points)))
    bar = None
    if progress:
        from tqdm import tqdm
        bar = tqdm(total=len(points), unit="run", file=sys.stderr, dynamic_ncols=True,
                   smoothing=0.05, desc="sweep")

    def feed():
        while queue and (skip is None or executor.pending() < max(1, window)):
            i = queue.pop(0)
            if skip is not None and skip(points[i], records):
                counts.skipped += 1
                if bar is not None:
                    bar.update(1)
                continue
            executor.submit({"id": i, "attempt": 1, "params": points[i].params, "force": force})

    try:
        feed()
        while executor.pending():
            job, reply = executor.wait()
            i = job["id"]
            if not reply["ok"]:
                errors[i].append(reply["error"])
                if job["attempt"] < ATTEMPTS:
                    counts.retried += 1
                    executor.submit({**job, "attempt": job["attempt"] + 1})
                    if bar is not None:
                        bar.set_postfix_str(str(counts))
                    continue
            record = _record(points[i], job, reply, errors[i], version, extra, case)
            files.append_line(results_path, json.dumps(record))
            records.append(record)
            if reply["ok"]:
                counts.ok += 1
                counts.accommodated += bool(record.get("accommodated"))
            else:
                counts.failed += 1
            if bar is not None:
                bar.set_postfix_str(str(counts), refresh=False)
                bar.update(1)
            feed()
    finally:
        if bar is not None:
            bar.close()
    return counts
