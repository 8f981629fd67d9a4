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


def cut_disk(s: np.ndarray, c: float) -> np.ndarray:
    """The area of disks of radii s less their segment past a line c from their centre."""
    seg = np.where(s > c, s ** 2 * np.arccos(np.minimum(c / np.maximum(s, 1e-12), 1.0))
                   - c * np.sqrt(np.maximum(s ** 2 - c ** 2, 0.0)), 0.0)
    return np.pi * s ** 2 - seg


def trapezoid(y, x) -> float:
    """∫ y dx by the trapezoid rule (numpy 2 renamed np.trapz)."""
    return float((getattr(np, "trapezoid", None) or np.trapz)(y, x))


def half_space_room(rho: float, rise: float, c: float) -> float:
    """Per layer, the room around a straight line of anchors `rise` apart, beside a plane c Å
    away (the eroded face of a wide core): ∫ over one rise of (disk − the segment past the
    plane), the disk of the nearest anchor's ball at that height."""
    z = np.linspace(-rise / 2, rise / 2, 20001)
    return trapezoid(cut_disk(np.sqrt(np.maximum(rho ** 2 - z ** 2, 0.0)), c), z)


def anchors(p) -> np.ndarray:
    angle, height = helix.chain_transforms(p)
    ax, ay = p.anchor_xy
    return np.column_stack([np.cos(angle) * ax - np.sin(angle) * ay,
                            np.sin(angle) * ax + np.cos(angle) * ay, height])


def reach(p) -> float:
    x = chain_x(p)
    return (x[p.linker] - x[0]) * (1.0 + p.stretch_tolerance)


def box_push(p, c: np.ndarray, r: float, layers=None) -> np.ndarray:
    """For each centre, the vector that moves its ball out of the nearest layer box it enters
    (zero if it enters none). `layers`: the core's layers (default the fibril's)."""
    hx, hy, hz = p.slab[0] / 2.0, p.slab[1] / 2.0, p.slab[2] / 2.0
    push = np.zeros_like(c)
    worst = np.zeros(len(c))
    for k in (range(p.layers) if layers is None else layers):
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


def layout(p, seed: int = 0, steps: int = 600, R: float | None = None,
           decorated: np.ndarray | None = None) -> np.ndarray | None:
    """A layout at p's linker, or with the centres' reach R (Å) if given. `decorated`: bool per
    chain (helix.chain_layers' order: layer-major), the chains that carry a domain (a mixed
    fibril; default every chain); the others carry none, and the core is every layer's."""
    R = reach(p) if R is None else R
    return _descend(p, decorated, R, seed, steps, range(0, 1), lambda c, r: None,
                    lambda c, a, r: valid(p, c, a, R, r))


def _descend(p, decorated, R: float, seed: int, steps: int, images, core_layers, ok):
    """The descent both layouts share: balls started R out from their anchors (the decorated
    chains' only, if `decorated` is given) with a seeded jitter, pushed apart from each other
    and from every image S^m, m in `images` (range(0, 1): the finite fibril), and out of the
    boxes (of `core_layers(c, r)`, None: the fibril's own), pulled back within R of their
    anchors, until `ok(c, a, r)`; None after `steps`."""
    rng = np.random.default_rng(seed)
    a = anchors(p)
    if decorated is not None:
        a = a[np.asarray(decorated, dtype=bool).ravel()]
        if len(a) == 0:
            return a
    r = p.globule_radius
    out = a.copy()
    out[:, :2] *= 1.0 + R / np.maximum(np.linalg.norm(a[:, :2], axis=1), 1e-9)[:, None]
    c = out + rng.normal(scale=1.0, size=a.shape)
    for _ in range(steps):
        move = np.zeros_like(c)
        for m in images:
            diff = c[:, None] - (screw(p, c, m) if m else c)[None]
            dist = np.linalg.norm(diff, axis=2)
            if m == 0:
                dist = dist + np.eye(len(c)) * 1e9
            over = np.maximum(2 * r * 1.001 - dist, 0.0)
            move += (diff / np.maximum(dist, 1e-9)[..., None] * over[..., None] / 2.0).sum(1)
        c = c + move + box_push(p, c, r * 1.001, core_layers(c, r))
        off = c - a
        n = np.linalg.norm(off, axis=1)
        far = n > R
        c[far] = a[far] + off[far] / n[far, None] * R
        if ok(c, a, r):
            return c
    return None


def shortest(p, longest: int = 40) -> int | None:
    """The shortest linker at which `layout` finds a layout (None up to `longest`)."""
    for L in range(1, longest + 1):
        q = p.replace(linker=L)
        if any(layout(q, seed=s) is not None for s in range(2)):
            return L
    return None


# ---- the infinite fibril: a screw-periodic cell ----------------------------------------------
def screw(p, c: np.ndarray, m: int) -> np.ndarray:
    """Centres c moved by m cells of the infinite fibril (p.layers layers a cell): turned by
    m·layers·twist about the axis and raised by m·layers·rise."""
    ang, dz = m * p.layers * p.twist, m * p.layers * p.rise
    co, si = np.cos(ang), np.sin(ang)
    return np.column_stack([co * c[:, 0] - si * c[:, 1], si * c[:, 0] + co * c[:, 1],
                            c[:, 2] + dz])


def _images(p, R: float, r: float) -> range:
    n = int(np.ceil((2 * R + 2 * r + p.rise) / (p.layers * p.rise))) + 1
    return range(-n, n + 1)


def _core_layers(p, c: np.ndarray, r: float) -> range:
    lo = int(np.floor((c[:, 2].min() - r) / p.rise)) - 1
    hi = int(np.ceil((c[:, 2].max() + r) / p.rise)) + 2
    return range(lo, hi)


def periodic_valid(p, c: np.ndarray, a: np.ndarray, R: float, r: float) -> bool:
    """The exact checks on the infinite fibril: each centre within R of its anchor, every pair
    of balls (a cell's with every image's) at least a diameter apart, and no ball entering any
    layer's box."""
    if (np.linalg.norm(c - a, axis=1) > R + 1e-9).any():
        return False
    for m in _images(p, R, r):
        d = np.linalg.norm(c[:, None] - screw(p, c, m)[None], axis=2)
        if m == 0:
            d = d + np.eye(len(c)) * 1e9
        if (d < 2 * r - 1e-9).any():
            return False
    push = box_push(p, c, r - 1e-9, _core_layers(p, c, r))
    return not (np.linalg.norm(push, axis=1) > 0).any()


def periodic_layout(p, decorated: np.ndarray, R: float, seed: int = 0,
                    steps: int = 400) -> np.ndarray | None:
    """A layout of the infinite fibril whose cell (p.layers × protofilaments, layer-major) has
    these chains decorated, the centres within R of their anchors; None if the descent finds
    none that passes `periodic_valid`."""
    return _descend(p, decorated, R, seed, steps, _images(p, R, p.globule_radius),
                    lambda c, r: _core_layers(p, c, r),
                    lambda c, a, r: periodic_valid(p, c, a, R, r))
