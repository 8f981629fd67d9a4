"""The atoms a decorated fibril is written with (`--pdb-atoms`): each protofilament's core chain
in its own chain frame and each domain in its body frame. Plain numpy; gemmi reads the files.

The body frame of a domain (the globule object's local frame) is the rule of `domain.body_frame`:
the domain's heavy atoms minus their centroid, not rotated. A globule's world matrix after the
bake then places the domain's atoms (docs/guide/atoms-and-domains.md#body-frame).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import domain as D, fibril as F, reading


@dataclass
class AtomSet:
    """Heavy atoms of one piece of a chain, in some local frame."""

    xyz: np.ndarray      # (n, 3) Å
    name: np.ndarray     # (n,) atom names
    element: np.ndarray  # (n,) element symbols
    resname: np.ndarray  # (n,) residue names
    resnum: np.ndarray   # (n,) int residue numbers
    b: np.ndarray        # (n,) B-factors as read (a predicted model's pLDDT)

    def __len__(self) -> int:
        return len(self.xyz)

    @classmethod
    def of_chain(cls, chain: reading.ChainAtoms, keep=None) -> "AtomSet":
        keep = np.ones(len(chain.heavy), bool) if keep is None else np.asarray(keep, bool)
        return cls(chain.heavy[keep].copy(), chain.heavy_name[keep], chain.heavy_element[keep],
                   chain.heavy_resname[keep], chain.heavy_residue[keep], chain.heavy_b[keep])

    def moved(self, xyz: np.ndarray) -> "AtomSet":
        return AtomSet(np.asarray(xyz, float), self.name, self.element, self.resname,
                       self.resnum, self.b)


@dataclass
class Sources:
    """What `--pdb-atoms` places: per protofilament of the fibril file its core chain in its
    own chain frame (or None without --fibril), the domains in chain order in their body frames
    (empty without --domain), the core's anchor residue and the side its linker leaves by."""

    core: list | None
    domains: list
    anchor_residue: int | None = None
    side: str = "C"  # "C": the linker follows the anchor in sequence; "N": it precedes it

    def linker_numbers(self, beads: int, skip: int = 0) -> np.ndarray:
        """Residue numbers of a chain's `beads` linker residues (anchor side first): after the
        anchor (before it on the N side) in the protein's numbering, or 2 .. beads + 1 without
        a fibril file; `skip` residues after the anchor first (a buried anchor's exit:
        docs/model/buried-terminus.md#model)."""
        step = -1 if self.side == "N" else 1
        if self.anchor_residue is None:
            return np.arange(2 + skip, beads + 2 + skip)
        return self.anchor_residue + step * np.arange(1 + skip, beads + 1 + skip)


def core_atoms(path, geometry: F.FibrilGeometry, option: str = "--fibril") -> list:
    """Each protofilament's reference chain in its own chain frame: the model's layer frame,
    turned and lowered by that protofilament's measured offset (so protofilament j of layer k
    is placed by the model's chain pose, helix.chain_transforms). Residues beyond the anchor on
    the linker's side are left out: the linker beads stand for them."""
    origin, frame = F.layer_frame(geometry)
    side = "N" if geometry.terminus == "N" else "C"
    out = []
    for j, (chain, anchor) in enumerate(zip(F.reference_chains(path, geometry, option),
                                            geometry.anchors)):
        res = anchor["residue"]
        keep = chain.heavy_residue <= res if side == "C" else chain.heavy_residue >= res
        atoms = AtomSet.of_chain(chain, keep)
        local = (atoms.xyz - origin) @ frame.T
        rot, rise = geometry.pf_offsets[j] if j < len(geometry.pf_offsets) else (0.0, 0.0)
        c, s = math.cos(-rot), math.sin(-rot)
        x, y = local[:, 0].copy(), local[:, 1].copy()
        local[:, 0], local[:, 1] = c * x - s * y, s * x + c * y
        local[:, 2] -= rise
        out.append(atoms.moved(local))
    return out


def domain_atoms(path, *, chain: str | None = None, residues=None,
                 option: str = "--domain") -> AtomSet:
    """A domain's heavy atoms (as `inspect --domain` measures them) in its body frame."""
    loaded = reading.load(path, option)
    c, keep, _ = D.select(loaded, chain=chain, residues=residues)
    atoms = AtomSet.of_chain(c, keep)
    return atoms.moved(D.body_frame(atoms.xyz)[1])


def sources(fibril_path=None, geometry=None, domains=()) -> Sources:
    """Sources for --pdb-atoms. `domains`: AtomSets in body frames, in chain order."""
    core = anchor = None
    side = "C"
    if fibril_path is not None:
        core = core_atoms(fibril_path, geometry)
        anchor = int(geometry.anchors[0]["residue"])
        side = "N" if geometry.terminus == "N" else "C"
    return Sources(core, list(domains), anchor, side)
