"""`--full-length FILE`: a predicted model of the whole chain (AlphaFold-style, pLDDT in the
B-factor column) in the fibril's numbering, cut into folded domains and the linkers between.

A folded domain is a run of at least MIN_DOMAIN residues with pLDDT >= MIN_PLDDT outside the
fibril's core (dips of up to BRIDGE residues inside a run, a loop, do not cut it); the residues
between the core and a domain, or between two domains, are a linker
(docs/guide/atoms-and-domains.md#full-length-models).
"""
from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np

from . import reading
from .domain import RG_TO_DIAMETER
from .errors import StructureError

MIN_PLDDT = 70.0
MIN_DOMAIN = 40  # residues
BRIDGE = 3  # residues: a shorter dip below MIN_PLDDT between two confident runs is a loop
OPTION = "--full-length"


@dataclass
class Segmentation:
    """What `inspect --full-length` prints. Residue numbers are the file's (the fibril's)."""

    file: str
    sha256: str
    chain: str
    residues: list  # [first, last] modelled
    core: list  # the fibril's core [first, last], or [] without --fibril
    domains: list  # [{first, last, plddt_mean, diameter, side}] in sequence order
    linkers: list  # [{first, last, length, between}] core-domain and domain-domain gaps
    notes: list = field(default_factory=list)

    def to_dict(self) -> dict:
        return asdict(self)

    def chain_order(self, side: str) -> list:
        """The domains on one side of the core ("C": after it, "N": before it), from the core
        outward, each with the linker before it (residues between it and the previous piece)."""
        picked = [d for d in self.domains if d["side"] == side]
        return picked if side == "C" else picked[::-1]


def no_domain(file: str) -> str:
    """Why a model gives the chain no domain (after its option's name)."""
    return (f"no folded domain (pLDDT >= {MIN_PLDDT:g} over at least {MIN_DOMAIN} residues) on "
            f"the linker's side of the core in {file}")


def _runs(mask: np.ndarray) -> list:
    """[start, stop) of each run of True."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(np.int8), [0]])))
    return list(zip(edges[::2], edges[1::2]))


def segment(path, core=None, *, chain: str | None = None) -> Segmentation:
    """Segment a full-length model. `core`: the fibril's core residues [first, last] (None: no
    fibril given, the whole chain is searched)."""
    loaded = reading.load(path, OPTION)
    name = loaded.path.name
    names = [c.name for c in loaded.chains]
    if chain is not None and chain not in names:
        raise StructureError(OPTION, f"{name}: no protein chain {chain!r} (chains: "
                                     f"{', '.join(names)})")
    c = loaded.chains[names.index(chain)] if chain else loaded.chains[0]
    notes = list(loaded.notes)
    if chain is None and len(names) > 1:
        notes.append(f"{len(names)} protein chains: chain {c.name} used")
    plddt = np.asarray(c.ca_b, float)
    if np.ptp(plddt) == 0:
        raise StructureError(OPTION, f"{name}: no pLDDT in the B-factor column (every "
                                     f"B-factor is {plddt[0]:g}): give a predicted model")
    if plddt.max() <= 1.0:  # some predictors write pLDDT as a fraction
        plddt = plddt * 100.0
        notes.append("pLDDT given as a fraction (0-1): read as percent")
    res = c.residues
    if core is not None:
        want = np.arange(core[0], core[1] + 1)
        missing = np.setdiff1d(want, res)
        if len(missing):
            raise StructureError(OPTION, f"{name}: residues {res[0]}-{res[-1]} "
                                         f"({len(res)} modelled) do not cover the fibril's "
                                         f"core {core[0]}-{core[1]} ({len(missing)} missing): "
                                         "it must use the fibril's numbering")
    confident = plddt >= MIN_PLDDT
    for a, b in _runs(~confident):  # bridge short dips between confident residues
        if 0 < a and b < len(res) and b - a <= BRIDGE:
            confident[a:b] = True
    outside = np.ones(len(res), bool) if core is None else (res < core[0]) | (res > core[1])
    # a gap in the numbering (unmodelled residues) ends a run too
    breaks = np.concatenate([[False], np.diff(res) != 1])
    domains = []
    for a, b in _runs(confident & outside):
        cuts = [a, *(a + np.flatnonzero(breaks[a + 1:b]) + 1), b]
        for s, e in zip(cuts, cuts[1:]):
            if e - s < MIN_DOMAIN:
                continue
            first, last = int(res[s]), int(res[e - 1])
            keep = (c.heavy_residue >= first) & (c.heavy_residue <= last)
            xyz = c.heavy[keep]
            rg = float(np.sqrt(((xyz - xyz.mean(axis=0)) ** 2).sum(axis=1).mean()))
            side = "N" if core is not None and last < core[0] else "C"
            domains.append({"first": first, "last": last,
                            "plddt_mean": round(float(plddt[s:e].mean()), 2),
                            "diameter": round(RG_TO_DIAMETER * rg, 3), "residues": int(e - s),
                            "side": side if core is not None else ""})
    return Segmentation(name, loaded.sha256, c.name, [int(res[0]), int(res[-1])],
                        list(core) if core is not None else [], domains,
                        _linkers(domains, core), notes)


def _linkers(domains: list, core) -> list:
    """Residues between the core and the nearest domain on each side, and between consecutive
    domains (without a core: between consecutive domains only)."""
    pieces = sorted([(d["first"], d["last"], f"domain {d['first']}-{d['last']}")
                     for d in domains])
    if core is not None:
        pieces = sorted(pieces + [(core[0], core[1], f"core {core[0]}-{core[1]}")])
    out = []
    for (_, a_last, a_name), (b_first, _, b_name) in zip(pieces, pieces[1:]):
        out.append({"first": int(a_last + 1), "last": int(b_first - 1),
                    "length": int(b_first - a_last - 1),
                    "between": [a_name, b_name]})
    return out
