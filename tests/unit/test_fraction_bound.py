"""The proven upper bound on the fraction of decorated subunits (fibrilfit/model/fraction_bound.py,
docs/model/bound.md#fraction): how protofilaments' caps combine, its agreement with the linker
bound at fraction 1, a room known in closed form, monotone in the linker, the bracket's words,
and random geometries against an independent search for mixed layouts (tests/bound_oracle.py)."""
from __future__ import annotations

import math
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, event, given, settings, strategies as st

from fibrilfit.model import bound as B
from fibrilfit.model import fraction_bound as F
from fibrilfit.model import params as P

import bound_oracle as oracle

BUDGET = 3e5  # a coarser grid: a bound as sound, and weaker or equal (bound.linker_bound)


# ---- how the protofilaments' caps combine ----------------------------------------------------
def test_partitions_are_every_grouping_once():
    for k, bell in ((1, 1), (2, 2), (3, 5), (4, 15), (5, 52)):
        parts = list(F.partitions(list(range(k))))
        assert len(parts) == bell
        assert all(sorted(i for g in part for i in g) == list(range(k)) for part in parts)
        assert len({tuple(sorted(tuple(sorted(g)) for g in part)) for part in parts}) == bell


def test_a_blocked_protofilament_caps_only_its_own_share():
    # protofilament 0 has no room, 1 all it needs: half the subunits can be decorated (all of
    # protofilament 1), not none (the least cap per chain would say so, wrongly)
    best, groups = F.combine({(0,): 0.0, (1,): 1.0, (0, 1): 1.0}, 2)
    assert best == 1.0 and sorted(map(sorted, groups)) == [[0], [1]]
    # a shared room binds both together
    best, groups = F.combine({(0,): 1.0, (1,): 1.0, (0, 1): 1.3}, 2)
    assert best == 1.3 and groups == [[0, 1]]
    # three: one pair crowded, the third free
    cap = {(0,): 1, (1,): 1, (2,): 1, (0, 1): 0.5, (0, 2): 2, (1, 2): 2, (0, 1, 2): 3}
    assert F.combine(cap, 3)[0] == 1.5


# ---- at fraction 1 it is the linker bound; monotone ---------------------------------------------
@pytest.mark.parametrize("diameter", [40.0, 50.0])
def test_fraction_one_is_exactly_the_linker_bound(diameter):
    p = P.make_params(globule_diameter=diameter, protocol="inflate", periodic="auto")
    b = B.linker_bound(p, budget=BUDGET)["impossible_below"]
    assert b > 1  # something below it to test
    f = [F.fraction_bound(p, L, budget=BUDGET) for L in range(1, b + 4)]
    assert all(x < 1.0 for x in f[:b - 1]) and all(x == 1.0 for x in f[b - 1:])
    assert all(0.0 < x <= y for x, y in zip(f, f[1:]))  # non-decreasing in the linker
    assert F.fraction_bound(p, 60, budget=BUDGET) == 1.0  # past the room's measured reach
    assert F.impossible_below_at(p, 1.0, budget=BUDGET) == b
    at = [F.impossible_below_at(p, x, budget=BUDGET) for x in (0.05, 0.3, 0.6, 0.8, 0.95, 1.0)]
    assert at == sorted(at)  # a higher fraction never needs a shorter linker
    for x, L in zip((0.05, 0.3, 0.6, 0.8, 0.95, 1.0), at):  # the first L that passes
        assert x <= F.fraction_bound(p, L, budget=BUDGET) + F.TOLERANCE
        assert L == 1 or x > F.fraction_bound(p, L - 1, budget=BUDGET)


def test_no_path_out_of_the_core_excludes_every_fraction():
    p = P.make_params(exit_residues=3, linker=10, periodic="auto", protocol="inflate")
    assert F.fraction_bound(p, 3, budget=BUDGET) == 0.0  # the exit's residues: still inside
    assert F.impossible_below_at(p, 0.01, budget=BUDGET) >= 4


# ---- a room known in closed form --------------------------------------------------------------
def test_the_fraction_bound_is_the_closed_form_room_over_the_domain():
    # one protofilament, no twist, a 400 Å core: per layer the room is the half-ball slab of
    # the closed form (half_space_room in tests/bound_oracle.py), so f_B = room / volume, the voxel
    # room above it by less than the room two voxels (2h) wider and deeper into the core. A bound
    # made lower than the room (a wrong reach, a packing density below 1, a count rounded on
    # a density) fails here.
    p = P.make_params(slab=(400.0, 400.0, 4.8), twist=0.0, periodic=9, protocol="inflate",
                      globule_diameter=30.0, linker=10)
    s = B.setting(p)
    need = s.volumes[0]
    checked = 0
    for L in range(1, s.impossible_below):
        rho, h = B.reach(p, s.terms, L)[0], s.room.h
        exact = oracle.half_space_room(rho, 4.8, 1.75 + B.CORE_ENTRY)
        wider = oracle.half_space_room(rho + 2 * h, 4.8, 1.75 + B.CORE_ENTRY + 2 * h)
        f = F.fraction_bound(p, L)
        assert exact / need <= f <= wider / need < 1.0
        checked += 1
    assert checked >= 2


