"""`--pdb-atoms FILE.cif`: the decorated fibril in atoms (issue #24)."""
import importlib
import json

import gemmi  # requirements-dev installs it: missing, this fails (never skips)
import numpy as np
import pytest
from helpers import ROOT

DATA = ROOT / "tests" / "data"
FAST = ["--layers", "3", "--frames", "30"]


def _pairwise(xyz):
    return np.linalg.norm(xyz[:, None] - xyz[None], axis=-1)


def _heavy(chain):
    return np.array([a.pos.tolist() for r in chain for a in r if not a.is_hydrogen()])


def test_the_decorated_fibril_reads_back_and_keeps_every_domain_rigid(ff, scene, tmp_path):
    out = tmp_path / "fibril.cif"
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), "--domain",
                        str(DATA / "1ubq.pdb.gz"), *FAST, "--pdb-atoms", str(out),
                        "--json", str(tmp_path / "r.json")]) == 0
    st = gemmi.read_structure(str(out))
    model = st[0]
    fib = importlib.import_module("fibrilfit.structure").measure_fibril(DATA / "6cu7.pdb.gz")
    chains = 3 * fib.protofilaments
    assert len(model) == 2 * chains  # (layer, protofilament) and its domain
    assert "linker" in st.info["_struct.title"]
    # every placed ubiquitin has the input's interatomic distances: a rigid transform
    ref = gemmi.read_structure(str(DATA / "1ubq.pdb.gz"))
    ref.remove_hydrogens()
    ref.remove_ligands_and_waters()
    want = _pairwise(_heavy(ref[0][0]))
    domains = [ch for ch in model if len(ch.name) == 3]
    assert len(domains) == chains
    for ch in domains:
        got = _pairwise(_heavy(ch))
        assert got.shape == want.shape
        assert np.abs(got - want).max() < 0.005  # 3 decimals in the file
    # and none of them is the input itself: they were moved
    assert not np.allclose(_heavy(domains[0]), _heavy(ref[0][0]), atol=1.0)
    # the core: each chain ends at the anchor K97, then the linker's beads, CA only
    core = model["0A"]
    numbers = [r.seqid.num for r in core]
    names = [r.name for r in core]
    anchor = numbers.index(fib.anchors[0]["residue"])
    assert names[anchor] == "LYS" and set(names[anchor + 1:]) == {"UNK"}
    linker = json.loads((tmp_path / "r.json").read_text())["params"]["linker"]
    assert numbers[anchor + 1:] == list(range(98, 98 + linker - 1))  # linker counts the anchor
    assert all(len(r) == 1 and r[0].name == "CA" for r in core[anchor + 1:])


def test_the_core_chains_stack_as_deposited(ff, scene, tmp_path):
    """Every written core chain superimposes on a deposited chain of 6CU7 (in the model's
    frame) within 1 Å: the stack is the file's, layer by layer."""
    S = importlib.import_module("fibrilfit.structure")
    fibril = importlib.import_module("fibrilfit.structure.fibril")
    out = tmp_path / "fibril.cif"
    assert ff.cli.main(["run", "--fibril", str(DATA / "6cu7.pdb.gz"), *FAST, "--stop-after",
                        "build", "--pdb-atoms", str(out)]) == 0
    fib = S.measure_fibril(DATA / "6cu7.pdb.gz")
    origin, frame = fibril.layer_frame(fib)
    deposited = {}
    loaded = S.reading.load(DATA / "6cu7.pdb.gz")
    for c in loaded.chains:  # CA per residue in the model's frame
        deposited[c.name] = dict(zip(c.residues.tolist(), (c.ca - origin) @ frame.T))
    st = gemmi.read_structure(str(out))
    matched = 0
    for ch in st[0]:
        if len(ch.name) != 2:
            continue
        ca = {n: np.array(r.find_atom("CA", "*").pos.tolist()) for r in ch for n in
              [r.seqid.num] if r.name != "UNK"}
        best = min(np.sqrt(np.mean([np.sum((ca[n] - dep[n]) ** 2) for n in ca if n in dep]))
                   for dep in deposited.values())
        matched += best < 1.0
    # layers 0..2 of the model are the file's reference layer and the two above it (0.14 Å)
    assert matched == 3 * fib.protofilaments
    # the globule without a file: one pseudo-atom per chain
    assert sum(1 for ch in st[0] if len(ch.name) == 3) == 3 * fib.protofilaments


