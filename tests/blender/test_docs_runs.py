"""One short run at one seed for each physics table whose runs are cheap: the
number the run gives is read from the page's table (docs_rows.docs_table), so that editing it, or
code that stops giving it, fails here (issue #46; tests/unit/test_docs_tables.py names these tests
above their tables).

- docs/validation.md#gallery (MODEL_VERSION 6): the tutorial's minimal linker, 5, and one below:
  seed 0 fits at 5 and not at 4 (inflate, as the walk); the negative control on 20 layers at its
  real linker, seed 0: no layout found (a clear miss at its first judgement, 161 frames);
- docs/guide/atoms-and-domains.md#tdp43-three-domains: the lumped 40 Å sphere at linker 3, seed
  0, tutorial protocol, jams with 36 clashing pairs and a bond stretched 374 %;
- the same page, "Under inflate": that sphere at linker 3 under inflate finds no layout (its
  pairs and stretch, 31 and 260 % at MODEL_VERSION 2, are not today's: since MODEL_VERSION 6
  a clear miss ends the run at its judgement, docs/model/search.md#clear-miss);
- the same page, #tdp43-minimal-linker: the lumped sphere's minimal linker, 7, and one below:
  seed 0 fits at 7 and not at 6;
- docs/model/domain-shapes.md#measured: ubiquitin's sphere on 6CU7, 10 layers, inflate: seed 0
  fits at 4 and not at 3.

Timed 2026-11-27 07:12-07:15 UTC on bpy 5.0.1 (pytest under /usr/bin/time, the shared 2 cores
at load 13-18): the negative control 79 s of wall time but 15 s of CPU (5OQV's exit path measured
in it), the other five 135 s of wall, 37 s of CPU; at load ~6 (06:58 UTC) the guides' four took
5.6, 2.5, 48 and 31 s (pytest --durations). The tables name bpy 5.0.1, the Makefile's BPY, so
these run there only (one_bpy: the numbers to the digit are that bpy's)."""
import json
import re

import pytest
from docs_rows import docs_table
from helpers import ROOT

EXAMPLES = ROOT / "examples"
TDP43 = ("--case", str(EXAMPLES / "numbers" / "tdp43_8qx9.toml"), "--layers", "16", "--score-layers", "4")
UBIQUITIN = ("--case", str(EXAMPLES / "asyn_6cu7_ubiquitin.toml"), "--layers", "10")
GUIDE = "guide/atoms-and-domains.md"
GALLERY = "| case | experiment says |"
SPHERE = "one 40 Å sphere"


def gallery_row(case: str) -> dict:
    return next(r for r in docs_table("validation.md", GALLERY) if r["case"].startswith(case))


def run(ff, tmp_path, *args) -> dict:
    out = tmp_path / f"run{len(list(tmp_path.iterdir()))}.json"
    assert ff.cli.main(["run", *args, "--quiet", "--json", str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["checks_agree"]
    return r


@pytest.mark.one_bpy
def test_the_lumped_sphere_jams_at_linker_3_under_the_tutorial_protocol(scene, ff, tmp_path):
    row = next(r for r in docs_table(GUIDE, "| chain | linker to domain 1 | seed | verdict |")
               if r["chain"] == SPHERE and r["linker to domain 1"] == "3")
    pairs = int(re.fullmatch(r"intersection \((\d+) pairs\)", row["verdict"])[1])
    stretch = int(re.fullmatch(r"(\d+) %", row["worst bond stretch"])[1])
    r = run(ff, tmp_path, *TDP43, "--protocol", "tutorial", "--linker", "3", "--seed", row["seed"])
    assert r["verdict"] == "intersection" and not r["accommodated"]
    assert (len(r["clashing_pairs"]), round(100 * r["max_bond_stretch"])) == (pairs, stretch)


@pytest.mark.one_bpy
def test_the_lumped_sphere_finds_no_layout_at_linker_3_under_inflate(scene, ff, tmp_path):
    row = next(r for r in docs_table(GUIDE, "| chain | linker to domain 1 | protocol | answer |")
               if r["chain"] == SPHERE and r["protocol"].startswith("inflate"))
    r = run(ff, tmp_path, *TDP43, "--protocol", "inflate", "--linker", row["linker to domain 1"],
            "--seed", "0")
    assert r["answer"] == row["answer"] == "no layout found"


@pytest.mark.one_bpy
def test_the_lumped_spheres_minimal_linker_one_seed(scene, ff, tmp_path):
    row = next(r for r in docs_table(GUIDE, "| chain | minimal linker to domain 1 |")
               if r["chain"] == SPHERE)
    minimal = int(re.fullmatch(r"\*\*(\d+)\*\*", row["minimal linker to domain 1"])[1])
    assert row["one shorter"] == f"0/3 at {minimal - 1}"
    args = (*TDP43, "--protocol", "inflate", "--seed", "0")
    assert run(ff, tmp_path, *args, "--linker", str(minimal))["accommodated"]
    assert not run(ff, tmp_path, *args, "--linker", str(minimal - 1))["accommodated"]


@pytest.mark.one_bpy
def test_ubiquitins_sphere_minimal_linker_on_10_layers_one_seed(scene, ff, tmp_path):
    row = next(r for r in docs_table("model/domain-shapes.md", "| domain on fibril | shape (")
               if r["domain on fibril"].startswith("ubiquitin")
               and r["shape (protocol)"] == "`sphere` (inflate)")
    m = re.fullmatch(r"(\d+) \((\d)/2 fit; 0% at (\d+)\)",
                     row["minimal linker (restarts fitting; below)"])
    minimal = int(m[1])
    assert int(m[3]) == minimal - 1
    args = (*UBIQUITIN, "--protocol", "inflate", "--seed", "0")
    assert run(ff, tmp_path, *args, "--linker", str(minimal))["accommodated"]
    assert not run(ff, tmp_path, *args, "--linker", str(minimal - 1))["accommodated"]


@pytest.mark.one_bpy
def test_the_tutorials_minimal_linker_one_seed(scene, ff, tmp_path):
    row = gallery_row("`tutorial.toml`")
    m = re.fullmatch(r"(\d+) \(3/3 fit; (\d+): 0/3\)", row["minimal linker (walk)"])
    minimal = int(m[1])
    assert int(m[2]) == minimal - 1
    args = ("--case", str(EXAMPLES / "tutorial.toml"), "--protocol", "inflate", "--seed", "0")
    assert run(ff, tmp_path, *args, "--linker", str(minimal))["accommodated"]
    assert not run(ff, tmp_path, *args, "--linker", str(minimal - 1))["accommodated"]


@pytest.mark.one_bpy
def test_the_negative_control_on_20_layers_fits_at_its_real_linker(scene, ff, tmp_path):
    """MODEL_VERSION 8 (the exit rule: 1 residue spent): the 20-layer negative control fits in
    every seed, the row says so (docs/validation.md#negative-control)."""
    case = "abeta42_5oqv_gfp_linker12_20layers.toml"
    row = gallery_row(f"`{case}`")
    said = row["FibrilFit says at the real linker (answer: P(fit))"]
    r = run(ff, tmp_path, "--case", str(EXAMPLES / case), "--seed", "0")
    assert r["params"]["linker"] == int(row["real linker"])
    assert said.startswith(r["answer"] + ": 3/3") and r["answer"] == "fits"
