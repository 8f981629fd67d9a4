"""The outline of a set of atoms projected on a plane: a tight polygon (atoms' radii, small
crevices closed), not a bounding box. numpy only: a raster closing, then a boundary trace."""
from __future__ import annotations

import numpy as np

from ..geom import polygons

STEP = 0.5  # Å per raster cell
CLOSE = 2.5  # Å: crevices narrower than about twice this are closed
SIMPLIFY = 0.5  # Å: largest distance of a dropped outline point from the polygon
# the 8 neighbours, clockwise from west (x right, y up)
_RING = [(-1, 0), (-1, 1), (0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1)]


def _disk(radius_cells: float) -> np.ndarray:
    r = int(np.ceil(radius_cells))
    i, j = np.mgrid[-r:r + 1, -r:r + 1]
    keep = i * i + j * j <= radius_cells * radius_cells
    return np.stack([i[keep], j[keep]], axis=1)


def _stamp(mask: np.ndarray, centres: np.ndarray, radius_cells: float, value: bool) -> None:
    if len(centres) == 0:
        return
    cells = (centres[:, None, :] + _disk(radius_cells)[None, :, :]).reshape(-1, 2)
    ok = ((cells >= 0) & (cells < mask.shape)).all(axis=1)
    mask[cells[ok, 0], cells[ok, 1]] = value


def _grow(seed: np.ndarray, allowed: np.ndarray) -> np.ndarray:
    """Flood fill (4-connected) from seed inside allowed."""
    region = seed & allowed
    while True:
        grown = region.copy()
        grown[1:] |= region[:-1]
        grown[:-1] |= region[1:]
        grown[:, 1:] |= region[:, :-1]
        grown[:, :-1] |= region[:, 1:]
        grown &= allowed
        if (grown == region).all():
            return region
        region = grown


def _boundary(mask: np.ndarray) -> np.ndarray:
    inner = mask.copy()
    inner[1:-1, 1:-1] = (mask[1:-1, 1:-1] & mask[:-2, 1:-1] & mask[2:, 1:-1]
                         & mask[1:-1, :-2] & mask[1:-1, 2:])
    return np.argwhere(mask & ~inner)


def _trace(mask: np.ndarray) -> list:
    """Moore-neighbour trace of the outer boundary of one 8-connected region (cells)."""
    cells = np.argwhere(mask)
    p0 = tuple(cells[np.lexsort((cells[:, 1], cells[:, 0]))[0]])  # smallest x, then y
    p, b, out = p0, (p0[0] - 1, p0[1]), [p0]
    for _ in range(8 * int(mask.sum()) + 8):
        bdir = _RING.index((b[0] - p[0], b[1] - p[1]))
        for k in range(1, 9):
            d = (bdir + k) % 8
            q = (p[0] + _RING[d][0], p[1] + _RING[d][1])
            if mask[q]:
                break
        else:
            return out  # a single cell
        if p == p0 and len(out) > 1 and q == out[1]:
            return out[:-1]  # the first step again: closed
        prev = _RING[(d - 1) % 8]
        b, p = (p[0] + prev[0], p[1] + prev[1]), q
        out.append(p)
    return out


def _simplify(points: np.ndarray, tol: float) -> np.ndarray:
    """Ramer-Douglas-Peucker on a closed polygon."""
    n = len(points)
    if n < 4:
        return points
    far = int(np.argmax(np.linalg.norm(points - points[0], axis=1)))
    keep = np.zeros(n + 1, bool)
    keep[[0, far, n]] = True
    closed = np.vstack([points, points[:1]])
    stack = [(0, far), (far, n)]
    while stack:
        i, j = stack.pop()
        if j <= i + 1:
            continue
        a, b = closed[i], closed[j]
        seg = b - a
        rel = closed[i + 1:j] - a
        length = np.linalg.norm(seg)
        dist = (np.abs(seg[0] * rel[:, 1] - seg[1] * rel[:, 0]) / length if length > 1e-9
                else np.linalg.norm(rel, axis=1))
        k = int(np.argmax(dist))
        if dist[k] > tol:
            keep[i + 1 + k] = True
            stack += [(i, i + 1 + k), (i + 1 + k, j)]
    return closed[keep][:-1]


def polygon(xy: np.ndarray, radii: np.ndarray, *, step: float = STEP, close: float = CLOSE,
            tol: float = SIMPLIFY):
    """Counter-clockwise outline (k, 2) of the disks (xy, radii) closed by `close` Å, and the
    fraction of atoms outside it (other, separate pieces; 0 when the section is one piece)."""
    pad = radii.max() + close + 3 * step
    lo = xy.min(axis=0) - pad
    shape = tuple((np.ceil((xy.max(axis=0) + pad - lo) / step)).astype(int) + 1)
    centres = np.rint((xy - lo) / step).astype(int)
    grown = np.zeros(shape, bool)
    for r in np.unique(radii):
        _stamp(grown, centres[radii == r], (r + close) / step, True)
    border = np.zeros(shape, bool)
    border[[0, -1], :] = border[:, [0, -1]] = True
    outside = _grow(border, ~grown)
    solid = ~outside  # holes filled
    _stamp(solid, _boundary(outside), close / step, False)  # erode back: a closing
    solid[[0, -1], :] = solid[:, [0, -1]] = False
    # the piece holding most atoms
    piece, best, left = None, -1, solid.copy()
    while left.any():
        seed = np.zeros(shape, bool)
        seed[tuple(np.argwhere(left)[0])] = True
        region = _grow(seed, left)
        left &= ~region
        count = int(region[centres[:, 0], centres[:, 1]].sum())
        if count > best:
            piece, best = region, count
    stray = 1.0 - best / len(xy) if len(xy) else 0.0
    cells = np.array(_trace(piece), float)
    pts = _simplify(cells * step + lo, tol)
    return polygons.counter_clockwise(pts), stray

