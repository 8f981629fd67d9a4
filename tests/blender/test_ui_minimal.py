"""The sidebar's Minimal linker… (ui/operators/minimal.py): the modal operator, driven as
Blender's event loop would, gives the `minimal-linker` command's map for the same options and
seeds, shows it in the panel, and Esc stops its workers with nothing kept.

The case: the tutorial protocol, 3 layers, 60 frames, seeds 4-5, diameters 8 and 20 Å, lengths
up to 4 (on bpy 5.0.1, 2026-11-26: 8 Å fits at 1; 20 Å misses at 1 with both seeds and fits at 2;
the command took 12 s on 2 workers)."""
import json
import os
import tempfile
import time
import types

import bpy
import pytest

from fibrilfit import cli
from fibrilfit.model import params as P
from fibrilfit.ui import minimal_summary, panels, properties
from fibrilfit.ui.operators import background, minimal
from ui_fakes import _Progress, _text_px, _Workspace, FIELD_PX, detached, event

TINY = dict(protocol="tutorial", layers=3, frames=60, seed=4)
CLI_TINY = ["--protocol", "tutorial", "--layers", "3", "--frames", "60", "--seed", "4"]
SLOW = dict(protocol="inflate", layers=6, seed=0)  # runs long enough to be cancelled mid-run


@pytest.fixture
def ui(registered):
    yield registered
    background.RUNNING.clear()


def _operator(restarts, max_linker, diameters=""):
    op = detached(minimal.FIBRILFIT_OT_minimal_linker)
    op.restarts, op.max_linker, op.diameters = restarts, max_linker, diameters
    return op


def _ticks(op, until: float = 300.0, context=None):
    """TIMER events until the operator ends (its walk's runs are on worker processes)."""
    end = time.monotonic() + until
    context = context or bpy.context
    while (state := op.modal(context, event("TIMER"))) in ({"RUNNING_MODAL"}, {"PASS_THROUGH"}):
        assert time.monotonic() < end, "the walk did not end"
        time.sleep(0.05)
    return state


def _walk_folders() -> set:
    return {n for n in os.listdir(tempfile.gettempdir()) if n.startswith("fibrilfit-minimal-")}


def test_the_panels_walk_gives_the_commands_map(ui, tmp_path, capsys):
    properties.write_params(ui, P.make_params(**TINY, globule_diameter=30.0))
    op = _operator(2, 4, "8,20")
    ws = _Workspace()  # the status bar's
    context = types.SimpleNamespace(scene=bpy.context.scene, workspace=ws, screen=None,
                                    window_manager=bpy.context.window_manager)
    op.start(context)
    assert op.modal(context, event("MIDDLEMOUSE")) == {"PASS_THROUGH"}  # Blender stays live
    assert _ticks(op, context=context) == {"FINISHED"}
    bars = []
    for draw in ws.status[:-1]:
        if callable(draw):
            bar = _Progress()
            draw(types.SimpleNamespace(layout=bar), context)
            bars += bar.drawn
    assert ws.status[-1] is None  # the status bar is the user's again
    assert bars and bars[-1]["text"].startswith("FibrilFit: minimal linker: 20 Å at linker ")
    assert bars[-1]["text"].endswith(" runs done (Esc to cancel)")
    mine = op._job.result
    summary = json.loads(ui.minimal_map)
    assert summary["state"] == "done" and op.reports[-1] == ({"INFO"},
                                                            "Minimal linker: 8 Å: 1, 20 Å: 2")

    out = tmp_path / "cli"
    capsys.readouterr()
    assert cli.main(["minimal-linker", *CLI_TINY, "--globule-diameter", "8,20", "--restarts",
                     "2", "--max-linker", "4", "--out", str(out), "--no-plot", "--quiet"]) == 0
    printed = capsys.readouterr().out
    rows = json.loads((out / "minimal_linker.json").read_text())["rows"]
    for r in (*rows, *mine["rows"]):
        r.pop("kind")  # the options named: the panel gives every value, the command a few
    assert mine["rows"] == rows
    assert [r["minimal_linker"] for r in rows] == [1, 2]
    assert rows[1]["tried"]["1"] == {"accommodated": 0, "restarts": 2}
    assert mine["table"] in printed  # the same table, bracket lines and all

    # the panel's lines and table (issue #45), each within the default sidebar's width
    texts = [t for t, _ in minimal_summary.summary_lines(summary)]
    table = minimal_summary.table_rows(summary)
    assert [r[:2] for r in table[1:]] == [("8", "1"), ("20", "2")]
    assert all(_text_px(t) <= FIELD_PX for t in texts), texts
    assert all(_text_px(c) <= FIELD_PX / 4 for r in table for c in r), table
    drawn = _Box()
    panels.draw_map(drawn, ui, "minimal_map", minimal_summary)
    assert drawn.labels[:len(texts)] == texts
    assert drawn.labels[len(texts):len(texts) + 4 * len(table)] == [c for r in table for c in r]


def test_esc_stops_the_workers_and_keeps_nothing(ui):
    properties.write_params(ui, P.make_params(**SLOW, globule_diameter=30.0))
    before = _walk_folders()
    op = _operator(2, 8)
    op.start(bpy.context)
    end = time.monotonic() + 120
    while not (op._job.executor.workers and all(w.ready for w in op._job.executor.workers)
               and op._job.progress.submitted):
        assert op.modal(bpy.context, event("TIMER")) == {"PASS_THROUGH"}
        assert time.monotonic() < end, "no run started"
        time.sleep(0.05)
    procs = [w.proc for w in op._job.executor.workers]
    assert not bpy.ops.fibrilfit.minimal_linker.poll()  # one walk at a time
    assert op.modal(bpy.context, event("ESC")) == {"RUNNING_MODAL"}  # stopping
    assert _ticks(op, 60) == {"CANCELLED"}
    assert all(p.poll() is not None for p in procs)  # every worker gone
    assert _walk_folders() == before  # its runs' folder too
    # a run was under way when Esc came (an inflate run of 6 layers takes tens of seconds: none
    # had ended here, 2026-11-26)
    done = op._job.progress.done
    assert done < op._job.progress.submitted
    assert json.loads(ui.minimal_map) == {"state": "cancelled", "runs": done}
    assert op.reports[-1] == ({"WARNING"}, f"Minimal linker cancelled after "
                                           f"{minimal_summary.runs(done)}; nothing kept")
    assert ui.minimal_map and bpy.ops.fibrilfit.minimal_linker.poll()  # it can run again


def test_from_a_script_it_waits_for_the_walk(ui):
    properties.write_params(ui, P.make_params(**TINY, globule_diameter=8.0))
    assert bpy.ops.fibrilfit.minimal_linker.poll()
    assert bpy.ops.fibrilfit.minimal_linker(restarts=1, max_linker=2) == {"FINISHED"}
    summary = json.loads(ui.minimal_map)
    assert [(r["globule_diameter"], r["minimal_linker"]) for r in summary["rows"]] == [(8.0, 1)]
    with pytest.raises(RuntimeError, match="[Dd]iameters|Globule diameter"):
        bpy.ops.fibrilfit.minimal_linker(restarts=1, max_linker=2, diameters="big")


class _Box:
    def __init__(self):
        self.labels = []

    def label(self, text, icon="NONE"):
        self.labels.append(text)

    def row(self, **kw):  # a table's row: its cells are labels of the box, in order
        return self
