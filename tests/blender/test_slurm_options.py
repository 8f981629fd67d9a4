"""The executor options without a SLURM: the job script `--executor slurm` would submit, the same
for every command that runs many models, and `run --restarts`, `minimal-linker` and `report`
running through the executor their options name (a stand-in that records how it was made and
runs the jobs on local workers). (Through a real SLURM: test_cluster.py, `make test-cluster`.)"""
import json
import sys

import dask_jobqueue  # noqa: F401 (requirements-dev installs it: a broken wheel fails, never skips)
import distributed  # noqa: F401
import pytest


# In this process, no physics: the same on every bpy (tests/blender/conftest.py's one_bpy).
pytestmark = pytest.mark.one_bpy


def sweep(ff, capsys, *args):
    """headless.py sweep ARGS, in this process (no bpy work happens): (exit code, out, err)."""
    code = ff.cli.main(["sweep", *args])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_the_job_script_carries_the_options(ff, capsys, tmp_path):
    out = tmp_path / "sweep"
    code, stdout, stderr = sweep(ff, capsys, "--linker", "2,6", "--executor", "slurm", "--partition", "short",
                 "--account", "lab42", "--memory", "3GB", "--walltime", "1-02:00:00",
                 "--job-name", "ff", "--job-directive=--qos=low", "--job-directive=--exclusive",
                 "--job-prologue", "module load gcc", "--python", sys.executable,
                 "--out", str(out), "--show-job-script")
    assert code == 0, stderr
    script = stdout.splitlines()
    directives = [line for line in script if line.startswith("#SBATCH")]
    assert directives == [
        "#SBATCH -J ff", f"#SBATCH -e {out}/slurm/ff-%J.err", f"#SBATCH -o {out}/slurm/ff-%J.out",
        "#SBATCH -p short", "#SBATCH -A lab42", "#SBATCH -n 1", "#SBATCH --cpus-per-task=1",
        "#SBATCH --mem=3G", "#SBATCH -t 1-02:00:00", "#SBATCH --qos=low", "#SBATCH --exclusive"]
    prologue = script.index("module load gcc")
    (worker,) = [line for line in script if "distributed.cli.dask_worker" in line]
    assert script.index(worker) > prologue
    assert worker.startswith(f"{sys.executable} -m distributed.cli.dask_worker tcp://")
    assert "--nthreads 1" in worker and "--nanny" in worker  # one single-threaded worker per job
    assert not out.exists()  # it submits nothing and writes nothing


def test_default_job_script(ff, capsys, tmp_path):
    code, stdout, stderr = sweep(ff, capsys, "--linker", "2", "--executor", "slurm", "--out",
                                 str(tmp_path / "s"), "--show-job-script")
    assert code == 0, stderr
    assert "#SBATCH --mem=2G" in stdout and "#SBATCH -J fibrilfit" in stdout
    assert "#SBATCH -p" not in stdout and "#SBATCH -A" not in stdout


@pytest.mark.parametrize("args, says", [
    (("--partition", "short"), "--partition: only with --executor slurm"),
    (("--executor", "dask", "--job-directive=--qos=low"), "--job-directive: only with --executor slurm"),
    (("--executor", "slurm", "--walltime", "4h"), "--walltime: must be a SLURM time"),
    (("--executor", "slurm", "--memory", "lots"), "--memory: must be a size such as 2GB"),
    (("--executor", "slurm", "--python", "/no/such/python"), "--python: '/no/such/python' is not"),
    (("--executor", "slurm", "--job-directive", "qos=low"), "--job-directive: must be an sbatch"),
    (("--executor", "slurm", "--scheduler", "tcp://h:8786"), "--scheduler: only with --executor dask"),
    (("--executor", "slurm", "--workers", "0"), "--workers: must be at least 1"),
])
def test_bad_slurm_options_exit_2_with_one_line_and_write_nothing(ff, capsys, tmp_path, args,
                                                                  says):
    code, _, stderr = sweep(ff, capsys, "--linker", "2", *args, "--out", str(tmp_path / "s"))
    assert code == 2 and says in stderr, stderr
    assert len(stderr.strip().splitlines()) == 1 and not (tmp_path / "s").exists()




# ---- run --restarts, minimal-linker and report go through the executor their options name ------

TINY = ["--layers", "3", "--grow-frames", "20", "--hold-frames", "20", "--regrow-cycles", "0",
        "--globule-diameter", "12", "--restarts", "2", "--quiet"]


