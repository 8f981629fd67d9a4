"""FibrilFit's benchmarks side by side with the baselines; prints one table. `make bench` runs it.

    .venv/bin/python bench/run.py [--runs 3] [--only build100,scaling,job20,bake,analysis]

Targets (issue #6); every figure is the median of --runs rounds, and every ratio is taken within
one round from runs made back to back (the machine may be shared, so ratios are the figure to
trust, not absolute seconds):

    build at 100 layers           >= 10x faster than seed_port.py
    build 2000 vs 200 layers      <= 12x (linear), with peak memory at 2000 layers
    the whole 20-layer job        <= 0.5x seed_port.py (build + bake + check)
    bake per simulated step       within 1.2x of raw Bullet (bullet_peer.py), 20 and 100 layers;
                                  also against bullet_rigid_peer.py, its rigid-body twin
    analysis at 2000 layers       < 1 s (BVH + analytic check)

Every measurement is a fresh subprocess of this interpreter (`run.py --worker NAME ...`); the
baselines (seed_port.py, bullet_peer.py) are in bench/baselines/ (copied, with provenance), or
in $FIBRILFIT_BASELINES.
"""
from __future__ import annotations

import argparse
import json
import os
import pathlib
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
BASELINES = pathlib.Path(os.environ.get("FIBRILFIT_BASELINES", ROOT / "bench" / "baselines"))
BULLET_STEPS = 250 * 10  # bullet_peer.py steps 250 frames x 10 substeps, whatever the layers
MEASUREMENTS = ("build100", "scaling", "job20", "bake", "analysis")


# ---- workers: each runs in its own process and prints one line "BENCH {json}" -------------------

def _fibrilfit():
    import bpy  # noqa: F401  (first: it makes mathutils and bmesh importable)
    import fibrilfit
    return fibrilfit


def _peak_mib() -> float:
    import resource
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: KiB


def _rss_mib() -> float:
    """Resident memory now (Linux), for memory per object; the peak is _peak_mib()."""
    try:
        with open("/proc/self/status") as f:
            return next(int(ln.split()[1]) for ln in f if ln.startswith("VmRSS:")) / 1024.0
    except (OSError, StopIteration):
        return _peak_mib()


def worker_build(layers: int, frames: int = 0) -> dict:
    """Build; then the first depsgraph evaluation; then `frames` frames of simulation.

    Times are wall clock; `*_cpu` are this process's CPU seconds (all threads), which a shared
    machine disturbs less.
    """
    ff = _fibrilfit()
    import bpy
    bpy.ops.wm.read_factory_settings(use_empty=True)
    p = ff.model.params.make_params(layers=layers, frames=frames + 2, force=True)
    out = {"rss_start_mib": _rss_mib()}
    t, c = time.perf_counter(), time.process_time()
    model = ff.pipeline.build(p, bpy.context.scene, force=True)
    out.update(build=time.perf_counter() - t, build_cpu=time.process_time() - c,
               objects=len(model.root.all_objects), rss_build_mib=_rss_mib())
    t, c = time.perf_counter(), time.process_time()
    bpy.context.view_layer.update()
    out.update(evaluate=time.perf_counter() - t, evaluate_cpu=time.process_time() - c,
               rss_eval_mib=_rss_mib())
    if frames:
        scene = bpy.context.scene
        ff.builders.setup_world(scene, p)
        t = time.perf_counter()
        for f in range(2, frames + 2):
            scene.frame_set(f)
        out.update(frame=(time.perf_counter() - t) / frames, rss_sim_mib=_rss_mib())
    out["peak_mib"] = _peak_mib()
    return out


def worker_job(layers: int) -> dict:
    """The whole job as `headless.py run` does it: build, bake, check."""
    ff = _fibrilfit()
    import bpy
    bpy.ops.wm.read_factory_settings(use_empty=True)
    r = ff.pipeline.run_model(ff.model.params.make_params(layers=layers), bpy.context.scene)
    t = r["timings_s"]
    return {**t, "total": t["build"] + t["bake"] + t["check"], "verdict": r["verdict"],
            "frames": r["frames_simulated"]}


