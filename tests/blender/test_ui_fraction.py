"""The sidebar's Largest fraction… (ui/operators/minimal.py): the modal operator, driven as
Blender's event loop would, gives the `largest-fraction` command's map for the same options and
seeds, shows it in the panel's box with its bracket (tied to the values it was made for: greyed
once they change, gone with Clear), and Esc stops its workers with nothing kept.

The case: the tutorial protocol, 3 layers, 60 frames, seeds 4-5, a 20 Å domain at linker 1 (on
bpy 5.0.1, 2026-11-27: 2 of the 3 subunits fit, 1/1; all 3 miss with both seeds; the command took
19 s on 2 workers)."""
import json
import time
import types

import bpy
import pytest

from fibrilfit import cli
from fibrilfit.model import params as P
from fibrilfit.ui import fraction_summary, minimal_summary, properties
from fibrilfit.ui.operators import background, minimal
from ui_fakes import _Progress, _Workspace, FakeLayout, detached, event

TINY = dict(protocol="tutorial", layers=3, frames=60, seed=4, globule_diameter=20.0, linker=1)
CLI_TINY = ["--protocol", "tutorial", "--layers", "3", "--frames", "60", "--seed", "4",
            "--globule-diameter", "20", "--linker", "1"]
SLOW = dict(protocol="inflate", layers=6, seed=0, globule_diameter=30.0)


@pytest.fixture
def ui(registered):
    yield registered
    background.RUNNING.clear()


def _operator(restarts, diameters="", linkers=""):
    op = detached(minimal.FIBRILFIT_OT_largest_fraction)
    op.restarts, op.max_linker = restarts, 30
    op.diameters, op.linkers = diameters, linkers
    return op


def _ticks(op, until: float = 300.0, context=None):
    end = time.monotonic() + until
    context = context or bpy.context
    while (state := op.modal(context, event("TIMER"))) in ({"RUNNING_MODAL"}, {"PASS_THROUGH"}):
        assert time.monotonic() < end, "the walk did not end"
        time.sleep(0.05)
    return state


def _box_labels(context) -> list:
    from fibrilfit.ui import panels
    log = []
    panels.draw_run(FakeLayout(log), context)
    return [text for kind, text in log if kind == "label"]


def test_the_panels_largest_fraction_is_the_commands_map(ui, tmp_path, capsys):
    properties.write_params(ui, P.make_params(**TINY, occupancy=0.5))  # searched: left out
    op = _operator(2)
    ws = _Workspace()
    context = types.SimpleNamespace(scene=bpy.context.scene, workspace=ws, screen=None,
                                    window_manager=bpy.context.window_manager)
    op.start(context)
    assert not bpy.ops.fibrilfit.largest_fraction.poll()  # one walk at a time
    assert bpy.ops.fibrilfit.minimal_linker.poll()  # the other map is its own
    assert op.modal(context, event("MIDDLEMOUSE")) == {"PASS_THROUGH"}  # Blender stays live
    assert _ticks(op, context=context) == {"FINISHED"}
    bars = []
    for draw in ws.status[:-1]:
        if callable(draw):
            bar = _Progress()
            draw(types.SimpleNamespace(layout=bar), context)
            bars += bar.drawn
    assert ws.status[-1] is None
    assert bars and bars[-1]["text"].startswith("FibrilFit: largest fraction: 20 Å at linker 1")
    summary = json.loads(ui.fraction_map)
    assert summary["state"] == "done"
    assert op.reports[-1] == ({"INFO"}, "Largest fraction: 20 Å at 1: 2/3")
    # the values it answers for: the panel's, but the fraction it searched and the seed
    assert "occupancy" not in summary["model"] and summary["model"]["linker"] == 1

    out = tmp_path / "cli"
    capsys.readouterr()
    assert cli.main(["largest-fraction", *CLI_TINY, "--restarts", "2", "--out", str(out),
                     "--no-plot", "--quiet"]) == 0
    printed = capsys.readouterr().out
    rows = json.loads((out / "largest_fraction.json").read_text())["rows"]
    mine = op._job.result["rows"]
    for r in (*rows, *mine):
        r.pop("kind")  # the options named: the panel gives every value, the command a few
    assert mine == rows
    assert op._job.result["table"] in printed
    (row,) = rows
    assert (row["largest_count"], row["subunits"], row["count_above"]) == (2, 3, 3)

    # the panel's box: the answer with its bracket, a clause a line, tied to its values
    labels = _box_labels(bpy.context)
    start = labels.index("Largest fraction (tutorial)")
    box = labels[start:start + 8]
    assert box[2:] == ["20 Å, linker 1:", "Fits: 2 of 3 (66.7 %)", "P(fit) 1/1 there",
                       *[c[:1].upper() + c[1:] for c in row["bracket"].split(" / ")]]
    assert box[5].startswith("Impossible above") and box[6].startswith("Fits at")
    assert box[7].startswith("Open between")
    ui.layers = 4  # another model: the box says it belongs to earlier values
    labels = _box_labels(bpy.context)
    assert labels[labels.index("Largest fraction (tutorial)") - 1].startswith(
        "Earlier values: Layers")
    ui.layers = 3
    assert bpy.ops.fibrilfit.run_all() == {"FINISHED"}
    assert bpy.ops.fibrilfit.clear() == {"FINISHED"}  # Clear takes it with the model
    assert ui.fraction_map == "" and "Largest fraction (tutorial)" not in _box_labels(bpy.context)


def test_esc_stops_the_workers_and_keeps_nothing(ui):
    properties.write_params(ui, P.make_params(**SLOW))
    op = _operator(2)
    op.start(bpy.context)
    end = time.monotonic() + 120
    while not (op._job.executor.workers and all(w.ready for w in op._job.executor.workers)
               and op._job.progress.submitted):
        assert op.modal(bpy.context, event("TIMER")) == {"PASS_THROUGH"}
        assert time.monotonic() < end, "no run started"
        time.sleep(0.05)
    procs = [w.proc for w in op._job.executor.workers]
    assert op.modal(bpy.context, event("ESC")) == {"RUNNING_MODAL"}
    assert _ticks(op, 60) == {"CANCELLED"}
    assert all(p.poll() is not None for p in procs)
    done = op._job.progress.done
    assert json.loads(ui.fraction_map) == {"state": "cancelled", "runs": done}
    assert op.reports[-1] == ({"WARNING"}, f"Largest fraction cancelled after "
                                           f"{minimal_summary.runs(done)}; nothing kept")
    assert fraction_summary.summary_lines(json.loads(ui.fraction_map))[0][0] == \
        "Largest fraction: cancelled"


def test_from_a_script_it_waits_and_refuses_a_fixed_pattern_in_one_line(ui):
    properties.write_params(ui, P.make_params(**{**TINY, "layers": 2}))
    assert bpy.ops.fibrilfit.largest_fraction(restarts=1) == {"FINISHED"}
    (row,) = json.loads(ui.fraction_map)["rows"]
    assert row["subunits"] == 2 and row["bracket"]
    ui.pattern = "periodic"
    with pytest.raises(RuntimeError, match="Pattern: largest-fraction searches the random"):
        bpy.ops.fibrilfit.largest_fraction(restarts=1)
