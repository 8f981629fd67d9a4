"""`run --ensemble` (docs/model/ensemble.md#use): the option declared once and parsed into the
run's and the report's plans, refused where it cannot work; the result's block made from a small
model (plain numpy, no bpy), valid against the result schema, with its words in the printed
result; a block with a key missing fails the schema."""
import copy
import json
import pathlib

import jsonschema
import numpy as np
import pytest

from fibrilfit.api.plans import ReportPlan, RunPlan, make_plan
from fibrilfit.cli.parser import build_parser
from fibrilfit.ensemble import account, system
from fibrilfit.ensemble.plans import EnsemblePlan
from fibrilfit.exports import ensemble_words, run_text
from fibrilfit.model import params as P, start_layout
from fibrilfit.plans import PlanError

REFERENCE = pathlib.Path(__file__).resolve().parents[2] / "docs" / "reference"
SAMPLE = json.loads((REFERENCE / "samples" / "run_ensemble.json").read_text(encoding="utf-8"))


def errors(doc):
    schema = json.loads((REFERENCE / "result.schema.json").read_text(encoding="utf-8"))
    return list(jsonschema.Draft202012Validator(schema).iter_errors(doc))


def test_the_option_parses_into_the_run_and_report_plans():
    plan, _ = make_plan(RunPlan, {"ensemble": "40", "ensemble_replicas": "8",
                                  "ensemble_map": "m.mrc", "linker": 8})
    assert plan.sampling == EnsemblePlan(ensemble=40, ensemble_replicas=8, ensemble_map="m.mrc")
    assert plan.sampling.on and plan.model == {"linker": 8}
    assert not make_plan(RunPlan, {})[0].sampling.on  # off by default
    assert make_plan(ReportPlan, {"ensemble": 5})[0].sampling.ensemble == 5
    ns = build_parser().parse_args(["run", "--ensemble", "12", "--ensemble-map", "x.mrc"])
    assert (ns.ensemble, ns.ensemble_map) == ("12", "x.mrc")
    ns = build_parser().parse_args(["run", "--ensemble", "12", "--ensemble-volume"])
    assert make_plan(RunPlan, {"ensemble": 12, "ensemble_volume": ns.ensemble_volume})[0] \
        .sampling.ensemble_volume is True
    with pytest.raises(PlanError, match="^--ensemble-volume: not a report option"):
        make_plan(ReportPlan, {"ensemble": 5, "ensemble_volume": True})


@pytest.mark.parametrize("values, says", [
    ({"ensemble": -1}, "--ensemble: must be an integer from 0 to 100000 sweeps"),
    ({"ensemble": "many"}, "--ensemble: must be an integer"),
    ({"ensemble": 10, "ensemble_replicas": 1}, "--ensemble-replicas: must be an integer from 2"),
    ({"ensemble_map": "m.mrc"}, "--ensemble-map: only with --ensemble"),
    ({"ensemble": 10, "stop_after": "bake"}, "--ensemble: starts from a checked layout"),
    ({"ensemble_volume": True}, "--ensemble-volume: only with --ensemble"),
])
def test_bad_values_are_one_line_naming_the_option(values, says):
    with pytest.raises(PlanError) as err:
        make_plan(RunPlan, values)
    assert str(err.value).startswith(says) and "\n" not in str(err.value)


def test_why_no_ensemble():
    assert "stopped after build" in account.why_not({"stage": "build"})
    assert "does not fit (no layout found)" in account.why_not(
        {"stage": "check", "accommodated": False, "answer": "no layout found"})
    assert account.why_not({"stage": "check", "accommodated": True}) is None
    assert account.not_sampled("x") == {"sampled": False, "reason": "x"}


@pytest.fixture(scope="module")
def small_block():
    """A small model's block from its rest layout (burn-in repairs its overlaps), twice with
    the same seed and once with another."""
    p = P.make_params(layers=6, globule_diameter=10.0)
    plan = EnsemblePlan(ensemble=8, ensemble_replicas=4, ensemble_burn_in=4)
    start, scored = start_layout.rest_positions(p), np.ones(p.chains, bool)
    return p, [account.sampled_block(p, start, scored, plan, seed=s) for s in (3, 3, 4)]


