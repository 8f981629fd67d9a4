"""What `inspect` reads of the deposited set (issue #47 item 7,
docs/guide/structures.md#read-survey): short-peptide fibrils, protofilaments that are not copies
of each other (the one screw of every layer), side contacts between protofilaments, chains of
several kinds; and tools/read_survey.py. Files: tests/data/README.md "Reading the deposited set".
"""
import csv
import importlib.util
import math
import pathlib
import re
import shutil
import types

import numpy as np
import pytest

from helpers import ROOT
from fibrilfit.api import inspect
from fibrilfit.structure import chain_kinds, fibril as F, one_screw, reading, side_contacts
from fibrilfit.structure.errors import StructureError

import gemmi  # noqa: E402 (requirements-dev installs it)
DATA = ROOT / "tests" / "data"
PEPTIDE, NOT_COPIES, MISSES = (str(DATA / f"{n}.pdb.gz") for n in ("2m5n", "7m61", "9cz3"))

PAGE, SURVEY = ROOT / "docs" / "guide" / "structures.md", ROOT / "docs" / "read_survey.csv"

spec = importlib.util.spec_from_file_location("read_survey", ROOT / "tools" / "read_survey.py")
read_survey = importlib.util.module_from_spec(spec)
spec.loader.exec_module(read_survey)


def test_a_short_peptide_fibril_is_read_with_its_axis_through_the_core():
    """2M5N: 20 chains of TTR(105-115), 11 residues each (none of 20): read as two protofilaments
    of 10 layers. The one screw of its layers turns 0.7° a layer about an axis 127 Å from the
    core: the axis is taken along the layers' mean step through the core, and the anchors lie
    within the core's 24 Å (on the screw's axis they were 121-128 Å out)."""
    fib = inspect(fibril=PEPTIDE).data["fibril"]
    assert any("short-peptide fibril (chains of 6 residues or more)" in n for n in fib["notes"])
    assert (fib["protofilaments"], fib["layers"], fib["core_residues"]) == (2, 10, [105, 115])
    assert fib["rise"] == pytest.approx(4.658, abs=0.01)  # the CA steps are 4.64-4.68 Å
    assert not fib["axis_exact"]
    warning = next(w for w in fib["warnings"] if "not copies" in w)
    away, held = map(float, re.search(r"axis ([\d.]+) Å from the core's centroid, outside the "
                                      r"([\d.]+) Å", warning).groups())
    assert away > held
    assert all(a["radius"] < held for a in fib["anchors"])


def test_short_chains_that_do_not_stack_are_not_a_fibril(tmp_path):
    """The lower minimum reads chains of 6-19 residues only as a fibril, and only if they stack:
    2M5N's chains pulled 15 Å apart are refused; as a domain file, 20 residues still hold."""
    st = gemmi.read_structure(PEPTIDE)
    for k, chain in enumerate(st[0]):
        for res in chain:
            for atom in res:
                atom.pos = gemmi.Position(atom.pos.x + 15.0 * k, atom.pos.y, atom.pos.z)
    apart = tmp_path / "apart.pdb"
    st.write_pdb(str(apart))
    with pytest.raises(StructureError, match=r"no two chains stack 4.2-5.6 Å apart"):
        F.measure(apart)
    with pytest.raises(StructureError, match=r"no protein chain of at least 20 residues"):
        reading.load(PEPTIDE, "--domain")


def test_protofilaments_that_are_not_copies_are_read_on_the_one_screw_of_every_layer():
    """7M61: the screws from a chain of protofilament 0 onto its neighbour in protofilament 1
    differ by up to 10.9° and 18.1 Å from layer to layer (the protofilaments are not copies),
    but one screw takes every layer onto the next within 0.00 Å: read on it, and said."""
    fib = inspect(fibril=NOT_COPIES).data["fibril"]
    warning = next(w for w in fib["warnings"] if "not copies" in w)
    degrees, angstroms, miss = map(float, re.search(
        r"differ by up to ([\d.]+)° and ([\d.]+) Å\): the axis is the one screw that takes every "
        r"layer onto the next, within ([\d.]+) Å", warning).groups())
    assert degrees > F.MAX_AXIS_SPREAD[0] and miss <= one_screw.EXACT
    assert fib["axis_exact"] and fib["protofilaments"] == 2 and fib["layers"] == 10
    assert fib["rise"] == pytest.approx(4.81, abs=0.005)
    assert math.degrees(fib["twist"]) == pytest.approx(-2.94, abs=0.01)
    assert fib["rise_sd"] < 0.001  # every layer pair on the one screw


def test_layers_that_miss_the_one_screw_are_refused_with_the_miss(monkeypatch):
    """9CZ3 (6-residue chains, 3 protofilaments): one screw's copies miss protofilament U-d's
    layers by 1.79 Å CA RMSD: refused, saying so. The limit is what refuses it: at 2 Å it
    reads."""
    with pytest.raises(StructureError) as err:
        inspect(fibril=MISSES)
    message = str(err.value)
    assert "nor does one screw take every layer onto the next" in message
    assert re.search(r"miss the file's layers by up to 1\.79 Å CA RMSD \(the protofilament of "
                     r"chains U-d; the others within 1\.41 Å; at most 1 Å read\)", message)
    monkeypatch.setattr(one_screw, "MAX_DEVIATION", 2.0)
    assert inspect(fibril=MISSES).data["fibril"]["protofilaments"] == 3


