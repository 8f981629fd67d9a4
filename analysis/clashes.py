"""Which globules intersect: the tutorial's BVH self-overlap, and an analytic sphere test."""
from __future__ import annotations

import contextlib
import gc
import itertools

import numpy as np
from mathutils.bvhtree import BVHTree

BVH_EPSILON = 1e-5


def mesh_arrays(mesh) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Vertices (n, 3), polygon loop starts and loop vertex indices of a mesh, via foreach_get."""
    verts = np.empty(len(mesh.vertices) * 3, dtype=np.float32)
    mesh.vertices.foreach_get("co", verts)
    starts = np.empty(len(mesh.polygons), dtype=np.int32)
    mesh.polygons.foreach_get("loop_start", starts)
    loops = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", loops)
    return verts.reshape(-1, 3).astype(float), starts, loops


def joined_globules(mesh, matrices: np.ndarray) -> tuple[np.ndarray, list]:
    """All globules joined in world space: the tutorial's join, without touching the objects.

    `matrices`: (n, 4, 4) world matrices of globules sharing `mesh`. Returns the vertices
    (n, v, 3) and the mesh's polygons as vertex-index lists (the same for every globule).
    """
    verts, starts, loops = mesh_arrays(mesh)
    world = np.einsum("nij,vj->nvi", matrices[:, :3, :3], verts) + matrices[:, None, :3, 3]
    polys = [p.tolist() for p in np.split(loops, starts[1:])] if len(starts) else []
    return world, polys


def bounding_radius(mesh, matrices: np.ndarray) -> float:
    """A radius about each object's origin that holds every globule's vertices, in world units."""
    verts = mesh_arrays(mesh)[0]
    local = float(np.linalg.norm(verts, axis=1).max()) if len(verts) else 0.0
    scale = np.linalg.norm(matrices[:, :3, :3], ord=2, axis=(1, 2)).max() if len(matrices) else 0.0
    return local * float(scale)


def candidate_pairs(mesh, matrices: np.ndarray) -> np.ndarray:
    """Globule pairs (i < j) whose bounding spheres meet: the only ones whose faces can overlap.

    A margin covers float32 rounding of world coordinates, so no overlapping pair is missed.
    """
    centres = matrices[:, :3, 3]
    if len(centres) < 2:
        return np.empty((0, 2), dtype=np.intp)
    margin = 1e-3 + 1e-6 * float(np.abs(centres).max()) + BVH_EPSILON
    a, b, _ = close_pairs(centres, 2.0 * bounding_radius(mesh, matrices) + margin)
    return np.stack([np.minimum(a, b), np.maximum(a, b)], axis=1)


def bvh_clashes(mesh, matrices: np.ndarray) -> tuple[int, set[tuple[int, int]]]:
    """BVH overlap of the globules in world space (epsilon 1e-5), as in the tutorial's step 8.

    Returns the number of faces in any overlapping pair and the set of globule pairs (i < j)
    whose faces overlap. Faces of one globule never count against each other.

    The tutorial joins every globule into one tree and overlaps it with itself. Here each
    globule that can touch another gets its own tree (same world coordinates, same polygons,
    same epsilon), and only pairs whose bounding spheres meet are overlapped: the same faces
    and pairs, without testing each globule against itself or against far-away globules.
    """
    matrices = np.asarray(matrices, dtype=float).reshape(-1, 4, 4)
    candidates = candidate_pairs(mesh, matrices)
    if not len(candidates):
        return 0, set()
    involved = np.unique(candidates)
    world, polys = joined_globules(mesh, matrices[involved])
    per = len(polys)
    faces, pairs = [], set()
    with _gc_paused():  # thousands of small lists: the cyclic GC would rescan them again and again
        trees = {g: BVHTree.FromPolygons(w.tolist(), polys, epsilon=BVH_EPSILON)
                 for g, w in zip(involved.tolist(), world)}
        for i, j in candidates.tolist():
            hits = trees[i].overlap(trees[j])
            if hits:
                pairs.add((i, j))
                hits = np.array(hits, dtype=np.int64)
                faces += [i * per + hits[:, 0], j * per + hits[:, 1]]
    return (int(np.unique(np.concatenate(faces)).size) if faces else 0), pairs


@contextlib.contextmanager
def _gc_paused():
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def close_pairs(centres: np.ndarray, reach: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Index pairs (a, b) of points closer than `reach`, and their distances.

    Sort and sweep along the axis of widest spread: O(n log n + candidates), not all pairs.
    """
    centres = np.asarray(centres, dtype=float).reshape(-1, 3)
    n = len(centres)
    if n < 2:
        empty = np.empty(0, dtype=np.intp)
        return empty, empty, np.empty(0)
    axis = int(np.argmax(np.ptp(centres, axis=0)))
    order = np.argsort(centres[:, axis], kind="stable")
    key = centres[order, axis]
    stop = np.searchsorted(key, key + reach, side="right")
    counts = np.maximum(stop - np.arange(n) - 1, 0)
    first = np.repeat(np.arange(n), counts)
    second = first + 1 + (np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts))
    a, b = order[first], order[second]
    dist = np.linalg.norm(centres[a] - centres[b], axis=1)
    hit = dist < reach
    return a[hit], b[hit], dist[hit]


def sphere_clashes(centres: np.ndarray, radius: float, tolerance: float = 1e-3
                   ) -> list[tuple[int, int, float]]:
    """Pairs of equal spheres closer than 2·radius − tolerance, with their overlap depth (Å).

    Sort and sweep along the axis of widest spread (close_pairs), not all pairs.
    """
    reach = 2.0 * radius - tolerance
    a, b, dist = close_pairs(centres, reach)
    depth = 2.0 * radius - dist
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    out = sorted(zip(lo.tolist(), hi.tolist(), depth.tolist()))
    return [(i, j, float(d)) for i, j, d in out]
