"""Batch work on a thread of its own, for a caller that must stay responsive (the sidebar's
Minimal linker…, Largest fraction… and Report…, ui/operators/minimal.py and report.py): the same
plan, runs and rows as the `minimal-linker` command (linker_map.py) or the `largest-fraction`
command (fraction_map.py), or the first stages of `report` (report.py's search), on worker
processes, with their progress readable and a stop that kills the workers.
Nothing here touches bpy: the runs happen in the workers, and the thread only waits for them.
The walk's runs go to a temporary folder removed at the end, and the report's to a folder beside
its own, moved into place only when the report is whole, so a stopped job leaves nothing
behind."""
from __future__ import annotations

import os
import pathlib
import shutil
import tempfile
import threading

from ..batch import outdir
from ..batch.executors import Stopped
from . import fraction_map, linker_map, report
from .table import table


class Progress:
    """What the job has done so far, read by the caller while it runs."""

    def __init__(self, stage: str):
        self.submitted = self.done = 0
        self.running = None  # (diameter, linker) of the run submitted last
        self.stage = stage  # the walk: "bound" (each diameter's floor), then "runs";
        # the report: its STAGES


class _Counted:
    """An executor that counts what goes through it into a Progress."""

    def __init__(self, executor, progress: Progress):
        self.executor, self.progress = executor, progress

    def submit(self, job: dict) -> None:
        self.executor.submit(job)
        self.progress.submitted += 1
        self.progress.running = (job["params"]["globule_diameter"], job["params"]["linker"])

    def pending(self) -> int:
        return self.executor.pending()

    def wait(self):
        job, reply = self.executor.wait()
        self.progress.done += 1
        return job, reply


class Background:
    """`_work()` on a daemon thread, its runs on `executor`: an unentered executor with stop()
    (batch/executors.py's ProcessExecutor), made by the caller on its own thread. When
    `finished`, exactly one of `result` (what _work returned), `error` (an exception) or
    `stopped` is set."""

    name = "fibrilfit-background"
    first_stage = ""

    def __init__(self, executor):
        self.executor = executor
        self.progress = Progress(self.first_stage)
        self.result = self.error = None
        self.stopped = False
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name=self.name, daemon=True)

    def start(self) -> "Background":
        self._thread.start()
        return self

    @property
    def finished(self) -> bool:
        return self._thread.ident is not None and not self._thread.is_alive()

    def stop(self) -> None:
        """Stop the job: no run is started after this, the runs under way are killed; the
        thread ends soon after (at once unless it is computing a bound: seconds)."""
        self._stop.set()
        self.executor.stop()

    def join(self, timeout: float | None = None) -> None:
        self._thread.join(timeout)

    def stage(self, name: str) -> None:
        """The job has reached stage `name`; a stop asked for before it is honoured here."""
        self.progress.stage = name
        if self._stop.is_set():
            raise Stopped("stopped")

    def counted(self, executor) -> _Counted:
        return _Counted(executor, self.progress)

    def _run(self) -> None:
        try:
            self.result = self._work()
        except Stopped:
            self.stopped = True
        except BaseException as exc:  # the caller reports it, on its own thread
            self.error = exc

    def _work(self):
        raise NotImplementedError


class BackgroundWalk(Background):
    """`linker_map.walks_for` and the walk for `values` (as minimal-linker takes them) under
    `plan` (api/plans.py's MinimalLinkerPlan); its result is the map: rows, table, seeds,
    protocol, restarts. A subclass walks another map (BackgroundFraction) by its three
    hooks: walks_for, rows and table, as its command makes them."""

    name, first_stage = "fibrilfit-minimal-linker", "bound"

    def __init__(self, plan, values: dict, executor):
        super().__init__(executor)
        self.plan, self.values = plan, dict(values)

    def walks_for(self, values: dict) -> tuple:
        return linker_map.walks_for(values, self.plan)

    def rows(self, values: dict, seeds: range, walks: list) -> list:
        return linker_map.minimal_rows(values, seeds, walks, force=self.plan.force)

    def table(self, rows: list, values: dict, seeds: range) -> str:
        return table(rows, values["protocol"], self.plan.search.restarts, seeds)

    def _work(self) -> dict:
        values, seeds, walks = self.walks_for(self.values)
        self.stage("runs")
        with tempfile.TemporaryDirectory(prefix=f"{self.name}-") as out, \
                self.executor as executor:
            counted = self.counted(executor)
            linker_map.step_walks(values, seeds, walks, pathlib.Path(out), self.plan,
                                  lambda: counted)
        rows = self.rows(values, seeds, walks)
        search = self.plan.search
        return {"rows": rows, "protocol": values["protocol"], "restarts": search.restarts,
                "seeds": [seeds[0], seeds[-1]], "max_linker": search.max_linker,
                "table": self.table(rows, values, seeds)}


class BackgroundFraction(BackgroundWalk):
    """The `largest-fraction` walks (fraction_map.walks_for: one per diameter and linker, over
    the decorated count) for `values` under `plan` (api/plans.py's LargestFractionPlan); its
    result is the map as BackgroundWalk's, each row largest_fraction.json's (the largest
    count with a fit, P(fit) there and at one more, the bound and the bracket)."""

    name = "fibrilfit-largest-fraction"

    def walks_for(self, values: dict) -> tuple:
        return fraction_map.walks_for(values, self.plan)

    def rows(self, values: dict, seeds: range, walks: list) -> list:
        return fraction_map.fraction_rows(values, walks)

    def table(self, rows: list, values: dict, seeds: range) -> str:
        return fraction_map.table(rows, values["protocol"], self.plan.search.restarts, seeds)


class BackgroundReport(Background):
    """The report's restarts and minimal-linker walk (report.search) for the model `p` and
    `values` under `plan` (api/plans.py's ReportPlan), into `work`: a new folder beside
    plan.output.out (the report's folder, which may hold
    an earlier report: its runs are reused, as --resume does). The caller then writes the rest
    on its own thread (report.write into `work`) and calls keep(), which moves it all into
    the report's folder; or discard(), which removes `work`. Its result is report.search's."""

    name, first_stage = "fibrilfit-report", report.STAGES[0]

    def __init__(self, plan, p, values: dict, executor, work: pathlib.Path):
        super().__init__(executor)
        self.plan, self.p, self.values, self.work = plan, p, dict(values), pathlib.Path(work)

    @staticmethod
    def folder_beside(final: pathlib.Path) -> pathlib.Path:
        """A new empty folder beside `final` (on its file system, so keep() only renames),
        holding a copy of `final`'s runs when it has any (reused as --resume reuses them)."""
        final.parent.mkdir(parents=True, exist_ok=True)
        work = pathlib.Path(tempfile.mkdtemp(prefix=f".{final.name}.fibrilfit-",
                                             dir=final.parent))
        if (final / outdir.RESULTS).is_file():
            shutil.copy2(final / outdir.RESULTS, work / outdir.RESULTS)
        return work

    def _work(self) -> dict:
        return report.search(self.plan, self.p, self.values, self.work, self.stage,
                             executor=self.executor, counted=self.counted)

    def keep(self, final: pathlib.Path) -> None:
        """Every file of `work` moved into `final` (replacing those of an earlier report), then
        `work` removed."""
        final.mkdir(parents=True, exist_ok=True)
        for f in self.work.iterdir():
            if f.name != ".lock":
                os.replace(f, final / f.name)
        shutil.rmtree(self.work, ignore_errors=True)

    def discard(self) -> None:
        shutil.rmtree(self.work, ignore_errors=True)
