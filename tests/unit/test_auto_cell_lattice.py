"""Issue #36 §4: the cell `--periodic auto` picks under inflate holds whole periods of the
inflate start's lattice, and the start fans its chains in that lattice
(docs/model/periodic-cell.md#auto-cell, docs/model/search.md#lattice-start)."""
import numpy as np

from fibrilfit.model import helix, params as P, start_layout as S
from fibrilfit.search import linker_map
from fibrilfit.sweep import grid


def test_auto_under_inflate_holds_whole_lattice_periods_at_or_above_the_margin():
    # D: (the margin ceil(2 D / 4.8 Å), rows a side round(D / 9.6 Å), the cell)
    want = {15: (7, 2, 8), 20: (9, 2, 12), 30: (13, 3, 18), 40: (17, 4, 24), 50: (21, 5, 30)}
    for d, (margin, rows, cell) in want.items():
        p = P.make_params(globule_diameter=d, periodic="auto", protocol="inflate")
        assert (helix.base_cell_layers(p), helix.lattice_rows(p), p.periodic) == \
            (margin, rows, cell)
        assert p.periodic % (2 * rows) == 0 and margin <= p.periodic < margin + 2 * rows
        assert S.lattice_columns(p) == rows
    # the tutorial protocol keeps the margin (no lattice start to hold)
    assert P.make_params(periodic="auto").periodic == 13
    assert P.make_params(periodic="auto", globule_diameter=20).periodic == 9


def test_auto_is_every_seeds_and_the_walk_records_it():
    cells = {P.make_params(globule_diameter=20, periodic=" AUTO ", protocol="inflate",
                           seed=s).periodic for s in range(7)}
    assert cells == {12}
    points = grid.build({"periodic": ["auto"], "globule_diameter": ["50"],
                         "protocol": ["inflate"]}, [str(s) for s in range(3)])
    assert [pt.params["periodic"] for pt in points] == [30, 30, 30]
    walk = linker_map.restart_points({"periodic": "auto", "protocol": "inflate"}, 40.0, 11,
                                     range(5))
    assert [pt.params["periodic"] for pt in walk] == [24] * 5
    assert [pt.params["seed"] for pt in walk] == list(range(5))


def test_the_lattice_start_needs_a_cell_holding_whole_periods():
    assert S.lattice_columns(P.make_params(globule_diameter=20, periodic=12)) == 2
    assert S.lattice_columns(P.make_params(globule_diameter=20, periodic=16)) == 2
    assert S.lattice_columns(P.make_params(globule_diameter=20, periodic=9)) == 0
    assert S.lattice_columns(P.make_params(globule_diameter=30, periodic=18)) == 3
    assert S.lattice_columns(P.make_params(globule_diameter=30, periodic=13)) == 0
    assert S.lattice_columns(P.make_params(globule_diameter=20, layers=12)) == 0  # ends: none


def test_the_lattice_start_alternates_sides_and_cycles_the_rows():
    """As the 12-layer layout found for 20 Å globules at linker 4: sides alternate, each side's
    row changes every second layer, neighbours one layer apart in different rows."""
    assert S.lattice_amplitudes(np.arange(12), 2).tolist() == [1.0, 0.5, 0.5, 1.0] * 3
    assert S.lattice_amplitudes(np.arange(6), 3).tolist() == [1.0, 0.5, 0.75, 0.75, 0.5, 1.0]
    p = P.make_params(globule_diameter=20, periodic=12, linker=4, protocol="inflate")
    rest = S.rest_positions(p)
    a, b = S.inflate_layout(p, rest, 3)[0], S.inflate_layout(p, rest, 3)[0]
    assert np.array_equal(a, b)  # the seed still fixes it
    assert not np.allclose(a, S.inflate_layout(p, rest, 4)[0])
    rng = np.random.default_rng([3, S.SEED_SALT])
    fan = S.fan_directions(rest, rng, periodic=True, columns=S.lattice_columns(p))
    tilt = (fan * S.fan_frames(rest)[2]).sum(axis=1)  # sideways
    assert np.all(np.sign(tilt[::2]) == -np.sign(tilt[1::2]))  # sides alternate
    assert np.allclose(tilt[:4], tilt[4:8]) and np.allclose(tilt[:4], tilt[8:])  # period 4
    assert len(np.unique(np.round(np.abs(tilt), 6))) == 2  # two rows a side


def test_a_cell_without_whole_periods_starts_as_before():
    """The random amplitudes stay where no lattice fits (and in fibrils with ends): the same
    start as before the lattice, draw for draw."""
    p = P.make_params(globule_diameter=20, periodic=9, linker=4, protocol="inflate")
    rest = S.rest_positions(p)
    rng = np.random.default_rng([5, S.SEED_SALT])
    fan = S.fan_directions(rest, rng, periodic=True, columns=0)
    rng = np.random.default_rng([5, S.SEED_SALT])
    u, a, s = S.fan_frames(rest)
    h = rest[:, 0, 2]
    levels = np.unique(np.round(h, 3), return_inverse=True)[1].ravel()
    side = np.where(levels % 2 == 0, 1.0, -1.0) * rng.choice([-1.0, 1.0])
    side = side * rng.uniform(0.5, 1.0, len(h))
    old = u + S.FAN_SIDE * side[:, None] * s
    assert np.allclose(fan, old / np.linalg.norm(old, axis=1, keepdims=True))
