"""`headless.py report` on 6CU7 + ubiquitin: wall time of the whole command, the time of each
stage (report.json's timings_s), peak memory and the machine's load while it ran; with
`--baseline DIR` the same command from another checkout (e.g. `git worktree add DIR <commit>`)
in every round, the two back to back in alternating order, and their answers compared.

    .venv/bin/python bench/report.py [--rounds 3] [--baseline DIR] [--restarts 8] [--workers 2]
                                     [--linker 8] [--out DIR] [--quick]

Target (issue #35): at most 60 s wall on a 2-core machine with 8 restarts on 2 workers, with
the same answer as the baseline on the same seeds: P(fit) at the linker, the minimal linker and
P(fit) one below it. The machine is shared: the load average before and after is printed beside
each time. `--quick` (make bench QUICK=1) checks that the command still runs and answers, on 6
layers with 2 restarts and a small picture; its time means nothing.
"""
import argparse
import json
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import threading
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"


def tree_rss_kib(pid: int) -> int:
    """Resident memory of a process and all its descendants (KiB), from /proc (Linux)."""
    total, todo = 0, [pid]
    while todo:
        p = todo.pop()
        try:
            with open(f"/proc/{p}/status") as f:
                total += next(int(line.split()[1]) for line in f if line.startswith("VmRSS:"))
            for task in os.listdir(f"/proc/{p}/task"):
                with open(f"/proc/{p}/task/{task}/children") as f:
                    todo += [int(c) for c in f.read().split()]
        except (OSError, StopIteration, ValueError):
            continue
    return total


def measured(cmd: list[str], code: pathlib.Path | None = None) -> dict:
    """Run `cmd`; its wall time, the load before and after, and the peak resident memory of its
    whole process tree (the command and its workers, sampled every 0.25 s). `code`: the
    checkout whose package the command's Python imports first (PYTHONPATH), for a baseline."""
    env = dict(os.environ)
    if code is not None:
        env["PYTHONPATH"] = os.pathsep.join([str(code)] + ([env["PYTHONPATH"]]
                                                          if env.get("PYTHONPATH") else []))
    load0 = os.getloadavg()
    t = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env=env)
    peak = [0]

    def sample():
        while proc.poll() is None:
            peak[0] = max(peak[0], tree_rss_kib(proc.pid))
            time.sleep(0.25)
    sampler = threading.Thread(target=sample, daemon=True)
    sampler.start()
    out, err = proc.communicate()
    wall = time.perf_counter() - t
    sampler.join()
    return {"wall_s": round(wall, 1), "load_before": [round(x, 1) for x in load0],
            "load_after": [round(x, 1) for x in os.getloadavg()],
            "peak_rss_mib": round(peak[0] / 1024), "returncode": proc.returncode,
            "stderr_tail": err.strip()[-400:]}


def answer(out: pathlib.Path) -> dict:
    """What the report answers: P(fit) at the linker, the minimal linker, P(fit) one below."""
    doc = json.loads((out / "report.json").read_text())
    m, pf = doc["minimal_linker"], doc["p_fit"]
    tried = m["tried"]
    below = m["linker_below"]
    return {"p_fit_at_linker": f"{pf['fits']}/{pf['runs']}", "minimal_linker": m["linker"],
            "below": below,
            "p_fit_below": ("proven 0 (bound)" if m.get("below_settled_by_bound") else
                            f"{tried[str(below)]['accommodated']}/{tried[str(below)]['restarts']}"
                            if below is not None and str(below) in tried else None),
            "runs": sum(t["restarts"] for t in tried.values())
            + sum(1 for L in [pf["linker"]] if str(L) not in tried) * pf["runs"],
            "stages_s": doc.get("timings_s")}


def command(code: pathlib.Path, args, out: pathlib.Path) -> list[str]:
    cmd = [sys.executable, str(code / "headless.py"), "report", "--fibril",
           str(DATA / "6cu7.pdb.gz"), "--domain", str(DATA / "1ubq.pdb.gz"), "--linker",
           str(args.linker), "--restarts", str(args.restarts), "--workers", str(args.workers),
           "--out", str(out), "--quiet"]
    if args.quick:
        cmd += ["--layers", "6", "--render-size", "160x90", "--render-samples", "1"]
    return cmd


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--baseline", type=pathlib.Path,
                    help="a checkout of the code to compare against (its headless.py)")
    ap.add_argument("--code", type=pathlib.Path, default=ROOT,
                    help="the checkout measured as 'this' (default: this one)")
    ap.add_argument("--restarts", type=int, default=8)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--linker", type=int, default=8)
    ap.add_argument("--out", type=pathlib.Path, default=ROOT / "out" / "bench_report")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--json", type=pathlib.Path, help="write every round's figures here")
    args = ap.parse_args()
    if args.quick:
        args.restarts = min(args.restarts, 2)
    sides = [("this", args.code.resolve())] + ([("baseline", args.baseline.resolve())]
                                                if args.baseline else [])
    rounds = []
    for k in range(args.rounds):
        row = {}
        for name, code in (sides if k % 2 == 0 else sides[::-1]):
            out = args.out / f"{name}-{k}"
            shutil.rmtree(out, ignore_errors=True)
            m = measured(command(code, args, out), code)
            if m["returncode"] != 0:
                sys.exit(f"{name}: report failed ({m['returncode']}): {m['stderr_tail']}")
            row[name] = {**m, **answer(out)}
            print(f"round {k + 1} {name}: wall {m['wall_s']} s, peak {m['peak_rss_mib']} MiB, "
                  f"load {m['load_before'][0]} -> {m['load_after'][0]}; {row[name]}", flush=True)
        rounds.append(row)
    print(" ".join(command(ROOT, args, args.out)[1:]))
    print(f"{os.cpu_count()} cores")
    for name, _ in sides:
        walls = [r[name]["wall_s"] for r in rounds]
        print(f"{name}: median wall {statistics.median(walls):.1f} s over {len(walls)} rounds "
              f"({', '.join(f'{w:.1f}' for w in walls)}); peak {max(r[name]['peak_rss_mib'] for r in rounds)} MiB; "
              f"answer {({k: v for k, v in rounds[-1][name].items() if k in ('p_fit_at_linker', 'minimal_linker', 'below', 'p_fit_below')})}")
    if args.baseline:
        keys = ("p_fit_at_linker", "minimal_linker", "below", "p_fit_below")
        same = all(r["this"][k] == r["baseline"][k] for r in rounds for k in keys[:3])
        print("same answer (P(fit) at the linker, minimal linker, the length below): "
              + ("yes" if same else "NO"))
    if args.json:
        args.json.write_text(json.dumps(rounds, indent=1))


if __name__ == "__main__":
    main()