def _chain(name, first, last):
    return types.SimpleNamespace(name=name, residues=np.arange(first, last + 1))


def test_chains_of_two_kinds_are_named_in_the_refusal():
    """Chains that share no residue numbers (9FOF's TDP-43 282-345 and annexin A11 39-74) are
    refused naming each kind, its residues and its chains."""
    chains = [_chain(n, 282, 345) for n in "ACE"] + [_chain(n, 39, 74) for n in "BDFHJ"]
    with pytest.raises(StructureError) as err:
        F._stacking(chains, "x.pdb", "--fibril")
    assert str(err.value) == (
        "--fibril: x.pdb: the chains share 0 residue numbers: they are of 2 kinds (residues "
        "39-74: 5 chains, B, D, F, H, …; residues 282-345: 3 chains, A, C, E): a heteromeric "
        "fibril, or one molecule's segments in separate chains; FibrilFit reads a fibril of "
        "one kind of chain")
    assert chain_kinds.why(chains[:3], 2) == ("the chains share 2 residue numbers: the layers "
                                              "do not stack")


def _stack(n):
    return np.ones(n, bool)


def test_side_contacts_between_protofilaments_are_dropped_or_the_file_refused():
    """Two protofilaments of three layers (0-1-2, 3-4-5) stacked over 21 residues; chain 1 also
    over 5 residues of chain 4 (9KZO's 5-7 beside 21): a side contact, dropped and noted. Over 15
    it is not clearly weaker: refused, naming the chain and its partners. No chain with more
    than two partners: left as it is."""
    layers = {(0, 1): _stack(21), (1, 2): _stack(21), (3, 4): _stack(21), (4, 5): _stack(21)}
    names = list("ABCDEF")
    assert side_contacts.layers_only(layers, names, "x", "--fibril", []) is layers
    notes = []
    kept = side_contacts.layers_only({**layers, (1, 4): _stack(5)}, names, "x", "--fibril",
                                     notes)
    assert kept == layers
    assert notes == ["1 contacts between protofilaments side by side, over 5 residues or fewer "
                     "(same-numbered CA 4.2-5.6 Å apart), are not layers: dropped"]
    with pytest.raises(StructureError, match=r"chain B stacks on more than two others, A \(21 "
                                             r"residues\), C \(21 residues\), E \(15 residues\)"):
        side_contacts.layers_only({**layers, (1, 4): _stack(15)}, names, "x", "--fibril", [])


def test_the_read_survey_tool_writes_each_file_and_groups_the_reasons(tmp_path, capsys):
    """tools/read_survey.py over the three files: a row each, read or refused with its one line,
    and the summary's counts."""
    for f in (PEPTIDE, NOT_COPIES, MISSES):
        shutil.copy(f, tmp_path)
    out = tmp_path / "survey.csv"
    assert read_survey.main([str(tmp_path), "--csv", str(out)]) == 0
    rows = {r["file"]: r for r in csv.DictReader(open(out))}
    assert {f: r["read"] for f, r in rows.items()} == {
        "2m5n.pdb.gz": "read", "7m61.pdb.gz": "read", "9cz3.pdb.gz": "refused"}
    assert (rows["7m61.pdb.gz"]["chains"], rows["7m61.pdb.gz"]["core_residues"]) == ("20", "28-48")
    assert "1.79 Å" in rows["9cz3.pdb.gz"]["reason"]
    printed = capsys.readouterr().out
    assert "read 2 (66.7 %), refused 1" in printed
    assert re.search(r"\| refused \| the protofilaments share no common axis \| 1 \| 9CZ3 \|",
                     printed)


def test_the_read_survey_page_agrees_with_its_csv_and_todays_code():
    """docs/guide/structures.md#read-survey: its counts and its table are those of
    docs/read_survey.csv (grouped as the tool groups them), and today's `inspect` reads the
    three files copied here (2M5N, 7M61, 9CZ3: the set's own bytes) as that CSV says, with the
    same reason, chains, layers, protofilaments and core."""
    text = PAGE.read_text()
    start = text.index("{#read-survey}")
    section = text[start:text.index("\n### ", start)]
    rows = list(csv.DictReader(open(SURVEY)))
    n, read = len(rows), sum(r["read"] == "read" for r in rows)
    assert f"`inspect` over {n} files" in section
    assert f"read {read} ({100 * read / n:.1f} %), refused {n - read}" in section
    table = [(o, k, int(c)) for o, k, c in
             re.findall(r"^\| (read|refused) \| (.+?) \| (\d+) \|", section, re.M)]
    assert table == [(o, k, len(files)) for o, k, files in read_survey.groups(rows)]
    for path in (PEPTIDE, NOT_COPIES, MISSES):
        name = pathlib.Path(path).name.removesuffix(".gz")
        page = next(r for r in rows if r["file"] == name)
        today = {k: str(v).replace(".pdb.gz", ".pdb")
                 for k, v in read_survey.read_file(pathlib.Path(path), 120).items()}
        assert {k: today[k] for k in read_survey.COLUMNS if k not in ("file", "seconds")} == \
               {k: page[k] for k in read_survey.COLUMNS if k not in ("file", "seconds")}
