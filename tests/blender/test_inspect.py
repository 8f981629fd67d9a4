"""`headless.py inspect`: measurements printed and written as JSON; every bad input one line,
exit 2, nothing written. No scene needed."""
import gzip
import json

import pytest
from helpers import ROOT, run_cli

DATA = ROOT / "tests" / "data"
KEYS = {"axis", "rise", "rise_sd", "twist", "twist_sd", "protofilaments", "pf_rotation", "pf_rise",
        "layers", "core_residues", "core_outline", "anchors", "tail_residues"}


def test_inspect_writes_json_and_prints(tmp_path):
    out = tmp_path / "m.json"
    proc = run_cli("inspect", "--fibril", str(DATA / "6cu7.pdb.gz"), "--domain",
                   str(DATA / "1ubq.pdb.gz"), "--json", str(out))
    assert proc.returncode == 0, proc.stderr
    assert "left-handed" in proc.stdout and "protofilaments 2" in proc.stdout
    data = json.loads(out.read_text())
    assert KEYS <= set(data["fibril"]) and {"rg", "globule_diameter"} <= set(data["domain"])
    assert data["fibril"]["sha256"] == __import__("hashlib").sha256(
        (DATA / "6cu7.pdb.gz").read_bytes()).hexdigest()
    assert data["model_values"]["globule_diameter"] == data["domain"]["globule_diameter"]
    assert data["model_values"]["twist"] == data["fibril"]["twist"] < 0


def test_inspect_options(ff, capsys, tmp_path):
    out = tmp_path / "n.json"
    assert ff.cli.main(["inspect", "--fibril", str(DATA / "2n0a.pdb.gz"), "--terminus", "N",
                        "--json", str(out)]) == 0
    fib = json.loads(out.read_text())["fibril"]
    assert fib["anchors"][0]["residue"] == 29 and fib["tail_residues"] == [1, 28]
    assert ff.cli.main(["inspect", "--fibril", str(DATA / "6cu7.pdb.gz"), "--anchor-residue",
                        "60", "--json", str(out)]) == 0
    assert [a["residue"] for a in json.loads(out.read_text())["fibril"]["anchors"]] == [60, 60]
    assert ff.cli.main(["inspect", "--domain", str(DATA / "1gfl.pdb.gz"), "--domain-chain", "B",
                        "--domain-residues", "1-230", "--json", str(out)]) == 0
    data = json.loads(out.read_text())
    assert data["fibril"] is None and data["domain"]["chain"] == "B"
    assert data["domain"]["globule_diameter"] == pytest.approx(43.9, abs=0.5)


def _bad_files(tmp_path):
    text = tmp_path / "hello.pdb"
    text.write_text("hello\n")
    junk = tmp_path / "junk.cif"
    junk.write_bytes(bytes(range(256)) * 4)
    water = tmp_path / "water.pdb"
    water.write_text("HETATM    1  O   HOH A   1      10.000  10.000  10.000  1.00 20.00"
                     "           O\nEND\n")
    folder = tmp_path / "folder.pdb"
    folder.mkdir()
    gz = tmp_path / "broken.pdb.gz"
    gz.write_bytes(gzip.compress(b"ATOM")[:10])
    return {"text": text, "junk": junk, "water": water, "folder": folder, "gz": gz}


BAD = [
    (["--fibril", "{tmp}/missing.pdb"], "--fibril", "no such file"),
    (["--fibril", "{folder}"], "--fibril", "no such file"),
    (["--fibril", "{tmp}/x.txt"], "--fibril", ".pdb"),
    (["--fibril", "{text}"], "--fibril", "not a structure"),
    (["--fibril", "{junk}"], "--fibril", "not a readable structure"),
    (["--fibril", "{gz}"], "--fibril", "not a structure"),
    (["--fibril", "{water}"], "--fibril", "no protein chain"),
    (["--fibril", "{data}/1ubq.pdb.gz"], "--fibril", "--rise and --twist"),
    (["--fibril", "{data}/1gfl.pdb.gz"], "--fibril", "do not stack"),
    (["--fibril", "{data}/6cu7.pdb.gz", "--anchor-residue", "5"], "--anchor-residue",
     "not in chain"),
    (["--fibril", "{data}/6cu7.pdb.gz", "--anchor-residue", "K97"], "--anchor-residue",
     "must be a residue number (got 'K97')"),
    (["--fibril", "{data}/6cu7.pdb.gz", "--terminus", "X"], "--terminus", "invalid choice"),
    (["--domain", "{data}/1gfl.pdb.gz", "--domain-chain", "Z"], "--domain-chain", "chains: A, B"),
    (["--domain", "{data}/1ubq.pdb.gz", "--domain-residues", "500-600"], "--domain-residues",
     "no residue"),
    (["--domain", "{data}/1ubq.pdb.gz", "--domain-residues", "ten"], "--domain-residues",
     "a-b"),
    (["--domain", "{text}"], "--domain", "not a structure"),
    ([], "inspect", "--fibril FILE"),
    (["--domain-chain", "A", "--fibril", "{data}/6cu7.pdb.gz"], "--domain-chain", "--domain"),
]


@pytest.mark.parametrize("args, names, says", BAD)
def test_bad_input_one_line_nothing_written(ff, capsys, tmp_path, args, names, says):
    files = _bad_files(tmp_path)
    args = [a.format(tmp=tmp_path, data=DATA, **files) for a in args]
    out = tmp_path / "never.json"
    assert ff.cli.main(["inspect", *args, "--json", str(out)]) == ff.exits.EXIT_USAGE
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("fibrilfit: error: "), captured.err
    assert names in lines[0] and says in lines[0], lines[0]
    assert "Traceback" not in captured.err and captured.out == ""
    assert not out.exists()


def test_bad_input_exit_code_from_the_command_line(tmp_path):
    proc = run_cli("inspect", "--fibril", str(DATA / "1ubq.pdb.gz"), "--json",
                   str(tmp_path / "x.json"))
    assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "x.json").exists()
