"""The traces behind a stopping rule for one run (issue #35): inflate runs baked to their end as
today, each inflate cycle's judgement kept (cycle, frame, clashing pairs, worst stretch, deepest
overlap: the result's `inflate.cycles`), then every candidate rule replayed on them: how many
runs it would have stopped early that went on to fit (must be 0), and the frames it saves.

    nice -n 15 .venv/bin/python bench/stop_traces.py run [--only NAME,...] [--out DIR]
    .venv/bin/python bench/stop_traces.py table [--out DIR]      # the table, from what ran

`run` goes through SYSTEMS in order, one `headless.py sweep --workers 1 --resume` each, into
DIR/<name>/ (default out/stop_traces): interrupted, it continues where it stopped. `table`
reads every DIR/*/results.jsonl (only runs baked to their end: `to_the_end`). `run` switches
the clear-miss rule off (--clear-miss-pairs 0 --clear-miss-stretch 0), so its runs are such.
"""
import argparse
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"


def to_the_end(r: dict) -> bool:
    """Whether an inflate run was baked to the end of its schedule: MODEL_VERSION 5, or a later
    one with the clear-miss rule off. From MODEL_VERSION 6 a clear miss ends a run early
    (docs/model/search.md#clear-miss): its trace is cut where the rule fired and says nothing of
    what would have come after."""
    p = r.get("params") or {}
    return r.get("model_version") == 5 or (
        (r.get("model_version") or 0) >= 6
        and p.get("clear_miss_pairs") == 0 and p.get("clear_miss_stretch") == 0)


SEEDS = "10"  # seeds 0-9 per point (seed-major: an interrupted system covers its grid evenly)

# (name, sweep options): small layer counts, linkers at and just below each system's minimum
# (docs/minimal_linker.csv at 20 layers; docs/notebook/search.md#infinite-fibril-map for the
# cell), so that both fits and misses, early and late, are in the data. Cheapest first. (At 8
# layers the slab's 30 Å domains all fit at linker 4 at the first judgement: measured, the
# first system; 8 layers are easier than 20, so the other slab points are at 20 layers.)
SYSTEMS = [
    ("slab8_d30", ["--layers", "8", "--globule-diameter", "30", "--linker", "4,5"]),
    # the cell at 30 Å, linker 7: 4 of 5 seeds fit there (the map), some after regrows
    ("cell_d30_7", ["--periodic", "auto", "--globule-diameter", "30", "--linker", "7"]),
    ("cell_d20", ["--periodic", "auto", "--globule-diameter", "20", "--linker", "4,5"]),
    ("6cu7_ubq8", ["--fibril", str(DATA / "6cu7.pdb.gz"), "--domain", str(DATA / "1ubq.pdb.gz"),
                   "--layers", "8", "--linker", "4,5"]),
    ("cell_d30_6", ["--periodic", "auto", "--globule-diameter", "30", "--linker", "6"]),
    ("slab20_d30", ["--globule-diameter", "30", "--linker", "4,5"]),
    ("cell_d40", ["--periodic", "auto", "--globule-diameter", "40", "--linker", "10,11"]),
]


def run(out: pathlib.Path, only: set | None) -> None:
    for name, opts in SYSTEMS:
        if only and name not in only:
            continue
        cmd = [sys.executable, str(ROOT / "headless.py"), "sweep", *opts, "--protocol", "inflate",
               "--seeds", SEEDS, "--clear-miss-pairs", "0", "--clear-miss-stretch", "0", "--workers", "1", "--out", str(out / name), "--resume",
               "--no-plot", "--quiet"]
        print(" ".join(cmd[1:]), flush=True)
        proc = subprocess.run(cmd)
        if proc.returncode:
            sys.exit(f"{name}: sweep exited {proc.returncode}")


def system(path: pathlib.Path) -> str:
    """A results file's system: its folder, or for a validation run's `real` and
    `minimal-linker` folders the case's folder too (out/validate/<case>/real)."""
    if path.parent.name in ("real", "minimal-linker"):
        return f"{path.parent.parent.name}/{path.parent.name}"
    return path.parent.name


def traces(out: pathlib.Path, also=()) -> list[dict]:
    """One row per run: its system (`system`), params, whether it fit, frames, and its cycles;
    from DIR/*/results.jsonl and the results files in `also` (e.g. a report's), of the model
    runs baked to their end (`to_the_end`)."""
    rows = []
    for path in sorted(out.glob("*/results.jsonl")) + [pathlib.Path(a) for a in also]:
        for line in path.read_text().splitlines():
            try:
                r = json.loads(line)
            except json.JSONDecodeError:
                continue
            if r.get("status") != "ok" or not to_the_end(r):
                continue
            cycles = (r.get("inflate") or {}).get("cycles") or []
            if not cycles:  # not an inflate run (e.g. the tutorial protocol): no judgements
                continue
            rows.append({"system": system(path), "linker": r["params"]["linker"],
                         "diameter": r["params"]["globule_diameter"], "seed": r["seed"],
                         "fit": bool(r["accommodated"]), "frames": r["frames_simulated"],
                         "near": (r.get("inflate") or {}).get("near_cycles_granted"),
                         "cycles": cycles, "params": r["params"]})
    return rows


# ---- candidate rules: (name, fires(params, cycle record) -> True: stop after this judgement) ----

def _near(p, c) -> bool:
    """judgement.near_fit on a cycle's record (deepest overlap at most 1 Å, stretch at most 3 x tol)"""
    return (float(c.get("max_overlap") or 0.0) <= 1.0
            and c["max_bond_stretch"] <= 3.0 * p["stretch_tolerance"])


