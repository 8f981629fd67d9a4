"""Bad input refused cleanly, and runs that are killed or interrupted leave no result. (The same
seed across processes: test_determinism.py.)"""
import re
import signal
import subprocess
import sys

import bpy
import pytest
from bad_inputs import BAD_INPUTS
from helpers import ROOT, cli_in_process, run_cli, snapshot_user

from fibrilfit.model import params as P
from fibrilfit import pipeline
from fibrilfit.ui.panel_words import field_label


def _refuse(cli, cli_args, name, tmp_path):
    out = cli("run", *cli_args, "--json", str(tmp_path / "r.json"),
              "--blend", str(tmp_path / "m.blend"))
    assert out.returncode == 2
    err = out.stderr.strip()
    assert "\n" not in err and f"{name}:" in err
    assert "Traceback" not in out.stderr + out.stdout
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("cli_args,api_kwargs,name", BAD_INPUTS, ids=lambda v: str(v)[:40])
def test_cli_refuses_bad_input(cli_args, api_kwargs, name, tmp_path):
    """In this process (tests/helpers.py's cli_in_process): the refusal comes before any work."""
    _refuse(cli_in_process, cli_args, name, tmp_path)


def test_cli_refuses_bad_input_in_a_fresh_process(tmp_path):
    """One row as a user's shell sees it: the process's own stderr and exit code."""
    cli_args, _, name = BAD_INPUTS[0]
    _refuse(run_cli, cli_args, name, tmp_path)


@pytest.mark.parametrize("cli_args,api_kwargs,name", BAD_INPUTS, ids=lambda v: str(v)[:40])
def test_api_refuses_bad_input_and_keeps_the_scene(cli_args, api_kwargs, name, scene, user_objects):
    pipeline.run_model(P.make_params(layers=2, frames=5), scene)
    before_user = snapshot_user(user_objects)
    before = sorted(ob.name for ob in scene.objects)
    with pytest.raises(P.ParamError) as err:
        pipeline.run_model(P.make_params(**api_kwargs), scene)
    assert err.value.param == name and "\n" not in str(err.value)
    assert sorted(ob.name for ob in scene.objects) == before
    assert snapshot_user(user_objects) == before_user


def test_force_lifts_the_layer_limit():
    assert P.make_params(layers=20000, force=True).layers == 20000


def test_unknown_option_and_command():
    for cli, args in ((run_cli, ["run", "--linkr", "4"]), (cli_in_process, ["bake"]),
                      (cli_in_process, [])):
        out = cli(*args)
        assert out.returncode == 2 and out.stderr.count("\n") == 1, args
        assert "Traceback" not in out.stderr


def _start(args, tmp_path):
    return subprocess.Popen([sys.executable, str(ROOT / "headless.py"), "run", *args, "--progress",
                             "--json", str(tmp_path / "r.json"), "--blend", str(tmp_path / "m.blend")],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT,
                            preexec_fn=_ctrl_c_as_in_a_terminal)


def _ctrl_c_as_in_a_terminal():
    # A shell starts background jobs with SIGINT ignored, and Python then never turns SIGINT
    # into KeyboardInterrupt: give the run the disposition it has when started from a terminal.
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _wait_for_bake(proc):
    """Block until the run reports its first baked frame: inside the bake, whatever the speed."""
    seen = []
    for line in proc.stderr:
        seen.append(line)
        if line.startswith("fibrilfit: bake frame "):
            return
    raise AssertionError(f"the run ended before its bake began: {proc.wait()} {seen}")


# 100 layers, 1000 frames, no settling: the bake lasts seconds, so the signal lands inside it
LONG_RUN = ["--layers", "100", "--frames", "1000", "--no-settle"]


def test_progress_lines_count_the_frames(tmp_path):
    out = run_cli("run", "--layers", "2", "--frames", "60", "--no-settle", "--progress")
    assert out.returncode == 0, out.stderr
    lines = out.stderr.splitlines()
    assert lines[1:] == ["fibrilfit: bake frame 25/60", "fibrilfit: bake frame 50/60"]
    assert lines[0].startswith("fibrilfit: bake frame ")


