"""Plane geometry of one layer: the core's outline, the anchor, and where the chain starts.

Plain Python and numpy (no bpy), so params.py can validate with it. Everything is in the
layer's frame: Å, the fibril axis at the origin, X/Y across the fibril.

The linker's direction (docs/model/protofilaments.md#protofilaments): the chain leaves the
anchor in a straight line, radially away from the axis as in the tutorial. If a bead or the
globule would then start overlapping the core, it runs along the outward normal of the core's
edge nearest the anchor instead; if that is blocked too, along the free direction closest to
radial (1° steps). If every direction is blocked the parameters are refused.
"""
from __future__ import annotations

import math

import numpy as np

CLEARANCE_SLACK = 1e-6  # Å: a bead exactly touching the core counts as outside


class GeometryError(ValueError):
    """A polygon or layout the model cannot build; params.py turns it into a ParamError."""


def box_outline(width: float, depth: float) -> np.ndarray:
    """The tutorial's slab seen from above: a width × depth rectangle about the axis, CCW."""
    x, y = width / 2.0, depth / 2.0
    return np.array([(-x, -y), (x, -y), (x, y), (-x, y)], dtype=float)


def signed_area(points) -> float:
    """Shoelace area: positive for a counter-clockwise polygon."""
    p = np.asarray(points, dtype=float)
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def counter_clockwise(points) -> np.ndarray:
    p = np.asarray(points, dtype=float)
    return p if signed_area(p) >= 0 else p[::-1].copy()


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def self_intersection(points) -> tuple[int, int] | None:
    """The first pair of edges (i, j) that cross or touch other than at a shared corner, else None.

    Edge i runs from point i to point i + 1 (the last back to the first).
    """
    p = np.asarray(points, dtype=float)
    n = len(p)
    a, b = p, np.roll(p, -1, axis=0)
    scale = max(float(np.abs(p).max(initial=0.0)), 1.0)
    eps = 1e-12 * scale * scale
    for i in range(n):
        j = np.arange(i + 1, n)
        c, d = a[j], b[j]
        r, s = b[i] - a[i], d - c
        denom = _cross(r, s)
        qp = c - a[i]
        adjacent = (j == i + 1) | ((i == 0) & (j == n - 1))
        # proper or touching crossings of non-adjacent edges
        t = np.where(np.abs(denom) > eps, _cross(qp, s) / np.where(denom == 0, 1, denom), np.nan)
        u = np.where(np.abs(denom) > eps, _cross(qp, r) / np.where(denom == 0, 1, denom), np.nan)
        cross = (~adjacent) & (t >= 0) & (t <= 1) & (u >= 0) & (u <= 1)
        # collinear overlaps (also adjacent edges folding back onto each other)
        collinear = (np.abs(denom) <= eps) & (np.abs(_cross(qp, r)) <= eps)
        rr = float(r @ r) or 1.0
        t0 = (qp @ r) / rr
        t1 = ((d - a[i]) @ r) / rr
        lo, hi = np.minimum(t0, t1), np.maximum(t0, t1)
        overlap = np.minimum(hi, 1.0) - np.maximum(lo, 0.0)
        folded = collinear & (overlap > 1e-9)
        hit = np.flatnonzero(cross | folded)
        if hit.size:
            return i, int(j[hit[0]])
    return None


