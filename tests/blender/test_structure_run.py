"""`run` and `sweep` with --fibril/--domain: the model filled from the files, explicit options
winning, and a `structure` block in every result."""
import importlib
import json

import numpy as np
import pytest
from helpers import ROOT, run_cli

DATA = ROOT / "tests" / "data"
FAST = ["--layers", "4", "--linker", "3", "--frames", "10"]


def test_run_fills_the_model_from_files_and_records_them(ff, scene, tmp_path, capsys):
    out = tmp_path / "r.json"
    code = ff.cli.main(["run", "--fibril", str(DATA / "2n0a.pdb.gz"), "--domain",
                        str(DATA / "1gfl.pdb.gz"), *FAST, "--stop-after", "build",
                        "--json", str(out)])
    assert code == 0
    r = json.loads(out.read_text())
    s = r["structure"]
    S = importlib.import_module("fibrilfit.structure")
    fib = S.measure_fibril(DATA / "2n0a.pdb.gz")
    dom = S.measure_domain(DATA / "1gfl.pdb.gz")
    values = S.model_values(fib, dom)
    assert s["fibril"]["file"] == "2n0a.pdb.gz" and s["domain"]["file"] == "1gfl.pdb.gz"
    assert s["fibril"]["sha256"] == fib.sha256 and s["domain"]["sha256"] == dom.sha256
    assert s["fibril"]["measured"]["twist"] == fib.twist
    assert s["domain"]["measured"]["rg"] == dom.rg
    # every measured value is used, overridden by an option, or named as not in this model
    assert set(s["applied"]) | set(s["overridden"]) | set(s["not_in_model"]) == set(values)
    assert s["overridden"] == ["linker"] and r["params"]["linker"] == 3  # the option wins
    for name, value in s["applied"].items():
        assert np.allclose(r["params"][name], value, atol=1e-9), name
    assert r["params"]["twist"] == fib.twist > 0 and r["params"]["rise"] == fib.rise
    assert r["params"]["globule_diameter"] == dom.globule_diameter
    err = capsys.readouterr().err
    assert ("not in this model" in err) == bool(s["not_in_model"])


def test_an_explicit_option_wins_and_no_file_means_no_block(ff, scene, tmp_path):
    out = tmp_path / "r.json"
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--twist", "0.02",
                        *FAST, "--stop-after", "build", "--json", str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["params"]["twist"] == 0.02 and "twist" in r["structure"]["overridden"]
    assert r["params"]["rise"] == pytest.approx(4.825, abs=0.002)  # tests/data/README.md; 4.8 fails
    # the protofilament model (issue "Real fibril geometry") takes the rest
    assert r["structure"]["not_in_model"] == []
    assert r["params"]["protofilaments"] == 2
    assert r["params"]["pf_rotation"] == pytest.approx(3.1325, abs=0.002)
    assert r["params"]["pf_rise"] == pytest.approx(2.41, abs=0.1)
    assert len(r["params"]["core_outline"]) > 50 and len(r["params"]["anchor"]) == 2
    assert "domain" not in r["structure"]
    assert ff.cli.main(["run", *FAST, "--stop-after", "build", "--json", str(out)]) == 0
    assert "structure" not in json.loads(out.read_text())


def test_run_with_a_bad_structure_writes_nothing(ff, scene, tmp_path, capsys):
    out = tmp_path / "r.json"
    code = ff.cli.main(["run", "--fibril", str(DATA / "1ubq.pdb.gz"), *FAST, "--json", str(out)])
    assert code == ff.exits.EXIT_USAGE and not out.exists()
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--fibril" in err[0] and "--rise" in err[0]


def test_sweep_grid_takes_measured_values_as_a_fixed_base(ff):
    grid = importlib.import_module("fibrilfit.sweep.grid")
    points = grid.build({"linker": ["2", "4"]}, ["0"], base={"twist": -0.0169, "rise": 4.825})
    assert [p.params["twist"] for p in points] == [-0.0169, -0.0169]
    assert all(set(p.point) == {"linker", "seed"} for p in points)  # not a sweep axis


@pytest.mark.slow
def test_sweep_from_files_records_the_structure(tmp_path):
    out = tmp_path / "s"
    cp = run_cli("sweep", "--fibril", str(DATA / "8a9l.pdb.gz"), "--domain",
                 str(DATA / "1ubq.pdb.gz"), "--linker", "2,3", "--layers", "4", "--frames", "10",
                 "--seeds", "1", "--workers", "1", "--no-plot", "--quiet", "--out", str(out))
    assert cp.returncode == 0, cp.stderr
    records = [json.loads(x) for x in (out / "results.jsonl").read_text().splitlines()]
    assert len(records) == 2
    for r in records:
        assert r["structure"]["fibril"]["file"] == "8a9l.pdb.gz"
        assert r["params"]["twist"] == r["structure"]["fibril"]["measured"]["twist"] > 0
        assert r["params"]["globule_diameter"] == 30.276  # 1UBQ measured (not the default 30.0)


def test_a_beta_solenoid_builds_one_domain_per_molecule(ff, scene, tmp_path):
    """2KJ3 (HET-s, two rungs per molecule): one layer of the model per molecule, so one domain
    and one core prism per molecule rise, not per rung (docs/guide/structures.md#beta-solenoids)."""
    out = tmp_path / "r.json"
    # the exit search finds no way out for G282's CA, sandwiched between rungs (a sealed exit
    # builds nothing): the measured anchor's bead is given, which takes no exit with it
    S = importlib.import_module("fibrilfit.structure")
    x, y = S.model_values(S.measure_fibril(DATA / "2kj3.pdb.gz"))["anchor"]
    assert ff.cli.main(["run", "--fibril", str(DATA / "2kj3.pdb.gz"), *FAST, "--anchor", str(x),
                        str(y), "--stop-after", "build", "--json", str(out)]) == 0
    r = json.loads(out.read_text())
    measured = r["structure"]["fibril"]["measured"]
    assert measured["rungs"] == 2 and r["params"]["rise"] == measured["rise"] > 8.0
    import bpy
    model = ff.builders.find_model(bpy.context.scene)
    assert len(model.slabs) == len(model.globules) == len(model.chain) == 4  # one per molecule
    # the layers (anchors) stand one molecule rise apart along the axis, each core prism as tall
    z = sorted(np.array(c[0].matrix_world)[2, 3] for c in model.chain)
    assert np.diff(z) == pytest.approx([measured["rise"]] * 3, abs=1e-3)
    heights = {round(float(np.ptp([v.co.z for v in s.data.vertices])), 3) for s in model.slabs}
    assert heights == {round(measured["rise"], 3)}
