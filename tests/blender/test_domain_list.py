"""The sidebar's list of a chain's domains (issue #33, docs/guide/sidebar.md#domains): Import
domain… adds one, Import full-length model… fills it as `--full-length` segments, remove and
move; the panel's Params are the command line's for the same options, exactly; bad input is one
sentence and changes nothing; the user's objects are left alone."""
import types

import bpy
import pytest

from fibrilfit.api import model as resolved_model
from fibrilfit.api.plans import RunPlan, make_plan
from fibrilfit.cli import build_parser
from fibrilfit.ui import domain_list, panels, properties
from full_length_model import two_domain_model
from helpers import ROOT, snapshot_user

DATA = ROOT / "tests" / "data"
UBQ, FIBRIL = str(DATA / "1ubq.pdb.gz"), str(DATA / "6cu7.pdb.gz")


def cli_params(*argv):
    """The Params `run ARGV` would run with (the command line's own parser, plan and merge)."""
    args = vars(build_parser().parse_args(["run", *argv]))
    args.pop("command")
    plan, _ = make_plan(RunPlan, args, case=args.pop("case", None), command="run")
    return resolved_model.resolve(plan).p


def names(ui) -> list:
    return [e.name.split(",")[0] for e in ui.domains]


def main_panel(log):
    """The main panel's draw() into a strict stand-in layout (ui_fakes.FakeLayout)."""
    from ui_fakes import FakeLayout
    panels.FIBRILFIT_PT_main.draw(types.SimpleNamespace(layout=FakeLayout(log)), bpy.context)
    return log


def renumbered(tmp_path, shift: int) -> str:
    """Ubiquitin numbered from 1 + shift (a small domain: each measurement is a few seconds)."""
    import gemmi
    st = gemmi.read_structure(UBQ)
    for ch in st[0]:
        for res in ch:
            res.seqid.num += shift
    out = tmp_path / f"ubq{shift}.pdb"
    st.write_pdb(str(out))
    return str(out)


def test_two_imported_domains_give_the_command_lines_params(registered, scene, user_objects,
                                                            tmp_path):
    """Ubiquitin as 128-203 then 230-305: 26 residues between from their numbering, as the
    command line takes it; the user's linker in the list as --domain-linker."""
    ui, before = registered, snapshot_user(user_objects)
    near, far = renumbered(tmp_path, 127), renumbered(tmp_path, 229)
    assert bpy.ops.fibrilfit.import_domain(filepath=near) == {"FINISHED"}
    one = main_panel([])
    assert not any(k == "template_list" for k, _ in one)  # one domain: the single globule's look
    assert properties.read_params(ui) == cli_params("--domain", near)
    assert bpy.ops.fibrilfit.import_domain(filepath=far) == {"FINISHED"}
    assert names(ui) == ["ubq127.pdb A 128-203", "ubq229.pdb A 230-305"]
    assert ui.domains[0].linker == 26
    p = properties.read_params(ui)
    assert p == cli_params("--domain", near, "--domain", far)
    assert p.domain_linker == (26,) and p.domain_diameters == (30.276,) and p.further_atoms is None
    ui.domains[0].linker, ui.domain_shape = 7, "hull"
    p = properties.read_params(ui)
    assert p == cli_params("--domain", near, "--domain", far, "--domain-linker", "7",
                           "--domain-shape", "hull")
    assert p.domain_linker == (7,) and p.several_shapes
    log = main_panel([])
    assert ("template_list", "domains") in log
    assert {"fibrilfit.domain_move", "fibrilfit.domain_remove"} <= {n for k, n in log
                                                                     if k == "operator"}
    rows = []  # each row: its short name (issue #45: the linker is set under the list)
    for i, item in enumerate(ui.domains):
        from ui_fakes import FakeLayout
        domain_list.FIBRILFIT_UL_domains.draw_item(None, bpy.context, FakeLayout(rows), ui,
                                                   item, 0, ui, "domain_index", i)
    assert rows == [("label", "ubq127 A 128-203, 30 Å"), ("label", "ubq229 A 230-305, 30 Å")]
    assert ("prop", "linker") in log  # the selected domain's linker to the next, under it
    assert snapshot_user(user_objects) == before
    assert len(scene.objects) == len(user_objects) + 2  # and each domain's CA trace (#45)


def test_a_full_length_model_gives_the_command_lines_params(registered, scene, tmp_path):
    """tests/full_length_model.py's chain: ubiquitin 118-193 and GFP 209-438 after 6CU7's core,
    20 residues from K97 (linker 21 with the anchor) and 15 between the two."""
    ui, model = registered, str(two_domain_model(tmp_path / "fl.pdb"))
    assert bpy.ops.fibrilfit.import_fibril(filepath=FIBRIL) == {"FINISHED"}
    assert bpy.ops.fibrilfit.import_full_length(filepath=model) == {"FINISHED"}
    assert names(ui) == ["fl.pdb A 118-193", "fl.pdb A 209-438"]
    assert ui.domains[0].linker == 15 and ui.linker == 21
    assert properties.read_params(ui) == cli_params("--fibril", FIBRIL, "--full-length", model)
    # the list's linker is editable: the command line's --domain-linker over the numbering's
    ui.domains[0].linker, ui.domain_shape = 9, "spheres"
    assert properties.read_params(ui) == cli_params("--fibril", FIBRIL, "--full-length", model,
                                                    "--domain-shape", "spheres",
                                                    "--domain-linker", "9")


