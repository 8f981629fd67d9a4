"""`make pictures`: every picture the docs show that the model makes, made again from this
checkout's code and stamped with its MODEL_VERSION (tools/picture_stamp.py;
tests/unit/test_pictures.py fails a picture whose stamp is older than the code's).

    .venv/bin/python tools/pictures.py [--only NAME,NAME] [--report-dir DIR] [--list]

NAME is a picture's file name (`report_6cu7.png`). What is not made here, and how it is kept
honest:
- the sidebar's screens in the real Blender (in docs/images/: the panel's and result.png):
  `make test-blender ACCEPT_SCREENS=1` takes them in Blender 4.3.2 and stamps every screen it
  took or compared equal (tests/realblender/test_gui.py);
- a dated notebook's pictures (docs/notebook/ pages only): a record of what was measured then,
  stamped with the MODEL_VERSION the page names (the test holds them to a stamp, not to today's
  version).

The report screenshot needs the trixie chroot's Chromium (`make test-blender` builds it; root);
without it that picture fails with one line and the others are still made. Roughly 20 minutes
on two quiet cores, most of it the 20-layer report (8 restarts and the walk); the ensemble
(bench/ensemble.py) and the largest-fraction map took 1.5 and 2 minutes of wall time beside
other work (load 6-10, 2026-11-27). Every maker runs this checkout's
code (PYTHONPATH is set to it, so an editable install of another checkout is not used) into a
fresh folder under out/pictures/ (only --report-dir photographs a report made before).
"""
from __future__ import annotations

import argparse
import datetime
import functools
import importlib.util
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _picture_stamp():
    """tools/picture_stamp.py, loaded by its path (tools/ is not a package)."""
    spec = importlib.util.spec_from_file_location(
        "picture_stamp", pathlib.Path(__file__).resolve().parent / "picture_stamp.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


picture_stamp = _picture_stamp()

PY = sys.executable
OUT = ROOT / "out" / "pictures"
DATA = "tests/data"
# this checkout's package first, for `-m fibrilfit` and for scripts (bench/, tools/) alike
ENV = {**os.environ, "PYTHONPATH": os.pathsep.join(
    [str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])])}
REPORT = ["report", "--fibril", f"{DATA}/6cu7.pdb.gz", "--domain", f"{DATA}/1ubq.pdb.gz",
          "--linker", "8", "--restarts", "8", "--workers", "2", "--quiet"]


def fibrilfit(*args: str) -> None:
    cp = subprocess.run([PY, "-m", "fibrilfit", *args], cwd=ROOT, capture_output=True, text=True,
                        env=ENV)
    if cp.returncode != 0:
        raise RuntimeError(f"fibrilfit {' '.join(args)}: exit {cp.returncode}: {cp.stderr[-400:]}")


def render(dest: str, *args: str):
    """A `run --render` picture, as the page that shows it gives the command."""
    def make(report_dir):
        fibrilfit("run", *args, "--render", dest)
        return "fibrilfit run " + " ".join(args) + f" --render {dest}"
    return make


def report_shot(report_dir: pathlib.Path | None) -> str:
    """docs/report_6cu7.png: the report of docs/guide/report.md's command, photographed by
    headless Chromium (the trixie chroot of make test-blender; no network)."""
    folder = report_dir or OUT / "report"
    if report_dir is None:
        shutil.rmtree(folder, ignore_errors=True)
        fibrilfit(*REPORT, "--out", str(folder.relative_to(ROOT)))
    shot = OUT / "report_6cu7.png"
    shot.parent.mkdir(parents=True, exist_ok=True)
    inside = lambda p: "/fibrilfit/" + p.resolve().relative_to(ROOT).as_posix()  # noqa: E731
    flags = ("--headless --no-sandbox --disable-gpu --hide-scrollbars "
             "--host-resolver-rules='MAP * ~NOTFOUND' --proxy-server=127.0.0.1:9 "
             "--virtual-time-budget=5000 --window-size=1200,1600")
    cp = subprocess.run(["sh", str(ROOT / ".ci" / "blender" / "chroot.sh"), "run",
                         f"export HOME=/tmp/chromium-home && chromium {flags} "
                         f"--screenshot={inside(shot)} file://{inside(folder / 'report.html')}"],
                        capture_output=True, text=True, timeout=600)
    if cp.returncode != 0 or not shot.exists():
        raise RuntimeError(f"Chromium in the chroot: {cp.stderr.strip()[-300:]}")
    shutil.copyfile(shot, ROOT / "docs" / "report_6cu7.png")
    return ("fibrilfit " + " ".join(REPORT) + f" --out {folder.relative_to(ROOT)}; headless "
            "Chromium 1200x1600 (tools/pictures.py)")