def test_ctrl_c_exits_130_and_writes_nothing(tmp_path):
    proc = _start(LONG_RUN, tmp_path)
    _wait_for_bake(proc)
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


def test_killed_run_leaves_no_file_that_looks_complete(tmp_path):
    proc = _start(LONG_RUN, tmp_path)
    _wait_for_bake(proc)
    proc.kill()
    proc.wait(timeout=60)
    assert not (tmp_path / "r.json").exists() and not (tmp_path / "m.blend").exists()


@pytest.mark.parametrize("cli_args,api_kwargs,name", BAD_INPUTS, ids=lambda v: str(v)[:40])
def test_operators_refuse_bad_input_and_keep_the_scene(cli_args, api_kwargs, name, registered,
                                                       scene, user_objects):
    """The panel's limits clamp what a user types; a script or an old file can still store any
    number as a raw ID property. Either way no bad value reaches the model."""
    settings = registered
    settings.layers, settings.frames = 2, 5
    assert bpy.ops.fibrilfit.run_all() == {"FINISHED"}
    before, before_user = sorted(ob.name for ob in scene.objects), snapshot_user(user_objects)
    (key, value), = api_kwargs.items()  # one bad value per input
    rna = settings.bl_rna.properties[key]
    if isinstance(value, str) or (rna.type == "INT" and value != int(value)):
        # not a number of the field's type (layers "twenty", twist "2turns" and "-0.961",
        # linker 2.5): refused on entry, the property keeps the value it had
        kept = getattr(settings, key)
        with pytest.raises(TypeError):
            setattr(settings, key, value)
        assert getattr(settings, key) == kept
    else:
        # stored raw, of the property's own type (RNA ignores a raw value of another type)
        settings[key] = tuple(map(float, value)) if rna.type == "FLOAT" and rna.is_array else (
            float(value) if rna.type == "FLOAT" else int(value))
        for op in ("run_all", "build_slab", "replicate_layers"):
            # the panel names the field by its label (issue #45: "Layers: ...", not "layers: ...")
            with pytest.raises(RuntimeError, match=re.escape(f"{field_label(name)}: ")) as err:
                getattr(bpy.ops.fibrilfit, op)()
            assert "\n" not in str(err.value).strip()
    assert sorted(ob.name for ob in scene.objects) == before
    assert snapshot_user(user_objects) == before_user


def _datablocks():
    return {kind: {d.name for d in getattr(bpy.data, kind)}
            for kind in ("objects", "meshes", "materials", "collections", "cameras", "lights",
                         "worlds", "images")}


def test_every_operator_spares_the_users_data_and_clear_removes_exactly_the_model(
        registered, scene, user_objects, tmp_path):
    settings = registered
    settings.layers, settings.linker, settings.frames, settings.seed = 6, 2, 30, 1
    scene.collection.objects.link(bpy.data.objects.new("Empty", None))  # a user object, no data
    before, before_user = _datablocks(), snapshot_user(user_objects)
    ops = ["build_slab", "build_anchor", "build_linker", "build_globule", "replicate_layers",
           "bake", "check_intersections", "join_globules", "run_all", "run_all"]
    for op in ops:
        assert getattr(bpy.ops.fibrilfit, op)() == {"FINISHED"}, op
        assert snapshot_user(user_objects) == before_user, op
    assert bpy.ops.fibrilfit.export_pdb(filepath=str(tmp_path / "m.pdb")) == {"FINISHED"}
    assert snapshot_user(user_objects) == before_user
    globules = [ob for ob in scene.objects if ob.get("fibrilfit") == "globule"]
    assert len(globules) == 6  # run_all twice: exactly one model
    assert bpy.ops.fibrilfit.clear() == {"FINISHED"}
    assert _datablocks() == before  # the model's meshes, materials and rigid-body collections too
    assert snapshot_user(user_objects) == before_user


