"""The tutorial's step 8 without its damage: one new mesh of all globules, for Mesh Analysis.

The tutorial joined the globule objects themselves, which destroyed the simulation. This adds a
separate, static copy at the current frame and leaves the rigid bodies and their cache alone.
"""
from __future__ import annotations

import bpy
import numpy as np

from ..analysis.clashes import joined_globules
from ..analysis.verdict import world_matrices
from .scene import LAYER, TAG, is_ours, tag

ROLE = "joined"


def join_globules(model) -> bpy.types.Object:
    """Replace any earlier joined copy with the globules, joined in world space as they stand now.

    Each face carries the integer attribute "fibrilfit_layer", the layer of its globule.
    """
    remove_joined(model)
    globules = model.globules
    mesh_in = globules[0].data
    verts, polys = joined_globules(mesh_in, world_matrices(globules))
    mesh = tag(bpy.data.meshes.new("FibrilFit joined globules"), ROLE)
    mesh.from_pydata(verts.tolist(), [], polys)
    layers = np.repeat(np.array([ob[LAYER] for ob in globules], dtype=np.int32),
                       len(mesh_in.polygons))
    mesh.attributes.new(LAYER, "INT", "FACE").data.foreach_set("value", layers)
    mesh.update()
    ob = tag(bpy.data.objects.new("FibrilFit joined globules", mesh), ROLE)
    model.root.objects.link(ob)
    return ob


def find_joined(model) -> list:
    return [ob for ob in model.root.objects if ob.get(TAG) == ROLE]


def remove_joined(model) -> int:
    """Remove the joined copy (object and mesh); returns how many objects went."""
    obs = find_joined(model)
    meshes = [ob.data for ob in obs if ob.data is not None and is_ours(ob.data)]
    bpy.data.batch_remove(obs)
    bpy.data.batch_remove([m for m in meshes if m.users == 0])
    return len(obs)
