"""The cheapest rows of the model pages' physics tables, re-run under today's model and compared
with the page (tests/docs_rows.py reads the row, or, for a page that renders the table from a
measured file, docs/data/model/*.csv, that file: so editing a number there makes these fail).
Those tables were measured under older model versions; each page says under the table that the
row was re-checked under MODEL_VERSION 6 and names the test here.

- docs/model/end-effects.md#end-effects: 20 layers, linker 6, 250 frames, no settling, seeds
  0-2: no clashing pair, none deeper than the grazing band, no layer whose globule clashes.
- docs/model/linker-integrity.md#linker-integrity: 30 Å, 20 layers, 250 frames, no settling,
  seeds 0-4, linker 6 at 5 × 5 and 10 × 10 (substeps × iterations) and linker 4 at 10 × 10: the
  worst stretch at the end, the worst after the push-apart (or "never back"), the frames the
  push-apart ended at, and how many were accommodated.
- docs/model/search.md#inflate-schedule: the default schedule, 30 Å, linker 5, 20 layers, seeds
  0-4: accommodated, how many in the first cycle, the median frames.
- docs/model/protofilaments.md#stretched-linkers: the old MESH core's table changed with the
  solid core; the table beside it, under MODEL_VERSION 6: 6CU7 + ubiquitin, linker 20, 20
  layers, seed 0, two protofilaments and one: the worst stretch and the members inside a core.
- docs/model/settling.md#settling: its rows' bakes were not recorded; the row beside them, under
  MODEL_VERSION 6: the default model, 20 layers, seeds 0-4, settled against the full bake.
- docs/model/periodic-cell.md#cell-search: the table beside the old one, under MODEL_VERSION 6:
  the 13-layer cell at 30 Å, linker 5 (seeds 0-4, each a clear miss at its first judgement) and
  linker 7 (seeds 5 and 6, each a fit in cycle 0).

Measured 2026-11-27 (07:05-07:30 UTC) on bpy 5.0.1, 4.2.0 and 5.2.3: every seed's numbers the
same on the three (the counts, stretches to 1e-6, frames), so the answer does not depend on the
bpy: one_bpy. CPU a test 10-26 s (about 120 s for all), wall 15-150 s at a load of 10-15 on this
2-core machine; the rows with 100-200 layers, 20 × 20 quality or linker 4's five cycles a seed
cost minutes and are left out."""
import csv
import statistics

import bpy
import pytest
from docs_rows import ROOT, row, span, table

from fibrilfit import pipeline
from fibrilfit.model import params as P

MODEL = ROOT / "docs" / "model"
DATA = ROOT / "docs" / "data" / "model"


