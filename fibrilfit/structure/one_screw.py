"""The axis of a fibril whose protofilaments are not copies of each other: the one screw that
takes every layer onto the next in every protofilament (docs/guide/structures.md#read-survey).

fibril.py finds the axis of two or more protofilaments from the screw that takes a chain of
protofilament 0 onto its neighbour in protofilament 1. When those screws disagree from layer to
layer, the two protofilaments are not copies of each other (different folds, or an asymmetric
pair), yet the deposited layers may still be exact helical copies of the layers below them: the
helical symmetry imposed in the reconstruction. That screw is the fibril's axis. It is accepted
when its copies of each protofilament's middle layer land on the file's layers within
MAX_DEVIATION; otherwise the file is refused with what was measured. Where the layers barely
twist, the screw's axis may land outside the fibril (2M5N: 127 Å from a core 24 Å across at
0.7° a layer): then the axis is taken along the screw through the core's centroid, approximate,
as for one protofilament whose layers are not exact copies (fibril._axis).
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
    how = f"within {dev[worst]:.2f} Å CA RMSD of the file's layers"
    xyz = cca.reshape(-1, 3)
    centre = xyz.mean(axis=0)
    off = float(np.linalg.norm(_across(centre - p, u)))
    extent = float(np.max(np.linalg.norm(_across(xyz - centre, u), axis=-1)))
    if angle < UNTWISTED or off > extent:  # no axis to place: the mean step, through the core
        why = ("the layers do not twist (one translation takes every layer onto the next, "
               f"{how})" if angle < UNTWISTED else
               f"the one screw that takes every layer onto the next ({how}, "
               f"{math.degrees(angle):.2f}° a layer) has its axis {off:.1f} Å from the core's "
               f"centroid, outside the {extent:.1f} Å that holds every core CA")
        warnings.append(f"the protofilaments are not copies of each other ({spread}) and {why}: "
                        "axis approximate, along the layers' mean step through the core's "
                        "centroid")
        step = (b - a).mean(axis=0)
        u = step / np.linalg.norm(step)
        return (u if u @ along >= 0 else -u), centre, False
    exact = dev[worst] <= EXACT
    warnings.append(f"the protofilaments are not copies of each other ({spread}): the axis "
                    f"is the one screw that takes every layer onto the next, {how}"
                    + ("" if exact else ": axis approximate"))
    u = u if u @ along >= 0 else -u
    return u, p, exact


def _across(v, u):
    """The part of v (a vector or rows of vectors) across the direction u."""
    return v - np.multiply.outer(v @ u, u)
