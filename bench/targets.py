"""The three speed targets of issue #35, each the whole command in a fresh process, with its wall
time, the peak resident memory of its process tree and the machine's load; `--baseline DIR`
runs each from another checkout too (alternating order), for a side-by-side table.

    .venv/bin/python bench/targets.py [--rounds 1] [--only report,map,validate]
                                      [--baseline DIR] [--quick] [--json out/bench_targets.json]

- report: `bench/report.py` (6CU7 + ubiquitin, linker 8, 8 restarts, 2 workers) — target 60 s;
- map: the infinite fibril's minimal-linker map, `minimal-linker --globule-diameter 20:50:10
  --periodic auto --restarts 5 --workers 2 --no-plot` — target 10 min;
- validate: `tools/validate.py --no-docs` (make validate) into an empty results folder —
  target 10 min (the venv's one-time set-up is not in it).

`--quick` (make bench QUICK=1, CI) checks that each still runs and answers on a small case
(report on 6 layers, 2 restarts; the map at 20 Å, 2 restarts; validate on the tutorial case, 1
restart); its times mean nothing. The map's answer is checked either way: each diameter's
minimal linker in its minimal_linker.csv must be the one docs/notebook/search.md#map-v5
publishes (bench/docs_map.py), else the target fails (quick: 20 Å, 4, which seed 0 shows:
tests/blender/test_auto_cell.py).
"""
import csv
import argparse
import json
import os
import pathlib
import shutil
import statistics
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
import docs_map  # bench/docs_map.py, the same way
import report as report_bench  # bench/report.py: run as a script, this file's folder is sys.path[0]

TARGETS_S = {"report": 60, "map": 600, "validate": 600}


def commands(code: pathlib.Path, name: str, out: pathlib.Path, quick: bool) -> list[str]:
    py = sys.executable
    if name == "report":  # this checkout's bench/report.py, running `code`'s headless.py
        cmd = [py, str(ROOT / "bench" / "report.py"), "--code", str(code), "--out", str(out)]
        return cmd + (["--quick"] if quick else [])
    if name == "map":
        return [py, str(code / "headless.py"), "minimal-linker", "--globule-diameter",
                "20" if quick else "20:50:10", "--periodic", "auto", "--restarts",
                "2" if quick else "5", "--workers", "2", "--no-plot", "--quiet", "--out", str(out)]
    if name == "validate":
        cmd = [py, str(code / "tools" / "validate.py"), "--no-docs", "--out", str(out)]
        return cmd + (["--restarts", "1", str(code / "examples" / "tutorial.toml")] if quick else [])
    raise ValueError(name)


def map_answer(out: pathlib.Path) -> tuple[list[str], bool]:
    """The map's minima (its minimal_linker.csv) against the docs' table: one line per diameter,
    "D Å: minimal linker M (docs: N)", and whether every one is the published number (False
    too for a missing or empty file, or a diameter the docs do not publish)."""
    published = docs_map.published_map()
    path = out / "minimal_linker.csv"
    if not path.exists():
        return [f"{path}: not written"], False
    lines, same = [], True
    for row in csv.DictReader(path.open(encoding="utf-8")):
        d = float(row["globule_diameter"])
        want = published.get(int(d), {}).get("minimal_linker") if d == int(d) else None
        got = row["minimal_linker"] or "none found"
        lines.append(f"{d:g} Å: minimal linker {got} (docs: "
                     f"{want if want is not None else 'not published'})")
        same &= got == str(want)
    return (lines, same) if lines else ([f"{path}: no rows"], False)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--only", default="report,map,validate")
    ap.add_argument("--baseline", type=pathlib.Path)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", type=pathlib.Path, default=ROOT / "out" / "bench_targets")
    ap.add_argument("--json", type=pathlib.Path)
    args = ap.parse_args()
    names = [n.strip() for n in args.only.split(",") if n.strip()]
    bad = set(names) - set(TARGETS_S)
    if bad:
        sys.exit(f"--only: one or more of {', '.join(TARGETS_S)} (got {', '.join(sorted(bad))})")
    sides = [("this", ROOT)] + ([("baseline", args.baseline.resolve())] if args.baseline else [])
    figures = {}
    failed = False
    for name in names:
        for k in range(args.rounds):
            for side, code in (sides if k % 2 == 0 else sides[::-1]):
                out = args.out / f"{name}-{side}-{k}"
                shutil.rmtree(out, ignore_errors=True)
                m = report_bench.measured(commands(code, name, out, args.quick), code)
                figures.setdefault(name, {}).setdefault(side, []).append(m)
                ok = m["returncode"] == 0
                failed |= not ok
                print(f"{name} ({side}, round {k + 1}): wall {m['wall_s']} s, peak "
                      f"{m['peak_rss_mib']} MiB, load {m['load_before'][0]} -> "
                      f"{m['load_after'][0]}" + ("" if ok else f"; FAILED: {m['stderr_tail']}"),
                      flush=True)
                if name == "map" and side == "this" and ok:  # the answer, not only the exit code
                    m["minima"], same = map_answer(out)
                    failed |= not same
                    print("  map's answer: " + "; ".join(m["minima"])
                          + ("" if same else "; FAILED: not docs/notebook/search.md#map-v5's"),
                          flush=True)
    print(f"\n| target | side | median wall | rounds | peak memory | load (1 min) before-after "
          f"| target |{' (quick: times mean nothing)' if args.quick else ''}")
    print("|---|---|---|---|---|---|---|")
    for name, by_side in figures.items():
        for side, ms in by_side.items():
            walls = [m["wall_s"] for m in ms]
            print(f"| {name} | {side} | {statistics.median(walls):.1f} s | {len(ms)} | "
                  f"{max(m['peak_rss_mib'] for m in ms)} MiB | "
                  f"{min(m['load_before'][0] for m in ms)}-{max(m['load_after'][0] for m in ms)} | "
                  f"{TARGETS_S[name]} s |")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(figures, indent=1))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    main()
