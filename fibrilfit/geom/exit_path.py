"""The shortest path a chain can take from a buried residue to the surface of the core, clear
of the core's atoms (docs/model/buried-terminus.md#method). Plain numpy.

A bead of radius `bead_radius` (the model's residue) may stand where it overlaps no atom's van
der Waals sphere: its centre at least `bead_radius + r_atom` from every atom. The free centres
are the voxels of a grid (`step` Å) through which the bead's centre travels; the path is the
shortest one in the grid's 26-neighbour graph from the start to any free voxel whose (x, y) lies
outside the core's outline (Dijkstra, in Dial's bucket form: buckets one `step` wide, the least
edge, so every voxel of a bucket is final when it is reached and a bucket is relaxed at once
with numpy), then pulled taut (a corner is cut wherever the straight segment stays clear).
The layers above and below are a stack: the grid spans `z_half` Å about the start and its top
and bottom are walls, so the path cannot leave through the end of a finite model.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from . import polygons

STEP = 0.25  # Å per voxel: at 0.5 Å the lattice misses 5OQV's channel, which 0.25 finds
# (17.8 Å; docs/model/buried-terminus.md#method)
SAMPLE = 0.25  # Å between the points a straight segment is checked at
MAX_LENGTH = 40.0  # Å: no path is searched farther (then: none found within it)


@dataclass
class ExitPath:
    """The shortest clear path from `start` to the surface, or none (`found` False)."""

    found: bool
    length: float  # Å along the path (inf when none)
    points: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))  # (k, 3) start first
    depth: float = 0.0  # Å: the start's straight distance to the outline (0 when outside it)

    @property
    def exit_point(self) -> np.ndarray | None:
        return self.points[-1] if self.found else None


def residues_spent(length: float, spacing: float) -> int:
    """Residues a path of `length` Å costs the chain beyond the anchor: the anchor's own bead
    stands up to one spacing from its CA (as every surface anchor's bead does, one bead radius
    outside the outline), each further `spacing` Å is one residue: ceil(length / spacing) - 1,
    at least 0 (docs/model/buried-terminus.md#counting)."""
    if not math.isfinite(length):
        raise ValueError("no path: no count")
    return max(0, math.ceil(length / spacing - 1e-9) - 1)


def _offsets() -> tuple[np.ndarray, np.ndarray]:
    off = np.array([o for o in itertools.product((-1, 0, 1), repeat=3) if any(o)])
    return off, np.linalg.norm(off, axis=1)


def _clear(points: np.ndarray, atoms: np.ndarray, reach: np.ndarray) -> np.ndarray:
    """Whether each point (k, 3) is at least reach[i] from atom i, for every atom."""
    out = np.ones(len(points), bool)
    for lo in range(0, len(points), 256):
        d = np.linalg.norm(points[lo:lo + 256, None] - atoms[None], axis=-1)
        out[lo:lo + 256] = (d >= reach[None] - 1e-9).all(axis=1)
    return out


def _segment_clear(a, b, atoms, reach) -> bool:
    n = max(2, int(math.ceil(np.linalg.norm(b - a) / SAMPLE)) + 1)
    t = np.linspace(0.0, 1.0, n)[:, None]
    r = float(reach.max(initial=0.0))
    near = ((atoms >= np.minimum(a, b) - r) & (atoms <= np.maximum(a, b) + r)).all(axis=1)
    return bool(_clear(a + t * (b - a), atoms[near], reach[near]).all())


BOXES = (6.0, 12.0, 24.0)  # Å: the half-widths searched first (a shorter path stays in them)


def shortest_exit(atoms, radii, start, outline, *, bead_radius: float, z_half: float,
                  step: float = STEP, max_length: float = MAX_LENGTH) -> ExitPath:
    """The shortest path of a bead's centre from `start` (3,) to the surface: a point outside
    `outline` (k, 2) in (x, y), every point of the way at least bead_radius + radii[i] from
    atoms[i] (n, 3). The start itself is not checked (it is the anchor's CA, which its own
    neighbours touch: leave them out of `atoms`). Searched in boxes of growing half-width about
    the start (a path no longer than the half-width cannot leave its box, so the first box
    whose shortest path is no longer than it gives the shortest of all), up to `max_length`;
    z_half Å about the start in z, walled there."""
    found = None
    for box in [b for b in BOXES if b < max_length] + [max_length]:
        found, enclosed = _in_box(atoms, radii, start, outline, bead_radius=bead_radius,
                                  z_half=z_half, step=step, box=box)
        if found.found and found.length <= box:
            return found
        if enclosed:  # every voxel the start reaches is searched and none touches the box's
            break     # sides: a larger box holds the same room, and no way out either
    return found if found.found and found.length <= max_length else \
        ExitPath(False, math.inf, np.zeros((0, 3)), found.depth)


def _in_box(atoms, radii, start, outline, *, bead_radius: float, z_half: float,
            step: float, box: float) -> tuple[ExitPath, bool]:
    """shortest_exit's search in a box of half-width `box` about the start, and whether no way
    out was found with every voxel the start reaches searched, none of them on the box's sides
    (the room is enclosed: a larger box finds none either)."""
    atoms = np.asarray(atoms, float).reshape(-1, 3)
    reach = np.asarray(radii, float).reshape(-1) + bead_radius
    start = np.asarray(start, float)
    poly = np.asarray(outline, float)
    depth = float(polygons.edge_distance(poly, start[None, :2])[0][0]) \
        if polygons.inside(poly, start[None, :2])[0] else 0.0
    if depth == 0.0:
        return ExitPath(True, 0.0, start[None].copy(), 0.0), False
    margin = float(reach.max(initial=bead_radius)) + 2 * step
    lo_xy = np.maximum(np.minimum(poly.min(axis=0), start[:2]) - margin, start[:2] - box)
    hi_xy = np.minimum(np.maximum(poly.max(axis=0), start[:2]) + margin, start[:2] + box)
    # the grid aligned on the start: the start is a voxel centre
    lo = np.array([*(start[:2] - np.ceil((start[:2] - lo_xy) / step) * step),
                   start[2] - math.floor(z_half / step) * step])
    hi = np.array([*(start[:2] + np.ceil((hi_xy - start[:2]) / step) * step),
                   start[2] + math.floor(z_half / step) * step])
    shape = tuple(int(v) for v in np.rint((hi - lo) / step).astype(int) + 1)
    free = np.ones(shape, bool)
    near = ((np.abs(atoms[:, 2] - start[2]) <= z_half + reach)
            & (atoms[:, :2] >= lo[None, :2] - reach[:, None]).all(axis=1)
            & (atoms[:, :2] <= hi[None, :2] + reach[:, None]).all(axis=1))
    _stamp_blocked(free, atoms[near], reach[near], lo, step)
    free[:, :, 0] = free[:, :, -1] = False  # the walls of the stack
    s_idx = tuple(int(v) for v in np.rint((start - lo) / step))
    free[s_idx] = True
    gx = lo[0] + step * np.arange(shape[0])
    gy = lo[1] + step * np.arange(shape[1])
    xy = np.stack(np.meshgrid(gx, gy, indexing="ij"), axis=-1).reshape(-1, 2)
    outside = ~polygons.inside(poly, xy).reshape(shape[:2])
    goal = free & outside[:, :, None]
    dist, end = _dial(free, goal, s_idx, step, 4 * box)
    if end is None:  # dist: the distances searched when the search ran out, else None
        enclosed = dist is not None and not any(
            np.isfinite(f).any() for f in (dist[0], dist[-1], dist[:, 0], dist[:, -1]))
        return ExitPath(False, math.inf, np.zeros((0, 3)), depth), enclosed
    cells = _descend(dist, end, s_idx, step)
    pts = lo + step * np.asarray(cells, float)
    pts[0] = start
    pts = _taut(pts, atoms[near], reach[near])
    length = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())
    return ExitPath(True, length, pts, depth), False


