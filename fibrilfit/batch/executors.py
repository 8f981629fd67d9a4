"""Where the runs happen: local worker processes, a Dask cluster, or SLURM jobs (their plan:
plans.py).

Both offer submit(job), pending() and wait() -> (job, reply), where reply is the worker's
{"ok": True, "result": ...} or {"ok": False, "error": ...}. Retrying is the runner's business.
"""
from __future__ import annotations

import collections
import logging
import os
import pathlib
import queue
import sys
import threading
import time
import uuid

from . import pool, slurm

POOL_FILE = str(pathlib.Path(pool.__file__).resolve())  # what Dask workers load (dask_task.py)
START_FAILURES = 3  # workers dying before they are ready, in a row, before the sweep gives up


class SweepError(RuntimeError):
    """The sweep cannot run at all (workers cannot start, scheduler unreachable)."""


class Stopped(Exception):
    """The caller stopped the executor from another thread (ProcessExecutor.stop: the sidebar's
    Esc): raised where the runs are waited for, so leaving the executor kills its workers."""


def cpu_count() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


class ProcessExecutor:
    """`workers` long-lived worker processes on this machine, each running one job at a time.
    A worker that dies (crash, SIGKILL, --timeout) fails its job and is replaced."""

    def __init__(self, workers: int, *, timeout: float | None = None, log_path=None,
                 blender_binary: str = ""):
        self.size, self.timeout, self.log_path = workers, timeout, log_path
        self.worker_argv = pool.worker_command(blender_binary)
        self.events: queue.Queue = queue.Queue()
        self.queue: collections.deque = collections.deque()
        self.workers: list[pool.WorkerProcess] = []
        self.start_failures = 0
        self.log, self.log_lock = None, threading.Lock()
        self.stopped = threading.Event()

    def __enter__(self):
        if self.log_path:
            self.log = open(self.log_path, "a", encoding="utf-8")
        return self

    def __exit__(self, *exc):
        for w in self.workers:
            if exc[0] is not None:
                w.kill()  # interrupted or failing: do not wait for runs in flight
            w.close()
        self.workers.clear()
        if self.log:
            self.log.close()

    def pending(self) -> int:
        return len(self.queue) + sum(w.job is not None for w in self.workers)

    def submit(self, job: dict) -> None:
        if self.stopped.is_set():
            raise Stopped("stopped")
        self.queue.append(job)
        self._fill()

    def stop(self) -> None:
        """From another thread: the next submit() or wait() raises Stopped, and a wait() under
        way wakes up to raise it (leaving the executor then kills the workers)."""
        self.stopped.set()
        self.events.put((None, {"stopped": True}))

    def _dispatch(self, w: pool.WorkerProcess) -> None:
        if w.ready and w.job is None and self.queue:
            w.send(self.queue.popleft())

    def _fill(self) -> None:
        for w in self.workers:
            self._dispatch(w)
        starting = sum(not w.ready for w in self.workers)
        while len(self.workers) < self.size and starting < len(self.queue):
            self.workers.append(pool.WorkerProcess(self.worker_argv, self.events, self.log,
                                                   self.log_lock))
            starting += 1

    def wait(self) -> tuple[dict, dict]:
        while True:
            if self.stopped.is_set():
                raise Stopped("stopped")
            for w in self.workers:  # checked every turn: a busy event queue must not hide a hang
                if w.overdue(self.timeout):
                    w.kill(self.timeout)
            try:
                w, message = self.events.get(timeout=0.5)
            except queue.Empty:
                continue
            if message.get("stopped"):
                continue  # stop()'s wake-up: the loop's top raises Stopped
            if message.get("ready"):
                w.ready, self.start_failures = True, 0
                self._dispatch(w)
            elif "exit" in message:
                self.workers.remove(w)
                if not w.ready:
                    self.start_failures += 1
                    if self.start_failures >= START_FAILURES:
                        raise SweepError(f"sweep workers cannot start: {w.death(message['exit'])}")
                job = w.job
                self._fill()
                if job is not None:
                    return job, {"id": job["id"], "ok": False, "error": w.death(message["exit"])}
            elif "ok" in message and w.job is not None and message.get("id") == w.job["id"]:
                job, w.job = w.job, None
                self._dispatch(w)
                return job, message


