"""Runs inside the GUI Blender of tests/realblender/test_domains_gui.py (`blender --python
domains_probe.py`, in a window under Xvfb, the extension installed from its zip): it drives the
sidebar's operators as their buttons do, the file browsers' answers given as their paths, from
$FIBRILFIT_DOMAINS/steps.json: {"values": {panel values}, "cases": [{"name", "imports":
[[operator, {its properties}], ...]}]}. For each case in turn: the imports, then Run all in the
window (modal, as its button runs it); when the panel shows the verdict, what it shows and the
parameters the panel ran with go into $FIBRILFIT_DOMAINS/results.json, and after the last case
Blender quits. An error is written to results.json as {"error": ...}.
"""
import json
import os
import pathlib
import time
import traceback

import bpy

HERE = pathlib.Path(os.environ["FIBRILFIT_DOMAINS"])
ADDON = "bl_ext.user_default.fibrilfit"
PLAN = json.loads((HERE / "steps.json").read_text())
_run = {"case": 0, "waiting": False, "results": [], "t0": time.monotonic()}


def _override():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "WINDOW")
    return bpy.context.temp_override(window=window, area=area, region=region)


def _write(data) -> None:
    tmp = HERE / "results.json.tmp"
    tmp.write_text(json.dumps(data))
    tmp.replace(HERE / "results.json")


def _start_case(case) -> None:
    s = bpy.context.scene.fibrilfit
    with _override():
        for name, value in PLAN["values"].items():
            setattr(s, name, value)
        for op, props in case["imports"]:
            group, name = op.split(".")
            assert getattr(getattr(bpy.ops, group), name)("EXEC_DEFAULT", **props) == {"FINISHED"}
        s.verdict = ""
        assert bpy.ops.fibrilfit.run_all("INVOKE_DEFAULT") in ({"RUNNING_MODAL"}, {"FINISHED"})


def _record(case) -> dict:
    import importlib
    properties = importlib.import_module(ADDON + ".ui.properties")
    s = bpy.context.scene.fibrilfit
    return {"name": case["name"], "domains": [e.name for e in s.domains],
            "linkers": [e.linker for e in s.domains],
            "params": json.loads(json.dumps(properties.read_params(s).to_dict())),
            "verdict": s.verdict, "clash_count": s.clash_count,
            "accommodated": s.accommodated, "max_bond_stretch": s.max_bond_stretch,
            "seconds": round(time.monotonic() - _run["t0"], 1)}


def _tick():
    try:
        cases = PLAN["cases"]
        case = cases[_run["case"]]
        if not _run["waiting"]:
            _start_case(case)
            _run["waiting"] = True
            return 0.5
        if not bpy.context.scene.fibrilfit.verdict:
            return 0.5
        _run["results"].append(_record(case))
        _run["case"] += 1
        _run["t0"] = time.monotonic()
        _run["waiting"] = False
        if _run["case"] < len(cases):
            return 0.5
        _write({"cases": _run["results"], "blender": bpy.app.version_string})
    except Exception:  # the test reads it
        _write({"error": traceback.format_exc(), "cases": _run["results"]})
    bpy.ops.wm.quit_blender()
    return None


bpy.app.timers.register(_tick, first_interval=2.0)
