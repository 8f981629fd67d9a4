"""Sweeps through a real SLURM (`--executor slurm`): `make test-cluster` sets up a single-node SLURM
(.ci/slurm/setup.sh) and runs this file with `-m cluster` and FIBRILFIT_REQUIRE_SLURM=1, under
which a SLURM with no node up fails every test. Skipped otherwise, so `make test` never submits a
job, even where a SLURM answers."""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

import pytest
from helpers import ROOT, run_cli

from fibrilfit.sweep import grid

pytestmark = pytest.mark.cluster

DONE_WHEN = ("--linker", "1,12", "--layers", "8", "--seeds", "3", "--workers", "2")
# Waits for what the machine's load decides (a job starting bpy, a 40-layer run) are generous:
# on a shared 2-core machine at load 20 a run takes minutes. The wait for what the executor
# decides (a replacement job: its watchdog polls squeue every 10 s) stays short.
SLOW = 900
# 16 runs of about a second on 2 jobs: long enough to cancel jobs and interrupt the sweep mid-way
LONGER = ("--linker", "2,6", "--layers", "40", "--seeds", "8", "--workers", "2")


def _node_state() -> str:
    if shutil.which("sinfo") is None:
        return "no sinfo"
    cp = subprocess.run(["sinfo", "-h", "-N", "-o", "%T"], capture_output=True, text=True,
                        timeout=30)
    return cp.stdout.strip() or cp.stderr.strip() or "no node"


@pytest.fixture(scope="module")
def node_state():
    return _node_state()


@pytest.fixture(autouse=True)
def slurm_up(request, node_state):
    if "cluster" not in (request.config.getoption("markexpr") or ""):
        pytest.skip("submits SLURM jobs: run with -m cluster (make test-cluster)")
    if not any(s in node_state for s in ("idle", "mixed", "allocated", "completing")):
        if os.environ.get("FIBRILFIT_REQUIRE_SLURM") == "1":  # make test-cluster: a dead SLURM
            pytest.fail(f"no SLURM node is up ({node_state})")  # fails, never a green skip
        pytest.skip(f"no SLURM node is up ({node_state}): run make test-cluster")


def lines(path):
    return [json.loads(line) for line in path.read_text().splitlines()]


def keys(records):
    return [grid.point_key(r["params"]) for r in records]


def same_run(record: dict) -> dict:
    """A result without what legitimately differs between two runs of one point."""
    return {k: v for k, v in record.items() if k not in ("timings_s", "worker")}


def jobs(name: str, states: str = "PD,R,CG") -> list[str]:
    cp = subprocess.run(["squeue", "-h", "-n", name, "-t", states, "-o", "%i"],
                        capture_output=True, text=True, timeout=30, check=True)
    return cp.stdout.split()


def wait_for(condition, seconds: float, what: str):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.1)
    raise AssertionError(f"waited {seconds:g} s for {what}")


def count(path) -> int:
    return len(path.read_text().splitlines()) if path.exists() else 0


def _default_sigint():
    signal.signal(signal.SIGINT, signal.SIG_DFL)  # background shells start us with it ignored


def start_sweep(*args) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, str(ROOT / "headless.py"), "sweep", *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT,
                            preexec_fn=_default_sigint)


def test_slurm_sweep_gives_the_local_executors_results(tmp_path):
    cp = run_cli("sweep", *DONE_WHEN, "--out", str(tmp_path / "local"), "--quiet")
    assert cp.returncode == 0, cp.stderr
    cp = run_cli("sweep", *DONE_WHEN, "--executor", "slurm", "--job-name", "ff-same",
                 "--out", str(tmp_path / "slurm"), "--quiet")
    assert cp.returncode == 0, cp.stderr
    ours = {grid.point_key(r["params"]): r for r in lines(tmp_path / "local" / "results.jsonl")}
    theirs = lines(tmp_path / "slurm" / "results.jsonl")
    assert len(theirs) == 6 and set(keys(theirs)) == set(ours)
    for r in theirs:  # the whole result: only timings and the worker differ
        assert same_run(r) == same_run(ours[grid.point_key(r["params"])])
    assert (tmp_path / "slurm" / "summary.csv").read_text() == \
        (tmp_path / "local" / "summary.csv").read_text()
    ran_in = {r["worker"]["slurm_job"] for r in theirs}  # the runs happened inside SLURM jobs
    assert len(ran_in) == 2
    logs = sorted(p.name for p in (tmp_path / "slurm" / "slurm").iterdir())
    assert logs == sorted(f"ff-same-{j}.{ext}" for j in ran_in for ext in ("err", "out"))
    wait_for(lambda: not jobs("ff-same", "PD,R"), 30, "the sweep's jobs to end")


