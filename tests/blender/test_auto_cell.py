"""Issue #36 §4: `--periodic auto` under inflate picks a cell holding whole periods of the
lattice start, and the result records the cell and the lattice
(docs/model/periodic-cell.md#auto-cell, docs/model/search.md#lattice-start)."""
import pytest

from fibrilfit.model import params as P


def test_the_result_records_the_cell_and_its_lattice(scene, ff):
    p = P.make_params(periodic="auto", protocol="inflate", grow_frames=2, hold_frames=2,
                      regrow_cycles=0, near_cycles=0)
    r = ff.pipeline.run_model(p, scene)
    cell = r["periodic"]
    assert cell["cell_layers"] == cell["auto_cell_layers"] == 18  # 30 Å: 3 rows a side
    assert cell["lattice_rows"] == 3 and len(r["globule_centres"]) == 18
    assert not any("measured margin" in w for w in r["warnings"])
    # 4 frames of growth, no regrow: judged at once, a clear miss (measured 2026-11-27: 19
    # clashing pairs, 101 % stretch, 21 frames); the full search is the fast case below
    assert r["frames_simulated"] == 21 and r["accommodated"] is False
    assert r["verdict"] == "intersection" and len(r["clashing_pairs"]) == 19
    r = ff.pipeline.run_model(p.replace(periodic=13, layers=13), scene)
    assert r["periodic"]["lattice_rows"] == 0 and r["periodic"]["auto_cell_layers"] == 18


def _fits(scene, ff, diameter, linker, cell="auto", seeds=range(5)):
    fits = 0
    for seed in seeds:
        p = P.make_params(globule_diameter=diameter, periodic=cell, protocol="inflate",
                          linker=linker, seed=seed)
        r = ff.pipeline.run_model(p, scene)
        assert r["checks_agree"] and r["periodic"]["cell_layers"] == p.periodic
        if r["accommodated"]:
            assert r["intersecting_faces"] == 0 and r["max_bond_stretch"] <= 0.05
        fits += r["accommodated"]
    return fits


@pytest.mark.slow
def test_the_auto_cell_fits_20A_globules_at_linker_4_in_most_seeds(scene, ff):
    """Measured 2026-11-25 (docs/notebook/search.md#auto-cell): 4 of seeds 0-4 in the 12-layer
    cell from the lattice start (seed 4 ends near: 2 pairs, 3.6 %), where the 9-layer cell
    `auto` picked before fitted none and the 12-layer cell from the random start 2 of 5."""
    assert _fits(scene, ff, 20, 4) == 4


@pytest.mark.slow
def test_the_auto_cell_gives_the_30A_row_of_the_map(scene, ff):
    """Measured 2026-11-25 (docs/notebook/search.md#auto-cell), the 18-layer cell from the
    lattice start: linker 7 fits every seed (cycles 0, 1, 2, 2, 4), linker 6 none (10-17
    clashing pairs, 34-45 % stretch)."""
    assert _fits(scene, ff, 30, 7) == 5
    assert _fits(scene, ff, 30, 6) == 0


@pytest.mark.slow
def test_twice_the_auto_cell_fits_20A_globules_at_linker_4_as_often(scene, ff):
    """The check at 2x the cell: 24 layers fit linker 4 in 4 of seeds 0-4 (seed 3 ends near:
    clash-free, 9.5 %), the 12-layer cell's share."""
    assert _fits(scene, ff, 20, 4, cell=24) == 4
