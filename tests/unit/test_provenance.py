"""Where the sidebar's values came from and whether a kept result still belongs to them
(fibrilfit/ui/provenance.py, no bpy; the panel's route through it: tests/blender/test_ui_route.py)."""
import numpy as np

from fibrilfit.model import params as P
from fibrilfit.ui.provenance import SIDEBAR, changed_names, panel_sources, same_value


def test_one_value_across_the_panels_float32_and_its_lists():
    measured = 4.8251234
    assert same_value(float(np.float32(measured)), measured)  # the panel's 32 bits read back
    assert not same_value(4.83, measured)
    assert same_value([10], (10,)) and same_value((1.0, 2.0), [1.0, 2.0])  # issue #45's "10 to [10]"
    assert not same_value([10, 12], (10,)) and not same_value([10], (11,))
    assert not same_value(True, 1) and same_value(False, False)  # a flag is not a number
    assert same_value("hull", "hull") and not same_value("hull", "sphere")


def test_each_value_names_its_true_source():
    panel = {f.name: getattr(P.DEFAULTS, f.name) for f in P.fields()}
    panel.update(rise=float(np.float32(4.8251234)), linker=9, layers=P.DEFAULTS.layers)
    block = {"fibril": {"file": "6cu7.pdb.gz"}, "domain": None,
             "sources": {"rise": "6cu7.pdb.gz: measured over 36 layer pairs"}}
    values, sources = panel_sources(panel, {"rise": 4.8251234, "twist": 0.5}, block)
    assert values["rise"] == 4.8251234  # the result runs the measurement, not its float32
    assert sources["rise"] == "6cu7.pdb.gz: measured over 36 layer pairs"
    assert sources["linker"] == SIDEBAR and sources["layers"] == "default"
    assert sources["twist"] == "default"  # the panel holds the default, not the measured twist
    assert values["twist"] == panel["twist"]


def test_a_kept_result_names_the_values_the_panel_no_longer_holds():
    then = {"layers": 20, "linker": 6, "domain_linker": (10,), "globule_diameter": 30.0}
    now = dict(then, layers=6, domain_linker=[10], globule_diameter=float(np.float32(30.0)))
    assert changed_names(then, now) == ["layers"]
    assert changed_names(then, dict(now, linker=7), ignore=("linker",)) == ["layers"]
    assert changed_names(then, then) == []