def _stamp_blocked(free: np.ndarray, atoms: np.ndarray, reach: np.ndarray, lo, step) -> None:
    """Mark False every voxel whose centre lies within reach[i] of atoms[i]. Offsets surely
    inside a ball (by more than half a cell's diagonal) are marked without a test, those near
    its surface tested exactly; on a grid padded by the ball, by flat index."""
    if not len(atoms):
        return
    half = step * math.sqrt(3.0) / 2.0
    kmax = int(math.ceil(reach.max() / step)) + 1  # the widest ball's half-width in cells
    pad = 2 * kmax + 1
    big = np.ones(tuple(n + 2 * pad for n in free.shape), bool)
    strides = np.array([big.shape[1] * big.shape[2], big.shape[2], 1])
    flat = big.reshape(-1)
    centres = np.rint((atoms - lo) / step).astype(int)
    # an atom farther than a ball outside the grid cannot reach into it
    keep = ((centres >= -kmax) & (centres < np.array(free.shape) + kmax)).all(axis=1)
    atoms, reach, centres = atoms[keep], reach[keep], centres[keep]
    base = (centres + pad) @ strides
    frac = atoms - (lo + step * centres)  # the atom from its voxel's centre, |frac| <= half
    for r in np.unique(np.round(reach, 3)):
        pick = np.isclose(reach, r, atol=1e-3)
        k = int(math.ceil(r / step)) + 1
        g = np.arange(-k, k + 1)
        ball = np.stack(np.meshgrid(g, g, g, indexing="ij"), axis=-1).reshape(-1, 3)
        norm = np.linalg.norm(ball, axis=1) * step
        inner, shell = ball[norm < r - half - 1e-6], ball[(norm >= r - half - 1e-6)
                                                          & (norm < r + half)]
        inner_at, shell_at = inner @ strides, shell @ strides
        b_all, f_all = base[pick], frac[pick]
        for lo_a in range(0, len(b_all), 64):
            flat[(b_all[lo_a:lo_a + 64, None] + inner_at[None]).reshape(-1)] = False
        # |step * shell - frac| by axis: each axis's squared offsets (atoms, 2k + 1), gathered
        # and summed in norm's order (x + y) + z: the same distances, a third of the work
        at = step * g
        for lo_a in range(0, len(b_all), 128):
            b = b_all[lo_a:lo_a + 128]
            f = f_all[lo_a:lo_a + 128]
            sq = [(at[None] - f[:, c:c + 1]) ** 2 for c in range(3)]
            d = np.sqrt(sq[0][:, shell[:, 0] + k] + sq[1][:, shell[:, 1] + k]
                        + sq[2][:, shell[:, 2] + k])
            hit = d < r - 1e-9
            flat[(b[:, None] + shell_at[None])[hit]] = False
    free &= big[pad:-pad, pad:-pad, pad:-pad]


