"""The screw-periodic cell's images: bodies that stand in for the rest of an infinite fibril.
Over 400 lines because it is one room: which images a cell needs (chains, cores, bare tails)
and the follower that keeps them at S^m of their originals, which must agree on the same list.

Only images that can reach the cell are built (from the linker's length, not a fixed ±1 cell):
static passive copies of the cores and anchors, and kinematic ("Animated") copies of the linker
beads and globules, which ImageFollower moves after every frame to S^m of their originals, all
in one foreach_set. A mixed fibril's bare tails get theirs the same way (their anchors static,
their beads kinematic, tagged TAIL). Every image is tagged under the model's "images" collection.
"""
from __future__ import annotations

import bpy
import numpy as np
from mathutils import Matrix

from ..geom.rigid import euler_xyz
from ..model import helix
from ..model.chain import tail_reach
from ..model.hetero import widest_body_radii, widest_chain_reach
from .readback import MatrixReader
from .scene import INDEX, LAYER, TAG, new_collection, tag

MOVING, STATIC = "image", "image_static"  # roles of the two kinds of image
CHAIN = "fibrilfit_chain"  # on an image: the chain (or core, for a static core image) it copies
CELL = "fibrilfit_cell"    # on an image: m, the power of the screw
TAIL = "fibrilfit_tail"    # on an image of a bare tail's member (anchor or bead): 1; its CHAIN
# is then the tail's index in model.tails
COLLECTIONS = {MOVING: "FibrilFit images", STATIC: "FibrilFit static images"}
FADE_TO, FADE = (0.3, 0.32, 0.36), 0.6  # images: their original's colour, 60 % of the way to the
# render's backdrop (exports/dressing.BACKGROUND), so the cell stands out
_RB_COPIED = ("friction", "restitution", "use_margin", "collision_margin")


def plan(p, chain_layers, core_layers, tail_layers=()) -> dict:
    """Which images to build: {"moving": [(m, chain, member)], "static": [(m, kind, index)],
    "tails": [(m, tail, member)]}.

    A body of an image layer a height gap g beyond the cell is built when its own reach
    (model.chain.chain_reach, tail_reach for a bare tail's, or half the core's height) plus the
    farthest reach of any cell body covers g; a static "anchor" image copies member 0 of a
    chain, "tail" member 0 of a bare tail (`tail_layers`: each tail's layer), "core" a core
    object. "tails": the kinematic images of the bare tails' beads.
    """
    tails = tail_reach(p) if len(tail_layers) else np.zeros(0)
    # protofilaments rise from one to the next: the layer's chains spread over that much more
    # (a hetero-amyloid: the wider reach of an A or a B chain, member by member)
    chains = widest_chain_reach(p)
    reach_cell = (max(float(chains.max()), p.slab[2] / 2.0, float(tails.max(initial=0.0)))
                  + p.pf_rise_step * (p.protofilaments - 1))  # chain.body_reach's, and the tails'
    moving, static, tail_moving = [], [], []
    for layers, member_reach, kind, beads in ((chain_layers, chains, "anchor", moving),
                                              (tail_layers, tails, "tail", tail_moving)):
        if not len(layers):
            continue
        for m, k in helix.image_layers(p, reach_cell + float(member_reach.max())):
            g = helix.image_gap(p, m, k)
            for c in np.flatnonzero(np.asarray(layers) == k).tolist():
                for i in np.flatnonzero(member_reach + reach_cell >= g).tolist():
                    (static if i == 0 else beads).append((m, kind, c) if i == 0 else (m, c, i))
    for m, k in helix.image_layers(p, reach_cell + p.slab[2] / 2.0):
        for j in np.flatnonzero(np.asarray(core_layers) == k).tolist():
            static.append((m, "core", j))
    return {"moving": moving, "static": static, "tails": tail_moving}


