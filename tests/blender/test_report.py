"""Issue #23: pictures that say what they show, and one command, one report."""
import base64
import json
import re

import jsonschema
import numpy as np
from mathutils import Vector
import pytest
from helpers import ROOT, cli_in_process, run_cli

from fibrilfit import pipeline, structure
from fibrilfit.analysis import clash_kinds, clashing_layers
from fibrilfit.builders.colours import CLASH_COLOR, GRAZE_COLOR, colour_globules, part_colour
from fibrilfit.exports import envelope_plot, legend, render
from fibrilfit.model import params as P
from fibrilfit.sweep.stats import wilson

DATA = ROOT / "tests" / "data"
FAST = ["--layers", "3", "--grow-frames", "20", "--hold-frames", "20", "--regrow-cycles", "0",
        "--globule-diameter", "12", "--linker", "3", "--restarts", "2", "--max-linker", "4",
        "--workers", "2", "--render-engine", "workbench", "--render-size", "320x180"]


# ---- clash and graze in two colours -------------------------------------------------------------

def test_deep_clashes_and_grazes_are_told_apart():
    """A crafted result: pair (0, 1) is deep, pair (1, 2) only grazes, pair (3, 4) only grazes.
    Globule 1 is in a deep pair, so it is a clash; 2, 3 and 4 only graze."""
    r = {"verdict": "intersection", "clashing_pairs": [[0, 1, 0.9], [1, 2, 0.1], [3, 4, 0.05]],
         "grazing_pairs": [[1, 2, 0.1], [3, 4, 0.05]]}
    assert clash_kinds(r) == ([0, 1], [2, 3, 4])
    assert sorted(sum(clash_kinds(r), [])) == clashing_layers(r)
    assert clash_kinds({**r, "verdict": "successful"}) == ([], [])
    assert clash_kinds({**r, "grazing_pairs": []}) == ([0, 1, 2, 3, 4], [])


def test_clash_and_graze_globules_get_different_colours(scene):
    pipeline.run_model(P.make_params(layers=5, linker=2), scene, stop_after="build")
    model = pipeline.current_model(scene)
    assert colour_globules(model, [0], scene, grazing=[0, 2]) == [0]  # deep wins over graze
    colours = [tuple(round(c, 3) for c in ob.color) for ob in model.globules]
    deep, pale = (tuple(round(c, 3) for c in col) for col in (CLASH_COLOR, GRAZE_COLOR))
    assert deep != pale
    assert colours[0] == deep and colours[2] == pale
    assert colours[1] == tuple(round(c, 3) for c in part_colour("globule", 0))


# ---- legend and scale bar -----------------------------------------------------------------------

def test_legend_is_composed_onto_the_picture(tmp_path):
    from matplotlib.image import imread, imsave
    plain = np.full((180, 320, 3), 0.58, dtype=np.float32)
    plain[60:120, 200:300] = 0.9  # "the model", upper right area
    imsave(tmp_path / "in.png", plain)
    entries = [("fibril core", (0.55, 0.62, 0.75)), ("clash: overlap > 0.29 Å (2)", CLASH_COLOR),
               ("graze: overlap ≤ 0.29 Å (1)", GRAZE_COLOR)]
    info = legend.compose(tmp_path / "in.png", tmp_path / "out.png", entries, 0.25)
    out = imread(tmp_path / "out.png")[..., :3]
    assert out.shape == plain.shape  # the same size
    assert info["drawn"] and info["entries"] == [e[0] for e in entries]
    assert info["scale_bar_angstrom"] == 10  # a fifth of 320 px at 0.25 Å/px is 16 Å: 10
    corner = info["legend_corner"]
    assert corner != "upper right"  # not over the model
    rows = slice(0, 60) if corner.startswith("upper") else slice(120, 180)
    cols = slice(0, 120) if corner.endswith("left") else slice(200, 320)
    assert np.abs(out[rows, cols] - plain[rows, cols]).max() > 0.3  # the legend is there
    assert legend.scale_length(0.4, 640) == 50 and legend.scale_length(1.3, 640) == 100


