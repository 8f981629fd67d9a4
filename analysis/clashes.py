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


def bvh_clashes(mesh, matrices: np.ndarray, keep: np.ndarray | None = None
                ) -> tuple[int, set[tuple[int, int]]]:
    """BVH self-overlap of the joined globules (epsilon 1e-5), as in the tutorial's step 8.

    Returns the number of faces in any overlapping pair and the set of globule pairs (i < j)
    whose faces overlap. Faces of one globule never count against each other. With `keep`
    (a boolean per globule), only pairs with at least one kept globule count.
    """
    if len(matrices) == 0:
        return 0, set()
    verts, polys = joined_globules(mesh, matrices)
    tree = BVHTree.FromPolygons(verts.tolist(), polys, epsilon=BVH_EPSILON)
    overlap = np.array(tree.overlap(tree), dtype=np.int64).reshape(-1, 2)
    per = len(mesh.polygons)
    owner = overlap // per
    between = owner[:, 0] != owner[:, 1]
    if keep is not None:
        keep = np.asarray(keep, dtype=bool)
        between &= keep[owner[:, 0]] | keep[owner[:, 1]]
    faces = np.unique(overlap[between])
    pairs = {(int(min(a, b)), int(max(a, b))) for a, b in owner[between]}
    return int(faces.size), pairs


def grazing_depth(mesh) -> float:
    """Deepest sphere overlap (Å) that the faceted globule mesh can miss: twice its sag.

    The mesh's vertices lie on its sphere, so it holds a ball of radius r_in (the smallest
    distance from its centre to a face plane). Two such meshes whose spheres overlap by more
    than 2·(R − r_in) hold overlapping balls, so their surfaces must cross whichever way each
    is turned; at any shallower overlap, whether faces cross depends on the turn.
    For the 32 × 16 globule of radius 15 Å this is 0.287 Å.
    """
    verts, starts, loops = mesh_arrays(mesh)
    centre = verts.mean(axis=0)
    radius = np.linalg.norm(verts - centre, axis=1).max()
    bounds = np.append(starts, len(loops))
    inner = radius
    for a, b in zip(bounds[:-1], bounds[1:]):
        face = verts[loops[a:b]] - centre
        for k in range(1, len(face) - 1):  # the triangles the BVH tests
            normal = np.cross(face[k] - face[0], face[k + 1] - face[0])
            inner = min(inner, abs(float(normal @ face[0])) / float(np.linalg.norm(normal)))
    return 2.0 * (radius - inner)


# The 13 forward neighbours of a grid cell (with the cell itself, every neighbouring pair of cells
# is visited once).
_FORWARD = np.array([(dx, dy, dz) for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                     if (dx, dy, dz) > (0, 0, 0)], dtype=np.int64)


def sphere_clashes(centres: np.ndarray, radius: float, tolerance: float = 1e-3
                   ) -> list[tuple[int, int, float]]:
    """Pairs (i < j) of equal spheres closer than 2·radius − tolerance, with overlap depth (Å).

    A uniform grid of cells one reach wide: only spheres in the same or neighbouring cells are
    compared, so the cost is O(n log n + close pairs) however the centres are spread, not O(n²).
    """
    centres = np.asarray(centres, dtype=float).reshape(-1, 3)
    n = len(centres)
    reach = 2.0 * radius - tolerance
    if n < 2 or reach <= 0:
        return []
    cell = np.floor((centres - centres.min(axis=0)) / reach).astype(np.int64) + 1
    dims = cell.max(axis=0) + 2  # a margin of one empty cell on each side: no wrap-around
    strides = np.array([dims[1] * dims[2], dims[2], 1], dtype=np.int64)
    key = cell @ strides
    order = np.argsort(key, kind="stable")
    skey = key[order]
    firsts, seconds = [], []
    for offset in [np.zeros(3, dtype=np.int64), *_FORWARD]:
        target = skey + offset @ strides
        lo = np.searchsorted(skey, target, side="left")
        hi = np.searchsorted(skey, target, side="right")
        if not offset.any():
            lo = np.arange(n) + 1  # same cell: only later members, each pair once
        counts = np.maximum(hi - lo, 0)
        total = int(counts.sum())
        if total == 0:
            continue
        first = np.repeat(np.arange(n), counts)
        within = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
        firsts.append(first)
        seconds.append(np.repeat(lo, counts) + within)
    if not firsts:
        return []
    a, b = order[np.concatenate(firsts)], order[np.concatenate(seconds)]
    dist = np.linalg.norm(centres[a] - centres[b], axis=1)
    hit = dist < reach
    a, b, depth = a[hit], b[hit], 2.0 * radius - dist[hit]
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    by = np.lexsort((hi, lo))
    return list(zip(lo[by].tolist(), hi[by].tolist(), depth[by].tolist()))
