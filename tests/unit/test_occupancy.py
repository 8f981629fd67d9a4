"""The mixed fibril's pattern (model/occupancy.py, issue #44): which subunits carry the domain.
No bpy: the pattern is pure numpy."""
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from fibrilfit.model import helix, occupancy as O, params as P
from fibrilfit.model.param_spec import ParamError


def test_full_occupancy_decorates_every_subunit():
    p = P.make_params(layers=12, protofilaments=2, pf_rotation=3.13, pf_rise=2.3)
    assert O.decorated(p).shape == (12, 2) and O.decorated(p).all()
    assert not O.is_mixed(p)
    assert O.decorated_chains(p).tolist() == list(range(24))


@settings(max_examples=60, deadline=None)
@given(n=st.integers(1, 400), seed=st.integers(0, 2**31 - 1),
       f=st.floats(0.0, 1.0), g=st.floats(0.0, 1.0))
def test_random_draws_are_exact_counts_and_nested(n, seed, f, g):
    lo, hi = sorted((f, g))
    p = P.make_params(layers=n)
    order = O.draw_order(n, seed)
    assert sorted(order.tolist()) == list(range(n))  # a permutation
    if int(np.floor(lo * n + 0.5)) < 1:
        with pytest.raises(ParamError, match="occupancy"):
            O.decorated(p.replace(occupancy=max(lo, 1e-6)), seed=seed)
        return
    a = O.decorated(p.replace(occupancy=lo), seed=seed)
    b = O.decorated(p.replace(occupancy=hi), seed=seed)
    assert a.sum() == int(np.floor(lo * n + 0.5)) and b.sum() == int(np.floor(hi * n + 0.5))
    assert not (a & ~b).any()  # nested: every subunit of the lower fraction is in the higher


def test_a_seed_reproduces_its_pattern_and_another_seed_draws_another():
    p = P.make_params(layers=60, occupancy=0.3, seed=7)
    first = O.decorated(p)
    assert np.array_equal(first, O.decorated(P.make_params(layers=60, occupancy=0.3, seed=7)))
    assert not np.array_equal(first, O.decorated(p.replace(seed=8)))
    assert first.sum() == 18


def test_the_random_stream_is_the_patterns_own():
    """The same seed draws different orders for different N (a cell of 12 is no prefix of 24)
    and the pattern's salt keeps it apart from a plain permutation of the seed."""
    assert not np.array_equal(O.draw_order(24, 3)[:12], O.draw_order(12, 3))
    assert not np.array_equal(O.draw_order(50, 3), np.random.default_rng(3).permutation(50))


def test_periodic_along_each_protofilament_and_over_the_fibril():
    base = dict(layers=12, protofilaments=2, pf_rotation=3.13, pf_rise=2.3, pattern="periodic",
                pattern_period=3)
    each = O.decorated(P.make_params(**base))
    assert each[:, 0].tolist() == [k % 3 == 0 for k in range(12)]
    assert np.array_equal(each[:, 0], each[:, 1])
    across = O.decorated(P.make_params(**base, pattern_across="fibril"))
    assert across.ravel().tolist() == [c % 3 == 0 for c in range(24)]
    assert across[0].tolist() == [True, False] and across[1].tolist() == [False, True]
    assert O.fraction(P.make_params(**base)) == pytest.approx(1 / 3)


def test_layers_pattern_repeats_its_letters():
    p = P.make_params(layers=7, pattern="layers", pattern_layers="A.")
    assert O.decorated(p)[:, 0].tolist() == [True, False] * 3 + [True]
    p = P.make_params(layers=6, pattern="layers", pattern_layers="a..")
    assert O.decorated(p)[:, 0].tolist() == [True, False, False] * 2


def test_the_periodic_cell_repeats_the_pattern_under_the_layer_screw():
    """In a cell of M layers chain c of image m is chain c of the cell, moved by the screw S^m
    (helix.apply_points): the pattern of the infinite fibril, read layer by layer over three
    cells, is the cell's pattern M-periodic, and it is the periodic pattern of the long fibril."""
    p = P.make_params(periodic=12, pattern="periodic", pattern_period=4)
    cell = O.decorated(p)
    long = O.decorated(p.replace(periodic=0, layers=36))
    assert np.array_equal(np.tile(cell, (3, 1)), long)
    # the images' chains sit where the long fibril's chains sit: image m of layer k is layer
    # k + m·M (the screw), so the repeated pattern is the long fibril's, position by position
    q = p.replace(periodic=0, layers=36)
    angle, height = helix.chain_transforms(q)
    for m in (1, 2):
        pts = np.column_stack([np.cos(angle[:12]), np.sin(angle[:12]), height[:12]])
        moved = helix.apply_points(p, m, pts)
        want = np.column_stack([np.cos(angle[12 * m:12 * m + 12]),
                                np.sin(angle[12 * m:12 * m + 12]), height[12 * m:12 * m + 12]])
        assert np.allclose(moved, want, atol=1e-9)
        assert np.array_equal(cell, long[12 * m:12 * m + 12])