class DaskExecutor:
    """Jobs as Dask tasks: on the cluster at `scheduler`, or on a LocalCluster of `workers`
    single-threaded processes. Each Dask worker process hands its jobs, one at a time, to a bpy
    subprocess of its own (pool.run_here), so bpy never runs in Dask's threads."""

    KEEP_EVERY = 10.0  # seconds a result is waited for between keep() calls

    def __init__(self, workers: int, *, scheduler: str | None = None,
                 timeout: float | None = None):
        self.size, self.scheduler, self.timeout = workers, scheduler, timeout
        self.client = self.cluster = None
        self.futures: dict = {}

    def __enter__(self):
        import distributed
        from .dask_task import make_task
        self._task = make_task()
        try:
            self._connect(distributed)
        except (OSError, TimeoutError, ValueError) as exc:
            self.__exit__(None, None, None)
            raise SweepError(f"cannot reach the Dask scheduler {self.scheduler or '(local)'}: "
                             f"{exc}") from None
        self.done = distributed.as_completed()
        return self

    def _connect(self, distributed) -> None:
        if self.scheduler:
            self.client = distributed.Client(self.scheduler, timeout="30s")
        else:
            self.cluster = distributed.LocalCluster(
                n_workers=self.size, threads_per_worker=1, processes=True,
                dashboard_address=None, silence_logs=logging.ERROR)
            self.client = distributed.Client(self.cluster)

    def __exit__(self, *exc):
        for thing in (self.client, self.cluster):
            if thing is not None:
                thing.close()

    def pending(self) -> int:
        return len(self.futures)

    def submit(self, job: dict) -> None:
        key = f"fibrilfit-{job['id']}-{job['attempt']}-{uuid.uuid4().hex[:8]}"
        future = self.client.submit(self._task, POOL_FILE, job, self.timeout, key=key,
                                    pure=False)
        self.futures[future.key] = job
        self.done.add(future)

    def keep(self) -> None:
        """Called while a result is awaited: nothing to look after here (SlurmExecutor replaces
        lost jobs)."""

    def next_done(self):
        return next(self.done)

    def wait(self) -> tuple[dict, dict]:
        future = self.next_done()
        job = self.futures.pop(future.key)
        reply = self.reply(future, job)
        future.release()
        return job, reply

    def reply(self, future, job: dict) -> dict:
        """The future's reply, waited for KEEP_EVERY seconds at a time with keep() between.
        A finished future is lost again when the worker holding its result goes before the
        result is fetched (a cancelled SLURM job), and Dask computes it again on the workers
        left; a wait that blocked in result() could not replace the jobs that rerun needs, and
        the sweep waited forever with none (measured in CI, 2026-11-25:
        docs/guide/cluster.md#lost-results)."""
        while True:
            try:
                return future.result(timeout=self.KEEP_EVERY)
            except TimeoutError as exc:
                if future.status == "error":  # the task itself raised it
                    return {"id": job["id"], "ok": False, "error": f"TimeoutError: {exc}"}
                self.keep()
            except Exception as exc:  # KilledWorker, a lost connection, ...: the runner retries
                return {"id": job["id"], "ok": False, "error": f"{type(exc).__name__}: {exc}"}


