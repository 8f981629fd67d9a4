"""Which globules intersect: the tutorial's BVH self-overlap, and an analytic sphere test."""
from __future__ import annotations

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

    `matrices`: (n, 4, 4) world matrices of globules sharing `mesh`.
    """
    verts, starts, loops = mesh_arrays(mesh)
    world = np.einsum("nij,vj->nvi", matrices[:, :3, :3], verts) + matrices[:, None, :3, 3]
    bounds = np.append(starts, len(loops))
    polys = [loops[a:b] for a, b in zip(bounds[:-1], bounds[1:])]
    offsets = np.arange(len(matrices))[:, None] * len(verts)
    all_polys = [(poly + off).tolist() for off in offsets[:, 0] for poly in polys]
    return world.reshape(-1, 3), all_polys


def bvh_clashes(mesh, matrices: np.ndarray) -> tuple[int, set[tuple[int, int]]]:
    """BVH self-overlap of the joined globules (epsilon 1e-5), as in the tutorial's step 8.

    Returns the number of faces in any overlapping pair and the set of globule pairs (i < j)
    whose faces overlap. Faces of one globule never count against each other.
    """
    if len(matrices) == 0:
        return 0, set()
    verts, polys = joined_globules(mesh, matrices)
    tree = BVHTree.FromPolygons(verts.tolist(), polys, epsilon=BVH_EPSILON)
    overlap = np.array(tree.overlap(tree), dtype=np.int64).reshape(-1, 2)
    per = len(mesh.polygons)
    owner = overlap // per
    between = owner[:, 0] != owner[:, 1]
    faces = np.unique(overlap[between])
    pairs = {(int(min(a, b)), int(max(a, b))) for a, b in owner[between]}
    return int(faces.size), pairs


def sphere_clashes(centres: np.ndarray, radius: float, tolerance: float = 1e-3
                   ) -> list[tuple[int, int, float]]:
    """Pairs of equal spheres closer than 2·radius − tolerance, with their overlap depth (Å).

    Sort and sweep along the axis of widest spread: O(n log n + candidates), not all pairs.
    """
    centres = np.asarray(centres, dtype=float).reshape(-1, 3)
    n = len(centres)
    if n < 2:
        return []
    reach = 2.0 * radius - tolerance
    axis = int(np.argmax(np.ptp(centres, axis=0)))
    order = np.argsort(centres[:, axis], kind="stable")
    key = centres[order, axis]
    stop = np.searchsorted(key, key + reach, side="right")
    counts = stop - np.arange(n) - 1
    first = np.repeat(np.arange(n), counts)
    second = first + 1 + (np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts))
    a, b = order[first], order[second]
    dist = np.linalg.norm(centres[a] - centres[b], axis=1)
    hit = dist < reach
    a, b, depth = a[hit], b[hit], 2.0 * radius - dist[hit]
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    out = sorted(zip(lo.tolist(), hi.tolist(), depth.tolist()))
    return [(i, j, float(d)) for i, j, d in out]
