"""The real-shape thresholds after MODEL_VERSION 4 (the joint's bond measured at the CA): the
minimal linker of a domain as its convex hull, under inflate, as `make validate-shapes` and the
TDP-43 runs measured them (docs/validation.md#real-shapes,
docs/guide/atoms-and-domains.md#tdp43-real-shapes):

- ubiquitin (1UBQ) on 6CU7, 20 layers: 6 (3/3 fit; 5: 0/3);
- GFP (1GFL chain A) on 2N0A, 20 layers: 7 (2/3 fit; 6: 0/3);
- three ubiquitin hulls as TDP-43's RRM2, RRM1 and NTD on 8QX9, 16 layers, 4 unscored at each
  end: 5 (3/3 fit; 4: 0/3).

The thresholds and the fits at them are read from the two pages' tables (issue #46: editing a
published threshold fails the fast case; tests/unit/test_docs_tables.py names it above them).
The fast cases (make test) take one seed at the same settings, fitting at the threshold and not
one below. The full ones (`slow`) take seeds 0-2 as the docs did. Fewer layers are no fast case:
on 10 layers ubiquitin's hull fits at 5 too (measured, seed 0, 40 s a run).
"""
import json
import re

import pytest
from docs_rows import docs_table
from helpers import ROOT

EXAMPLES, DATA = ROOT / "examples", ROOT / "tests" / "data"
HULL = ("--domain-shape", "hull", "--protocol", "inflate")
UBIQUITIN = ("--case", str(EXAMPLES / "asyn_6cu7_ubiquitin.toml"))
GFP = ("--case", str(EXAMPLES / "asyn_2n0a_gfp.toml"))
TDP43 = ("--case", str(EXAMPLES / "numbers" / "tdp43_8qx9.toml"), *("--domain", str(DATA / "1ubq.pdb.gz")) * 3,
         "--domain-linker", "23,24", "--globule-diameter", "30.276", "--layers", "16",
         "--score-layers", "4")


def accommodated(ff, tmp_path, case, linker: int, seed: int) -> bool:
    out = tmp_path / f"linker{linker}-seed{seed}.json"
    assert ff.cli.main(["run", *case, *HULL, "--linker", str(linker), "--seed", str(seed),
                        "--quiet", "--json", str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["params"]["domain_shape"] == "hull" and r["checks_agree"]
    if r["accommodated"]:
        assert r["intersecting_faces"] == 0 and r["max_bond_stretch"] <= 0.05
    return r["accommodated"]




def published() -> dict[str, tuple[int, int]]:
    """{name: (threshold, fits of seeds 0-2 at it)} as the pages give them: the hull table of
    docs/validation.md#real-shapes ("7 (2/3 fit; 6: 0/3)") and the three hulls' rows of
    docs/guide/atoms-and-domains.md#tdp43-real-shapes (the shortest linker some seed fits at,
    none at the one below)."""
    out = {}
    for row in docs_table("validation.md", "| case | source | observed | P(fit) at the real"):
        m = re.fullmatch(r"(\d+) \((\d)/3 fit; (\d+): 0/3\)", row["minimal linker"])
        assert m and int(m[3]) == int(m[1]) - 1, row["minimal linker"]
        name = {"`asyn_6cu7_ubiquitin.toml`": "ubiquitin", "`asyn_2n0a_gfp.toml`": "gfp"}[
            row["case"].split()[0]]
        out[name] = int(m[1]), int(m[2])
    rows = docs_table("guide/atoms-and-domains.md", "| chain | linker to domain 1 | fits (seeds")
    fits = {int(r["linker to domain 1"]): int(r["fits (seeds 0, 1, 2)"].split("/")[0])
            for r in rows if r["chain"] == "three ubiquitin hulls"}
    threshold = min(k for k, n in fits.items() if n)
    assert fits[threshold - 1] == 0, fits
    out["tdp43"] = threshold, fits[threshold]
    return out


# case, threshold, fits of seeds 0-2 at the threshold in the docs (none one below)
CASES = {"ubiquitin": UBIQUITIN, "gfp": GFP, "tdp43": TDP43}
CLAIMS = {name: (CASES[name], *found) for name, found in published().items()}
# the seed measured to fit at the threshold and not one below (see the fast test)
ONE_SEED = {"ubiquitin": 0, "gfp": 0, "tdp43": 0}


# A run that does not fit goes through the whole schedule (5 cycles, 805 frames of 20 layers of
# hulls): minutes each. The fast cases run on one bpy, the Makefile's BPY (one_bpy,
# tests/blender/conftest.py): the eight runs compared on 4.2, 5.0 and 5.2 for issue #32 (hulls,
# spheres, TDP-43-like chains, a periodic cell) gave the same numbers to the digit, so the other
# two would repeat them at three times the cost; `make test-slow` runs the full ones on all three.


@pytest.mark.one_bpy
@pytest.mark.timeout(1800)  # past the 300 s default: 194 s the longest under MODEL_VERSION 6 (below)
@pytest.mark.parametrize("name", list(ONE_SEED))
def test_one_seed_fits_at_the_threshold_and_not_one_below(scene, ff, tmp_path, name):
    """Measured 2026-11-25 on bpy 5.0.1, a shared 2-core machine: ubiquitin's hull, seed 0,
    fits at linker 6 in its first cycle (161 frames, worst stretch 0.09 %), not at 5: no
    clash, but a bond stretched 8.4 % after 10 cycles (1607 frames; the docs found 8.4 and
    8.7 % for the two seeds that fit at 5 before MODEL_VERSION 4); the test took 352 s at a load
    of 3-4 (4.3 min of CPU).
    GFP's hull, seed 0: fits at 7 in its 4th cycle (644 frames, worst stretch 4.35 %, 51 s), not
    at 6 (3 clashing pairs, 46 % stretch, 805 frames, 62 s), at a load of 3.
    TDP-43's three hulls, seed 0: fit at 5 in the 2nd cycle (322 frames, worst stretch 1.3 %,
    bake 254 s), not at 4 (3 clashing pairs, 64 % stretch, 805 frames, bake 539 s), as the docs
    (3, 2, 2 pairs; 64-74 %); the test took 811 s at a load of 10 (6 min of CPU).
    Re-timed under MODEL_VERSION 6 (issue #46; `make test`'s junit, bpy 5.0.1, commit 5513144,
    2026-11-27 02:28 UTC, the other two bpy passes beside it on 2 cores): ubiquitin 194 s, GFP
    104 s, TDP-43 42 s, 340 s in all, the longest part of the bpy 5.0 pass (1165 s)."""
    (case, threshold, _), seed = CLAIMS[name], ONE_SEED[name]
    assert accommodated(ff, tmp_path, case, threshold, seed)
    assert not accommodated(ff, tmp_path, case, threshold - 1, seed)


@pytest.mark.slow
@pytest.mark.parametrize("name", list(CLAIMS))
def test_the_threshold_over_three_seeds(scene, ff, tmp_path, name):
    """The docs' measurement again: at the threshold at least as many of seeds 0-2 fit as the
    docs found less one (a seed's fit turns on its last regrows), and one below none does (a fit
    there would move the threshold itself)."""
    case, threshold, measured = CLAIMS[name]
    fits = sum(accommodated(ff, tmp_path, case, threshold, seed) for seed in range(3))
    assert fits >= max(1, measured - 1)
    assert not any(accommodated(ff, tmp_path, case, threshold - 1, seed) for seed in range(3))
