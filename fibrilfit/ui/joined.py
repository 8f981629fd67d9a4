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
    # each globule's own mesh (several real-shaped domains: one per domain; else one shared)
    mesh = _joined_mesh([ob.data for ob in globules], world_matrices(globules))
    faces = [len(ob.data.polygons) for ob in globules]
    layers = np.repeat(np.array([ob[LAYER] for ob in globules], dtype=np.int32), faces)
    mesh.attributes.new(LAYER, "INT", "FACE").data.foreach_set("value", layers)
    pfs = np.repeat(np.array([ob.get(PROTOFILAMENT, 0) for ob in globules], dtype=np.int32),
                    faces)
    mesh.attributes.new(PROTOFILAMENT, "INT", "FACE").data.foreach_set("value", pfs)
    ob = tag(bpy.data.objects.new("FibrilFit joined globules", mesh), ROLE)
    model.root.objects.link(ob)
    return ob


def _joined_mesh(meshes, matrices: np.ndarray) -> bpy.types.Mesh:
    """Copies of each globule's mesh (`meshes`, one per matrix) placed by `matrices`
    (n, 4, 4), as one mesh, in bulk."""
    arrays = {}
    for m in meshes:
        if m.session_uid not in arrays:
            arrays[m.session_uid] = mesh_arrays(m)
    world, loops_all, starts_all = [], [], []
    nv = nl = 0
    for m, mat in zip(meshes, np.asarray(matrices, float)):
        verts, starts, loops = arrays[m.session_uid]
        world.append(verts @ mat[:3, :3].T + mat[:3, 3])
        loops_all.append(loops + nv)
        starts_all.append(starts + nl)
        nv, nl = nv + len(verts), nl + len(loops)
    mesh = tag(bpy.data.meshes.new("FibrilFit joined globules"), ROLE)
    if not world:
        return mesh
    mesh.vertices.add(nv)
    mesh.vertices.foreach_set("co", np.concatenate(world).astype(np.float32).ravel())
    mesh.loops.add(nl)
    mesh.loops.foreach_set("vertex_index", np.concatenate(loops_all).astype(np.int32))
    starts = np.concatenate(starts_all).astype(np.int32)
    mesh.polygons.add(len(starts))
    mesh.polygons.foreach_set("loop_start", starts)
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