def test_a_cancelled_job_loses_no_run(tmp_path):
    out = tmp_path / "s"
    args = (*LONGER, "--executor", "slurm", "--job-name", "ff-cancel", "--out", str(out),
            "--quiet")
    proc = start_sweep(*args)
    try:
        # after the first result both jobs are busy (see test_sweep's killed-worker test)
        wait_for(lambda: count(out / "results.jsonl"), SLOW, "the first result")
        victim = jobs("ff-cancel", "R")[0]
        subprocess.run(["scancel", victim], check=True, timeout=30)
        stdout, stderr = proc.communicate(timeout=2 * SLOW)
    finally:
        proc.kill()
    assert proc.returncode == 0, stderr
    records = lines(out / "results.jsonl")
    assert len(records) == 16 and len(set(keys(records))) == 16
    assert all(r["status"] == "ok" for r in records)
    assert "16 with a verdict, 0 failed" in stdout
    # --resume finds nothing to do and changes nothing
    before = (out / "results.jsonl").read_bytes()
    cp = run_cli("sweep", *args, "--resume", timeout=2 * SLOW)
    assert cp.returncode == 0, cp.stderr
    assert (out / "results.jsonl").read_bytes() == before


def test_every_job_cancelled_then_interrupted_and_resumed(tmp_path):
    out = tmp_path / "s"
    args = (*LONGER, "--executor", "slurm", "--job-name", "ff-all", "--out", str(out), "--quiet")
    proc = start_sweep(*args)
    try:
        wait_for(lambda: count(out / "results.jsonl"), SLOW, "the first result")
        first = jobs("ff-all", "PD,R")  # every job of the sweep, also one still queued
        subprocess.run(["scancel", *first], check=True, timeout=30)
        at_cancel = count(out / "results.jsonl")
        # no job left: the sweep goes on only because the executor submits replacements
        new = wait_for(lambda: set(jobs("ff-all", "PD,R")) - set(first), 120,
                       "a replacement job")
        wait_for(lambda: count(out / "results.jsonl") > at_cancel + 1, SLOW,
                 "a result from a replacement job")
        proc.send_signal(signal.SIGINT)
        _, stderr = proc.communicate(timeout=120)
    finally:
        proc.kill()
    assert proc.returncode == 130, stderr
    assert "continue with --resume" in stderr
    wait_for(lambda: not jobs("ff-all", "PD,R"), 60, "Ctrl-C to cancel the jobs")
    kept = lines(out / "results.jsonl")
    assert at_cancel < len(kept) < 16
    assert {r["worker"]["slurm_job"] for r in kept[at_cancel + 1:]} <= new

    cp = run_cli("sweep", *args, "--resume", timeout=2 * SLOW)
    assert cp.returncode == 0, cp.stderr
    records = lines(out / "results.jsonl")
    assert records[:len(kept)] == kept
    assert len(records) == 16 and len(set(keys(records))) == 16  # every point, none twice
    assert all(r["status"] == "ok" for r in records)


def test_a_job_cancelled_while_queued_is_replaced(tmp_path):
    """Issue #25: a job cancelled before it started never had a Dask worker, so Dask never
    misses it; the executor's watchdog, asking squeue, replaces it. 3 one-core jobs on the
    2-CPU node: one waits in the queue."""
    out = tmp_path / "s"
    args = ("--linker", "2,6", "--layers", "40", "--seeds", "8", "--workers", "3",
            "--executor", "slurm", "--job-name", "ff-queued", "--out", str(out), "--quiet")
    proc = start_sweep(*args)
    try:
        # two running and one waiting for a CPU (right after sbatch all three are pending for a
        # moment: cancelling them then would be the every-job case)
        wait_for(lambda: len(jobs("ff-queued", "R")) == 2 and jobs("ff-queued", "PD"), SLOW,
                 "two running jobs and one waiting in the queue")
        queued = jobs("ff-queued", "PD")
        before = set(jobs("ff-queued", "PD,R"))
        subprocess.run(["scancel", *queued], check=True, timeout=30)
        wait_for(lambda: set(jobs("ff-queued", "PD,R")) - before, 120, "a replacement job")
        proc.send_signal(signal.SIGINT)
        _, stderr = proc.communicate(timeout=120)
    finally:
        proc.kill()
    assert proc.returncode == 130, stderr
    assert "fibrilfit: 1 SLURM job ended early; submitted 1 replacement\n" in stderr
    wait_for(lambda: not jobs("ff-queued", "PD,R"), 60, "Ctrl-C to cancel the jobs")


def default_partition() -> str:
    cp = subprocess.run(["sinfo", "-h", "-o", "%P"], capture_output=True, text=True, timeout=30,
                        check=True)
    (name,) = [p.rstrip("*") for p in cp.stdout.split() if p.endswith("*")]
    return name


def set_partition(name: str, state: str) -> None:
    subprocess.run(["scontrol", "update", f"PartitionName={name}", f"State={state}"],
                   check=True, timeout=30)