def worker_bake(layers: int, dump: str = "") -> dict:
    """Build, then bake through the pipeline (its per-frame stretch tracking included)."""
    ff = _fibrilfit()
    import bpy
    import numpy as np
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    p = ff.model.params.make_params(layers=layers, force=True)
    model = ff.pipeline.build(p, scene, force=True)
    t = time.perf_counter()
    r = ff.pipeline.bake(model, scene)
    bake = time.perf_counter() - t
    # Frame 1 is the start frame, where Blender sets the world up and does not step it.
    steps = (r["frames_simulated"] - 1) * p.substeps
    if dump:
        bodies = scene.rigidbody_world.collection.objects
        raw = np.empty(len(bodies) * 16, dtype=np.float32)
        bodies.foreach_get("matrix_world", raw)
        np.savez(dump, raw=raw, layers=layers)
    return {"bake": bake, "steps": steps, "per_step_ms": 1000 * bake / steps,
            "substeps": p.substeps, "solver_iterations": p.solver_iterations,
            "frames": r["frames_simulated"]}


def worker_analysis(layers: int, relaxed: str = "") -> dict:
    """The check (pipeline.check: BVH + spheres + stretch) on a `layers` model, twice:

    as built (each globule overlaps its ~12 nearest layers: the worst case), and relaxed: the
    end of a baked 100-layer model, stacked along the fibril's screw axis to `layers` layers.
    """
    ff = _fibrilfit()
    import bpy
    import numpy as np
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    p = ff.model.params.make_params(layers=layers, force=True)
    model = ff.pipeline.build(p, scene, force=True)
    out = {}
    t, c = time.perf_counter(), time.process_time()
    r = ff.pipeline.check(model, scene)
    out.update(as_built=time.perf_counter() - t, as_built_cpu=time.process_time() - c,
               as_built_faces=r["intersecting_faces"], as_built_pairs=len(r["clashing_pairs"]))
    if relaxed:
        bodies = scene.rigidbody_world.collection.objects
        bodies.foreach_set("matrix_world", _stacked(relaxed, p, len(bodies)).ravel())
        t, c = time.perf_counter(), time.process_time()
        r = ff.pipeline.check(model, scene)
        out.update(relaxed=time.perf_counter() - t, relaxed_cpu=time.process_time() - c,
                   relaxed_faces=r["intersecting_faces"], relaxed_pairs=len(r["clashing_pairs"]))
    return out


def _stacked(path: str, p, count: int):
    """Raw world matrices of a baked model's bodies, repeated up the screw axis to `count`."""
    import numpy as np
    from fibrilfit.model import helix
    data = np.load(path)
    block = int(data["layers"])
    raw = data["raw"].reshape(-1, 4, 4).astype(float)  # column-major: translation in row 3
    per_layer = len(raw) // block
    copies = -(-count // len(raw))
    out = []
    for b in range(copies):
        screw = helix.turn_matrix(*helix.layer_turn(p, b * block))  # b·block layers up
        out.append(np.einsum("ij,njk->nik", screw, raw.transpose(0, 2, 1)).transpose(0, 2, 1))
    stacked = np.concatenate(out)[:count]
    assert count % per_layer == 0
    return stacked.astype(np.float32)


WORKERS = {"build": worker_build, "job": worker_job, "bake": worker_bake,
           "analysis": worker_analysis}


# ---- the orchestrator ---------------------------------------------------------------------------

def _run(cmd, timeout=3600) -> tuple[str, float]:
    t = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=ROOT)
    wall = time.perf_counter() - t
    if proc.returncode != 0:
        tail = (proc.stderr or proc.stdout).strip().splitlines()[-5:]
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed ({proc.returncode}): " + " | ".join(tail))
    return proc.stdout, wall


def ours(name: str, *args) -> dict:
    out, wall = _run([sys.executable, __file__, "--worker", name, *map(str, args)])
    line = [ln for ln in out.splitlines() if ln.startswith("BENCH ")][-1]
    return {**json.loads(line[6:]), "wall": wall}


def seed_port(layers: int) -> dict:
    out, wall = _run([sys.executable, BASELINES / "seed_port.py", str(layers), "6", "0"])
    m = re.search(r"build=([\d.]+) bake=([\d.]+) check=([\d.]+)", out)
    build, bake, check = map(float, m.groups())
    return {"build": build, "bake": bake, "check": check, "total": build + bake + check,
            "wall": wall}


