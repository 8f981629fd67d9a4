"""The periodic cell against the 100-layer interior job, side by side; prints one table.

    .venv/bin/python bench/periodic.py [--runs 3] [--linker 6] [--seed 0] [--cell auto]
                                       [--also-cell M] [--old CHECKOUT] [--floor]
                                       [--also-one-update]

Target (issue #12): a periodic job at the default model (`--periodic auto`) costs at most 1/4 of
the wall time of the 100-layer `--layers 100 --score-layers 20` job. Each job is the whole
command (`headless.py run`) in a fresh process, the two run back to back in every round, so the
ratio is taken within a round (the machine may be shared: trust the ratio, not the seconds).
Memory is each process's peak resident set (ru_maxrss of the child). "job" is the run's own
build + bake + check (timings_s), without starting Python and importing bpy. `--old CHECKOUT` adds
the periodic job run from another checkout (e.g. a git worktree of an older commit) in every round.

`--floor` adds, in every round, two jobs that bound what any periodic cell of the same M could
cost: "startup" (`--layers 1 --frames 1`: starting Python, importing bpy, building, one frame,
checking, writing the JSON) and "M plain layers" (the cell's M layers with no images at all, one
scene frame per frame, baked for exactly as many frames as the 100-layer job took this round, no
settling). A cell has these M layers' bodies plus its images, so neither floor is reachable by
any way of moving the images. `--also-one-update` adds the cell with one image update per frame
(`--image-updates 1`): the cheapest way Blender can move the images, whose contacts across the
ends bounce (docs/model/periodic-cell.md#periodic-cell); a cost, not a usable setting.
"""
from __future__ import annotations

import argparse
import json
import os
import pathlib
import resource
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
JOBS = {
    "periodic": ["--periodic", "auto"],
    "layers100": ["--layers", "100", "--score-layers", "20"],
}


