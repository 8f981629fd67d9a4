"""The collection FibrilFit owns, and removing what it built without touching anything else.

Everything the model creates is tagged with the custom property TAG, so it is found by tag,
never by name: a user's "Sphere.001" or "globula" is never ours.
"""
from __future__ import annotations

import bpy

TAG = "fibrilfit"          # on every ID the model creates; value = its role
LAYER = "fibrilfit_layer"  # on objects: layer index, 0 = lowest
INDEX = "fibrilfit_index"  # on chain objects: 0 = anchor ... linker = globule
PROTOFILAMENT = "fibrilfit_protofilament"  # on chain objects and bonds: 0 .. K - 1
ROOT = "model"
PART_COLLECTIONS = {"slab": "slabs", "anchor": "anchors", "residue": "linkers",
                    "globule": "globules", "bond": "bonds"}  # role: title; tagged role + "s"
WORLD_OWNED = "fibrilfit_owns_rigidbody_world"


def tag(id_block, role: str):
    id_block[TAG] = role
    return id_block


def is_ours(id_block) -> bool:
    return id_block.get(TAG) is not None


def find_root(scene: bpy.types.Scene) -> bpy.types.Collection | None:
    for coll in scene.collection.children_recursive:
        if coll.get(TAG) == ROOT:
            return coll
    return None


def new_collection(name: str, role: str, parent: bpy.types.Collection) -> bpy.types.Collection:
    coll = tag(bpy.data.collections.new(name), role)
    parent.children.link(coll)
    return coll


def clear_model(scene: bpy.types.Scene) -> int:
    """Remove the model and every datablock it made that nothing else uses. Returns objects removed."""
    root = find_root(scene)
    removed = 0
    if root is not None:
        colls = [root, *root.children_recursive]
        objects = {ob for c in colls for ob in c.objects if is_ours(ob)}
        removed = len(objects)
        bpy.data.batch_remove(objects)
        bpy.data.batch_remove([c for c in colls if is_ours(c)])
    rbw = scene.rigidbody_world
    if rbw is not None:
        for attr in ("collection", "constraints"):
            coll = getattr(rbw, attr)
            if coll is not None and is_ours(coll):
                setattr(rbw, attr, None)
                if not coll.objects:
                    bpy.data.collections.remove(coll)
    if scene.world is not None and is_ours(scene.world):  # the render's backdrop (exports/)
        scene.world = None
    # Meshes first: a material is an orphan only once the meshes using it are gone.
    for kinds in ((bpy.data.meshes, bpy.data.curves, bpy.data.cameras, bpy.data.lights,
                   bpy.data.worlds, bpy.data.volumes, bpy.data.node_groups),
                  (bpy.data.materials,)):
        bpy.data.batch_remove([d for kind in kinds for d in kind if is_ours(d) and d.users == 0])
    return removed
