"""An independent search for layouts, for testing the linker bound: plain numpy, no Bullet.

For a finite fibril with a box core, it looks for sphere centres within each chain's reach of
its anchor ((chain_x[globule] − chain_x[anchor])·(1 + tolerance)), pairwise at least a diameter
apart and each whole ball outside every layer's box: a layout that every definition in
docs/model/bound.md#assumptions accepts (the verdict's meshes lie inside those spheres; the
beads can fold anywhere within the reach). Projected gradient descent from a radial start with a
seeded jitter; `layout` returns the centres only when they pass the exact checks, else None.
"""
from __future__ import annotations

import numpy as np

from fibrilfit.model import helix
from fibrilfit.model.chain import chain_x


def anchors(p) -> np.ndarray:
    angle, height = helix.chain_transforms(p)
    ax, ay = p.anchor_xy
    return np.column_stack([np.cos(angle) * ax - np.sin(angle) * ay,
                            np.sin(angle) * ax + np.cos(angle) * ay, height])


def reach(p) -> float:
    x = chain_x(p)
    return (x[p.linker] - x[0]) * (1.0 + p.stretch_tolerance)


def box_push(p, c: np.ndarray, r: float) -> np.ndarray:
    """For each centre, the vector that moves its ball out of the nearest layer box it enters
    (zero if it enters none)."""
    hx, hy, hz = p.slab[0] / 2.0, p.slab[1] / 2.0, p.slab[2] / 2.0
    push = np.zeros_like(c)
    worst = np.zeros(len(c))
    for k in range(p.layers):
        ang = k * p.twist
        co, si = np.cos(-ang), np.sin(-ang)
        x = co * c[:, 0] - si * c[:, 1]
        y = si * c[:, 0] + co * c[:, 1]
        z = c[:, 2] - k * p.rise
        q = np.stack([np.clip(x, -hx, hx), np.clip(y, -hy, hy), np.clip(z, -hz, hz)], 1)
        d = np.stack([x, y, z], 1) - q
        dist = np.linalg.norm(d, axis=1)
        depth = r - dist
        hit = depth > worst
        # a centre inside the box: push along x, out through the nearer face
        inside = dist < 1e-9
        d[inside] = np.column_stack([np.sign(x[inside]) + (x[inside] == 0), np.zeros(inside.sum()),
                                     np.zeros(inside.sum())])
        n = d / np.maximum(np.linalg.norm(d, axis=1), 1e-9)[:, None]
        step_local = n * np.maximum(depth, 0)[:, None]
        co2, si2 = np.cos(ang), np.sin(ang)
        step = np.column_stack([co2 * step_local[:, 0] - si2 * step_local[:, 1],
                                si2 * step_local[:, 0] + co2 * step_local[:, 1], step_local[:, 2]])
        push[hit] = step[hit]
        worst = np.maximum(worst, depth)
    return push


def valid(p, c: np.ndarray, a: np.ndarray, R: float, r: float) -> bool:
    if (np.linalg.norm(c - a, axis=1) > R + 1e-9).any():
        return False
    d = np.linalg.norm(c[:, None] - c[None], axis=2) + np.eye(len(c)) * 1e9
    if (d < 2 * r - 1e-9).any():
        return False
    return not (np.linalg.norm(box_push(p, c, r - 1e-9), axis=1) > 0).any()


def layout(p, seed: int = 0, steps: int = 600, R: float | None = None) -> np.ndarray | None:
    """A layout at p's linker, or with the centres' reach R (Å) if given."""
    rng = np.random.default_rng(seed)
    a = anchors(p)
    R, r = (reach(p) if R is None else R), p.globule_radius
    out = a.copy()
    out[:, :2] *= 1.0 + R / np.maximum(np.linalg.norm(a[:, :2], axis=1), 1e-9)[:, None]
    c = out + rng.normal(scale=1.0, size=a.shape)
    for _ in range(steps):
        diff = c[:, None] - c[None]
        dist = np.linalg.norm(diff, axis=2) + np.eye(len(c)) * 1e9
        over = np.maximum(2 * r * 1.001 - dist, 0.0)
        move = (diff / dist[..., None] * over[..., None] / 2.0).sum(1)
        c = c + move + box_push(p, c, r * 1.001)
        off = c - a
        n = np.linalg.norm(off, axis=1)
        far = n > R
        c[far] = a[far] + off[far] / n[far, None] * R
        if valid(p, c, a, R, r):
            return c
    return None


def shortest(p, longest: int = 40) -> int | None:
    """The shortest linker at which `layout` finds a layout (None up to `longest`)."""
    for L in range(1, longest + 1):
        q = p.replace(linker=L)
        if any(layout(q, seed=s) is not None for s in range(2)):
            return L
    return None
