"""The sidebar's Load case and Save case: the same files as --case and --save-case."""
import json
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


def test_a_case_loaded_and_run_in_the_panel_gives_the_command_lines_result(ui, tmp_path):
    """examples/hnrnpdl2_7zir.toml (every value not the default: slab, linker 25, 36 Å, twist,
    score layers) on 6 layers with 2 scored, set the same way in both: Load case and Run all
    as their buttons call them, then `run --case` (8 s on bpy 5.0.1, 2026-11-26: fits)."""
    from fibrilfit import cli
    from fibrilfit.ui.operators import common
    from fibrilfit.builders import find_model
    from helpers import ROOT
    from test_reliability import _as_the_ui
    case = ROOT / "examples" / "hnrnpdl2_7zir.toml"
    assert _as_the_ui("fibrilfit", "load_case", filepath=str(case)) == {"FINISHED"}
    assert (ui.linker, ui.globule_diameter) == (25, 36.0)
    ui.layers, ui.score_layers = 6, 2  # the override, as --layers 6 --score-layers 2 below
    assert _as_the_ui("fibrilfit", "run_all") == {"FINISHED"}
    panel = json.loads(find_model(bpy.context.scene).root[common.RESULT])
    out = tmp_path / "cli.json"
    assert cli.main(["run", "--case", str(case), "--layers", "6", "--score-layers", "2",
                     "--json", str(out)]) == 0
    line = json.loads(out.read_text())
    assert panel["params"] == line["params"]
    for key in ("verdict", "answer", "accommodated", "clashing_pairs", "max_bond_stretch",
                "frames_simulated", "globule_centres", "bound"):
        assert panel[key] == line[key], key
    assert line["answer"] == "fits"


def test_loading_a_case_with_structure_files_says_they_are_not_measured(ui):
    """`run --case` measures a case's [structure] files; Load case does not (yet): it says so
    rather than leaving the panel at values the case never meant."""
    from helpers import ROOT
    from fibrilfit.ui.operators import cases as case_ops
    from test_ui import detached
    op = detached(case_ops.FIBRILFIT_OT_load_case)
    op.filepath = str(ROOT / "examples" / "asyn_2n0a_gfp.toml")
    assert op.execute(bpy.context) == {"FINISHED"}
    assert op.reports[0] == ({"WARNING"}, "Load case does not read the case's structure files "
                                          "(2n0a.pdb.gz, 1gfl.pdb.gz): Import fibril… and "
                                          "Import domain… measure them into the panel, as "
                                          "`run --case` does")
