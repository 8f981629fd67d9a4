"""The sidebar as a biologist walks it (issue #45): two domains imported, Run all, Step by step ›
Bake, Report…, Clear; results that belong to their run; the words the panel speaks.

New tests of issue #45 live here (tests/blender/test_ui.py keeps the older ones)."""
import json
import types

import bpy
import pytest
from helpers import ROOT

from fibrilfit.builders import find_model, model_stage
from fibrilfit.model import params as P
from fibrilfit.ui import properties, structure_trace

DATA = ROOT / "tests" / "data"
SMALL = dict(layers=6, frames=10, seed=5)


@pytest.fixture
def ui(registered):
    properties.write_params(registered, P.make_params(**SMALL))
    return registered


def run(op: str, *args, **kw):
    return getattr(bpy.ops.fibrilfit, op)(*args, **kw)


def import_two_domains():
    assert run("import_domain", filepath=str(DATA / "1ubq.pdb.gz")) == {"FINISHED"}
    assert run("import_domain", filepath=str(DATA / "1gfl.pdb.gz"), chain="A") == {"FINISHED"}


def main_labels(context=None):
    from test_ui import draw_all
    drawn = draw_all(context or bpy.context)
    return [t for kind, t in drawn["FIBRILFIT_PT_main"] if kind == "label"]


# ---- 1. two domains bake step by step ---------------------------------------------------------

def test_two_domains_run_all_then_bake_step_by_step(ui, scene):
    """Issue #45 item 1: with two domains in the list, the panel's domain_linker (a list) and the
    model's (a tuple) are the same value: no "changed since the build", and Bake runs."""
    import_two_domains()
    assert len(ui.domains) == 2
    assert run("run_all") == {"FINISHED"}
    assert not any("Changed since the build" in t for t in main_labels())
    assert properties.changed_fields(ui, find_model(scene).params) == []
    assert run("bake") == {"FINISHED"}
    assert model_stage(scene) == "baked"
    assert run("check_intersections") == {"FINISHED"} and ui.verdict


# ---- 2 and 3. a report from the panel is a record, and belongs to its values -------------------

# test_ui_report.py's FAST (inflate without regrowth, 2 restarts, lengths up to 4) on a model
# measured from 6CU7 and ubiquitin: small globule, 3 layers
FAST = dict(layers=3, linker=3, protocol="inflate", grow_frames=20, hold_frames=20,
            regrow_cycles=0)


def _report(out, context):
    from test_ui_report import _operator, _ticks
    op = _operator(out, 2, 4)
    op.start(context)
    assert _ticks(op, context) == {"FINISHED"}
    return op


@pytest.fixture
def idle(ui):
    from fibrilfit.ui.operators import background
    yield ui
    background.RUNNING.clear()


def _context(scene):
    from test_ui import _Workspace
    return types.SimpleNamespace(scene=scene, workspace=_Workspace(), screen=None,
                                 window_manager=bpy.context.window_manager)


