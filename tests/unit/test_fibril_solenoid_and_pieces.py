"""A β-solenoid (2KJ3, HET-s(218-289): two rungs per molecule) and a core in two pieces (9XBO,
Sup35 NM: 5-65 and 102-132), read from the files of tests/data/README.md (issue #47 items 1-2;
docs/guide/structures.md#beta-solenoids, docs/guide/structures.md#cores-in-pieces)."""
import importlib
import math

import numpy as np
import pytest
from fibrilfit.geom import polygons, rigid
from fibrilfit.structure.fibril import layer_frame, reference_chains
from fibrilfit.structure.inspect_text import text as inspect_text
from helpers import ROOT

DATA = ROOT / "tests" / "data"


@pytest.fixture(scope="module")
def S():
    return importlib.import_module("fibrilfit.structure")


@pytest.fixture(scope="module")
def het_s(S):
    return {end: S.measure_fibril(DATA / "2kj3.pdb.gz", terminus=end) for end in ("C", "N")}


@pytest.fixture(scope="module")
def sup35(S):
    return {end: S.measure_fibril(DATA / "9xbo.pdb.gz", terminus=end) for end in ("C", "N")}


def _ca_in_frame(S, g, residues):
    """The reference chain's CAs of `residues` in the model's layer frame (x, y, z)."""
    origin, frame = layer_frame(g)
    ref = reference_chains(DATA / g.file, g)[0]
    return (ref.ca_of(residues) - origin) @ frame.T


def _inside(poly, xy, slack):
    """Points inside the polygon, or within `slack` Å of its edge."""
    pts = np.atleast_2d(xy)
    inside = polygons.even_odd(np.asarray(poly, float), pts)
    dist, _ = polygons.edge_distance(np.asarray(poly, float), pts)
    return inside | (dist <= slack)


def test_het_s_is_a_two_rung_solenoid_one_molecule_a_layer(het_s):
    g = het_s["C"]
    assert g.rungs == 2 and g.layers == 10 and g.protofilaments == 1
    assert g.layer_chains == [list("ABCDEFGHIJ")]  # one molecule per layer, in file order here
    # the molecule's rise, as this file's stack gives it (its molecules kink every second
    # step: 9.2-9.3 Å within a pair, 8.1 Å across; cryo-EM 9.4 Å), twice the rungs' spacing
    assert g.rise == pytest.approx(8.43, abs=0.05) and g.rise_sd == pytest.approx(0.67, abs=0.05)
    assert g.rung_rise == pytest.approx(4.48, abs=0.05)
    assert g.rise / g.rung_rise == pytest.approx(2.0, abs=0.25)
    assert g.twist < 0 and not g.axis_exact  # left-handed; the warning says the axis is approximate
    assert any("axis approximate" in w for w in g.warnings)


def test_het_s_core_is_both_rungs_and_the_anchor_the_last_rung_residue(S, het_s):
    g = het_s["C"]
    # the residues stacked rung on rung in every chain: 224-249 and 259-282 (the loop between
    # them, 250-258, and the termini are not)
    assert g.core_segments == [[224, 249], [259, 282]] and g.core_residues == [224, 282]
    a = g.anchors[0]
    assert (a["residue"], a["residue_name"]) == (282, "GLY")
    assert g.tail_residues == [283, 295]  # the modelled C-terminal tail: linker
    n = het_s["N"].anchors[0]
    assert n["residue"] == 224 and het_s["N"].tail_residues == [217, 223]
    # the outline is the molecule's: both rungs' CAs lie in it (within a CA's 1.9 Å)
    rungs = [r for a0, b0 in g.core_segments for r in range(a0, b0 + 1)]
    ca = _ca_in_frame(S, g, rungs)
    assert _inside(g.core_outline, ca[:, :2], 1.9).all()
    # and the reference molecule spans both rungs: its CAs' heights spread over ~a rung's rise
    assert np.ptp(ca[:, 2]) > 0.8 * g.rung_rise


def test_het_s_model_values_one_domain_per_molecule(S, het_s):
    g = het_s["C"]
    values = S.model_values(g)
    assert values["rise"] == g.rise > 2 * 4.0  # a layer of the model is a molecule, two rungs
    assert values["twist"] == g.twist
    assert len(values["core_outline"]) == len(g.core_outline)
    assert values["linker"] == 1 + 295 - 283 + 1  # the anchor and the modelled tail


def test_inspect_says_what_it_measured(het_s, sup35):
    text = inspect_text(het_s["C"])
    assert "β-solenoid, 2 rungs per molecule, one molecule per 8.4 Å" in text
    assert "core residues 224-249, 259-282 (250-258 between them" in text
    text = inspect_text(sup35["C"])
    assert "core residues 5-65, 102-132 (66-101 between them: inside the fibril, not " in text
    assert "anchor pf 0: I GLN132" in text and "(linker)" not in text


