"""Protofilaments at their measured turns and interface termini (issue #50 items 2-3;
docs/guide/structures.md#interface-termini) on two deposited fibrils the model refused
(tests/data/README.md#interface-termini-issue-50). No bpy."""
from __future__ import annotations

import math
import pathlib

import numpy as np
import pytest
from docs_rows import page_text

from fibrilfit.api import inspect
from fibrilfit.api import model as M
from fibrilfit.api.plans import RunPlan, make_plan
from fibrilfit.model import helix, params as P
from fibrilfit.model.param_spec import ParamError
from fibrilfit.structure import fibril as F, termini

DATA = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data"
SIX_ZRR, SEVEN_RL4 = str(DATA / "6zrr.pdb.gz"), str(DATA / "7rl4.pdb.gz")


def resolve(**values):
    return M.resolve(make_plan(RunPlan, values)[0])


@pytest.fixture(scope="module")
def rl4():
    return F.measure(SEVEN_RL4)


def test_7rl4_builds_with_each_protofilament_at_its_measured_turn(rl4):
    """7RL4's four protofilaments stand at 0, 8.1, 138.1 and 178.2° in the file: the model put
    protofilament j at j × 8.1° (protofilament 2's copy of the anchor then lay in the core)."""
    turns = [math.degrees(a) for a, _ in rl4.pf_offsets]
    assert rl4.protofilaments == 4
    assert turns == pytest.approx([0.0, 8.1, 138.1, 178.2], abs=0.1)
    p = resolve(fibril=SEVEN_RL4).p
    assert p.pf_turns is not None and len(p.pf_turns) == 4
    angle, height = helix.chain_transforms(p)
    _, pf = helix.chain_layers(p)
    for j in range(4):  # layer 0's chain of protofilament j at the file's turn and rise
        assert angle[j] == pytest.approx(rl4.pf_offsets[j][0])
        assert height[j] == pytest.approx(rl4.pf_offsets[j][1])
    # the same values with one turn for every step (as before): refused, protofilament 2's copy
    with pytest.raises(ParamError, match="protofilament 2's copy"):
        p.replace(pf_turns=None)


def test_explicit_protofilament_values_take_the_measured_turns_with_them():
    plan = make_plan(RunPlan, {"fibril": SEVEN_RL4, "pf_rotation": math.pi})[0]
    values, block, _ = M.measured_values(plan.structure, plan.given())
    assert values.get("pf_turns") is None
    assert "pf_turns" in block["overridden"] and "pf_turns" not in block["applied"]


def test_without_pf_turns_the_protofilaments_are_placed_as_before():
    """No pf_turns: j × pf_angle and j × pf_rise exactly (every case of the gallery)."""
    p = P.make_params(protofilaments=2, pf_rotation=3.1295, pf_rise=2.41, layers=5)
    angle, height = helix.chain_transforms(p)
    k, j = helix.chain_layers(p)
    assert np.array_equal(angle, p.twist * k.astype(float) + j.astype(float) * p.pf_angle)
    assert np.array_equal(height, p.rise * k.astype(float) + j.astype(float) * p.pf_rise)
    assert p.pf_rise_step == abs(p.pf_rise)


def test_anchors_that_coincide_only_under_one_turn_for_all():
    """7QJX's four protofilaments at 0, 179.5, -118.1 and -13.5°: one turn of 179.5° for every
    step puts protofilament 2 at 359°, its anchor on protofilament 0's (the pilot's "1.10 Å
    apart"); at the measured turns the anchors are apart."""
    degs = [0.0, 179.5, -118.1, -13.5]
    common = dict(protofilaments=4, pf_rise=0.0, layers=5)
    with pytest.raises(ParamError, match="protofilaments [02] and [02] would start"):
        P.make_params(pf_rotation=math.radians(179.5), **common)
    p = P.make_params(pf_rotation=math.radians(179.5),
                      pf_turns=[[math.radians(d), 0.0] for d in degs], **common)
    xy = np.array([np.cos(p.pf_offsets()[0]), np.sin(p.pf_offsets()[0])]).T * p.anchor_x
    gaps = np.linalg.norm(xy[:, None] - xy[None], axis=-1)[np.triu_indices(4, 1)]
    assert gaps.min() > 2 * p.residue_radius


