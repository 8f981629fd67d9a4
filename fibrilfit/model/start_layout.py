"""Where the chains start: the rest layout (rest_positions, bond_pivots: each chain straight out
from its anchor, turned and raised by the helix), the inflate protocol's (every chain a random
outward walk, the chains fanned), and the spread start of full-size covering spheres. Several
real-shaped domains per chain start bent: bent_layout.py.

Pure numpy (no bpy): (params, rest layout, seed) -> member positions and constraint pivots.
Written over chains generically: any number of chains, anchors anywhere; each chain's outward
direction is taken from its rest layout (anchor -> globule), the fibril axis is Z.
"""
from __future__ import annotations

import numpy as np

from ..geom.shape import directions
from . import helix
from .chain import chain_radii, joint_lever, rest_lengths

FAN_AXIAL = 0.9       # tan of the largest tilt along the fibril axis (chains at the ends): ~42°
FAN_SIDE = 0.6        # tan of the sideways tilt, alternating layer by layer: ~31°
WALK_NOISE = 0.25     # spread of each step's direction about the chain's fan direction (rad)
MIN_OUTWARD = 0.3     # every step keeps at least this cosine with the outward direction
SEED_SALT = 0x1F1A7E  # keeps this stream apart from any other use of the seed


def rest_positions(p) -> np.ndarray:
    """Rest positions of every chain member, shape (layers × protofilaments, linker + 1, 3).

    Each protofilament's chain (chain.ChainLayout, in polar form: protofilament 0's for every
    one, or its own with interface termini, Params.pf_layouts) turned and raised per chain
    (helix.chain_transforms); for the tutorial's model the same floats as one chain per layer.
    """
    angle, height = helix.chain_transforms(p)
    layouts = p.pf_layouts
    _, pf = helix.chain_layers(p)
    radius = np.stack([lay.radius for lay in layouts])[pf]
    turn = angle[:, None] + np.stack([lay.angle for lay in layouts])[pf]
    pos = np.empty((p.chains, radius.shape[1], 3))
    pos[..., 0] = np.cos(turn) * radius
    pos[..., 1] = np.sin(turn) * radius
    pos[..., 2] = height[:, None]
    return pos


def bond_pivots(p) -> np.ndarray:
    """POINT-constraint pivots: where consecutive members touch, shape (chains, linker, 3)."""
    pos = rest_positions(p)
    a, b = pos[:, :-1], pos[:, 1:]
    ra = np.asarray(chain_radii(p)[:-1])
    ra[-1] = joint_lever(p)  # a real shape's joint: one residue spacing on (chain.joint_lever)
    frac = ra / np.asarray(rest_lengths(p))
    return a + (b - a) * np.minimum(frac, 1.0)[None, :, None]


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(n > 0, n, 1.0)