def test_a_random_cell_repeats_with_the_cell():
    p = P.make_params(periodic=14, occupancy=0.5, seed=3)
    assert O.decorated(p).shape == (14, 1) and O.decorated(p).sum() == 7


def test_auto_cell_rounds_up_to_the_patterns_repeat():
    auto = P.make_params(periodic="auto").periodic
    p = P.make_params(periodic="auto", pattern="layers", pattern_layers="A..")
    assert p.periodic % 3 == 0 and auto <= p.periodic < auto + 3


@pytest.mark.parametrize("values, param, words", [
    (dict(occupancy=0.01, layers=20), "occupancy", "rounds to none"),
    (dict(occupancy=0), "occupancy", "from"),
    (dict(occupancy=1.5), "occupancy", "from"),
    (dict(pattern="periodic", occupancy=0.5), "occupancy", "only with pattern random"),
    (dict(pattern="layers", pattern_layers="AB"), "domain_b_diameter", "is needed"),
    (dict(domain_b_diameter=40.0), "domain_b_diameter", "pattern is random"),
    (dict(pattern="layers", pattern_layers="A.", linker_b=6), "linker_b",
     "pattern_layers has no B"),
    (dict(pattern_layers="AB", domain_b_diameter=40.0), "domain_b_diameter",
     "pattern is random"),
    (dict(pattern_layers="AB"), "pattern_layers", "only with pattern layers"),
    (dict(pattern="layers", pattern_layers="AB", domain_b_diameter=40.0, linker_b=7),
     "linker_b", "not built yet"),
    (dict(pattern="layers", pattern_layers="AB", domain_b_diameter=40.0, bare_tail=2),
     "bare_tail", "not supported yet"),
    (dict(pattern="layers", pattern_layers="AB", domain_b_diameter=40.0,
          domain_diameters=[20.0], domain_linker=[3]), "domain_diameters",
     "not supported yet"),
    (dict(pattern="layers", pattern_layers="AB", domain_b_diameter=0.1),
     "domain_b_diameter", "from"),
    (dict(pattern="layers", pattern_layers="AB", domain_b_diameter=40.0, periodic=15),
     "pattern", "multiple of 2"),
    (dict(pattern="layers", pattern_layers="A-"), "pattern_layers", "only A"),
    (dict(pattern="layers", pattern_layers=".."), "pattern_layers", "no domain"),
    (dict(pattern="layers", pattern_layers="A..", periodic=16), "pattern", "multiple of 3"),
    (dict(pattern="zigzag"), "pattern", "one of random, periodic, layers"),
    (dict(pattern_period=0), "pattern_period", "from 1"),
    (dict(bare_tail=-1), "bare_tail", "from 0"),
    (dict(layers=20, score_layers=5, occupancy=0.05, seed=1), "score_layers",
     "no decorated subunit"),
])
def test_bad_values_get_one_line_naming_the_parameter(values, param, words):
    with pytest.raises(ParamError) as exc:
        P.make_params(**values)
    assert exc.value.param == param and words in str(exc.value) and "\n" not in str(exc.value)


def test_the_printed_result_and_the_report_say_the_fraction():
    """A mixed fibril's result prints its fraction and what the answer speaks of; report.json
    carries the occupancy block (valid against its schema) and the page shows its row."""
    import json
    import jsonschema
    from helpers import ROOT
    from fibrilfit.exports import report_page, run_text
    ref = ROOT / "docs" / "reference"
    p = P.make_params(layers=20, occupancy=0.3, seed=2)
    r = json.loads((ref / "samples" / "run_result.json").read_text())
    r = {**r, "params": p.to_dict(), "occupancy": O.occupancy_block(p)}
    text = run_text.text(r)
    assert "occupancy: 6 of 20 subunits (30.0 %) carry the domain (random, drawn with seed 2" \
        in text and "a fibril of 20 layers with two ends" in text
    jsonschema.Draft202012Validator(json.loads((ref / "result.schema.json").read_text())
                                    ).validate(r)
    doc = json.loads((ref / "samples" / "report.json").read_text())
    doc["occupancy"] = O.report_block(p, 8)
    jsonschema.Draft202012Validator(json.loads((ref / "report.schema.json").read_text())
                                    ).validate(doc)
    page = report_page.html(doc, ROOT)
    assert "fraction carrying the domain</th><td>30 %" in page
    assert "each draw their own pattern" in page
    del doc["occupancy"]
    assert "Occupancy" not in report_page.html(doc, ROOT)  # f = 1: the page as before


