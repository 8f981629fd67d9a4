"""The tables of docs/model/bound.md#fraction: the proven bound on the fraction f_B against the
linker, for the default model on the infinite fibril (20-50 Å globules) and for the gallery's
negative control (Aβ42-GFP on 5OQV, the buried exit), with the linker bound at 10-100 % and
what windows of w layers would add. Geometry only, no bpy; prints Markdown with its date,
commit and MODEL_VERSION.

    .venv/bin/python tools/fraction_bound_table.py [--budget 2e7]

(the venv's fibrilfit; a worktree's with PYTHONPATH=.)
"""
from __future__ import annotations

import argparse
import dataclasses
import datetime
import math
import pathlib
import subprocess
import sys
import time

from fibrilfit.model import bound as B, fraction_bound as F, params as P
from fibrilfit.model.version import MODEL_VERSION

ROOT = pathlib.Path(__file__).resolve().parents[1]

FRACTIONS = (0.10, 0.25, 0.50, 0.75, 1.0)
NEGATIVE_CONTROL = ROOT / "examples" / "abeta42_5oqv_gfp_linker12.toml"


def pct(x: float) -> str:
    return f"{math.ceil(x * 1000 - 1e-6) / 10:g} %"  # up: the bound's side


def window_room(p, s, L: int, widths=range(1, 7)) -> float:
    """The least ⌊vol(U_w) / v⌋ / w over windows of w consecutive layers of protofilament 0 on
    the infinite fibril (its core continued past the window by the reach): what counting whole
    domains in a window could add to the per-layer cap (docs/model/bound.md#windows)."""
    rho = B.reach(p, s.terms, L)[0]
    best = math.inf
    for w in widths:
        pad = int(math.ceil(rho / p.rise)) + 3
        q = dataclasses.replace(p, periodic=0, layers=2 * pad + w)
        room = B.Room(q, rho, False, pad, pad + w, budget=5e6)
        best = min(best, math.floor(room.volume([0], rho) / s.volumes[0]) / w)
    return best


def default_rows(budget: float) -> list[str]:
    out = ["| globule | impossible below (f = 1) | f_B at linker 1, 2, … up to it | "
           "linker bound at 10 / 25 / 50 / 75 / 100 % | windows w ≤ 6 (least ⌊x_w⌋/w) | "
           "cost (s) |", "|---|---|---|---|---|---|"]
    for d in (20.0, 30.0, 40.0, 50.0):
        p = P.make_params(globule_diameter=d, periodic="auto", protocol="inflate")
        B._CACHE.clear()
        t = time.perf_counter()
        b = B.linker_bound(p, budget)["impossible_below"]
        t_linker = time.perf_counter() - t
        t = time.perf_counter()
        fs = [F.fraction_bound(p, L, budget) for L in range(1, b + 1)]
        at = [F.impossible_below_at(p, f, budget) for f in FRACTIONS]
        t_fraction = time.perf_counter() - t
        s = B.setting(p, budget)
        win = [window_room(p, s, L) for L in range(s.first, b)]
        out.append(
            f"| {d:g} Å (cell {p.layers}) | {b} | "
            + ", ".join(f"{L}: {pct(f)}" for L, f in zip(range(1, b + 1), fs))
            + " | " + " / ".join(str(x) for x in at)
            + " | " + (", ".join(f"{L}: {w:.3g}" for L, w in zip(range(s.first, b), win))
                       or "(none below the bound)")
            + f" | {t_linker:.2f} + {t_fraction:.2f} |")
    return out


def control_rows(budget: float) -> list[str]:
    from fibrilfit.api.model import resolve
    from fibrilfit.api.plans import RunPlan, make_plan
    plan, _ = make_plan(RunPlan, {}, case=str(NEGATIVE_CONTROL), command="run")
    p = resolve(plan).p
    b = B.linker_bound(p, budget)
    out = [f"Aβ42-GFP on 5OQV ({NEGATIVE_CONTROL.name}, its `periodic = \"auto\"` cell of "
           f"{p.layers} layers × {p.protofilaments} protofilaments, exit "
           f"{p.exit_residues} residues, GFP's inner volume {b['inner_volume_A3'][0]:,.0f} Å³): "
           f"impossible below **{b['impossible_below']}** at f = 1.", "",
           "| linker | f_B | most decorated of the cell | binding room |", "|---|---|---|---|"]
    for L in (6, 8, 10, 11, 12, 13, 15):
        lim = F.fraction_limit(p, L, budget)
        why = "; ".join(f"protofilaments {g['protofilaments']}: cap {g['cap']}"
                        + (f" ({g['needed_A3']:,.0f} Å³ a GFP, {g['room_A3']:,.0f} Å³ of room)"
                           if "room_A3" in g else "") for g in lim["binding"]) or "none (f_B = 1)"
        out.append(f"| {L} | {pct(lim['fraction_bound'])} | {lim['count']} of {lim['of']} "
                   f"| {why} |")
    at = [F.impossible_below_at(p, f, budget) for f in FRACTIONS]
    out += ["", "The linker bound at 10 / 25 / 50 / 75 / 100 % decorated: "
            + " / ".join(str(x) for x in at) + "."]
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--budget", type=float, default=B.GRID_BUDGET,
                    help="voxel-anchor distances per grid [default: the bound's own]")
    args = ap.parse_args(argv)
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "fibrilfit"],
                           capture_output=True, text=True).stdout.strip()
    today = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")
    print(f"Measured {today}, commit {commit}{' (+ uncommitted model code)' if dirty else ''}, "
          f"MODEL_VERSION {MODEL_VERSION}, `tools/fraction_bound_table.py` (budget "
          f"{args.budget:g}).\n")
    print("\n".join(default_rows(args.budget)))
    print()
    print("\n".join(control_rows(args.budget)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
