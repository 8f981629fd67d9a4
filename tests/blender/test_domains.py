"""Domains as they are (issue #24) in a run: the linker from numbering, several domains."""
import json

import gemmi
from helpers import ROOT

DATA = ROOT / "tests" / "data"
FAST = ["--layers", "3", "--frames", "10"]


def renumbered(tmp_path, shift: int):
    st = gemmi.read_structure(str(DATA / "1ubq.pdb.gz"))
    for ch in st[0]:
        for res in ch:
            res.seqid.num += shift
    out = tmp_path / f"ubq{shift}.pdb"
    st.write_pdb(str(out))
    return out


def test_the_run_takes_the_linker_from_numbering_and_says_so(ff, scene, tmp_path):
    dom, out = renumbered(tmp_path, 127), tmp_path / "r.json"
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--domain", str(dom),
                        *FAST, "--stop-after", "build", "--json", str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["params"]["linker"] == 31 and r["structure"]["applied"]["linker"] == 31
    assert r["structure"]["sources"]["linker"].startswith("numbering: 30 residues between")
    # an explicit --linker wins, and the source says so
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--domain", str(dom),
                        *FAST, "--linker", "5", "--stop-after", "build", "--json",
                        str(out)]) == 0
    r = json.loads(out.read_text())
    assert r["params"]["linker"] == 5 and "linker" in r["structure"]["overridden"]
    assert r["structure"]["sources"]["linker"].startswith("the --linker option")


def test_inspect_says_where_the_linker_comes_from(ff, tmp_path, capsys):
    dom, out = renumbered(tmp_path, 127), tmp_path / "i.json"
    assert ff.cli.main(["inspect", "--fibril", str(DATA / "6cu7.pdb.gz"), "--domain", str(dom),
                        "--json", str(out)]) == 0
    assert "linker: numbering: 30 residues between LYS97" in capsys.readouterr().out
    data = json.loads(out.read_text())
    assert data["model_values"]["linker"] == 31 and "numbering" in data["sources"]["linker"]


def test_a_full_length_model_gives_the_domain_and_its_linker(ff, scene, tmp_path, capsys):
    from helpers import synthetic_full_length
    fl, js = synthetic_full_length(tmp_path), tmp_path / "i.json"
    assert ff.cli.main(["inspect", "--fibril", str(DATA / "6cu7.pdb.gz"), "--full-length",
                        str(fl), "--json", str(js)]) == 0
    data = json.loads(js.read_text())
    assert [(d["first"], d["last"]) for d in data["domains"]] == [(128, 203)]
    assert data["linkers"] == [{"first": 98, "last": 127, "length": 30,
                                "between": ["core 38-97", "domain 128-203"]}]
    assert "linker 98-127: 30 residues" in capsys.readouterr().out
    out, cif = tmp_path / "r.json", tmp_path / "r.cif"
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--full-length", str(fl),
                        *FAST, "--stop-after", "build", "--json", str(out), "--pdb-atoms",
                        str(cif)]) == 0
    r = json.loads(out.read_text())
    assert r["params"]["linker"] == 31  # 30 residues between K97 and 128, plus the anchor
    assert r["params"]["globule_diameter"] == 30.276  # ubiquitin's own coordinates
    assert r["structure"]["full_length"]["domains"][0]["first"] == 128
    st = gemmi.read_structure(str(cif))
    dom = st[0]["0A1"]
    assert (dom[0].seqid.num, dom[len(dom) - 1].seqid.num) == (128, 203)
    core = st[0]["0A"]  # the beads continue the numbering up to the domain
    assert core[len(core) - 1].seqid.num == 127


def test_bad_full_length_models_are_refused_in_one_line(ff, scene, tmp_path, capsys):
    from helpers import synthetic_full_length
    for bad, words in ((synthetic_full_length(tmp_path, flat=True, name="flat.pdb"),
                        "no pLDDT"),
                       (synthetic_full_length(tmp_path, shift=500, name="far.pdb"),
                        "do not cover the fibril's core 38-97")):
        out = tmp_path / "r.json"
        assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--full-length",
                            str(bad), *FAST, "--json", str(out)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and err[0].startswith("fibrilfit: error: --full-length: ")
        assert words in err[0] and not out.exists()
