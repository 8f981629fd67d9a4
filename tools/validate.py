"""`make validate`: run the gallery (examples/*.toml) and write the README's validation table.

For every case: its seeds at the real linker (P(fit) = the accommodated fraction, with its 95 %
Wilson interval, and the envelope's outer diameter over the seeds), then the minimal linker: the
shortest linker of a coarse ladder at which every seed is accommodated (searched upwards, stopping
at the first such linker; skipped when the real linker is not longer than the ladder's start).
Runs go through `headless.py sweep` (results kept in out/validate/, so running again resumes).
A case that cannot run in this build (e.g. a parameter from an issue not merged yet) gets a row
saying why. Nothing is filled in by hand.

    python tools/validate.py [--out out/validate] [--workers 2] [--no-readme] [CASE.toml ...]
"""
from __future__ import annotations

import argparse
import importlib
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
import _load  # noqa: E402

ff = _load.load(ROOT)
cases, runner, summary, stats = (importlib.import_module(f"{ff.__name__}.{m}") for m in
                                 ("cases", "sweep.runner", "sweep.summary", "sweep.stats"))
wilson = stats.wilson

LADDER = (2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 24, 32, 40)
START, END = "<!-- validation table: written by make validate -->", "<!-- end of validation table -->"


def sweep(case_path, out: pathlib.Path, workers: int, *extra) -> list[dict]:
    """Run `headless.py sweep --case` (resuming) and return its records."""
    cmd = [sys.executable, str(ROOT / "headless.py"), "sweep", "--case", str(case_path),
           "--out", str(out), "--workers", str(workers), "--quiet", "--no-plot", *extra]
    if (out / "results.jsonl").exists():
        cmd.append("--resume")
    cp = subprocess.run(cmd, capture_output=True, text=True)
    if cp.returncode not in (0, 1):
        raise RuntimeError(cp.stderr.strip().splitlines()[-1] if cp.stderr.strip() else
                           f"sweep exited {cp.returncode}")
    records, _ = runner.read_lines(out / "results.jsonl")
    return records


def minimal_linker(case_path, case, p, out, workers) -> dict:
    real = p.linker
    if real <= LADDER[0]:
        return {"status": f"not searched: the real linker ({real}) is at the ladder's start"}
    tried = []
    for linker in [n for n in LADDER if n < real] + [real]:
        rows = summary.rows(sweep(case_path, out / f"linker{linker}", workers,
                                  "--linker", str(linker)))
        row = rows[0]
        tried.append((linker, row.accommodated, row.n))
        if row.n and row.accommodated == row.n:
            return {"linker": linker, "tried": tried,
                    "below": tried[-2][0] if len(tried) > 1 else None}
    return {"status": f"none up to the real linker {real}", "tried": tried}


def contour_radius(p) -> float:
    """Where the build puts a globule: the linker fully stretched, radially."""
    return p.chain_x()[-1]


def validate(case_path: pathlib.Path, out: pathlib.Path, workers: int) -> dict:
    row = {"case": case_path.name}
    try:
        case = cases.load(case_path)
    except cases.CaseError as exc:
        row["error"] = str(exc).replace(str(case_path) + ": ", "")
        return row
    p = case.make_params()
    row.update(name=case.meta.get("name", case_path.stem), meta=case.meta, params=p.to_dict())
    records = sweep(case_path, out / case_path.stem / "real", workers)
    (r,) = summary.rows(records)
    row["fit"] = {"accommodated": r.accommodated, "n": r.n, "failed": r.failed,
                  "wilson95": list(wilson(r.accommodated, r.n)) if r.n else None}
    mid, low, high = r.diameter
    row["outer_diameter"] = {"median": mid, "min": low, "max": high}
    medians = [x["envelope"]["r_median"] for x in records if x.get("envelope")]
    row["envelope_at_contour"] = bool(medians) and all(
        abs(m - contour_radius(p)) < 0.01 * contour_radius(p) for m in medians)
    row["frames"] = sorted({x["frames_simulated"] for x in records if "frames_simulated" in x})
    row["minimal"] = minimal_linker(case_path, case, p, out / case_path.stem / "minimal", workers)
    return row


