"""The bodies of each layer: one part of one layer at a time (the tutorial's order), sharing
meshes and the precomputed layer geometry, then every transform and colour set in bulk
(LayerBuilder.place). How each domain shape is drawn: GLOBULE_MESHES.

A mixed fibril (model/occupancy.py): only the decorated subunits get a chain (anchor, linker,
domains); the others get their bare tail (role "tail", bonds "tail_bond"), kept apart from the
chains so that every chain of model.chain is whole (docs/model/occupancy.md#the-model), or,
without a tail, a marker at their anchor's place (role "bare_anchor": drawn, no body, so the
physics is the same) so the picture shows which subunits carry the domain.

Over 400 lines because LayerBuilder is one room: which bodies a layer gets (core, anchor,
linker, domains, bare tails) and where they go are decided together, over the same shared
meshes and layer geometry; splitting the tails out is the seam if it grows further."""
from __future__ import annotations

import bpy
import numpy as np

from ..geom import shape
from ..geom.rigid import euler_xyz, joint_rotations
from ..model import helix, hetero, occupancy, params as P
from ..model.param_spec import GLOBULE_RINGS, GLOBULE_SEGMENTS, RESIDUE_RINGS, RESIDUE_SEGMENTS
from ..model.bent_layout import domain_terminals, real_chain_layout, spread_chains
from ..model.chain import tail_chain, tail_members
from ..model.start_layout import (bond_pivots, inflate_layout, rest_positions, spread_layout,
                                  walk_directions)
from . import meshes
from .colours import part_colour
from .scene import INDEX, LAYER, PART_COLLECTIONS, PROTOFILAMENT, TAG, new_collection, tag