def test_a_sweep_grids_the_fraction_and_the_pattern():
    from fibrilfit.sweep import grid
    spec = lambda **kw: {k: grid.parse_spec(k, v) for k, v in kw.items()}  # noqa: E731
    pts = grid.build(spec(occupancy="0.1:0.3:0.1", layers="20"), ["0", "1"])
    assert [(pt.params["occupancy"], pt.params["seed"]) for pt in pts] == \
        [(0.1, 0), (0.2, 0), (0.3, 0), (0.1, 1), (0.2, 1), (0.3, 1)]
    assert [pt.params["occupancy"] for pt in grid.build(spec(occupancy="25%,50%"), ["0"])] == \
        [0.25, 0.5]
    pts = grid.build(spec(pattern="layers", pattern_layers="A.,A.."), ["0"])
    assert [pt.params["pattern_layers"] for pt in pts] == ["A.", "A.."]
    with pytest.raises(ParamError, match="rounds to none"):
        grid.build(spec(occupancy="0.01", layers="20"), ["0"])


def test_a_case_file_carries_the_fraction_and_the_pattern(tmp_path):
    from fibrilfit.model import cases
    case = tmp_path / "mixed.toml"
    case.write_text('[params]\nlayers = 12\noccupancy = "25%"\nbare_tail = 3\n', encoding="utf-8")
    p = P.make_params(**cases.load(case).params)
    assert (p.occupancy, p.bare_tail, O.decorated(p).sum()) == (0.25, 3, 3)
    case.write_text('[params]\npattern = "layers"\npattern_layers = "A.."\n', encoding="utf-8")
    assert O.decorated(P.make_params(**cases.load(case).params))[:3, 0].tolist() == \
        [True, False, False]
    case.write_text('[params]\noccupancy = "many"\n', encoding="utf-8")
    with pytest.raises(cases.CaseError, match="params.occupancy"):
        cases.load(case)


def test_a_mixed_fibril_keeps_only_the_exit_bound():
    """The excluded-volume bound counts every subunit: it is not a proof for a mixed fibril,
    which keeps only the exit's bound; at f = 1 the bound is the excluded volume's as before."""
    from fibrilfit.model import bound
    base = dict(globule_diameter=50.0, periodic=21, protocol="inflate")
    full = bound.linker_bound(P.make_params(**base))
    assert full["impossible_below"] > 1 and "excluded volume" in full["method"]
    mixed = bound.linker_bound(P.make_params(**base, pattern="periodic", pattern_period=3))
    assert mixed["impossible_below"] == 1 and mixed["fails_below"] is None
    assert bound.bound_block(P.make_params(**base, occupancy=0.25, linker=1))["below"] is False
    assert bound.bound_block(P.make_params(**base, linker=1))["below"] is True


def test_the_restarts_line_says_what_p_fit_counts():
    from fibrilfit.search import linker_map
    s = {"accommodated": 6, "restarts": 8, "p_fit": 0.75, "p_fit_interval": [0.41, 0.93],
         "failed": 0, "best_seed": 5}
    assert "over" not in linker_map.restarts_line(s)
    p = P.make_params(layers=16, occupancy=0.5)
    line = linker_map.restarts_line({**s, "p_fit_counts": O.report_block(p, 8)["p_fit_counts"]})
    assert "P(fit) 0.75 (95 % Wilson 0.41-0.93) over restarts that each draw their own " \
           "pattern and start from their seed; best layout: seed 5" in line


def test_bare_tails_are_built_in_a_periodic_cell():
    """A cell takes bare tails (their images: builders/periodic.py); each tail member reaches
    as far as a linker bead at its place along the chain (model.chain.tail_reach)."""
    from fibrilfit.model import chain
    p = P.make_params(periodic=14, occupancy=0.5, bare_tail=10)
    assert (p.bare_tail, chain.tail_members(p)) == (10, 10)
    reach = chain.tail_reach(p)
    assert len(reach) == 10 and reach[0] == pytest.approx(p.residue_radius)
    assert np.diff(reach) == pytest.approx(p.residue_spacing * (1 + p.stretch_tolerance))
    linker = chain.chain_reach(p)[:p.free_linker]  # the linker's beads: the same places
    assert reach[:len(linker)] == pytest.approx(linker)


