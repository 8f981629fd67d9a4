"""The sidebar's Load case and Save case: the same files as --case and --save-case."""
import json
import re
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
    panels.FIBRILFIT_PT_main.draw(types.SimpleNamespace(layout=Labels(log)), bpy.context)
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


class Labels:
    """Records labels; everything else is a no-op (ui_fakes.FakeLayout checks the RNA)."""

    def __init__(self, log):
        self.log = log

    def __getattr__(self, name):
        return lambda *a, **kw: self

    def label(self, text="", **kw):
        self.log.append(text)


def test_a_case_loaded_and_run_in_the_panel_gives_the_command_lines_result(ui, tmp_path):
    """examples/numbers/hnrnpdl2_7zir.toml (every value not the default: slab, linker 25, 36 Å, twist,
    score layers) on 6 layers with 2 scored, set the same way in both: Load case and Run all
    as their buttons call them, then `run --case` (8 s on bpy 5.0.1, 2026-11-26: fits)."""
    from fibrilfit import cli
    from fibrilfit.ui.operators import common
    from fibrilfit.builders import find_model
    from helpers import ROOT
    from test_reliability import _as_the_ui
    case = ROOT / "examples" / "numbers" / "hnrnpdl2_7zir.toml"
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


def _cli_params(case):
    """The Params `run --case CASE` runs with: the command line's parser, --case and merge."""
    from fibrilfit.api import model as resolved_model
    from fibrilfit.api.plans import RunPlan, make_plan
    from fibrilfit.cli import build_parser
    args = vars(build_parser().parse_args(["run", "--case", str(case)]))
    args.pop("command")
    plan, _ = make_plan(RunPlan, args, case=args.pop("case", None), command="run")
    return resolved_model.resolve(plan).p


def test_load_case_measures_the_cases_structure_files_as_run_does(ui, scene):
    """examples/asyn_6cu7_ubiquitin.toml: 6CU7 and ubiquitin (the cheapest structure case: two
    small files) measured by Load case give `run --case`'s Params, key by key; the list holds
    the domain, the fibril's trace and measurement are in place."""
    from helpers import ROOT
    from fibrilfit.ui import structure_trace
    case = ROOT / "examples" / "asyn_6cu7_ubiquitin.toml"
    ui.layers, ui.globule_diameter = 33, 50.0  # not in the file: the case's values replace them
    assert bpy.ops.fibrilfit.load_case(filepath=str(case)) == {"FINISHED"}
    panel, line = properties.read_params(ui).to_dict(), _cli_params(case).to_dict()
    assert panel.keys() == line.keys()
    for key in line:
        assert panel[key] == line[key], key
    assert panel["linker"] == 30 and panel["protofilaments"] == 2  # the case's, the file's
    assert panel["globule_diameter"] != P.DEFAULTS.globule_diameter  # measured from 1UBQ
    assert [e.name.split(",")[0] for e in ui.domains] == ["1ubq.pdb.gz A 1-76"]
    measured = structure_trace.measured(scene)
    assert measured["fibril"]["file"] == "6cu7.pdb.gz" and set(measured) == {"fibril", "domain"}
    assert json.loads(ui.case_metadata)["name"].startswith("α-synuclein 6CU7")


@pytest.mark.parametrize("what", ["missing", "not a structure"])
def test_a_case_naming_a_bad_structure_file_leaves_the_panel_unchanged(ui, scene, tmp_path,
                                                                      what):
    """A [structure] file that is not there (refused as the case is read) or is not a structure
    (refused as it is measured): one sentence, and the panel, its list and the scene as they
    were."""
    from helpers import ROOT
    if what == "not a structure":
        (tmp_path / "fibril.pdb").write_text("not a structure\n", encoding="utf-8")
    src = tmp_path / "c.toml"
    src.write_text(f'[params]\nlinker = 12\n[structure]\nfibril = "fibril.pdb"\n'
                   f'domain = "{ROOT / "tests" / "data" / "1ubq.pdb.gz"}"\n', encoding="utf-8")
    assert bpy.ops.fibrilfit.load_case(
        filepath=str(ROOT / "examples" / "numbers" / "hnrnpdl2_7zir.toml")) == {"FINISHED"}
    before, meta, objects = properties.values(ui), ui.case_metadata, len(bpy.data.objects)
    said = ("structure.fibril: no file 'fibril.pdb'" if what == "missing"
            else re.escape("fibril.pdb: not a structure (no atoms)"))
    with pytest.raises(RuntimeError, match=said) as caught:
        bpy.ops.fibrilfit.load_case(filepath=str(src))
    assert len(str(caught.value).strip().splitlines()) == 1
    assert properties.values(ui) == before and len(ui.domains) == 0
    assert ui.case_metadata == meta and json.loads(meta)["name"].startswith("hnRNPDL")
    assert len(bpy.data.objects) == objects