def build_images(model, scene) -> dict:
    """Build the images of a built cell (model.params.periodic > 0). Returns counts by kind."""
    p = model.params
    chain_layers = [members[0][LAYER] for members in model.chain]
    core_layers = [ob[LAYER] for ob in model.slabs]
    tail_layers = [members[0][LAYER] for members in model.tails]
    todo = plan(p, chain_layers, core_layers, tail_layers)
    colls = {role: new_collection(title, role + "s", model.root)
             for role, title in COLLECTIONS.items()}
    bodies = scene.rigidbody_world.collection
    made = {MOVING: [], STATIC: []}
    spheres = {}  # a `spheres` globule's child spheres, by the globule (one pass, not .children)
    for coll in (c for c in model.root.children_recursive if c.get(TAG) == "globule_spheres"):
        for child in coll.objects:
            spheres.setdefault(child.parent.session_uid, []).append(child)
    for m, what, j in todo["static"]:
        source = (model.slabs[j] if what == "core" else
                  (model.chain if what == "anchor" else model.tails)[j][0])
        ob = _copy(source, STATIC, m, j, 0, colls[STATIC], bodies)
        if what == "tail":
            ob[TAIL] = 1
        ob.matrix_world = _to_blender(helix.apply_matrices(p, m, _matrix(source)[None])[0])
        made[STATIC].append(ob)
        _copy_pieces(source, ob, colls[STATIC], bodies)
    for m, c, i in todo["moving"]:
        ob = _copy(model.chain[c][i], MOVING, m, c, i, colls[MOVING], bodies)
        ob.rigid_body.kinematic = True
        made[MOVING].append(ob)
        if ob.rigid_body.collision_shape == "COMPOUND":  # a `spheres` globule's, kept apart
            # from the images ImageFollower moves (it sets every object of their collection)
            if "spheres" not in colls:
                colls["spheres"] = new_collection("FibrilFit image spheres", "image_spheres",
                                                  colls[MOVING])
            _copy_pieces(model.chain[c][i], ob, colls["spheres"], bodies, "globule_sphere",
                         spheres.get(model.chain[c][i].session_uid, ()))
    for m, t, i in todo["tails"]:  # a bare tail's beads: kinematic, after the chains' images
        ob = _copy(model.tails[t][i], MOVING, m, t, i, colls[MOVING], bodies)
        ob[TAIL] = 1
        ob.rigid_body.kinematic = True
        made[MOVING].append(ob)
    follower = ImageFollower(model)
    rest = np.array([[np.array(ob.matrix_world.translation) for ob in members]
                     for members in model.chain])
    follower.place(rest)
    return {"moving": len(made[MOVING]), "static": len(made[STATIC]),
            "cells": sorted({m for m, *_ in todo["moving"] + todo["static"] + todo["tails"]}),
            **({"tail_moving": len(todo["tails"])} if todo["tails"] else {})}


def _matrix(ob) -> np.ndarray:
    return np.array(ob.matrix_world, dtype=float)


def _to_blender(m: np.ndarray):
    return Matrix(m.tolist())


def _copy(source, role, m, chain, index, coll, bodies):
    """A new body sharing `source`'s mesh, shape and surface, tagged as image m of it."""
    ob = tag(bpy.data.objects.new(f"FF image {m:+d} {source.name}", source.data), role)
    ob[CELL], ob[CHAIN], ob[INDEX] = int(m), int(chain), int(index)
    ob[LAYER] = source[LAYER]
    coll.objects.link(ob)
    bodies.objects.link(ob)
    rb, src = ob.rigid_body, source.rigid_body
    rb.type = "PASSIVE"
    rb.collision_shape = src.collision_shape
    for attr in _RB_COPIED:
        setattr(rb, attr, getattr(src, attr))
    ob.color = (*(c + FADE * (b - c) for c, b in zip(source.color[:3], FADE_TO)), 1.0)
    return ob


def _copy_pieces(source, image, coll, bodies, role: str = "core_piece", children=None) -> None:
    """The children of a COMPOUND body for its image: an outline core's solid convex pieces
    (children of its slab, builders.layers), or a `spheres` globule's spheres (`role`
    "globule_sphere", each at its place in the globule's frame). A COMPOUND shape without them
    would collide with nothing. `children`: the source's, when known (else source.children,
    which scans every object of the file)."""
    for child in (source.children if children is None else children):
        if child.get(TAG) != role:
            continue
        ob = tag(bpy.data.objects.new(f"FF image {image[CELL]:+d} {child.name}", child.data),
                 role)
        ob[LAYER], ob[INDEX] = child[LAYER], child[INDEX]
        ob.parent = image
        ob.hide_render, ob.display_type = True, "WIRE"
        coll.objects.link(ob)
        bodies.objects.link(ob)
        ob.rigid_body.type = "PASSIVE"
        ob.rigid_body.collision_shape = child.rigid_body.collision_shape
        if role == "core_piece":
            ob.matrix_world = image.matrix_world
        else:
            ob.location = child.location


