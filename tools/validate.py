"""`make validate`: run the gallery (examples/*.toml) and write the validation table of the docs
(docs/validation.md, between its markers).

For every case: its seeds at the real linker (P(fit) = the accommodated fraction, with its 95 %
Wilson interval, and the envelope's outer diameter over the seeds), then the minimal linker from
`headless.py minimal-linker --case` (issue #13's walk with R restarts per length, protocol
inflate unless the case sets one), searched up to the real linker or MAX_LINKER.
Runs go through `headless.py sweep` (results kept in out/validate/, so running again resumes).
A case that cannot run in this build (e.g. a parameter from an issue not merged yet) gets a row
saying why. Nothing is filled in by hand. (Over 400 lines: the runs, the walk, the stored rows and
the page's text are one pipeline; the table's cells are fibrilfit/sweep/validation.py's.)

    python tools/validate.py [--out out/validate] [--workers 2] [--parallel 2] [--restarts 3]
                             [--no-docs] [CASE.toml ...]
"""
from __future__ import annotations

import argparse
import collections
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
from fibrilfit.model.chain import chain_x  # noqa: E402
from fibrilfit.sweep import runner, stats, summary, validation  # noqa: E402
from fibrilfit.sweep.validation import glance, provenance, table  # noqa: E402,F401 (tests)
wilson = stats.wilson

MAX_LINKER = 40  # minimal-linker gives up above this (or above the real linker)
START, END = "<!-- validation table: written by make validate -->", "<!-- end of validation table -->"
# the short table at the page's top (issue #47 item 5), from the same rows
GLANCE = ("<!-- validation at a glance: written by make validate -->",
          "<!-- end of validation at a glance -->")


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


def reuse_real_runs(case_path, real: pathlib.Path, walk: pathlib.Path) -> int:
    """Copy into the walk's folder, before it first starts, the real linker's runs that the walk
    would make again: a run is a pure function of its parameters (seed included), and the walk
    resumes by the whole parameter set (sweep/grid.point_key), so it reuses exactly the runs
    whose parameters are its own and bakes the rest. Only runs under the walk's protocol are
    copied (minimal-linker's: inflate unless the case sets one; search/linker_map.walks_for).
    Measured 2026-11-26: the negative control's walks, and the near-threshold case's, baked
    their real linker's restarts a second time, bit for bit the same runs, 12 % of make
    validate's worker-seconds (docs/benchmarks.md#validate-v6). Returns how many were copied."""
    source, target = real / "results.jsonl", walk / "results.jsonl"
    if target.exists() or not source.exists():
        return 0  # a walk already begun keeps its own runs
    protocol = cases.load(case_path).params.get("protocol", "inflate")
    lines = [line for line in source.read_text(encoding="utf-8").splitlines() if line.strip()]
    keep = []
    for line in lines:
        r = json.loads(line)
        if r.get("status") == "ok" and r.get("params", {}).get("protocol") == protocol:
            keep.append(line)
    if keep:
        walk.mkdir(parents=True, exist_ok=True)
        target.write_text("\n".join(keep) + "\n", encoding="utf-8")
    return len(keep)


BOUND_KEYS = ("impossible_below", "over", "fails_below", "exit_residues")


