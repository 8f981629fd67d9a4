"""Predicted widths against measured ones (issue #48 item 6): the ensemble of a case's model,
sampled from several Bullet layouts in two independent halves, its width read from the
helically averaged map's projection (docs/model/ensemble.md#density-map, one definition for
every system), against the width a microscope measured. Nothing is fitted per system: the case
file's parameters (and, with --linker, another linker, recorded in the row) are the model.

    python tools/widths.py run CASE.toml --system NAME [--linker N] [--starts 3]
                               [--replicas 12] [--sweeps 60] [--burn-in 30]
                               [--measured NM --technique TEXT --domain-kda KDA --core-source TEXT]
    python tools/widths.py table          # rewrite docs/validation.md#widths from the CSV

`run`: each half h (0, 1) relaxes the model with Bullet at seeds of its own (h·K ..), keeping the
first K layouts that fit (a layout that does not fit is not one of the hard-core model's), then
samples them with the replicas taking them in turn (sampler seed h). Written: the row of
docs/data/widths.csv for NAME (its measured columns kept when the row exists) and
a JSON in docs/data/widths/ named by NAME's slug (every number of the run: each half's and each start's width,
the outer diameter's distribution, τ, ESS, the halves' agreement, times). The page's table is
docs/data/widths.csv rendered (`table`; tests/unit/test_widths_table.py checks they agree).
"""
from __future__ import annotations

import argparse
import csv
import datetime
import io
import json
import os
import pathlib
import re
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
CSV = ROOT / "docs" / "data" / "widths.csv"
RUNS = ROOT / "docs" / "data" / "widths"
PAGE = ROOT / "docs" / "validation.md"
COLUMNS = ("system", "core_source", "domain_kDa", "linker", "layers", "technique", "measured_nm",
           "predicted_width_nm", "interval_lo", "interval_hi", "ess", "date", "commit",
           "model_version")
START, END = "<!-- widths table: written by tools/widths.py -->", "<!-- end of widths table -->"


def read_rows(path: pathlib.Path = CSV) -> list[dict]:
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        if tuple(row) != COLUMNS:
            raise ValueError(f"{path}: columns {tuple(row)}, expected {COLUMNS}")
    return rows


def write_rows(rows: list[dict], path: pathlib.Path = CSV) -> None:
    out = io.StringIO()
    w = csv.DictWriter(out, fieldnames=COLUMNS, lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    path.write_text(out.getvalue(), encoding="utf-8")


def measured_range(text: str) -> tuple[float, float]:
    """'25' -> (25, 25); '14-25' -> (14, 25)."""
    lo, _, hi = text.partition("-")
    return float(lo), float(hi or lo)


def off_by(row: dict) -> str:
    """How far the prediction is from the measured width (or range), in %: 0 inside a range."""
    if not row["predicted_width_nm"]:
        return ""
    w = float(row["predicted_width_nm"])
    lo, hi = measured_range(row["measured_nm"])
    if lo <= w <= hi:
        return "within the range" if lo < hi else "+0 %"
    ref = hi if w > hi else lo
    return f"{100.0 * (w - ref) / ref:+.0f} %" + (f" (of {ref:g})" if lo < hi else "")


def cell(row: dict) -> str:
    if not row["predicted_width_nm"]:
        return "pending"
    return f"{row['predicted_width_nm']} [{row['interval_lo']}, {row['interval_hi']}]"


def table(rows: list[dict]) -> str:
    """The page's table: one line per CSV row, in the CSV's order."""
    lines = ["| system | core | domain, kDa | linker | layers | technique | measured, nm | "
             "predicted width, nm [interval] | predicted − measured | ESS (outer diameter) | date | "
             "commit | "
             "MODEL_VERSION |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| " + " | ".join([
            r["system"], r["core_source"], r["domain_kDa"], r["linker"], r["layers"],
            r["technique"], r["measured_nm"].replace("-", "–"), cell(r), off_by(r),
            r["ess"] or "", r["date"] or "", r["commit"] or "", r["model_version"] or ""]) + " |")
    return "\n".join(lines)


def page_block(page: pathlib.Path = PAGE) -> str:
    """The table as it stands on the page, between the markers."""
    text = page.read_text(encoding="utf-8")
    m = re.search(re.escape(START) + r"\n(.*?)\n" + re.escape(END), text, re.S)
    if m is None:
        raise ValueError(f"{page}: no widths table between {START} and {END}")
    return m.group(1)


def write_page(rows: list[dict], page: pathlib.Path = PAGE) -> None:
    text = page.read_text(encoding="utf-8")
    new = re.sub(re.escape(START) + r"\n(?:.*?\n)?" + re.escape(END),
                 lambda _: f"{START}\n{table(rows)}\n{END}", text, count=1, flags=re.S)
    if new == text and START + "\n" + table(rows) + "\n" + END not in text:
        raise ValueError(f"{page}: no widths table between {START} and {END}")
    page.write_text(new, encoding="utf-8")


def slug(system: str) -> str:
    return re.sub(r"[^a-z0-9]+", "_", system.lower()).strip("_")


def git_commit() -> str:
    return subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                          capture_output=True, text=True).stdout.strip()