def test_the_block_of_a_small_model(small_block):
    p, (block, again, other) = small_block
    od = block["outer_diameter"]
    assert block["sampled"] and block["seed"] == 3 and block["sweeps"] == 8
    lo, hi = od["interval_95"]
    # the domains (radius 5 Å) hang from anchors by a chain of fixed bonds: the outer
    # diameter lies within the anchor's distance plus the whole chain, plus the radius
    chain = system.from_params(p)
    anchor = float(np.hypot(*start_layout.rest_positions(p)[0, 0, :2]))
    assert 10.0 < lo <= od["median"] <= hi <= 2 * (anchor + chain.bonds.sum() + 5.0)
    assert len(od["halves"]["means"]) == 2 and od["ess"] > 0
    assert 0 < block["width"]["value"] < hi + 2 * block["width"]["voxel"]
    assert block["width"]["definition"] == account.WIDTH_DEFINITION
    assert errors({**SAMPLE, "ensemble": block}) == []
    assert stable(block) == stable(again)  # the seed fixes the ensemble
    assert stable(other)["outer_diameter"] != stable(block)["outer_diameter"]


@pytest.fixture(scope="module")
def small_sample():
    """A small model's block, its map (one helical turn) and the volume's map."""
    p = P.make_params(layers=6, globule_diameter=10.0)
    plan = EnsemblePlan(ensemble=4, ensemble_replicas=4, ensemble_burn_in=4, ensemble_volume=True)
    start, scored = start_layout.rest_positions(p), np.ones(p.chains, bool)
    return (p, *account.sample(p, start, scored, plan, seed=3))


def test_the_volumes_map_is_the_widths_over_the_models_layers(small_sample):
    """The map put over the model in Blender (account.volume_map) is the width's map (one
    helical turn) cut to the model's own layers: the same voxels, the same values."""
    p, block, turn, vmap = small_sample
    assert vmap.layers == p.layers < turn.layers and vmap.voxel == turn.voxel
    assert vmap.origin == turn.origin and vmap.data.shape[1:] == turn.data.shape[1:]
    assert vmap.data.shape[0] * vmap.voxel >= p.layers * p.rise
    np.testing.assert_allclose(vmap.data, turn.data[:vmap.data.shape[0]], atol=1e-5)
    assert vmap.data.max() > 0.1
    start, scored = start_layout.rest_positions(p), np.ones(p.chains, bool)
    assert account.sample(p, start, scored, EnsemblePlan(ensemble=4, ensemble_replicas=4,
                                                         ensemble_burn_in=4), seed=3)[2] is None


def test_the_reports_picture_has_the_projection_its_profile_and_the_radial_density(
        small_sample, tmp_path):
    """ensemble.png: the projection with the width's edges, the profile across the axis with
    its level at 10 % of the peak and the width between its crossings, the radial density with
    its peak; the page embeds it with a caption and has the radial density's row."""
    from fibrilfit.ensemble import density
    from fibrilfit.exports import ensemble_plot, report_page
    _, block, turn, _ = small_sample
    fig = ensemble_plot.draw(block, turn)
    projection, profile, radial = fig.axes[:3]
    assert projection.images and "width" in projection.get_title()
    x, prof = density.profile(turn)
    level = 0.1 * prof.max()
    flat = [ln.get_ydata()[0] for ln in profile.lines if len(set(ln.get_ydata())) == 1]
    assert flat == pytest.approx([level])
    upright = sorted(ln.get_xdata()[0] for ln in profile.lines if len(set(ln.get_xdata())) == 1)
    assert len(upright) == 2 and upright[1] - upright[0] == pytest.approx(block["width"]["value"],
                                                                          abs=0.01)
    # the crossings are where the profile meets the level
    assert np.interp(upright, x, prof) == pytest.approx([level, level], rel=0.02)
    rd = block["radial_density"]
    r_peak = rd["r"][int(np.argmax(rd["mass_density_da_per_a3"]))]
    assert any(ln.get_xdata()[0] == r_peak for ln in radial.lines if len(set(ln.get_xdata())) == 1)
    out = ensemble_plot.write(block, turn, tmp_path / "ensemble.png")
    assert (tmp_path / "ensemble.png").stat().st_size > 10_000 and out["peak_projection"] > 0
    doc = {"ensemble": block, "files": {"ensemble_plot": "ensemble.png"},
           "envelope": {"best_layout": {"outer_diameter": 30.0}}}
    page = report_page.ensemble_picture(doc, tmp_path)
    assert 'alt="ensemble" src="data:image/png;base64,' in page and "Middle: " in page
    assert "10 % of its peak" in page
    assert f"ensemble: radial density</th><td>domain mass highest {r_peak:.0f} Å" in \
        report_page.envelope_text(doc)


