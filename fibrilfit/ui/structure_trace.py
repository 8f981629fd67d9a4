"""The imported structures in the scene: the fibril's CA trace on the model's core and each
domain's beside the layer-0 globule (one after the other along -Y, in the list's order), each one
tagged mesh object (no rigid body) in a collection FibrilFit owns; the measurements kept on it.
A build moves them with the model (follow): the fibril's trace stays centred in the model's
stack of layers, the domains' beside its layer-0 globule."""
from __future__ import annotations

import json

import bpy
import numpy as np

from ..builders.scene import TAG, is_ours, tag
from ..model.chain import chain_x
from ..structure import trace

COLLECTION = "structures"  # role of the collection holding imported structures
TRACE = "structure_trace"  # role of a CA trace object
MEASURED = "fibrilfit_measured"  # JSON of the measurements, on the collection: {fibril, domain}
KIND = "fibrilfit_trace_of"  # on a trace object: "fibril" or "domain"
ENTRY = "fibrilfit_trace_entry"  # on a domain's trace: the list entry it shows (entry_key)
PLACED = "fibrilfit_trace_placed"  # on the fibril's: [layers shifted, rise, twist, lo, hi]
REACH = "fibrilfit_trace_reach"  # on a domain's: its farthest CA from its centre, Å
GAP = 5.0  # Å between a domain's trace and the globule or the trace before it


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


def traces(scene, kind: str) -> list:
    """The `kind` ("fibril" or "domain") CA traces, oldest first."""
    coll = find_collection(scene)
    if coll is None:
        return []
    return [ob for ob in coll.objects if is_ours(ob) and ob.get(TAG) == TRACE
            and ob.get(KIND, "fibril") == kind]


def entry_key(filepath: str, chain: str, residues: str) -> str:
    """What names a domain of the list (ui/domain_list.py's entry) on its trace."""
    return f"{filepath}|{chain}|{residues}"


def remove_traces(scene, kind: str, entry: str | None = None) -> None:
    """Remove the `kind` traces (only the one of list entry `entry`, when given)."""
    old = [ob for ob in traces(scene, kind) if entry is None or ob.get(ENTRY) == entry]
    old_meshes = [ob.data for ob in old]
    bpy.data.batch_remove(old)
    bpy.data.batch_remove([m for m in old_meshes if m.users == 0])


def add_trace(scene, chains, name: str, offset=(0.0, 0.0, 0.0), kind: str = "fibril",
              entry: str | None = None) -> bpy.types.Object:
    """Replace the `kind` CA trace (a domain's: the one of list entry `entry`, the other
    domains' kept): one vertex per CA, an edge between consecutive residues of a chain (no edge
    across a gap in the numbering). `chains`: [(chain, residues, xyz)]."""
    coll = collection(scene)
    remove_traces(scene, kind, entry if kind == "domain" else None)
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
    if entry is not None:
        ob[ENTRY] = entry
    coll.objects.link(ob)
    return ob


def place_fibril(ob, chains_layers: list, p) -> None:
    """Put the fibril's trace `ob` (its vertices as first placed, PLACED) on the model `p`: its
    file's layers centred in p's stack (or cell) of layers, along p's screw (trace.on_model's
    shift, applied as the object's turn about Z and rise along it)."""
    if chains_layers:  # first placed: its vertices are on_model's for these values
        lo, hi = min(chains_layers), max(chains_layers)
        _, s = trace.on_model([], [lo, hi], p.periodic or p.layers, p.rise, p.twist)
        ob[PLACED] = [s, p.rise, p.twist, lo, hi]
        return
    s0, rise0, twist0, lo, hi = ob[PLACED]
    _, s = trace.on_model([], [int(lo), int(hi)], p.periodic or p.layers, p.rise, p.twist)
    ob.rotation_euler = (0.0, 0.0, s * p.twist - s0 * twist0)
    ob.location = (0.0, 0.0, s * p.rise - s0 * rise0)


def place_domains(scene, p) -> None:
    """Each domain's trace beside the model `p`'s layer-0 globule, at its rest place (the
    chain's end), one after the other along -Y in the order imported, clear of the globule and of
    each other."""
    x, y = max(chain_x(p)) + p.globule_radius, -p.globule_radius - GAP
    for ob in traces(scene, "domain"):
        reach = float(ob.get(REACH, 0.0))
        ob.location = (x, y - reach, 0.0)
        y -= 2 * reach + GAP


def follow(scene, p) -> None:
    """After a build: the traces where the model `p` has its core and layer-0 globule."""
    for ob in traces(scene, "fibril"):
        if PLACED in ob:
            place_fibril(ob, [], p)
    place_domains(scene, p)


def points(scene) -> np.ndarray:
    """Every trace's vertices in world coordinates (n, 3): what Import frames."""
    out = [np.zeros((0, 3))]
    for ob in traces(scene, "fibril") + traces(scene, "domain"):
        co = np.empty(3 * len(ob.data.vertices))
        ob.data.vertices.foreach_get("co", co)
        m = np.array(ob.matrix_basis)  # no parent; live, unlike matrix_world
        out.append(co.reshape(-1, 3) @ m[:3, :3].T + m[:3, 3])
    return np.concatenate(out)


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
