"""`--pdb-assembly N` (issue #48, item 5): the periodic cell written once with a helical assembly,
a flat list of screw operators, read back with gemmi and expanded to the whole fibril.

The oracle is the whole fibril of 2N + 1 cells written the default way (no assembly): a fibril
with ends of (2N + 1)·M layers whose core chains are placed by its own layer transforms, and whose
beads and domains (what the physics moves) are the cell's, carried up by a screw this file
computes with its own trigonometry. docs/guide/atoms-and-domains.md#helical-assembly
"""
import re

import gemmi  # requirements-dev installs it: missing, this fails (never skips)
import numpy as np
import pytest
from helpers import ROOT
from scipy.spatial.transform import Rotation

from fibrilfit import structure as S
from fibrilfit.exports import mmcif
from fibrilfit.exports.plans import OutputPlan
from fibrilfit.model import occupancy, params as P
from fibrilfit.plans import PlanError
from fibrilfit.structure import atoms as A

DATA = ROOT / "tests" / "data"
CELLS = 2  # the cell and its images in 2 cells below and above: 5 cells
M = 8


def _screw(p, n: int) -> np.ndarray:
    """The test's own S^n: turn n·M·twist about Z, raise n·M·rise (4 × 4, column vectors)."""
    a, h = n * p.periodic * p.twist, n * p.periodic * p.rise
    t = np.eye(4)
    t[:2, :2] = [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]
    t[2, 3] = h
    return t


def _moved(t: np.ndarray, xyz: np.ndarray) -> np.ndarray:
    return xyz @ t[:3, :3].T + t[:3, 3]


