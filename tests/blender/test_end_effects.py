"""--score-layers: only interior layers count, and each scored layer says whether it clashes."""
import json

from helpers import run_cli

from fibrilfit.model import params as P
from fibrilfit import pipeline


def test_scored_layers_and_layer_clashes_on_a_baked_model(scene):
    p = P.make_params(layers=10, linker=1, frames=40, settle=False)
    every = pipeline.run_model(p, scene)
    inner = pipeline.run_model(p.replace(score_layers=3), scene)  # same bake: same seed
    assert every["globule_centres"] == inner["globule_centres"]
    assert every["scored_layers"] == [0, 9] and inner["scored_layers"] == [3, 6]
    assert None not in every["layer_clashes"]
    assert inner["layer_clashes"][:3] == [None] * 3 and inner["layer_clashes"][7:] == [None] * 3
    assert inner["layer_clashes"][3:7] == every["layer_clashes"][3:7]
    # A pair counts when at least one of its globules is scored.
    want = [q for q in every["clashing_pairs"] if 3 <= q[0] <= 6 or 3 <= q[1] <= 6]
    assert inner["clashing_pairs"] == want and want
    for k, clash in enumerate(every["layer_clashes"]):
        assert clash == any(k in q[:2] for q in every["clashing_pairs"])


def test_cli_score_layers(tmp_path):
    out = run_cli("run", "--layers", "8", "--linker", "1", "--frames", "20", "--score-layers", "2",
                  "--json", str(tmp_path / "r.json"))
    assert out.returncode == 0, out.stderr
    r = json.loads((tmp_path / "r.json").read_text())
    assert r["params"]["score_layers"] == 2 and r["scored_layers"] == [2, 5]
    assert "in layers 2-5" in out.stdout
    out = run_cli("run", "--layers", "8", "--frames", "2", "--score-layers", "all", "--quiet",
                  "--json", str(tmp_path / "all.json"))
    assert out.returncode == 0, out.stderr
    r = json.loads((tmp_path / "all.json").read_text())  # "all": every layer scored
    assert r["params"]["score_layers"] == 0 and r["scored_layers"] == [0, 7]
    assert None not in r["layer_clashes"] and len(r["layer_clashes"]) == 8
    out = run_cli("run", "--layers", "8", "--score-layers", "4", "--json", str(tmp_path / "x.json"))
    assert out.returncode == 2 and "score_layers" in out.stderr and "from 0 to 3" in out.stderr
    assert not (tmp_path / "x.json").exists()