def half(p, h: int, starts: int, replicas: int, sweeps: int, burn_in: int,
         max_tries: int) -> dict:
    """Half h: the first `starts` Bullet layouts that fit, from seeds h·max_tries on, sampled
    (sampler seed h). Returns the scored domain centres (S, R, D, 3), the outer diameters
    (S, R) and an account of the half."""
    import numpy as np
    from fibrilfit import pipeline
    from fibrilfit.analysis import scored_chains
    from fibrilfit.analysis.verdict import chain_positions
    from fibrilfit.ensemble import observables, sampler, system

    t = time.perf_counter()
    begun, tried = [], []
    for seed in range(h * max_tries, (h + 1) * max_tries):
        result = pipeline.run_model(p.replace(seed=seed))
        tried.append({"seed": seed, "answer": result["answer"],
                      "outer_diameter": result["envelope"]["outer_diameter"]})
        if result.get("accommodated") is True:
            begun.append(chain_positions(pipeline.current_model()))
        if len(begun) == starts:
            break
    bullet = time.perf_counter() - t
    if not begun:
        return {"error": f"no Bullet layout fitted in seeds {tried[0]['seed']}-"
                         f"{tried[-1]['seed']}: nothing to sample", "bullet": tried}
    hard = system.from_params(p)
    ens = sampler.sample(hard, np.stack(begun), seed=h, replicas=replicas, sweeps=sweeps,
                         burn_in=burn_in)
    scored = np.asarray(scored_chains(p), bool)
    d = ens.domains[:, :, scored]
    d = d.reshape(*d.shape[:2], -1, 3)
    od = observables.outer_diameters(d, p.widest_diameter / 2.0)
    return {"centres": d, "outer": od, "starts": len(begun), "bullet": tried,
            "bullet_seconds": round(bullet, 1), "sampling_seconds": round(ens.seconds, 1),
            "repair_sweeps": int(ens.notes["repair_sweeps"]),
            "burn_in_sweeps": int(ens.burn_in_sweeps),
            "acceptance": ens.acceptance.get("overall")}