class SlurmExecutor(DaskExecutor):
    """The DaskExecutor on a dask-jobqueue SLURMCluster: `workers` SLURM jobs, one single-threaded
    Dask worker each (options: batch/slurm.py). A job that ends early (scancel, walltime, a failed
    node) loses its run in flight, which Dask runs again elsewhere.

    Replacing lost jobs is this class's own watchdog, not Dask's: every KEEP_EVERY seconds it asks
    squeue which of the sweep's jobs are still queued or running, and submits a new job (under a
    new worker name) for each one that is not. dask-jobqueue alone replaces a job only after the
    scheduler has seen its worker leave and lost-worker-timeout has passed, so a job cancelled
    before its worker connected, or one whose worker's leaving went unnoticed on a loaded machine,
    was never replaced and the sweep waited forever (issue #25). If sbatch refuses the
    replacements, the sweep stops with SweepError (one line, exit 2); the finished runs are in
    results.jsonl already, so --resume loses nothing.
    """

    KEEP_EVERY = 10.0  # seconds between squeue polls (a poll is one squeue call of the user's jobs)
    ALIVE = {"PENDING", "CONFIGURING", "RUNNING", "SUSPENDED", "REQUEUED", "REQUEUE_HOLD",
             "REQUEUE_FED", "RESIZING", "SIGNALING", "STAGE_OUT", "RESV_DEL_HOLD", "SPECIAL_EXIT"}

    def __init__(self, workers: int, cluster_options: dict, *, timeout: float | None = None):
        super().__init__(workers, timeout=timeout)
        self.cluster_options = cluster_options
        self.kept = 0.0
        self.replaced = 0  # jobs submitted in place of lost ones
        self.unstarted = 0  # lost jobs in a row whose worker never connected
        self.connected: set = set()  # worker names that have reached the scheduler

    def _connect(self, distributed) -> None:
        import shutil
        with slurm.ctrl_c_kept():  # its import sets SIGINT to sys.exit (slurm.ctrl_c_kept)
            from dask_jobqueue import SLURMCluster
        if shutil.which("sbatch") is None:
            raise SweepError("--executor slurm: sbatch is not on the PATH (run the sweep on a "
                             "SLURM login node)")
        self.cluster = SLURMCluster(**self.cluster_options)
        self.client = distributed.Client(self.cluster)
        # SpecCluster.scale(), but waited for: sbatch's refusal (a wrong partition or account)
        # must stop the sweep, where scale() would only log it and leave the sweep waiting
        while len(self.cluster.worker_spec) < self.size:
            self.cluster.worker_spec.update(self.cluster.new_worker_spec())
        self._submit("SLURM refused the worker jobs", close=True)
        self.kept = time.monotonic()

    def _submit(self, what: str, *, close: bool = False) -> None:
        """Submit a job for every worker spec without one, waiting for sbatch's answer; its
        refusal is a SweepError (after closing the cluster if `close`: not entered yet)."""
        try:
            self.cluster.sync(self.cluster._correct_state)
        except Exception as exc:
            from distributed.core import Status
            for job in self.cluster.workers.values():
                if job.job_id is None:  # never submitted; close() insists on a final state
                    job.status = Status.failed
            if close:
                self.__exit__(None, None, None)
            raise SweepError(f"{what}: {slurm.submit_error(exc)}") from None

    def job_ids(self) -> dict:
        """Worker name -> SLURM job id, for the jobs submitted and not yet given up."""
        return {name: job.job_id for name, job in self.cluster.workers.items() if job.job_id}

    def lost(self) -> list:
        """Names of the workers whose job is no longer queued or running (squeue), [] when
        squeue does not answer (a busy controller is not a lost job)."""
        ids = self.job_ids()
        if not ids:
            return []
        alive = slurm.alive_jobs(self.ALIVE)
        if alive is None:
            return []
        return [name for name, job_id in ids.items() if job_id not in alive]

    def watch(self) -> int:
        """One round of the watchdog: replace every lost job; how many were replaced."""
        self.connected |= {w.get("name") for w in self.cluster.scheduler_info.get(
            "workers", {}).values()}
        if self.connected & set(self.cluster.workers):
            self.unstarted = 0
        lost = self.lost()
        if not lost:
            return 0
        from distributed.core import Status
        for name in lost:
            job = self.cluster.workers.pop(name)
            self.cluster.worker_spec.pop(name, None)
            if name not in self.connected:
                self.unstarted += 1
            self.cluster.sync(job.close)  # scancel; a job already gone is no error
            job.status = Status.closed  # jobqueue's close() leaves it running: close() asserts
        if self.unstarted > START_FAILURES * self.size:
            raise SweepError(f"SLURM jobs keep ending before their Dask worker starts "
                             f"({self.unstarted} in a row); see the job logs in "
                             f"{self.cluster_options.get('log_directory')}")
        while len(self.cluster.worker_spec) < self.size:
            self.cluster.worker_spec.update(self.cluster.new_worker_spec())  # a new name
        self._submit("SLURM refused the replacement jobs")
        self.replaced += len(lost)
        print(f"fibrilfit: {len(lost)} SLURM job{'s' * (len(lost) > 1)} ended early; "
              f"submitted {len(lost)} replacement{'s' * (len(lost) > 1)}", file=sys.stderr)
        return len(lost)

    def keep(self) -> None:
        """The watchdog, at most every KEEP_EVERY seconds."""
        if time.monotonic() - self.kept > self.KEEP_EVERY:
            self.watch()
            self.kept = time.monotonic()

    def next_done(self):
        while not self.done.has_ready():
            self.keep()
            time.sleep(0.1)
        return next(self.done)


def executor_spec(plan, *, out=None, runs: int = 0) -> dict:
    """What an executor plan (batch/plans.py) asks for, as plain values (make_executor builds
    it): the kind, the workers (SLURM: jobs sized for `runs`), the timeout, and the Dask scheduler or the
    SLURMCluster's options (their job logs under `out`). The same plan gives the same spec
    whichever command made it."""
    spec = {"executor": plan.executor, "timeout": plan.timeout}
    if plan.executor == "slurm":
        import pathlib
        return {**spec, "workers": slurm.jobs(plan, runs),
                "cluster_options": slurm.cluster_options(plan, pathlib.Path(out).resolve())}
    spec["workers"] = plan.workers or cpu_count()
    if plan.executor == "dask":
        spec["scheduler"] = plan.scheduler
    return spec


def make_executor(plan, *, out=None, runs: int = 0, log_path=None):
    """The executor an executor plan asks for: --executor slurm (jobs sized for `runs`,
    their files under `out`), dask (--scheduler, or a local cluster), or worker processes on
    this machine (their stderr in `log_path`)."""
    spec = executor_spec(plan, out=out, runs=runs)
    if spec["executor"] == "slurm":
        return SlurmExecutor(spec["workers"], spec["cluster_options"], timeout=spec["timeout"])
    if spec["executor"] == "dask":
        return DaskExecutor(spec["workers"], scheduler=spec["scheduler"],
                            timeout=spec["timeout"])
    import bpy  # inside Blender's own executable, workers are that executable in background mode
    return ProcessExecutor(spec["workers"], timeout=spec["timeout"], log_path=log_path,
                           blender_binary=bpy.app.binary_path)
