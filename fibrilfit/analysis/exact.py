"""The exact clash checks, one per domain shape, that the BVH's mesh check is compared with
(docs/model/domain-shapes.md#two-checks): spheres by their centres, hulls by GJK, covering
spheres ball by ball. EXACT_CHECKS says which judges each shape of model.domains.SHAPES."""
from __future__ import annotations

import numpy as np

from ..model import occupancy
from .clashes import (_margin, candidate_pairs, close_pairs, float_tolerance, grazing_depth,
                      mesh_arrays, sphere_band)


def sphere_clashes(centres: np.ndarray, radius, tolerance: float = 1e-3
                   ) -> list[tuple[int, int, float]]:
    """Pairs of spheres closer than the sum of their radii − tolerance, with their overlap
    depth (Å). `radius`: one for all, or one per sphere (several domain sizes).

    Found through the grid of close_pairs, not all pairs.
    """
    radii = np.asarray(radius, dtype=float)
    reach = 2.0 * float(radii.max()) - tolerance
    a, b, dist = close_pairs(centres, reach)
    if radii.ndim:
        depth = radii[a] + radii[b] - dist
        keep = depth > tolerance
        a, b, depth = a[keep], b[keep], depth[keep]
    else:
        depth = 2.0 * radius - dist
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    by = np.lexsort((hi, lo))
    return list(zip(lo[by].tolist(), hi[by].tolist(), depth[by].tolist()))




# ---- real domain shapes (docs/model/domain-shapes.md#two-checks) ------------------------------
GJK_TOLERANCE = 1e-5  # Å: GJK stops once the distance is known to within this


