"""`make validate`: run the gallery (examples/*.toml) and write the validation table of the docs
(docs/validation.md, between its markers).

For every case: its seeds at the real linker (P(fit) = the accommodated fraction, with its 95 %
Wilson interval, and the envelope's outer diameter over the seeds), then the minimal linker from
`headless.py minimal-linker --case` (issue #13's walk with R restarts per length, protocol
inflate unless the case sets one), searched up to the real linker or MAX_LINKER.
Runs go through `headless.py sweep` (results kept in out/validate/, so running again resumes).
A case that cannot run in this build (e.g. a parameter from an issue not merged yet) gets a row
saying why. Nothing is filled in by hand.

    python tools/validate.py [--out out/validate] [--workers 2] [--parallel 2] [--restarts 3]
                             [--no-docs] [CASE.toml ...]
"""
from __future__ import annotations

import argparse
import concurrent.futures
import datetime
import importlib
import json
import pathlib
import subprocess
import sys
import threading
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]

from fibrilfit.model import cases, params as P  # noqa: E402
from fibrilfit.sweep import runner, stats, summary  # noqa: E402
wilson = stats.wilson

MAX_LINKER = 40  # minimal-linker gives up above this (or above the real linker)
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


def minimal_linker(case_path, p, out: pathlib.Path, workers: int, restarts: int,
                   until: float | None = None, fits_at_real: bool = False,
                   extra: tuple = ()) -> dict:
    """`headless.py minimal-linker --case` (issue #13's walk, protocol inflate unless the case
    sets one), up to the real linker or MAX_LINKER. A case that fits at its real linker tells
    the walk so (--known-fit): it brackets the minimum below it and bisects (issue #25)."""
    top = min(p.linker, MAX_LINKER)
    cmd = [sys.executable, str(ROOT / "headless.py"), "minimal-linker", "--case", str(case_path),
           "--restarts", str(restarts), "--max-linker", str(top), "--out", str(out),
           "--workers", str(workers), "--quiet", "--no-plot", *extra]
    # all R at the minimum too: the table gives P(fit) there (k/R); a fit costs a few seconds,
    # the misses one below (all R either way) are the cost (docs/model/search.md#decided)
    cmd.append("--all-restarts")
    if fits_at_real:  # beyond MAX_LINKER too: the walk then still stops at the cap
        cmd += ["--known-fit", str(p.linker)]
    if (out / "results.jsonl").exists():
        cmd.append("--resume")
    try:
        cp = subprocess.run(cmd, capture_output=True, text=True,
                            timeout=None if until is None else max(1.0, until - time.time()))
    except subprocess.TimeoutExpired:
        return {"status": "not finished in this run's time budget (--until); make validate "
                          "again resumes it"}
    if cp.returncode != 0:
        last = cp.stderr.strip().splitlines()[-1] if cp.stderr.strip() else f"exit {cp.returncode}"
        return {"status": f"minimal-linker failed: {last}"}
    (row,) = json.loads((out / "minimal_linker.json").read_text(encoding="utf-8"))["rows"]
    return {"row": row, "max": top, "restarts": restarts}


def bodies(case_path) -> int:
    """A case's size at its real linker: the rigid bodies it builds (chains x members), what a
    run's cost grows with; 0 for a case that cannot be read (its row will say why)."""
    try:
        p = cases.load(case_path).make_params(force=True)
    except Exception:  # noqa: BLE001 (the run reports it)
        return 0
    return p.layers * p.protofilaments * (p.linker + 2)


def contour_radius(p) -> float:
    """Where the build puts a globule: the linker fully stretched, radially."""
    return p.chain_x()[-1]


