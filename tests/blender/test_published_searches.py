"""The 20 Å rows of the docs' current-model maps, recomputed by the search that made them and
compared with the page (tests/docs_rows.py reads it, so editing a number there makes these fail);
what needs no bake (cells, bounds, brackets) is tests/unit/test_published_maps.py.

- docs/benchmarks.md#map-v6-cost, the minimal-linker map at MODEL_VERSION 6 (`minimal-linker
  --periodic auto --restarts 5 --workers 2`): at 20 Å, in the 12-layer cell, its runs were 5
  misses, every one a clear miss, and 2 fits. The walk runs the 5 seeds one below the minimum
  (linker 3) and the minimum's (4) two at a time (the workers' width) until a fit: seeds 0 and 1
  both fit.
- docs/model/largest-fraction.md#map, the largest fraction at 20 Å, linker 3 (`largest-fraction
  --periodic auto --restarts 3`, one worker): 8 of 12 subunits, found by 1 run of 1, and 0 of
  3 at 9.

Measured 2026-11-27 on bpy 5.0.1 at 06:48 UTC (this worktree, model as main at 020e8b9): the
same counts as the pages; the minimal-linker walk 68 s and the largest-fraction search 69 s of
wall time, side by side on this 2-core machine at a load of 2-3 (the pages' costs: the map's
20 Å runs 27 worker-seconds, the fraction search 38). On bpy 4.2.0 and 5.2.3 (06:56 UTC) every
run of both searches was the same as on 5.0.1 (linker, decorated count, seed, fit, clear miss,
clashing pairs, worst stretch to 1e-4, frames), so the answer does not depend on the bpy:
one_bpy (about 100 s once, on the Makefile's BPY).
The 30-50 Å rows take minutes to hours each (docs/benchmarks.md#map-v6-cost,
docs/model/largest-fraction.md#cost) and are left to the bench."""
import json
import subprocess
import sys

import pytest
from docs_rows import largest_fraction_map, map_v6_runs
from helpers import ROOT

PY = sys.executable


def _search(tmp_path, command, *args):
    out = tmp_path / command
    proc = subprocess.run([PY, str(ROOT / "headless.py"), command, "--globule-diameter", "20",
                           "--periodic", "auto", "--quiet", "--out", str(out), *args],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    runs = [json.loads(x) for x in (out / "results.jsonl").read_text().splitlines()]
    return out, runs


@pytest.mark.one_bpy
def test_the_20A_runs_of_the_map_at_model_version_6(tmp_path):
    row = map_v6_runs()[20]
    out, runs = _search(tmp_path, "minimal-linker", "--restarts", "5", "--workers", "2",
                        "--no-plot")
    assert {r["periodic"]["cell_layers"] for r in runs} == {row["cell_layers"]}
    misses = [r for r in runs if not r["accommodated"]]
    assert len(misses) == row["misses"]
    assert sum(r["inflate"]["clear_miss"] for r in misses) == row["clear_misses"]
    assert len(runs) - len(misses) == row["fits"]
    (walk,) = json.loads((out / "minimal_linker.json").read_text())["rows"]
    assert {r["params"]["linker"] for r in misses} == {walk["minimal_linker"] - 1}


@pytest.mark.one_bpy
def test_the_20A_linker_3_row_of_the_largest_fraction_map(tmp_path):
    row = next(r for r in largest_fraction_map() if (r["diameter"], r["linker"]) == (20, 3))
    out, runs = _search(tmp_path, "largest-fraction", "--linker", "3", "--restarts", "3",
                        "--workers", "1")
    (found,) = json.loads((out / "largest_fraction.json").read_text())["rows"]
    assert found["subunits"] == row["subunits"]
    assert found["largest_count"] == row["largest_count"]
    assert (found["fits"], found["restarts"]) == row["fits"]
    above = [r for r in runs if round(r["params"]["occupancy"] * row["subunits"])
             == row["above"][0]]
    assert len(above) == row["above"][1] and not any(r["accommodated"] for r in above)
    assert found["bracket"] == row["bracket"]
