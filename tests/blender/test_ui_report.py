"""The sidebar's Report… (ui/operators/report.py): the modal operator, driven as Blender's event
loop would, runs the restarts and the walk on worker processes with the stage in the status
bar, then writes the same report as `report` for the same seeds and settings and shows its
numbers; Esc stops the workers and writes nothing; and the panel does not claim a change the
user never made.

The case: test_report.py's FAST (12 Å globules on 3 layers, linker 3, inflate without regrowth,
2 restarts, lengths up to 4), which fits at every linker (bpy 4.2, 5.0, 5.2)."""
import json
import os
import time
import types

import bpy
import jsonschema
import pytest

from fibrilfit import cli
from fibrilfit.builders import find_model
from fibrilfit.model import params as P
from fibrilfit.search import report
from fibrilfit.ui import minimal_summary, panels, properties, report_summary
from fibrilfit.ui.operators import background, report as report_op
from helpers import ROOT
from ui_fakes import _Progress, _Workspace, detached, event
from test_ui_cases import Labels  # the panel's labels, recorded

FAST = dict(layers=3, linker=3, globule_diameter=12, protocol="inflate", grow_frames=20,
            hold_frames=20, regrow_cycles=0)
SLOW = dict(protocol="inflate", layers=6, seed=0)  # runs long enough to be cancelled mid-run


@pytest.fixture
def ui(registered):
    yield registered
    background.RUNNING.clear()


def _operator(directory, restarts, max_linker, fraction_plot=""):
    op = detached(report_op.FIBRILFIT_OT_report)
    op.directory, op.restarts, op.max_linker = str(directory), restarts, max_linker
    op.fraction_plot = fraction_plot
    return op


def _ticks(op, context, until: float = 300.0):
    """TIMER events until the operator ends (its runs are on worker processes)."""
    end = time.monotonic() + until
    while (state := op.modal(context, event("TIMER"))) in ({"RUNNING_MODAL"}, {"PASS_THROUGH"}):
        assert time.monotonic() < end, "the report did not end"
        time.sleep(0.05)
    return state


def _beside(folder) -> set:
    """What a report being made leaves beside its folder (BackgroundReport.folder_beside)."""
    return {n for n in os.listdir(folder.parent) if n.startswith(f".{folder.name}.fibrilfit-")}


def test_the_panels_report_is_the_commands_and_blender_stays_live(ui, tmp_path, monkeypatch):
    opened = []
    monkeypatch.setattr(report_op, "open_page", lambda path: opened.append(path) or True)
    properties.write_params(ui, P.make_params(**FAST, seed=0))
    out = tmp_path / "page"
    op = _operator(out, 2, 4)
    ws = _Workspace()  # the status bar's
    context = types.SimpleNamespace(scene=bpy.context.scene, workspace=ws, screen=None,
                                    window_manager=bpy.context.window_manager)
    assert not bpy.ops.fibrilfit.open_report.poll()  # no report yet
    op.start(context)
    assert not bpy.ops.fibrilfit.report.poll()  # one report at a time
    assert op.modal(context, event("MIDDLEMOUSE")) == {"PASS_THROUGH"}  # Blender stays live
    assert not out.exists() and len(_beside(out)) == 1  # made beside, moved in at the end
    assert _ticks(op, context) == {"FINISHED"}
    assert bpy.ops.fibrilfit.report.poll()
    assert ws.status[-1] is None  # the status bar is the user's again
    bars = []
    for draw in ws.status[:-1]:
        if callable(draw):
            bar = _Progress()
            draw(types.SimpleNamespace(layout=bar), context)
            bars += [b["text"] for b in bar.drawn]
    assert bars and all(b.startswith("FibrilFit: report: ") and b.endswith("(Esc to cancel)")
                        for b in bars)
    assert any("stage 1 of 6" in b for b in bars) and any("stage 2 of 6" in b for b in bars)
    assert _beside(out) == set() and (out / "report.html").is_file()

    # the panel: the report's numbers, Open report, the scene's best layout checked
    s = ui
    summary = json.loads(s.report_summary)
    doc = json.loads((out / "report.json").read_text())
    assert summary == report_summary.summary_of(doc, str(out))
    assert bpy.ops.fibrilfit.open_report() == {"FINISHED"} and opened == [out / "report.html"]
    assert (s.report_dir, s.report_restarts, s.report_max_linker) == (str(out), 2, 4)
    best = json.loads((out / "best_layout.json").read_text())
    assert best["seed"] == doc["p_fit"]["best_seed"]
    assert (s.verdict, s.accommodated) == (best["verdict"], best["accommodated"])
    assert op.reports[-1] == ({"INFO"}, f"{doc['answer']}: wrote {out / 'report.html'}")
    # the user changed nothing: the panel is the model in the scene, the best layout, seed 1 of
    # seeds 0-1 (bpy 5.0.1, 2026-11-26), so it does not say "Physics changed: Bake again"
    model = find_model(bpy.context.scene)
    assert best["seed"] == 1 and s.seed == 1 and model.params.seed == 1
    assert properties.changed_fields(s, model.params) == []
    log = []
    panels.FIBRILFIT_PT_main.draw(types.SimpleNamespace(layout=Labels(log)), bpy.context)
    assert not any("Physics changed" in t for t in log) and "Report: fits" in log
    schema = json.loads((ROOT / "docs" / "reference" / "report.schema.json").read_text())
    jsonschema.Draft202012Validator(schema).validate(doc)  # the published schema
    assert doc["sources"]["linker"] == "sidebar" and doc["p_fit"]["seeds"] == [0, 1]
    assert (out / "report.html").read_text().count('src="data:image/png;base64,') == 3  # the render, the envelope, the bracket
    assert doc["command"][1:4] == ["report", "--case", str(out / "case.toml")]

    # the command line, for the same case and seeds, gives the same numbers
    line = tmp_path / "cli"
    assert cli.main(["report", "--case", str(out / "case.toml"), "--restarts", "2",
                     "--max-linker", "4", "--out", str(line), "--quiet", "--render-engine",
                     "workbench", "--render-size", "320x180"]) == 0
    theirs = json.loads((line / "report.json").read_text())
    assert summary == report_summary.summary_of(theirs, str(out))
    for key in ("answer", "model", "p_fit", "minimal_linker", "bound", "bracket", "margin",
                "best_layout"):
        assert doc[key] == theirs[key], key
    assert doc["p_fit"]["runs"] == 2 and doc["answer"] == "fits"


