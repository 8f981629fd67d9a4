"""`sweep --executor slurm` without a SLURM: its options and the job script it would submit.
(Sweeps through a real SLURM: test_cluster.py, `make test-cluster`.)"""
import sys

import pytest


def sweep(ff, capsys, *args):
    """headless.py sweep ARGS, in this process (no bpy work happens): (exit code, out, err)."""
    code = ff.cli.main(["sweep", *args])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_the_job_script_carries_the_options(ff, capsys, tmp_path):
    pytest.importorskip("dask_jobqueue")
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
    pytest.importorskip("dask_jobqueue")
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