def rule(after: int, pairs: int | None = None, stretch: float | None = None, both: bool = False):
    """Stop after the judgement of cycle >= `after` when it is not a near miss and (if given)
    has at least `pairs` clashing pairs, or (if given) a worst stretch of at least `stretch`
    times the tolerance (with `both`: and, not or)."""
    def fires(p, c):
        if c["accommodated"] or c["cycle"] < after or _near(p, c):
            return False
        hit = []
        if pairs is not None:
            hit.append(c["clashing_pairs"] >= pairs)
        if stretch is not None:
            hit.append(c["max_bond_stretch"] >= stretch * p["stretch_tolerance"])
        return (all(hit) if both else any(hit)) if hit else True
    bits = [f"pairs >= {pairs}"] if pairs is not None else []
    if stretch is not None:
        bits.append(f"stretch >= {stretch:g} x tol")
    return ", ".join([f"cycle >= {after}", "not near"]
                     + ([(" and " if both else " or ").join(bits)] if bits else [])), fires


def no_near_cycles():
    """The near-miss cycles never granted: stop at the last regular cycle's judgement."""
    return ("cycle >= regrow_cycles (no near-miss cycles)",
            lambda p, c: not c["accommodated"] and c["cycle"] >= p["regrow_cycles"])


def regrow_cycles(c0: int):
    """What the existing model parameter `--regrow-cycles c0` would have done (the option this
    data is for: it is off at today's 4): a clear miss stops at cycle c0's judgement, a near
    miss there gets near_cycles more. (Cycles after c0 are the same regrows either way; a run
    whose trace ends before the new schedule would stop is counted as not stopped.)"""
    def fires(p, c):
        if c["accommodated"] or c["cycle"] < c0:
            return False
        return (c["cycle"] == c0 and not _near(p, c)) or c["cycle"] >= c0 + p["near_cycles"]
    return f"--regrow-cycles {c0} (today 4)", fires


RULES = [rule(0), rule(1), rule(2), rule(0, pairs=4), rule(1, pairs=4), rule(0, stretch=5),
         rule(1, stretch=5), rule(0, pairs=8, stretch=10), rule(1, pairs=8, stretch=10),
         rule(0, pairs=8, stretch=10, both=True),
         no_near_cycles(), regrow_cycles(0), regrow_cycles(1), regrow_cycles(2)]


def replay(rows: list[dict], fires) -> dict:
    """What the rule would have done: runs stopped early, of those how many fit in the end,
    frames saved (the frame of the stopping judgement against the run's own end)."""
    stopped = wrong = saved = total = 0
    for r in rows:
        total += r["frames"]
        for c in r["cycles"]:
            if fires(r["params"], c) and c["judged_at"] < r["frames"]:
                stopped += 1
                wrong += r["fit"]
                saved += r["frames"] - c["judged_at"]
                break
    return {"stopped": stopped, "stopped_then_fit": wrong,
            "frames_saved": round(saved / total, 3) if total else 0.0}


def table(out: pathlib.Path, also=()) -> str:
    rows = traces(out, also)
    fits = sum(r["fit"] for r in rows)
    late = sum(r["fit"] and len(r["cycles"]) > 1 for r in rows)
    lines = [f"{len(rows)} runs ({fits} fit, {late} of them after a regrow; "
             f"{len(rows) - fits} misses) in {len({r['system'] for r in rows})} systems: "
             + ", ".join(f"{s} {sum(r['system'] == s for r in rows)}"
                         for s in sorted({r['system'] for r in rows})),
             "",
             "| rule: stop after a judgement that is ... | runs stopped early | of them fit in the end | frames saved |",
             "|---|---|---|---|"]
    for name, fires in RULES:
        x = replay(rows, fires)
        lines.append(f"| {name} | {x['stopped']} | **{x['stopped_then_fit']}** | "
                     f"{100 * x['frames_saved']:.0f} % |")
    lines += ["", "| system | linker | runs | fit | fit at cycle (count) | misses' frames | "
                  "first judgement of the runs that fit late: pairs, stretch/tol, overlap Å |",
              "|---|---|---|---|---|---|---|"]
    for key in sorted({(r["system"], r["linker"]) for r in rows}):
        rs = [r for r in rows if (r["system"], r["linker"]) == key]
        at = {}
        for r in rs:
            if r["fit"]:
                at[len(r["cycles"]) - 1] = at.get(len(r["cycles"]) - 1, 0) + 1
        miss_frames = sorted(r["frames"] for r in rs if not r["fit"])
        firsts = [r["cycles"][0] for r in rs if r["fit"] and len(r["cycles"]) > 1]
        tol = rs[0]["params"]["stretch_tolerance"]
        first = "; ".join(f"{c['clashing_pairs']}, {c['max_bond_stretch'] / tol:.1f}, "
                          f"{c.get('max_overlap') or 0:.1f}" for c in firsts) or "-"
        lines.append(f"| {key[0]} | {key[1]} | {len(rs)} | {sum(r['fit'] for r in rs)} | "
                     + (", ".join(f"{k}: {v}" for k, v in sorted(at.items())) or "-") + " | "
                     + (f"{miss_frames[0]}-{miss_frames[-1]}" if miss_frames else "-")
                     + f" | {first} |")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("what", choices=("run", "table"))
    ap.add_argument("--out", type=pathlib.Path, default=ROOT / "out" / "stop_traces")
    ap.add_argument("--only", help="comma-separated system names")
    ap.add_argument("--also", nargs="*", default=[],
                    help="more results.jsonl files (e.g. a report's) for the table")
    args = ap.parse_args()
    if args.what == "run":
        run(args.out, set(args.only.split(",")) if args.only else None)
    print(table(args.out, args.also))


if __name__ == "__main__":
    main()
