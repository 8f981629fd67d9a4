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