def test_pdb_atoms_without_a_structure_is_refused(ff, scene, tmp_path, capsys):
    out = tmp_path / "x.cif"
    assert ff.cli.main(["run", *FAST, "--pdb-atoms", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--pdb-atoms" in err[0] and "--fibril" in err[0]
    assert not out.exists()
    assert ff.cli.main(["run", "--domain", str(DATA / "1ubq.pdb.gz"), *FAST,
                        "--pdb-atoms", str(tmp_path / "x.pdb")]) == 2
    assert not (tmp_path / "x.pdb").exists()


@pytest.mark.one_bpy
def test_the_helical_assembly_of_a_periodic_cell_expands_seamlessly(ff, scene, tmp_path, capsys):
    """`--pdb-atoms --pdb-assembly 2` on a built cell of 8A9L (one protofilament) + ubiquitin:
    gemmi expands assembly 1 to 5 cells, and across every seam the core goes on one layer at a
    time (layer 0 of a copy is one layer above the top layer of the copy below). The expansion
    against the whole fibril atom by atom: tests/unit/test_helical_assembly.py."""
    out, cells, M = tmp_path / "cell.cif", 2, 10
    assert ff.cli.main(["run", "--fibril", str(DATA / "8a9l.pdb.gz"), "--domain",
                        str(DATA / "1ubq.pdb.gz"), "--periodic", str(M), "--stop-after", "build",
                        "--pdb-atoms", str(out), "--pdb-assembly", str(cells),
                        "--json", str(tmp_path / "r.json")]) == 0
    result = json.loads((tmp_path / "r.json").read_text())
    info = result["pdb_atoms"]["assembly"]
    assert info["operators"] == 2 * cells + 1 and info["image_cells"] == [-1, -2, 1, 2]
    st = gemmi.read_structure(str(out))
    n = len(st[0])
    assert n == 2 * M  # the cell: a core chain and a domain chain per layer
    whole = gemmi.make_assembly(st.assemblies[0], st[0], gemmi.HowToNameCopiedChain.Dup)
    assert len(whole) == info["chains"] == (2 * cells + 1) * n
    assert sum(1 for _ in whole.all()) == info["atoms"] == (2 * cells + 1) * sum(
        1 for _ in st[0].all())
    p = result["params"]
    a, h = p["twist"], p["rise"]
    one_layer = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])

    def core(copy: int, layer: int):
        chain = whole[copy * n + 2 * layer]  # copies in operator order: the cell, S^-1, S^-2, ...
        assert chain.name == f"{layer}A"
        return np.array([at.pos.tolist() for r in chain for at in r if r.name != "UNK"])

    order, z = [0, *info["image_cells"]], {}
    for copy, m in enumerate(order):
        z[m] = core(copy, 0)[:, 2].mean()
        if m > -cells:  # this copy's layer 0 over the top layer of the copy below it
            step = core(copy, 0) - (core(order.index(m - 1), M - 1) @ one_layer.T + [0, 0, h])
            assert np.abs(step).max() < 2e-3, m
    assert np.allclose(np.diff([z[m] for m in sorted(z)]), M * h, atol=1e-3)
    # a fibril with ends has no helical assembly: refused before anything runs
    capsys.readouterr()
    assert ff.cli.main(["run", "--fibril", str(DATA / "8a9l.pdb.gz"), "--layers", "3",
                        "--pdb-atoms", str(tmp_path / "ends.cif"), "--pdb-assembly", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--pdb-assembly: only with --periodic" in err[0]
    assert not (tmp_path / "ends.cif").exists()