def clean_outline(points) -> np.ndarray:
    """Validate a closed polygon: at least 3 distinct corners, finite, no zero area, not
    self-intersecting. A repeated first point at the end (an explicitly closed ring) is dropped.
    Returns the corners as given (n, 2); raises GeometryError saying what is wrong."""
    try:
        p = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise GeometryError("must be a list of [x, y] points in Å") from None
    if p.ndim != 2 or p.shape[1] != 2:
        raise GeometryError(f"must be a list of [x, y] points in Å (got shape {list(p.shape)})")
    if not np.isfinite(p).all():
        raise GeometryError("has a point that is not a finite number")
    if len(p) > 1 and np.array_equal(p[0], p[-1]):
        p = p[:-1]
    if len(p) < 3:
        raise GeometryError(f"needs at least 3 points (got {len(p)})")
    step = np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)
    if (step < 1e-9).any():
        i = int(np.argmax(step < 1e-9))
        raise GeometryError(f"repeats point {i} ({p[i, 0]:g}, {p[i, 1]:g}) twice in a row")
    crossing = self_intersection(p)
    if crossing is not None:
        i, j = crossing
        raise GeometryError(f"intersects itself: edge {i} (point {i} to {(i + 1) % len(p)}) "
                            f"meets edge {j} (point {j} to {(j + 1) % len(p)})")
    if abs(signed_area(p)) < 1e-9:
        raise GeometryError("encloses no area")
    return p


CHUNK = 4096  # points per block of the (points × edges) arrays: they stay in the cache


def _crossings(a, b, qy):
    """Where each edge (a → b) crosses the horizontal line(s) qy, and whether it does."""
    straddles = (a[:, 1] > qy) != (b[:, 1] > qy)
    dy = np.where(b[:, 1] == a[:, 1], 1.0, b[:, 1] - a[:, 1])
    return straddles, a[:, 0] + (qy - a[:, 1]) * (b[:, 0] - a[:, 0]) / dy


def even_odd(points, xy) -> np.ndarray:
    """Whether each point of `xy` (m, 2) is inside the polygon by the even-odd rule (a point on
    the boundary may fall either way: `inside` excludes it). Points that share a y (a grid's
    rows) share the edges' crossings: those are found once per row and counted by a sorted
    search, the same crossings and the same count as the test of every point on every edge."""
    poly = np.asarray(points, dtype=float)
    q = np.atleast_2d(np.asarray(xy, dtype=float))
    a, b = poly, np.roll(poly, -1, axis=0)
    rows, row_of = np.unique(q[:, 1], return_inverse=True)
    row_of = row_of.reshape(-1)
    if 4 * len(rows) <= len(q):
        out = np.zeros(len(q), bool)
        order = np.argsort(row_of, kind="stable")
        bounds = np.searchsorted(row_of[order], np.arange(len(rows) + 1))
        for r, y in enumerate(rows):
            straddles, x_cross = _crossings(a, b, y)
            x_cross = np.sort(x_cross[straddles])
            idx = order[bounds[r]:bounds[r + 1]]
            right = len(x_cross) - np.searchsorted(x_cross, q[idx, 0], side="right")
            out[idx] = right % 2 == 1  # crossings with qx < x_cross
        return out
    out = np.empty(len(q), bool)
    for lo in range(0, len(q), CHUNK):
        qx, qy = q[lo:lo + CHUNK, 0:1], q[lo:lo + CHUNK, 1:2]
        straddles, x_cross = _crossings(a, b, qy)
        out[lo:lo + CHUNK] = (straddles & (qx < x_cross)).sum(axis=1) % 2 == 1
    return out


def near_edges(points, xy, dist: float) -> np.ndarray:
    """Whether each point of `xy` (m, 2) lies within `dist` (+1e-6) of some edge's bounding
    box: a point for which this is False is farther than `dist` from the boundary (an edge is
    no nearer than its box), so the exact distance is needed only where it is True."""
    poly = np.asarray(points, dtype=float)
    q = np.atleast_2d(np.asarray(xy, dtype=float))
    a, b = poly, np.roll(poly, -1, axis=0)
    pad = dist + 1e-6
    lo, hi = np.minimum(a, b) - pad, np.maximum(a, b) + pad
    out = np.empty(len(q), bool)
    for k in range(0, len(q), CHUNK):
        qx, qy = q[k:k + CHUNK, 0:1], q[k:k + CHUNK, 1:2]
        out[k:k + CHUNK] = ((qx > lo[:, 0]) & (qx < hi[:, 0])
                            & (qy > lo[:, 1]) & (qy < hi[:, 1])).any(axis=1)
    return out


