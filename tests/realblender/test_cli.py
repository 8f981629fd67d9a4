"""`blender -b -c fibrilfit ...` with the real Blender 4.3.2 and the installed zip: the same
verdicts as the bpy module for the same seeds, and bad options refused with one line, exit 2."""
import csv
import json

import pytest

from realblender.helpers import OUT, chroot, inside, module, own_lines, quote, read_json

# Small cases: the default model, a short linker that cannot fit, two protofilaments, inflate.
CASES = {
    "default": ["--layers", "20", "--linker", "6"],
    "short-linker": ["--layers", "8", "--linker", "2", "--seed", "3"],
    "two-protofilaments": ["--layers", "6", "--protofilaments", "2", "--linker", "8",
                           "--pf-rise", "2.4", "--seed", "1"],
    "inflate": ["--layers", "6", "--linker", "6", "--protocol", "inflate", "--seed", "2",
                "--regrow-cycles", "1"],
}
COMPARED = ("verdict", "accommodated", "linker_intact")


def both_run(name, args):
    real, ref = OUT / f"run-{name}-blender.json", OUT / f"run-{name}-module.json"
    cp = chroot(f"blender -b -c fibrilfit run {quote(args)} --json {inside(real)}")
    assert cp.returncode == 0, cp.stdout[-2000:] + cp.stderr[-2000:]
    cp_ref = module(["run", *args, "--json", str(ref)])
    assert cp_ref.returncode == 0, cp_ref.stderr[-2000:]
    return read_json(real), read_json(ref)


@pytest.mark.parametrize("name", CASES)
def test_run_gives_the_bpy_modules_verdict(installed, name):
    real, ref = both_run(name, CASES[name])
    assert real["blender_version"] == "4.3.2" and ref["blender_version"] != "4.3.2"
    assert real["params"] == ref["params"] and real["gravity"] == ref["gravity"]
    assert {k: real[k] for k in COMPARED} == {k: ref[k] for k in COMPARED}
    assert len(real["clashing_pairs"]) == len(ref["clashing_pairs"])


def test_inspect_reads_structures_with_the_bundled_gemmi(installed):
    args = ["inspect", "--fibril", "tests/data/6cu7.pdb.gz", "--domain", "tests/data/1ubq.pdb.gz"]
    real, ref = OUT / "inspect-blender.json", OUT / "inspect-module.json"
    cp = chroot(f"blender -b -c fibrilfit {quote(args)} --json {inside(real)}")
    assert cp.returncode == 0, cp.stdout[-2000:] + cp.stderr[-2000:]
    assert module([*args, "--json", str(ref)]).returncode == 0
    a, b = read_json(real), read_json(ref)
    for d in (a, b):  # where the files were read from differs (/fibrilfit/... in the chroot)
        d.pop("blender_version", None)
        d.pop("fibrilfit_version", None)
    assert json.dumps(a, sort_keys=True).replace("/fibrilfit/", "") == \
        json.dumps(b, sort_keys=True).replace(str(OUT.parents[1]) + "/", "")


def test_sweep_runs_workers_on_the_real_blender(installed):
    # with its plot: the zip bundles tqdm and matplotlib (docs/guide/install.md#which-zip)
    args = ["sweep", "--linker", "2,6", "--layers", "8", "--seeds", "2", "--workers", "2",
            "--quiet"]
    real, ref = OUT / "sweep-blender", OUT / "sweep-module"
    cp = chroot(f"rm -rf {inside(real)} && blender -b -c fibrilfit {quote(args)} "
                f"--out {inside(real)}")
    assert cp.returncode == 0, cp.stdout[-2000:] + cp.stderr[-2000:]
    assert module([*args, "--out", str(ref)]).returncode == 0

    def verdicts(folder):
        rows = [json.loads(ln) for ln in (folder / "results.jsonl").read_text().splitlines()]
        return sorted((r["params"]["linker"], r["params"]["seed"], r["blender_version"] == "4.3.2",
                       r["verdict"], r["accommodated"]) for r in rows)

    got, want = verdicts(real), verdicts(ref)
    assert (real / "phase.png").is_file()  # drawn by the zip's matplotlib
    assert len(got) == 4 and all(r[2] for r in got) and not any(r[2] for r in want)
    assert [r[:2] + r[3:] for r in got] == [r[:2] + r[3:] for r in want]


def test_minimal_linker_agrees(installed):
    args = ["minimal-linker", "--globule-diameter", "20", "--layers", "8", "--restarts", "2",
            "--max-linker", "8", "--quiet", "--no-plot"]
    real, ref = OUT / "minimal-blender", OUT / "minimal-module"
    cp = chroot(f"rm -rf {inside(real)} && blender -b -c fibrilfit {quote(args)} "
                f"--out {inside(real)}")
    assert cp.returncode == 0, cp.stdout[-2000:] + cp.stderr[-2000:]
    assert module([*args, "--out", str(ref)]).returncode == 0

    def table(folder):
        with open(folder / "minimal_linker.csv", newline="") as f:
            return [(r["globule_diameter"], r["minimal_linker"], r["p_fit"])
                    for r in csv.DictReader(f)]

    assert table(real) == table(ref) and table(real)


@pytest.mark.parametrize("args", [
    ["run", "--linker", "-3"],
    ["run", "--globule-diameter", "abc"],
    ["run", "--no-such-option"],
    ["sweep", "--linker", "0,4"],
    ["inspect", "--fibril", "no/such/file.pdb"],
])
def test_bad_options_exit_2_with_one_line(installed, args):
    cp = chroot(f"blender -b -c fibrilfit {quote(args)}")
    lines = own_lines(cp.stderr)
    assert cp.returncode == 2, (cp.returncode, cp.stderr)
    assert len(lines) == 1 and "Traceback" not in cp.stderr + cp.stdout, cp.stderr
    ref = module(args)
    assert ref.returncode == 2 and own_lines(ref.stderr) == lines  # the same words