@pytest.mark.parametrize("rows, words", [([[0.0, 0.0], [1.0, 0.0]], "one row"),
                                         ([[0.1, 0.0], [1.0, 0.0], [2.0, 0.0]], "the first")])
def test_pf_turns_must_match_the_protofilaments(rows, words):
    with pytest.raises(ParamError, match=f"pf_turns: .*{words}"):
        P.make_params(protofilaments=3, pf_turns=rows)


@pytest.fixture(scope="module")
def zrr():
    """6ZRR as `run` models it (the survey's GFP ball, linker 12, the infinite fibril)."""
    return resolve(fibril=SIX_ZRR, globule_diameter=44.0, linker=12, periodic="auto")


def test_6zrr_interface_terminus_builds_as_it_is(zrr):
    """6ZRR: protofilament 1's Thr47 lies 23.6 Å deep between the other two; protofilament 0's
    copy turned onto it started 9.2 Å inside the core (refused before). Now each protofilament
    has its own anchor, where its own way out (measured through every protofilament's atoms)
    leaves the outline, and its own exit: protofilament 1's spends 2 residues, 0 and 2 none."""
    g = F.measure(SIX_ZRR)
    own = termini.own_termini(SIX_ZRR, g)
    assert [t["residue"] for t in own] == [47, 47, 47]
    assert own[1]["exit_found"] and own[1]["exit_residues"] == 2
    assert own[0]["exit_residues"] == 0  # protofilament 0's exit: the measurement's, unchanged
    p = zrr.p
    rows = np.asarray(p.pf_anchors)
    assert rows[:, 2].tolist() == [0, 2, 0]
    for j, t in enumerate(own):  # each row is the protofilament's own measured anchor
        assert rows[j, :2] == pytest.approx(t["anchor"], abs=1e-9)
    assert rows[0, :2] == pytest.approx(p.anchor_xy)
    assert p.exit_residues == 0 and p.exit_spent == 2 and p.free_linker == 10
    # protofilament 1's own path drawn: its rows, the buried CA first, ending near its anchor
    paths = np.asarray(p.pf_exit_paths)
    assert set(paths[:, 0]) == {1.0}
    assert np.linalg.norm(paths[0, 1:3] - np.asarray(own[1]["ca"])[:2]) < 2e-3  # 3 decimals
    assert np.linalg.norm(paths[-1, 1:3] - rows[1, :2]) < 2 * p.residue_radius + 0.5
    assert "pf_anchors" in zrr.block["applied"]
    assert zrr.block["sources"]["pf_anchors"].startswith("6zrr.pdb.gz: measured")
    src = M.param_sources({}, p, zrr.block)
    assert src["pf_anchors"].startswith("6zrr.pdb.gz: measured")
    # the result's exit: protofilament 0's, and each protofilament's own with the free linker
    from fibrilfit.structure.from_files import exit_block
    way = exit_block(p, zrr.block)
    assert way["residues"] == 0 and way["pf_residues"] == [0, 2, 0] and way["free_linker"] == 10
    # what was refused before is refused without the measured rows (the copies as they were)
    with pytest.raises(ParamError, match="protofilament 1's copy"):
        p.replace(pf_anchors=None, pf_exit_paths=None)


def test_each_protofilament_starts_where_its_own_terminus_leaves(zrr):
    """Layer k's chain of protofilament j starts at protofilament j's own anchor turned by k
    twists (not protofilament 0's turned by j's turn), outside the core, its chain clear of it."""
    from fibrilfit.geom import polygons
    from fibrilfit.model.start_layout import rest_positions
    p = zrr.p
    pos = rest_positions(p)
    k, j = helix.chain_layers(p)
    own = np.asarray(p.pf_anchors)[:, :2]
    outline = p.outline()
    for c in range(p.chains):
        back = helix.turn_xy(pos[c, :, 0], pos[c, :, 1], -k[c] * p.twist)
        assert back[0] == pytest.approx(own[j[c]], abs=1e-9)
        assert not polygons.inside(outline, back).any()  # every member outside the core
        assert pos[c, 0, 2] == pytest.approx(k[c] * p.rise + p.pf_offsets()[1][j[c]])
    copy = polygons.rotate(np.asarray(p.anchor_xy), p.pf_offsets()[0][1])
    assert np.linalg.norm(copy - own[1]) > 5.0  # the copy would be far from it (9.2 Å deep)