class LayerBuilder:
    """Adds one part of one layer at a time; shares meshes and the precomputed layer geometry."""

    def __init__(self, model, scene: bpy.types.Scene):
        self.model = model
        p = self.p = model.params
        rbw = scene.rigidbody_world
        self.bodies, self.bonds = rbw.collection, rbw.constraints
        tags = {c.get(TAG): c for c in model.root.children}
        self.parts = {role: tags[role + "s"] for role in PART_COLLECTIONS}
        self.angle, self.height = helix.layer_transforms(p)  # per layer: the cores
        self.chain_angle = helix.chain_transforms(p)[0]     # per chain: its members
        self.pos, self.pivots = rest_positions(p), bond_pivots(p)
        self.pfs = p.protofilaments
        self.turns = None  # several real shapes: each domain's turn (chains, D, 3, 3)
        if p.several_shapes:  # bent at every domain (docs/guide/atoms-and-domains.md#shapes-of-several-domains)
            if p.protocol == "tutorial" and p.shape.spread:  # full size: spread
                self.pos, self.pivots, self.turns = spread_chains(p, self.pos)
            else:
                wanted = walk_directions(p, self.pos, p.seed) if p.protocol == "inflate" else None
                self.pos, self.pivots, self.turns = real_chain_layout(p, self.pos, wanted)
        elif p.protocol == "inflate":  # fanned random walks: positions and pivots of that layout
            self.pos, self.pivots = inflate_layout(p, self.pos, p.seed)
        elif p.shape.spread:  # full size from the start: spread, or they can lock
            # (docs/model/domain-shapes.md#spheres-start)
            self.pos, self.pivots = spread_layout(p, self.pos, spheres_body(p))
        # a hetero-amyloid: the B subunits' chains are B's model's (its diameter and linker),
        # laid out as A's are (docs/model/occupancy.md#hetero)
        self.b = hetero.b_subunits(p)
        if self.b.any():
            self._b_layout()
        self.domain_at = {d.member: d for d in p.domains}  # each domain by its place
        # which subunits carry the domain (chain c, layer-major); model.chain holds those only,
        # in the same order: self.slot[c] is chain c's place in it
        self.decorated = occupancy.decorated(p).ravel()
        self.slot = {}
        self.tail = tail_members(p) if not self.decorated.all() else 0
        if self.tail:
            self.tail_pos, self.tail_pivots = tail_layout(p, self.tail)
        self.mesh = {}
        # Each object with its (layer, index), per part, in the order they were linked: place()
        # sets transforms and colours in bulk afterwards (one foreach_set each, not per object).
        self.placed = {role: [] for role in PART_COLLECTIONS}

    def _b_layout(self) -> None:
        """The B subunits' rest (or inflate) places and pivots: B's model's, whose last bond
        reaches B's surface; the same start as A's chains otherwise (the same seed's walks)."""
        q = hetero.b_params(self.p)
        pos, pivots = rest_positions(q), bond_pivots(q)
        if self.p.protocol == "inflate":
            pos, pivots = inflate_layout(q, pos, self.p.seed)
        self.pos = np.where(self.b[:, None, None], pos, self.pos)
        self.pivots = np.where(self.b[:, None, None], pivots, self.pivots)

    def add(self, part: str, k: int) -> None:
        getattr(self, "_" + part)(k)

    def _shared_mesh(self, role):
        if role not in self.mesh:
            p = self.p
            if role == "slab" and p.core_outline is not None:
                self.mesh[role] = meshes.prism("FibrilFit core", p.outline(), p.rise)
            elif role == "slab":
                self.mesh[role] = meshes.box("FibrilFit slab", p.slab)
            elif role == "globule":
                self.mesh[role] = globule_mesh(p)
            elif role.startswith("globule "):  # several real shapes: domain k's own
                self.mesh[role] = globule_mesh(p, int(role.split()[1]))
            else:  # the anchor and the linker's residues are the same bead
                self.mesh[role] = meshes.uv_sphere("FibrilFit residue", p.residue_radius,
                                                   RESIDUE_SEGMENTS, RESIDUE_RINGS)
        return self.mesh[role]

    def _slab(self, k):
        # A concave outline: a convex hull would fill its notches (docs/model/protofilaments.md#concave-cores), and
        # Bullet's triangle-mesh shape is a hollow surface that traps a bead once it is pushed
        # through (docs/model/protofilaments.md#stretched-linkers). So the core is a
        # compound of solid convex prisms, children of the slab, which keeps the drawn prism.
        shape = "BOX" if self.p.core_outline is None else "COMPOUND"
        slab = _body(f"FF{k:04d} slab", self._shared_mesh("slab"), "slab", k, self.parts,
                     self.bodies, "PASSIVE", shape)
        self.placed["slab"].append((slab, k, 0))
        self.model.slabs.append(slab)
        if shape == "COMPOUND":
            self._core_pieces(slab, k)

    def _core_pieces(self, slab, k):
        """The convex prisms of layer k's core outline, parented to its slab (same frame)."""
        if "pieces" not in self.mesh:
            self.mesh["pieces"] = [meshes.prism(f"FibrilFit core piece {i}", piece, self.p.rise)
                                   for i, piece in enumerate(meshes.convex_pieces(
                                       self.p.outline()))]
            self.pieces_coll = new_collection("FibrilFit core pieces", "core_pieces",
                                              self.parts["slab"])
        for i, mesh in enumerate(self.mesh["pieces"]):
            ob = tag(bpy.data.objects.new(f"FF{k:04d} core piece {i}", mesh), "core_piece")
            ob[LAYER], ob[INDEX] = k, i
            self._compound_part(ob, slab, self.pieces_coll, "PASSIVE", "CONVEX_HULL")
            self.placed.setdefault("core_piece", []).append((ob, k, 0))

    def _compound_part(self, ob, parent, coll, kind: str, shape: str) -> None:
        """A hidden wire child body of `parent` (a core piece of its slab, a covering sphere of
        its globule): in `coll` and the rigid-body world, with its kind and collision shape."""
        ob.parent = parent
        ob.hide_render = True
        ob.display_type = "WIRE"
        coll.objects.link(ob)
        self.bodies.objects.link(ob)
        ob.rigid_body.type = kind
        ob.rigid_body.collision_shape = shape

    def _name(self, k, j):
        return f"FF{k:04d}" if self.pfs == 1 else f"FF{k:04d}.{j}"

    def _member(self, k, i):
        """Member i of every protofilament's chain in layer k, protofilament 0 first."""
        for j in range(self.pfs):
            self._chain_member(k, j, i)

    def _chain_member(self, k, j, i):
        p = self.p
        c = k * self.pfs + j
        if not self.decorated[c]:  # an undecorated subunit: its bare tail's anchor, if any
            # (its beads, however many: _linker; never again at a globule's place)
            if i == 0 and self.tail:
                self._tail_member(k, j, i)
            elif i == 0 and not self.tail:
                self._bare_anchor(k, j)
            return
        role = "anchor" if i == 0 else ("globule" if i in self.domain_at else "residue")
        # several real shapes: each domain its own mesh; spheres share domain 1's, scaled
        domain = self.domain_at[i].index if role == "globule" and p.shape.real else 0
        mesh = self._shared_mesh(("globule" if not domain else f"globule {domain}")
                                 if role == "globule" else "residue")
        shape = p.shape.collision if role == "globule" else "SPHERE"
        ob = _body(f"{self._name(k, j)} {role} {i}", mesh, role, k, self.parts, self.bodies,
                   "PASSIVE" if i == 0 else "ACTIVE", shape)
        ob[INDEX], ob[PROTOFILAMENT] = i, j
        if role == "globule" and p.shape.real:
            self._real_globule(ob, k, domain)
        self.placed[role].append((ob, c, i))
        chain = self.model.chain
        if i == 0:
            self.slot[c] = len(chain)
            chain.append([])
            self.model.constraints.append([])
        chain[self.slot[c]].append(ob)
        if i > 0:
            self._bond(k, j, i - 1)

    def _tail_member(self, k, j, i):
        """Bead i of an undecorated subunit's bare tail (0: its passive anchor), bonded to the
        one before; in the tails' own collections (tails_collections)."""
        if "tail" not in self.parts:
            self.parts.update(tails_collections(self.model.root))
            self.placed.update(tail=[], tail_bond=[])
        c = k * self.pfs + j
        ob = _body(f"{self._name(k, j)} tail {i}", self._shared_mesh("residue"), "tail", k,
                   self.parts, self.bodies, "PASSIVE" if i == 0 else "ACTIVE", "SPHERE")
        ob[INDEX], ob[PROTOFILAMENT] = i, j
        self.placed["tail"].append((ob, c, i))
        if i == 0:
            self.slot[c] = len(self.model.tails)
            self.model.tails.append([])
        members = self.model.tails[self.slot[c]]
        members.append(ob)
        if i > 0:
            empty = tag(bpy.data.objects.new(f"{self._name(k, j)} tail bond {i - 1}", None),
                        "tail_bond")
            empty[LAYER], empty[INDEX], empty[PROTOFILAMENT] = k, i - 1, j
            self.placed["tail_bond"].append((empty, c, i - 1))
            self.parts["tail_bond"].objects.link(empty)
            self.bonds.objects.link(empty)
            rbc = empty.rigid_body_constraint
            rbc.type = "POINT"
            rbc.object1, rbc.object2 = members[i - 1], members[i]
            rbc.disable_collisions = True

    def _bare_anchor(self, k, j):
        """The marker of an undecorated subunit without a tail: the anchor's bead at its place,
        in the bare tails' colour, in a collection of its own; not a rigid body (nothing in the
        physics changes), only what the picture and the viewport show."""
        if "bare_anchor" not in self.parts:
            self.parts["bare_anchor"] = new_collection("FibrilFit bare anchors", "bare_anchors",
                                                       self.model.root)
            self.placed["bare_anchor"] = []
        ob = tag(bpy.data.objects.new(f"{self._name(k, j)} bare anchor",
                                      self._shared_mesh("residue")), "bare_anchor")
        ob[LAYER], ob[INDEX], ob[PROTOFILAMENT] = k, 0, j
        self.parts["bare_anchor"].objects.link(ob)
        self.placed["bare_anchor"].append((ob, k * self.pfs + j, 0))
        self.model.bare_anchors.append(ob)

    def _real_globule(self, ob, k, domain=0):
        """A hull keeps Bullet's surface its margin (domains.HULL_MARGIN) outside its mesh (the
        mesh is what the check tests); spheres become a compound of child spheres, like the
        concave cores. `domain`: which domain of the chain (several real shapes: each its own
        spheres)."""
        if self.p.shape.margin is not None:
            ob.rigid_body.use_margin = True
            ob.rigid_body.collision_margin = self.p.shape.margin
        if not self.p.shape.compound:
            return
        key = "sphere_meshes" if not domain else f"sphere_meshes {domain}"
        spheres = [tuple(row) for row in self.p.domains[domain].rows]
        if key not in self.mesh:
            name = "FibrilFit globule sphere" if not domain else f"FibrilFit domain {domain} sphere"
            self.mesh[key] = [
                meshes.uv_sphere(f"{name} {n}", r, GLOBULE_SEGMENTS, GLOBULE_RINGS)
                for n, (*_, r) in enumerate(spheres)]
        if not hasattr(self, "spheres_coll"):
            self.spheres_coll = new_collection("FibrilFit globule spheres", "globule_spheres",
                                               self.parts["globule"])
        for n, ((x, y, z, _), mesh) in enumerate(zip(spheres, self.mesh[key])):
            child = tag(bpy.data.objects.new(f"{ob.name} sphere {n}", mesh), "globule_sphere")
            child[LAYER], child[INDEX] = k, n
            child.location = (x, y, z)
            self._compound_part(child, ob, self.spheres_coll, "ACTIVE", "SPHERE")
            self.placed.setdefault("globule_sphere", []).append((child, ob))

    def _bond(self, k, j, i):
        """The POINT constraint between members i and i + 1 of protofilament j's chain in layer k."""
        c = k * self.pfs + j
        members = self.model.chain[self.slot[c]]
        empty = tag(bpy.data.objects.new(f"{self._name(k, j)} bond {i}", None), "bond")
        empty[LAYER], empty[INDEX], empty[PROTOFILAMENT] = k, i, j
        self.placed["bond"].append((empty, c, i))
        self.parts["bond"].objects.link(empty)
        self.bonds.objects.link(empty)
        rbc = empty.rigid_body_constraint
        rbc.type = "POINT"
        rbc.object1, rbc.object2 = members[i], members[i + 1]
        rbc.disable_collisions = True
        self.model.constraints[self.slot[c]].append(empty)

    def _anchor(self, k):
        self._member(k, 0)

    def _linker(self, k):
        for j in range(self.pfs):  # each protofilament's linker whole: bonds in chain order
            # (an undecorated subunit: its whole bare tail, however long)
            if not self.decorated[k * self.pfs + j]:
                for i in range(1, self.tail):
                    self._tail_member(k, j, i)
                continue
            for i in range(1, self.p.free_linker):
                self._chain_member(k, j, i)

    def _globule(self, k):
        self._member(k, self.p.free_linker)
        self._further_domains(k)

    def _further_domains(self, k):
        """Several domains per chain: each protofilament's chain on from its first globule
        (beads, globule, beads, globule ...), bonds in chain order."""
        last = self.p.domains[-1].member
        for j in range(self.pfs):
            for i in range(self.p.free_linker + 1, last + 1):
                self._chain_member(k, j, i)

    def _domain_scale(self, members: np.ndarray, chains: np.ndarray):
        """Globules of further domains share domain 1's mesh, scaled to their size: Bullet's
        sphere follows the scale (docs/guide/atoms-and-domains.md#several-domains). None for
        one domain (no scale set: the build as before). A hetero-amyloid's B globules share A's
        sphere too, at B's scale (`chains`: each globule's chain)."""
        if self.b.any():  # one sphere domain per chain (occupancy.check_second_domain)
            return np.where(self.b[chains], hetero.b_scale(self.p), 1.0)
        if len(self.domain_at) == 1 or self.p.shape.real:  # each its own mesh
            return None
        return np.array([self.domain_at[int(i)].radius / self.p.globule_radius for i in members])

    def place(self) -> None:
        """Location, rotation, world matrix and colour of every object, one foreach_set each.

        The objects were linked in the order Bullet sees them (that order fixes the result for
        a seed); only their transforms come later, with the same float32 values as one by one.
        """
        for role, placed in self.placed.items():
            if role == "globule_sphere":  # children of their globule: placed with it, below
                continue
            if role == "core_piece":  # children of their slab: the slab's frame
                objects = _in_order(self.pieces_coll, [ob for ob, _, _ in placed])
                k = np.array([ki for _, ki, _ in placed], dtype=np.intp)
                loc = np.zeros((len(k), 3))
                loc[:, 2] = self.height[k]
                _place(objects, np.zeros((len(k), 3)), np.zeros(len(k)), loc, self.angle[k])
                continue
            objects = _in_order(self.parts[role], [ob for ob, _, _ in placed])
            # (layer, 0) for slabs; (chain, member) for the rest
            k, i = np.array([ki for _, *ki in placed], dtype=np.intp).reshape(-1, 2).T
            if role == "slab":
                loc = np.zeros((len(k), 3))
                loc[:, 2] = self.height[k]
            elif role.startswith("tail"):
                loc = (self.tail_pivots if role == "tail_bond" else self.tail_pos)[k, i]
            else:
                loc = (self.pivots if role == "bond" else self.pos)[k, i]
            rot_z = (np.zeros(len(k)) if role in ("bond", "tail_bond") else
                     self.angle[k] if role == "slab" else self.chain_angle[k])
            scale = self._domain_scale(i, k) if role == "globule" else None
            _place(objects, loc, rot_z, scale=scale)
            if role == "globule" and self.turns is not None:  # several real shapes
                dom = np.array([self.domain_at[int(m)].index for m in i])
                self._turn_globules(objects, k, loc, self.turns[k, dom])
            elif role == "globule" and self.p.shape.real:  # one domain a chain
                self._turn_globules(objects, k, loc)
            if role in ("bond", "tail_bond"):
                objects.foreach_set("empty_display_size",
                                    np.full(len(k), self.p.residue_radius, np.float32))
            else:
                pf = k % self.pfs if role != "slab" else np.zeros(len(k), dtype=np.intp)
                tints = np.array([part_colour(role, j) for j in range(self.pfs)], np.float32)
                objects.foreach_set("color", tints[pf].ravel())

    def _turn_globules(self, objects, c, loc, rot=None) -> None:
        """Put each real-shaped globule's joint (its terminal CA) on its last bond's pivot, the
        surface nearest the joint facing back along the bond: the body then reaches past the
        pivot towards the linker by only the joint's depth. Children (spheres) follow.
        `rot`: the turns of several real-shaped domains, laid out with their places `loc`
        (bent_layout.real_chain_layout)."""
        p = self.p
        if rot is None:
            (terminal,) = domain_terminals(p)  # the joint and the surface's normal there
            joint, out = terminal["joint"], terminal["joint_out"]
            pivot = self.pivots[c, -1]
            rot = joint_rotations(out, loc - pivot)
            loc = pivot - rot @ joint
        objects.foreach_set("location", loc.astype(np.float32).ravel())
        objects.foreach_set("rotation_euler", euler_xyz(rot).astype(np.float32).ravel())
        mat = np.zeros((len(c), 4, 4))
        mat[:, :3, :3], mat[:, :3, 3], mat[:, 3, 3] = rot, loc, 1.0
        objects.foreach_set("matrix_world", mat.transpose(0, 2, 1).astype(np.float32).ravel())
        children = self.placed.get("globule_sphere", [])
        if children:  # their location is their place in the globule's frame, set when made
            world = {ob.session_uid: m for ob, m in zip(objects, mat)}
            local = np.tile(np.eye(4), (len(children), 1, 1))
            local[:, :3, 3] = [tuple(child.location) for child, _ in children]
            child_world = np.array([world[parent.session_uid] for _, parent in children]) @ local
            coll = _in_order(self.spheres_coll, [child for child, _ in children])
            coll.foreach_set("matrix_world",
                             child_world.transpose(0, 2, 1).astype(np.float32).ravel())


