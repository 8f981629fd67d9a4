"""The measurements of docs/model/occupancy.md, one JSON line per run on stdout (tutorial protocol,
the default model otherwise; run with bpy importable, e.g. the project's .venv):

    python tools/occupancy_runs.py nested SEED   # shortest fitting linker at f = 0.25, 0.5, 1
    python tools/occupancy_runs.py cell          # random f = 0.5 and layers 'A.' in cells of
                                                 # 14 and 28 layers, and 'A.' at linker 4 in more
    python tools/occupancy_runs.py tails [LINKER [A:B]]  # the auto cell at linker 4 (or
                                                 # LINKER), f = 0.5, seeds 0-2 (or A..B-1),
                                                 # without and with a 40-residue bare tail
    python tools/occupancy_runs.py unchanged OUT.json   # five f = 1 models' whole results, to
                                                 # compare between two checkouts (PYTHONPATH)
    python tools/occupancy_runs.py hetero SEED   # shortest fitting linker of AA, AB (B 40 Å)
                                                 # and all-40 Å, and an AB inflate run
"""
import json
import sys
import time

import bpy

from fibrilfit import pipeline
from fibrilfit.model import params as P


def run(**values) -> dict:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    t = time.perf_counter()
    r = pipeline.run_model(P.make_params(**values))
    return {**{k: v for k, v in values.items()}, "fits": r["accommodated"], "answer": r["answer"],
            "decorated": (r.get("occupancy") or {}).get("decorated", r["params"]["layers"]),
            "stretch": r["max_bond_stretch"], "pairs": len(r["clashing_pairs"]),
            **({"tail_pairs": len(r["tail_clashes"]["pairs"]),
                "tail_depth": r["tail_clashes"]["max_depth"]} if "tail_clashes" in r else {}),
            **({"cell_layers": r["periodic"]["cell_layers"]} if "periodic" in r else {}),
            "frames": r["frames_simulated"], "settled_at": r["settled_at"],
            "seconds": round(time.perf_counter() - t, 1)}


def nested(seed: int) -> None:
    """16 layers, 150 frames: the linker scanned upward from 1 to the first fit, per fraction."""
    for f in (0.25, 0.5, 1.0):
        for linker in range(1, 13):
            row = run(layers=16, occupancy=f, linker=linker, seed=seed, frames=150)
            print(json.dumps(row), flush=True)
            if row["fits"]:
                break


def cell() -> None:
    for linker in (3, 5, 7):
        for m in (14, 28):
            for s in range(6):
                print(json.dumps(run(periodic=m, linker=linker, seed=s, occupancy=0.5)), flush=True)
    for linker in (2, 3, 4, 5):
        for m in (14, 28):
            for s in range(3):
                print(json.dumps(run(periodic=m, linker=linker, seed=s, pattern="layers",
                                     pattern_layers="A.")), flush=True)
    for m in (16, 18, 20, 22):
        for s in range(3):
            print(json.dumps(run(periodic=m, linker=4, seed=s, pattern="layers",
                                 pattern_layers="A.")), flush=True)


def tails(linker: int = 4, seeds: str = "0:3") -> None:
    """The auto cell (default model, tutorial), f = 0.5, at `linker`: bare_tail 0 and 40
    (alpha-synuclein's C-terminal tail) under the same seeds (`seeds` a range "a:b"), so the
    same patterns."""
    lo, hi = map(int, seeds.split(":"))
    for tail in (0, 40):
        for s in range(lo, hi):
            print(json.dumps(run(periodic="auto", linker=linker, occupancy=0.5, bare_tail=tail,
                                 seed=s)), flush=True)


def hetero(seed: int) -> None:
    """docs/model/occupancy.md#hetero: 16 layers, 150 frames, the linker scanned upward from 2
    to the first fit: A 30 Å on every layer (AA), A 30 Å and B 40 Å alternating (AB), 40 Å on
    every layer; then one AB run under inflate (10 layers, linker 8)."""
    for name, extra in (("AA 30", dict(pattern_layers="AA")),
                        ("AB 30/40", dict(pattern_layers="AB", domain_b_diameter=40.0)),
                        ("AA 40", dict(pattern_layers="AA", globule_diameter=40.0))):
        for linker in range(2, 16):
            row = run(layers=16, pattern="layers", linker=linker, seed=seed, frames=150, **extra)
            print(json.dumps({"case": name, **row}), flush=True)
            if row["fits"]:
                break
    row = run(layers=10, pattern="layers", pattern_layers="AB", domain_b_diameter=40.0,
              linker=8, seed=seed, protocol="inflate", regrow_cycles=1, near_cycles=0)
    print(json.dumps({"case": "AB 30/40 inflate", **row}), flush=True)


UNCHANGED = {"default": {}, "linker4": dict(linker=4, frames=120),
             "cell": dict(periodic="auto", frames=80),
             "inflate": dict(protocol="inflate", layers=10, linker=8, regrow_cycles=1,
                             near_cycles=0),
             "two_pf": dict(layers=10, protofilaments=2, pf_rotation=3.13, pf_rise=2.3,
                            frames=80, score_layers=2)}


def unchanged(path: str) -> None:
    """Every result but its timings and code versions, for a key-by-key comparison."""
    out = {}
    for name, values in UNCHANGED.items():
        bpy.ops.wm.read_factory_settings(use_empty=True)
        r = pipeline.run_model(P.make_params(**values))
        for key in ("timings_s", "fibrilfit_version", "model_sources_sha256", "code"):
            r.pop(key, None)
        out[name] = r
    with open(path, "w", encoding="utf-8") as f:
        json.dump(out, f, sort_keys=True, default=str)


if __name__ == "__main__":
    if sys.argv[1:2] == ["nested"]:
        nested(int(sys.argv[2]))
    elif sys.argv[1:2] == ["cell"]:
        cell()
    elif sys.argv[1:2] == ["tails"]:
        tails(*([int(sys.argv[2])] if sys.argv[2:] else []), *sys.argv[3:4])
    elif sys.argv[1:2] == ["hetero"]:
        hetero(int(sys.argv[2]))
    elif sys.argv[1:2] == ["unchanged"]:
        unchanged(sys.argv[2])
    else:
        sys.exit(__doc__)
