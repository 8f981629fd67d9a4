"""`headless.py report` on 6CU7 + ubiquitin: wall time of the whole command, the time of each
stage (report.json's timings_s), and the machine's load while it ran.

    .venv/bin/python bench/report.py [--restarts 8] [--workers 2] [--linker 8] [--out DIR]

Target (issue #23): within 3 minutes on a 2-core machine with 8 restarts on 2 workers. The
machine is shared: the load average before and after is printed beside the time.
"""
import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--restarts", type=int, default=8)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--linker", type=int, default=8)
    ap.add_argument("--out", type=pathlib.Path, default=ROOT / "out" / "bench_report")
    args = ap.parse_args()
    shutil.rmtree(args.out, ignore_errors=True)
    cmd = [sys.executable, str(ROOT / "headless.py"), "report", "--fibril",
           str(DATA / "6cu7.pdb.gz"), "--domain", str(DATA / "1ubq.pdb.gz"), "--linker",
           str(args.linker), "--restarts", str(args.restarts), "--workers", str(args.workers),
           "--out", str(args.out), "--quiet"]
    load0 = os.getloadavg()
    t = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t
    load1 = os.getloadavg()
    if proc.returncode != 0:
        sys.exit(f"report failed ({proc.returncode}): {proc.stderr.strip()[-500:]}")
    doc = json.loads((args.out / "report.json").read_text())
    print(" ".join(cmd[1:]))
    print(f"wall {wall:.1f} s on {os.cpu_count()} cores; load average (1, 5, 15 min) before "
          f"{load0[0]:.1f} {load0[1]:.1f} {load0[2]:.1f}, after {load1[0]:.1f} {load1[1]:.1f} "
          f"{load1[2]:.1f}")
    print(f"stages (s): {doc['timings_s']}")
    m = doc["minimal_linker"]
    print(f"answer {doc['answer']}; P(fit) {doc['p_fit']['fits']}/{doc['p_fit']['runs']} at "
          f"linker {doc['p_fit']['linker']}; minimal linker {m['linker']} (tried "
          f"{sorted(int(k) for k in m['tried'])})")


if __name__ == "__main__":
    main()