def test_esc_stops_the_workers_and_writes_nothing(ui, tmp_path):
    properties.write_params(ui, P.make_params(**SLOW, globule_diameter=30.0))
    out = tmp_path / "page"
    op = _operator(out, 2, 8)
    op.start(bpy.context)
    job = op._job
    end = time.monotonic() + 120
    while not (job.executor.workers and all(w.ready for w in job.executor.workers)
               and job.progress.submitted):
        assert op.modal(bpy.context, event("TIMER")) == {"PASS_THROUGH"}
        assert time.monotonic() < end, "no run started"
        time.sleep(0.05)
    procs = [w.proc for w in job.executor.workers]
    assert op.modal(bpy.context, event("ESC")) == {"RUNNING_MODAL"}  # stopping
    assert _ticks(op, bpy.context, 60) == {"CANCELLED"}
    assert all(p.poll() is not None for p in procs)  # every worker gone
    assert not out.exists() and _beside(out) == set()  # nothing written, nothing beside
    # a run was under way when Esc came (an inflate run of 6 layers takes tens of seconds)
    assert job.progress.done < job.progress.submitted and job.progress.stage == "restarts"
    assert op.reports[-1] == ({"WARNING"}, f"Report cancelled after "
                                           f"{minimal_summary.runs(job.progress.done)}; "
                                           f"nothing written")
    assert ui.report_summary == "" and bpy.ops.fibrilfit.report.poll()  # it can run again


def test_stage_progress_reads_the_stages():
    p = types.SimpleNamespace(stage="minimal linker", done=1, submitted=4)
    text, fraction = report_op.FIBRILFIT_OT_report.progress_text(p)
    assert text == "minimal linker (stage 2 of 6), 1 of 4 runs done"
    assert fraction == pytest.approx((1 + 1 / 4) / 6)
    assert report.STAGES[1] == "minimal linker"


def test_the_panels_report_refuses_a_fraction_plot_it_cannot_draw(ui, tmp_path):
    """Report…'s Fraction plot is checked before anything runs or is made: two fractions that
    decorate the same count of the panel's 3 subunits, or a pattern that fixes its fraction, are
    one line each (the command line's), with no folder beside the one picked."""
    from fibrilfit.plans import PlanError
    properties.write_params(ui, P.make_params(**FAST, seed=0))
    out = tmp_path / "page"
    for plot, values, needle in (
            ("0.3,0.4", {}, "--fraction-plot: 0.3 and 0.4 both decorate 1 of the 3 subunits"),
            ("0.5", {"pattern": "layers", "pattern_layers": "A."},
             "--fraction-plot: needs pattern random")):
        properties.write_params(ui, P.make_params(**FAST, seed=0, **values))
        op = _operator(out, 2, 4, fraction_plot=plot)
        with pytest.raises(PlanError, match=needle):
            op.start(bpy.context)
        assert not out.exists() and _beside(out) == set()
        assert background.RUNNING.get(op.bl_idname) is None