def validate(case_path: pathlib.Path, out: pathlib.Path, workers: int, extra: tuple = ()) -> dict:
    """The real linker's seeds (the minimal linker comes in a second pass, see main)."""
    row = {"case": case_path.name}
    try:
        case = cases.load(case_path)
    except cases.CaseError as exc:
        row["error"] = str(exc).replace(str(case_path) + ": ", "")
        return row
    p = case.make_params()
    row.update(name=case.meta.get("name", case_path.stem), meta=case.meta, params=p.to_dict())
    records = sweep(case_path, out / case_path.stem / "real", workers, *extra)
    if records and "params" in records[0]:  # as run: structure files may have filled some
        p = P.make_params(force=True, **records[0]["params"])
        row["params"] = p.to_dict()
    (r,) = summary.rows(records)
    row["fit"] = {"accommodated": r.accommodated, "n": r.n, "failed": r.failed,
                  "wilson95": list(wilson(r.accommodated, r.n)) if r.n else None}
    mid, low, high = r.diameter
    row["outer_diameter"] = {"median": mid, "min": low, "max": high}
    medians = [x["envelope"]["r_median"] for x in records if x.get("envelope")]
    row["envelope_at_contour"] = bool(medians) and all(
        abs(m - contour_radius(p)) < 0.01 * contour_radius(p) for m in medians)
    row["frames"] = sorted({x["frames_simulated"] for x in records if "frames_simulated" in x})
    row["minimal"] = {"status": "not computed in this run (time budget, --until); "
                                "make validate again resumes"}
    return row


def _fit_text(row) -> str:
    f = row["fit"]
    if not f["n"]:
        return f"no run finished ({f['failed']} failed)"
    low, high = f["wilson95"]
    return f"{f['accommodated']}/{f['n']} ({low:.2f}-{high:.2f})"


def _minimal_text(row) -> tuple[str, str]:
    m, real = row["minimal"], row["params"]["linker"]
    if "row" not in m:
        return m["status"], "-"
    r = m["row"]
    if r.get("error"):
        return f"not found: {r['error']}", "-"
    if r["minimal_linker"] is None:
        return f"none up to {m['max']} ({m['restarts']} restarts each)", "-"
    below = (f"; {r['linker_below']}: 0/{m['restarts']}" if r.get("linker_below") else "")
    return (f"{r['minimal_linker']} ({r['fits']}/{r['restarts']} fit{below})",
            f"{real / r['minimal_linker']:.1f}")


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
                   "exists (docs/model/verdict.md#proves), or an estimate is off")
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


PAGE = ROOT / "docs" / "validation.md"  # the page whose table this writes


def markers(shape: str | None) -> tuple:
    """The page's markers around the table: the gallery's, or its re-run with a domain shape."""
    if shape is None:
        return START, END
    return (f"<!-- validation table, domain shape {shape}: written by make validate-shapes -->",
            f"<!-- end of validation table, domain shape {shape} -->")


def has_domain_file(case_path) -> bool:
    try:
        return bool(cases.load(case_path).structure.get("domain"))
    except Exception:  # noqa: BLE001 (not a structure case)
        return False


