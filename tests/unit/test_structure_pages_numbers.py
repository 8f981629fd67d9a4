"""Numbers of the structure guides' physics tables that today's code gives without a bake, read
from the pages (docs_rows.docs_table), so that editing one, or code that stops giving it, fails here
(issue #46; tests/unit/test_docs_tables.py names these tests above their tables):

- docs/guide/structures.md#run-from-files: the domains' sphere diameters (ubiquitin 30.3 Å, GFP
  43.9 Å), 6CU7's protofilaments, and the linker `--fibril 2n0a` fills in (44);
- docs/model/domain-shapes.md#measured-cell: the `auto` cell of GFP on 2N0A under the tutorial
  protocol (18 layers, as `sphere` and as `hull`). The table's inflate row (18 layers,
  MODEL_VERSION 2) is of an older model: since MODEL_VERSION 5 `auto` under inflate takes whole
  lattice periods (docs/model/periodic-cell.md#auto-cell), 24 layers for this sphere.

The runs of these tables are baked by tests/blender/test_docs_runs.py."""
import re

import pytest
from docs_rows import docs_table
from helpers import ROOT

from fibrilfit import structure
from fibrilfit.api.model import resolve
from fibrilfit.api.plans import RunPlan, make_plan

DATA, EXAMPLES = ROOT / "tests" / "data", ROOT / "examples"
FROM_FILES = docs_table("guide/structures.md", "| fibril + domain | linker | accommodated |")
CELL = docs_table("model/domain-shapes.md", "| GFP (1GFL chain A) on 2N0A | shape | linker |")


def test_the_domains_diameters_are_what_the_files_give():
    said = {m[1]: float(m[2]) for row in FROM_FILES
            for m in [re.search(r"\((1UBQ|1GFL), ([\d.]+) Å\)", row["fibril + domain"])] if m}
    assert set(said) == {"1UBQ", "1GFL"}
    for code, diameter in said.items():
        got = structure.measure_domain(DATA / f"{code.lower()}.pdb.gz").globule_diameter
        assert round(got, 1) == diameter, code


def test_6cu7s_protofilaments_and_2n0as_linker_are_what_the_files_give():
    first = FROM_FILES[0]["fibril + domain"]
    assert first.startswith("6CU7") and re.search(r"(\d+) protofilaments", first)
    assert structure.measure_fibril(DATA / "6cu7.pdb.gz").protofilaments == int(
        re.search(r"(\d+) protofilaments", first)[1])
    tail = next(r for r in FROM_FILES if "what `--fibril` fills in" in r["fibril + domain"])
    plan, _ = make_plan(RunPlan, {"fibril": str(DATA / "2n0a.pdb.gz"),
                                  "domain": str(DATA / "1gfl.pdb.gz")}, command="run")
    assert resolve(plan).p.linker == int(tail["linker"]) == int(
        re.search(r"linker (\d+)", tail["fibril + domain"])[1])


TUTORIAL_CELL = [r for r in CELL if re.fullmatch(r"`auto` cell \(\d+ layers\), tutorial",
                                                   r["GFP (1GFL chain A) on 2N0A"])]


@pytest.mark.parametrize("row", TUTORIAL_CELL, ids=lambda r: r["shape"].strip("`"))
def test_the_auto_cell_under_the_tutorial_protocol_is_todays(row):
    assert len(TUTORIAL_CELL) == 2  # `sphere` and `hull`
    fibril = row["GFP (1GFL chain A) on 2N0A"]
    layers = int(re.fullmatch(r"`auto` cell \((\d+) layers\), tutorial", fibril)[1])
    linker = int(row["linker"].split(" / ")[0])
    plan, _ = make_plan(RunPlan, {"periodic": "auto", "protocol": "tutorial", "linker": linker,
                                  "domain_shape": row["shape"].strip("`")},
                        case=str(EXAMPLES / "asyn_2n0a_gfp.toml"), command="run")
    p = resolve(plan).p
    assert p.periodic == p.layers == layers
