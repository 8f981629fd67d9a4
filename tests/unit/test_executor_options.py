"""The executor options (batch/plans.py's ExecutorPlan) without a SLURM: every command that runs many models
takes the same ones and makes the same executor of them; sbatch's errors in one line.
(Through a real SLURM: tests/blender/test_cluster.py, `make test-cluster`.)"""
import argparse
import re
import sys

import pytest


def test_sbatch_errors_are_reduced_to_their_line():
    from fibrilfit.batch.slurm import submit_error
    exc = RuntimeError("Command exited with non-zero exit code.\nExit code: 1\n"
                       "Command:\nsbatch /tmp/tmpx.sh\nstdout:\n\nstderr:\n"
                       "sbatch: error: invalid partition specified: nope\n"
                       "sbatch: error: Batch job submission failed: Invalid partition name "
                       "specified\n\n")
    assert submit_error(exc) == "sbatch: error: invalid partition specified: nope"
    assert submit_error(ValueError("no sbatch here")) == "no sbatch here"


# ---- one set of executor options for every command that runs many models -----------------------

# the commands that run many models, each with what it needs besides the executor options
MANY = {"run": ["run", "--restarts", "2"], "minimal-linker": ["minimal-linker"],
        "report": ["report"], "sweep": ["sweep", "--linker", "2"]}
SLURM = ["--executor", "slurm", "--workers", "3", "--timeout", "60", "--partition", "short",
         "--account", "lab42", "--memory", "3GB", "--walltime", "01:00:00", "--job-name", "ff",
         "--job-directive=--qos=low", "--job-prologue", "module load gcc", "--interface", "lo",
         "--python", sys.executable]
DASK = ["--executor", "dask", "--workers", "2", "--scheduler", "tcp://host:8786",
        "--timeout", "30"]


def _parsed(argv):
    from fibrilfit.cli import build_parser
    return build_parser().parse_args(argv)


def _planned(argv):
    """The command's plan from a command line, as cli/commands.main makes it."""
    from fibrilfit.api.plans import COMMAND_PLANS, make_plan
    args = _parsed(argv)
    given = {k: v for k, v in vars(args).items() if k not in ("command", "case")}
    return make_plan(COMMAND_PLANS[args.command], given)[0]


def _subparsers():
    from fibrilfit.cli import build_parser
    (sub,) = [a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    return sub.choices


def test_every_batch_command_declares_the_same_executor_options():
    from fibrilfit.batch.plans import ExecutorPlan
    from fibrilfit.plans import option_fields
    names = {f.name for f in option_fields(ExecutorPlan)}
    assert {"executor", "workers", "scheduler", "timeout", "partition", "walltime",
            "show_job_script"} <= names
    subs = _subparsers()
    for command in MANY:
        actions = {a.dest: a for a in subs[command]._actions}
        assert names <= set(actions), (command, names - set(actions))
        assert actions["executor"].choices == ("processes", "dask", "slurm"), command
        for name in names:  # the very same declaration: help and default alike
            first = {a.dest: a for a in subs["sweep"]._actions}[name]
            assert (actions[name].help, actions[name].default) == (first.help, first.default)
    assert not names & {a.dest for a in subs["inspect"]._actions}  # inspect runs no model


@pytest.mark.parametrize("given", [SLURM, DASK, ["--workers", "2"]],
                         ids=["slurm", "dask", "processes"])
def test_the_same_options_give_the_same_executor_in_every_command(tmp_path, given):
    from fibrilfit.batch.executors import executor_spec
    specs = {}
    for command, argv in MANY.items():
        plan = _planned([*argv, *given])  # accepted by every one (checked when made)
        specs[command] = executor_spec(plan.executor, out=tmp_path, runs=5)
    first = specs["sweep"]
    assert all(spec == first for spec in specs.values()), specs
    if given is SLURM:
        assert first["executor"] == "slurm" and first["workers"] == 3 and first["timeout"] == 60
        cluster = first["cluster_options"]
        assert (cluster["queue"], cluster["account"], cluster["memory"], cluster["walltime"],
                cluster["job_name"], cluster["interface"], cluster["python"]) == (
            "short", "lab42", "3GB", "01:00:00", "ff", "lo", sys.executable)
        assert cluster["job_extra_directives"] == ["--qos=low"]
        assert cluster["job_script_prologue"] == ["module load gcc"]
        assert cluster["log_directory"] == str(tmp_path.resolve() / "slurm")
    elif given is DASK:
        assert first == {"executor": "dask", "workers": 2, "scheduler": "tcp://host:8786",
                         "timeout": 30}
    else:
        assert first == {"executor": "processes", "workers": 2, "timeout": None}


def test_slurm_jobs_default_to_one_per_run_at_most_sixteen(tmp_path):
    from fibrilfit.batch.executors import executor_spec
    plan = _planned(["minimal-linker", "--executor", "slurm"]).executor
    assert [executor_spec(plan, out=tmp_path, runs=n)["workers"] for n in (1, 5, 40)] == [1, 5, 16]


@pytest.mark.parametrize("command", list(MANY))
@pytest.mark.parametrize("bad, says", [
    (["--partition", "short"], "--partition: only with --executor slurm"),
    (["--executor", "slurm", "--walltime", "4h"], "--walltime: must be a SLURM time"),
    (["--executor", "slurm", "--scheduler", "tcp://h:8786"], "--scheduler: only with --executor dask"),
    (["--workers", "0"], "--workers: must be at least 1"),
    (["--timeout", "0"], "--timeout: must be a positive number"),
])
def test_every_batch_command_refuses_bad_executor_options_alike(command, bad, says):
    from fibrilfit.exits import UsageError
    with pytest.raises(UsageError, match=f"^{re.escape(says)}"):
        _planned([*MANY[command], *bad])


def test_run_takes_executor_options_only_with_restarts():
    from fibrilfit.exits import UsageError
    # the command's own reason first (RunPlan.refuse), before the executor's plan would say
    # that a SLURM option needs --executor slurm
    for bad, says in ((["--partition", "short"], "--partition: only with --restarts"),
                      (["--executor", "slurm", "--partition", "short"],
                       "--executor: only with --restarts"),
                      (["--executor", "slurm"], "--executor: only with --restarts")):
        with pytest.raises(UsageError, match=f"^{re.escape(says)}$"):
            _planned(["run", *bad])
    _planned(["run", "--workers", "4"])  # as before: ignored, no error


def test_the_sidebars_report_has_every_executor_option_at_its_default():
    # as ui/operators/report.py makes its plan: the model and the search, nothing else
    import dataclasses
    from fibrilfit.api.plans import ReportPlan
    from fibrilfit.batch.plans import ExecutorPlan
    from fibrilfit.search.plans import REPORT_SEARCH
    plan = ReportPlan.make(model={}, search=REPORT_SEARCH.replace(restarts=3, max_linker=10))
    defaults = {f.name: f.default for f in dataclasses.fields(ExecutorPlan)}
    assert {k: getattr(plan.executor, k) for k in defaults} == defaults
    plan.executor.check()
    assert _planned(["report"]).executor.executor == plan.executor.executor == "processes"


def test_run_and_report_declare_the_same_render_options():
    subs = _subparsers()
    names = ("render_size", "render_samples", "render_engine")
    run = {a.dest: a for a in subs["run"]._actions}
    report = {a.dest: a for a in subs["report"]._actions}
    for name in names:
        assert (run[name].help, run[name].default, run[name].choices) == (
            report[name].help, report[name].default, report[name].choices)
