"""Which globules intersect, by the tutorial's BVH self-overlap of their meshes; the exact checks
each shape is also judged by are in exact.py."""
from __future__ import annotations

import contextlib
import gc

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


def bounding_radius(meshes, matrices: np.ndarray) -> float:
    """A radius about each object's origin that holds every globule's vertices, in world units:
    the largest over `meshes` (a list; one mesh is a list of one)."""
    scale = _largest_scale(matrices)
    return max(_local_radius(mesh) * scale for mesh in meshes)


def _local_radius(mesh) -> float:
    verts = mesh_arrays(mesh)[0]
    return float(np.linalg.norm(verts, axis=1).max()) if len(verts) else 0.0


def _largest_scale(matrices: np.ndarray) -> float:
    return float(np.linalg.norm(matrices[:, :3, :3], ord=2, axis=(1, 2)).max()) if len(matrices) else 0.0


def _margin(centres: np.ndarray) -> float:
    """Slack for float32 rounding of world coordinates (and the tree's epsilon)."""
    return 1e-3 + 1e-6 * float(np.abs(centres).max(initial=0.0)) + BVH_EPSILON


def candidate_pairs(meshes, matrices: np.ndarray, radius: float | None = None) -> np.ndarray:
    """Globule pairs (i < j) whose bounding spheres meet: the only ones whose faces can overlap.
    `radius`: the bounding radius, if not the largest of `meshes` (bounding_radius).

    A margin covers float32 rounding of world coordinates, so no overlapping pair is missed.
    """
    centres = matrices[:, :3, 3]
    if len(centres) < 2:
        return np.empty((0, 2), dtype=np.intp)
    if radius is None:
        radius = bounding_radius(meshes, matrices)
    reach = 2.0 * radius + _margin(centres)
    a, b, _ = close_pairs(centres, reach)
    return np.stack([np.minimum(a, b), np.maximum(a, b)], axis=1)


def involved_pairs(candidates: np.ndarray, keep: np.ndarray | None = None):
    """The candidate pairs that touch a kept globule (all if `keep` is None), numbered only over
    the globules involved: (involved globules, pairs (k, 2) of indices into them)."""
    if keep is not None:
        keep = np.asarray(keep, dtype=bool)
        candidates = candidates[keep[candidates[:, 0]] | keep[candidates[:, 1]]]
    if not len(candidates):
        return np.empty(0, dtype=np.intp), np.empty((0, 2), dtype=np.intp)
    involved, local = np.unique(candidates, return_inverse=True)
    return involved, local.reshape(-1, 2)


def facing_faces(mesh, matrices: np.ndarray, pairs: np.ndarray, chunk: int = 4096,
                 partner_radius: float | None = None) -> np.ndarray:
    """Which faces of each globule can reach the other globule of one of its `pairs`: (n, faces).

    A face can only cross a face of globule j where it enters j's bounding sphere, so a face
    whose own bounding sphere (about its centroid) stays outside every partner's is left out.
    Distances are taken in each globule's own frame (its partner's centre mapped back), and
    divided by the matrix's smallest stretch, so scaled globules stay on the safe side.
    `partner_radius`: the partners' bounding radius in world units when they have other meshes
    (default: this mesh's).
    """
    verts, starts, loops = mesh_arrays(mesh)
    sizes = np.diff(np.append(starts, len(loops)))
    owner = np.repeat(np.arange(len(starts)), sizes)
    centroid = np.zeros((len(starts), 3))
    np.add.at(centroid, owner, verts[loops])
    centroid /= sizes[:, None]
    face_radius = np.zeros(len(starts))
    np.maximum.at(face_radius, owner, np.linalg.norm(verts[loops] - centroid[owner], axis=1))
    linear, centres = matrices[:, :3, :3], matrices[:, :3, 3]
    stretch = np.linalg.svd(linear, compute_uv=False)  # (n, 3), largest first
    singular = stretch[:, -1] < 1e-9  # flat globules: keep all their faces
    smallest = np.where(singular, 1.0, stretch[:, -1])
    inverse = np.linalg.inv(np.where(singular[:, None, None], np.eye(3), linear))
    partner = bounding_radius([mesh], matrices) if partner_radius is None else partner_radius
    reach = partner + stretch[:, 0].max() * face_radius + _margin(centres)
    keep = np.zeros((len(matrices), len(starts)), dtype=bool)
    keep[singular] = True
    for lo in range(0, len(pairs), chunk):
        part = pairs[lo:lo + chunk]
        rows = np.concatenate([part[:, 0], part[:, 1]])
        other = np.concatenate([part[:, 1], part[:, 0]])
        q = np.einsum("nij,nj->ni", inverse[rows], centres[other] - centres[rows])
        dist2 = (q * q).sum(1)[:, None] - 2.0 * q @ centroid.T + (centroid * centroid).sum(1)
        near = dist2 <= (reach[None, :] / smallest[rows, None]) ** 2
        order = np.argsort(rows, kind="stable")
        rows, near = rows[order], near[order]
        first = np.flatnonzero(np.r_[True, rows[1:] != rows[:-1]])
        keep[rows[first]] |= np.logical_or.reduceat(near, first, axis=0)
    return keep