def test_every_render_has_a_legend_with_clash_and_graze(scene, tmp_path):
    pipeline.run_model(P.make_params(layers=3, linker=3), scene, stop_after="build")
    with_it = render.render_png(scene, tmp_path / "a.png", clashing=[0], grazing=[2],
                                size=(320, 180), engine="workbench")
    without = render.render_png(scene, tmp_path / "b.png", clashing=[0], grazing=[2],
                                size=(320, 180), engine="workbench", with_legend=False)
    assert with_it["legend"]["drawn"] and without["legend"] == {"drawn": False,
                                                              "reason": "not asked for"}
    tiny = render.render_png(scene, tmp_path / "c.png", size=(64, 36), engine="workbench")
    assert tiny["legend"] == {"drawn": False,
                              "reason": "the picture is smaller than 240x135 pixels"}
    labels = with_it["legend"]["entries"]
    assert any(x.startswith("clash") and x.endswith("(1)") for x in labels)
    assert any(x.startswith("graze") and x.endswith("(1)") for x in labels)
    assert with_it["legend"]["scale_bar_angstrom"] > 0
    from matplotlib.image import imread
    a, b = imread(tmp_path / "a.png")[..., :3], imread(tmp_path / "b.png")[..., :3]
    assert a.shape == b.shape == (180, 320, 3) and np.abs(a - b).max() > 0.3


# ---- the envelope plot's core -------------------------------------------------------------------

def test_envelope_plot_draws_the_structure_models_own_core(scene):
    values = structure.model_values(structure.measure_fibril(DATA / "6cu7.pdb.gz"), None)
    outline = np.asarray(values["core_outline"])
    reach = float(np.hypot(outline[:, 0], outline[:, 1]).max())
    assert 45 < reach < 52  # 6CU7's core reaches ~48-50 Å, not the slab's 23 Å
    centres = np.c_[np.full(6, 70.0), np.zeros(6), 4.8 * np.arange(6)]
    p = P.make_params(layers=6, score_layers=0, **values)
    result = {"params": p.to_dict(), "globule_centres": centres.tolist(), "scored_layers": [0, 5],
              "seed": 0, "envelope": {"r_median": 70.0, "r95": 70.0, "r_max": 70.0, "n": 6,
                                      "outer_diameter": 170.0}}
    fig = envelope_plot.draw(result)
    top = fig.axes[0]
    rings = {p.get_label(): p for p in top.patches if p.get_label().startswith("core reach")}
    (label, ring), = rings.items()
    assert ring.radius == pytest.approx(reach) and "outline" in label
    drawn = [p for p in top.patches if p.get_label() == "core outline (first layer)"]
    assert len(drawn) == 1 and len(drawn[0].get_xy()) >= len(outline)
    # the default slab keeps its corner
    slab = envelope_plot.core_shape(P.DEFAULTS.to_dict())
    assert slab[1] == pytest.approx(np.hypot(*P.DEFAULTS.slab[:2]) / 2)


# ---- one command, one report --------------------------------------------------------------------