# ---- a hetero-amyloid: the letter B (docs/model/occupancy.md#hetero) -------------------------
def test_b_layers_carry_the_second_domain_and_count_as_decorated():
    p = P.make_params(pattern="layers", pattern_layers="AB", domain_b_diameter=40.0, layers=6,
                      protofilaments=2, pf_rotation=3.13, pf_rise=2.3)
    assert O.is_hetero(p) and not O.is_mixed(p) and O.decorated(p).all()
    assert O.second_domain(p)[:, 0].tolist() == [False, True] * 3
    assert (O.second_domain(p)[:, 0] == O.second_domain(p)[:, 1]).all()  # a layer's letter
    assert O.repeat_layers(p) == 2 and p.widest_diameter == 40.0
    q = P.make_params(pattern="layers", pattern_layers="A.B.", domain_b_diameter=20.0, layers=8)
    assert O.is_mixed(q) and O.decorated(q)[:, 0].tolist() == [True, False] * 4
    assert O.second_domain(q)[:, 0].tolist() == [False, False, True, False] * 2
    assert q.widest_diameter == 30.0  # A's is the wider
    assert not O.is_hetero(P.make_params(pattern="layers", pattern_layers="A."))
    assert P.DEFAULTS.domain_b_diameter is None and P.DEFAULTS.linker_b is None


def test_a_hetero_cell_holds_whole_repeats_and_is_long_enough_for_b():
    auto = P.make_params(pattern="layers", pattern_layers="AB", domain_b_diameter=60.0,
                         periodic="auto")
    assert auto.periodic % 2 == 0 and auto.periodic * auto.rise > 60.0
    with pytest.raises(ParamError, match="periodic"):  # 8 layers: 38.4 Å, shorter than B
        P.make_params(pattern="layers", pattern_layers="AB", domain_b_diameter=60.0, periodic=8)


def test_each_chain_has_its_own_last_bond_and_globule():
    from fibrilfit.model import hetero
    from fibrilfit.model.chain import rest_lengths
    p = P.make_params(pattern="layers", pattern_layers="A.B", domain_b_diameter=40.0, layers=6,
                      linker=4)
    b = hetero.b_chains(p)  # the model's chains: the decorated subunits, layers 0, 2, 3, 5
    assert b.tolist() == [False, True, False, True]
    rest = hetero.rest_lengths_by_chain(p)
    assert rest.shape == (4, 4)
    assert rest[~b] == pytest.approx(np.tile(rest_lengths(p), (2, 1)))
    assert rest[b, -1] == pytest.approx(20.0 + p.residue_radius)  # B's surface
    assert rest[b, :-1] == pytest.approx(3.5)
    assert hetero.globule_radii_by_chain(p).tolist() == [15.0, 20.0, 15.0, 20.0]
    same = P.make_params(pattern="layers", pattern_layers="AB", domain_b_diameter=30.0, layers=4)
    plain = P.make_params(pattern="layers", pattern_layers="AA", layers=4)
    assert np.array_equal(hetero.rest_lengths_by_chain(same), hetero.rest_lengths_by_chain(plain))


def test_the_occupancy_block_names_the_b_subunits_and_validates():
    import json
    import jsonschema
    from helpers import ROOT
    ref = ROOT / "docs" / "reference"
    p = P.make_params(pattern="layers", pattern_layers="AB", domain_b_diameter=40.0, layers=4)
    block = O.occupancy_block(p)
    assert block["second_domain"] == {"letter": "B", "diameter": 40.0, "linker": p.linker,
                                      "subunits": [[1, 0], [3, 0]]}
    r = json.loads((ref / "samples" / "run_result.json").read_text())
    r = {**r, "params": p.to_dict(), "occupancy": block}
    jsonschema.Draft202012Validator(json.loads((ref / "result.schema.json").read_text())
                                    ).validate(r)
    from fibrilfit.exports import run_text
    assert "second domain: B, 40 Å (a sphere) on a 6-residue linker, on 2 of those subunits " \
           "(pattern 'AB'); the others carry A, 30 Å" in run_text.text(r)


