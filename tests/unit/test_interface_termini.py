"""Protofilaments at their measured turns and interface termini (issue #50 items 2-3;
docs/guide/structures.md#interface-termini) on two deposited fibrils the model refused
(tests/data/README.md#interface-termini-issue-50). No bpy."""
from __future__ import annotations

import math
import pathlib

import numpy as np
import pytest

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


def test_6zrr_interface_terminus_is_measured_and_the_refusal_says_so():
    """6ZRR: protofilament 1's Thr47 lies 23.6 Å deep between the other two; its own way out,
    through every protofilament's atoms, spends 2 residues; protofilament 0's copy turned onto
    it starts 9.2 Å inside the core. The refusal names the measurement and the way on."""
    with pytest.raises(ParamError) as err:
        resolve(fibril=SIX_ZRR)
    text = str(err.value)
    assert text.startswith("anchor: protofilament 1's copy")
    assert "THR47" in text and "2 residue(s) spent" in text and "--protofilaments 1" in text
    g = F.measure(SIX_ZRR)
    own = termini.own_termini(SIX_ZRR, g)
    assert [t["residue"] for t in own] == [47, 47, 47]
    assert own[1]["exit_found"] and own[1]["exit_residues"] == 2
    assert own[0]["exit_residues"] == 0  # protofilament 0's exit: the measurement's, unchanged
    # what the refusal offers builds: protofilament 0's chains, the whole section as the core
    p = resolve(fibril=SIX_ZRR, protofilaments=1).p
    assert p.protofilaments == 1 and len(p.core_outline) == len(g.core_outline)


def test_inspect_says_what_run_will_do():
    """`inspect` and `run` agree: a fibril `inspect` reads, `run` builds, or `inspect` says why
    it will not, in run's own words."""
    refused = inspect(fibril=SIX_ZRR)
    assert refused["run"]["builds"] is False
    with pytest.raises(ParamError) as err:
        resolve(fibril=SIX_ZRR)
    assert refused["run"]["refusal"] == str(err.value)
    assert refused.text.splitlines()[-1].startswith("run: refuses")
    built = inspect(fibril=SEVEN_RL4)
    assert built["run"] == {"builds": True, "refusal": None}


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
    """tools/deposited_survey.py on 6ZRR: read, refused by run (and inspect said so), built
    with --protofilaments 1, the exits of both termini measured; the summary counts it."""
    import importlib.util
    spec = importlib.util.spec_from_file_location(
        "deposited_survey", DATA.parents[1] / "tools" / "deposited_survey.py")
    survey = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(survey)
    row = survey.survey_file(pathlib.Path(SIX_ZRR))
    assert row["read"] is True and row["inspect_run"] == "refuses"
    assert row["built_C"] is False and row["refusal_C"].startswith("anchor: protofilament 1's")
    assert row["built_C_pf1"] is True and row["bound_C"] == ""
    assert row["exit_C"] == "0" and row["exit_N"] != ""
    text = survey.summary([row])
    assert "`run` builds 0 of them" in text and "`--protofilaments 1`: 1 of 1" in text


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