def image_collection(model, role: str = MOVING):
    for coll in model.root.children:
        if coll.get(TAG) == role + "s":
            return coll
    return None


class ImageFollower:
    """After each frame, moves every kinematic image to S^m of its original: one foreach_set.

    Spheres' images need only their centres: each gets its original's centre under S^m and the
    screw's turn (the check and the exports use exact matrices). A real shape's globule images
    (hull, spheres) also carry their originals' turn (TurnedImages).
    Only images that can touch a cell body now are moved for Bullet (their evaluated copies'
    matrices written, see _write): an image whose place, old and new, lies farther along Z from
    every cell body than its radius plus the largest cell body's plus twice this frame's largest
    move keeps its old place, which nothing can reach.

    A mixed fibril's bare tails (model.tails) are cell bodies too: their beads' images (TAIL)
    follow them, read with one foreach_get of their own each frame (the bake's positions are
    the chains').
    """

    def __init__(self, model):
        self.p = model.params
        self.coll = image_collection(model, MOVING)
        obs = self.objects = list(self.coll.objects) if self.coll is not None else []
        self.m = np.array([ob[CELL] for ob in obs], dtype=float)
        self.chain = np.array([ob[CHAIN] for ob in obs], dtype=np.intp)
        self.member = np.array([ob[INDEX] for ob in obs], dtype=np.intp)
        self.tail = np.array([bool(ob.get(TAIL, 0)) for ob in obs], dtype=bool)
        # the bare tails' members, (tails, members): read each frame when any has an image
        self.tails = (MatrixReader([ob for t in model.tails for ob in t], model.root.children)
                      if self.tail.any() else None)
        self.tail_shape = (len(model.tails), len(model.tails[0]) if model.tails else 0, 3)
        angle, _ = helix.screw_turn(self.p, self.m)
        self.rotation = np.zeros((len(obs), 3), dtype=np.float32)
        self.rotation[:, 2] = angle
        self.count = len(obs)
        # each image's original: an image carries its scale (inflate grows and shrinks globules)
        self.sources = [(model.tails if t else model.chain)[c][i] for c, i, t
                        in zip(self.chain.tolist(), self.member.tolist(), self.tail.tolist())]
        # several domains per chain: the further globules share domain 1's mesh at their own
        # scale (builders.layers), and their images must carry it under every protocol
        self.scale = np.array([ob.scale[0] for ob in self.sources], dtype=np.float32)
        radii = widest_body_radii(self.p)  # a real shape's globule: its reach
        own = np.where(self.tail, 0, self.member)  # a bare tail's bead: a residue's radius
        self.radius = (np.where(self.tail, self.p.residue_radius, radii[own]) if len(obs)
                       else np.zeros(0))
        self.reach = float(max(radii.max(), self.p.slab[2] / 2.0))  # the largest cell body's
        self.core_z = (-self.p.slab[2] / 2.0,  # the cell's cores, bottom to top
                       (self.p.layers - 1) * self.p.rise + self.p.slab[2] / 2.0
                       + self.p.pf_rise_step * (self.p.protofilaments - 1))
        self.current = None  # the places Blender holds, (n, 3)
        self.tagged: list[int] = []  # per frame: images moved for Bullet
        self.prev = None
        self.lag: list[float] = []  # per frame: the farthest an image lagged behind (Å)
        self.depsgraphs = None  # the scene's depsgraphs, known from the first frame's hook call
        self.turned = TurnedImages(model, self) if self.p.shape.real else None

    def originals(self, positions: np.ndarray) -> np.ndarray:
        """Each image's original's centre now (n, 3), from the chain positions (chains, members,
        3) and, for a bare tail's images, the tails as they stand."""
        if self.tails is None:
            return positions[self.chain, self.member]
        out = np.empty((self.count, 3))
        own = ~self.tail
        out[own] = positions[self.chain[own], self.member[own]]
        out[self.tail] = self.tail_positions()[self.chain[self.tail], self.member[self.tail]]
        return out

    def tail_positions(self) -> np.ndarray:
        """The bare tails' members now, (tails, members, 3)."""
        return self.tails.positions().reshape(self.tail_shape)

    def targets(self, positions: np.ndarray) -> np.ndarray:
        """Where the images belong for chain positions (chains, members, 3)."""
        return helix.apply_points(self.p, self.m, self.originals(positions))

    def near(self, positions: np.ndarray, loc: np.ndarray, margin: float) -> np.ndarray:
        """Images whose new or old place can touch a cell body along Z (see the class)."""
        z = positions[..., 2]
        radii = widest_body_radii(self.p)
        lo = min(float((z - radii).min()), self.core_z[0]) - self.reach - margin
        hi = max(float((z + radii).max()), self.core_z[1]) + self.reach + margin
        if self.tails is not None:  # the bare tails' beads are cell bodies too
            tz = self.tail_positions()[..., 2]
            lo = min(lo, float(tz.min()) - self.p.residue_radius - self.reach - margin)
            hi = max(hi, float(tz.max()) + self.p.residue_radius + self.reach + margin)
        out = np.zeros(self.count, dtype=bool)
        for where in (loc, self.current):
            out |= (where[:, 2] + self.radius >= lo) & (where[:, 2] - self.radius <= hi)
        return out

    def source_scales(self) -> np.ndarray:
        """Each image's original's (uniform) scale now (only inflate scales them)."""
        if self.p.protocol != "inflate":
            return self.scale
        return np.array([ob.scale[0] for ob in self.sources], dtype=np.float32)

    def _know(self, scene) -> None:
        if self.depsgraphs is None:  # every view layer's that exists: the active one steps Bullet
            self.depsgraphs = [vl.depsgraph for vl in scene.view_layers if vl.depsgraph]

    def before_frame(self, scene, frame) -> None:
        """Give the images their originals' scale when it changed since they were placed (the
        inflate hook, which runs first, grows or shrinks the originals before each frame)."""
        self._know(scene)
        if self.count and self.current is not None:
            scale = self.source_scales()
            changed = scale != self.scale
            if changed.any():  # the images near the cell are handed to the depsgraph again
                self.scale = scale
                self._write(changed & self.near_now)

    def place(self, positions: np.ndarray, margin: float | None = None) -> None:
        """Move the images to S^m of `positions`, with their originals' scale; with `margin`
        (Å), only those near the cell."""
        if not self.count:
            return
        loc = self.targets(positions)
        if margin is None or self.current is None:
            moving = np.ones(self.count, dtype=bool)
        else:
            moving = self.near(positions, loc, margin)
            loc = np.where(moving[:, None], loc, self.current)
        self.current = loc
        self.scale = self.source_scales()
        if self.turned is not None:
            self.turned.update(moving)
        self.tagged.append(int(moving.sum()))
        self.near_now = moving
        self._write(moving)

    def _write(self, moving: np.ndarray) -> None:
        """Set every image's place, turn and scale (one foreach_set each, on the data Blender
        saves) and hand those `moving` to Bullet by writing their evaluated copies' matrices."""
        loc, sc = self.current, self.scale
        objects = self.coll.objects
        objects.foreach_set("location", loc.astype(np.float32).ravel())
        objects.foreach_set("rotation_euler", self.rotation.ravel())
        objects.foreach_set("scale", np.repeat(sc, 3))
        c, s = np.cos(self.rotation[:, 2]), np.sin(self.rotation[:, 2])
        mat = np.zeros((self.count, 4, 4), dtype=np.float32)
        mat[:, 0, 0], mat[:, 0, 1], mat[:, 1, 0], mat[:, 1, 1] = c * sc, s * sc, -s * sc, c * sc
        mat[:, 2, 2], mat[:, 3, 3] = sc, 1.0
        mat[:, 3, :3] = loc
        if self.turned is not None:
            self.turned.apply(mat, sc)
        objects.foreach_set("matrix_world", mat.ravel())
        # foreach_set tags nothing, so Bullet, which reads the evaluated copies, would never see
        # the move. Tagging an image costs ~30 us of depsgraph work a frame; writing the copy's
        # matrix costs ~2 us and Bullet reads it (the copy is rebuilt from the data above when
        # anything tags it). bench/periodic.py --old measures the difference against a checkout
        # that tags.
        idx = np.flatnonzero(moving).tolist()
        if not self.depsgraphs:  # before the bake (once, at build): no evaluated copies yet
            for k in idx:
                self.objects[k].update_tag(refresh={"OBJECT"})
            return
        for dg in self.depsgraphs:
            for k in idx:
                self.objects[k].evaluated_get(dg).matrix_world = _to_blender(mat[k].T)
        if self.turned is not None and self.turned.kids:
            self.turned.write_children(moving, mat, self.depsgraphs)

    def after_frame(self, scene, frame, positions) -> None:
        """Move the images to where this frame left their originals. During the frame they
        stood where the previous frame had left them: that distance is the frame's lag.
        (Placing them where the last move would take them next instead was measured and is
        worse: the images overshoot at every contact, and the cell blew apart.)"""
        self._know(scene)
        now = self.originals(positions)
        self.lag.append(float(np.linalg.norm(now - self.prev, axis=-1).max())
                        if self.prev is not None and self.count else 0.0)
        self.prev = now.copy()
        self.place(positions, margin=2.0 * self.lag[-1] + 1.0)

    def summary(self) -> dict:
        """The bake result's "image_lag": the images' lag behind S^m of their originals."""
        lag = np.asarray(self.lag or [0.0])
        return {"image_lag": {"max": round(float(lag.max()), 4),
                              "max_frame": int(lag.argmax()) + 1,
                              "last": round(float(lag[-1]), 4)},
                "images_moved_per_frame": round(float(np.mean(self.tagged or [0])), 1)}