# ---- finite fibrils --------------------------------------------------------------------------
def test_a_finite_fibrils_unscored_layers_are_free():
    p = P.make_params(protofilaments=3, globule_diameter=70.0, layers=8, score_layers=2,
                      slab=(20.0, 14.0, 4.8), linker=30, protocol="inflate")
    s = B.setting(p, BUDGET)
    lim = F.fraction_limit(p, 1, budget=BUDGET)
    assert lim["of"] == 24 and lim["count"] >= 3 * 4  # the four unscored layers' subunits
    assert lim["fraction_bound"] == lim["count"] / 24
    assert F.fraction_bound(p, s.impossible_below, budget=BUDGET) == 1.0


# ---- the bracket, said once --------------------------------------------------------------------
def test_the_bracket_rounds_each_clause_the_way_that_keeps_it_true():
    assert F.fraction_bracket(0.6281, 0.5) == (
        "impossible above 62.9 % (proof) / fits at 50 % (a layout) / open between 50 % and "
        "62.9 %")
    assert F.fraction_bracket(0.25, 0.25) == (
        "impossible above 25 % (proof) / fits at 25 % (a layout) / closed")
    assert F.fraction_bracket(0.333333, None).endswith("no layout found / open up to 33.4 %")
    assert "outside the bound's assumptions" in F.fraction_bracket(0.3, 0.5)


# ---- layouts found by an independent search -------------------------------------------------
def _spread(n: int, m: int) -> np.ndarray:
    d = np.zeros(n, dtype=bool)
    d[np.floor(np.arange(m) * n / m).astype(int)] = True
    return d


def test_layouts_of_the_default_fibril_lie_under_the_bound():
    # not vacuous: the search finds mixed layouts where the bound is below 1, and the full one
    # at a linker the bound leaves open (the tutorial's 30 Å model, a 12-layer cell)
    p = P.make_params(globule_diameter=50.0, periodic=12, protocol="inflate", linker=30)
    c, _ = B.reach_terms(p)[0]
    L = B.linker_bound(p, budget=BUDGET)["impossible_below"] - 1
    R = ((L - 1) * p.residue_spacing + c) * (1.0 + p.stretch_tolerance)
    assert oracle.periodic_layout(p, _spread(12, 3), R) is not None
    assert 3 / 12 <= F.fraction_bound(p, L, budget=BUDGET) < 1.0
    q = P.make_params(globule_diameter=30.0, periodic=9, protocol="inflate", linker=30)
    c, _ = B.reach_terms(q)[0]
    R = ((12 - 1) * q.residue_spacing + c) * (1.0 + q.stretch_tolerance)
    assert oracle.periodic_layout(q, np.ones(9, dtype=bool), R) is not None
    assert F.fraction_bound(q, 12, budget=BUDGET) == 1.0


# Random periodic geometries (one or two protofilaments, 30-60 Å domains, a box core, twist,
# rise and tolerance random), a random linker and a random decorated pattern of the cell: where
# the search finds a layout, its fraction must not exceed the bound.
geometries = st.fixed_dictionaries({
    "protofilaments": st.integers(1, 2),
    "globule_diameter": st.floats(30.0, 60.0),
    "twist": st.floats(-0.06, 0.06),
    "rise": st.floats(4.5, 5.0),
    "slab": st.tuples(st.floats(16.0, 40.0), st.floats(12.0, 30.0)),
    "stretch_tolerance": st.sampled_from([0.0, 0.05, 0.1]),
    "linker": st.integers(1, 8),
    "pattern": st.sampled_from(["spread", "random", "one protofilament"]),
    "share": st.floats(0.05, 1.0),
    "seed": st.integers(0, 1000),
})


def _check_random(g):
    L, pattern, share, seed = g.pop("linker"), g.pop("pattern"), g.pop("share"), g.pop("seed")
    slab = (*g.pop("slab"), g["rise"])
    cell = math.ceil(g["globule_diameter"] / g["rise"]) + 1  # the shortest cell allowed
    try:
        p = P.make_params(slab=slab, linker=30, periodic=cell, protocol="inflate", **g)
    except P.ParamError:
        assume(False)
    K = p.protofilaments
    n = p.layers * K
    m = max(1, round(share * n))
    rng = np.random.default_rng(seed)
    if pattern == "spread":
        d = _spread(n, m)
    elif pattern == "random":
        d = np.zeros(n, dtype=bool)
        d[rng.permutation(n)[:m]] = True
    else:  # along protofilament 0 only, every k-th layer
        rows = _spread(p.layers, max(1, round(share * p.layers)))
        d = np.zeros((p.layers, K), dtype=bool)
        d[:, 0] = rows
        d = d.ravel()
    c, _ = B.reach_terms(p)[0]
    R = ((L - 1) * p.residue_spacing + c) * (1.0 + p.stretch_tolerance)
    f = F.fraction_bound(p, L, budget=BUDGET)
    found = oracle.periodic_layout(p, d, R, seed=seed, steps=250) is not None
    event("layout found" if found else "none found")
    event(f"bound {'< 1' if f < 1 else '= 1'}")
    if found:
        assert d.sum() / n <= f + F.TOLERANCE, f"a layout at {d.sum()}/{n} above f_B {f}: {g}"


@settings(max_examples=8, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(geometries)
def test_no_layout_above_the_fraction_bound_on_random_geometries(g):
    _check_random(g)


@pytest.mark.slow
@settings(max_examples=int(os.environ.get("FRACTION_EXAMPLES", "300")), deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(geometries)
def test_no_layout_above_the_fraction_bound_on_300_random_geometries(g):
    _check_random(g)
