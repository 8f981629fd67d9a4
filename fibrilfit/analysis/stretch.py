"""How far each linker bond is pulled beyond its rest length."""
from __future__ import annotations

import numpy as np

from ..model.chain import joint_lever, rest_lengths


def bond_stretch(positions: np.ndarray, rest_lengths) -> np.ndarray:
    """Stretch of each bond, (distance − rest) / rest, for chain positions (layers, members, 3).

    Rest lengths are the sums of the two members' radii in the tutorial's model.
    Returns (layers, members − 1); negative means compressed.
    """
    dist = np.linalg.norm(np.diff(positions, axis=1), axis=-1)
    rest = np.asarray(rest_lengths, dtype=float)
    return dist / rest - 1.0


def bond_ends(p, matrices: np.ndarray, rest=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where each linker bond starts and ends in the world, (chains, members − 1, 3) each, and its
    rest length, from the chain members' world matrices (chains, members, 4, 4).

    A bead or a sphere globule is its centre (the tutorial's bonds: rest length the two radii).
    A real-shaped domain (hull, spheres) is held by its terminal CAs: the bond into it ends at
    its joint and the bond out of it (several domains) starts at its exit, each one residue
    spacing from the bead beside it. Measured from the domain's centre, a joint pulled 0.95 Å
    apart read as 4 % of GFP's 23.5 Å centre bond, against 27 % of the 3.5 Å bond it is
    (docs/model/domain-shapes.md#joint-stretch).

    `rest`: each chain's own rest lengths (chains, members − 1), a hetero-amyloid's
    (model.hetero.rest_lengths_by_chain: a B chain's last bond reaches B's surface); default
    the one chain's of `p`, (members − 1,).
    """
    matrices = np.asarray(matrices, dtype=float)
    positions = matrices[..., :3, 3]
    starts, ends = positions[:, :-1].copy(), positions[:, 1:].copy()
    rest = np.array(rest_lengths(p) if rest is None else rest, dtype=float)
    for d in p.domains:  # a sphere has no joint: its bonds end at its centre, as a bead's
        if d.joint is None:
            continue
        g, m = d.member, matrices[:, d.member]
        ends[:, g - 1] = m[:, :3, :3] @ d.joint + m[:, :3, 3]
        rest[..., g - 1] = joint_lever(p)
        if d.exit is not None and g < positions.shape[1] - 1:
            starts[:, g] = m[:, :3, :3] @ d.exit + m[:, :3, 3]
            rest[..., g] = p.residue_spacing
    return starts, ends, rest


def ends_stretch(starts: np.ndarray, ends: np.ndarray, rest) -> np.ndarray:
    """bond_stretch for bonds given by their two ends (bond_ends)."""
    return np.linalg.norm(ends - starts, axis=-1) / np.asarray(rest, dtype=float) - 1.0


class StretchLog:
    """The worst bond stretch of every frame of a bake, summarised honestly.

    The model is built with neighbouring globules overlapping (30 Å spheres 4.8 Å apart), so
    Bullet's first frames push them apart and pull every linker far beyond its length (measured
    300–1300 % around frames 2–5, on models that end intact). The raw worst over the bake is
    therefore reported together with what happened after that push-apart.
    """

    def __init__(self, rest_lengths, tolerance: float, scored: slice = slice(None)):
        """`rest_lengths`: one chain's (members − 1,), or every chain's (chains, members − 1)
        (a hetero-amyloid's: model.hetero.rest_lengths_by_chain), then taken at `scored`."""
        if np.ndim(rest_lengths) == 2:
            rest_lengths = np.asarray(rest_lengths)[scored]
        self.rest, self.tolerance, self.scored = rest_lengths, tolerance, scored
        self.worst: list[float] = []

    def add(self, positions: np.ndarray) -> float:
        """Record one frame's chain positions (layers, members, 3); return its worst stretch."""
        s = bond_stretch(positions[self.scored], self.rest)
        self.worst.append(float(s.max()) if s.size else 0.0)
        return self.worst[-1]

    def summary(self) -> dict:
        """Fields of the result; frames are 1-based, None where a frame does not exist."""
        w = np.asarray(self.worst)
        if w.size == 0:
            return {}
        over = w > self.tolerance
        back = np.nonzero(~over[1:])[0]  # frame 1 is the built model, always at rest length
        push_end = int(back[0]) + 2 if back.size else None
        still_over = np.nonzero(over)[0]
        intact_from = None if over[-1] else (int(still_over[-1]) + 2 if still_over.size else 1)
        return {
            "max_bond_stretch_bake": round(float(w.max()), 6),
            "max_bond_stretch_bake_frame": int(w.argmax()) + 1,
            "push_apart_end_frame": push_end,
            "max_bond_stretch_after_push": (round(float(w[push_end - 1:].max()), 6)
                                            if push_end else None),
            "frames_over_tolerance": int(over.sum()),
            "intact_from_frame": intact_from,
        }


def linker_spans(p, starts: np.ndarray, ends: np.ndarray, rest, exit_start=None,
                 exit_length=None) -> tuple[np.ndarray, np.ndarray]:
    """Each domain's linker, as the model counts it, end to end and along its contour:
    (distance, contour), each (chains, domains), from bond_ends's `starts`, `ends` and `rest`
    (docs/model/linker-integrity.md#linker-span).

    Domain k's linker runs from where its chain leaves the member before it (the anchor's bead;
    a real domain's exit CA; a sphere's surface) to where it enters domain k (a real domain's
    joint CA; a sphere's surface, facing the last bead), over the bonds between; its contour is
    their rest lengths, each bond at full stretch (a residue spacing, 3.5 Å, bead to bead), less
    a sphere's radius at either end. A buried anchor's exit (`exit_start`: the anchor residue's
    CA, (chains, 3), NaN where a chain has none; `exit_length`: the fixed path from there to the
    anchor's bead, (chains,)) starts the first linker at the CA and adds the path to its contour.
    A linker laid out straight at rest length spans its contour exactly (1.0); one that folds,
    less.
    """
    starts, ends = np.asarray(starts, dtype=float), np.asarray(ends, dtype=float)
    rest = np.broadcast_to(np.asarray(rest, dtype=float), starts.shape[:2])
    members = [d.member for d in p.domains]
    spheres = [d.joint is None for d in p.domains]
    distance = np.empty((len(starts), len(members)))
    contour = np.empty_like(distance)
    for k, g in enumerate(members):
        g0 = members[k - 1] if k else 0
        a, b = starts[:, g0].copy(), ends[:, g - 1].copy()
        length = rest[:, g0:g].sum(axis=1)
        if spheres[k]:  # the bond ends at the centre: its radius is not linker
            radius = rest[:, g - 1] - p.residue_radius
            b += radius[:, None] * _unit(starts[:, g - 1] - b)
            length -= radius
        if k and spheres[k - 1]:  # the bond leaves from the centre before
            radius = rest[:, g0] - p.residue_radius
            a += radius[:, None] * _unit(ends[:, g0] - a)
            length -= radius
        if k == 0 and exit_start is not None:
            buried = ~np.isnan(np.asarray(exit_start, dtype=float)).any(axis=1)
            a[buried] = np.asarray(exit_start, dtype=float)[buried]
            length = length + np.where(buried, np.nan_to_num(np.asarray(exit_length, float)), 0)
        distance[:, k] = np.linalg.norm(b - a, axis=-1)
        contour[:, k] = length
    return distance, contour


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.divide(v, n, out=np.zeros_like(v), where=n > 0)


def linker_stretch_block(distance: np.ndarray, contour: np.ndarray) -> dict | None:
    """The result's `linker_stretch`: every linker's end-to-end distance as a fraction of its
    contour (linker_spans), their median and worst (the largest: the most stretched), which
    chain and domain that is, and with several domains the same per domain (None: no linker
    scored)."""
    fraction = np.asarray(distance, dtype=float) / np.asarray(contour, dtype=float)
    if fraction.size == 0:
        return None
    chain, domain = np.unravel_index(int(np.argmax(fraction)), fraction.shape)
    out = {"median": round(float(np.median(fraction)), 4),
           "worst": round(float(fraction.max()), 4),
           "worst_linker": {"chain": int(chain), "domain": int(domain)},
           "linkers": int(fraction.size),
           "contour_A": round(float(np.median(contour)), 2)}
    if fraction.shape[1] > 1:
        out["by_domain"] = [{"domain": k, "median": round(float(np.median(f)), 4),
                             "worst": round(float(f.max()), 4),
                             "contour_A": round(float(np.median(c)), 2)}
                            for k, (f, c) in enumerate(zip(fraction.T, np.asarray(contour).T))]
    return out
