"""Worker processes that import bpy once and run one model at a time (see worker.py).

Standard library only and no package imports: Dask workers load this file by path (dask_task.py),
without importing FibrilFit or bpy themselves. Each worker is a subprocess talking JSON lines:
a killed or crashed worker is just a process that exited, so the caller records the error and
carries on, and bpy's global state never meets a thread pool.
"""
from __future__ import annotations

import atexit
import collections
import json
import os
import queue
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

WORKER = "worker.py"  # beside this file; it finds the package from its own __file__


def worker_command(blender_binary: str = "") -> list[str]:
    """How to start a worker: under the bpy module, this Python; inside Blender's own executable
    (whose Python cannot import bpy as a module), that executable in background mode."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), WORKER)
    if blender_binary:
        return [blender_binary, "-b", "--factory-startup", "--python-exit-code", "1", "-P", script]
    return [sys.executable, script]


_EXTENSIONS = {"dir": None}


def worker_env() -> dict:
    """The environment of a worker: this one, with Blender's user extensions in a folder of the
    workers' own (BLENDER_USER_EXTENSIONS, empty, removed at exit). A worker resets to factory
    settings before each run (worker.py), and Blender then uninstalls the wheels of every
    extension not enabled from the shared extensions/.local site-packages: the installed
    FibrilFit's own matplotlib and gemmi, under the Blender that started the workers (measured on
    Blender 4.3.2: the report lost its legend and envelope plot, issue #33)."""
    if _EXTENSIONS["dir"] is None:
        _EXTENSIONS["dir"] = tempfile.mkdtemp(prefix="fibrilfit-worker-extensions-")
        atexit.register(shutil.rmtree, _EXTENSIONS["dir"], True)
    return {**os.environ, "BLENDER_USER_EXTENSIONS": _EXTENSIONS["dir"]}


# Blender 5.2 logs informational lines on stderr as it starts, e.g.
# "00:00.085  color_management | Using OCIO=.../config.ocio": they never say why a worker died.
_BLENDER_INFO = re.compile(r"^\d+:\d\d\.\d+\s+[\w.]+\s+\|\s(?!.*\b(?:ERROR|FATAL|WARNING)\b)")


def last_words(lines) -> str:
    """The last line of a worker's stderr worth quoting: not blank, not Blender's info log."""
    return next((t for t in reversed(lines) if t.strip() and not _BLENDER_INFO.match(t)), "")


def exit_reason(returncode: int) -> str:
    if returncode < 0:
        try:
            return f"killed by {signal.Signals(-returncode).name}"
        except ValueError:
            return f"killed by signal {-returncode}"
    return f"exited with code {returncode}"


class WorkerProcess:
    """One worker subprocess. Its messages, and finally {"exit": returncode}, go to `events` as
    (worker, message) pairs; its stderr is kept (last lines) and copied to `log`."""

    def __init__(self, command: list[str], events: queue.Queue, log=None, log_lock=None):
        self.events, self.log, self.log_lock = events, log, log_lock or threading.Lock()
        self.tail = collections.deque(maxlen=20)
        self.job = None
        self.ready = False
        self.timed_out = None  # the timeout in seconds, once it has been hit
        self.started = 0.0
        self.proc = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True, encoding="utf-8",
                                     errors="replace", bufsize=1, env=worker_env())
        self.pid = self.proc.pid
        self._stderr = threading.Thread(target=self._read_stderr, daemon=True)
        self._stderr.start()
        threading.Thread(target=self._read_stdout, daemon=True).start()

    def _read_stderr(self):
        for line in self.proc.stderr:
            self.tail.append(line.rstrip("\n"))
            if self.log is not None:
                with self.log_lock:
                    self.log.write(f"[worker {self.pid}] {line}")
                    self.log.flush()

    def _read_stdout(self):
        for line in self.proc.stdout:
            try:
                message = json.loads(line)
            except json.JSONDecodeError:
                self.tail.append(f"(unreadable reply) {line.strip()[:200]}")
                continue
            self.events.put((self, message))
        returncode = self.proc.wait()
        self._stderr.join(timeout=5)  # so the exit message can quote the last error line
        self.events.put((self, {"exit": returncode}))

    def send(self, job: dict) -> None:
        self.job, self.started = job, time.monotonic()
        try:
            self.proc.stdin.write(json.dumps(job) + "\n")
            self.proc.stdin.flush()
        except (BrokenPipeError, OSError):
            pass  # it died; its exit event follows

    def overdue(self, timeout: float | None) -> bool:
        return bool(timeout and self.job is not None and not self.timed_out
                    and time.monotonic() - self.started > timeout)

    def kill(self, timeout: float | None = None) -> None:
        if timeout is not None:
            self.timed_out = timeout
        try:
            self.proc.kill()
        except ProcessLookupError:
            pass

    def death(self, returncode: int) -> str:
        """The error recorded for the job this worker was running when it exited."""
        if self.timed_out is not None:
            return f"timed out after {self.timed_out:g} s (worker pid {self.pid} stopped)"
        last = last_words(self.tail)
        return f"worker pid {self.pid} {exit_reason(returncode)}" + (f": {last}" if last else "")

    def close(self, grace: float = 5.0) -> None:
        """Ask it to finish (end of input), then make sure it has gone."""
        try:
            self.proc.stdin.close()
        except OSError:
            pass
        try:
            self.proc.wait(timeout=grace)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()


# ---- one worker per calling process (the Dask path) ------------------------------------------
_HERE = {"worker": None, "events": None}
_LOCK = threading.Lock()  # one job at a time per process, whatever the Dask worker's threads


def run_here(job: dict, timeout: float | None = None) -> dict:
    """Run `job` on this process's own worker subprocess, starting it if needed; return the reply.
    A dead or timed-out worker gives {"ok": False, "error": ...} and is replaced next time."""
    with _LOCK:
        worker = _HERE["worker"]
        if worker is None:
            _HERE["events"] = queue.Queue()
            worker = _HERE["worker"] = WorkerProcess(worker_command(), _HERE["events"])
        events = _HERE["events"]
        sent = False
        while True:
            if worker.ready and not sent:
                worker.send(job)
                sent = True
            try:
                _, message = events.get(timeout=1.0)
            except queue.Empty:
                if sent and worker.overdue(timeout):
                    worker.kill(timeout)
                continue
            if "exit" in message:
                _HERE["worker"] = None
                error = worker.death(message["exit"])
                if not worker.ready:
                    error = f"worker could not start: {error}"
                return {"id": job["id"], "ok": False, "error": error}
            if message.get("ready"):
                worker.ready = True
            elif "ok" in message and message.get("id") == job["id"]:
                worker.job = None
                return message
