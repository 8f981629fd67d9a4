"""The sidebar's Load case and Save case: the same files as --case and --save-case."""
import types

import bpy
import pytest

from fibrilfit.model import cases, params as P
from fibrilfit.ui import properties
from fibrilfit.ui import panels


@pytest.fixture
def ui(registered):
    return registered


def test_load_then_save_keeps_parameters_and_metadata(ui, tmp_path):
    src = tmp_path / "in.toml"
    src.write_text('name = "tdp"\ndoi = "10.1/x"\nseeds = [4, 5]\n[params]\nlinker = 12\n'
                   "twist = -0.0309\nslab = [56.5, 22, 4.8]\n", encoding="utf-8")
    ui.layers = 33  # not in the file: back to its default
    assert bpy.ops.fibrilfit.load_case(filepath=str(src)) == {"FINISHED"}
    want = P.make_params(linker=12, twist=-0.0309, slab=(56.5, 22, 4.8))
    assert properties.read_params(ui) == want
    log = []
    panels.FIBRILFIT_PT_main.draw(types.SimpleNamespace(layout=_Layout(log)), bpy.context)
    assert "Case: tdp" in log
    ui.globule_diameter = 40
    out = tmp_path / "out.toml"
    assert bpy.ops.fibrilfit.save_case(filepath=str(out)) == {"FINISHED"}
    saved = cases.load(out)
    assert saved.make_params() == want.replace(globule_diameter=40.0)
    assert saved.meta == {"name": "tdp", "doi": "10.1/x"} and saved.seeds == [4, 5]


def test_a_bad_case_is_reported_and_changes_nothing(ui, tmp_path):
    src = tmp_path / "bad.toml"
    src.write_text("[params]\nlinker = 4\nglobule_diameter = -1\n", encoding="utf-8")
    before = properties.values(ui)
    with pytest.raises(RuntimeError, match="params.globule_diameter: must be a number"):
        bpy.ops.fibrilfit.load_case(filepath=str(src))
    assert properties.values(ui) == before and ui.case_metadata == ""


def test_save_case_refuses_a_bad_path(ui, tmp_path):
    with pytest.raises(RuntimeError, match="filepath: must be a file ending in .toml"):
        bpy.ops.fibrilfit.save_case(filepath=str(tmp_path / "case.txt"))


class _Layout:
    """Records labels; everything else is a no-op (test_ui.FakeLayout checks the RNA)."""

    def __init__(self, log):
        self.log = log

    def __getattr__(self, name):
        return lambda *a, **kw: self

    def label(self, text="", **kw):
        self.log.append(text)