def test_move_and_remove_reorder_the_chain(registered, scene, user_objects, tmp_path):
    ui, before = registered, snapshot_user(user_objects)
    near, far = renumbered(tmp_path, 127), renumbered(tmp_path, 229)
    for path in (UBQ, near, far):
        assert bpy.ops.fibrilfit.import_domain(filepath=path) == {"FINISHED"}
    ui.domains[0].linker, ui.domains[1].linker = 4, 5
    ui.domain_index = 1
    assert bpy.ops.fibrilfit.domain_move(direction="UP") == {"FINISHED"}
    assert names(ui) == ["ubq127.pdb A 128-203", "1ubq.pdb.gz A 1-76", "ubq229.pdb A 230-305"]
    assert ui.domain_index == 0
    assert properties.read_params(ui) == cli_params(
        "--domain", near, "--domain", UBQ, "--domain", far, "--domain-linker", "5,4")
    assert bpy.ops.fibrilfit.domain_move(direction="DOWN") == {"FINISHED"}
    assert names(ui)[:2] == ["1ubq.pdb.gz A 1-76", "ubq127.pdb A 128-203"]
    assert ui.domain_index == 1
    assert bpy.ops.fibrilfit.domain_remove() == {"FINISHED"}  # ubq127
    assert names(ui) == ["1ubq.pdb.gz A 1-76", "ubq229.pdb A 230-305"] and ui.domain_index == 1
    assert properties.read_params(ui) == cli_params("--domain", UBQ, "--domain", far,
                                                    "--domain-linker", "4")
    for _ in range(2):
        assert bpy.ops.fibrilfit.domain_remove() == {"FINISHED"}
    # none: the panel's own values, the globule keeping the size it had
    assert properties.read_params(ui) == cli_params("--globule-diameter", "30.276")
    assert snapshot_user(user_objects) == before


def test_bad_input_is_one_sentence_and_changes_nothing(registered, scene, tmp_path, ff,
                                                       capsys):
    ui = registered
    assert bpy.ops.fibrilfit.import_domain(filepath=UBQ) == {"FINISHED"}
    before = (names(ui), properties.values(ui))
    for op, kw, words in (
            (bpy.ops.fibrilfit.import_full_length, {"filepath": str(tmp_path / "x.pdb")},
             "import the fibril first"),
            (bpy.ops.fibrilfit.import_domain, {"filepath": FIBRIL}, "Domain file: 6cu7.pdb.gz"),
            (bpy.ops.fibrilfit.domain_move, {"direction": "UP"}, "already the first")):
        with pytest.raises(RuntimeError, match=words) as caught:  # an ERROR report raises
            op(**kw)
        assert len(str(caught.value).strip().splitlines()) == 1
        assert (names(ui), properties.values(ui)) == before
    assert bpy.ops.fibrilfit.import_fibril(filepath=FIBRIL) == {"FINISHED"}
    before = (names(ui), properties.values(ui))
    with pytest.raises(RuntimeError, match="do not cover the fibril's core"):
        bpy.ops.fibrilfit.import_full_length(filepath=UBQ)  # not in the fibril's numbering
    assert (names(ui), properties.values(ui)) == before
    # the linker on the core's N side: the model's N-terminal tail is no domain; the panel says
    # what the command line says
    model = str(two_domain_model(tmp_path / "fl.pdb"))
    assert bpy.ops.fibrilfit.import_fibril(filepath=FIBRIL, terminus="N") == {"FINISHED"}
    before = (names(ui), properties.values(ui))
    with pytest.raises(RuntimeError) as caught:
        bpy.ops.fibrilfit.import_full_length(filepath=model)
    assert (names(ui), properties.values(ui)) == before
    assert ff.cli.main(["run", "--fibril", FIBRIL, "--terminus", "N", "--full-length", model,
                        "--json", str(tmp_path / "r.json")]) == 2
    said = capsys.readouterr().err.strip()
    assert said == "fibrilfit: error: --full-length: no folded domain (pLDDT >= 70 over at " \
                   "least 40 residues) on the linker's side of the core in fl.pdb"
    assert str(caught.value).strip() == "Error: " + said.removeprefix(  # in the panel's words
        "fibrilfit: error: ").replace("--full-length", "Full-length model")


def test_load_case_replaces_the_list(registered, scene, tmp_path):
    ui = registered
    for _ in range(2):
        bpy.ops.fibrilfit.import_domain(filepath=UBQ)
    case = tmp_path / "c.toml"
    case.write_text('[params]\nglobule_diameter = 25.0\n')
    assert bpy.ops.fibrilfit.load_case(filepath=str(case)) == {"FINISHED"}
    assert len(ui.domains) == 0
    p = properties.read_params(ui)
    assert p.globule_diameter == 25.0 and p.domain_diameters is None