def bullet_peer(layers: int, rigid: bool = False) -> dict:
    """bullet_peer.py as shipped (multibodies), or through bullet_rigid_peer.py (rigid bodies)."""
    wrap = [ROOT / "bench" / "bullet_rigid_peer.py"] if rigid else []
    out, wall = _run([sys.executable, *wrap, BASELINES / "bullet_peer.py", str(layers), "6", "0"])
    bake = float(re.search(r"bake=([\d.]+)", out).group(1))
    return {"bake": bake, "per_step_ms": 1000 * bake / BULLET_STEPS, "wall": wall}


def _round(r: int, only: set, tmp: pathlib.Path, log) -> dict:
    """One round: each comparison's two sides back to back, order alternating between rounds."""
    first = (lambda a, b: (a(), b())) if r % 2 == 0 else (lambda a, b: tuple(reversed((b(), a()))))
    got = {}
    if "build100" in only:
        got["ours100"], got["seed100"] = first(lambda: ours("build", 100), lambda: seed_port(100))
        log(f"build 100: ours {got['ours100']['build']:.3f} s, seed_port {got['seed100']['build']:.3f} s")
    if "scaling" in only:
        # The small model builds in ~0.1 s, where a shared machine's noise weighs most: it runs
        # three times and the round keeps its median build.
        small = lambda: sorted((ours("build", 200, 1) for _ in range(3)), key=lambda g: g["build"])[1]  # noqa: E731
        got["b200"], got["b2000"] = first(small, lambda: ours("build", 2000, 1))
        log(f"build 200: {got['b200']['build']:.3f} s, 2000: {got['b2000']['build']:.3f} s")
    if "job20" in only:
        got["job"], got["seed20"] = first(lambda: ours("job", 20), lambda: seed_port(20))
        log(f"job 20: ours {got['job']['total']:.3f} s, seed_port {got['seed20']['total']:.3f} s")
    dump = tmp / f"relaxed{r}.npz"
    if "bake" in only:
        for n in (20, 100):
            got[f"bake{n}"], got[f"bullet{n}"] = first(
                lambda: ours("bake", n, dump if n == 100 else ""), lambda: bullet_peer(n))
            got[f"rigid{n}"] = bullet_peer(n, rigid=True)
            log(f"bake {n}: ours {got[f'bake{n}']['per_step_ms']:.3f} ms/step, "
                f"bullet {got[f'bullet{n}']['per_step_ms']:.3f} ms/step, "
                f"rigid bodies {got[f'rigid{n}']['per_step_ms']:.3f} ms/step")
    if "analysis" in only:
        if not dump.exists():
            ours("bake", 100, dump)
        got["analysis"] = ours("analysis", 2000, dump)
        log(f"analysis 2000: relaxed {got['analysis']['relaxed']:.3f} s, "
            f"as built {got['analysis']['as_built']:.3f} s")
    return got


def _median(rounds, fn):
    values = []
    for g in rounds:
        try:
            values.append(fn(g))
        except KeyError:
            pass
    return statistics.median(values) if values else None