def _dial(free, goal, s_idx, step, max_length):
    """Distances from s_idx over free voxels (26 neighbours, Euclidean steps), bucket by bucket
    of one `step` (the least edge: a bucket's voxels are final when it is taken); stops at the
    first bucket holding a goal voxel. Returns (distances, the nearest goal's index); (the
    distances, None) when every voxel the start reaches is taken and none is a goal; (None,
    None) when the search stops at max_length. Only the open voxels (reached, not yet final)
    are looked at, by flat index on a grid padded by one closed voxel (no bounds to test)."""
    off, w = _offsets()
    pshape = tuple(n + 2 for n in free.shape)
    strides = np.array([pshape[1] * pshape[2], pshape[2], 1])
    open_ok = np.zeros(pshape, bool)
    open_ok[1:-1, 1:-1, 1:-1] = free
    open_ok = open_ok.reshape(-1)  # free and not yet final
    is_goal = np.zeros(pshape, bool)
    is_goal[1:-1, 1:-1, 1:-1] = goal
    is_goal = is_goal.reshape(-1)
    dist = np.full(pshape, np.inf)
    flat = dist.reshape(-1)
    start = int((np.asarray(s_idx) + 1) @ strides)
    flat[start] = 0.0
    steps, hops = off @ strides, w * step
    front = np.array([start])  # reached (finite distance), not final
    k = 0
    while k * step <= max_length:
        if not len(front):
            return dist[1:-1, 1:-1, 1:-1], None  # nothing left to reach: sealed
        in_band = flat[front] < (k + 1) * step - 1e-9
        if not in_band.any():
            k += 1
            continue
        band = np.sort(front[in_band])  # the order of the grid's voxels
        front = front[~in_band]
        open_ok[band] = False
        at_goal = band[is_goal[band]]
        if len(at_goal):
            best = at_goal[np.argmin(flat[at_goal])]
            return dist[1:-1, 1:-1, 1:-1], tuple(int(v) - 1 for v in
                                                  np.unravel_index(best, pshape))
        base = flat[band]
        touched = [front]
        for o, h in zip(steps, hops):
            nb = band + o
            keep = open_ok[nb]
            nb = nb[keep]
            np.minimum.at(flat, nb, base[keep] + h)
            touched.append(nb)
        front = np.unique(np.concatenate(touched))
        k += 1
    return None, None


def _descend(dist, end, s_idx, step) -> list:
    """The voxels from the start to `end`: back from `end` along neighbours whose distance plus
    the step equals its own (the shortest path's predecessors)."""
    off, w = _offsets()
    path, cur = [end], np.array(end)
    while tuple(cur) != s_idx:
        best, best_d = None, math.inf
        for o, wo in zip(off, w):
            nb = cur + o
            if (nb < 0).any() or (nb >= dist.shape).any():
                continue
            d = dist[tuple(nb)]
            if abs(d + wo * step - dist[tuple(cur)]) < 1e-6 and d < best_d:
                best, best_d = nb, d
        cur = best
        path.append(tuple(int(v) for v in cur))
    return path[::-1]


def _taut(pts: np.ndarray, atoms: np.ndarray, reach: np.ndarray) -> np.ndarray:
    """The path pulled taut: from each kept point, straight to the farthest later point whose
    segment stays clear of the atoms (the start's own segment is allowed its first voxel)."""
    out, i = [pts[0]], 0
    while i < len(pts) - 1:
        j = len(pts) - 1
        while j > i + 1 and not _segment_clear(pts[i] if i else pts[1], pts[j], atoms, reach):
            j -= 1
        out.append(pts[j])
        i = j
    return np.array(out)
