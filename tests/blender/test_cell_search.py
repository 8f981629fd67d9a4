"""The inflate search in a periodic cell (docs/model/periodic-cell.md#cell-search): at 30 Å,
linker 7 accommodated in at least 4 of seeds 0-4 and linker 5 in none, on the 13-layer cell and
on one twice as long (the target's numbers came from an optimizer whose data the repository does
not keep: they are the target, not evidence; the fast case is tests/blender/test_auto_cell.py's
cell of 18 layers, seed 0 at linker 7 and 6).

Measured 2026-11-25 on the auto cell: 2 of 5 at linker 7 with 4 regrows; with near_cycles (5
more regrows for a near miss) 4 of 5 (seed 2 does not fit; seeds 5-9: 5 of 5), and 4 of 5 on the
26-layer cell (seed 2 does not fit). Measured on the 13-layer cell that `auto` then was for every
seed; under inflate `auto` is now a cell holding whole periods of the lattice start (18 layers
at 30 Å: docs/model/periodic-cell.md#auto-cell), so the claim names the cell it was measured on.
"""
import pytest

from fibrilfit.model import params as P


def _fits(scene, ff, linker, cell):
    fits = 0
    for seed in range(5):
        r = ff.pipeline.run_model(P.make_params(protocol="inflate", periodic=cell, linker=linker,
                                                seed=seed), scene)
        assert r["checks_agree"]
        if r["accommodated"]:
            assert r["intersecting_faces"] == 0 and r["max_bond_stretch"] <= 0.05
        fits += r["accommodated"]
    return fits


@pytest.mark.slow
@pytest.mark.parametrize("cell", [13, 26])
def test_the_cell_fits_linker_7_in_most_seeds(scene, ff, cell):
    """Measured 4 of 5 on both cells (seed 2 misses). The bound leaves one seed of room: a seed's
    fit turns on its last regrows (4 regrows gave 2 of 5, the near cycles' 5 more gave 4: the
    module's docstring), so a change to the schedule or the physics that keeps the claim may
    move one seed; a majority still says the search reaches the threshold from most starts.
    Linker 5 (below) has no such room: one fit there would move the threshold itself."""
    assert _fits(scene, ff, 7, cell) >= 3


@pytest.mark.slow
@pytest.mark.parametrize("cell", [13, 26])
def test_the_cell_never_fits_linker_5(scene, ff, cell):
    assert _fits(scene, ff, 5, cell) == 0


# The fast cases (make test): one seed each way on each cell (random start: a cell that is not
# `auto` holds no lattice), measured 2026-11-27 on bpy 5.0.1, MODEL_VERSION 6, `run --periodic M
# --protocol inflate --globule-diameter 30 --linker L --seed S` (58-88 s each at a load of 20 on
# 2 cores; about 10 s each alone): at linker 7 seed 5 on 13 layers and seed 3 on 26 fit in their
# first cycle (the table's rows: cycle 0; seed 6 on 13 layers too), seed 0 at linker 5 is a
# clear miss after its first cycle on both. (frames, clashing pairs, worst stretch)
FAST = {(13, 7, 5): (801, 0, 0.0359), (13, 5, 0): (801, 14, 1.1465),
        (26, 7, 3): (801, 0, 0.0188), (26, 5, 0): (801, 31, 1.1059)}


@pytest.mark.parametrize("cell, linker, seed", sorted(FAST))
def test_one_seed_of_the_cell_at_linker_7_and_at_5(scene, ff, cell, linker, seed):
    frames, pairs, stretch = FAST[cell, linker, seed]
    r = ff.pipeline.run_model(P.make_params(protocol="inflate", periodic=cell, linker=linker,
                                            seed=seed), scene)
    assert r["checks_agree"] and r["periodic"]["cell_layers"] == cell
    assert r["accommodated"] is (linker == 7) and len(r["inflate"]["cycles"]) == 1
    assert r["frames_simulated"] == frames and len(r["clashing_pairs"]) == pairs
    assert r["max_bond_stretch"] == pytest.approx(stretch, abs=5e-4)
