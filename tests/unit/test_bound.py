"""The proven lower bound on the linker (fibrilfit/model/bound.py, docs/model/bound.md): each
ingredient, a case whose bound is known in closed form, a constructed case known by hand, every
fit recorded in the repository, and random geometries against an independent layout search."""
from __future__ import annotations

import csv
import math
import os
import pathlib

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, event, given, settings, strategies as st

from fibrilfit.geom import shape as geom_shape
from fibrilfit.model.chain import chain_x
from fibrilfit.model import bound as B
from fibrilfit.model import params as P

import bound_oracle as oracle

ROOT = pathlib.Path(__file__).resolve().parents[2]


# ---- ingredients ------------------------------------------------------------------------------
def test_uv_sphere_inradius_is_the_measured_mesh_sag():
    # the globule mesh's grazing depth, measured on the Blender mesh (analysis/clashes.py
    # GRAZING_AT_15, 0.287 Å at 15 Å), is twice its sag
    f = geom_shape.uv_sphere_inradius(32, 16)
    assert 2 * 15.0 * (1 - f) == pytest.approx(0.287, abs=1e-3)
    assert geom_shape.uv_sphere_inradius(64, 32) > f  # a finer mesh sags less


def test_ball_union_volume_is_a_lower_bound():
    one = 4 / 3 * math.pi * 5 ** 3
    assert B.ball_union_volume([[0, 0, 0, 5]]) == pytest.approx(one)
    apart = B.ball_union_volume([[0, 0, 0, 5], [20, 0, 0, 5]])
    assert 0.8 * 2 * one <= apart <= 2 * one
    same = B.ball_union_volume([[0, 0, 0, 5], [0, 0, 0, 5]])
    assert 0.8 * one <= same <= one  # never above the union's true volume


def test_central_ball_lies_inside_the_atoms_hull():
    u = geom_shape.directions(300)
    rows = np.column_stack([u * 10.0, np.full(300, 1.5)])  # atoms on a 10 Å sphere
    r = B.central_ball(rows)
    assert 10.0 <= r <= 11.5  # the hull of the balls reaches 11.5 Å at most


def test_reach_grows_by_one_stretched_spacing_per_residue():
    p = P.make_params(linker=6)
    terms = B.reach_terms(p)
    r6, r7 = B.reach(p, terms, 6)[0], B.reach(p, terms, 7)[0]
    assert r7 - r6 == pytest.approx(3.5 * 1.05)
    x = chain_x(p)  # at the model's own linker: the centre's rest distance, stretched, + body
    assert r6 == pytest.approx((x[6] - x[0]) * 1.05 + 15.0 * B.uv_fraction())


# ---- a bound known in closed form -------------------------------------------------------------
_half_space_volume = oracle.half_space_room  # the closed form, shared with test_fraction_bound


def test_one_protofilament_on_a_wide_core_matches_its_closed_form():
    # twist 0 and a 400 Å core: the anchors are a straight line beside a plane (1.75 Å from
    # the face, so 1.75 + CORE_ENTRY from the eroded one)
    p = P.make_params(slab=(400.0, 400.0, 4.8), twist=0.0, periodic=9, protocol="inflate",
                      globule_diameter=30.0, linker=10)
    terms = B.reach_terms(p)
    need = B.ball_union_volume(B.inner_balls(p, p.domains[0]))
    closed = next(L for L in range(1, 60)
                  if need <= _half_space_volume(B.reach(p, terms, L)[0], 4.8,
                                                1.75 + B.CORE_ENTRY))
    got = B.linker_bound(p)
    assert got["impossible_below"] in (closed - 1, closed)  # voxels only over-count the room
    room = B.Room(p, B.reach(p, terms, closed)[0], True, 0, 1)
    exact = _half_space_volume(B.reach(p, terms, closed)[0], 4.8, 1.75 + B.CORE_ENTRY)
    assert exact <= room.volume([0], B.reach(p, terms, closed)[0]) <= exact * 1.05


# ---- a case known by hand ---------------------------------------------------------------------
def test_an_anchor_deep_in_a_narrow_slot_needs_the_slot_depth():
    # a 150 × 160 Å core with a 6 Å wide slot 60 Å deep from its +x face; the anchor at the
    # slot's bottom. A 30 Å domain's inner ball (r 14.86) cannot enter a 6 Å slot, so until its
    # reach passes the mouth its room is the slot (and the core's 0.5 Å skin): at most
    # 7 × 60 × 4.8 = 2016 Å³ per layer, against a ball of 13,736 Å³. So every linker whose
    # reach ρ stays 2 Å inside the mouth is impossible, and the bound must say so (the core's
    # other faces are farther: 80 Å to the sides, 90 Å behind).
    outline = [(-100, -80), (50, -80), (50, -3), (-10, -3), (-10, 3), (50, 3), (50, 80),
               (-100, 80)]
    p = P.make_params(core_outline=outline, anchor=(-8.25, 0.0), globule_diameter=30.0,
                      periodic=9, protocol="inflate", linker=25, force=True)
    terms = B.reach_terms(p)
    depth = 60.0 - 1.75  # from the anchor's centre to the mouth
    by_hand = max(L for L in range(1, 40) if B.reach(p, terms, L)[0] < depth - 2.0)
    assert by_hand >= 6
    assert B.linker_bound(p)["impossible_below"] > by_hand