def test_the_bound_uses_each_protofilaments_own_free_linker(zrr):
    """The proven bound with each protofilament's own exit: protofilament 1 spends 2 residues,
    0 and 2 none, so their domains reach 2 residue spacings further (stretched) than the model's
    chains (the smallest free linker governs the simulation). The bound lies between the bounds
    with every protofilament spending 0 and spending 2 (lengths are monotone)."""
    from fibrilfit.model import bound as B
    p = zrr.p
    terms = B.reach_terms(p)
    own = B.pf_reach(p, terms, 12)
    step = 2 * p.residue_spacing * (1 + p.stretch_tolerance)
    assert own[0, 0] - own[1, 0] == pytest.approx(step)
    assert own[1, 0] == pytest.approx(B.reach(p, terms, 12)[0])
    b = B.linker_bound(p)
    assert b["pf_exit_residues"] == [0, 2, 0]
    rows = np.asarray(p.pf_anchors)
    low = B.linker_bound(p.replace(pf_anchors=[[*r[:2], 0] for r in rows]))
    high = B.linker_bound(p.replace(pf_anchors=[[*r[:2], 0 if i == 0 else 2]
                                                for i, r in enumerate(rows)]))
    assert low["impossible_below"] <= b["impossible_below"] <= high["impossible_below"]
    # measured: 9 with no exit anywhere, 11 with every protofilament spending 2, 10 as it is
    assert (low["impossible_below"], b["impossible_below"], high["impossible_below"]) == (9, 10, 11)


def test_own_anchors_on_top_of_each_other_are_refused_with_the_measurement():
    """Two protofilaments whose own anchors (rows measured from a file) lie 1 Å apart: refused,
    naming both anchors and the way on."""
    values, _, measured = M.measured_values(make_plan(RunPlan, {"fibril": SIX_ZRR})[0].structure,
                                            {})
    values, _ = termini.as_they_are(values, measured, {})
    rows = [list(r) for r in values["pf_anchors"]]
    rows[2][:2] = [rows[0][0] + 1.0, rows[0][1]]  # protofilament 2 on protofilament 0's anchor
    with pytest.raises(ParamError) as err:
        termini.make_params({**values, "pf_anchors": rows}, measured, {})
    text = str(err.value)
    # 1 Å apart across, 1.92 Å in 3-D with protofilament 2's rise
    assert text.startswith("pf_anchors: the file's own protofilaments 0 and 2 start 1.92 Å apart")
    assert "--protofilaments 1" in text


def test_a_sealed_own_exit_is_refused_with_the_measurement(monkeypatch):
    """Protofilament 1's own terminus with no way out (planted in the measurement): refused,
    with what was measured and --protofilaments 1."""
    real = termini.own_termini

    def sealed(*a, **k):
        out = real(*a, **k)
        out[1] = {**out[1], "exit_found": False, "exit_length": None, "exit_residues": None,
                  "path": None}
        return out
    monkeypatch.setattr(termini, "own_termini", sealed)
    with pytest.raises(ParamError, match=r"anchor: protofilament 1's own terminus, chain I "
                                         r"THR47 .*is sealed.*--protofilaments 1"):
        resolve(fibril=SIX_ZRR)


@pytest.mark.parametrize("rows, words", [
    ([[1.0, 0.0, 0]], "one row"), ([[0.0, 0.0, 0], [0.0, 30.0, 1]], "the first row")])
def test_pf_anchors_rows_are_checked(rows, words):
    with pytest.raises(ParamError, match=f"pf_anchors: .*{words}"):
        P.make_params(protofilaments=2, pf_anchors=rows)


def test_inspect_says_what_run_will_do():
    """`inspect` and `run` agree: a fibril `inspect` reads, `run` builds, or `inspect` says why
    it will not, in run's own words."""
    said = inspect(fibril=SIX_ZRR)
    assert said["run"] == {"builds": True, "refusal": None, "own_exits": [0, 2, 0]}
    assert resolve(fibril=SIX_ZRR).p.pf_exit_residues().tolist() == [0, 2, 0]
    assert said.text.splitlines()[-1] == (
        "run: builds (these files, nothing else given), each protofilament from its own "
        "terminus (its exit spends 0, 2, 0 residue(s); "
        "docs/guide/structures.md#interface-termini)")
    built = inspect(fibril=SEVEN_RL4)
    assert built["run"] == {"builds": True, "refusal": None}
    assert resolve(fibril=SEVEN_RL4).p.pf_anchors is None  # copies that build: as before


