"""The SLURM executor's watchdog (issue #25) against a stand-in for dask-jobqueue's cluster and for
squeue, so `make test` covers its logic; tests/blender/test_cluster.py runs it on a real SLURM."""
import asyncio
import os
import stat

import pytest

from fibrilfit.batch import executors, slurm


class Job:
    def __init__(self, job_id):
        self.job_id, self.status, self.cancelled = job_id, "running", False

    async def close(self):
        self.cancelled = True


class Cluster:
    """What SlurmExecutor uses of a SLURMCluster: workers, worker_spec, scheduler_info, sync,
    new_worker_spec and _correct_state (sbatch for every spec without a job)."""

    def __init__(self, size):
        self.workers, self.worker_spec, self.i, self.next_id = {}, {}, 0, 100
        self.scheduler_info = {"workers": {}}
        self.refuse = None
        for _ in range(size):
            self.worker_spec.update(self.new_worker_spec())
        self.sync(self._correct_state)

    def new_worker_spec(self):
        self.i += 1
        return {f"w{self.i}": {}}

    def _correct_state(self):
        for name in set(self.worker_spec) - set(self.workers):
            if self.refuse:
                self.workers[name] = Job(None)
                raise RuntimeError(f"Command exited with non-zero exit code.\n{self.refuse}\n")
            self.next_id += 1
            self.workers[name] = Job(str(self.next_id))

    def sync(self, fn):
        out = fn()
        return asyncio.run(out) if asyncio.iscoroutine(out) else out

    def connect(self, *names):
        self.scheduler_info["workers"] = {f"tcp://{n}": {"name": n} for n in names}


@pytest.fixture
def executor(monkeypatch):
    ex = executors.SlurmExecutor(2, {"log_directory": "/out/slurm"})
    ex.cluster = Cluster(2)
    alive = {"ids": set(ex.job_ids().values())}
    monkeypatch.setattr(slurm, "alive_jobs", lambda states: alive["ids"])
    return ex, alive


def test_every_job_lost_is_replaced_under_a_new_name(executor, capsys):
    ex, alive = executor
    ex.cluster.connect("w1", "w2")
    assert ex.watch() == 0  # both alive: nothing to do
    old = dict(ex.cluster.workers)
    alive["ids"] = set()  # scancel of every job
    assert ex.watch() == 2
    assert all(job.cancelled and job.status != "running" for job in old.values())
    assert set(ex.cluster.workers) == set(ex.cluster.worker_spec) == {"w3", "w4"}
    assert {j.job_id for j in ex.cluster.workers.values()} == {"103", "104"}
    assert "2 SLURM jobs ended early; submitted 2 replacements" in capsys.readouterr().err
    alive["ids"] = {"103", "104"}
    assert ex.watch() == 0 and ex.replaced == 2


def test_a_job_lost_before_its_worker_connected_is_replaced_too(executor):
    """Dask never saw its worker, so only squeue can tell it is gone."""
    ex, alive = executor
    ex.cluster.connect("w1")  # w2 still queued
    alive["ids"] = {ex.cluster.workers["w1"].job_id}
    assert ex.watch() == 1 and "w1" in ex.cluster.workers and "w2" not in ex.cluster.workers


def test_no_answer_from_squeue_replaces_nothing(executor, monkeypatch):
    ex, _ = executor
    monkeypatch.setattr(slurm, "alive_jobs", lambda states: None)
    before = dict(ex.cluster.workers)
    assert ex.watch() == 0 and ex.cluster.workers == before


def test_sbatch_refusing_the_replacements_is_one_line(executor):
    ex, alive = executor
    alive["ids"] = set()
    ex.cluster.refuse = ("sbatch: error: Batch job submission failed: Required partition not "
                         "available (inactive or drain)")
    with pytest.raises(executors.SweepError) as err:
        ex.watch()
    assert str(err.value) == ("SLURM refused the replacement jobs: sbatch: error: Batch job "
                              "submission failed: Required partition not available (inactive "
                              "or drain)")
    assert all(job.status != "running" for job in ex.cluster.workers.values()
               if job.job_id is None)  # close() would assert otherwise


