"""Case files: load, save, round trip, options that win, and refusals naming the key."""
import json

import pytest
from helpers import ROOT, cli_in_process, run_cli

from fibrilfit.model import cases, params as P
from fibrilfit import pipeline

SMALL = {"layers": 6, "linker": 4, "globule_diameter": 20.0, "frames": 40, "seed": 3}


def write(path, text: str):
    path.write_text(text, encoding="utf-8")
    return path


def same_run(result: dict) -> dict:
    return {k: v for k, v in result.items() if k not in ("timings_s", "case")}


def test_a_case_round_trips_to_the_same_parameters_and_result(scene, tmp_path):
    case = cases.from_dict({"name": "small", "doi": "10.1/x", "expected": "fits",
                            "estimates": ["globule_diameter"], "seeds": [3, 4],
                            "params": {**SMALL, "twist": -0.0843, "slab": [38.5, 20, 4.8]}})
    p = case.make_params()
    first = pipeline.run_model(p, scene)
    path = cases.write(tmp_path / "saved.toml", case.resolved(p))
    again = cases.load(path)
    assert again.make_params() == p
    assert again.meta == case.meta and again.seeds == [3, 4]
    assert again.sha256 and again.path == path
    assert same_run(pipeline.run_model(again.make_params(), scene)) == same_run(first)


def test_cli_options_beside_the_case_win(tmp_path):
    case = write(tmp_path / "c.toml", 'name = "c"\n[params]\nlinker = 4\nlayers = 6\n'
                                      'twist = -0.03\n')
    out = tmp_path / "r.json"
    cp = run_cli("run", "--case", str(case), "--linker", "7", "--stop-after", "build",
                 "--json", str(out), "--save-case", str(tmp_path / "s.toml"))
    assert cp.returncode == 0, cp.stderr
    r = json.loads(out.read_text())
    assert (r["params"]["linker"], r["params"]["layers"], r["params"]["twist"]) == (7, 6, -0.03)
    assert r["case"]["name"] == "c" and r["case"]["overridden"] == ["linker"]
    assert r["case"]["params"] == r["params"] and r["case"]["file"] == str(case)
    assert "case: c; set on the command line: linker" in cp.stdout
    saved = cases.load(tmp_path / "s.toml")
    assert saved.make_params() == P.make_params(**r["params"]) and saved.meta == {"name": "c"}


def test_a_run_without_a_case_embeds_none(tmp_path):
    out = tmp_path / "r.json"
    cp = run_cli("run", "--layers", "3", "--stop-after", "build", "--json", str(out))
    assert cp.returncode == 0, cp.stderr
    assert "case" not in json.loads(out.read_text())


@pytest.mark.parametrize("text, says", [
    ('colour = "red"\n', "c.toml: colour: unknown key"),
    ("[params]\nlinkr = 4\n", "c.toml: params.linkr: unknown parameter"),
    ("[params]\nlinker = 0\n", "c.toml: params.linker: must be an integer from 1 to 200"),
    ('[params]\nlinker = "6"\n', "c.toml: params.linker: must be a number, not str"),
    ("[params]\nsettle = 1\n", "c.toml: params.settle: must be true or false"),
    ("[params]\nslab = 40\n", "c.toml: params.slab: must be an array"),
    ("[params]\nslab = [40, 22]\n", "c.toml: params.slab: must be three sizes"),
    ("[params]\nlayers = 10\nscore_layers = 5\n", "c.toml: params.score_layers: must leave"),
    ('expected = "maybe"\n', "c.toml: expected: must be one of fits, does not fit, unknown"),
    ("envelope_width = -3\n", "c.toml: envelope_width: must be a positive number"),
    ('estimates = ["linkr"]\n', "c.toml: estimates: 'linkr' is not a parameter"),
    ("seeds = [1, -2]\n", "c.toml: seeds: must be a non-empty list of integers"),
    ("params = 3\n", "c.toml: params: must be a table"),
    ("linker = = 4\n", "is not valid TOML"),
])
def test_bad_cases_exit_2_with_one_line_naming_the_key(tmp_path, text, says):
    case = write(tmp_path / "c.toml", text)
    out = tmp_path / "r.json"
    cp = cli_in_process("run", "--case", str(case), "--json", str(out))
    assert cp.returncode == 2, cp.stdout
    assert cp.stderr.count("\n") == 1 and says in cp.stderr, cp.stderr
    assert "Traceback" not in cp.stderr and not out.exists()


def test_a_missing_or_misnamed_case_is_refused(tmp_path):
    for path, says in ((tmp_path / "none.toml", "--case: cannot read"),
                       (write(tmp_path / "c.json", "{}"), "--case: must be a .toml file")):
        cp = cli_in_process("run", "--case", str(path))
        assert cp.returncode == 2 and says in cp.stderr and cp.stderr.count("\n") == 1