def test_a_panel_report_names_its_structures_sources_and_a_runnable_command(idle, scene,
                                                                          tmp_path):
    """Issue #45 items 2 and 3: the report from the panel names 6cu7 and ubiquitin with their
    sha256, says which values the files gave, which the sidebar and which the defaults, and
    its command (pip's `fibrilfit report --case ...` here, bpy as a module) makes the same
    report; its box is marked once the panel's values change and Run all rebuilds, and Clear
    takes it away."""
    import hashlib
    from fibrilfit import cli
    ui = idle
    assert run("import_fibril", filepath=str(DATA / "6cu7.pdb.gz")) == {"FINISHED"}
    assert run("import_domain", filepath=str(DATA / "1ubq.pdb.gz")) == {"FINISHED"}
    for k, v in FAST.items():
        setattr(ui, k, v)
    ui.globule_diameter = 12.0  # by hand: a small globule, fast to bake
    out = tmp_path / "page"
    _report(out, _context(scene))
    doc = json.loads((out / "report.json").read_text())
    block = doc["structure"]
    assert block["fibril"]["file"] == "6cu7.pdb.gz" and block["domain"]["file"] == "1ubq.pdb.gz"
    for key, name in (("fibril", "6cu7.pdb.gz"), ("domain", "1ubq.pdb.gz")):
        assert block[key]["sha256"] == hashlib.sha256((DATA / name).read_bytes()).hexdigest()
    src = doc["sources"]
    for name in ("rise", "twist", "core_outline", "anchor", "protofilaments"):
        assert src[name].startswith("6cu7.pdb.gz: measured"), (name, src[name])
    assert src["layers"] == src["linker"] == src["globule_diameter"] == "sidebar"
    assert src["frames"] == "sidebar"  # SMALL's 10
    assert src["slab"] == src["stretch_tolerance"] == "default"
    # the command: pip's here (bpy as a module); the case beside the page names the files
    cmd = doc["command"]
    assert cmd[:4] == ["fibrilfit", "report", "--case", str(out / "case.toml")]
    assert ["--restarts", "2"] == cmd[cmd.index("--restarts"):cmd.index("--restarts") + 2]
    case = (out / "case.toml").read_text()
    assert str(DATA / "6cu7.pdb.gz") in case and str(DATA / "1ubq.pdb.gz") in case
    page = (out / "report.html").read_text()
    assert "fibrilfit report --case" in page and "headless.py" not in page
    # item 2: the box belongs to these values; after Layers 3 -> 4 and Run all it says so
    assert any(t.startswith("Report: ") for t in main_labels())
    assert not any(t.startswith("Earlier values") for t in main_labels())
    ui.layers = 4
    assert run("run_all") == {"FINISHED"}
    labels = main_labels()
    assert any(t.startswith("Earlier values: Layers") for t in labels), labels
    assert run("clear") == {"FINISHED"}
    assert not any(t.startswith(("Report", "Earlier values")) for t in main_labels())
    assert ui.report_summary == ""
    # and the command makes the same report (the command line's own fresh scene: last)
    again = tmp_path / "again"
    words = cmd[1:]
    words[words.index("--out") + 1] = str(again)
    assert cli.main([*words, "--quiet", "--render-engine", "workbench",
                     "--render-size", "320x180"]) == 0
    theirs = json.loads((again / "report.json").read_text())
    for key in ("answer", "model", "p_fit", "minimal_linker", "bound"):
        assert doc[key] == theirs[key], key
    assert theirs["structure"]["fibril"]["sha256"] == block["fibril"]["sha256"]


# ---- 4. the traces follow the model; import frames them where a 3D View exists ----------------

def _traces(scene, kind):
    """The scene's `kind` CA traces, found by their tags (as the code of a2caed5 tags them)."""
    from fibrilfit.builders.scene import TAG
    return [o for o in scene.objects if o.get(TAG) == structure_trace.TRACE
            and o.get(structure_trace.KIND, "fibril") == kind]


def _world_points(ob):
    import numpy as np
    co = np.array([v.co for v in ob.data.vertices])
    m = np.array(ob.matrix_basis)
    return co @ m[:3, :3].T + m[:3, 3]


def test_the_fibril_trace_follows_a_rebuild(ui, scene):
    """Issue #45 item 4: 6CU7's trace is centred in the model's layers after Layers 20 -> 6 and
    a rebuild (it floated 32-58 Å above the model), same axis, each CA layer on a model layer."""
    import numpy as np
    ui.layers = 20
    assert run("import_fibril", filepath=str(DATA / "6cu7.pdb.gz")) == {"FINISHED"}
    assert run("run_all") == {"FINISHED"}
    p20 = find_model(scene).params
    (ob,) = _traces(scene, "fibril")
    z20 = _world_points(ob)[:, 2]
    r20 = np.sort(np.hypot(*_world_points(ob)[:, :2].T))
    assert 0 < z20.min() and z20.max() < (p20.layers - 1) * p20.rise + 5
    ui.layers = 6
    assert run("run_all") == {"FINISHED"}
    p = find_model(scene).params
    assert p.layers == 6
    (ob,) = _traces(scene, "fibril")
    pts = _world_points(ob)
    top = (p.layers - 1) * p.rise
    assert -5 < pts[:, 2].min() and pts[:, 2].max() < top + 5, (pts[:, 2].min(), top)
    # centred: the trace's mid-height near the stack's
    assert abs((pts[:, 2].min() + pts[:, 2].max()) / 2 - top / 2) < p.rise
    # the turn follows the twist: radii about the axis unchanged
    assert np.allclose(r20, np.sort(np.hypot(*pts[:, :2].T)), atol=1e-3)
    # and the same as importing onto the 6-layer model directly
    direct = _world_points(ob)
    assert run("import_fibril", filepath=str(DATA / "6cu7.pdb.gz")) == {"FINISHED"}
    (ob,) = _traces(scene, "fibril")
    assert np.allclose(_world_points(ob), direct, atol=1e-3)


