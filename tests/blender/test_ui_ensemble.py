"""The sidebar's Sample ensemble… (ui/operators/ensemble.py): after Run all, it samples the
checked layout's ensemble as `run --ensemble` does (the same block for the same seed and
options), keeps it in the model's result and shows its lines in the panel's result box, puts
its density over the model as a Volume object; the next check clears both; a model the sampler does not model is refused in one report."""
import json

import bpy
import pytest
from ui_fakes import FakeLayout

from fibrilfit import cli
from fibrilfit.model import params as P
from fibrilfit.ui import panels, properties
from fibrilfit.ui.operators.common import RESULT

SMALL = dict(layers=6, seed=0)
OPTIONS = dict(sweeps=6, replicas=4, burn_in=4)


def _labels(context) -> list:
    log = []
    panels.draw_run(FakeLayout(log), context)
    return [text for kind, text in log if kind == "label"]


def test_the_panels_ensemble_is_the_commands(registered, tmp_path):
    out = tmp_path / "r.json"
    assert cli.main(["run", "--layers", "6", "--ensemble", "6", "--ensemble-replicas", "4",
                     "--ensemble-burn-in", "4", "--quiet", "--json", str(out)]) == 0
    command = json.loads(out.read_text())["ensemble"]
    s = bpy.context.scene.fibrilfit  # the command replaced the scene
    properties.write_params(s, P.make_params(**SMALL))
    assert bpy.ops.fibrilfit.run_all() == {"FINISHED"}
    assert s.ensemble_summary == ""
    assert bpy.ops.fibrilfit.sample_ensemble(**OPTIONS) == {"FINISHED"}
    shown = json.loads(s.ensemble_summary)
    assert shown["sampled"] and shown["outer_diameter"] == command["outer_diameter"]
    assert shown["width"]["value"] == command["width"]["value"]
    from fibrilfit import pipeline
    kept = json.loads(pipeline.current_model().root[RESULT])["ensemble"]
    assert kept["outer_diameter"] == command["outer_diameter"]
    labels = " ".join(_labels(bpy.context))
    assert "ensemble: outer diameter" in labels and "ensemble: width" in labels
    # the density over the model, as the command's --ensemble-volume makes it
    from fibrilfit.builders import density_volume
    volume = density_volume.find(bpy.context.scene)
    assert volume is not None and shown["volume"]["object"] == volume.name
    assert "ensemble: density over the model as the Volume object" in labels
    assert bpy.ops.fibrilfit.check_intersections() == {"FINISHED"}  # a new check: cleared
    assert s.ensemble_summary == "" and "ensemble:" not in " ".join(_labels(bpy.context))
    assert density_volume.find(bpy.context.scene) is None  # its density too


def test_a_model_the_sampler_does_not_model_is_refused(registered):
    s = bpy.context.scene.fibrilfit
    properties.write_params(s, P.make_params(**SMALL, occupancy=0.5))
    assert bpy.ops.fibrilfit.run_all() == {"FINISHED"}
    with pytest.raises(RuntimeError, match="ensemble samples fully decorated"):
        bpy.ops.fibrilfit.sample_ensemble(**OPTIONS)
    assert s.ensemble_summary == ""
