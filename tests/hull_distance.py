"""The distance between two convex hulls, for tests, by a method that shares nothing with
fibrilfit.analysis.exact.hull_distance (GJK): qhull (scipy.spatial.ConvexHull) builds the
Minkowski difference A - B of the two point sets, and the distance is the distance from the
origin to that polytope: 0 when the origin lies inside (the hulls meet), else the least distance
to its boundary triangles (a face's plane where the origin's projection falls inside it, else the
nearest point of its edges)."""
import numpy as np
from scipy.spatial import ConvexHull


def _corners(x: np.ndarray) -> np.ndarray:
    x = np.asarray(x, float).reshape(-1, 3)
    if len(x) < 5:
        return x
    return x[ConvexHull(x).vertices]


def _segments(o, a, b) -> np.ndarray:
    """Distance from point o to each segment a[i]-b[i]."""
    ab = b - a
    t = np.clip(np.einsum("ij,ij->i", o - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab),
                                                               1e-300), 0.0, 1.0)
    return np.linalg.norm(a + t[:, None] * ab - o, axis=1)


def hull_distance_qhull(a, b, tol: float = 1e-9) -> float:
    """Euclidean distance (Å) between the convex hulls of point sets a and b; 0.0 when they meet."""
    d = (_corners(a)[:, None, :] - _corners(b)[None, :, :]).reshape(-1, 3)
    hull = ConvexHull(d)
    normals, offsets = hull.equations[:, :3], hull.equations[:, 3]  # n.x + c <= 0 inside
    if (offsets <= tol).all():  # the origin is inside (or on) every facet: the hulls meet
        return 0.0
    o = np.zeros(3)
    tri = d[hull.simplices]  # (faces, 3, 3)
    best = np.inf
    # the origin's projection on each face's plane, kept where it lies inside the triangle
    proj = -offsets[:, None] * normals  # o - (n.o + c) n with o = 0
    v0, v1, v2 = tri[:, 0], tri[:, 1], tri[:, 2]
    e0, e1, w = v1 - v0, v2 - v0, proj - v0
    d00, d01, d11 = (np.einsum("ij,ij->i", e0, e0), np.einsum("ij,ij->i", e0, e1),
                     np.einsum("ij,ij->i", e1, e1))
    d20, d21 = np.einsum("ij,ij->i", w, e0), np.einsum("ij,ij->i", w, e1)
    den = d00 * d11 - d01 * d01
    ok = np.abs(den) > 1e-300
    u = np.where(ok, (d11 * d20 - d01 * d21) / np.where(ok, den, 1), -1)
    v = np.where(ok, (d00 * d21 - d01 * d20) / np.where(ok, den, 1), -1)
    inside = ok & (u >= 0) & (v >= 0) & (u + v <= 1)
    if inside.any():
        best = float(np.abs(offsets[inside]).min())
    edges = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    return min(best, float(_segments(o, edges[:, 0], edges[:, 1]).min()))