def tutorial_atoms(report_dir) -> str:
    cif = OUT / "tutorial" / "model.cif"
    cif.parent.mkdir(parents=True, exist_ok=True)
    args = ["run", "--fibril", f"{DATA}/6cu7.pdb.gz", "--domain", f"{DATA}/1ubq.pdb.gz",
            "--linker", "8", "--layers", "4", "--domain-shape", "hull", "--pdb-atoms",
            str(cif.relative_to(ROOT))]
    fibrilfit(*args)
    subprocess.run([PY, str(ROOT / "tools" / "atoms_picture.py"), str(cif),
                    str(ROOT / "docs" / "images" / "tutorial-atoms.png")], check=True, cwd=ROOT,
                   env=ENV)
    return "fibrilfit " + " ".join(args) + "; tools/atoms_picture.py"


def linker_count(report_dir) -> str:
    subprocess.run([PY, str(ROOT / "tools" / "linker_figure.py")], check=True, cwd=ROOT, env=ENV)
    return "tools/linker_figure.py"


# docs/data/pictures/: what the runs behind the model's plots measured (their own JSON), so a
# page's caption can quote them from a file
PICTURE_DATA = ROOT / "docs" / "data" / "pictures"
ENSEMBLE = ["bench/ensemble.py", "--out-dir", "out/pictures/ensemble", "--json",
            "out/pictures/ensemble/summary.json"]


@functools.cache
def ensemble_run() -> str:
    """bench/ensemble.py with its defaults (the default model, two halves of 4 Bullet starts,
    16 replicas, 30 sweeps of burn-in and 100 kept: docs/model/ensemble.md#cost), once per
    invocation of this script, into a fresh out/pictures/ensemble; its summary JSON kept as
    docs/data/pictures/ensemble_default.json."""
    out = OUT / "ensemble"
    shutil.rmtree(out, ignore_errors=True)
    subprocess.run([PY, *ENSEMBLE], check=True, cwd=ROOT, env=ENV)
    PICTURE_DATA.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(out / "summary.json", PICTURE_DATA / "ensemble_default.json")
    return (" ".join(ENSEMBLE) + " (its defaults: the default model, 4 Bullet starts a half, "
            "16 replicas, 30 + 100 sweeps; summary docs/data/pictures/ensemble_default.json)")


def ensemble_picture(bench_name: str, docs_name: str):
    """docs/model/<docs_name>: the bench's <bench_name> of ensemble_run()."""
    def make(report_dir):
        made_by = ensemble_run()
        shutil.copyfile(OUT / "ensemble" / bench_name, ROOT / "docs" / "model" / docs_name)
        return f"{made_by}: its {bench_name}"
    return make


# The largest-fraction map's picture, small enough for make pictures (a few minutes on two
# loaded cores): the table's smallest domain (20 Å balls, whose cell is the shortest, 12
# layers) on the infinite fibril as the table has it, at linkers 1-4 (the three below the fully
# decorated fibril's minimal linker, 4, and that one), 2 restarts (the table has 3; the cost is
# in the misses at one more decorated subunit, which 2 restarts make a third cheaper).
LARGEST = ["largest-fraction", "--globule-diameter", "20", "--linker", "1:4", "--periodic",
           "auto", "--restarts", "2", "--workers", "2", "--quiet"]


