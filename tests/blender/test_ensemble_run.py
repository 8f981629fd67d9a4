"""`run --ensemble` headless (docs/model/ensemble.md#use): a small model's run samples its
ensemble from the relaxed layout, the block is in the result JSON (schema-valid, values in range,
both halves), the map is an MRC whose header reads back, the run's seed fixes the ensemble; what
the sampler does not model is refused in one line naming the parameter, exit 2, nothing written;
a run whose layout does not fit says why no ensemble was sampled."""
import copy
import json

import jsonschema
import mrcfile
import numpy as np
import pytest
from helpers import ROOT

SMALL = ("--layers", "6", "--ensemble", "6", "--ensemble-replicas", "4", "--ensemble-burn-in",
         "4")


def run(ff, tmp_path, *args) -> tuple[int, dict | None]:
    out = tmp_path / f"run{len(list(tmp_path.iterdir()))}.json"
    code = ff.cli.main(["run", *args, "--quiet", "--json", str(out)])
    return code, (json.loads(out.read_text()) if out.exists() else None)


def stable(block: dict) -> dict:
    out = copy.deepcopy(block)
    out.pop("seconds")
    out["width"].pop("map_seconds")
    out.pop("map", None)
    return out


def test_run_with_an_ensemble(scene, ff, tmp_path):
    mrc = tmp_path / "m.mrc"
    code, r = run(ff, tmp_path, *SMALL, "--ensemble-map", str(mrc))
    assert code == 0 and r["accommodated"]
    schema = json.loads((ROOT / "docs/reference/result.schema.json").read_text(encoding="utf-8"))
    assert list(jsonschema.Draft202012Validator(schema).iter_errors(r)) == []
    e = r["ensemble"]
    od = e["outer_diameter"]
    assert e["sampled"] and e["seed"] == r["seed"] == 0
    assert (e["replicas"], e["sweeps"]) == (4, 6)
    # the ensemble moves the domains about the relaxed layout, not far from it: its outer
    # diameters bracket values within a third of the layout's own
    single = r["envelope"]["outer_diameter"]
    lo, hi = od["interval_95"]
    assert lo <= od["median"] <= hi and 0.67 * single < od["median"] < 1.5 * single
    assert len(od["halves"]["means"]) == 2 and od["halves"]["relative_difference"] < 0.2
    assert 0 < e["width"]["value"] < hi
    phi = np.asarray(e["radial_density"]["volume_fraction"])
    assert phi.max() > 0 and phi.min() >= 0
    with mrcfile.open(mrc) as m:
        assert float(m.voxel_size.x) == e["map"]["voxel"] == 3.0
        assert [float(m.header.origin[a]) for a in "xyz"] == \
            pytest.approx(e["map"]["origin"], abs=1e-3)
        assert list(m.data.shape) == e["map"]["shape_zyx"]
    # the run's seed fixes the ensemble; another seed gives another
    _, again = run(ff, tmp_path, *SMALL)
    assert stable(again["ensemble"]) == stable(e)
    _, other = run(ff, tmp_path, *SMALL, "--seed", "1")
    assert other["ensemble"]["seed"] == 1
    assert other["ensemble"]["outer_diameter"] != od


def test_what_the_sampler_does_not_model_is_refused(scene, ff, tmp_path, capsys):
    hull = ("--domain", str(ROOT / "tests/data/1ubq.pdb.gz"), "--domain-shape", "hull")
    for extra, name in [(("--occupancy", "0.5"), "occupancy:"), (hull, "domain_shape:")]:
        mrc = tmp_path / "never.mrc"
        code, r = run(ff, tmp_path, *SMALL, *extra, "--ensemble-map", str(mrc))
        err = capsys.readouterr().err.strip()
        assert code == 2 and r is None and not mrc.exists()
        assert len(err.splitlines()) == 1 and name in err and "the ensemble" in err, err


def test_a_run_that_does_not_fit_says_why_no_ensemble(scene, ff, tmp_path):
    code, r = run(ff, tmp_path, "--layers", "6", "--linker", "1", "--globule-diameter", "40",
                  "--ensemble", "4")
    assert code == 0 and not r["accommodated"]
    assert r["ensemble"]["sampled"] is False
    assert "does not fit" in r["ensemble"]["reason"]


def test_report_with_an_ensemble(scene, ff, tmp_path):
    """`report --ensemble`: the best layout's ensemble in report.json (the report schema), its
    picture (the projection and the radial density) embedded in the page, its rows in the
    envelope table."""
    out = tmp_path / "rep"
    assert ff.cli.main(["report", "--layers", "3", "--grow-frames", "20", "--hold-frames", "20",
                        "--regrow-cycles", "0", "--globule-diameter", "12", "--linker", "3",
                        "--restarts", "2", "--max-linker", "4", "--workers", "1", "--quiet",
                        "--ensemble", "4", "--ensemble-replicas", "4", "--out", str(out)]) == 0
    doc = json.loads((out / "report.json").read_text())
    e = doc["ensemble"]
    assert e["sampled"] and e["seed"] == doc["best_layout"]["seed"]
    assert doc["files"]["ensemble_plot"] == "ensemble.png" and (out / "ensemble.png").is_file()
    schema = json.loads((ROOT / "docs/reference/report.schema.json").read_text(encoding="utf-8"))
    assert list(jsonschema.Draft202012Validator(schema).iter_errors(doc)) == []
    page = (out / "report.html").read_text()
    assert 'alt="ensemble" src="data:image/png;base64,' in page
    assert "ensemble: outer diameter" in page and "ensemble: width" in page


def test_the_python_api_gives_the_commands_block(scene, ff, tmp_path):
    """api.ensemble of a model's values, of a run still in the scene, and api.run's option:
    the same block as `run --ensemble` for the same seed and options."""
    from fibrilfit import api
    _, r = run(ff, tmp_path, *SMALL)
    options = dict(sweeps=6, replicas=4, burn_in=4)
    assert stable(api.ensemble(layers=6, quiet=True, **options)) == stable(r["ensemble"])
    done = api.run(layers=6, quiet=True)
    assert stable(api.ensemble(done, **options)) == stable(r["ensemble"])
    assert done.ensemble is not None  # kept in the result it was sampled for