def table(rounds: list[dict]) -> list[tuple]:
    """(measurement, ours, baseline, ratio, target, met) rows from the rounds' medians."""
    m = lambda fn: _median(rounds, fn)  # noqa: E731
    rows = []

    def row(what, mine, base, ratio, target, ok):
        if mine:
            rows.append((what, mine, base or "", ratio or "", target, ok))

    b_ours, b_seed = m(lambda g: g["ours100"]["build"]), m(lambda g: g["seed100"]["build"])
    faster = m(lambda g: g["seed100"]["build"] / g["ours100"]["build"])
    row("Build, 100 layers (vs seed_port.py)", _s(b_ours), _s(b_seed) + " seed_port",
        _x(faster) + " faster", ">= 10x faster", _ok(faster, ">=", 10))
    ev = m(lambda g: g["ours100"]["build"] + g["ours100"]["evaluate"])
    ev_faster = m(lambda g: g["seed100"]["build"] / (g["ours100"]["build"] + g["ours100"]["evaluate"]))
    row("  same, plus the first depsgraph evaluation", _s(ev), _s(b_seed) + " seed_port",
        _x(ev_faster) + " faster", "(info)", "")

    s200, s2000 = m(lambda g: g["b200"]["build"]), m(lambda g: g["b2000"]["build"])
    scale = m(lambda g: g["b2000"]["build"] / g["b200"]["build"])
    cpu_scale = m(lambda g: g["b2000"]["build_cpu"] / g["b200"]["build_cpu"])
    row("Build scaling, 200 -> 2000 layers", _span(s200, s2000), "",
        f"{_x(scale)} (CPU {_x(cpu_scale)})", "<= 12x", _ok(scale, "<=", 12))
    e200 = m(lambda g: g["b200"]["build"] + g["b200"]["evaluate"])
    e2000 = m(lambda g: g["b2000"]["build"] + g["b2000"]["evaluate"])
    escale = m(lambda g: (g["b2000"]["build"] + g["b2000"]["evaluate"])
               / (g["b200"]["build"] + g["b200"]["evaluate"]))
    row("  same, plus the first depsgraph evaluation", _span(e200, e2000), "",
        _x(escale), "(info)", "")
    f200, f2000 = m(lambda g: g["b200"]["frame"]), m(lambda g: g["b2000"]["frame"])
    fscale = m(lambda g: g["b2000"]["frame"] / g["b200"]["frame"])
    row("  one simulated frame, 200 -> 2000 layers", _span(f200, f2000), "",
        _x(fscale), "(info)", "")
    peak = m(lambda g: g["b2000"]["rss_sim_mib"])
    per_obj = m(lambda g: 1024 * (g["b2000"]["rss_sim_mib"] - g["b200"]["rss_sim_mib"])
                / (g["b2000"]["objects"] - g["b200"]["objects"]))
    per_obj_build = m(lambda g: 1024 * (g["b2000"]["rss_build_mib"] - g["b200"]["rss_build_mib"])
                      / (g["b2000"]["objects"] - g["b200"]["objects"]))
    if peak is not None:
        objects = rounds[0]["b2000"]["objects"]
        row("Peak memory, 2000 layers (built, evaluated, 1 frame simulated)",
            f"{peak:.0f} MiB", f"{objects} objects",
            f"{per_obj:.1f} KiB/object ({per_obj_build:.1f} built only)", "report", "")

    j_ours, j_seed = m(lambda g: g["job"]["total"]), m(lambda g: g["seed20"]["total"])
    jr = m(lambda g: g["job"]["total"] / g["seed20"]["total"])
    row("Whole 20-layer job, build + bake + check", _s(j_ours), _s(j_seed) + " seed_port",
        _x(jr), "<= 0.5x", _ok(jr, "<=", 0.5))
    jw = m(lambda g: g["job"]["wall"] / g["seed20"]["wall"])
    row("  same, whole processes (bpy import included)", _s(m(lambda g: g["job"]["wall"])),
        _s(m(lambda g: g["seed20"]["wall"])) + " seed_port", _x(jw), "(info)", "")

    for n in (20, 100):
        mine = m(lambda g: g[f"bake{n}"]["per_step_ms"])
        peer = m(lambda g: g[f"bullet{n}"]["per_step_ms"])
        ratio = m(lambda g: g[f"bake{n}"]["per_step_ms"] / g[f"bullet{n}"]["per_step_ms"])
        row(f"Bake per simulated step, {n} layers (vs raw Bullet)", _ms(mine),
            _ms(peer) + " bullet_peer", _x(ratio), "<= 1.2x", _ok(ratio, "<=", 1.2))
        rigid = m(lambda g: g[f"rigid{n}"]["per_step_ms"])
        ratio = m(lambda g: g[f"bake{n}"]["per_step_ms"] / g[f"rigid{n}"]["per_step_ms"])
        row("  same, vs raw Bullet with rigid bodies (the tighter floor)", _ms(mine),
            _ms(rigid) + " bullet_rigid_peer", _x(ratio), "<= 1.2x", _ok(ratio, "<=", 1.2))

    rel = m(lambda g: g["analysis"]["relaxed"])
    if rel is not None:
        a = rounds[0]["analysis"]
        cpu = m(lambda g: g["analysis"]["relaxed_cpu"])
        row("Analysis, 2000 layers, relaxed (baked 100-layer model stacked x20)",
            f"{_s(rel)} (CPU {_s(cpu)})",
            f"{a['relaxed_pairs']} clashing pairs, {a['relaxed_faces']} faces", "", "< 1 s",
            _ok(rel, "<", 1.0))
    worst = m(lambda g: g["analysis"]["as_built"])
    if worst is not None:
        a = rounds[0]["analysis"]
        row("Analysis, 2000 layers, as built (every globule overlaps ~12 others)", _s(worst),
            f"{a['as_built_pairs']} clashing pairs, {a['as_built_faces']} faces", "", "(info)", "")
    return rows


