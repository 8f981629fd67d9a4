"""Fast cases, in `make test`, of the slow physical checks of the cell and the search.

The slow tests (`make test-slow`) hold the full claims: the periodic verdicts at linker 6 and 8
(tests/blender/test_periodic.py), inflate's linker 5 fits / 4 never on 20 layers and the cell's
thresholds (tests/blender/test_search.py). These are the same physics, capped so that each case
runs in a few seconds of CPU, with the margins measured in docs/model/search.md#evidence.
"""
import importlib
import json

import pytest
from helpers import ROOT, run_cli

from fibrilfit.model import params as P

DATA = ROOT / "tests" / "data"

# The auto cell's verdicts at linker 6 and 8 (once capped here at 60 frames): test_periodic.py's
# full bake, in make test since it takes seconds (docs/model/search.md#evidence).


# The slow test's model (30 Å globules, 20 layers, inflate) with fewer regrows. A fibril of a few
# layers is no place for a "never": its end layers fan out along the axis, and 6, 8 and 10 layers
# (all scored, or 10 with 3 unscored at each end) fitted linker 4 in their first cycle, seeds 0-2
# (docs/model/search.md#evidence).
SHORT_SEARCH = {"protocol": "inflate", "regrow_cycles": 1}


def test_inflate_fits_linker_5_on_twenty_layers(scene, ff):
    r = ff.pipeline.run_model(P.make_params(linker=5, seed=2, **SHORT_SEARCH), scene)
    assert r["accommodated"] is True and r["intersecting_faces"] == 0
    assert r["max_bond_stretch"] <= 0.05 and r["checks_agree"]


@pytest.mark.parametrize("seed", [0, 1])
def test_inflate_never_fits_linker_4_on_twenty_layers(scene, ff, seed):
    """Every judgement of every cycle (and polish) is far from a fit: clashes, or linkers
    stretched by more than three times the tolerance (the whole schedule: the clear-miss rule
    off). With the rule on (the default) the run is the same up to where it stops, a miss."""
    p = P.make_params(linker=4, seed=seed, **SHORT_SEARCH)
    r = ff.pipeline.run_model(p.replace(clear_miss_pairs=0, clear_miss_stretch=0.0), scene)
    assert r["accommodated"] is False and r["verdict"] == "intersection"
    cycles = r["inflate"]["cycles"]
    assert [c["cycle"] for c in cycles if not c["polished"]] == [0, 1]
    assert all(not c["accommodated"] for c in cycles)
    assert all(c["clashing_pairs"] > 0 or c["max_bond_stretch"] > 0.15 for c in cycles)
    cut = ff.pipeline.run_model(p, scene)
    assert cut["accommodated"] is False
    assert cut["inflate"]["cycles"] == cycles[:len(cut["inflate"]["cycles"])]


def test_a_sweep_from_files_records_the_structure_in_its_worker(tmp_path):
    """The fast case of tests/blender/test_structure_run.py's sweep: one linker, one seed, one
    worker; the worker's record holds the structure and the model built from it."""
    out = tmp_path / "s"
    cp = run_cli("sweep", "--fibril", str(DATA / "8a9l.pdb.gz"), "--domain",
                 str(DATA / "1ubq.pdb.gz"), "--linker", "2", "--layers", "4", "--frames", "10",
                 "--seeds", "1", "--workers", "1", "--no-plot", "--quiet", "--out", str(out))
    assert cp.returncode == 0, cp.stderr
    (r,) = [json.loads(x) for x in (out / "results.jsonl").read_text().splitlines()]
    assert r["status"] == "ok" and r["structure"]["fibril"]["file"] == "8a9l.pdb.gz"
    assert r["params"]["twist"] == r["structure"]["fibril"]["measured"]["twist"] > 0
    assert r["params"]["globule_diameter"] == 30.276  # 1UBQ measured (not the default 30.0)


def test_a_near_miss_gets_near_cycles_and_a_clear_miss_does_not():
    """docs/model/search.md#near-cycles: the judgements of seed 0 (a near miss) and of linker 5
    (a clear miss) in the auto cell after their fifth cycle."""
    growth = importlib.import_module("fibrilfit.builders.growth")
    hook = growth.Inflate.__new__(growth.Inflate)
    hook.p, hook.extended = P.make_params(protocol="inflate", regrow_cycles=4, near_cycles=5), False
    near = {"accommodated": False, "max_overlap": 0.0601, "max_bond_stretch": 0.079408}
    far = {"accommodated": False, "max_overlap": 1.1341, "max_bond_stretch": 0.975223}
    hook.cycle = 3
    assert hook.last_cycle(near) == 4 and not hook.extended  # only from the last regular cycle
    hook.cycle = 4
    assert hook.last_cycle(far) == 4 and not hook.extended
    assert hook.last_cycle(near) == 9 and hook.extended
    hook.cycle = 6
    assert hook.last_cycle(far) == 9  # granted once, for the whole run