def git_commit() -> str:
    """The last commit that changed the model's code (version.MODEL_SOURCES: what the runs'
    numbers depend on), "+changes" if the checkout's model code differs from it."""
    from fibrilfit.model import version
    paths = [f"fibrilfit/{x}" for x in version.MODEL_SOURCES]

    def git(*a):
        return subprocess.run(["git", *a], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    dirty = git("status", "--porcelain", "--", *paths)
    return git("log", "-1", "--format=%h", "--", *paths) + ("+changes" if dirty else "")


def code_now(records=()) -> dict:
    """The code a row is measured with now: date, commit, MODEL_VERSION, bpy."""
    from fibrilfit.model import version
    first = records[0] if records else {}
    bpy = first.get("blender_version")
    return {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"),
            "commit": git_commit(),
            "model_version": first.get("model_version", version.MODEL_VERSION),
            "bpy": ".".join(str(x) for x in bpy) if isinstance(bpy, list) else bpy}


def case_bound(case_path) -> dict:
    """The bound of a case's model at its real linker (geometry only, no run; structure files
    measured as `run` measures them), with the code it was computed with."""
    from fibrilfit.api.model import resolve
    from fibrilfit.api.plans import RunPlan, make_plan
    from fibrilfit.model import bound
    plan, _ = make_plan(RunPlan, {}, case=str(case_path), command="run")
    p = resolve(plan).p
    b = bound.linker_bound(p)
    out = {k: b.get(k) for k in BOUND_KEYS}
    out["computed"] = {k: v for k, v in code_now().items() if k != "bpy"}
    return out


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
    return chain_x(p)[-1]


def validate(case_path: pathlib.Path, out: pathlib.Path, workers: int, extra: tuple = (),
             collect: bool = False) -> dict:
    """The real linker's seeds (the minimal linker comes in a second pass, see main)."""
    row = {"case": case_path.name}
    try:
        case = cases.load(case_path)
    except cases.CaseError as exc:
        row["error"] = str(exc).replace(str(case_path) + ": ", "")
        return row
    p = case.make_params()
    row.update(name=case.meta.get("name", case_path.stem), meta=case.meta, params=p.to_dict(),
               case_sha256=case.sha256)  # a walk of another version of the case is not this one's
    if collect:  # the runs already there, however many seeds finished
        records = runner.read_lines(out / case_path.stem / "real" / "results.jsonl")[0]
    else:
        try:
            records = sweep(case_path, out / case_path.stem / "real", workers, *extra)
        except RuntimeError as exc:  # refused by this build (e.g. a file it cannot read yet)
            return {"case": case_path.name, "error": f"cannot run in this build: {exc}"}
    if not records:
        return {"case": case_path.name, "error": "no seed finished (make validate runs it)"}
    if "params" in records[0]:  # as run: structure files may have filled some
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
    row["answers"] = dict(collections.Counter(x["answer"] for x in records if x.get("answer")))
    if records and records[0].get("bound"):  # every result carries it (docs/model/bound.md)
        row["bound"] = {k: records[0]["bound"].get(k) for k in BOUND_KEYS}
        row["bound"]["computed"] = None  # with the runs (the row's `measured`)
    if records and records[0].get("exit"):
        row["exit"] = {k: records[0]["exit"].get(k) for k in ("residues", "length", "depth",
                                                               "free_linker")}
    row["measured"] = code_now(records)
    row["minimal"] = {"status": "walk not run (make validate runs none: make validate-walks "
                                "does; or the time budget of --until)"}
    return row


PAGE = ROOT / "docs" / "validation.md"  # the page whose table this writes
# Every row measured so far, with the code it was measured with: the table is written from it,
# so a row outlives a run that did not re-run its case (a full make validate: 17 min).
STORED = ROOT / "examples" / "measured.json"
KEPT_PARAMS = ("linker", "layers", "score_layers", "periodic", "protocol", "globule_diameter",
               "exit_residues")


def stored_path(shape: str | None = None) -> pathlib.Path:
    return STORED if shape is None else STORED.with_name(f"measured-{shape}.json")


def stored_rows(shape: str | None = None) -> dict:
    path = stored_path(shape)
    if not path.exists():
        return {}
    return {r["case"]: r for r in json.loads(path.read_text(encoding="utf-8"))}


def save_stored(stored: dict, shape: str | None = None) -> None:
    rows = [stored[k] for k in sorted(stored)]
    stored_path(shape).write_text(json.dumps(rows, indent=1, ensure_ascii=False) + "\n",
                                  encoding="utf-8")


def kept(row: dict) -> dict:
    """A row as stored: its measured numbers and the few parameters the table reads."""
    out = {k: v for k, v in row.items() if k not in ("params", "meta", "name")}
    if "params" in row:
        out["params"] = {k: row["params"][k] for k in KEPT_PARAMS if k in row["params"]}
    return out


def gallery_rows(gallery: list, stored: dict) -> list[dict]:
    """The table's rows in the gallery's order: each case's stored row, with the case file's
    own words (what the experiment says is the paper's, not a run's), and its bound computed
    if the row has none (geometry only: about a minute for a structure-file case)."""
    rows = []
    for path in gallery:
        row = dict(stored.get(path.name) or {})
        if not row:
            rows.append({"case": path.name, "error": "not measured yet: make validate runs it"})
            continue
        if "error" not in row:
            try:
                case = cases.load(path)
                row["meta"] = case.meta
                row["name"] = case.meta.get("name", path.stem)
                if not row.get("bound"):
                    row["bound"] = stored[path.name]["bound"] = case_bound(path)
            except Exception as exc:  # noqa: BLE001 (the row says why)
                row = {"case": path.name, "error": f"case file: {exc}"}
        rows.append(row)
    return rows


def fibrils_and_runs(rows: list[dict]) -> str:
    """The line under the provenance: each measured row's fibril (its layers, or the periodic
    cell of the infinite fibril) and its runs (the seeds at the real linker, the walk's restarts
    a length), from the stored rows (docs/contributing.md#results-tables)."""
    groups: dict = {"Fibrils": {}, "Runs at the real linker": {}, "The minimal-linker walk": {}}
    for r in (r for r in rows if "error" not in r and (r.get("params") or {}).get("layers")):
        p, case = r["params"], r["case"].removesuffix(".toml")
        cut = p.get("score_layers") and f", {p['score_layers']} left out of the score at each end"
        size = (f"a periodic cell of {p['periodic']} layers (the infinite fibril)"
                if p.get("periodic") else f"{p['layers']} layers{cut or ''}")
        seeds, walk = (r.get("fit") or {}).get("n"), (r.get("minimal") or {}).get("restarts")
        for name, key in (("Fibrils", size),
                          ("Runs at the real linker", seeds and f"{seeds} seeds"),
                          ("The minimal-linker walk", walk and f"{walk} restarts a length")):
            if key:
                groups[name].setdefault(key, []).append(case)
    return " ".join(f"{name}: " + "; ".join(f"{k}: {', '.join(v)}" for k, v in g.items()) + "."
                    for name, g in groups.items() if g)


def page_text(rows: list[dict]) -> str:
    """What make validate writes between the page's markers: the table, its provenance, and its
    fibrils and runs."""
    text = table(rows) + "\n\n" + provenance(rows)
    more = fibrils_and_runs(rows)
    return text + ("\n\n" + more if more else "")


def glance_text(rows: list[dict]) -> str:
    """What make validate writes at the page's top: the short table, its provenance, and its
    fibrils and runs (as under the wide table)."""
    more = fibrils_and_runs(rows)
    return glance(rows) + "\n\n" + provenance(rows) + ("\n\n" + more if more else "")


def gallery_paths() -> list[pathlib.Path]:
    """The gallery's case files in the table's order: the tutorial first, then by name."""
    return sorted((ROOT / "examples").glob("*.toml"), key=lambda q: (q.stem != "tutorial", q.stem))


def written_blocks() -> dict[tuple[str, str], str]:
    """What `make validate --table-only` writes between the page's markers, from the stored
    rows: {(start marker, end marker): text}. tests/unit/test_docs_numbers.py reads a page's
    generated blocks against it, so a block that is not what the data renders is prose."""
    rows = gallery_rows(gallery_paths(), stored_rows())
    return {(START, END): page_text(rows), GLANCE: glance_text(rows)}


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


def write_page(text: str, page: pathlib.Path = PAGE, shape: str | None = None,
               between: tuple | None = None) -> bool:
    """Write `text` between the page's markers; False (the page untouched) where the block is a
    `{{ ... }}` the docs build renders from a data file (the hull table: docs/data/validation/
    hull.json), which a typed table must not replace."""
    start, end = between or markers(shape)
    body = page.read_text(encoding="utf-8")
    if start not in body or end not in body:
        raise SystemExit(f"{page.relative_to(ROOT)} has no {start} ... {end} markers")
    a, b = body.index(start) + len(start), body.index(end)
    if "{{" in body[a:b]:
        return False
    page.write_text(body[:a] + "\n" + text + "\n" + body[b:], encoding="utf-8")
    return True


def case_file(name: pathlib.Path) -> pathlib.Path:
    """A case named on the command line: a path to a .toml file, or a gallery case by its name
    (`tutorial`, `orb2_6vps.toml`); anything else is refused (ValueError, one line)."""
    for path in (name, ROOT / "examples" / name, ROOT / "examples" / f"{name}.toml"):
        if path.suffix == ".toml" and path.is_file():
            return path
    known = ", ".join(sorted(q.stem for q in (ROOT / "examples").glob("*.toml")))
    raise ValueError(f"cases: no case file {str(name)!r} (give a .toml path, or one of: {known})")


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
                    help="print the table only; leave docs/validation.md and examples/"
                         "measured.json as they are (bench/targets.py: a timing run, not a "
                         "measurement of record)")
    ap.add_argument("--table-only", action="store_true",
                    help="run nothing: write the table from the stored rows (examples/"
                         "measured.json), computing the bound of a row that has none")
    ap.add_argument("--collect", action="store_true",
                    help="run nothing new: make the rows of the cases named from the runs "
                         "already in --out (the seeds that finished), e.g. after a run was cut "
                         "short; implies --no-walk")
    ap.add_argument("--walk", dest="walk", action=argparse.BooleanOptionalAction, default=True,
                    help="the minimal-linker walk after the seeds [default: on]")
    args = ap.parse_args(argv)
    if args.collect:
        args.walk = False
    if args.until:
        hh, mm = (int(x) for x in args.until.split(":"))
        now = datetime.datetime.now(datetime.timezone.utc)
        args.until = now.replace(hour=hh, minute=mm, second=0, microsecond=0).timestamp()
    gallery = gallery_paths()
    try:
        paths = [] if args.table_only else ([case_file(c) for c in args.cases] or gallery)
    except ValueError as exc:  # before anything runs or is written
        print(f"validate: {exc}", file=sys.stderr)
        return 2
    extra = ()
    if args.domain_shape:
        paths = [q for q in paths if has_domain_file(q)]
        gallery = [q for q in gallery if has_domain_file(q)]
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
        rows[i] = validate(path, args.out, args.workers, extra, collect=args.collect)
        said(f"{path.name} at its real linker: done")
        with lock:
            save()

    def walk(i, path):
        row = rows[i]
        if not args.walk or "error" in row or (args.until and time.time() > args.until):
            return  # the row keeps saying it was not computed
        reused = reuse_real_runs(path, args.out / path.stem / "real",
                                 args.out / path.stem / "minimal-linker")
        said(f"minimal linker of {path.name}"
             + (f" ({reused} runs at its real linker reused)" if reused else ""))
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
    stored = stored_rows(args.domain_shape)
    for row in rows:  # a skipped case keeps its stored row
        if row is not None and not str(row.get("error", "")).startswith("skipped"):
            old = stored.get(row["case"], {})
            if ("row" not in row.get("minimal", {}) and "row" in old.get("minimal", {})
                    and old.get("measured", {}).get("model_version")
                    == row.get("measured", {}).get("model_version")
                    and old.get("case_sha256") == row.get("case_sha256")):
                row["minimal"] = old["minimal"]  # a walk this run did not redo stays
            stored[row["case"]] = kept(row)
    shown = gallery_rows(gallery, stored)
    text = page_text(shown)
    print(text)
    if not args.no_docs:
        save_stored(stored, args.domain_shape)
        if not write_page(text, shape=args.domain_shape):
            print(f"{PAGE.relative_to(ROOT)}: its table for this run is rendered from a data file "
                  f"(docs/data/validation/hull.json), so the page is left as it is; this run's rows "
                  f"are in {stored_path(args.domain_shape).relative_to(ROOT)}")
        if args.domain_shape is None:
            write_page(glance_text(shown), between=GLANCE)
    return 0


if __name__ == "__main__":
    sys.exit(main())
