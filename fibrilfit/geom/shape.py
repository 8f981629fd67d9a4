"""A domain's real shape in its body frame (domain.body_frame): the atoms that make its grown
convex hull, a few covering spheres, and the joint (the terminal residue's CA). numpy only.

docs/model/domain-shapes.md#hull explains the construction and its measured departure.
"""
from __future__ import annotations

import math

import numpy as np

# Directions over which an atom must be outermost somewhere to be kept for the hull. Between two
# of these 20,000 directions (< 1.6° apart) an atom left out reaches past the kept ones by at most
# (extent · angle²)/2 < 0.01 Å for a 60 Å domain; GROW_SLACK covers it.
SUPPORT_DIRECTIONS = 20_000
GROW_SLACK = 0.01  # Å
SPHERES = 16  # covering spheres of the `spheres` shape (docs/model/domain-shapes.md#spheres)
KMEANS_ROUNDS = 50


def directions(n: int) -> np.ndarray:
    """n unit vectors spread evenly over the sphere (a Fibonacci lattice), (n, 3)."""
    i = np.arange(n) + 0.5
    z = 1.0 - 2.0 * i / n
    phi = i * math.pi * (3.0 - math.sqrt(5.0))
    r = np.sqrt(np.maximum(0.0, 1.0 - z * z))
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def icosphere(subdivisions: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Unit icosphere: vertices (n, 3) and triangles (f, 3), outward. 1 subdivision: 42, 80."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    verts = [np.array(p, float) / np.linalg.norm(p) for p in v]
    for _ in range(subdivisions):
        mid, faces = {}, []

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                p = verts[a] + verts[b]
                verts.append(p / np.linalg.norm(p))
                mid[key] = len(verts) - 1
            return mid[key]
        for a, b, c in f:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = faces
    return np.array(verts), np.array(f)


def inradius(verts: np.ndarray, faces: np.ndarray) -> float:
    """The smallest distance from the origin to a face plane of a convex polyhedron."""
    a, b, c = verts[faces[:, 0]], verts[faces[:, 1]], verts[faces[:, 2]]
    n = np.cross(b - a, c - a)
    return float(np.min(np.abs((n * a).sum(1)) / np.linalg.norm(n, axis=1)))


# Each kept atom becomes these 42 points at radius (r + grow): the hull of a 42-point icosphere
# holds the unit ball once scaled by 1/inradius (0.934: 7.1 % more), so every atom's ball is inside
# and no point lies more than `grow` (0.12 Å for carbon's 1.7 Å) outside the atoms' grown hull.
ICO_VERTS, ICO_FACES = icosphere(1)
ICO_INRADIUS = inradius(ICO_VERTS, ICO_FACES)


def grow(radius) -> np.ndarray:
    """How far (Å) each kept atom's points sit beyond its van der Waals radius."""
    return np.asarray(radius, float) * (1.0 / ICO_INRADIUS - 1.0) + GROW_SLACK


def hull_atoms(local, radii, n: int = SUPPORT_DIRECTIONS) -> np.ndarray:
    """The atoms [x, y, z, r] that are outermost (a·u + r largest) in some of n directions: the
    ones whose balls make the grown convex hull. In input order."""
    local = np.asarray(local, float).reshape(-1, 3)
    radii = np.broadcast_to(np.asarray(radii, float), (len(local),))
    keep = np.zeros(len(local), bool)
    u = directions(n)
    for lo in range(0, n, 2000):
        keep[np.argmax(local @ u[lo:lo + 2000].T + radii[:, None], axis=0)] = True
    return np.column_stack([local[keep], radii[keep]])


def hull_points(atoms) -> np.ndarray:
    """The points whose convex hull is the `hull` shape: 42 per kept atom, at r + grow(r)."""
    atoms = np.asarray(atoms, float).reshape(-1, 4)
    reach = atoms[:, 3] + grow(atoms[:, 3])
    return (atoms[:, None, :3] + reach[:, None, None] * ICO_VERTS[None]).reshape(-1, 3)


def grown_support(local, radii, u) -> np.ndarray:
    """The atoms' grown hull's support function h(u) = max over atoms of a·u + r, per u."""
    local = np.asarray(local, float).reshape(-1, 3)
    return (local @ np.asarray(u, float).T + np.asarray(radii, float)[:, None]).max(axis=0)


def depth_below(local, radii, point, n: int = SUPPORT_DIRECTIONS) -> float:
    """How deep (Å) a point lies below the atoms' grown hull: min over directions of h(u) − p·u
    (negative outside). Sampled over n directions: at most (extent · angle²)/2 too deep."""
    u = directions(n)
    return float((grown_support(local, radii, u) - u @ np.asarray(point, float)).min())


def covering_spheres(local, radii, n: int = SPHERES, rounds: int = KMEANS_ROUNDS) -> np.ndarray:
    """n spheres [x, y, z, r] covering every atom's ball: k-means of the atoms (started from
    farthest points, so the same atoms give the same spheres), each cluster then held by the
    smallest sphere reaching its atoms' balls (enclosing_ball)."""
    local = np.asarray(local, float).reshape(-1, 3)
    radii = np.broadcast_to(np.asarray(radii, float), (len(local),))
    n = max(1, min(n, len(local)))
    centres = [local[np.argmax(np.linalg.norm(local, axis=1))]]
    for _ in range(1, n):
        d = np.min([np.linalg.norm(local - c, axis=1) for c in centres], axis=0)
        centres.append(local[np.argmax(d)])
    centres = np.array(centres)
    label = np.zeros(len(local), int)
    for _ in range(rounds):
        label = np.argmin(np.linalg.norm(local[:, None] - centres[None], axis=-1), axis=1)
        moved = np.array([local[label == k].mean(axis=0) if (label == k).any() else centres[k]
                          for k in range(n)])
        if np.allclose(moved, centres):
            break
        centres = moved
    return np.array([enclosing_ball(local[label == k], radii[label == k])
                     for k in range(n) if (label == k).any()])


def enclosing_ball(points, radii, steps: int = 2000) -> list:
    """A small sphere [x, y, z, r] holding every ball (points, radii): Badoiu-Clarkson steps
    towards the farthest ball from the centroid (within about 1/√steps of the smallest), then
    the radius that reaches the farthest ball exactly, so all are held."""
    points = np.asarray(points, float)
    radii = np.asarray(radii, float)
    c = points.mean(axis=0)
    for k in range(1, steps + 1):
        far = np.argmax(np.linalg.norm(points - c, axis=1) + radii)
        c = c + (points[far] - c) / (k + 1)
    r = float((np.linalg.norm(points - c, axis=1) + radii).max())
    return [*c.tolist(), r]


def union_exit(spheres, point, n: int = 4000) -> tuple[np.ndarray, float]:
    """The nearest way out of a union of spheres [x, y, z, r] from a point inside it: the
    direction whose ray leaves the union soonest, and that distance (Å)."""
    s = np.asarray(spheres, float).reshape(-1, 4)
    u = directions(n)
    p = np.asarray(point, float)
    t = np.zeros(n)
    for _ in range(4 * len(s)):
        q = p[None] + t[:, None] * u  # (n, 3): where each ray is now
        rel = q[:, None] - s[None, :, :3]  # (n, k, 3)
        inside = (rel ** 2).sum(-1) < s[None, :, 3] ** 2 - 1e-9
        if not inside.any():
            break
        b = (rel * u[:, None]).sum(-1)  # the exit of each sphere along the ray
        c2 = (rel ** 2).sum(-1) - s[None, :, 3] ** 2
        out = -b + np.sqrt(np.maximum(b * b - c2, 0.0))
        t = t + np.where(inside, out, 0.0).max(axis=1) + 1e-6 * inside.any(axis=1)
    k = int(np.argmin(t))
    return u[k], float(t[k])


def outward(rows, point, n: int = SUPPORT_DIRECTIONS) -> np.ndarray:
    """The outward normal of the surface nearest a point inside the grown hull of `rows`
    [x, y, z, r] (hull atoms or covering spheres): the direction u of least h(u) − p·u."""
    rows = np.asarray(rows, float).reshape(-1, 4)
    u = directions(n)
    gap = grown_support(rows[:, :3], rows[:, 3], u) - u @ np.asarray(point, float)
    return u[int(np.argmin(gap))]


def uv_sphere_inradius(segments: int, rings: int) -> float:
    """The inradius of a unit UV sphere (Blender's create_uvsphere: `segments` around, `rings`
    from pole to pole, vertices on the sphere): the least distance from its centre to a face's
    plane. A quad between two rings is planar (an isosceles trapezoid); the poles' triangles too."""
    theta = np.linspace(0.0, math.pi, rings + 1)
    phi = 2.0 * math.pi / segments
    inner = 1.0
    for t0, t1 in zip(theta[:-1], theta[1:]):
        corners = np.array([[math.sin(t) * math.cos(a), math.sin(t) * math.sin(a), math.cos(t)]
                            for t in (t0, t1) for a in (0.0, phi)])
        pts = corners[np.linalg.norm(corners - corners[:, None], axis=2).sum(1) > 0]
        # the face's plane through three distinct corners (a pole's quad has two equal)
        uniq = [pts[0]]
        for q in pts[1:]:
            if all(np.linalg.norm(q - u) > 1e-12 for u in uniq):
                uniq.append(q)
        n = np.cross(uniq[1] - uniq[0], uniq[2] - uniq[0])
        inner = min(inner, abs(float(n @ uniq[0])) / float(np.linalg.norm(n)))
    return inner