def tail_layout(p, n: int) -> tuple[np.ndarray, np.ndarray]:
    """A bare tail of n beads at every subunit: rest places (chains, n, 3) and its bonds'
    pivots (chains, n - 1, 3), straight out from the anchor along the chain's own line (a
    one-sphere chain as long as the tail, whose first n members are the beads)."""
    q = tail_chain(p)
    return rest_positions(q)[:, :n], bond_pivots(q)[:, :n - 1]


def tails_collections(root) -> dict:
    """The bare tails' collections under the model's root, made on first use (a model without
    tails has none): {"tail": beads, "tail_bond": their bonds}."""
    return {"tail": new_collection("FibrilFit bare tails", "tails", root),
            "tail_bond": new_collection("FibrilFit bare tail bonds", "tail_bonds", root)}


# How each shape of model.domains.SHAPES is drawn: its mesh from its name and rows.
GLOBULE_MESHES = {
    "sphere": lambda p, name, rows: meshes.uv_sphere("FibrilFit globule", p.globule_radius,
                                                      GLOBULE_SEGMENTS, GLOBULE_RINGS),
    "hull": lambda p, name, rows: meshes.convex_hull(name, shape.hull_points(rows)),
    "spheres": lambda p, name, rows: meshes.sphere_union(name, [tuple(r) for r in rows],
                                                         GLOBULE_SEGMENTS, GLOBULE_RINGS),
}


