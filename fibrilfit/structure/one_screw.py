"""The axis of a fibril whose protofilaments are not copies of each other: the one screw that
takes every layer onto the next in every protofilament (docs/guide/structures.md#read-survey).

fibril.py finds the axis of two or more protofilaments from the screw that takes a chain of
protofilament 0 onto its neighbour in protofilament 1. When those screws disagree from layer to
layer, the two protofilaments are not copies of each other (different folds, or an asymmetric
pair), yet the deposited layers may still be exact helical copies of the layers below them: the
helical symmetry imposed in the reconstruction. That screw is the fibril's axis. It is accepted
when its copies of each protofilament's middle layer land on the file's layers within
MAX_DEVIATION; otherwise the file is refused with what was measured.
"""
from __future__ import annotations

import math

import numpy as np

from ..geom import rigid as G
from .errors import StructureError

# Å, CA RMSD of a layer against the screw's copy of its protofilament's middle layer: a quarter
# of the CA-CA spacing (3.8 Å), so every copied residue lies nearest its own residue in the file
MAX_DEVIATION = 1.0
EXACT = 0.5  # Å: within it the axis is exact (fibril.EXACT_COPIES_RMSD)
UNTWISTED = math.radians(0.1)  # below it the screw is a translation: no axis position


def deviations(paths, cca, R, t) -> list:
    """Per protofilament: the largest CA RMSD of one of its layers against the screw (R, t)
    applied to its middle layer as often as the layers are apart."""
    out = []
    for q in paths:
        mid, worst = len(q) // 2, 0.0
        for k, i in enumerate(q):
            y = cca[q[mid]].copy()
            for _ in range(abs(k - mid)):
                y = y @ R.T + t if k > mid else (y - t) @ R
            worst = max(worst, float(np.sqrt(((y - cca[i]) ** 2).sum(axis=1).mean())))
        out.append(worst)
    return out


def axis(paths, cca, cen, along, pair_spread: tuple, chain_names: list, name: str,
         option: str, warnings: list) -> tuple:
    """(u, p, exact): the one screw's axis (direction, a point), or a StructureError saying how
    far its copies miss the file's layers. `paths`: each protofilament's chain indices in
    stacking order; `along`: the direction protofilament 0 runs; `pair_spread`: (°, Å), how far
    the protofilament pairs' axes disagree (fibril._axis)."""
    paths = [q if (cen[q[-1]] - cen[q[0]]) @ along >= 0 else q[::-1] for q in paths]
    stacks = [q for q in paths if len(q) > 1]
    a = np.concatenate([cca[i] for q in stacks for i in q[:-1]])
    b = np.concatenate([cca[i] for q in stacks for i in q[1:]])
    R, t, _ = G.superpose(a, b)
    u, p, angle, _ = G.screw_axis(R, t)
    dev = deviations(stacks, cca, R, t)
    worst = int(np.argmax(dev))
    spread = (f"the layer pairs' axes differ by up to {pair_spread[0]:.1f}° and "
              f"{pair_spread[1]:.1f} Å")
    if dev[worst] > MAX_DEVIATION:
        q = stacks[worst]
        others = max([d for k, d in enumerate(dev) if k != worst], default=0.0)
        raise StructureError(option, f"{name}: the protofilaments share no common axis ({spread}"
                                     f"), nor does one screw take every layer onto the next: "
                                     f"its copies miss the file's layers by up to "
                                     f"{dev[worst]:.2f} Å CA RMSD (the protofilament of chains "
                                     f"{chain_names[q[0]]}-{chain_names[q[-1]]}; the others "
                                     f"within {others:.2f} Å; at most {MAX_DEVIATION:g} Å "
                                     "read)")
    exact = dev[worst] <= EXACT and angle >= UNTWISTED
    how = f"within {dev[worst]:.2f} Å CA RMSD of the file's layers"
    if angle < UNTWISTED:  # an untwisted stack: the step's direction, through the core
        u = t / np.linalg.norm(t)
        p = cca.reshape(-1, 3).mean(axis=0)
        warnings.append(f"the protofilaments are not copies of each other ({spread}) and the "
                        f"layers do not twist (one translation takes every layer onto the next, "
                        f"{how}): axis approximate, along it through the core's centroid")
    else:
        warnings.append(f"the protofilaments are not copies of each other ({spread}): the axis "
                        f"is the one screw that takes every layer onto the next, {how}"
                        + ("" if exact else ": axis approximate"))
    u = u if u @ along >= 0 else -u
    return u, p, exact