def _span(a, b):
    return None if a is None or b is None else f"{_s(a)} -> {_s(b)}"


def _s(v):
    return "" if v is None else f"{v:.3f} s"


def _ms(v):
    return "" if v is None else f"{v:.3f} ms"


def _x(v):
    return "" if v is None else (f"{v:.2f}x" if v >= 1 else f"{v:.3f}x")


def _ok(v, op, target):
    if v is None:
        return ""
    return "yes" if {"<=": v <= target, ">=": v >= target, "<": v < target}[op] else "**no**"


def machine() -> dict:
    import bpy
    cpu = ""
    try:
        cpu = next(ln.split(":", 1)[1].strip() for ln in open("/proc/cpuinfo")
                   if ln.startswith("model name"))
    except (OSError, StopIteration):
        pass
    try:
        import pybullet  # noqa: F401
        bullet = "pybullet present"
    except ImportError:
        bullet = "pybullet MISSING (pip install -r bench/requirements.txt)"
    return {"cores": os.cpu_count(), "cpu": cpu, "blender": bpy.app.version_string,
            "python": platform.python_version(), "bullet": bullet,
            "load": os.getloadavg() if hasattr(os, "getloadavg") else None}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=3, help="rounds; figures are medians (default 3)")
    ap.add_argument("--only", default=",".join(MEASUREMENTS),
                    help=f"comma-separated subset of {','.join(MEASUREMENTS)}")
    ap.add_argument("--json", default=str(ROOT / "out" / "bench.json"), help="raw results")
    ap.add_argument("--worker", nargs="+", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        name, *rest = args.worker
        params = [int(rest[0]), *rest[1:]]
        if name == "build" and len(params) > 1:
            params[1] = int(params[1])
        print("BENCH " + json.dumps(WORKERS[name](*params)), flush=True)
        return 0

    only = set(args.only.split(","))
    unknown = only - set(MEASUREMENTS)
    if unknown:
        ap.error(f"--only: unknown {sorted(unknown)}; choose from {','.join(MEASUREMENTS)}")
    if not (BASELINES / "seed_port.py").exists():
        print(f"bench: baselines not found in {BASELINES} (set FIBRILFIT_BASELINES)", file=sys.stderr)
        return 2
    info = machine()
    log = lambda s: print(f"  [{time.strftime('%H:%M:%S')}] {s}", file=sys.stderr, flush=True)  # noqa: E731
    log(f"{info['cores']} cores, {info['cpu']}; Blender {info['blender']}; load {info['load']}")
    rounds = []
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(args.runs):
            log(f"round {r + 1}/{args.runs}")
            rounds.append(_round(r, only, pathlib.Path(tmp), log))
    info["load_after"] = os.getloadavg() if hasattr(os, "getloadavg") else None
    rows = table(rounds)
    print(f"\nFibrilFit benchmarks: Blender {info['blender']}, Python {info['python']}, "
          f"{info['cores']} cores ({info['cpu']}), {info['bullet']}; medians of {args.runs} "
          f"rounds; load average {_load(info['load'])} before, {_load(info['load_after'])} after\n")
    print("| measurement | FibrilFit | baseline | ratio | target | met |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print("| " + " | ".join(str(c) for c in r) + " |")
    path = pathlib.Path(args.json)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps({"machine": info, "rounds": rounds, "table": rows}, indent=1))
    print(f"\nraw results: {path}")
    return 0


def _load(v):
    return "?" if not v else "/".join(f"{x:.1f}" for x in v)


if __name__ == "__main__":
    sys.exit(main())