def inside(points, xy) -> np.ndarray:
    """Whether each point of `xy` (m, 2) lies strictly inside the polygon (even-odd rule). The
    boundary's distance (> 1e-9) is measured only for the points inside by the even-odd rule
    near an edge (near_edges): the others are farther from it than 1e-6."""
    poly = np.asarray(points, dtype=float)
    q = np.atleast_2d(np.asarray(xy, dtype=float))
    out = even_odd(poly, q)
    idx = np.nonzero(out)[0]
    idx = idx[near_edges(poly, q[idx], 1e-9)]
    if len(idx):
        out[idx] = edge_distance(poly, q[idx])[0] > 1e-9
    return out


def inside_by(points, xy, margin: float) -> np.ndarray:
    """Whether each point of `xy` (m, 2) is inside the polygon by the even-odd rule and at
    least `margin` from its boundary (as even_odd & (edge_distance >= margin); the distance
    measured only where near_edges says it may be less)."""
    poly = np.asarray(points, dtype=float)
    q = np.atleast_2d(np.asarray(xy, dtype=float))
    out = even_odd(poly, q)
    idx = np.nonzero(out)[0]
    idx = idx[near_edges(poly, q[idx], margin)]
    if len(idx):
        out[idx] = edge_distance(poly, q[idx])[0] >= margin
    return out