@pytest.fixture
def recorded(monkeypatch):
    """executors.DaskExecutor and SlurmExecutor replaced by stand-ins that record how they were
    made and run the jobs on 2 local worker processes: [(kind, workers, options)]."""
    import bpy
    from fibrilfit.batch import executors
    made = []

    def stand_in(kind):
        class Recorder:
            def __init__(self, workers, *positional, **keywords):
                made.append((kind, workers, {**keywords, **(
                    {"cluster_options": positional[0]} if positional else {})}))
                self.inner = executors.ProcessExecutor(
                    2, blender_binary=bpy.app.binary_path)

            def __enter__(self):
                self.inner.__enter__()
                return self

            def __exit__(self, *exc):
                return self.inner.__exit__(*exc)

            def submit(self, job):
                self.inner.submit(job)

            def pending(self):
                return self.inner.pending()

            def wait(self):
                return self.inner.wait()
        return Recorder
    monkeypatch.setattr(executors, "DaskExecutor", stand_in("dask"))
    monkeypatch.setattr(executors, "SlurmExecutor", stand_in("slurm"))
    return made


def test_run_restarts_goes_through_the_dask_scheduler_it_names(ff, capsys, tmp_path, recorded):
    out = tmp_path / "best.json"
    code = ff.cli.main(["run", *TINY, "--protocol", "inflate", "--linker", "3", "--executor",
                        "dask", "--scheduler", "tcp://nowhere:8786", "--workers", "2",
                        "--timeout", "600", "--json", str(out)])
    assert code == 0, capsys.readouterr().err
    assert recorded == [("dask", 2, {"scheduler": "tcp://nowhere:8786", "timeout": 600.0})]
    assert json.loads(out.read_text())["restarts"]["restarts"] == 2


def test_minimal_linker_goes_through_the_slurm_jobs_it_names(ff, capsys, tmp_path, recorded):
    out = tmp_path / "map"
    code = ff.cli.main(["minimal-linker", *TINY, "--max-linker", "2", "--no-plot", "--executor",
                        "slurm", "--partition", "short", "--walltime", "10", "--out", str(out)])
    assert code == 0, capsys.readouterr().err
    ((kind, jobs, made),) = recorded  # one executor for the whole walk
    assert (kind, made["timeout"]) == ("slurm", None)
    assert 1 <= jobs <= 2  # one job per run of the first step (2 restarts), none given
    cluster = made["cluster_options"]
    assert (cluster["queue"], cluster["walltime"]) == ("short", "10")
    assert cluster["log_directory"] == str(out.resolve() / "slurm")
    (row,) = json.loads((out / "minimal_linker.json").read_text())["rows"]
    runs = [json.loads(line) for line in (out / "results.jsonl").read_text().splitlines()]
    at_min = sorted((r for r in runs if r["params"]["linker"] == row["minimal_linker"]),
                    key=lambda r: r["params"]["seed"])
    assert len(at_min) in (1, 2)  # both restarts went out to SLURM; the second may not finish first
    fits = [r.get("accommodated") for r in at_min]
    # the minimum counts its seeds in seed order up to the first fit (docs/model/search.md#decided)
    assert row["restarts"] == fits.index(True) + 1


def test_report_goes_through_the_executor_it_names(ff, capsys, tmp_path, recorded):
    out = tmp_path / "rep"
    code = ff.cli.main(["report", *TINY, "--linker", "3", "--max-linker", "4", "--executor",
                        "slurm", "--workers", "2", "--account", "lab42", "--render-engine",
                        "workbench", "--render-size", "64x36", "--out", str(out)])
    assert code == 0, capsys.readouterr().err
    assert recorded and all(kind == "slurm" and jobs == 2 for kind, jobs, _ in recorded)
    assert {made["cluster_options"]["account"] for _, _, made in recorded} == {"lab42"}
    assert json.loads((out / "report.json").read_text())["p_fit"]["runs"] == 2


@pytest.mark.parametrize("command, argv", [
    ("run", ["--restarts", "2"]), ("minimal-linker", []), ("report", []), ("sweep", ["--linker", "2"])])
def test_every_batch_command_shows_the_same_job_script(ff, capsys, tmp_path, command, argv):
    out = tmp_path / "o"
    extra = [] if command == "run" else ["--out", str(out)]
    code = ff.cli.main([command, *argv, "--executor", "slurm", "--partition", "short",
                        "--job-name", "ff", "--memory", "3GB", *extra, "--show-job-script"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    directives = [line for line in captured.out.splitlines() if line.startswith("#SBATCH")]
    logs = (out if command != "run" else restarts_out()).resolve() / "slurm"
    assert directives == [
        "#SBATCH -J ff", f"#SBATCH -e {logs}/ff-%J.err", f"#SBATCH -o {logs}/ff-%J.out",
        "#SBATCH -p short", "#SBATCH -n 1", "#SBATCH --cpus-per-task=1", "#SBATCH --mem=3G",
        "#SBATCH -t 00:30:00"]
    assert not out.exists()  # it submits nothing and writes nothing


def restarts_out():
    """Where `run --restarts` puts its SLURM job logs: it has no --out."""
    import pathlib
    from fibrilfit.batch.plans import RESTARTS_OUT
    return pathlib.Path(RESTARTS_OUT)