# ---- monotone, and its own inequality --------------------------------------------------------
def test_the_bound_is_where_the_inequalities_start_to_hold():
    p = P.make_params(globule_diameter=50.0, periodic=21, protocol="inflate")
    b = B.linker_bound(p)
    L = b["impossible_below"]
    assert L > 1 and b["fails_below"]["linker"] == L - 1
    assert b["fails_below"]["needed_A3"] > b["fails_below"]["room_A3"]
    terms = B.reach_terms(p)
    room = B.Room(p, B.reach(p, terms, L + 5)[0], True, 0, 1)
    vol = [B.ball_union_volume(B.inner_balls(p, d)) for d in p.domains]
    for linker in (L, L + 2, L + 5):
        assert all(c["need"] <= c["have"] for c in B.constraints(p, room, terms, vol, linker, 1))


# ---- every fit recorded in the repository ---------------------------------------------------
def test_the_bound_never_exceeds_a_recorded_minimal_linker():
    # docs/minimal_linker.csv: the walk's minima (a fit found at each), default model
    rows = list(csv.DictReader(open(ROOT / "docs/minimal_linker.csv", encoding="utf-8")))
    checked = 0
    for row in rows:
        if not row["minimal_linker"]:
            continue
        kind = row["kind"]
        d = float(row["globule_diameter"])
        if kind.startswith("layers"):
            p = P.make_params(globule_diameter=d, layers=int(kind.split()[1]),
                              protocol="inflate")
        else:
            continue
        assert B.linker_bound(p, budget=2e6)["impossible_below"] <= int(row["minimal_linker"])
        checked += 1
    assert checked >= 10
    # the infinite fibril's map (docs/model/search.md#infinite-fibril): 20 → 5, 30 → 7,
    # 40 → 11, 50 → 15 residues in the auto cell
    for d, minimum in ((20, 5), (30, 7), (40, 11), (50, 15)):
        p = P.make_params(globule_diameter=d, protocol="inflate",
                          periodic=math.ceil(2 * d / 4.8))  # the auto cell
        assert B.linker_bound(p, budget=2e6)["impossible_below"] <= minimum


# ---- random geometries against an independent search -----------------------------------------
# Crowded geometries (several protofilaments, wide domains, a narrow core), where the bound of a
# finite fibril rises above 1: a geometry whose bound is 1 has nothing below it to test, and
# is discarded (hypothesis.assume).
geometries = st.fixed_dictionaries({
    "protofilaments": st.integers(2, 4),
    "globule_diameter": st.floats(40.0, 80.0),
    "layers": st.integers(5, 9),
    "twist": st.floats(-0.06, 0.06),
    "rise": st.floats(4.5, 5.0),
    "slab": st.tuples(st.floats(16.0, 40.0), st.floats(12.0, 30.0)),
    "stretch_tolerance": st.sampled_from([0.0, 0.05, 0.1]),
})


def _check_random(g):
    slab = (*g.pop("slab"), g["rise"])
    try:
        p = P.make_params(slab=slab, linker=30, **g)
    except P.ParamError:
        assume(False)
    b = B.linker_bound(p, budget=3e5)["impossible_below"]
    assume(b > 1)
    event(f"bound {b}")
    c, _ = B.reach_terms(p)[0]
    for L in range(max(1, b - 2), b):  # below the bound no layout may exist
        R = ((L - 1) * p.residue_spacing + c) * (1.0 + p.stretch_tolerance)
        assert oracle.layout(p, seed=0, R=R) is None, f"a layout at {L} below the bound {b}: {g}"


@settings(max_examples=6, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(geometries)
def test_no_layout_below_the_bound_on_random_geometries(g):
    _check_random(g)


@pytest.mark.slow
@settings(max_examples=int(os.environ.get("BOUND_EXAMPLES", "600")), deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(geometries)
def test_no_layout_below_the_bound_on_600_random_geometries(g):
    _check_random(g)


def test_the_oracle_finds_layouts_where_the_model_does():
    # not a vacuous witness: the default model fits at 6 (docs/model/default-model.md)
    assert oracle.layout(P.make_params(layers=6, linker=6), seed=0) is not None
    assert oracle.layout(P.make_params(layers=6, linker=1, globule_diameter=60.0),
                         seed=0) is None


def test_the_bound_is_the_geometrys_whatever_linker_asked_first():
    # a worker computes it once per geometry (cached): which linker came first must not show
    # (a dask sweep's results differed from the local ones by the bound's voxel before)
    first = B.linker_bound(P.make_params(layers=8, linker=3))
    B._CACHE.clear()
    assert B.linker_bound(P.make_params(layers=8, linker=12)) == first