def test_sbatch_refusing_the_replacements_stops_in_one_line_and_resumes(tmp_path):
    """Issue #25: every job ends and SLURM takes no new ones (the partition drained): the sweep
    stops with one line and exit 2, its jobs gone, the finished runs kept; once SLURM takes jobs
    again, --resume completes it without loss."""
    out = tmp_path / "s"
    args = (*LONGER, "--executor", "slurm", "--job-name", "ff-drain", "--out", str(out),
            "--quiet")
    partition = default_partition()
    proc = start_sweep(*args)
    try:
        wait_for(lambda: count(out / "results.jsonl"), SLOW, "the first result")
        set_partition(partition, "DRAIN")  # queued jobs run, new ones are refused
        subprocess.run(["scancel", *jobs("ff-drain")], check=True, timeout=30)
        _, stderr = proc.communicate(timeout=SLOW)
    finally:
        set_partition(partition, "UP")
        proc.kill()
    assert proc.returncode == 2, stderr
    kept = lines(out / "results.jsonl")
    assert stderr.strip().splitlines() == [
        "fibrilfit: error: SLURM refused the replacement jobs: sbatch: error: Batch job "
        "submission failed: Required partition not available (inactive or drain); "
        f"{len(kept)} results kept in {out / 'results.jsonl'}, continue with --resume"], stderr
    assert 0 < len(kept) < 16
    wait_for(lambda: not jobs("ff-drain", "PD,R"), 60, "the sweep's jobs to end")

    cp = run_cli("sweep", *args, "--resume", timeout=2 * SLOW)
    assert cp.returncode == 0, cp.stderr
    records = lines(out / "results.jsonl")
    assert records[:len(kept)] == kept
    assert len(records) == 16 and len(set(keys(records))) == 16  # every point, none twice
    assert all(r["status"] == "ok" for r in records)


def test_sbatch_refusing_the_jobs_is_one_line(tmp_path):
    cp = run_cli("sweep", "--linker", "2", "--layers", "4", "--executor", "slurm",
                 "--partition", "no-such-partition", "--out", str(tmp_path / "s"), "--quiet")
    assert cp.returncode == 2
    assert cp.stderr.strip().splitlines() == [
        "fibrilfit: error: SLURM refused the worker jobs: "
        "sbatch: error: invalid partition specified: no-such-partition"], cp.stderr
    assert not (tmp_path / "s" / "results.jsonl").exists()


def test_the_jobs_run_the_python_they_are_given(tmp_path):
    """--python and --job-prologue reach the job script; the prologue's output is in the job's
    log under --out."""
    cp = run_cli("sweep", "--linker", "2", "--layers", "4", "--executor", "slurm",
                 "--job-name", "ff-script", "--python", sys.executable,
                 "--job-prologue", "echo prologue-ran-in-$SLURM_JOB_ID", "--out",
                 str(tmp_path / "s"), "--quiet")
    assert cp.returncode == 0, cp.stderr
    (record,) = lines(tmp_path / "s" / "results.jsonl")
    job = record["worker"]["slurm_job"]
    log = (tmp_path / "s" / "slurm" / f"ff-script-{job}.out").read_text()
    assert f"prologue-ran-in-{job}" in log
    assert os.path.exists(tmp_path / "s" / "summary.csv")


def test_minimal_linker_through_slurm_gives_the_local_map(tmp_path):
    """`minimal-linker --executor slurm` (batch/plans.py: the executor plan of every batch command): a tiny
    walk (8 Å fits at linker 1; the walk ran 4 runs in CI's first try) gives the local executor's
    map from the same runs, each run in a job."""
    small = ("--globule-diameter", "8", "--restarts", "2", "--max-linker", "2", "--layers", "4",
             "--no-plot", "--quiet")
    cp = run_cli("minimal-linker", *small, "--out", str(tmp_path / "local"))
    assert cp.returncode == 0, cp.stderr
    cp = run_cli("minimal-linker", *small, "--executor", "slurm", "--workers", "2",
                 "--job-name", "ff-minimal", "--out", str(tmp_path / "slurm"), timeout=SLOW)
    assert cp.returncode == 0, cp.stderr
    ours = json.loads((tmp_path / "local" / "minimal_linker.json").read_text())["rows"]
    theirs = json.loads((tmp_path / "slurm" / "minimal_linker.json").read_text())["rows"]
    assert theirs == ours and theirs[0]["minimal_linker"] == 1
    records = lines(tmp_path / "slurm" / "results.jsonl")
    local = lines(tmp_path / "local" / "results.jsonl")
    assert len(records) == len(local) >= 2 and sorted(keys(records)) == sorted(keys(local))
    assert all(r["worker"].get("slurm_job") for r in records)
    wait_for(lambda: not jobs("ff-minimal", "PD,R"), 30, "the walk's jobs to end")
