"""Read a PDB/mmCIF file with gemmi into plain numpy arrays, one record per protein chain.

gemmi is imported here, lazily, so that the rest of FibrilFit works without it.
"""
from __future__ import annotations

import hashlib
import pathlib
from dataclasses import dataclass, field

import numpy as np

from ..exits import missing_packages
from .errors import StructureError

SUFFIXES = (".pdb", ".ent", ".cif", ".mmcif", ".mcif")
MIN_CHAIN_RESIDUES = 20  # shorter chains (peptides, unidentified densities) are ignored
# a fibril file with no chain of MIN_CHAIN_RESIDUES is read as a short-peptide fibril: chains of
# at least 6 residues, the shortest segments that form amyloid cross-β spines on their own (the
# six-residue steric zippers, Sawaya et al. 2007, Nature 447:453; e.g. 9CZ3's 6-residue chains).
# Its chains must still stack as layers (fibril.py) to be read as a fibril
# (docs/guide/structures.md#read-survey).
MIN_PEPTIDE_RESIDUES = 6


@dataclass
class ChainAtoms:
    """One protein chain: CA per residue number, heavy atoms with their residue numbers."""

    name: str
    residues: np.ndarray  # (n,) int residue numbers, ascending, each once
    names: list  # residue names, same order
    ca: np.ndarray  # (n, 3) CA coordinates
    heavy: np.ndarray  # (m, 3) heavy-atom coordinates
    heavy_residue: np.ndarray  # (m,) residue number of each heavy atom
    heavy_radius: np.ndarray  # (m,) van der Waals radius, Å
    # per heavy atom, for writing atoms out (exports/mmcif.py): atom name, element, residue
    # name, B-factor (a predicted model's pLDDT)
    heavy_name: np.ndarray | None = None
    heavy_element: np.ndarray | None = None
    heavy_resname: np.ndarray | None = None
    heavy_b: np.ndarray | None = None
    # per residue (same order as `residues`): the CA's B-factor
    ca_b: np.ndarray | None = None

    def ca_of(self, numbers) -> np.ndarray:
        idx = np.searchsorted(self.residues, numbers)
        return self.ca[idx]


@dataclass
class Loaded:
    path: pathlib.Path
    sha256: str
    chains: list
    models: int  # models in the file (an NMR ensemble has several; model 1 is used)
    notes: list = field(default_factory=list)
    structure: object = None  # the gemmi.Structure (model 1 kept), for symmetry expansion
    min_residues: int = MIN_CHAIN_RESIDUES  # the shortest chain kept (also for symmetry copies)