def globule_mesh(p: P.Params, domain: int = 0):
    """The globule's mesh: the sphere (32 × 16), the domain's grown hull, or its covering
    spheres joined, in the domain's body frame (structure.domain.body_frame). `domain`: which
    domain of the chain, 0 nearest the core (several real shapes: each its own mesh)."""
    name = f"FibrilFit globule {domain}" if domain else "FibrilFit globule"
    return GLOBULE_MESHES[p.shape.name](p, name, p.domains[domain].rows)


def spheres_body(p: P.Params):
    """body(pivots, d) for model.start_layout.spread_layout: the `spheres` globule's spheres in the
    world, turned as _turn_globules turns it when its last bond's pivot is at `pivots` and the
    bond points along `d` (k of each)."""
    (terminal,) = domain_terminals(p)  # the joint and the spheres' nearest way out there
    joint, out = terminal["joint"], terminal["joint_out"]
    spheres = p.domains[0].rows

    def body(pivots, d):  # (k, 3) each -> (k, spheres, 4)
        rot = joint_rotations(out, np.asarray(d, float).reshape(-1, 3))
        centre = np.asarray(pivots, float).reshape(-1, 3) - rot @ joint
        world = np.einsum("kij,sj->ksi", rot, spheres[:, :3]) + centre[:, None]
        return np.concatenate([world, np.broadcast_to(spheres[None, :, 3:], world[..., :1].shape)],
                              axis=-1)
    return body


