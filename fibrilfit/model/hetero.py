"""A hetero-amyloid's two domains, chain by chain (issue #44 item 1,
docs/model/occupancy.md#hetero): which of the model's chains carry the second domain B, the
lengths and sizes each chain has with its own domain, and each letter's share of the chains the
linker bound counts. Plain numpy, no bpy.

The pattern (which layers are A, B or none) is model/occupancy.py's; a B chain is the chain
of `b_params(p)`, the same model with B's diameter (and linker), so every length of it comes
from model/chain.py as an A chain's does. Each function returns an array over the chains that
is the same for every chain when the fibril has no B, with the very floats the one-chain
functions give (a fibril without B: the model as before, bit for bit).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from . import occupancy
from .chain import body_radii, chain_reach, rest_lengths


def b_params(p):
    """The B chains' model: p with the second domain's diameter and linker in place of A's
    (for their lengths and start layouts only: not a model of its own, never validated)."""
    return dataclasses.replace(p, globule_diameter=float(p.domain_b_diameter),
                               linker=p.linker if p.linker_b is None else int(p.linker_b))


def b_subunits(p) -> np.ndarray:
    """bool per subunit (layer-major, every subunit of the model): carries B."""
    return occupancy.second_domain(p).ravel()


def b_chains(p) -> np.ndarray:
    """bool per chain of the model (model.chain's order: the decorated subunits'): carries B."""
    b = b_subunits(p)
    return b[occupancy.decorated_chains(p)] if occupancy.is_mixed(p) else b


def model_chains(p) -> int:
    """How many chains the model holds (the decorated subunits)."""
    return int(occupancy.decorated(p).sum())


def rest_lengths_by_chain(p) -> np.ndarray:
    """Rest length of each bond of each chain of the model, (chains, bonds): a B chain's last
    bond reaches B's surface, not A's."""
    a = np.asarray(rest_lengths(p), dtype=float)
    rows = np.broadcast_to(a, (model_chains(p), a.size))
    if not occupancy.is_hetero(p):
        return rows
    b = np.asarray(rest_lengths(b_params(p)), dtype=float)
    return np.where(b_chains(p)[:, None], b[None], rows)


def globule_radii_by_chain(p) -> np.ndarray:
    """The radius of each chain's globule (one domain per chain: B is refused beside several),
    (chains,)."""
    radius = np.full(model_chains(p), p.globule_radius)
    if occupancy.is_hetero(p):
        radius[b_chains(p)] = float(p.domain_b_diameter) / 2.0
    return radius


def b_scale(p) -> float:
    """B's globule as a scale of A's sphere mesh, which B's globules share (builders.layers)."""
    return float(p.domain_b_diameter) / float(p.globule_diameter)


def widest_body_radii(p) -> np.ndarray:
    """chain.body_radii over both domains: how far each member's body can reach on an A or a B
    chain (what a periodic cell's images must allow for)."""
    radii = body_radii(p)
    return np.maximum(radii, body_radii(b_params(p))) if occupancy.is_hetero(p) else radii


def widest_chain_reach(p) -> np.ndarray:
    """chain.chain_reach over both domains (see widest_body_radii)."""
    reach = chain_reach(p)
    return np.maximum(reach, chain_reach(b_params(p))) if occupancy.is_hetero(p) else reach


def letter_shares(p, lo: int, hi: int) -> list[float]:
    """A hetero-amyloid's (the linker bound, docs/model/bound.md#hetero): the shares (A, B) of a protofilament's
    judged chains that carry each letter, as the inequalities count them (need = protofilaments
    × chains_per_pf × Σ share·V): a finite fibril's scored layers lo..hi-1 (counts over
    chains_per_pf = hi − lo), or a periodic cell's average per layer over the pattern's
    repeat (one layer of the infinite fibril)."""
    b = occupancy.second_domain(p)[:, 0]
    if p.periodic:
        n = len(occupancy.letters(p.pattern_layers))
        b_layers = sum(ch == occupancy.SECOND_DOMAIN for ch in occupancy.letters(p.pattern_layers))
        return [(n - b_layers) / n, b_layers / n]
    judged = b[lo:hi]
    return [float((~judged).sum()) / len(judged), float(judged.sum()) / len(judged)]