def run(args) -> int:
    import numpy as np
    import bpy  # noqa: F401  (the relaxation is Blender's)
    from fibrilfit.ensemble import account, density, observables, system
    from fibrilfit.model import cases
    from fibrilfit.model.version import MODEL_VERSION

    case = cases.load(args.case)
    given = {"linker": args.linker, "layers": args.layers, "score_layers": args.score_layers}
    p = case.make_params(**{k: v for k, v in given.items() if v is not None})
    t0 = time.perf_counter()
    halves = [half(p, h, args.starts, args.replicas, args.sweeps, args.burn_in, args.max_tries)
              for h in (0, 1)]
    out = {"system": args.system, "case": os.path.relpath(args.case, ROOT),
           "linker": p.linker, "layers": p.layers, "score_layers": p.score_layers,
           "globule_diameter": p.globule_diameter, "rise": p.rise, "twist": p.twist,
           "starts_per_half": args.starts, "replicas": args.replicas, "sweeps": args.sweeps,
           "burn_in": args.burn_in, "date": datetime.date.today().isoformat(),
           "commit": git_commit(), "model_version": MODEL_VERSION,
           "bpy": ".".join(str(v) for v in bpy.app.version),
           "width_definition": account.WIDTH_DEFINITION,
           "measured": {"measured_nm": args.measured, "technique": args.technique,
                        "domain_kDa": args.domain_kda, "core_source": args.core_source},
           "halves": [{k: v for k, v in hv.items() if k not in ("centres", "outer")}
                      for hv in halves]}
    if any("error" in hv for hv in halves):
        out["error"] = "; ".join(hv["error"] for hv in halves if "error" in hv)
    else:
        core = account.core_prism(p, system.from_params(p))
        radius = p.widest_diameter / 2.0

        def width_of(centres):
            return round(density.width(density.density_map(
                p, centres.reshape(-1, 3), radius, voxel=account.VOXEL, core=core)), 2)

        both = np.concatenate([hv["centres"] for hv in halves], axis=1)  # (S, 2R, D, 3)
        outer = np.concatenate([hv["outer"] for hv in halves], axis=1)
        tau = max(observables.integrated_time(hv["outer"]) for hv in halves)
        per_start = []
        for hv in halves:  # replica r started from start r mod K
            k = hv["starts"]
            per_start += [width_of(hv["centres"][:, j::k]) for j in range(k)]
        out.update(
            width=width_of(both),
            width_halves=[width_of(hv["centres"]) for hv in halves],
            width_per_start=per_start,
            outer_diameter={**observables.summary(outer, tau), "tau_samples": round(tau, 2),
                            "halves": observables.halves(halves[0]["outer"],
                                                         halves[1]["outer"])})
        w0, w1 = out["width_halves"]
        out["width_halves_relative_difference"] = round(abs(w0 - w1) / (0.5 * (w0 + w1)), 4)
    out["seconds"] = round(time.perf_counter() - t0, 1)
    RUNS.mkdir(parents=True, exist_ok=True)
    (RUNS / f"{slug(args.system)}.json").write_text(json.dumps(out, indent=1) + "\n",
                                                    encoding="utf-8")
    print(json.dumps({k: v for k, v in out.items() if k != "halves"}, indent=1))
    return 1 if "error" in out else 0


def row_of(out: dict, old: dict | None) -> dict:
    """The CSV row of a run's JSON (`out`): the measured columns kept from the row already in
    the CSV (`old`), or for a new row from the JSON's `measured` block (the run's options)."""
    row = dict(old) if old else dict.fromkeys(COLUMNS, "")
    row["system"] = out["system"]
    for key, value in out.get("measured", {}).items():  # the CSV's own, where it has them
        if value is not None and not row.get(key):
            row[key] = value
    lo, hi = min(out["width_per_start"]), max(out["width_per_start"])
    row.update(linker=str(out["linker"]), layers=str(out["layers"]),
               predicted_width_nm=f"{out['width'] / 10:.2f}", interval_lo=f"{lo / 10:.2f}",
               interval_hi=f"{hi / 10:.2f}", ess=f"{out['outer_diameter']['ess']:.0f}",
               date=out["date"], commit=out["commit"], model_version=str(out["model_version"]))
    return row


def collect() -> int:
    """The CSV's rows updated from every run's JSON in docs/data/widths/ (rows with no JSON,
    such as a pending system's, kept as they are), then the page's table."""
    rows = read_rows() if CSV.exists() else []
    for path in sorted(RUNS.glob("*.json")):
        out = json.loads(path.read_text(encoding="utf-8"))
        if "error" in out or out.get("draft"):
            continue
        old = next((r for r in rows if r["system"] == out["system"]), None)
        new = row_of(out, old)
        if old is None:
            rows.append(new)
        else:
            rows[rows.index(old)] = new
    write_rows(rows)
    write_page(rows)
    return 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run")
    r.add_argument("case", type=pathlib.Path)
    r.add_argument("--system", required=True)
    r.add_argument("--linker", type=int, default=None)
    r.add_argument("--starts", type=int, default=3, help="Bullet layouts per half")
    r.add_argument("--max-tries", type=int, default=8, help="Bullet seeds per half at most")
    r.add_argument("--replicas", type=int, default=12, help="replicas per half")
    r.add_argument("--sweeps", type=int, default=60)
    r.add_argument("--burn-in", type=int, default=30)
    r.add_argument("--layers", type=int, default=None)
    r.add_argument("--score-layers", type=int, default=None)
    r.add_argument("--measured")
    r.add_argument("--technique")
    r.add_argument("--domain-kda")
    r.add_argument("--core-source")
    sub.add_parser("table")
    sub.add_parser("collect")
    args = ap.parse_args(argv)
    if args.command == "table":
        write_page(read_rows())
        return 0
    if args.command == "collect":
        return collect()
    args.case = args.case.resolve()
    return run(args)


if __name__ == "__main__":
    sys.exit(main())
