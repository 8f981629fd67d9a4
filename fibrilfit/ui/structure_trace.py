"""The imported structures in the scene: the fibril's CA trace on the model's core and the
domain's beside the layer-0 globule, each one tagged mesh object (no rigid body) in a collection
FibrilFit owns; the measurements kept on it."""
from __future__ import annotations

import json

import bpy
import numpy as np

from ..builders.scene import TAG, is_ours, tag

COLLECTION = "structures"  # role of the collection holding imported structures
TRACE = "structure_trace"  # role of a CA trace object
MEASURED = "fibrilfit_measured"  # JSON of the measurements, on the collection: {fibril, domain}
KIND = "fibrilfit_trace_of"  # on a trace object: "fibril" or "domain"


def find_collection(scene) -> bpy.types.Collection | None:
    for coll in scene.collection.children_recursive:
        if coll.get(TAG) == COLLECTION:
            return coll
    return None


def collection(scene) -> bpy.types.Collection:
    coll = find_collection(scene)
    if coll is None:
        coll = tag(bpy.data.collections.new("FibrilFit structures"), COLLECTION)
        scene.collection.children.link(coll)
    return coll


def measured(scene) -> dict:
    coll = find_collection(scene)
    return json.loads(coll.get(MEASURED, "{}")) if coll is not None else {}


def store(scene, key: str, values: dict) -> None:
    coll = collection(scene)
    data = measured(scene)
    data[key] = values
    coll[MEASURED] = json.dumps(data)


def add_trace(scene, chains, name: str, offset=(0.0, 0.0, 0.0),
              kind: str = "fibril") -> bpy.types.Object:
    """Replace the `kind` CA trace: one vertex per CA, an edge between consecutive residues of a
    chain (no edge across a gap in the numbering). `chains`: [(chain, residues, xyz)]."""
    coll = collection(scene)
    old = [ob for ob in coll.objects if is_ours(ob) and ob.get(TAG) == TRACE
           and ob.get(KIND, "fibril") == kind]
    old_meshes = [ob.data for ob in old]
    bpy.data.batch_remove(old)
    bpy.data.batch_remove([m for m in old_meshes if m.users == 0])
    verts, edges = [], []
    for _, residues, xyz in chains:
        start = len(verts)
        verts.extend(map(tuple, np.asarray(xyz, float)))
        step = np.diff(residues) == 1
        edges.extend((start + i, start + i + 1) for i in np.nonzero(step)[0])
    mesh = tag(bpy.data.meshes.new(f"{name} CA trace"), TRACE)
    mesh.from_pydata(verts, edges, [])
    ob = tag(bpy.data.objects.new(f"{name} CA trace", mesh), TRACE)
    ob.location = offset
    ob[KIND] = kind
    coll.objects.link(ob)
    return ob


def remove_all(scene) -> None:
    coll = find_collection(scene)
    if coll is None:
        return
    meshes = [ob.data for ob in coll.objects if is_ours(ob)]
    bpy.data.batch_remove([ob for ob in coll.objects if is_ours(ob)])
    bpy.data.batch_remove([m for m in meshes if m.users == 0])
    bpy.data.collections.remove(coll)


def request(scene, settings):
    """The structure files the panel's values were measured from, as the command line names
    them (a StructureRequest: --fibril with its terminus and anchor residue, each --domain with
    its chain and residues, or --full-length): the imported fibril and the domain list. Empty
    (request.any False) when nothing was imported."""
    from ..structure.request import StructureRequest
    fib = (measured(scene).get("fibril") or {}).get("asked") or {}
    entries = list(settings.domains)
    whole = [e.filepath for e in entries if e.option == "--full-length"]
    parts = [e for e in entries if e.option != "--full-length"]
    return StructureRequest(
        fibril=fib.get("path"), terminus=fib.get("terminus") or "C",
        anchor_residue=fib.get("anchor_residue"),
        domain=tuple(e.filepath for e in parts) if not whole else (),
        domain_chain=tuple(e.chain for e in parts) if not whole else (),
        domain_residues=tuple(e.residues for e in parts) if not whole else (),
        full_length=whole[0] if whole else None)
