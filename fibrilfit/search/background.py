"""The minimal-linker walk on a thread of its own, for a caller that must stay responsive (the
sidebar's Minimal linker…, ui/operators/minimal.py): the same plan, walk and rows as the
`minimal-linker` command (command.py), on worker processes, with its progress readable and a
stop that kills the workers. Nothing here touches bpy: the runs happen in the workers, and the
thread only waits for them. Its runs go to a temporary folder removed at the end, so a stopped
walk leaves nothing behind."""
from __future__ import annotations

import pathlib
import tempfile
import threading

from ..batch.executors import Stopped
from . import command
from .table import table


class Progress:
    """What the walk has done so far, read by the caller while it runs."""

    def __init__(self):
        self.submitted = self.done = 0
        self.running = None  # (diameter, linker) of the run submitted last
        self.stage = "bound"  # "bound" (each diameter's floor), then "runs"


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


class BackgroundWalk:
    """`command.minimal_plan` and the walk for `values` (as minimal-linker takes them) on a
    daemon thread. `executor`: an unentered executor with stop() (batch/executors.py's
    ProcessExecutor), made by the caller on its own thread. When `finished`, exactly one of
    `result` (the map: rows, table, seeds, protocol, restarts), `error` (an exception) or
    `stopped` is set."""

    def __init__(self, args, values: dict, executor):
        self.args, self.values, self.executor = args, dict(values), executor
        self.progress = Progress()
        self.result = self.error = None
        self.stopped = False
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="fibrilfit-minimal-linker",
                                        daemon=True)

    def start(self) -> "BackgroundWalk":
        self._thread.start()
        return self

    @property
    def finished(self) -> bool:
        return self._thread.ident is not None and not self._thread.is_alive()

    def stop(self) -> None:
        """Stop the walk: no run is started after this, the runs under way are killed; the
        thread ends soon after (at once unless it is computing a bound: seconds)."""
        self._stop.set()
        self.executor.stop()

    def join(self, timeout: float | None = None) -> None:
        self._thread.join(timeout)

    def _run(self) -> None:
        try:
            values, seeds, walks = command.minimal_plan(self.args, self.values)
            self.progress.stage = "runs"
            if self._stop.is_set():
                raise Stopped("stopped")
            with tempfile.TemporaryDirectory(prefix="fibrilfit-minimal-") as out, \
                    self.executor as executor:
                counted = _Counted(executor, self.progress)
                command._walk(self.args, values, seeds, walks, pathlib.Path(out), lambda: counted)
            rows = command.minimal_rows(self.args, values, seeds, walks)
            self.result = {"rows": rows, "protocol": values["protocol"],
                           "restarts": self.args.restarts, "seeds": [seeds[0], seeds[-1]],
                           "max_linker": self.args.max_linker,
                           "table": table(rows, values["protocol"], self.args.restarts, seeds)}
        except Stopped:
            self.stopped = True
        except BaseException as exc:  # the caller reports it, on its own thread
            self.error = exc

