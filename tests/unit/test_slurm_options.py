"""`sweep --executor slurm` without a SLURM: its options and the job script it would submit.
(Sweeps through a real SLURM: test_cluster.py, `make test-cluster`.)"""


def test_sbatch_errors_are_reduced_to_their_line():
    from fibrilfit.batch.slurm import submit_error
    exc = RuntimeError("Command exited with non-zero exit code.\nExit code: 1\n"
                       "Command:\nsbatch /tmp/tmpx.sh\nstdout:\n\nstderr:\n"
                       "sbatch: error: invalid partition specified: nope\n"
                       "sbatch: error: Batch job submission failed: Invalid partition name "
                       "specified\n\n")
    assert submit_error(exc) == "sbatch: error: invalid partition specified: nope"
    assert submit_error(ValueError("no sbatch here")) == "no sbatch here"