VOLUME = {"object": "ensemble density", "grid": "density", "threshold": 0.02,
          "units": "volume fraction of protein per voxel", "voxel": 3.0,
          "origin": [-76.5, -76.5, -2.4], "shape_zyx": [10, 51, 51], "window_layers": 6,
          "peak": 2.19, "voxels_above_threshold": 4762, "material_density_per_fraction": 0.08}


def test_the_volumes_block_in_the_schema_and_the_words():
    block = {**SAMPLE["ensemble"], "volume": VOLUME}
    assert errors({**SAMPLE, "ensemble": block}) == []
    for key in ("threshold", "shape_zyx", "voxels_above_threshold"):
        broken = {**block, "volume": {k: v for k, v in VOLUME.items() if k != key}}
        assert errors({**SAMPLE, "ensemble": broken}), key
    assert ensemble_words.lines(block)[-1] == (
        'ensemble: density over the model as the Volume object "ensemble density" (6 layers, '
        '3 Å voxels, empty below a volume fraction of 0.02)')
    assert len(ensemble_words.lines(SAMPLE["ensemble"])) == 2


def stable(block):
    """The block without its timings."""
    out = copy.deepcopy(block)
    out.pop("seconds")
    out["width"].pop("map_seconds")
    return out


def test_the_schema_checks_the_block():
    assert "ensemble" in SAMPLE and SAMPLE["ensemble"]["sampled"]
    assert errors(SAMPLE) == []
    assert errors({**SAMPLE, "ensemble": {"sampled": False, "reason": "the run did not fit"}}) == []
    for path in [("width",), ("outer_diameter", "interval_95"), ("outer_diameter", "halves"),
                 ("radial_density",), ("seed",)]:
        broken = copy.deepcopy(SAMPLE)
        target = broken["ensemble"]
        for key in path[:-1]:
            target = target[key]
        del target[path[-1]]
        assert errors(broken), path
    assert errors({**SAMPLE, "ensemble": {"sampled": False}})
    assert errors({**SAMPLE, "ensemble": {"sampled": True, "reason": "x"}})


def test_the_printed_result_shows_the_ensemble_and_labels_the_layout():
    text = run_text.text(SAMPLE)
    od = SAMPLE["ensemble"]["outer_diameter"]
    assert f"ensemble: outer diameter {od['median']:.0f} Å (median; 95 % of layouts " \
           f"{od['interval_95'][0]:.0f}–{od['interval_95'][1]:.0f} Å)" in text
    assert f"ensemble: width {SAMPLE['ensemble']['width']['value']:.0f} Å" in text
    assert "envelope (this layout): " in text
    bare = run_text.text({k: v for k, v in SAMPLE.items() if k != "ensemble"})
    assert "ensemble" not in bare and "envelope: domain centres" in bare
    assert ensemble_words.lines({"sampled": False, "reason": "why"}) == \
        ["ensemble: not sampled: why"]


def test_the_report_shows_the_ensemble_above_the_best_layout():
    from fibrilfit.exports import report_page
    doc = {"envelope": {"best_layout": {"outer_diameter": 128.4}}, "ensemble": SAMPLE["ensemble"]}
    page = report_page.envelope_text(doc)
    od = SAMPLE["ensemble"]["outer_diameter"]
    rows = page.split("</tr>")
    assert "ensemble: outer diameter" in rows[0] and f"{od['median']:.0f} Å (median" in rows[0]
    assert "ensemble: width" in rows[1]
    assert "best layout: outer diameter" in page
    assert "ensemble" not in report_page.envelope_text({"envelope": doc["envelope"]})


def test_a_missing_mrcfile_is_one_line_before_anything_runs(monkeypatch, tmp_path):
    import sys
    from fibrilfit.api import ensemble_run
    from fibrilfit.exits import UsageError
    plan = EnsemblePlan(ensemble=5, ensemble_map=str(tmp_path / "m.mrc"))
    assert ensemble_run.check(plan, P.DEFAULTS) is not None  # mrcfile here: the path, checked
    with pytest.raises(P.ParamError, match="^occupancy: the ensemble samples"):
        ensemble_run.check(plan, P.make_params(occupancy=0.5))
    monkeypatch.setitem(sys.modules, "mrcfile", None)  # as in a Blender without it
    with pytest.raises(UsageError) as err:
        ensemble_run.check(plan, P.DEFAULTS)
    said = str(err.value)
    assert said.startswith("--ensemble-map needs the Python package mrcfile") and "\n" not in said
    assert not (tmp_path / "m.mrc").exists()
