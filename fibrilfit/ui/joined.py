"""The tutorial's step 8 without its damage: one new mesh of all globules, for Mesh Analysis.

The tutorial joined the globule objects themselves, which destroyed the simulation. This adds a
separate, static copy at the current frame and leaves the rigid bodies and their cache alone.
"""
from __future__ import annotations

import bpy
import numpy as np

from ..analysis.clashes import mesh_arrays
from ..analysis.verdict import world_matrices
from ..builders.scene import LAYER, PROTOFILAMENT, TAG, is_ours, tag

ROLE = "joined"


def join_globules(model) -> bpy.types.Object:
    """Replace any earlier joined copy with the globules, joined in world space as they stand now.

    Each face carries the integer attributes "fibrilfit_layer" and "fibrilfit_protofilament",
    the layer and protofilament of its globule.
    """
    remove_joined(model)
    globules = model.globules
    mesh = _joined_mesh(globules[0].data, world_matrices(globules))
    layers = np.repeat(np.array([ob[LAYER] for ob in globules], dtype=np.int32),
                       len(globules[0].data.polygons))
    mesh.attributes.new(LAYER, "INT", "FACE").data.foreach_set("value", layers)
    pfs = np.repeat(np.array([ob.get(PROTOFILAMENT, 0) for ob in globules], dtype=np.int32),
                    len(globules[0].data.polygons))
    mesh.attributes.new(PROTOFILAMENT, "INT", "FACE").data.foreach_set("value", pfs)
    ob = tag(bpy.data.objects.new("FibrilFit joined globules", mesh), ROLE)
    model.root.objects.link(ob)
    return ob


def _joined_mesh(shared, matrices: np.ndarray) -> bpy.types.Mesh:
    """Copies of the mesh `shared` placed by `matrices` (n, 4, 4), as one mesh, in bulk."""
    verts, starts, loops = mesh_arrays(shared)
    n = len(matrices)
    world = np.einsum("nij,vj->nvi", matrices[:, :3, :3], verts) + matrices[:, None, :3, 3]
    offsets = np.arange(n, dtype=np.int32)[:, None]
    mesh = tag(bpy.data.meshes.new("FibrilFit joined globules"), ROLE)
    mesh.vertices.add(n * len(verts))
    mesh.vertices.foreach_set("co", world.astype(np.float32).ravel())
    mesh.loops.add(n * len(loops))
    mesh.loops.foreach_set("vertex_index", (loops[None] + offsets * len(verts)).ravel())
    mesh.polygons.add(n * len(starts))
    mesh.polygons.foreach_set("loop_start", (starts[None] + offsets * len(loops)).ravel())
    mesh.update(calc_edges=True)
    return mesh


def find_joined(model) -> list:
    return [ob for ob in model.root.objects if ob.get(TAG) == ROLE]


def remove_joined(model) -> int:
    """Remove the joined copy (object and mesh); returns how many objects went."""
    obs = find_joined(model)
    meshes = [ob.data for ob in obs if ob.data is not None and is_ours(ob.data)]
    bpy.data.batch_remove(obs)
    bpy.data.batch_remove([m for m in meshes if m.users == 0])
    return len(obs)
