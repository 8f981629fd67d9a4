"""The fibril: `layers` copies of slab + anchor + linker + globule, each raised and twisted."""
from __future__ import annotations

from dataclasses import dataclass

import bpy
import numpy as np

from .. import params as P
from . import meshes
from .physics import check_world_free, ensure_world
from .scene import INDEX, LAYER, ROOT, clear_model, find_root, new_collection, tag

COLORS = {  # viewport/object colours; analysis recolours clashing globules
    "slab": (0.55, 0.62, 0.75, 1.0),
    "anchor": (0.25, 0.25, 0.3, 1.0),
    "residue": (0.95, 0.75, 0.2, 1.0),
    "globule": (0.7, 0.72, 0.7, 1.0),
}


@dataclass
class Model:
    """Handles to a built model. `chain[k][i]`: layer k, member i (0 anchor .. linker globule)."""

    root: bpy.types.Collection
    params: P.Params
    slabs: list
    chain: list
    constraints: list

    @property
    def globules(self) -> list:
        return [c[-1] for c in self.chain]

    @property
    def active(self) -> list:
        return [ob for c in self.chain for ob in c[1:]]


def layer_transforms(p: P.Params, count: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Angle (rad) and height (Å) of each layer about/along the fibril axis Z."""
    k = np.arange(p.layers if count is None else count, dtype=float)
    return k * p.twist, k * p.rise


def chain_positions(p: P.Params) -> np.ndarray:
    """Rest positions of every chain member, shape (layers, linker + 1, 3)."""
    angle, height = layer_transforms(p)
    x = np.asarray(p.chain_x())
    pos = np.empty((p.layers, x.size, 3))
    pos[..., 0] = np.cos(angle)[:, None] * x
    pos[..., 1] = np.sin(angle)[:, None] * x
    pos[..., 2] = height[:, None]
    return pos


def bond_pivots(p: P.Params) -> np.ndarray:
    """POINT-constraint pivots: where consecutive members touch, shape (layers, linker, 3)."""
    pos = chain_positions(p)
    a, b = pos[:, :-1], pos[:, 1:]
    ra = np.asarray(p.chain_radii()[:-1])
    frac = ra / np.asarray(p.rest_lengths())
    return a + (b - a) * np.minimum(frac, 1.0)[None, :, None]


def find_model(scene: bpy.types.Scene) -> Model | None:
    """The model built in `scene`, reassembled from its tags, or None."""
    root = find_root(scene)
    if root is None:
        return None
    p = P.make_params(force=True, **{k: v for k, v in root["params"].to_dict().items()})
    slabs, chain, cons = {}, {}, {}
    for ob in root.all_objects:
        role, k = ob.get("fibrilfit"), ob.get(LAYER)
        if role == "slab":
            slabs[k] = ob
        elif role in ("anchor", "residue", "globule"):
            chain.setdefault(k, {})[ob[INDEX]] = ob
        elif role == "bond":
            cons.setdefault(k, {})[ob[INDEX]] = ob
    ordered = lambda d: [d[i] for i in sorted(d)]
    return Model(root, p, ordered(slabs), [ordered(chain[k]) for k in sorted(chain)],
                 [ordered(cons[k]) for k in sorted(cons)])


def build_model(p: P.Params, scene: bpy.types.Scene | None = None, *, force: bool = False) -> Model:
    """Build the model in `scene` (default: the context's), replacing any previous one.

    Validates first (raising ParamError), so bad input leaves the scene as it was.
    """
    p = P.validate(p, force=force)
    scene = scene or bpy.context.scene
    check_world_free(scene)
    clear_model(scene)
    rbw = ensure_world(scene)

    root = new_collection("FibrilFit", ROOT, scene.collection)
    root["params"] = p.to_dict()
    parts = {role: new_collection(f"FibrilFit {title}", role + "s", root) for role, title in
             (("slab", "slabs"), ("anchor", "anchors"), ("residue", "linkers"),
              ("globule", "globules"), ("bond", "bonds"))}
    bodies = tag(bpy.data.collections.new("FibrilFit bodies"), "rigid_bodies")
    bonds = tag(bpy.data.collections.new("FibrilFit constraints"), "rigid_constraints")
    rbw.collection, rbw.constraints = bodies, bonds

    mesh = {
        "slab": meshes.box("FibrilFit slab", p.slab),
        "anchor": meshes.uv_sphere("FibrilFit residue", p.residue_radius,
                                   P.RESIDUE_SEGMENTS, P.RESIDUE_RINGS),
        "globule": meshes.uv_sphere("FibrilFit globule", p.globule_radius,
                                    P.GLOBULE_SEGMENTS, P.GLOBULE_RINGS),
    }
    mesh["residue"] = mesh["anchor"]

    slabs, chain, constraints = [], [], []
    for k in range(p.layers):
        # Objects are linked in the same order as ever (the rigid-body world's order is Bullet's
        # order, so it fixes the result for a seed); transforms and colours come after, in bulk.
        slabs.append(_body(f"FF{k:04d} slab", mesh["slab"], "slab", k, parts, bodies,
                           "PASSIVE", "BOX"))
        members = []
        for i in range(p.linker + 1):
            role = "anchor" if i == 0 else ("globule" if i == p.linker else "residue")
            ob = _body(f"FF{k:04d} {role} {i}", mesh[role], role, k, parts, bodies,
                       "PASSIVE" if i == 0 else "ACTIVE", "SPHERE")
            ob[INDEX] = i
            members.append(ob)
        chain.append(members)
        bonds_k = []
        for i in range(p.linker):
            empty = tag(bpy.data.objects.new(f"FF{k:04d} bond {i}", None), "bond")
            empty[LAYER], empty[INDEX] = k, i
            parts["bond"].objects.link(empty)
            bonds.objects.link(empty)
            rbc = empty.rigid_body_constraint
            rbc.type = "POINT"
            rbc.object1, rbc.object2 = members[i], members[i + 1]
            rbc.disable_collisions = True
            bonds_k.append(empty)
        constraints.append(bonds_k)
    place(p, parts)
    # No view_layer.update() here: place() sets valid world matrices, and the depsgraph is
    # built once, on first use (the bake's first frame, or the viewport's next redraw).
    return Model(root, p, slabs, chain, constraints)


def layer_placements(p: P.Params) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Location and Z rotation of every object of each part, in the order they are linked."""
    angle, height = layer_transforms(p)
    pos, pivots = chain_positions(p), bond_pivots(p)
    slab_loc = np.zeros((p.layers, 3))
    slab_loc[:, 2] = height
    members_angle = np.repeat(angle, p.linker - 1)
    return {
        "slab": (slab_loc, angle),
        "anchor": (pos[:, 0], angle),
        "residue": (pos[:, 1:-1].reshape(-1, 3), members_angle),
        "globule": (pos[:, -1], angle),
        "bond": (pivots.reshape(-1, 3), np.zeros(pivots.shape[0] * pivots.shape[1])),
    }


def place(p: P.Params, parts: dict) -> None:
    """Set location, rotation, world matrix and colour of every object, one foreach_set each."""
    for role, (loc, rot_z) in layer_placements(p).items():
        objects = parts[role].objects
        n = len(objects)
        rot = np.zeros((n, 3))
        rot[:, 2] = rot_z
        objects.foreach_set("location", loc.astype(np.float32).ravel())
        objects.foreach_set("rotation_euler", rot.astype(np.float32).ravel())
        # The world matrix too, so it is valid before any depsgraph evaluation. foreach_set
        # writes Blender's float[4][4] as stored: column-major, translation in the last row.
        mat = np.zeros((n, 4, 4))
        c, s = np.cos(rot_z), np.sin(rot_z)
        mat[:, 0, 0], mat[:, 0, 1], mat[:, 1, 0], mat[:, 1, 1] = c, s, -s, c
        mat[:, 2, 2] = mat[:, 3, 3] = 1.0
        mat[:, 3, :3] = loc
        objects.foreach_set("matrix_world", mat.astype(np.float32).ravel())
        if role == "bond":
            objects.foreach_set("empty_display_size", np.full(n, p.residue_radius, np.float32))
        else:
            objects.foreach_set("color", np.tile(np.float32(COLORS[role]), n))


def _body(name, mesh, role, k, parts, bodies, rb_type, shape):
    ob = tag(bpy.data.objects.new(name, mesh), role)
    ob[LAYER] = k
    parts[role].objects.link(ob)
    bodies.objects.link(ob)
    rb = ob.rigid_body
    rb.type = rb_type
    rb.collision_shape = shape
    return ob