def test_a_second_domain_keeps_the_firsts_trace(ui, scene):
    """Issue #45 item 4: importing GFP after ubiquitin keeps ubiquitin's trace (both beside the
    globule, clear of each other); removing one from the list removes its trace only."""
    import_two_domains()
    obs = sorted(_traces(scene, "domain"), key=lambda o: o.name)
    assert [o.name.split()[0] for o in obs] == ["1gfl.pdb.gz", "1ubq.pdb.gz"]
    b, a = (_world_points(o) for o in obs)
    assert a[:, 1].min() > b[:, 1].max()  # GFP further along -Y, no overlap
    ui.domain_index = 0
    assert run("domain_remove") == {"FINISHED"}
    assert [o.name.split()[0] for o in _traces(scene, "domain")] == \
        ["1gfl.pdb.gz"]


def test_import_frames_the_structures_where_a_3d_view_exists(ui, scene, monkeypatch):
    """Issue #45 item 4: each import frames what it imported (and the model, if any) through
    view.frame_points, which frames nothing without a 3D View (headless: here) and needs none."""
    import numpy as np
    from fibrilfit.ui import view
    from fibrilfit.ui.operators import structures
    framed = []
    monkeypatch.setattr(view, "frame_points", lambda context, pts: framed.append(len(pts)) or 0,
                        raising=False)
    monkeypatch.setattr(structures, "frame_points", view.frame_points, raising=False)
    import_two_domains()
    a, b = (_world_points(o) for o in _traces(scene, "domain"))
    assert framed == [len(a), len(a) + len(b)]
    monkeypatch.undo()
    assert view.frame_points(bpy.context, np.vstack([a, b])) == 0  # headless: no 3D View


# ---- 5 and 6. the minimal-linker box is a small table; one vocabulary, the answer first -------

def _minimal_map():
    """A map as Minimal linker… keeps it: 20 Å found at 4 over a bound of 3 (open bracket),
    27.5 Å at 1 with the bound 1 (closed), 40 Å none up to 30."""
    from fibrilfit.search.minimal import Walk
    from fibrilfit.ui import minimal_summary
    found = Walk(20.0, 4, 30, restarts=2, stop_at_fit=True, floor=3)
    found.record(3, 0, 2)
    found.record(4, 1, 1)
    closed = Walk(27.5, 1, 30, restarts=2, stop_at_fit=True, floor=1)
    closed.record(1, 2, 2)
    none = Walk(40.0, 29, 30, restarts=2, floor=5)
    for L in range(5, 31):
        none.record(L, 0, 2)
    rows = [{"kind": "", **w.row(), "protocol": "tutorial"} for w in (found, closed, none)]
    return minimal_summary.summary_of({"rows": rows, "protocol": "tutorial", "restarts": 2,
                                       "seeds": [4, 5], "max_linker": 30, "table": ""})


def test_the_minimal_linker_box_is_a_small_table_that_fits(ui):
    """Issue #45 item 5: a row per diameter (diameter, minimal linker, P(fit), bracket), every
    label within the default sidebar (a cell within a quarter of it); no repository path, no
    "open from 1 to 1"."""
    from test_ui import FIELD_PX, _text_px
    ui.minimal_map = json.dumps(_minimal_map())
    labels = main_labels()
    start = labels.index("Minimal linker (tutorial)")
    assert labels[-1].startswith("Lengths in Å")  # the panel's last line, after the box
    box = labels[start:-1]
    assert not any("docs/" in t or "open from" in t or ".md" in t for t in box), box
    assert all(_text_px(t) <= FIELD_PX for t in box), box
    for diameter, linker, p_fit, bracket in (("20", "4", "1/1", "3–4"),
                                              ("27.5", "1", "2/2", "1"),
                                              ("40", "> 30", "–", "5–?")):
        i = box.index(diameter)
        assert box[i:i + 4] == [diameter, linker, p_fit, bracket]
        assert all(_text_px(c) <= FIELD_PX / 4 for c in box[i:i + 4])
    assert len(box) <= 2 + 4 * 4 + 2  # title, restarts; header and 3 rows; the legend


