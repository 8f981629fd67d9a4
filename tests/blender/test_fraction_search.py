"""Issue #44 item 3 end to end: `largest-fraction` on a tiny fibril (3 layers: N = 3 subunits,
restarts 2) through the command line, its files, its bracket and its resumption; and
`minimal-linker --occupancy` on the same fibril (the floor at the fraction)."""
import json
import subprocess
import sys

from helpers import ROOT

PY = sys.executable
TINY = ["--layers", "3", "--grow-frames", "20", "--hold-frames", "20", "--regrow-cycles", "0",
        "--workers", "1", "--quiet", "--restarts", "2"]


def test_largest_fraction_writes_its_map_brackets_it_and_resumes(tmp_path):
    out = tmp_path / "lf"
    # 20 Å balls on 3 layers need linker 2 when every subunit carries one (test_search's
    # minimal-linker case): at linker 1 the walk has fewer than all three to find
    cmd = [PY, str(ROOT / "headless.py"), "largest-fraction", "--globule-diameter", "20",
           "--linker", "1", *TINY, "--out", str(out)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads((out / "largest_fraction.json").read_text())
    (row,) = doc["rows"]
    assert row["subunits"] == 3 and row["linker"] == 1
    runs = [json.loads(x) for x in (out / "results.jsonl").read_text().splitlines()]
    k = row["largest_count"]
    if k is not None:  # a fit at k: a run with k of 3 decorated was accommodated
        assert any(r["accommodated"] and round(r["params"]["occupancy"] * 3) == k for r in runs)
        assert row["largest_fraction"] == round(k / 3, 6)
    if row["count_above"] is not None and not row["above_settled_by_bound"]:
        above = [r for r in runs if round(r["params"]["occupancy"] * 3) == row["count_above"]]
        assert len(above) == 2 and not any(r["accommodated"] for r in above)
    assert row["bracket"].startswith("impossible above ")
    assert f"20 Å, linker 1: {row['bracket']}" in proc.stdout
    # every run's own bound block is the one at its fraction
    for r in runs:
        f = r["params"]["occupancy"]
        assert (r["bound"].get("fraction") == round(f, 6)) == (f < 1.0)
    head = (out / "largest_fraction.csv").read_text().splitlines()[0].split(",")
    assert head[:6] == ["kind", "globule_diameter", "linker", "subunits", "largest_count",
                        "largest_fraction"]
    assert (out / "largest_fraction.png").read_bytes()[:4] == b"\x89PNG"
    lines = (out / "results.jsonl").read_text().splitlines()
    again = subprocess.run(cmd + ["--resume"], capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    assert (out / "results.jsonl").read_text().splitlines() == lines  # nothing run twice
    assert json.loads((out / "largest_fraction.json").read_text())["rows"] == doc["rows"]


def test_minimal_linker_at_a_fraction_walks_from_the_bound_at_that_fraction(tmp_path):
    from fibrilfit.model import fraction_bound, params as P
    out = tmp_path / "ml"
    cmd = [PY, str(ROOT / "headless.py"), "minimal-linker", "--globule-diameter", "20",
           "--occupancy", "0.34", "--max-linker", "3", *TINY, "--out", str(out)]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0, proc.stderr
    (row,) = json.loads((out / "minimal_linker.json").read_text())["rows"]
    p = P.make_params(globule_diameter=20, occupancy=0.34, layers=3, protocol="inflate")
    assert row["floor"] == fraction_bound.impossible_below_at(p, 1 / 3)
    assert row["minimal_linker"] is not None
    runs = [json.loads(x) for x in (out / "results.jsonl").read_text().splitlines()]
    assert all(r["occupancy"]["decorated"] == 1 for r in runs)