class TurnedImages:
    """The globule images of a real shape (hull, spheres): each carries S^m of its original's
    whole turn, not only the screw's, or Bullet would hold the image's hull turned otherwise
    than the check's (docs/model/domain-shapes.md#periodic)."""

    def __init__(self, model, follower):
        domains = [d.member for d in model.params.domains]  # a tail's bead is none of them
        self.rows = np.flatnonzero(np.isin(follower.member, domains) & ~follower.tail)
        sources = [follower.sources[k] for k in self.rows.tolist()]
        globules = [c for c in model.root.children if c.get(TAG) == "globules"]
        self.reader = MatrixReader(sources, globules)
        angle = follower.rotation[self.rows, 2].astype(float)
        c, s = np.cos(angle), np.sin(angle)
        self.screw = np.zeros((len(self.rows), 3, 3))
        self.screw[:, 0, 0], self.screw[:, 0, 1], self.screw[:, 1, 0] = c, -s, s
        self.screw[:, 1, 1], self.screw[:, 2, 2] = c, 1.0
        self.follower = follower
        self.turn = self.screw.copy()  # until the first update: the screw's turn alone
        # a `spheres` image's child spheres: (image's index, child, its place in the frame)
        row = {follower.objects[k].session_uid: k for k in self.rows.tolist()}
        self.kids = [(row[ob.parent.session_uid], ob, np.append(ob.location[:], 1.0))
                     for coll in (follower.coll.children if follower.coll is not None else ())
                     for ob in coll.objects
                     if ob.parent is not None and ob.parent.session_uid in row]

    def update(self, moving: np.ndarray) -> None:
        """Read the originals' turns now; the images that move take S^m of them."""
        if not len(self.rows):
            return
        m = self.reader.matrices()[:, :3, :3]
        own = m / np.linalg.norm(m, axis=1, keepdims=True)  # unit columns: the turn alone
        now = moving[self.rows]
        self.turn[now] = self.screw[now] @ own[now]
        self.follower.rotation[self.rows[now]] = euler_xyz(self.turn[now]).astype(np.float32)

    def write_children(self, moving: np.ndarray, mat: np.ndarray, graphs) -> None:
        """Keep the evaluated copies of the moved images' child spheres at their place in the
        image (`mat` as Blender stores it): Blender rebuilds a compound from them when it is
        tagged or the world is rebuilt, and the depsgraph never moves them (their parents are
        moved by their evaluated matrices alone). Stale, a rebuild put the spheres where the
        image was built (docs/model/domain-shapes.md#periodic)."""
        for k, child, local in self.kids:
            if moving[k]:
                world = mat[k].T.astype(float)
                w = world.copy()
                w[:, 3] = world @ local
                m = _to_blender(w)
                for dg in graphs:
                    child.evaluated_get(dg).matrix_world = m

    def apply(self, mat: np.ndarray, scale: np.ndarray) -> None:
        """Put the turns, scaled, into `mat` (n, 4, 4) as Blender stores it (transposed)."""
        if len(self.rows):
            mat[self.rows, :3, :3] = (self.turn * scale[self.rows, None, None]
                                      ).transpose(0, 2, 1)