def _in_order(coll, objects):
    """`coll.objects`, checked (one foreach_get) to hold exactly `objects`, in that order."""
    uids = np.empty(len(coll.objects), dtype=np.int64)
    coll.objects.foreach_get("session_uid", uids)
    if not np.array_equal(uids, [ob.session_uid for ob in objects]):
        raise RuntimeError(f"collection '{coll.name}' changed while the model was being built")
    return coll.objects


def _place(objects, loc: np.ndarray, rot_z: np.ndarray, world_loc=None,
           world_rot_z=None, scale=None) -> None:
    """Set location and Z rotation of a collection's objects, and a world matrix to match
    (`world_loc`, `world_rot_z` for children: their parent's).

    The world matrix makes the objects' matrix_world right before any depsgraph evaluation.
    foreach_set writes Blender's float[4][4] as stored: column-major, translation in row 3.
    """
    n = len(loc)
    rot = np.zeros((n, 3))
    rot[:, 2] = rot_z
    objects.foreach_set("location", loc.astype(np.float32).ravel())
    objects.foreach_set("rotation_euler", rot.astype(np.float32).ravel())
    loc = loc if world_loc is None else world_loc
    rot_z = rot_z if world_rot_z is None else world_rot_z
    mat = np.zeros((n, 4, 4))
    c, s = np.cos(rot_z), np.sin(rot_z)
    mat[:, 0, 0], mat[:, 0, 1], mat[:, 1, 0], mat[:, 1, 1] = c, s, -s, c
    mat[:, 2, 2] = mat[:, 3, 3] = 1.0
    if scale is not None:  # uniform scales (several domain sizes on one mesh)
        objects.foreach_set("scale", np.repeat(scale, 3).astype(np.float32))
        mat[:, :3, :3] *= np.asarray(scale, float)[:, None, None]
    mat[:, 3, :3] = loc
    objects.foreach_set("matrix_world", mat.astype(np.float32).ravel())


def _body(name, mesh, role, k, parts, bodies, rb_type, shape):
    ob = tag(bpy.data.objects.new(name, mesh), role)
    ob[LAYER] = k
    parts[role].objects.link(ob)
    bodies.objects.link(ob)
    rb = ob.rigid_body
    rb.type = rb_type
    rb.collision_shape = shape
    return ob