def test_the_panel_says_the_answer_first_in_the_glossarys_words(ui, scene):
    """Issue #45 item 6: after Run all the box starts with the answer (fits / borderline / no
    layout found / impossible below B), then the globules, the stretch with its limit and the
    bound; none of "Verdict", "Accommodated", "successful", "intersection", a bare "95 %", a
    negative stretch or a double negative."""
    import re
    ui.linker = 3
    assert run("run_all") == {"FINISHED"}
    labels = main_labels()
    i = next(i for i, t in enumerate(labels) if t.startswith("Run: "))
    assert labels[i].removeprefix("Run: ") in ("fits", "borderline", "no layout found") or \
        labels[i].startswith("Run: impossible below ")
    assert labels[i + 1].startswith("Globules: ")
    assert re.fullmatch(r"Max stretch (\d+\.\d %|0 %), limit 5 %", labels[i + 2])
    text = " ".join(labels)
    for word in ("Verdict", "Accommodated", "successful", "intersection", "rules out no",
                 "Answer:", "−", "-0.", "95 %:"):
        assert word not in text, word
    # the same words in the report's box (ui/report_summary.py)
    from fibrilfit.ui import report_summary
    doc = {"answer": "no layout found", "model": None,
           "p_fit": {"fits": 0, "runs": 8, "low": 0.0, "high": 0.32, "linker": 3},
           "minimal_linker": {"linker": None, "max_linker": 12}, "bound": {"impossible_below": 1}}
    lines = [t for t, _ in report_summary.summary_lines(report_summary.summary_of(doc, "/r"))]
    assert lines[0] == "Report: no layout found"
    assert "P(fit) 95 % interval: 0.00–0.32" in lines
    assert "Bound: every length allowed" in lines


# ---- 7. the panel's messages speak the panel's labels ------------------------------------------

def test_messages_name_fields_by_their_labels(ui, scene, tmp_path, capfd):
    """Issue #45 item 7: errors and notes say "Fibril file", "Core outline", "Protofilament
    rise", never "--fibril:", "core_outline" or "pf_rise"."""
    import re
    with pytest.raises(RuntimeError) as bad:
        run("import_fibril", filepath=str(DATA / "1ubq.pdb.gz"))
    assert str(bad.value).startswith("Error: Fibril file: 1ubq.pdb.gz: "), str(bad.value)
    assert "--" not in str(bad.value)
    outline = tmp_path / "bad.json"
    outline.write_text("[[0, 0], [1, 1]]")
    with pytest.raises(RuntimeError, match=r"Core outline: .*at least 3 points") as bad:
        run("load_outline", filepath=str(outline))
    capfd.readouterr()
    assert run("import_fibril", filepath=str(DATA / "6cu7.pdb.gz")) == {"FINISHED"}
    said = capfd.readouterr().out
    assert "6cu7.pdb.gz: set" in said and "Protofilament rise" in said and "Core outline" in said
    assert not re.search(r"\b[a-z]+_[a-z_]+\b", said.split("6cu7.pdb.gz: set")[1].split("\n")[0])
    assert run("run_all") == {"FINISHED"}
    ui.use_pf_rise, ui.pf_rise = True, ui.pf_rise + 1.0
    with pytest.raises(RuntimeError, match=r"Protofilament rise changed from .* since the model "
                                           r"was built"):
        run("bake")
    labels = main_labels()
    assert "Changed since the build: Protofilament rise" in " ".join(labels), labels


# ---- 8. the linker explained where it is set; a "start here" line -------------------------------

def test_the_linker_says_its_unit_and_its_anchor_and_an_import_that_leaves_it_says_so(ui, scene):
    """Issue #45 item 8: "Linker (residues)", a tooltip that says "residues" once and what the
    passive anchor is; after importing ubiquitin alone (no numbering to give the linker) the
    panel and the import's report say it was left as it was, until the user sets it."""
    rna = ui.bl_rna.properties["linker"]
    assert rna.name == "Linker (residues)"
    assert rna.description.count("(residues)") <= 1
    assert "passive" in rna.description and "does not move" in rna.description
    assert "counts as the linker's first residue" in rna.description
    assert any(t.startswith("Start here") for t in main_labels())  # the empty panel
    assert run("import_domain", filepath=str(DATA / "1ubq.pdb.gz")) == {"FINISHED"}
    labels = main_labels()
    assert not any(t.startswith("Start here") for t in labels)
    assert "Not in the files: set the residues" in labels
    ui.linker = 12
    assert "Not in the files: set the residues" not in main_labels()


# ---- 9. the domain list is not cramped --------------------------------------------------------