def run_job(args: list[str], root: str = str(ROOT)) -> dict:
    """One `headless.py run` in a fresh process: wall time, peak memory, and its result."""
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "r.json"
        start = time.perf_counter()
        proc = subprocess.Popen([sys.executable, str(pathlib.Path(root) / "headless.py"), "run",
                                 *args, "--json", str(out), "--quiet"], cwd=root,
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        _, err = proc.communicate()
        wall = time.perf_counter() - start
        if proc.returncode not in (0, 1):
            raise RuntimeError(f"{' '.join(args)}: exit {proc.returncode}: {err.strip()}")
        result = json.loads(out.read_text())
    return {"wall_s": wall, "result": result}


def measure(args: list[str], root: str = str(ROOT)) -> dict:
    """run_job in a wrapper process, so the peak RSS reported is this job's alone."""
    code = ("import importlib.util, json, resource; "
            "s = importlib.util.spec_from_file_location('periodic_bench', %r); "
            "b = importlib.util.module_from_spec(s); s.loader.exec_module(b); "
            "r = b.run_job(%r, %r); "
            "u = resource.getrusage(resource.RUSAGE_CHILDREN); "
            "r['peak_mib'] = u.ru_maxrss / 1024.0; r['cpu_s'] = u.ru_utime + u.ru_stime; "
            "print('BENCH ' + json.dumps(r))") % (str(pathlib.Path(__file__).resolve()), args, root)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    line = next((ln for ln in out.stdout.splitlines() if ln.startswith("BENCH ")), None)
    if line is None:
        raise RuntimeError(out.stderr.strip()[-500:])
    return json.loads(line[6:])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--linker", default="6")
    ap.add_argument("--seed", default="0")
    ap.add_argument("--json", metavar="PATH", help="write every round's figures here")
    ap.add_argument("--old", metavar="CHECKOUT", help="also run the periodic job from here")
    ap.add_argument("--cell", default="auto", help="the periodic job's M (default auto)")
    ap.add_argument("--also-cell", metavar="M", help="also run a periodic job with this M")
    ap.add_argument("--also-one-update", action="store_true",
                    help="also run the cell with --image-updates 1")
    ap.add_argument("--floor", action="store_true",
                    help="also run the startup and M-plain-layers floors (see the docstring)")
    a = ap.parse_args(argv)
    extra = ["--linker", a.linker, "--seed", a.seed]
    jobs = {name: (args, str(ROOT)) for name, args in JOBS.items()}
    jobs["periodic"] = (["--periodic", a.cell], str(ROOT))
    if a.also_cell:
        jobs[f"periodic M={a.also_cell}"] = (["--periodic", a.also_cell], str(ROOT))
    if a.also_one_update:
        jobs["periodic, 1 image update per frame"] = (
            ["--periodic", a.cell, "--image-updates", "1"], str(ROOT))
    if a.old:
        jobs["periodic (--old)"] = (["--periodic", a.cell], str(pathlib.Path(a.old).resolve()))
    rounds = []
    for r in range(a.runs):
        row = {name: measure(args + extra, root) for name, (args, root) in jobs.items()}
        if a.floor:
            frames = row["layers100"]["result"]["frames_simulated"]
            cell = row["periodic"]["result"]["params"]["periodic"]
            floors = {"startup (1 layer, 1 frame)": ["--layers", "1", "--frames", "1"],
                      f"{cell} plain layers, no images, as many frames": [
                          "--layers", str(cell), "--frames", str(frames), "--no-settle"]}
            for name, args in floors.items():
                row[name] = measure(args + extra)
            names = list(jobs) + list(floors)
        else:
            names = list(jobs)
        for x in row.values():
            x["job_s"] = sum(x["result"]["timings_s"].values())
        row["ratio"] = row["periodic"]["wall_s"] / row["layers100"]["wall_s"]
        row["cpu_ratio"] = row["periodic"]["cpu_s"] / row["layers100"]["cpu_s"]
        row["job_ratio"] = row["periodic"]["job_s"] / row["layers100"]["job_s"]
        rounds.append(row)
        print(f"round {r + 1}: periodic {row['periodic']['wall_s']:.2f} s "
              f"{row['periodic']['peak_mib']:.0f} MiB, 100 layers {row['layers100']['wall_s']:.2f} s "
              f"{row['layers100']['peak_mib']:.0f} MiB, ratio {row['ratio']:.3f} "
              f"(CPU time {row['cpu_ratio']:.3f}, job {row['job_ratio']:.3f})", flush=True)
    med = lambda xs: statistics.median(xs)  # noqa: E731
    per = rounds[0]["periodic"]["result"]
    print(f"\nperiodic cell of {per['params']['periodic']} layers vs 100 layers, --score-layers 20 "
          f"(linker {a.linker}, seed {a.seed}; median of {a.runs} rounds, "
          f"{os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f})")
    print("| job | wall (s) | CPU (s) | peak memory (MiB) | job (s) | bake (s) | scene frames |")
    print("|---|---|---|---|---|---|---|")
    for name in names:
        rs = [row[name] for row in rounds]
        print(f"| {name} | {med([x['wall_s'] for x in rs]):.2f} | "
              f"{med([x['cpu_s'] for x in rs]):.2f} | {med([x['peak_mib'] for x in rs]):.0f} | "
              f"{med([x['job_s'] for x in rs]):.2f} | "
              f"{med([x['result']['timings_s']['bake'] for x in rs]):.2f} | "
              f"{med([x['result']['frames_simulated'] for x in rs]):.0f} |")
    ratio = med([row["ratio"] for row in rounds])
    cpu = med([row["cpu_ratio"] for row in rounds])
    job = med([row["job_ratio"] for row in rounds])
    mem = med([row["periodic"]["peak_mib"] / row["layers100"]["peak_mib"] for row in rounds])
    if a.floor:
        for name in names[len(jobs):]:
            fr = med([row[name]["wall_s"] / row["layers100"]["wall_s"] for row in rounds])
            fj = med([row[name]["job_s"] / row["layers100"]["job_s"] for row in rounds])
            print(f"floor {name} / 100 layers: wall {fr:.3f}, job {fj:.3f}")
    print(f"wall-time ratio periodic / 100 layers: {ratio:.3f} (target <= 0.25: "
          f"{'met' if ratio <= 0.25 else 'NOT met'}); CPU-time ratio {cpu:.3f}; job ratio "
          f"{job:.3f}; memory ratio {mem:.2f}")
    if a.old:
        old = med([row["periodic (--old)"]["job_s"] / row["periodic"]["job_s"] for row in rounds])
        print(f"periodic job, --old / this checkout: {old:.2f}")
    if a.json:
        pathlib.Path(a.json).write_text(json.dumps(rounds, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