def bvh_clashes(meshes, matrices: np.ndarray, keep: np.ndarray | None = None, kinds=None
                ) -> tuple[int, set[tuple[int, int]]]:
    """BVH overlap of the globules in world space (epsilon 1e-5), as in the tutorial's step 8.

    `meshes`: a list of meshes (one mesh is a list of one), globule g having meshes[kinds[g]]
    at matrices[g] (`kinds` None: every globule the first mesh; several real-shaped domains per
    chain have each its own mesh). Returns the number of faces in any overlapping pair and the
    set of globule pairs (i < j) whose faces overlap. Faces of one globule never count against
    each other. With `keep` (a boolean per globule), only pairs with at least one kept globule
    count.

    The tutorial joins every globule into one tree and overlaps it with itself. Here only
    pairs whose bounding spheres meet are overlapped, each globule in its own tree holding the
    faces that can reach one of its partners (same world coordinates, same polygons, same
    epsilon): the same faces and pairs, without testing each globule against itself, against
    far-away globules, or with its far side. Faces are numbered globule after globule.
    """
    matrices = np.asarray(matrices, dtype=float).reshape(-1, 4, 4)
    kinds = (np.zeros(len(matrices), dtype=np.intp) if kinds is None
             else np.asarray(kinds, dtype=np.intp))
    if len(matrices) < 2:
        return 0, set()
    involved, local = involved_pairs(candidate_pairs(meshes, matrices), keep)
    if not len(local):
        return 0, set()
    sub, sub_kind = matrices[involved], kinds[involved]
    partner = bounding_radius(meshes, sub)
    count = np.array([len(meshes[k].polygons) for k in kinds.tolist()], dtype=np.int64)
    offset = np.concatenate([[0], np.cumsum(count)[:-1]])  # globule g's faces start here
    trees, kept = {}, {}
    for k in np.unique(sub_kind).tolist():
        rows = np.flatnonzero(sub_kind == k)
        facing = facing_faces(meshes[k], sub, local, partner_radius=partner)
        world, polys = joined_globules(meshes[k], sub[rows])
        # thousands of small lists: the cyclic GC would rescan them again and again
        with _gc_paused():
            for r, g in enumerate(rows.tolist()):
                chosen = np.flatnonzero(facing[g])
                if not len(chosen):
                    continue
                kept[g] = chosen
                trees[g] = BVHTree.FromPolygons(world[r].tolist(), [polys[f] for f in chosen],
                                                epsilon=BVH_EPSILON)
    return tree_overlaps(trees, kept, local, involved, lambda g: offset[g])


def tree_overlaps(trees: dict, kept: dict, local, involved, first_face
                  ) -> tuple[int, set[tuple[int, int]]]:
    """The pairs `local` (indices into `involved`) whose BVH trees overlap, as globule pairs,
    and how many faces take part; trees[i] holds globule involved[i]'s faces kept[i], and
    first_face(g) is the number of globule g's first face among all globules' faces."""
    faces, pairs = [], set()
    with _gc_paused():
        for i, j in local.tolist():
            if i not in trees or j not in trees:
                continue
            hits = trees[i].overlap(trees[j])
            if hits:
                gi, gj = int(involved[i]), int(involved[j])
                pairs.add((gi, gj))
                hits = np.array(hits, dtype=np.int64)
                faces += [first_face(gi) + kept[i][hits[:, 0]],
                          first_face(gj) + kept[j][hits[:, 1]]]
    return (int(np.unique(np.concatenate(faces)).size) if faces else 0), pairs


def reach_from_axis(meshes, kinds, matrices: np.ndarray) -> np.ndarray:
    """Each globule's farthest vertex from the fibril axis (Z), globule g having
    meshes[kinds[g]] (one mesh: kinds all 0)."""
    matrices = np.asarray(matrices, dtype=float).reshape(-1, 4, 4)
    kinds = np.asarray(kinds, dtype=np.intp)
    out = np.empty(len(matrices))
    for k, mesh in enumerate(meshes):
        rows = np.flatnonzero(kinds == k)
        if len(rows):
            world, _ = joined_globules(mesh, matrices[rows])
            out[rows] = np.hypot(world[..., 0], world[..., 1]).max(axis=1)
    return out


@contextlib.contextmanager
def _gc_paused():
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


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


def close_pairs(centres: np.ndarray, reach: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Index pairs (a, b) of points closer than `reach`, and their distances.

    A uniform grid of cells one reach wide: only points in the same or neighbouring cells are
    compared, so the cost is O(n log n + close pairs) however the points are spread, not O(n²).
    """
    centres = np.asarray(centres, dtype=float).reshape(-1, 3)
    n = len(centres)
    if n < 2 or reach <= 0:
        empty = np.empty(0, dtype=np.intp)
        return empty, empty, np.empty(0)
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
        empty = np.empty(0, dtype=np.intp)
        return empty, empty, np.empty(0)
    a, b = order[np.concatenate(firsts)], order[np.concatenate(seconds)]
    dist = np.linalg.norm(centres[a] - centres[b], axis=1)
    hit = dist < reach
    return a[hit], b[hit], dist[hit]


def float_tolerance(centres: np.ndarray) -> float:
    """How far the BVH's float32 world coordinates and its epsilon can move a face (Å): the
    tolerance between the BVH and an exact check on the same faces (see _margin)."""
    return _margin(np.asarray(centres, dtype=float))


def sphere_band(radius: float) -> float:
    """grazing_depth of the 32 × 16 UV sphere of this radius: it scales with the radius
    (0.287 Å at 15 Å)."""
    return GRAZING_AT_15 * radius / 15.0


GRAZING_AT_15 = 0.287  # grazing_depth of the default globule mesh (32 × 16, radius 15 Å)
