"""Issue #36 §4: `--periodic auto` is a ladder of cells, one per seed, so restarts search the
cell too (docs/model/periodic-cell.md#cell-ladder)."""
from fibrilfit.model import helix, params as P
from fibrilfit.search import command
from fibrilfit.sweep import grid


def test_the_ladder_runs_from_the_shortest_cell_to_twice_it():
    # ceil(2 D / 4.8 Å) for the map's diameters, then ceil(base (1 + k/4)), k = 1..4
    want = {20: [9, 12, 14, 16, 18], 30: [13, 17, 20, 23, 26], 40: [17, 22, 26, 30, 34],
            50: [21, 27, 32, 37, 42]}
    for d, cells in want.items():
        p = P.make_params(globule_diameter=d, periodic="auto")
        assert helix.cell_ladder(p) == cells
        assert helix.base_cell_layers(p) == cells[0] and cells[-1] == 2 * cells[0]
        assert min(cells) >= helix.min_cell_layers(p)


def test_auto_picks_the_seeds_rung_and_always_the_same():
    cells = [P.make_params(globule_diameter=20, periodic="auto", seed=s).periodic
             for s in range(11)]
    assert cells == [9, 12, 14, 16, 18] * 2 + [9]  # rung seed mod 5; seed 0: the old auto
    again = [P.make_params(globule_diameter=20, periodic=" AUTO ", seed=s).periodic
             for s in range(11)]
    assert again == cells
    p = P.make_params(globule_diameter=20, periodic="auto", seed=3)
    assert p.layers == p.periodic == 16 and helix.auto_cell_layers(p) == 16
    # an explicit cell is every seed's
    assert {P.make_params(globule_diameter=20, periodic=12, seed=s).periodic
            for s in range(5)} == {12}


def test_sweeps_and_the_walk_give_each_restart_its_seeds_cell():
    points = grid.build({"periodic": ["auto"], "globule_diameter": ["50"]},
                        [str(s) for s in range(5)])
    assert [(pt.params["seed"], pt.params["periodic"]) for pt in points] == \
        [(0, 21), (1, 27), (2, 32), (3, 37), (4, 42)]
    walk = command.restart_points({"periodic": "auto", "protocol": "inflate"}, 40.0, 11,
                                  range(5))
    assert [pt.params["periodic"] for pt in walk] == [17, 22, 26, 30, 34]
    assert [pt.params["seed"] for pt in walk] == list(range(5))
    assert len({pt.key for pt in walk}) == 5