def _fit_text(row) -> str:
    f = row["fit"]
    if not f["n"]:
        return f"no run finished ({f['failed']} failed)"
    low, high = f["wilson95"]
    return f"{f['accommodated']}/{f['n']} ({low:.2f}-{high:.2f})"


def _minimal_text(row) -> tuple[str, str]:
    m, real = row["minimal"], row["params"]["linker"]
    if "linker" not in m:
        return m["status"], "-"
    below = f" ({m['below']} not)" if m.get("below") else ""
    return f"{m['linker']}{below}", f"{real / m['linker']:.1f}"


def _envelope_text(row) -> str:
    d = row["outer_diameter"]
    if d["median"] is None:
        return "-"
    text = f"{d['median'] / 10:.1f} nm ({d['min'] / 10:.1f}-{d['max'] / 10:.1f})"
    if row["envelope_at_contour"]:
        text += ", = the stretched linker (upper bound)"
    return text


def _agreement(row) -> str:
    meta, f = row["meta"], row["fit"]
    expected = meta.get("expected", "unknown")
    fits = f["accommodated"] > 0
    if expected == "unknown" or not f["n"]:
        verdict = "no verdict to compare"
    elif (expected == "fits") == fits:
        verdict = "agrees" + (" (a clash-free layout exists)" if fits else "")
    elif expected == "fits":
        verdict = ("disagrees: no seed found room; a failed search is not proof that none "
                   "exists (README, What a verdict proves), or an estimate is off")
    else:
        verdict = "disagrees: the model finds room the literature says is missing"
    width = meta.get("envelope_width")
    if width and row["outer_diameter"]["median"] is not None:
        ratio = row["outer_diameter"]["median"] / width
        verdict += f"; width {ratio:.1f}x the measured"
        if row["envelope_at_contour"]:
            verdict += " (the model's width is the linker's full extension, not a prediction)"
    return verdict


def table(rows: list[dict]) -> str:
    head = ("| case | source | observed | P(fit) at the real linker | real linker | minimal "
            "linker | margin (real / minimal) | predicted outer diameter | measured width | "
            "FibrilFit vs literature |")
    lines = [head, "|" + "---|" * 10]
    for row in rows:
        if "error" in row:
            lines.append(f"| `{row['case']}` | | | not run: {row['error']} | | | | | | |")
            continue
        meta = row["meta"]
        source = meta.get("pdb", "") + (f", doi:{meta['doi']}" if meta.get("doi") else "")
        minimal, margin = _minimal_text(row)
        width = meta.get("envelope_width")
        lines.append("| " + " | ".join([
            f"`{row['case']}` {row['name']}", source or meta.get("source", ""),
            meta.get("observed", ""), _fit_text(row), str(row["params"]["linker"]), minimal,
            margin, _envelope_text(row), f"{width / 10:.0f} nm" if width else "-",
            _agreement(row)]) + " |")
    return "\n".join(lines)


def write_readme(text: str) -> None:
    readme = ROOT / "README.md"
    body = readme.read_text(encoding="utf-8")
    if START not in body or END not in body:
        raise SystemExit(f"README.md has no {START} ... {END} markers")
    a, b = body.index(START) + len(START), body.index(END)
    readme.write_text(body[:a] + "\n" + text + "\n" + body[b:], encoding="utf-8")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("cases", nargs="*", type=pathlib.Path)
    ap.add_argument("--out", type=pathlib.Path, default=ROOT / "out" / "validate")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--no-readme", action="store_true")
    args = ap.parse_args(argv)
    paths = args.cases or sorted((ROOT / "examples").glob("*.toml"),
                                 key=lambda q: (q.stem != "tutorial", q.stem))
    rows = []
    for path in paths:
        print(f"validate: {path.name}", file=sys.stderr, flush=True)
        rows.append(validate(path, args.out, args.workers))
        (args.out / "validation.json").parent.mkdir(parents=True, exist_ok=True)
        (args.out / "validation.json").write_text(json.dumps(rows, indent=1), encoding="utf-8")
    text = table(rows)
    print(text)
    if not args.no_readme:
        write_readme(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