def _nearest_points(poly: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each point of q (m, 2), the nearest point on every edge (m, n, 2) and its distance."""
    a, b = poly, np.roll(poly, -1, axis=0)
    ab = b - a
    t = ((q[:, None, :] - a[None]) * ab[None]).sum(-1) / (ab * ab).sum(-1)[None]
    t = np.clip(t, 0.0, 1.0)
    nearest = a[None] + t[..., None] * ab[None]
    return nearest, np.linalg.norm(q[:, None, :] - nearest, axis=-1)


def edge_distance(points, xy) -> tuple[np.ndarray, np.ndarray]:
    """Distance from each point of `xy` (m, 2) to the polygon's boundary, and the nearest edge
    (in blocks of CHUNK points)."""
    poly = np.asarray(points, dtype=float)
    q = np.atleast_2d(np.asarray(xy, dtype=float))
    out, edge = np.empty(len(q)), np.empty(len(q), dtype=np.intp)
    for lo in range(0, len(q), CHUNK):
        _, dist = _nearest_points(poly, q[lo:lo + CHUNK])
        e = dist.argmin(axis=1)
        out[lo:lo + CHUNK], edge[lo:lo + CHUNK] = dist[np.arange(len(e)), e], e
    return out, edge


def nearest_on_boundary(points, xy) -> tuple[np.ndarray, np.ndarray]:
    """The point of the polygon's boundary nearest to one point `xy`, and the outward unit
    normal of the edge it lies on."""
    poly = np.asarray(points, dtype=float)
    nearest, dist = _nearest_points(poly, np.atleast_2d(np.asarray(xy, dtype=float)))
    edge = int(dist[0].argmin())
    return nearest[0, edge], outward_normal(poly, edge)


def outward_normal(points, edge: int) -> np.ndarray:
    """Unit normal of edge `edge` (point edge to edge + 1, as given) pointing out of the polygon."""
    poly = np.asarray(points, dtype=float)
    a, b = poly[edge], poly[(edge + 1) % len(poly)]
    d = (b - a) / np.linalg.norm(b - a)
    right = np.array([d[1], -d[0]])  # outside of a counter-clockwise edge
    return right if signed_area(poly) > 0 else -right


def blocked(points, xy, radii) -> np.ndarray:
    """Whether each sphere (centre xy, radius) starts inside or overlapping the core."""
    dist, _ = edge_distance(points, xy)
    return inside(points, xy) | (dist < np.asarray(radii, float) - CLEARANCE_SLACK)


def rotate(xy, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    q = np.asarray(xy, dtype=float)
    return np.stack([c * q[..., 0] - s * q[..., 1], s * q[..., 0] + c * q[..., 1]], axis=-1)


def linker_direction(outline, anchor, offsets, radii, copies=(0.0,)) -> tuple[np.ndarray, str]:
    """Unit direction of the chain from `anchor`, and the rule that chose it ("radial",
    "edge normal", "nearest free"). `copies`: angles of the other protofilaments' copies of
    the chain, all of which must be clear of the core too. Raises GeometryError if none is."""
    anchor = np.asarray(anchor, dtype=float)
    active_t, active_r = np.asarray(offsets)[1:], np.asarray(radii)[1:]

    def clear(u):
        pts = anchor[None] + active_t[:, None] * u[None]
        return not any(blocked(outline, rotate(pts, a), active_r).any() for a in copies)

    r = math.hypot(*anchor)
    radial = anchor / r if r > 1e-9 else np.array([1.0, 0.0])
    if clear(radial):
        return radial, "radial"
    _, edge = edge_distance(outline, anchor[None])
    normal = outward_normal(outline, int(edge[0]))
    if clear(normal):
        return normal, "edge normal"
    base = math.atan2(radial[1], radial[0])
    for step in range(1, 181):
        for sign in (1, -1):
            a = base + sign * math.radians(step)
            u = np.array([math.cos(a), math.sin(a)])
            if clear(u):
                return u, "nearest free"
    raise GeometryError("no straight direction from the anchor keeps the linker and the "
                        "globule outside the core")


def _convex_at(poly: np.ndarray, i: int) -> bool:
    """Whether corner i of a counter-clockwise polygon turns left (or goes straight)."""
    a, b, c = poly[i - 1], poly[i], poly[(i + 1) % len(poly)]
    return float(_cross(b - a, c - b)) >= -1e-9


def is_convex(poly) -> bool:
    """Whether a counter-clockwise polygon turns left (or goes straight) at every corner."""
    poly = np.asarray(poly, float)
    return all(_convex_at(poly, i) for i in range(len(poly)))


def convex_pieces(points, triangles) -> list[np.ndarray]:
    """Cover a polygon with convex pieces: the triangles of its triangulation (index triples
    into `points`, e.g. from mathutils.geometry.tessellate_polygon), merged across shared edges
    while the union stays convex (Hertel-Mehlhorn: at most 4× the fewest pieces). Each piece
    is counter-clockwise, (m, 2)."""
    pts = counter_clockwise(points) if signed_area(points) < 0 else np.asarray(points, float)
    flip = signed_area(points) < 0
    n = len(pts)
    pieces = []
    for tri in triangles:
        idx = [n - 1 - i for i in tri] if flip else list(tri)
        if signed_area(pts[idx]) < 0:
            idx = idx[::-1]
        pieces.append(idx)
    merged = True
    while merged:
        merged = False
        for a in range(len(pieces)):
            for b in range(a + 1, len(pieces)):
                joined = _join(pieces[a], pieces[b])
                if joined is not None and is_convex(pts[joined]):
                    pieces[a] = joined
                    del pieces[b]
                    merged = True
                    break
            if merged:
                break
    return [pts[p] for p in pieces]


def _join(p: list, q: list) -> list | None:
    """The union of two counter-clockwise index polygons sharing an edge (u, v) in p and
    (v, u) in q, as one index polygon; None if they share no edge."""
    for i in range(len(p)):
        u, v = p[i], p[(i + 1) % len(p)]
        for j in range(len(q)):
            if q[j] == v and q[(j + 1) % len(q)] == u:
                # p from v round to u, then q's corners strictly between u and v
                p_part = [p[(i + 1 + k) % len(p)] for k in range(len(p))]  # v ... u
                q_part = [q[(j + 2 + k) % len(q)] for k in range(len(q) - 2)]
                return p_part + q_part
    return None