def largest_fraction(report_dir) -> str:
    """docs/largest_fraction.png: the command's own plot (found and bound against the linker);
    its largest_fraction.json kept in docs/data/pictures/largest_fraction_20A.json with the
    date, commit, MODEL_VERSION, command and wall time beside it."""
    out = OUT / "largest_fraction"
    shutil.rmtree(out, ignore_errors=True)
    load, t = os.getloadavg(), time.perf_counter()
    fibrilfit(*LARGEST, "--out", str(out.relative_to(ROOT)))
    wall = time.perf_counter() - t
    shutil.copyfile(out / "largest_fraction.png", ROOT / "docs" / "largest_fraction.png")
    PICTURE_DATA.mkdir(parents=True, exist_ok=True)
    record = {"date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="minutes"),
              "commit": picture_stamp.commit(), "model_version": picture_stamp.model_version(),
              "command": "fibrilfit " + " ".join(LARGEST) + f" --out {out.relative_to(ROOT)}",
              "made_by": "make pictures (tools/pictures.py)", "wall_s": round(wall, 1),
              "load_average_before": [round(v, 2) for v in load],
              "load_average_after": [round(v, 2) for v in os.getloadavg()],
              "largest_fraction": json.loads((out / "largest_fraction.json").read_text())}
    (PICTURE_DATA / "largest_fraction_20A.json").write_text(json.dumps(record, indent=1) + "\n")
    return ("fibrilfit " + " ".join(LARGEST) + f" --out {out.relative_to(ROOT)} (its plot; "
            "rows in docs/data/pictures/largest_fraction_20A.json)")


F6, U, F2, G = (f"{DATA}/6cu7.pdb.gz", f"{DATA}/1ubq.pdb.gz", f"{DATA}/2n0a.pdb.gz",
                f"{DATA}/1gfl.pdb.gz")
# picture (under docs/) -> its maker, which returns what made it (the stamp's made_by)
PICTURES = {
    "images/linker-count.png": linker_count,
    "images/tutorial-atoms.png": tutorial_atoms,
    "6cu7_ubiquitin_linker6.png": render("docs/6cu7_ubiquitin_linker6.png", "--fibril", F6,
                                         "--domain", U),
    "6cu7_ubiquitin_linker30.png": render("docs/6cu7_ubiquitin_linker30.png", "--fibril", F6,
                                          "--domain", U, "--linker", "30"),
    "2n0a_gfp_linker44.png": render("docs/2n0a_gfp_linker44.png", "--fibril", F2, "--domain", G),
    "report_6cu7.png": report_shot,
    "largest_fraction.png": largest_fraction,
    "model/ensemble_projection.png": ensemble_picture("projection.png", "ensemble_projection.png"),
    "model/ensemble_radial_density.png": ensemble_picture("radial_density.png",
                                                          "ensemble_radial_density.png"),
}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", help="picture names, comma-separated (default: all)")
    ap.add_argument("--report-dir", type=pathlib.Path,
                    help="photograph this report of the same command instead of running it")
    ap.add_argument("--list", action="store_true")
    args = ap.parse_args()
    if args.list:
        for name, make in PICTURES.items():
            path = ROOT / "docs" / name
            print(f"docs/{name}: "
                  f"{(picture_stamp.read(path) or 'no stamp') if path.exists() else 'missing'}")
        return
    names = args.only.split(",") if args.only else list(PICTURES)
    unknown = [n for n in names if n not in PICTURES]
    if unknown:
        sys.exit(f"pictures: unknown {unknown}; known: {', '.join(PICTURES)}")
    failed = []
    for name in names:
        try:
            made_by = PICTURES[name](args.report_dir.resolve() if args.report_dir else None)
        except (RuntimeError, subprocess.CalledProcessError, OSError) as e:
            failed.append(name)
            print(f"docs/{name}: not made: {e}", file=sys.stderr)
            continue
        print(f"docs/{name}: {picture_stamp.stamp(ROOT / 'docs' / name, made_by)}", flush=True)
    if failed:
        sys.exit(f"pictures: not made: {', '.join(failed)}")


if __name__ == "__main__":
    main()