def fan_frames(rest: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per chain: outward u (anchor -> rest globule), axial a (Z made perpendicular to u) and
    sideways s = u × a, each (n, 3)."""
    u = _unit(rest[:, -1] - rest[:, 0])
    z = np.array([0.0, 0.0, 1.0])
    a = z - (u @ z)[:, None] * u
    along_z = np.linalg.norm(a, axis=1) < 1e-6  # an outward direction along the axis
    a[along_z] = np.array([1.0, 0.0, 0.0]) - u[along_z, 0:1] * u[along_z]
    a = _unit(a)
    return u, a, np.cross(u, a)


def fan_directions(rest: np.ndarray, rng: np.random.Generator,
                   periodic: bool = False, columns: int = 0) -> np.ndarray:
    """Each chain's fan direction: outward, tilted along the axis in proportion to its anchor's
    height (monotone, so neighbouring chains never cross) and sideways, alternating from one
    height to the next (so neighbours part) with a random amplitude.

    In a screw-periodic cell (`periodic`) there is no axial tilt: any tilt that grows with the
    height would jump back at the cell's end, where the top chain and the bottom chain's image
    (one rise above it) would then cross. An infinite fibril cannot spread along its axis, so
    the chains part sideways only; the images, S^m of the originals, follow that layout. With
    `columns` (lattice_columns) the sideways amplitudes form a lattice instead of random ones."""
    u, a, s = fan_frames(rest)
    h = rest[:, 0, 2]
    span = np.ptp(h) / 2.0
    axial = (h - h.mean()) / span if span > 0 and not periodic else np.zeros_like(h)
    levels = np.unique(np.round(h, 3), return_inverse=True)[1].ravel()
    side = np.where(levels % 2 == 0, 1.0, -1.0) * rng.choice([-1.0, 1.0])
    amplitude = rng.uniform(0.5, 1.0, len(h))
    if columns:  # a lattice: each side's chains in `columns` rows (lattice_amplitudes)
        amplitude = lattice_amplitudes(levels, columns)
    return _unit(u + FAN_AXIAL * axial[:, None] * a + FAN_SIDE * (side * amplitude)[:, None] * s)


def lattice_columns(p) -> int:
    """The inflate start's lattice in a periodic cell: how many rows of chains each side holds
    (helix.lattice_rows), or 0 (no lattice: random amplitudes, as in a fibril with ends) unless
    the cell's M layers hold a whole number of periods. Measured: the one layout found for 20 Å
    globules at linker 4 (a 12-layer cell, seed 2) repeats every 4 layers, its chains in 2 rows
    a side; started so, 4 of seeds 0-4 fit (docs/model/search.md#lattice-start)."""
    rows = helix.lattice_rows(p) if getattr(p, "periodic", 0) else 0
    return rows if rows and p.periodic % (2 * rows) == 0 else 0


def lattice_amplitudes(levels: np.ndarray, columns: int) -> np.ndarray:
    """Sideways amplitude of each chain at height index `levels` in a lattice of `columns`
    rows a side: chain k's side alternates with k (fan_directions), its row is (k // 2) mod
    columns, from the outermost (1.0) to the innermost (0.5) on one side and the other way
    round on the other, so that neighbours one layer apart stand in different rows."""
    levels = np.asarray(levels)
    row = (levels // 2) % columns
    row = np.where(levels % 2 == 0, row, columns - 1 - row)
    return 1.0 - 0.5 * row / max(1, columns - 1) if columns > 1 else np.full(len(levels), 0.75)


def inflate_layout(p, rest: np.ndarray, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Start positions (n, linker + 1, 3) and bond pivots (n, linker, 3) for the inflate protocol.

    `rest` is the rest layout (n chains × [anchor, beads..., globule] × 3). Anchors stay where
    they are. The first bond points straight out; later bonds turn towards the chain's fan
    direction over two steps, each with a random wobble (`seed`), never turning back towards
    the core (in a periodic cell, no axial tilt: fan_directions). Every bond keeps its rest
    length, and each pivot is the contact point of the new layout: member i's radius along the
    bond (the last: chain.joint_lever), so the globule's joint sits on its full-size surface,
    or at its real joint, whatever scale it starts at.
    """
    rest = np.asarray(rest, dtype=float)
    lengths = np.asarray(rest_lengths(p), dtype=float)
    d = walk_directions(p, rest, seed)
    pos = np.empty_like(rest)
    pos[:, 0] = rest[:, 0]
    for i in range(1, rest.shape[1]):
        pos[:, i] = pos[:, i - 1] + lengths[i - 1] * d[:, i - 1]
    return pos, _pivots(p, pos)


def _pivots(p, pos: np.ndarray) -> np.ndarray:
    """Each bond's pivot for positions (n, m, 3): member i's radius along the bond from it (the
    last bond's: chain.joint_lever, a real shape's joint one residue spacing on)."""
    lever = np.asarray(chain_radii(p), dtype=float)[:-1].copy()
    lever[-1] = joint_lever(p)
    return pos[:, :-1] + lever[None, :, None] * _unit(pos[:, 1:] - pos[:, :-1])


def _keep_outward(d: np.ndarray, normal: np.ndarray, least: float) -> np.ndarray:
    """Directions d (n, 3) turned back towards `normal` (n, 3) until each keeps at least the
    cosine `least` with it (a step too far round would turn back towards what it left)."""
    low = (d * normal).sum(axis=1) < least
    while low.any():
        d[low] = _unit(d[low] + 0.5 * normal[low])
        low = (d * normal).sum(axis=1) < least
    return d


SPREAD_DIRECTIONS = 400  # candidate directions for each chain of spread_layout
SPREAD_OUTWARD = 0.5     # each keeps at least this cosine with the chain's outward direction
SPREAD_ROUNDS = 3        # times each chain is placed again against all the others


def spread_layout(p, rest: np.ndarray, body, rounds: int = SPREAD_ROUNDS
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Start positions and bond pivots (as inflate_layout) for full-size real-shaped globules
    (`spheres` under the tutorial protocol): each chain straight along the candidate direction
    that leaves its globule clear of the others, or least deep in them. Chains are placed in
    order against those before them, then each is placed again against all the others,
    `rounds` times. The first bond points straight out, as in inflate_layout.

    `body(pivots, d)` gives the globule's covering spheres [x, y, z, r] in the world, (k, s, 4),
    when its last bond's pivot is at pivots (k, 3) and the bond points along d (k, 3)
    (builders.layers turns it so).
    Deterministic: no seed (docs/model/domain-shapes.md#spheres-start)."""
    rest = np.asarray(rest, dtype=float)
    n, m, _ = rest.shape
    lengths = np.asarray(rest_lengths(p), dtype=float)
    lever_last = joint_lever(p)
    u = fan_frames(rest)[0]
    cand = directions(SPREAD_DIRECTIONS)
    # member i >= 2 along d after the first bond (straight out): first + reach[i - 1]·d
    reach = np.concatenate([[0.0], np.cumsum(lengths[1:])])
    first = rest[:, 0] + lengths[0] * u
    options = []  # per chain: (directions, their globules' spheres (k, s, 4))
    for c in range(n):
        dirs = np.vstack([u[c], cand[cand @ u[c] >= SPREAD_OUTWARD]])  # rest direction first
        if m > 2:
            pivot = first[c][None] + (reach[-2] + lever_last) * dirs
        else:
            pivot = rest[c, 0][None] + lever_last * dirs
        options.append((dirs, body(pivot, dirs)))
    choice = _choose([o[1] for o in options], rounds)
    pos = np.empty_like(rest)
    pos[:, 0] = rest[:, 0]
    d = np.array([options[c][0][choice[c]] for c in range(n)])
    if m > 2:
        pos[:, 1] = first
        pos[:, 2:] = first[:, None] + reach[None, 1:, None] * d[:, None]
    else:
        pos[:, 1] = rest[:, 0] + lengths[0] * d
    return pos, _pivots(p, pos)


def _choose(spheres: list, rounds: int) -> np.ndarray:
    """Per chain, which of its options to take: spheres[c] (k, s, 4) are option k's covering
    spheres in the world. The first option clear of the chains placed before it (or least deep
    in them), chain by chain, then each chain again against all the others, `rounds` times."""
    n = len(spheres)
    choice = np.zeros(n, dtype=int)

    def best(c, others):
        if not len(others):
            return 0
        s = spheres[c]  # (k, spheres, 4)
        gap = (np.linalg.norm(s[:, :, None, :3] - others[None, None, :, :3], axis=-1)
               - s[:, :, None, 3] - others[None, None, :, 3]).min(axis=(1, 2))
        return int(np.argmax(gap >= 0.0)) if (gap >= 0.0).any() else int(np.argmax(gap))

    for c in range(n):
        choice[c] = best(c, np.concatenate([spheres[k][choice[k]] for k in range(c)])
                         if c else np.empty((0, 4)))
    for _ in range(rounds):
        for c in range(n):
            others = [spheres[k][choice[k]] for k in range(n) if k != c]
            choice[c] = best(c, np.concatenate(others) if others else np.empty((0, 4)))
    return choice


def walk_directions(p, rest: np.ndarray, seed: int) -> np.ndarray:
    """The inflate protocol's bond directions (n, m - 1, 3) from `seed` (inflate_layout walks
    them; the bent layout of real-shaped domains follows them)."""
    rest = np.asarray(rest, dtype=float)
    n, m, _ = rest.shape
    rng = np.random.default_rng([int(seed), SEED_SALT])
    u = fan_frames(rest)[0]
    fan = fan_directions(rest, rng, periodic=bool(getattr(p, "periodic", 0)),
                         columns=lattice_columns(p))
    out = np.empty((n, m - 1, 3))
    for i in range(1, m):
        w = min(1.0, (i - 1) / 2.0)
        d = _unit((1.0 - w) * u + w * fan + WALK_NOISE * w * rng.normal(size=(n, 3)))
        out[:, i - 1] = _keep_outward(d, u, MIN_OUTWARD)  # never back towards the core
    return out