def test_report_writes_one_page_its_json_and_the_pictures(tmp_path):
    out = tmp_path / "rep"
    proc = run_cli("report", *FAST, "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    assert "fibrilfit report" in proc.stderr  # the progress bar
    doc = json.loads((out / "report.json").read_text())
    schema = json.loads((ROOT / "docs" / "reference" / "report.schema.json").read_text())
    jsonschema.Draft202012Validator(schema).validate(doc)  # the published schema
    assert {"model", "sources", "warnings", "p_fit", "minimal_linker", "envelope",
            "files"} <= set(doc)
    pf = doc["p_fit"]
    assert {"fits", "runs", "low", "high"} <= set(pf) and pf["runs"] == 2
    assert [pf["low"], pf["high"]] == pytest.approx(wilson(pf["fits"], pf["runs"]), abs=1e-4)
    assert doc["model"]["linker"] == 3 and doc["model"]["protocol"] == "inflate"
    assert doc["sources"]["linker"] == "option" and doc["sources"]["protocol"] == "report default"
    assert doc["sources"]["rise"] == "default"
    # 12 Å globules on 3 layers fit at every linker: measured on bpy 4.2, 5.0 and 5.2, 2 of 2 at
    # linker 3, and the walk's minimum is the shortest linker, 1 (2 of 2), with nothing below it
    m = doc["minimal_linker"]
    assert pf["fits"] == 2 and doc["answer"] == "fits"
    assert m["linker"] == 1 and m["linker_below"] == 0 and m["error"] is None
    # the walk stops a length at its first fit and counts its seeds up to that fit: seed 0
    # fits, and seed 1, run beside it on the second worker, is not counted whichever finished
    # first (docs/model/search.md#decided)
    assert m["tried"]["1"] == {"accommodated": 1, "restarts": 1}
    for name in doc["files"].values():
        assert (out / name).is_file(), name
    assert {"render", "envelope_plot", "bracket_plot"} <= set(doc["files"])
    # the bracket's number line, drawn from the report's own numbers (search/bracket_plot.py)
    fig = doc["bracket_figure"]
    assert fig["impossible_below"] == doc["bracket"]["impossible_below"]
    assert fig["fits_at"] == m["linker"] == 1 and fig["asked"] == 3
    assert {x["linker"]: (x["fits"], x["runs"]) for x in fig["lengths"]} == {
        **{int(L): (t["accommodated"], t["restarts"]) for L, t in m["tried"].items()},
        3: (pf["fits"], pf["runs"])}
    # the best layout's linkers span at most their length (+ the tolerance): it fits
    span = doc["best_layout"]["linker_stretch"]
    assert 0 < span["median"] <= span["worst"] <= 1 + doc["model"]["stretch_tolerance"]
    # a 3-layer fibril: the short fibril's caveat among the warnings
    assert any("finite fibril of 3 layers with free ends" in w for w in doc["warnings"])
    assert doc["command"][1:3] == ["report", "--layers"]
    page = (out / "report.html").read_text()
    # one self-contained page: every picture inside it, no outside file
    srcs = re.findall(r'src="([^"]*)"', page)
    assert len(srcs) == 3 and all(s.startswith("data:image/png;base64,") for s in srcs)
    inside = [base64.b64decode(s.split(",", 1)[1]) for s in srcs]
    for key in ("render", "bracket_plot", "envelope_plot"):
        assert (out / doc["files"][key]).read_bytes() in inside, key
    assert "<link" not in page and "<script" not in page
    for needle in ("P(fit)", "Minimal linker", "Wilson", "Warnings", "report --layers 3",
                   "P(fit) by inflate", "end to end, the linkers span", "free ends",
                   "where each value came from", doc["versions"]["blender"]):
        assert needle in page, needle
    # every run is in results.jsonl; the walk reused the restarts at the linker (none twice)
    runs = [json.loads(x) for x in (out / "results.jsonl").read_text().splitlines()]
    keys = [(r["params"]["linker"], r["params"]["seed"]) for r in runs]
    assert len(keys) == len(set(keys))


# A tiny fibril where the fraction matters: 20 Å domains on 3 layers at linker 1, the tutorial's
# 60 frames, seed 4 (the same model misses at linker 1 with every subunit decorated and fits at 2:
# test_ui_minimal.py); measured on bpy 5.0.1, 2026-11-27: 1 of 3 decorated fits, 3 of 3 do not
FRACTION_TINY = ["--protocol", "tutorial", "--layers", "3", "--frames", "60", "--seed", "4",
                 "--globule-diameter", "20", "--linker", "1", "--restarts", "1",
                 "--max-linker", "3", "--workers", "2", "--render-engine", "workbench",
                 "--render-size", "320x180"]


@pytest.mark.one_bpy
def test_report_plots_p_fit_against_the_fraction(tmp_path):
    """--fraction-plot 0.34,1 on a tiny fibril (3 subunits, 1 restart): P(fit) at each fraction
    at the report's linker, the same numbers in report.json, the page's table and the plot,
    each row counted from the runs in results.jsonl (the report's own fraction, 1, its restarts
    reused, not run twice); one fraction fits and the other does not, so a row that took
    another row's runs, or the restarts for the fits, fails."""
    out = tmp_path / "rep"
    proc = run_cli("report", *FRACTION_TINY, "--fraction-plot", "0.34,1", "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((out / "report.json").read_text())
    schema = json.loads((ROOT / "docs" / "reference" / "report.schema.json").read_text())
    jsonschema.Draft202012Validator(schema).validate(doc)
    fp = doc["fraction_plot"]
    assert fp["linker"] == 1 and fp["restarts"] == 1 and fp["interval"] == "95 % Wilson"
    rows = fp["rows"]
    assert [(r["fraction_asked"], r["decorated"], r["subunits"]) for r in rows] == \
        [(0.34, 1, 3), (1.0, 3, 3)]
    assert [r["report_fraction"] for r in rows] == [False, True]
    assert [r["fits"] for r in rows] == [1, 0]  # as measured (above)
    runs = [json.loads(x) for x in (out / "results.jsonl").read_text().splitlines()]
    at_linker = [r for r in runs if r["params"]["linker"] == 1]
    for row in rows:
        mine = [r for r in at_linker if r["params"].get("occupancy", 1.0) == row["fraction_asked"]]
        assert len(mine) == row["restarts"] == 1  # one seed, run once
        fits = sum(r["accommodated"] for r in mine)
        assert row["fits"] == fits and row["p_fit"] == fits / len(mine)
        assert row["interval"] == pytest.approx(wilson(fits, len(mine)), abs=1e-4)
        assert row["seeds"] == [4, 4]
        if row["fraction_asked"] < 1:  # the draw: 1 of the 3 subunits in that run
            assert mine[0]["occupancy"]["decorated"] == 1
    own = rows[1]
    assert (own["fits"], own["restarts"]) == (doc["p_fit"]["fits"], doc["p_fit"]["runs"])
    assert doc["files"]["fraction_plot"] == "fraction_plot.png"
    assert (out / "fraction_plot.png").stat().st_size > 10_000
    page = (out / "report.html").read_text()
    table = page.split("id='fraction-plot'", 1)[1].split("</table>", 1)[0]
    cells = re.findall(r"<tr><td>([^<]*)</td><td>([^<]*)</td><td>([^<]*)</td><td>([^<]*)</td>"
                       r"<td>([^<]*)</td>", table)
    assert cells == [(f"{r['fraction_asked']:g}", f"{r['decorated']} of {r['subunits']} "
                      f"({100 * r['fraction']:.4g} %)", f"{r['fits']}/{r['restarts']}",
                      f"{r['p_fit']:.2f}", f"{r['interval'][0]:.2f}–{r['interval'][1]:.2f}")
                     for r in rows]
    assert len(re.findall(r'src="data:image/png;base64,', page)) == 4  # and the plot inside


@pytest.mark.parametrize("bad, needle", [
    (["--fraction-plot", "0.5,2"], "--fraction-plot"),
    (["--fraction-plot", "0.3,0.4"], "--fraction-plot"),
    (["--pattern", "periodic", "--pattern-period", "2", "--fraction-plot", "0.5"],
     "--fraction-plot"),
    (["--linker", "0"], "linker"),
    (["--layers", "many"], "layers"),
    (["--fibril", "no-such-file.pdb"], "no-such-file"),
    (["--restarts", "0"], "--restarts"),
    (["--render-size", "wide"], "--render-size"),
    (["--workers", "0"], "--workers"),
])
def test_report_refuses_what_run_refuses_and_writes_nothing(tmp_path, bad, needle):
    out = tmp_path / "rep"
    cli = run_cli if bad[0] == "--linker" else cli_in_process  # one in a fresh process
    proc = cli("report", *FAST, *bad, "--out", str(out))
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.strip().count("\n") == 0 and needle in proc.stderr
    assert "Traceback" not in proc.stderr and not out.exists()
    if bad[0] not in ("--restarts", "--render-size", "--workers", "--max-linker",
                      "--fraction-plot", "--pattern"):
        ran = cli_in_process("run", *bad, "--layers", "3", "--stop-after", "build") if \
            bad[0] != "--layers" else cli_in_process("run", *bad, "--stop-after", "build")
        assert ran.returncode == 2  # run refuses it too


def test_periodic_render_frames_the_cell_and_every_image(scene):
    from bpy_extras.object_utils import world_to_camera_view

    from fibrilfit.builders.periodic import MOVING, STATIC, image_collection
    from fibrilfit.exports import dressing
    pipeline.run_model(P.make_params(layers=8, linker=3, periodic=8), scene, stop_after="build")
    model = pipeline.current_model(scene)
    images = [ob for role in (MOVING, STATIC) if image_collection(model, role) is not None
              for ob in image_collection(model, role).all_objects if ob.type == "MESH"]
    assert images  # the cell has images to frame
    d = dressing.dress(scene, model, [], aspect=16 / 9)
    scene.render.resolution_x, scene.render.resolution_y = 1600, 900
    for ob in [*images, *model.globules]:
        for corner in ob.bound_box:  # every corner of every body in the picture, none cropped
            u, v, depth = world_to_camera_view(scene, d.camera, ob.matrix_world @ Vector(corner))
            assert -1e-6 <= u <= 1 + 1e-6 and -1e-6 <= v <= 1 + 1e-6 and depth > 0, ob.name