def test_jobs_that_never_start_a_worker_stop_the_sweep(executor):
    ex, alive = executor
    for _ in range(executors.START_FAILURES):
        alive["ids"] = set()  # every job ends before its worker connects
        ex.watch()
    alive["ids"] = set()
    with pytest.raises(executors.SweepError, match="keep ending before their Dask worker starts"):
        ex.watch()


class LostFuture:
    """A future that as_completed gave out as finished, then lost with its worker's job: Dask
    computes it again, so it finishes only once a job runs it (here: once the watchdog has
    replaced the lost jobs)."""

    key, status = "fibrilfit-0-0-x", "lost"

    def __init__(self, cluster):
        self.cluster, self.waits = cluster, 0

    def result(self, timeout=None):
        self.waits += 1
        if not {"w3", "w4"} & set(self.cluster.workers):
            raise TimeoutError  # what Future.result(timeout) raises while it is computed again
        self.status = "finished"
        return {"id": 0, "ok": True, "result": "rerun"}

    def release(self):
        pass


class Done:
    def __init__(self, future):
        self.future = future

    def has_ready(self):
        return True

    def __next__(self):
        return self.future


def lost_result(ex, monkeypatch):
    future = LostFuture(ex.cluster)
    ex.done, ex.futures = Done(future), {future.key: {"id": 0, "attempt": 0}}
    monkeypatch.setattr(ex, "KEEP_EVERY", 0.0)
    return future


def test_a_result_lost_after_it_finished_is_waited_for_with_the_watchdog(executor, monkeypatch):
    """CI, 2026-11-25: every job cancelled just after a run finished; its result went with its
    worker, and a wait blocked in Future.result() never replaced the jobs its rerun needed."""
    ex, alive = executor
    future = lost_result(ex, monkeypatch)
    alive["ids"] = set()  # scancel of every job
    job, reply = ex.wait()
    assert reply == {"id": 0, "ok": True, "result": "rerun"} and job["id"] == 0
    assert future.waits == 2 and ex.replaced == 2  # one timed-out wait, the watchdog, the rerun


def test_a_lost_result_with_sbatch_refusing_stops_in_one_line(executor, monkeypatch):
    ex, alive = executor
    lost_result(ex, monkeypatch)
    alive["ids"] = set()
    ex.cluster.refuse = "sbatch: error: Batch job submission failed: Required partition not " \
                        "available (inactive or drain)"
    with pytest.raises(executors.SweepError, match="SLURM refused the replacement jobs"):
        ex.wait()


def test_an_error_the_task_raised_is_its_reply(executor, monkeypatch):
    """A TimeoutError raised by the run itself is its reply, not a reason to wait again."""
    ex, _ = executor
    future = lost_result(ex, monkeypatch)
    future.status = "error"
    job, reply = ex.wait()
    assert reply["ok"] is False and reply["error"].startswith("TimeoutError")


def test_alive_jobs_reads_squeue(tmp_path, monkeypatch):
    squeue = tmp_path / "squeue"
    squeue.write_text("#!/bin/sh\nprintf '11 RUNNING\\n12 PENDING\\n13 COMPLETING\\n"
                      "14 CANCELLED\\n'\n")
    squeue.chmod(squeue.stat().st_mode | stat.S_IEXEC)
    monkeypatch.setenv("PATH", f"{tmp_path}{os.pathsep}{os.environ['PATH']}")
    assert slurm.alive_jobs(executors.SlurmExecutor.ALIVE) == {"11", "12"}
    squeue.write_text("#!/bin/sh\necho 'slurm_load_jobs error: Socket timed out' >&2\nexit 1\n")
    assert slurm.alive_jobs(executors.SlurmExecutor.ALIVE) is None
    monkeypatch.setenv("PATH", str(tmp_path / "none"))
    assert slurm.alive_jobs(executors.SlurmExecutor.ALIVE) is None