def data_table(name: str) -> list[dict[str, str]]:
    """The rows of the CSV `name` under docs/data/model/ (the file a model page renders its
    table from), each a {column: cell} as the page shows it."""
    with open(DATA / f"{name}.csv", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def _run(p):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    return pipeline.run_model(p, bpy.context.scene)


@pytest.mark.one_bpy
def test_end_effects_20_layers_linker_6(scene):
    want = row(table(MODEL / "end-effects.md", "{#end-effects}", "| layers | linker |"),
               {"layers": "20", "linker": "6"})
    runs = [_run(P.make_params(layers=20, linker=6, frames=250, settle=False, seed=seed))
            for seed in (0, 1, 2)]
    pairs = [len(r["clashing_pairs"]) for r in runs]
    deep = [len(r["sphere_check"]["clashing_pairs"]) for r in runs]
    layers = [sum(bool(c) for c in r["layer_clashes"]) for r in runs]
    assert all(r["frames_simulated"] == 250 and len(r["layer_clashes"]) == 20 for r in runs)
    assert all(r["sphere_check"]["tolerance"] == pytest.approx(0.29, abs=0.005) for r in runs)
    assert (min(pairs), max(pairs)) == span(want["clashing pairs"])
    assert (min(deep), max(deep)) == span(want["deeper than 0.29 Å"])
    assert (min(layers), max(layers)) == span(want["layers whose globule clashes"])
    assert want["layers whose globule clashes"].endswith("of 20")


def _as_printed(fraction: float, cell: str) -> float:
    """A stretch in per cent, rounded as the cell prints it ("0.3 %": one decimal, "72 %": none)."""
    decimals = len(cell.split(" ")[0].partition(".")[2])
    return round(100 * fraction, decimals)


@pytest.mark.one_bpy
@pytest.mark.parametrize("linker, quality", [("6", "5 × 5"), ("6", "10 × 10"), ("4", "10 × 10")])
def test_linker_integrity_30A(scene, linker, quality):
    want = row(data_table("linker-integrity_quality"),
               {"globule": "30 Å", "linker": linker, "substeps × iterations": quality})
    steps, iterations = map(int, quality.split(" × "))
    runs = [_run(P.make_params(layers=20, globule_diameter=30, linker=int(linker), frames=250,
                               settle=False, substeps=steps, solver_iterations=iterations,
                               seed=seed))
            for seed in range(int(want["seeds"]))]
    end = max(r["max_bond_stretch"] for r in runs)
    assert _as_printed(end, want["stretch at end, worst"]) == span(want["stretch at end, worst"])[1]
    over = [r["push_apart_end_frame"] for r in runs]
    if want["worst after the push-apart"] == "never back":
        assert over == [None] * len(runs) and want["push-apart over by frame"] == "–"
        assert all(r["max_bond_stretch_after_push"] is None for r in runs)
    else:
        after = max(r["max_bond_stretch_after_push"] for r in runs)
        assert (_as_printed(after, want["worst after the push-apart"])
                == span(want["worst after the push-apart"])[1])
        assert (min(over), max(over)) == span(want["push-apart over by frame"])
    fits = sum(r["accommodated"] for r in runs)
    assert f"{fits}/{len(runs)}" == want["accommodated"]


@pytest.mark.one_bpy
def test_the_default_inflate_schedule_at_linker_5(scene):
    want = row(data_table("search_inflate_schedule"), {"key": "default"})
    runs = [_run(P.make_params(layers=20, globule_diameter=30, linker=5, protocol="inflate",
                               seed=seed)) for seed in range(5)]
    fits = sum(r["accommodated"] for r in runs)
    first = sum(r["inflate"]["cycles"][0]["accommodated"] for r in runs)
    frames = statistics.median(r["frames_simulated"] for r in runs)
    assert f"{fits}/5" == want["linker 5: accommodated"]
    assert f"{first}/5" == want["of which in the first cycle"]
    assert frames == span(want["median frames"])[0]


def _six_cu7_ubiquitin():
    """6CU7 + ubiquitin measured from the files, as bench/stretched_linkers.py sets them."""
    from fibrilfit import structure
    from fibrilfit.structure import mapping
    data = ROOT / "tests" / "data"
    return mapping.model_values(structure.measure_fibril(str(data / "6cu7.pdb.gz")),
                                structure.measure_domain(str(data / "1ubq.pdb.gz")))


@pytest.mark.one_bpy
@pytest.mark.parametrize("change, extra", [("none (linker 20, seed 0)", {"seed": 0}),
                                           ("one protofilament", {"seed": 0, "protofilaments": 1})])
def test_stretched_linkers_today(scene, change, extra):
    from fibrilfit.analysis.leaks import members_inside_core
    from fibrilfit.analysis.verdict import chain_positions
    want = row(data_table("protofilaments_stretched_today"), {"change (MODEL_VERSION 6)": change})
    p = P.make_params(**{**_six_cu7_ubiquitin(), "linker": 20, **extra})
    r = _run(p)
    inside = members_inside_core(p, chain_positions(pipeline.current_model()))
    assert p.layers == 20 and r["frames_simulated"] == 250
    stretch = want["worst stretch"]
    assert _as_printed(r["max_bond_stretch"], stretch) == span(stretch)[0]
    assert len(inside) == int(want["members inside a core"])


@pytest.mark.one_bpy
def test_the_default_model_settles_with_the_full_bakes_verdict(scene):
    want = row(data_table("settling_default_model"),
               {"model (MODEL_VERSION 6)": "default model, seeds 0–4"})
    full, short = [], []
    for seed in range(5):
        p = P.make_params(layers=20, globule_diameter=30, linker=6, frames=250, seed=seed)
        full.append(_run(p.replace(settle=False)))
        short.append(_run(p))
    assert all(f["frames_simulated"] == 250 for f in full)
    settled = [s["settled_at"] for s in short if s["settled_at"] is not None]
    assert all(s["settled_at"] == s["frames_simulated"] for s in short)
    assert int(want["bakes"]) == len(short)
    assert int(want["settled before frame 250"]) == sum(x < 250 for x in settled)
    assert int(want["same verdict as the full bake"]) == sum(
        f["verdict"] == s["verdict"] for f, s in zip(full, short))
    assert int(want["same `accommodated`"]) == sum(
        f["accommodated"] == s["accommodated"] for f, s in zip(full, short))
    assert (min(settled), max(settled)) == span(want["settled at"].removeprefix("frames "))


@pytest.mark.one_bpy
@pytest.mark.parametrize("linker", ["5", "7"])
def test_the_13_layer_cell_today(scene, linker):
    want = row(data_table("periodic-cell_cell_search_today"), {"linker": linker})
    low, high = span(want["seeds"])
    runs = [_run(P.make_params(globule_diameter=30, linker=int(linker), seed=seed,
                               periodic=int(want["cell (layers)"]), protocol="inflate"))
            for seed in range(int(low), int(high) + 1)]
    fits = [r for r in runs if r["accommodated"]]
    assert f"{len(fits)} of {len(runs)}" == want["accommodated"]
    judgements = [len(r["inflate"]["cycles"]) for r in runs]
    assert (min(judgements), max(judgements)) == span(want["judgements a seed"])
    assert all(r["inflate"]["clear_miss"] for r in runs if not r["accommodated"])
    pairs = [r["inflate"]["cycles"][-1]["clashing_pairs"] for r in runs]
    stretch = [round(100 * r["inflate"]["cycles"][-1]["max_bond_stretch"]) for r in runs]
    assert (min(pairs), max(pairs)) == span(want["clashing pairs at the last"])
    assert (min(stretch), max(stretch)) == span(want["stretch at the last"])
    if fits:
        cycles = [r["inflate"]["cycles"][-1]["cycle"] for r in fits]
        assert (min(cycles), max(cycles)) == span(want["fitted in cycle"])
    else:
        assert want["fitted in cycle"] == "–"
