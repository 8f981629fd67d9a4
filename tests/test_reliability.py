"""Bad input refused cleanly, runs that are killed or interrupted leave no result, and the same
seed gives the same result across processes."""
import json
import os
import signal
import subprocess
import sys
import time

import bpy
import pytest
from bad_inputs import BAD_INPUTS
from helpers import ROOT, run_cli, snapshot_user

from fibrilfit import params as P, pipeline


@pytest.mark.parametrize("cli_args,api_kwargs,name", BAD_INPUTS, ids=lambda v: str(v)[:40])
def test_cli_refuses_bad_input(cli_args, api_kwargs, name, tmp_path):
    out = run_cli("run", *cli_args, "--json", str(tmp_path / "r.json"),
                  "--blend", str(tmp_path / "m.blend"))
    assert out.returncode == 2
    err = out.stderr.strip()
    assert "\n" not in err and f"{name}:" in err
    assert "Traceback" not in out.stderr + out.stdout
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("cli_args,api_kwargs,name", BAD_INPUTS, ids=lambda v: str(v)[:40])
def test_api_refuses_bad_input_and_keeps_the_scene(cli_args, api_kwargs, name, scene, user_objects):
    pipeline.run(P.make_params(layers=2, frames=5), scene)
    before_user = snapshot_user(user_objects)
    before = sorted(ob.name for ob in scene.objects)
    with pytest.raises(P.ParamError) as err:
        pipeline.run(P.make_params(**api_kwargs), scene)
    assert err.value.param == name and "\n" not in str(err.value)
    assert sorted(ob.name for ob in scene.objects) == before
    assert snapshot_user(user_objects) == before_user


def test_force_lifts_the_layer_limit():
    assert P.make_params(layers=20000, force=True).layers == 20000


def test_unknown_option_and_command():
    for args in (["run", "--linkr", "4"], ["bake"], []):
        out = run_cli(*args)
        assert out.returncode == 2 and out.stderr.count("\n") == 1, args
        assert "Traceback" not in out.stderr


def _start(args, tmp_path):
    return subprocess.Popen([sys.executable, str(ROOT / "headless.py"), "run", *args,
                             "--json", str(tmp_path / "r.json"), "--blend", str(tmp_path / "m.blend")],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT)


def _wait_for_bake(proc, seconds):
    time.sleep(seconds)  # long enough to be inside the bake of a 100-layer model
    assert proc.poll() is None, proc.communicate()


def test_ctrl_c_exits_130_and_writes_nothing(tmp_path):
    proc = _start(["--layers", "100"], tmp_path)
    _wait_for_bake(proc, 4)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


def test_killed_run_leaves_no_file_that_looks_complete(tmp_path):
    proc = _start(["--layers", "100"], tmp_path)
    _wait_for_bake(proc, 4)
    proc.kill()
    proc.wait(timeout=60)
    assert not (tmp_path / "r.json").exists() and not (tmp_path / "m.blend").exists()


def test_same_seed_same_json_across_processes(tmp_path):
    results = []
    for i in range(2):
        out = run_cli("run", "--layers", "10", "--linker", "4", "--seed", "11", "--frames", "150",
                      "--json", str(tmp_path / f"{i}.json"))
        assert out.returncode == 0, out.stderr
        r = json.loads((tmp_path / f"{i}.json").read_text())
        r.pop("timings_s")
        results.append(r)
    assert results[0] == results[1]
    assert results[0]["blender_version"] == bpy.app.version_string