def sha256(path: pathlib.Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _gemmi(option):
    try:
        import gemmi
    except ImportError:
        raise StructureError(option, missing_packages(["gemmi"], "reading structures")) from None
    return gemmi


def check_path(path, option: str) -> pathlib.Path:
    path = pathlib.Path(path)
    name = path.name.lower()
    base = name[:-3] if name.endswith(".gz") else name
    if not base.endswith(SUFFIXES):
        raise StructureError(option, f"{path.name}: must be a .pdb, .ent, .cif or .mmcif file, "
                                     "optionally .gz")
    if not path.is_file():
        raise StructureError(option, f"{path}: no such file")
    try:
        with open(path, "rb"):
            pass
    except OSError as exc:
        raise StructureError(option, f"{path}: cannot be read ({exc.strerror})") from None
    return path


def load(path, option: str = "--fibril", *, peptides: bool = False) -> Loaded:
    """Model 1 of the file, hydrogens, waters and ligands removed, protein chains only (of at
    least MIN_CHAIN_RESIDUES; with `peptides`, a fibril's, when no chain is that long, of at
    least MIN_PEPTIDE_RESIDUES)."""
    path = check_path(path, option)
    gemmi = _gemmi(option)
    try:
        st = gemmi.read_structure(str(path))
    except Exception as exc:  # gemmi raises ValueError/RuntimeError/OSError with its own text
        detail = " ".join(str(exc).split())[:160]
        raise StructureError(option, f"{path.name}: not a readable structure ({detail})") from None
    if len(st) == 0 or not any(len(ch) for ch in st[0]):
        raise StructureError(option, f"{path.name}: not a structure (no atoms)")
    models, notes = len(st), []
    if models > 1:
        notes.append(f"{models} models in the file (an ensemble): model 1 used")
        while len(st) > 1:
            del st[1]
    st.setup_entities()
    st.remove_hydrogens()
    st.remove_ligands_and_waters()
    least = MIN_PEPTIDE_RESIDUES if peptides else MIN_CHAIN_RESIDUES
    found = chains_of(st[0], least)
    chains = [c for c in found if len(c.residues) >= MIN_CHAIN_RESIDUES]
    shortest = MIN_CHAIN_RESIDUES
    if found and not chains:  # a short-peptide fibril
        chains, shortest = found, least
        notes.append(f"no chain of {MIN_CHAIN_RESIDUES} residues or more: read as a "
                     f"short-peptide fibril (chains of {least} residues or more)")
    elif len(chains) < len(found):  # the long chains are the fibril
        short = [c.name for c in found if len(c.residues) < MIN_CHAIN_RESIDUES]
        notes.append(f"{len(short)} chains of {least}-{MIN_CHAIN_RESIDUES - 1} residues not "
                     f"read ({', '.join(short[:4])}{', …' if len(short) > 4 else ''}): the "
                     f"fibril is read from its chains of {MIN_CHAIN_RESIDUES} residues or more")
    if not chains:
        raise StructureError(option, f"{path.name}: no protein chain of at least {least} "
                                     "residues")
    return Loaded(path, sha256(path), chains, models, notes, st, shortest)


def chains_of(model, min_residues: int = MIN_CHAIN_RESIDUES) -> list:
    """The protein chains of a gemmi.Model as ChainAtoms (chains of fewer than `min_residues`
    residues, and unidentified ones, dropped)."""
    import gemmi
    out = []
    for chain in model:
        residues, names, ca, heavy, heavy_res, radius = [], [], [], [], [], []
        atom_names, elements, resnames, bfac, ca_b = [], [], [], [], []
        seen = set()
        for res in chain:
            info = gemmi.find_tabulated_residue(res.name)
            if info is None or not info.is_amino_acid() or res.name == "UNK":
                continue
            atom = res.find_atom("CA", "*")
            num = res.seqid.num
            if atom is None or num in seen:  # altlocs / insertion codes: first one kept
                continue
            seen.add(num)
            residues.append(num)
            names.append(res.name)
            ca.append(atom.pos.tolist())
            ca_b.append(atom.b_iso)
            for a in res:
                if a.altloc not in ("\0", "A") or a.element.is_hydrogen:
                    continue
                heavy.append(a.pos.tolist())
                heavy_res.append(num)
                radius.append(a.element.vdw_r)
                atom_names.append(a.name)
                elements.append(a.element.name)
                resnames.append(res.name)
                bfac.append(a.b_iso)
        if len(residues) < min_residues:
            continue
        order = np.argsort(residues, kind="stable")
        out.append(ChainAtoms(chain.name, np.asarray(residues)[order], [names[i] for i in order],
                              np.asarray(ca, float)[order], np.asarray(heavy, float),
                              np.asarray(heavy_res, int), np.asarray(radius, float),
                              np.asarray(atom_names, dtype=object),
                              np.asarray(elements, dtype=object),
                              np.asarray(resnames, dtype=object), np.asarray(bfac, float),
                              np.asarray(ca_b, float)[order]))
    return out


def expand_symmetry(loaded: Loaded) -> bool:
    """Replace a one-chain model by its assembly (REMARK 350 / pdbx_struct_oper_list) or its NCS
    copies. Returns True if it made more than one chain."""
    import gemmi
    st = loaded.structure
    for assembly in st.assemblies:
        n_ops = sum(len(g.operators) for g in assembly.generators)
        if n_ops < 2:
            continue
        model = gemmi.make_assembly(assembly, st[0], gemmi.HowToNameCopiedChain.Short)
        chains = chains_of(model, loaded.min_residues)
        if len(chains) > 1:
            loaded.chains = chains
            loaded.notes.append(f"one chain in the file: {len(chains)} layers built from its "
                                f"assembly {assembly.name!r} ({n_ops} operators)")
            return True
    if len(st.ncs) > 1 and not all(op.given for op in st.ncs):
        copy = st.clone()
        copy.expand_ncs(gemmi.HowToNameCopiedChain.Short)
        chains = chains_of(copy[0], loaded.min_residues)
        if len(chains) > 1:
            loaded.chains = chains
            loaded.notes.append(f"one chain in the file: {len(chains)} layers built from its "
                                f"{len(st.ncs)} NCS operators")
            return True
    return False
