"""Issue #36 §4: `--periodic auto` runs each seed in its own rung of the cell ladder, and the
result records the cell it ran in (docs/model/periodic-cell.md#cell-ladder)."""
from fibrilfit.model import params as P


def test_each_seed_runs_in_its_rung_and_the_result_says_which(scene, ff):
    p = P.make_params(periodic="auto", seed=1, frames=2, settle=False)
    r = ff.pipeline.run_model(p, scene)
    cell = r["periodic"]
    assert cell["cell_layers"] == cell["auto_cell_layers"] == 17  # 30 Å: rung 1 of 13 ... 26
    assert cell["cell_ladder"] == [13, 17, 20, 23, 26]
    assert len(r["globule_centres"]) == 17
    assert not any("measured margin" in w for w in r["warnings"])  # above the shortest rung