def _closest_on_simplex(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The point of the simplex (1-4 points) nearest the origin, and the smallest sub-simplex
    holding it (by trying every face: at most 15, each a small least-squares solve)."""
    best, best_set, n = None, None, len(pts)
    for mask in range(1, 1 << n):
        idx = [i for i in range(n) if mask >> i & 1]
        p = pts[idx]
        if len(idx) == 1:
            x, lam = p[0], np.ones(1)
        else:
            e = p[1:] - p[0]
            g = e @ e.T
            if abs(np.linalg.det(g)) < 1e-18:
                continue
            t = np.linalg.solve(g, -e @ p[0])
            lam = np.concatenate([[1 - t.sum()], t])
            if (lam < -1e-12).any():
                continue
            x = p[0] + t @ e
        if best is None or x @ x < best @ best - 1e-15:
            best, best_set = x, np.array(idx)
    return best, best_set


def hull_distance(a: np.ndarray, b: np.ndarray, iterations: int = 100) -> float:
    """Distance (Å) between the convex hulls of point sets a and b (GJK); 0.0 if they meet."""
    x = a.mean(axis=0) - b.mean(axis=0)
    simplex = np.empty((0, 3))
    for _ in range(iterations):
        if x @ x < 1e-24:
            return 0.0
        s = a[np.argmax(a @ -x)] - b[np.argmax(b @ x)]  # support of a - b towards -x
        gap = x @ x - x @ s  # |x|·(|x| - lower bound)
        if gap <= GJK_TOLERANCE * np.sqrt(x @ x):
            return float(np.sqrt(x @ x))
        simplex = np.vstack([simplex, s])
        x, keep = _closest_on_simplex(simplex)
        simplex = simplex[keep]
        if len(simplex) == 4:  # the origin inside the tetrahedron
            return 0.0
    return float(np.sqrt(x @ x))


def face_overlap(a: np.ndarray, b: np.ndarray, normals: np.ndarray) -> float:
    """The smallest overlap (Å) of two convex point sets along `normals` (unit, (n, 3)): an
    upper bound of their penetration depth when they meet (negative: a normal separates)."""
    pa, pb = a @ normals.T, b @ normals.T
    return float(np.minimum(pa.max(0) - pb.min(0), pb.max(0) - pa.min(0)).min())


def face_normals(mesh) -> np.ndarray:
    """Unit normals of a mesh's polygons, (n, 3), duplicates (coplanar triangles) merged."""
    normals = np.empty(len(mesh.polygons) * 3, dtype=np.float32)
    mesh.polygons.foreach_get("normal", normals)
    return np.unique(np.round(normals.reshape(-1, 3).astype(float), 6), axis=0)


def hull_clashes(meshes, matrices: np.ndarray, tolerance: float, kinds=None
                 ) -> tuple[list[tuple[int, int, float]], callable]:
    """The analytic check of convex hull globules: pairs whose hulls (the meshes' vertices, in
    world space) are closer than -tolerance, i.e. overlap by more than it, with a depth (the
    smallest overlap along the two hulls' face normals), and the signed depth function of any
    pair (-distance when apart). Only pairs whose bounding spheres meet are looked at.
    `meshes`: a list (one mesh is a list of one), globule g's hull is meshes[kinds[g]]'s
    (`kinds` None: the first's)."""
    meshes = list(meshes)
    kinds = np.zeros(len(matrices), dtype=np.intp) if kinds is None else np.asarray(kinds)
    verts = [mesh_arrays(m)[0] for m in meshes]
    normals = [face_normals(m) for m in meshes]
    matrices = np.asarray(matrices, dtype=float).reshape(-1, 4, 4)
    cache = {}

    def depth(i, j):
        if (i, j) not in cache:
            ki, kj = int(kinds[i]), int(kinds[j])
            wa = verts[ki] @ matrices[i, :3, :3].T + matrices[i, :3, 3]
            wb = verts[kj] @ matrices[j, :3, :3].T + matrices[j, :3, 3]
            gap = hull_distance(wa, wb)
            if gap > 0.0:
                cache[i, j] = -gap
            else:
                n = np.vstack([normals[ki] @ _rotation(matrices[i]).T,
                               normals[kj] @ _rotation(matrices[j]).T])
                cache[i, j] = max(face_overlap(wa, wb, n), 0.0)
        return cache[i, j]

    pairs = candidate_pairs(meshes, matrices)
    out = [(int(i), int(j), depth(int(i), int(j))) for i, j in pairs.tolist()]
    return [(i, j, d) for i, j, d in sorted(out) if d > tolerance], depth


def _rotation(matrix: np.ndarray) -> np.ndarray:
    """The rotation of a (uniformly scaled) world matrix."""
    m = matrix[:3, :3]
    return m / np.cbrt(np.linalg.det(m))


def spheres_clashes(sets, matrices: np.ndarray, tolerance: float, kinds=None
                    ) -> tuple[list[tuple[int, int, float]], callable]:
    """The analytic check of globules made of spheres [x, y, z, r] (their body frame): pairs
    of globules with two spheres overlapping by more than `tolerance`, with the deepest overlap,
    and the depth function of any pair (the deepest sphere overlap; negative when apart).
    `sets`: a list of sets of spheres (one set is a list of one), globule g's being
    sets[kinds[g]] (`kinds` None: the first)."""
    sets = [np.asarray(x, dtype=float).reshape(-1, 4) for x in sets]
    matrices = np.asarray(matrices, dtype=float).reshape(-1, 4, 4)
    kinds = np.zeros(len(matrices), dtype=np.intp) if kinds is None else np.asarray(kinds)
    scale = np.cbrt(np.abs(np.linalg.det(matrices[:, :3, :3])))
    if len(sets) == 1:
        s = sets[0]
        centres = (np.einsum("nij,kj->nki", matrices[:, :3, :3], s[:, :3])
                   + matrices[:, None, :3, 3])
        radii = scale[:, None] * s[None, :, 3]
    else:
        centres = [sets[k][:, :3] @ m[:3, :3].T + m[:3, 3] for k, m in zip(kinds.tolist(), matrices)]
        radii = [sc * sets[k][:, 3] for k, sc in zip(kinds.tolist(), scale)]

    def depth(i, j):
        d = np.linalg.norm(centres[i][:, None] - centres[j][None], axis=-1)
        return float((radii[i][:, None] + radii[j][None] - d).max())

    far = max(float(np.max(np.linalg.norm(s[:, :3], axis=1) + s[:, 3])) for s in sets)
    reach = 2.0 * far * (float(scale.max()) if len(scale) else 1.0) + _margin(matrices[:, :3, 3])
    a, b, _ = close_pairs(matrices[:, :3, 3], reach)
    out = sorted((int(min(i, j)), int(max(i, j))) for i, j in zip(a.tolist(), b.tolist()))
    hits = [(i, j, depth(i, j)) for i, j in out]
    return [(i, j, d) for i, j, d in hits if d > tolerance], depth


class SphereCheck:
    """The sphere: centre distances against the radii, within the mesh's grazing band (its
    facets' sag, scaled to the widest domain: further domains share the mesh, scaled)."""

    @staticmethod
    def band(p, meshes) -> float:
        # a hetero-amyloid's B globules share the mesh too, at B's scale
        widest = max(d.radius for d in p.domains)
        if occupancy.is_hetero(p):
            widest = max(widest, float(p.domain_b_diameter) / 2.0)
        return grazing_depth(meshes[0]) * widest / p.globule_radius

    @staticmethod
    def clashes(p, meshes, matrices, kinds, centres, radius, band):
        """(pairs deeper than the band, band, slack (None: the default), depth (None: the
        centres'))."""
        return sphere_clashes(centres, radius, band), band, None, None


class HullCheck:
    """A hull: the same faces as the BVH, exactly (GJK); only rounding between the checks."""

    @staticmethod
    def band(p, meshes) -> float:
        return 0.0

    @staticmethod
    def clashes(p, meshes, matrices, kinds, centres, radius, band):
        band = float_tolerance(centres)
        found, depth = hull_clashes(meshes, matrices, band, kinds=kinds)
        return found, band, band, depth


class SpheresCheck:
    """Covering spheres, each domain its own, each drawn as a 32 × 16 mesh as the sphere's:
    ball by ball, within the largest ball's grazing band."""

    @staticmethod
    def band(p, meshes) -> float:
        return 0.0

    @staticmethod
    def clashes(p, meshes, matrices, kinds, centres, radius, band):
        sets = [d.rows for d in p.domains]
        band = sphere_band(max(float(s[:, 3].max()) for s in sets))
        found, depth = spheres_clashes(sets, matrices, band, kinds=kinds)
        return found, band, None, depth


# The exact check of each shape (keys: model.domains.SHAPES)
EXACT_CHECKS = {"sphere": SphereCheck, "hull": HullCheck, "spheres": SpheresCheck}
