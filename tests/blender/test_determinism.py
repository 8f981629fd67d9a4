"""The same seed on the same Blender gives the same result: in fresh processes, whatever the
number of threads the depsgraph evaluates with, in a sweep worker and after --restarts.

Inflate once depended on the order the depsgraph's threads ran in (docs/model/search.md#determinism):
a process held to one CPU (one evaluation thread) gave 147 frames where two CPUs mostly gave 161,
and a busy machine mixed the two. So one of the three fresh runs here is held to one CPU: on the
old code that made the comparison fail every time, not only when the machine happened to be busy.
"""
import json
import os
import subprocess
import sys

import pytest

from helpers import ROOT

INFLATE = ["--protocol", "inflate", "--linker", "5", "--seed", "2"]
# the smallest cell for 30 Å globules (8 layers), one cycle: jammed at full size, so every frame
# of the schedule (4 x 161) is simulated with globules touching their images
PERIODIC = INFLATE + ["--periodic", "8", "--regrow-cycles", "0"]
TUTORIAL = ["--linker", "5", "--seed", "2"]
TUTORIAL_PERIODIC = TUTORIAL + ["--periodic", "8", "--frames", "200"]


def _one_cpu():
    cpus = sorted(os.sched_getaffinity(0))
    return lambda: os.sched_setaffinity(0, {cpus[0]})


def _run(args, path, one_cpu=False):
    """A fresh process's result JSON, without its timings."""
    done = subprocess.run([sys.executable, str(ROOT / "headless.py"), "run", *args, "--quiet",
                           "--json", str(path)], capture_output=True, text=True, timeout=900,
                          cwd=ROOT, preexec_fn=_one_cpu() if one_cpu else None)
    assert done.returncode == 0, done.stderr
    result = json.loads(path.read_text())
    result.pop("timings_s")
    return result


def _same(runs):
    first = runs[0]
    for other in runs[1:]:
        # the globule centres first: the clearest message when a bake diverged
        assert other["globule_centres"] == first["globule_centres"]
        assert other["frames_simulated"] == first["frames_simulated"]
        assert other == first


@pytest.mark.parametrize("args", [INFLATE, PERIODIC, TUTORIAL, TUTORIAL_PERIODIC],
                         ids=["inflate", "inflate-periodic", "tutorial", "tutorial-periodic"])
def test_the_same_seed_gives_the_same_json_in_fresh_processes(tmp_path, args):
    """Three fresh processes, the second held to one CPU: the same JSON, timings aside."""
    runs = [_run(args, tmp_path / f"{i}.json", one_cpu=(i == 1)) for i in range(3)]
    _same(runs)


def test_a_worker_and_restarts_give_the_fresh_process_result(tmp_path):
    """--restarts 1 runs the seed in a sweep worker, then again here as the best seed: the
    worker's record, the run here and a fresh process agree."""
    fresh = _run(INFLATE, tmp_path / "fresh.json")
    done = _run(INFLATE + ["--restarts", "1", "--workers", "1"], tmp_path / "restarts.json")
    r = done.pop("restarts")
    (worker,) = r["runs"]
    assert (worker["seed"], r["best_seed"]) == (2, 2)
    assert worker["frames_simulated"] == fresh["frames_simulated"]
    assert worker["max_bond_stretch"] == fresh["max_bond_stretch"]
    assert worker["accommodated"] == fresh["accommodated"]
    assert r["reproduced"] is True
    assert done["globule_centres"] == fresh["globule_centres"]