@pytest.fixture(scope="module", params=["8a9l", "6cu7", "6cu7 mixed"])
def case(request):
    """A periodic cell on a deposited core (8A9L: one protofilament; 6CU7: two; mixed: every
    other subunit decorated, the rest bare core chains) with ubiquitin on the decorated chains,
    beads and globules placed at random (what the bake would have left)."""
    name, *mixed = request.param.split()
    geometry = S.measure_fibril(DATA / f"{name}.pdb.gz")
    values = {k: v for k, v in S.model_values(geometry).items() if k != "linker"}
    pattern = {"pattern": "periodic", "pattern_period": 2} if mixed else {}
    p = P.make_params(periodic=M, linker=4, **values, **pattern)
    ubq = A.domain_atoms(DATA / "1ubq.pdb.gz")
    sources = A.sources(DATA / f"{name}.pdb.gz", geometry, [ubq])
    rng = np.random.default_rng(11)
    n = len(occupancy.decorated_chains(p))
    assert n == (p.chains // 2 if mixed else p.chains)
    mats = np.tile(np.eye(4), (n, 1, 1))
    mats[:, :3, :3] = Rotation.random(n, random_state=rng).as_matrix()
    mats[:, :3, 3] = rng.normal(size=(n, 3)) * 30 + [60, 0, 0]
    mats[:, 2, 3] += np.linspace(0, p.periodic * p.rise, n, endpoint=False)  # up the cell
    positions = rng.normal(size=(n, p.linker + 1, 3)) * 5 + [40, 0, 0]
    return p, sources, positions, mats


def _whole(p, sources, positions, mats, tmp_path):
    """The oracle: the fibril of 2·CELLS + 1 cells written whole (the default form), in the frame
    of the cell's lowest image (its layer 0 is the cell's image S^-CELLS)."""
    cells = 2 * CELLS + 1
    q = P.make_params(**{**p.to_dict(), "periodic": 0, "layers": cells * p.periodic})
    up = [_screw(p, c) for c in range(cells)]  # chain c + c_cell·n is chain c moved by S^c_cell
    pos = np.concatenate([_moved(t, positions) for t in up])
    mat = np.concatenate([np.einsum("ij,njk->nik", t, mats) for t in up])
    assert q.chains == cells * p.chains
    cell = occupancy.decorated_chains(p)  # a mixed fibril: the cell's pattern, cell by cell
    assert np.array_equal(occupancy.decorated_chains(q),
                          np.concatenate([cell + c * p.chains for c in range(cells)]))
    atoms = mmcif.decorated_atoms(q, pos, mat, sources)
    mmcif.write(tmp_path / "whole.cif", atoms, mmcif.header({"params": q.to_dict()}))
    return q, atoms


def _by_chain(atoms: dict) -> dict:
    chain = atoms["chain"]
    return {c: atoms["xyz"][chain == c] for c in dict.fromkeys(chain.tolist())}


def _expanded_by_gemmi(path) -> list:
    """gemmi's own expansion of assembly 1: (chain name, xyz) in the order gemmi makes them."""
    st = gemmi.read_structure(str(path))
    assert [a.name for a in st.assemblies] == [mmcif.ASSEMBLY_ID]
    model = gemmi.make_assembly(st.assemblies[0], st[0], gemmi.HowToNameCopiedChain.Dup)
    return [(ch.name, np.array([a.pos.tolist() for r in ch for a in r])) for ch in model]


def _oper_table(path):
    block = gemmi.cif.read(str(path))[0]
    gen = block.get_mmcif_category("_pdbx_struct_assembly_gen.")
    ops = block.get_mmcif_category("_pdbx_struct_oper_list.")
    mats = {}
    for k, op in enumerate(ops["id"]):
        t = np.eye(4)
        for i in range(3):
            t[i, :3] = [float(ops[f"matrix[{i + 1}][{j + 1}]"][k]) for j in range(3)]
            t[i, 3] = float(ops[f"vector[{i + 1}]"][k])
        mats[op] = t
    return block, gen, ops, mats


def test_the_assembly_expands_to_the_whole_fibril(case, tmp_path):
    p, sources, positions, mats = case
    cell = mmcif.decorated_atoms(p, positions, mats, sources)
    helical = mmcif.helical_assembly(p, CELLS)
    info = mmcif.write(tmp_path / "cell.cif", cell, mmcif.header({"params": p.to_dict()}),
                       helical)
    q, whole = _whole(p, sources, positions, mats, tmp_path)
    want = _by_chain(whole)
    read_whole = {ch.name: np.array([a.pos.tolist() for r in ch for a in r])
                  for ch in gemmi.read_structure(str(tmp_path / "whole.cif"))[0]}
    order = list(dict.fromkeys(cell["chain"].tolist()))
    expanded = _expanded_by_gemmi(tmp_path / "cell.cif")
    assert len(expanded) == len(want) == info["assembly"]["chains"] == 5 * len(order)
    assert sum(len(xyz) for _, xyz in expanded) == info["assembly"]["atoms"] == len(whole["xyz"])
    to_whole = _screw(p, CELLS)  # the oracle's frame starts at the image S^-CELLS
    worst = worst_file = 0.0
    for i, (name, xyz) in enumerate(expanded):
        m = helical["m"][i // len(order)]
        assert name == order[i % len(order)]  # operator by operator, every chain of the cell
        layer, rest = re.fullmatch(r"(\d+)(\D.*)", name).groups()
        target = f"{int(layer) + (m + CELLS) * p.periodic}{rest}"  # the same chain, m cells on
        got = _moved(to_whole, xyz)
        assert got.shape == want[target].shape
        worst = max(worst, np.linalg.norm(got - want[target], axis=1).max())
        worst_file = max(worst_file, np.linalg.norm(got - read_whole[target], axis=1).max())
    assert worst < 1e-3  # the cell's 0.001 Å columns: at most 0.00087 Å off
    assert worst_file < 2e-3  # against the whole file: both rounded to 0.001 Å


def test_a_hand_expansion_of_the_oper_list_agrees_with_gemmi(case, tmp_path):
    """Expand assembly 1 by hand from the cif tables (no gemmi assembly code): the same
    coordinates as gemmi.make_assembly, chain by chain."""
    p, sources, positions, mats = case
    cell = mmcif.decorated_atoms(p, positions, mats, sources)
    mmcif.write(tmp_path / "cell.cif", cell, {}, mmcif.helical_assembly(p, CELLS))
    block, gen, _, opers = _oper_table(tmp_path / "cell.cif")
    site = block.get_mmcif_category("_atom_site.")
    xyz = np.array([[float(v) for v in site[f"Cartn_{c}"]] for c in "xyz"]).T
    asym = np.array(site["label_asym_id"])
    chains = gen["asym_id_list"][0].split(",")
    by_hand = [(c, _moved(opers[op], xyz[asym == c]))
               for op in gen["oper_expression"][0].split(",") for c in chains]
    by_gemmi = _expanded_by_gemmi(tmp_path / "cell.cif")
    assert [c for c, _ in by_hand] == [c for c, _ in by_gemmi]
    assert max(np.abs(a - b).max() for (_, a), (_, b) in zip(by_hand, by_gemmi)) < 1e-4


def test_the_operator_list_is_flat_and_every_operator_a_screw_about_z(case, tmp_path):
    p, sources, positions, mats = case
    cell = mmcif.decorated_atoms(p, positions, mats, sources)
    mmcif.write(tmp_path / "cell.cif", cell, {}, mmcif.helical_assembly(p, 3))
    block, gen, ops, opers = _oper_table(tmp_path / "cell.cif")
    assert len(gen["oper_expression"]) == 1
    expression = gen["oper_expression"][0]
    assert re.fullmatch(r"\d+(,\d+)*", expression)  # one id per copy: no '(1-5)(6)' product
    assert expression.split(",") == ops["id"] and len(ops["id"]) == 7
    assert sorted(gen["asym_id_list"][0].split(",")) == sorted(set(cell["chain"].tolist()))
    assert ops["type"][0] == "identity operation" and np.allclose(opers["1"], np.eye(4))
    s1 = opers[ops["id"][ops["name"].index("S^1")]]
    for name, op in zip(ops["name"], ops["id"]):
        t = opers[op]
        r = t[:3, :3]
        assert abs(np.linalg.det(r) - 1) < 1e-9 and np.abs(r @ r.T - np.eye(3)).max() < 1e-9
        assert np.allclose(r[2], [0, 0, 1]) and np.allclose(t[:2, 3], 0)  # about the fibril axis
        m = int(name.removeprefix("S^"))
        assert np.allclose(t, np.linalg.matrix_power(s1, m) if m >= 0 else
                           np.linalg.matrix_power(np.linalg.inv(s1), -m), atol=1e-6)
        assert np.allclose(t, _screw(p, m), atol=1e-6)
    assert sorted(int(n.removeprefix("S^")) for n in ops["name"]) == list(range(-3, 4))


def test_only_a_periodic_cell_has_an_assembly():
    ends = P.make_params(layers=6)
    with pytest.raises(mmcif.AtomsError, match="periodic"):
        mmcif.helical_assembly(ends, 1)
    with pytest.raises(PlanError, match="^--pdb-assembly: only with --periodic"):
        OutputPlan(pdb_atoms="x.cif", pdb_assembly=2).cells_for(ends)
    with pytest.raises(PlanError, match="^--pdb-assembly: only with --pdb-atoms"):
        OutputPlan(pdb_assembly=2)
    cell = P.make_params(periodic=M)
    assert OutputPlan(pdb_atoms="x.cif", pdb_assembly=2).cells_for(cell) == {
        "pdb_images": 0, "pdb_assembly": 2}
    assert OutputPlan(pdb_atoms="x.cif").cells_for(ends)["pdb_assembly"] == 0