def test_a_direction_blocked_only_by_the_copies_says_so():
    """A C-shaped core: protofilament 0's anchor on its closed side leaves radially; its copy
    turned by 180° sits in the 8 Å notch, where no straight line gets a 44 Å globule out. The
    refusal says the copies block it, and what to do; alone, protofilament 0's chain builds."""
    outline = [[-60, -12], [20, -12], [20, 12], [-60, 12], [-60, 4], [-20, 4], [-20, -4],
               [-60, -4]]
    common = dict(core_outline=outline, anchor=[21.75, 0.0], globule_diameter=44.0, linker=2,
                  pf_rise=2.4)
    assert P.make_params(protofilaments=1, **common).chain_layout.rule == "radial"
    with pytest.raises(ParamError, match=r"no straight direction.*copies turned onto the other "
                                         r"1 protofilament\(s\) block every one: give "
                                         r"--protofilaments 1"):
        P.make_params(protofilaments=2, **common)


def test_the_survey_tool_tabulates_what_inspect_and_run_say(tmp_path):
    """tools/deposited_survey.py on 6ZRR: read, built at C through each protofilament's own
    terminus (and inspect said so), each protofilament's exit and the bound at each terminus;
    the summary counts it, the table shows it, and a second run with --resume keeps the row."""
    import importlib.util
    spec = importlib.util.spec_from_file_location(
        "deposited_survey", DATA.parents[1] / "tools" / "deposited_survey.py")
    survey = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(survey)
    row = survey.survey_file(pathlib.Path(SIX_ZRR))
    assert row["read"] is True and row["inspect_run"] == "builds" and row["error"] == ""
    assert row["built_C"] is True and row["interface_C"] is True and row["refusal_C"] == ""
    assert row["exit_C"] == "0/2/0" and row["bound_C"] == 10 and row["built_C_pf1"] == ""
    assert row["exit_N"] != "" and (row["bound_N"] != "") == row["built_N"]
    text = survey.summary([row])
    assert "C terminus: `run` builds 1 of 1 read (1 with each protofilament's own" in text
    assert "a C-terminal exit: 1 of 1 (100 %; on the surface 0, buried with a way out 1)" in text
    assert "| 6zrr.pdb.gz | yes | yes (own termini) | 0/2/0 | 10 |" in survey.table([row])
    # the page's row for 6ZRR (the Amyloid Explorer's copy, tests/data/README.md) is today's
    page = page_text(DATA.parents[1] / "docs" / "guide" / "structures.md")  # as the site shows it
    shown = [line for line in page.splitlines() if line.startswith("| 6zrr.pdb |")]
    assert shown == [survey.table([{**row, "file": "6zrr.pdb"}]).splitlines()[-1]]
    out = tmp_path / "s.csv"
    import csv
    with open(out, "w", newline="") as fh:
        w = csv.DictWriter(fh, survey.COLUMNS)
        w.writeheader()
        w.writerow(row)
    assert survey.main([str(DATA), "--csv", str(out), "--only", "6zrr.pdb.gz", "--resume"]) == 0
    with open(out, newline="") as fh:
        assert [r["file"] for r in csv.DictReader(fh)] == ["6zrr.pdb.gz"]  # not surveyed again


def test_a_sealed_exit_stays_no_exit_whatever_the_copies():
    """The copies are judged only where the model is built: a sealed exit (the Amyloid
    Explorer's 5OQV) is the answer `no exit` before any layout, as before; only the refusal of a
    copy inside the core is explained."""
    common = dict(protofilaments=2, pf_rotation=0.5)  # the copy at (19.09, 10.43): in the box
    with pytest.raises(ParamError, match="protofilament 1's copy"):
        P.make_params(**common)
    assert P.make_params(exit_residues=P.SEALED, **common).free_linker < 1
    exc = ParamError("anchor", "something else")
    assert termini.explained(exc, None, {}) is exc