def test_the_domain_list_rows_fit_and_the_selected_linker_is_set_under_it(ui, scene):
    """Issue #45 item 9: each row of the list (about 190 px beside its buttons at the default
    sidebar width) shows its name and diameter uncut, with no field squeezed beside it; the
    selected domain's linker to the next is a full-width field under the list."""
    from fibrilfit.ui import domain_list
    from test_ui import FIELD_PX, _text_px
    import_two_domains()
    list_px = FIELD_PX - 40  # the move and remove buttons beside the list
    for i, e in enumerate(ui.domains):
        log = []
        layout = types.SimpleNamespace(
            label=lambda text="", **kw: log.append(("label", text)),
            prop=lambda data, name, text="", **kw: log.append(("prop", text)),
            row=lambda **kw: layout)
        domain_list.FIBRILFIT_UL_domains.draw_item(None, bpy.context, layout, ui, e, 0, ui,
                                                   "domain_index", i)
        assert [k for k, _ in log] == ["label"], log
        assert _text_px(log[0][1]) + 20 <= list_px, log  # the icon's 20 px
        assert f"{json.loads(e.measured)['globule_diameter']:.0f} Å" in log[0][1]
    ui.domain_index = 0
    from test_ui import draw_all
    props = [n for kind, n in draw_all(bpy.context)["FIBRILFIT_PT_main"] if kind == "prop"]
    assert "linker" in props  # the entry's, under the list (FakeLayout records its name)


# ---- 10. frictions: the last folder, one set of restarts, a report never replaced unasked ------

def test_file_browsers_start_in_the_last_folder_and_failed_imports_push_no_undo(ui, scene):
    """Issue #45 item 10: after a file is read from a folder the next file browser starts
    there; operators that open a file browser push their own undo step on success only (with
    the UNDO option Blender 4.3 pushes one whatever they return)."""
    from fibrilfit.ui.operators import cases, common, outline, structures
    for cls in (structures.FIBRILFIT_OT_import_fibril, structures.FIBRILFIT_OT_import_domain,
                cases.FIBRILFIT_OT_load_case, outline.FIBRILFIT_OT_load_outline):
        assert "UNDO" not in cls.bl_options, cls.__name__
    with pytest.raises(RuntimeError):
        run("import_fibril", filepath=str(DATA / "1ubq.pdb.gz"))
    assert ui.last_folder == ""
    assert run("import_domain", filepath=str(DATA / "1ubq.pdb.gz")) == {"FINISHED"}
    assert ui.last_folder == str(DATA)
    op = types.SimpleNamespace(filepath="")
    common.browse_from_last_folder(op, bpy.context, "case.toml")
    assert op.filepath == str(DATA / "case.toml")


def test_report_and_minimal_linker_offer_the_same_restarts(ui):
    for name in ("restarts", "max_linker"):
        mine = bpy.ops.fibrilfit.minimal_linker.get_rna_type().properties[name].default
        theirs = bpy.ops.fibrilfit.report.get_rna_type().properties[name].default
        assert mine == theirs == ui.bl_rna.properties[f"report_{name}"].default, name


def test_report_never_replaces_a_report_unasked(ui, tmp_path):
    """Report… into a folder that holds a report is refused (tick Replace to write over it),
    and the next Report… offers a new folder beside the last one."""
    from fibrilfit.ui.operators import report as report_op
    out = tmp_path / "page"
    out.mkdir()
    (out / "report.html").write_text("<p>an earlier report</p>")
    with pytest.raises(RuntimeError, match="already holds a report"):
        run("report", directory=str(out), restarts=1, max_linker=1)
    assert (out / "report.html").read_text() == "<p>an earlier report</p>"
    assert report_op.free_folder(str(out) + "/") == str(tmp_path / "page-2") + "/"
    assert report_op.free_folder(str(tmp_path / "new")) == str(tmp_path / "new") + "/"


def test_kept_results_are_marked_after_a_rebuild_with_other_values_and_cleared(ui, scene):
    """Issue #45 item 2, without a report's minutes: the report's box as Report… leaves it (its
    summary of report.json, the model it answered for), then Run all with Layers 6 -> 7: the box
    says the values changed, without its tick; Clear removes it and the minimal-linker map's."""
    from fibrilfit.ui import report_summary
    doc = {"answer": "fits", "model": properties.read_params(ui).to_dict(),
           "p_fit": {"fits": 2, "runs": 2, "low": 0.34, "high": 1.0, "linker": 6},
           "minimal_linker": {"linker": 3, "max_linker": 30}, "bound": {"impossible_below": 1}}
    ui.report_summary = json.dumps(report_summary.summary_of(doc, "/tmp/r"))
    ui.minimal_map = json.dumps(_minimal_map())
    assert run("run_all") == {"FINISHED"}
    labels = main_labels()
    assert "Report: fits" in labels and not any(t.startswith("Earlier") for t in labels)
    ui.layers = 7
    assert run("run_all") == {"FINISHED"}
    labels = main_labels()
    i = labels.index("Report: fits")
    assert labels[i - 1].startswith("Earlier values: Layers"), labels
    assert run("clear") == {"FINISHED"}
    assert ui.report_summary == ui.minimal_map == ""
    assert not any(t.startswith(("Report", "Minimal linker (", "Earlier")) for t in main_labels())