def test_every_scene_changing_operator_declares_undo(registered):
    """Each operator that changes the scene has its undo step: Blender's UNDO option, or, for one
    run from the file browser (which pushes an UNDO step whatever the operator returned, so a
    failed import added one: issue #45), its own step pushed on success (common.after_file)."""
    import inspect
    from fibrilfit.ui.operators import CLASSES
    own_step = []
    for cls in CLASSES:
        # these write a file, or open one in the browser, and change nothing in the scene
        if cls.bl_idname.split(".")[1] in ("render", "export_pdb", "save_case", "open_report"):
            continue
        if "UNDO" not in getattr(cls, "bl_options", set()):
            source = "".join(inspect.getsource(c) for c in cls.__mro__
                             if c.__module__.startswith("fibrilfit"))
            assert "common.after_file(" in source, cls.bl_idname
            own_step.append(cls.bl_idname)
    assert sorted(own_step) == ["fibrilfit.import_domain", "fibrilfit.import_fibril",
                                "fibrilfit.import_full_length",
                                "fibrilfit.load_case", "fibrilfit.load_outline"]


def _as_the_ui(module, op, **kw):
    """Call an operator as a button does: in a window, with its undo step pushed."""
    window = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=window):
        return getattr(getattr(bpy.ops, module), op)("EXEC_DEFAULT", True, **kw)


def _state():
    """Everything undo must restore, read afresh (undo reloads the data; old handles go stale)."""
    scene = bpy.context.scene
    scene.frame_set(scene.frame_current)
    ours = sorted((ob.name, ob.get("fibrilfit"), tuple(round(v, 4) for v in ob.matrix_world.translation))
                  for ob in scene.objects if ob.get("fibrilfit"))
    users = sorted((ob.name, tuple(ob.location), ob.data.name if ob.data else None,
                    tuple(c.name for c in ob.users_collection))
                   for ob in scene.objects if not ob.get("fibrilfit"))
    rbw = scene.rigidbody_world
    baked = bool(rbw and rbw.point_cache and rbw.point_cache.is_baked)
    return {"ours": ours, "users": users, "baked": baked, "frame": scene.frame_current,
            "verdict": scene.fibrilfit.verdict}


def test_undo_and_redo_of_run_all_clear_and_a_step(registered, user_objects):
    """Undo works in the bpy module once a window is in the context: each operator's own undo
    step takes the scene back exactly, the user's objects included, and redo brings it back."""
    settings = registered
    settings.layers, settings.linker, settings.frames, settings.seed = 4, 3, 40, 2
    assert _as_the_ui("ed", "undo_push", message="start") == {"FINISHED"}
    empty = _state()
    assert empty["ours"] == [] and len(empty["users"]) == 4

    assert _as_the_ui("fibrilfit", "run_all") == {"FINISHED"}
    done = _state()
    globules = [o for o in done["ours"] if o[1] == "globule"]
    assert len(globules) == 4 and done["baked"] and done["verdict"] in ("successful", "intersection")
    assert done["users"] == empty["users"]

    assert _as_the_ui("ed", "undo") == {"FINISHED"}
    assert _state() == empty
    assert _as_the_ui("ed", "redo") == {"FINISHED"}
    assert _state() == done  # the baked positions at the last frame too

    assert _as_the_ui("fibrilfit", "clear") == {"FINISHED"}
    assert _state()["ours"] == [] and _state()["users"] == empty["users"]
    assert _as_the_ui("ed", "undo") == {"FINISHED"}
    assert _state() == done

    assert _as_the_ui("fibrilfit", "build_slab") == {"FINISHED"}  # a step replaces the model
    assert {o[1] for o in _state()["ours"]} == {"slab"}
    assert _as_the_ui("ed", "undo") == {"FINISHED"}
    assert _state() == done