def test_a_hetero_fibril_is_bounded_with_each_letter_at_its_own_size():
    """Two domain sizes (docs/model/bound.md#hetero): B as large as A is bounded as the all-A
    fibril to the number; a larger B is bounded at most as high as the fibril of that larger
    domain on every layer (each of its inequalities is implied by one of that fibril's); a
    mixed hetero-amyloid keeps the exit's bound alone, and the fraction bound is refused."""
    from fibrilfit.model import bound, hetero
    base = dict(periodic=22, pattern="layers")
    aa = bound.linker_bound(P.make_params(**base, pattern_layers="AA"))
    same = bound.linker_bound(P.make_params(**base, pattern_layers="AB", domain_b_diameter=30.0))
    assert aa["impossible_below"] == same["impossible_below"] == 2
    assert "A and B each at its own size" in same["method"]
    for d in (40.0, 50.0):
        ab = bound.linker_bound(P.make_params(**base, pattern_layers="AB", domain_b_diameter=d))
        bb = bound.linker_bound(P.make_params(**base, pattern_layers="AA", globule_diameter=d))
        assert 1 <= ab["impossible_below"] <= bb["impossible_below"]
        assert ab["inner_volume_A3"][0] == aa["inner_volume_A3"][0]
        assert ab["inner_volume_A3"][1] == bb["inner_volume_A3"][0]
    # the shares each letter's volume is counted with: the scored layers' letters, or the
    # pattern's per layer in a cell
    def shares(**kw):
        q = P.make_params(pattern="layers", **kw)
        return hetero.letter_shares(q, q.score_layers, q.layers - q.score_layers)

    assert shares(layers=12, pattern_layers="AAB", domain_b_diameter=40.0) == \
        pytest.approx([8 / 12, 4 / 12])
    assert shares(layers=12, score_layers=2, pattern_layers="AAB", domain_b_diameter=40.0) == \
        pytest.approx([5 / 8, 3 / 8])  # layers 2-9: B on 2, 5, 8
    assert shares(periodic=21, pattern_layers="AAB", domain_b_diameter=40.0) == \
        pytest.approx([2 / 3, 1 / 3])
    mixed = P.make_params(periodic=24, pattern="layers", pattern_layers="A.B.",
                          domain_b_diameter=40.0)
    b = bound.linker_bound(mixed)
    assert b["impossible_below"] == 1 and "no excluded-volume bound" in b["method"]
    with pytest.raises(ValueError, match="hetero"):
        bound.setting(P.make_params(**base, pattern_layers="AB", domain_b_diameter=40.0))


def test_a_case_file_carries_the_second_domain(tmp_path):
    from fibrilfit.model import cases
    case = tmp_path / "hetero.toml"
    case.write_text('[params]\npattern = "layers"\npattern_layers = "AB"\n'
                    'domain_b_diameter = 40.0\nlinker_b = 6\n', encoding="utf-8")
    p = P.make_params(**cases.load(case).params)
    assert (p.domain_b_diameter, p.linker_b, O.is_hetero(p)) == (40.0, 6, True)


def test_the_core_entry_counts_each_globule_at_its_own_size():
    """The bound's third assumption, measured on a layout (bound.core_entry): a B globule's
    inner ball is B's, d_B / d_A times A's."""
    from fibrilfit.model import bound
    p = P.make_params(pattern="layers", pattern_layers="AB", domain_b_diameter=40.0, layers=4)
    m = np.tile(np.eye(4), (1, p.linker + 1, 1, 1))
    m[0, -1, :3, 3] = (30.0, 0.0, 0.0)  # layer 0's globule, 10 Å outside the 40 Å slab's face
    f = bound.uv_fraction()
    assert bound.core_entry(p, m) == pytest.approx(15.0 * f - 10.0, abs=1e-4)
    assert bound.core_entry(p, m, [40.0 / 30.0]) == pytest.approx(20.0 * f - 10.0, abs=1e-4)


def test_b_chains_that_cannot_leave_the_core_are_refused_before_a_build():
    """In a slot 34 Å wide a 30 Å domain's chain leaves the core straight, a 40 Å one cannot:
    a B of 40 Å beside that A is refused at validation, naming domain_b_diameter."""
    slot = [[-50, -60], [90, -60], [90, -17], [10, -17], [10, 17], [90, 17], [90, 60], [-50, 60]]
    base = dict(core_outline=slot, anchor=[11.75, 0.0], layers=4, linker=6)
    P.make_params(**base)
    P.make_params(**base, pattern="layers", pattern_layers="AB", domain_b_diameter=20.0)
    with pytest.raises(ParamError) as exc:
        P.make_params(**base, pattern="layers", pattern_layers="AB", domain_b_diameter=40.0)
    assert exc.value.param == "domain_b_diameter" and "the B chains (40 Å)" in str(exc.value)
    assert "\n" not in str(exc.value)