def test_sweep_takes_the_case_and_its_seeds(tmp_path):
    case = write(tmp_path / "c.toml", 'name = "s"\nseeds = [1, 2]\n[params]\nlayers = 4\n'
                                      "linker = 3\nframes = 30\nseed = 9\n")
    out = tmp_path / "sw"
    cp = run_cli("sweep", "--case", str(case), "--linker", "3,5", "--workers", "1", "--out",
                 str(out), "--quiet", "--no-plot")
    assert cp.returncode == 0, cp.stderr
    records = [json.loads(line) for line in (out / "results.jsonl").read_text().splitlines()]
    assert sorted((r["params"]["linker"], r["seed"]) for r in records) == [
        (3, 1), (3, 2), (5, 1), (5, 2)]
    assert all(r["params"]["layers"] == 4 and r["case"]["name"] == "s"
               and r["case"]["params"] == r["params"] and r["case"]["overridden"] == ["linker"]
               for r in records)
    head, *rows = (out / "summary.csv").read_text().splitlines()
    assert head.endswith("outer_diameter_median,outer_diameter_min,outer_diameter_max,protocol")
    assert len(rows) == 2 and all(float(row.split(",")[-4]) > 0 for row in rows)


def test_sweep_seed_options_beat_the_case_seeds(tmp_path):
    case = write(tmp_path / "c.toml", "seeds = [1, 2]\n[params]\nlayers = 3\nframes = 20\n")
    out = tmp_path / "sw"
    cp = run_cli("sweep", "--case", str(case), "--seeds", "1", "--workers", "1", "--out",
                 str(out), "--quiet", "--no-plot")
    assert cp.returncode == 0, cp.stderr
    (record,) = [json.loads(x) for x in (out / "results.jsonl").read_text().splitlines()]
    assert record["seed"] == 0


def test_outline_and_protofilaments_from_a_case(tmp_path):
    """A core outline as a file next to the case (recorded with its sha256) or inline; an
    anchor and two protofilaments; the saved case holds the points inline."""
    (tmp_path / "data").mkdir()
    square = [[-20, -12], [20, -12], [20, 12], [-20, 12]]
    (tmp_path / "data" / "core.json").write_text(json.dumps(square))
    case = write(tmp_path / "c.toml", '[params]\ncore_outline = "data/core.json"\n'
                                      "anchor = [24.0, 3.0]\nprotofilaments = 2\nlayers = 3\n"
                                      "linker = 3\n")
    out = tmp_path / "r.json"
    cp = run_cli("run", "--case", str(case), "--stop-after", "build", "--json", str(out),
                 "--save-case", str(tmp_path / "s.toml"))
    assert cp.returncode == 0, cp.stderr
    r = json.loads(out.read_text())
    assert r["params"]["core_outline"] == square and r["params"]["protofilaments"] == 2
    assert r["params"]["anchor"] == [24.0, 3.0]
    record = r["case"]["files"]["core_outline"]
    assert record["path"] == "data/core.json" and len(record["sha256"]) == 64
    inline = cases.load(tmp_path / "s.toml")
    assert inline.params["core_outline"] == square
    assert inline.make_params() == P.make_params(**r["params"])
    bad = write(tmp_path / "b.toml", '[params]\ncore_outline = "missing.json"\n')
    cp = run_cli("run", "--case", str(bad))
    assert cp.returncode == 2 and "b.toml: params.core_outline: no file 'missing.json'" in cp.stderr


def test_structure_files_from_a_case(tmp_path):
    """[structure] files are relative to the case, recorded with their sha256; measured values
    fill what the case leaves unset; an option beside the case wins; a saved case points to the
    same files from wherever it is saved."""
    import hashlib
    import os
    data = ROOT / "tests" / "data"
    rel = os.path.relpath(data / "2beg_model1.pdb.gz", tmp_path)
    case = write(tmp_path / "c.toml", f'[params]\nlinker = 3\nlayers = 4\n[structure]\n'
                                      f'fibril = "{rel}"\nterminus = "C"\n')
    out, saved = tmp_path / "r.json", tmp_path / "sub" / "s.toml"
    cp = run_cli("run", "--case", str(case), "--terminus", "N", "--stop-after", "build",
                 "--json", str(out), "--save-case", str(saved))
    assert cp.returncode == 0, cp.stderr
    r = json.loads(out.read_text())
    record = r["case"]["files"]["fibril"]
    assert record["path"] == rel
    assert record["sha256"] == hashlib.sha256((data / "2beg_model1.pdb.gz").read_bytes()).hexdigest()
    assert r["case"]["structure"]["terminus"] == "N" and "terminus" in r["case"]["overridden"]
    assert r["params"]["rise"] != P.DEFAULTS.rise  # measured from the file
    again = cases.load(saved)
    assert again.structure["fibril"] == str((data / "2beg_model1.pdb.gz").resolve())
    assert again.make_params() == P.make_params(**r["params"])


@pytest.mark.parametrize("text, says", [
    ("[structure]\nfibrl = 'x.pdb'\n", "c.toml: structure.fibrl: unknown key"),
    ("[structure]\nfibril = 'nothere.pdb'\n", "c.toml: structure.fibril: no file 'nothere.pdb'"),
    ("[structure]\nterminus = 'X'\n", "c.toml: structure.terminus: must be one of N, C"),
])
def test_bad_structure_tables(tmp_path, text, says):
    case = write(tmp_path / "c.toml", text)
    cp = cli_in_process("run", "--case", str(case))
    assert cp.returncode == 2 and says in cp.stderr and cp.stderr.count("\n") == 1, cp.stderr