def _regular_solenoid(tmp_path, layers=6):
    """2KJ3's chain B stacked on itself by its own step to C (a regular helix, exact copies):
    the expected rise and twist are that screw's."""
    import gemmi
    st = gemmi.read_structure(str(DATA / "2kj3.pdb.gz"))
    b, c = st[0]["B"], st[0]["C"]
    core = range(224, 283)
    pick = (lambda ch: np.array([[r["CA"][0].pos.x, r["CA"][0].pos.y, r["CA"][0].pos.z]
                                 for r in ch if r.seqid.num in core]))
    R, t, _ = rigid.superpose(pick(b), pick(c))
    n, _, angle, shift = rigid.screw_axis(R, t)
    model = gemmi.Model("1")
    Rk, tk = np.eye(3), np.zeros(3)
    for k in range(layers):
        copy = gemmi.Model("1")
        copy.add_chain(b.clone())
        copy.transform_pos_and_adp(gemmi.Transform(gemmi.Mat33(Rk.tolist()), gemmi.Vec3(*tk)))
        ch = copy[0].clone()
        ch.name = "ABCDEFGH"[k]
        model.add_chain(ch)
        Rk, tk = R @ Rk, R @ tk + t
    out = gemmi.Structure()
    out.add_model(model)
    out.setup_entities()
    f = tmp_path / "regular_2kj3.pdb"
    out.write_pdb(str(f))
    return f, abs(shift), angle * math.copysign(1.0, shift)


def test_a_regular_solenoid_gives_its_screw_exactly(S, tmp_path):
    f, rise, twist = _regular_solenoid(tmp_path)
    g = S.measure_fibril(f)
    assert g.rungs == 2 and g.layers == 6 and g.axis_exact
    assert g.rise == pytest.approx(rise, abs=1e-3) and g.twist == pytest.approx(twist, abs=1e-5)
    assert rise == pytest.approx(8.85, abs=0.01)  # chain B to C of the file, on 224-282
    assert g.rise / g.rung_rise == pytest.approx(2.0, abs=0.25)
    # chain B's own rung pairs alone (the file's ten chains agree on fewer: 224-249, 259-282)
    assert g.core_segments == [[222, 249], [257, 285]] and g.anchors[0]["residue"] == 285


def test_sup35_core_in_two_pieces(S, sup35):
    g = sup35["C"]
    assert g.rungs == 1 and g.rise == pytest.approx(4.814, abs=0.002)  # one rung: as before
    assert g.core_segments == [[5, 65], [102, 132]] and g.core_residues == [5, 132]
    a = g.anchors[0]
    assert (a["residue"], a["residue_name"]) == (132, "GLN")  # the chain's last ordered residue
    assert g.tail_residues == []  # 66-101 is inside the fibril, 102-132 core: no linker tail
    assert "linker" not in S.model_values(g)
    n = sup35["N"].anchors[0]
    assert n["residue"] == 5 and sup35["N"].tail_residues == []
    # the outline holds both segments: every CA of 5-65 and of 102-132 (within a CA's 1.9 Å)
    for lo, hi in g.core_segments:
        ca = _ca_in_frame(S, g, list(range(lo, hi + 1)))
        assert _inside(g.core_outline, ca[:, :2], 1.9).all(), (lo, hi)


def test_one_piece_cores_have_one_segment(S):
    for name, core in (("6cu7", [38, 97]), ("2n0a", [29, 97]), ("5oqv_addedH", [1, 42])):
        g = S.measure_fibril(DATA / f"{name}.pdb.gz")
        assert g.core_segments == [core] and g.core_residues == core and g.rungs == 1


def test_an_anchor_inside_the_core_counts_no_later_segment_as_linker(S):
    # --anchor-residue 65, the end of 9XBO's first segment: 102-132 are core, 66-101 inside
    g = S.measure_fibril(DATA / "9xbo.pdb.gz", anchor_residue=65)
    assert g.anchors[0]["residue"] == 65 and g.tail_residues == []
    # 2KJ3's first rung's end: the tail is the modelled C-terminus beyond the second rung
    g = S.measure_fibril(DATA / "2kj3.pdb.gz", anchor_residue=249)
    assert g.anchors[0]["residue"] == 249 and g.tail_residues == [283, 295]


def test_a_globular_beta_sheet_is_not_a_solenoid(S):
    # 1GFL's two GFP chains: strands 4.2-5.6 Å apart in each barrel, but not along a stack
    with pytest.raises(S.StructureError, match="nor does a chain stack on itself as a β-solenoid"):
        S.measure_fibril(DATA / "1gfl.pdb.gz")


def test_a_solenoid_given_as_a_domain_is_refused(S):
    with pytest.raises(S.StructureError, match="holds a stacked fibril \\(10 chains"):
        S.measure_domain(DATA / "2kj3.pdb.gz")