def write_page(text: str, page: pathlib.Path = PAGE, shape: str | None = None) -> None:
    start, end = markers(shape)
    body = page.read_text(encoding="utf-8")
    if start not in body or end not in body:
        raise SystemExit(f"{page.relative_to(ROOT)} has no {start} ... {end} markers")
    a, b = body.index(start) + len(start), body.index(end)
    page.write_text(body[:a] + "\n" + text + "\n" + body[b:], encoding="utf-8")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("cases", nargs="*", type=pathlib.Path)
    ap.add_argument("--out", type=pathlib.Path,
                    help="results (resumed) [default out/validate, or out/validate-SHAPE]")
    ap.add_argument("--domain-shape", choices=("hull", "spheres"),
                    help="re-run the cases that read a domain structure file with this shape "
                         "(issue #24), into their own table on the page")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--parallel", type=int, default=2, metavar="N",
                    help="cases run at the same time, each on --workers processes [default 2]")
    ap.add_argument("--restarts", type=int, default=3,
                    help="restarts per linker length in minimal-linker [default 3]")
    ap.add_argument("--until", metavar="HH:MM",
                    help="start no minimal-linker search after this UTC time, and stop one "
                         "still running then (its runs are kept for the next make validate)")
    ap.add_argument("--skip", action="append", default=[], metavar="CASE",
                    help="leave this case out (its row says so); repeatable")
    ap.add_argument("--no-docs", action="store_true",
                    help="print the table only; leave docs/validation.md as it is")
    args = ap.parse_args(argv)
    if args.until:
        hh, mm = (int(x) for x in args.until.split(":"))
        now = datetime.datetime.now(datetime.timezone.utc)
        args.until = now.replace(hour=hh, minute=mm, second=0, microsecond=0).timestamp()
    paths = args.cases or sorted((ROOT / "examples").glob("*.toml"),
                                 key=lambda q: (q.stem != "tutorial", q.stem))
    extra = ()
    if args.domain_shape:
        paths = [q for q in paths if has_domain_file(q)]
        extra = ("--domain-shape", args.domain_shape)
    if args.out is None:
        args.out = ROOT / "out" / ("validate" + (f"-{args.domain_shape}" if args.domain_shape else ""))
    rows = [None] * len(paths)  # in the gallery's order, whichever case finishes first

    def save():
        have = [r for r in rows if r is not None]
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "validation.json").write_text(json.dumps(have, indent=1), encoding="utf-8")
        (args.out / "table.md").write_text(table(have) + "\n", encoding="utf-8")

    lock = threading.Lock()
    started = time.time()

    def said(text):
        with lock:
            print(f"validate: [{time.time() - started:6.0f} s] {text}", file=sys.stderr,
                  flush=True)

    def real(i, path):
        if path.name in args.skip or path.stem in args.skip:
            rows[i] = {"case": path.name, "error": "skipped in this run (--skip), e.g. for "
                                                   "lack of time; make validate runs it"}
            return
        said(f"{path.name} at its real linker")
        rows[i] = validate(path, args.out, args.workers, extra)
        said(f"{path.name} at its real linker: done")
        with lock:
            save()

    def walk(i, path):
        row = rows[i]
        if "error" in row or (args.until and time.time() > args.until):
            return  # the row keeps saying it was not computed
        said(f"minimal linker of {path.name}")
        minimal = minimal_linker(path, P.make_params(force=True, **row["params"]),
                                 args.out / path.stem / "minimal-linker", args.workers,
                                 args.restarts, args.until,
                                 fits_at_real=row["fit"]["accommodated"] > 0, extra=extra)
        said(f"minimal linker of {path.name}: done")
        with lock:
            row["minimal"] = minimal
            save()

    # First every case at its real linker (the cheaper, more telling part), then the minimal
    # linkers, while time allows. --parallel cases at a time, each with --workers processes:
    # a case's last runs leave workers idle (3 seeds on 2 workers: a quarter of the time), which
    # the other case's runs fill (docs/benchmarks.md#validate).
    # Largest first (the longest-processing-time rule): a case queued last should be a short
    # one, or it runs alone at the end on one case's workers (measured: Orb2's three seeds at
    # its 200-residue linker were a third of the whole, docs/benchmarks.md#validate).
    order = sorted(range(len(paths)), key=lambda i: -bodies(paths[i]))
    with concurrent.futures.ThreadPoolExecutor(max(1, args.parallel)) as pool:
        reals = {i: pool.submit(real, i, paths[i]) for i in order}
        # queued behind every real-linker task; each starts once its own case's is done
        walks = [pool.submit(lambda i, path: (reals[i].result(), walk(i, path)), i, paths[i])
                 for i in order]
        for done in list(reals.values()) + walks:
            done.result()
    text = table(rows)
    print(text)
    if not args.no_docs:
        write_page(text, shape=args.domain_shape)
    return 0


if __name__ == "__main__":
    sys.exit(main())
