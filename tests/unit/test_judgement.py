"""The judgement's rules without Blender (fibrilfit/model/judgement.py): accommodated, grazing
against disagreement, the near miss and the clear miss; each edge pinned on both sides, so
`make mutate` (tools/mutate/judgement.toml) can tell a changed comparison."""
import importlib.util

import numpy as np
import pytest
from helpers import ROOT

from fibrilfit.model import params as P
from fibrilfit.model.judgement import (POLISH_OVERLAP, POLISH_STRETCH, TOUCH_SLACK, accommodated,
                                       clear_miss, compare_checks, near_fit)

TOL = 0.05


def test_accommodated_needs_no_crossing_and_every_bond_within_the_tolerance():
    assert accommodated("successful", TOL, TOL) is True  # at the tolerance: still intact
    assert accommodated("successful", TOL + 1e-9, TOL) is False
    assert accommodated("intersection", 0.0, TOL) is False
    assert accommodated("successful", 0.0, TOL) is True
    assert accommodated("successful", 0.0, TOL, tail_pairs=1) is False  # a tail in a domain
    assert accommodated("successful", 0.0, TOL, tail_pairs=0) is True


def test_compare_checks_tells_grazing_from_disagreement():
    depths = {(0, 1): 2.0, (1, 2): 0.1, (2, 3): -0.5, (3, 4): 0.5, (4, 5): -1e-6}
    depth = lambda i, j: depths[(i, j)]
    band = 0.287
    grazing, disagree = compare_checks({(0, 1), (1, 2), (4, 5)}, {(0, 1)}, depth, band)
    assert [(i, j) for i, j, _ in grazing] == [(1, 2), (4, 5)] and disagree == []
    # the BVH names spheres that are apart; the spheres name a pair the BVH missed
    grazing, disagree = compare_checks({(0, 1), (2, 3)}, {(0, 1), (3, 4)}, depth, band)
    assert grazing == [] and [(i, j) for i, j, _ in disagree] == [(2, 3), (3, 4)]


@pytest.mark.parametrize("d, kind", [(0.287, "grazing"), (0.2871, "disagree"),
                                     (-TOUCH_SLACK / 2, "grazing"), (-TOUCH_SLACK, "disagree"),
                                     (0.0, "grazing")])
def test_the_grazing_band_is_open_below_and_closed_above(d, kind):
    """(−slack, band]: a BVH-only pair exactly at the band grazes; exactly −slack apart it does
    not; the depth comes back with the pair."""
    grazing, disagree = compare_checks({(0, 1)}, set(), lambda i, j: d, 0.287)
    assert (grazing, disagree) == (([(0, 1, d)], []) if kind == "grazing" else ([], [(0, 1, d)]))


def test_a_pair_only_the_spheres_name_always_disagrees():
    assert compare_checks(set(), {(0, 1)}, lambda i, j: 0.1, 0.287) == ([], [(0, 1, 0.1)])
    assert compare_checks({(0, 1)}, {(0, 1)}, lambda i, j: 9.0, 0.287) == ([], [])


def _v(pairs=0, stretch=0.0, overlap=0.0, ok=False):
    return {"accommodated": ok, "clashing_pairs": pairs, "max_bond_stretch": stretch,
            "max_overlap": overlap}


def test_a_near_fit_is_a_shallow_miss_with_linkers_at_most_three_times_the_tolerance():
    p = P.make_params(protocol="inflate", stretch_tolerance=TOL)
    assert POLISH_STRETCH == 3.0 and POLISH_OVERLAP == 1.0  # docs/model/search.md#polish
    assert near_fit(p, _v(stretch=3 * TOL, overlap=1.0))  # both edges included
    assert not near_fit(p, _v(stretch=3 * TOL + 1e-9))
    assert not near_fit(p, _v(overlap=1.0 + 1e-9))
    assert not near_fit(p, _v(ok=True))  # a fit is no near miss
    assert near_fit(p, {"accommodated": False, "max_bond_stretch": 0.0})  # no overlap recorded


def test_a_clear_miss_by_pairs_or_by_stretch_each_at_its_threshold():
    p = P.make_params(protocol="inflate", stretch_tolerance=TOL)
    pairs, times = p.clear_miss_pairs, p.clear_miss_stretch
    assert (pairs, times) == (8, 10.0)  # the measured rule (docs/benchmarks.md#stopping-rule-gallery)
    deep = 1.5  # deeper than a near miss, so only the rule decides
    assert clear_miss(p, _v(pairs=8, overlap=deep)) and not clear_miss(p, _v(pairs=7, overlap=deep))
    assert clear_miss(p, _v(pairs=[[0, 1, 2.0]] * 8, overlap=deep))  # a list counts its pairs
    assert clear_miss(p, _v(stretch=10 * TOL))
    assert not clear_miss(p, _v(stretch=10 * TOL - 1e-9, overlap=deep))
    assert not clear_miss(p, _v(pairs=50, stretch=0.5, ok=True))  # a fit never ends as a miss
    assert not clear_miss(p, _v(pairs=50, stretch=0.1, overlap=0.5))  # a near miss goes on
    off = p.replace(clear_miss_pairs=0, clear_miss_stretch=0.0)
    assert not clear_miss(off, _v(pairs=50, stretch=5.0, overlap=deep))
    # the smallest settings that are on: one pair, or the tolerance itself (a half at 0 is off)
    one = p.replace(clear_miss_pairs=1, clear_miss_stretch=0.0)
    assert clear_miss(one, _v(pairs=1, overlap=deep))
    assert not clear_miss(one, _v(pairs=0, stretch=5.0, overlap=deep))
    low = p.replace(clear_miss_pairs=0, clear_miss_stretch=1.0)
    assert clear_miss(low, _v(stretch=3 * TOL + 1e-6))  # past a near miss, at least 1 x tol
    assert not clear_miss(low, _v(pairs=50, overlap=deep))


def test_the_clear_miss_rule_is_the_rule_replayed_on_the_traces():
    """clear_miss fires exactly where bench/stop_traces.py's replayed rule "cycle >= 0, not
    near, pairs >= 8 or stretch >= 10 x tol" does (the measured one), and 0 turns a half off."""
    spec = importlib.util.spec_from_file_location("stop_traces", ROOT / "bench" / "stop_traces.py")
    st = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(st)
    replayed = st.rule(0, pairs=8, stretch=10)[1]
    p = P.make_params(protocol="inflate")
    rng = np.random.default_rng(0)
    fired = 0
    for _ in range(2000):
        v = {"accommodated": bool(rng.random() < 0.1), "cycle": int(rng.integers(0, 9)),
             "clashing_pairs": int(rng.integers(0, 20)),
             "max_bond_stretch": float(rng.choice([rng.uniform(0, 0.2), rng.uniform(0, 1.0)])),
             "max_overlap": float(rng.uniform(0, 3))}
        want = replayed({"stretch_tolerance": p.stretch_tolerance}, v)
        assert clear_miss(p, v) == want, v
        fired += want
    assert fired == 1104  # both outcomes tried (seed 0: 1104 of 2000 fire, measured)
    off = p.replace(clear_miss_pairs=0)
    assert clear_miss(off, _v(pairs=50, stretch=0.2, overlap=3.0)) is False
    assert clear_miss(off, _v(pairs=1, stretch=0.6, overlap=3.0)) is True
