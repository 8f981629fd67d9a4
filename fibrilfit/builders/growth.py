"""The inflate protocol's schedule: grow the globules, hold at full size, judge; shrink a jammed
layout and grow it again under a new gravity.

One cycle: the globules' scale goes linearly from its start to 1 over `grow_frames` while the
random gravity is annealed linearly to zero; then up to `hold_frames` at full size with the
gravity off, until every body moves less than `settle_speed` per frame for `settle_frames`
frames. The layout is then judged (by the model's check when the bake was given it, else by
sphere depths and bond stretch). Accommodated, or no cycles left: the bake ends on that frame.
Otherwise every globule is shrunk to `regrow_scale` and the next cycle grows it again under a
new random gravity drawn from the seed, so the chains can leave the jam.

Bullet re-reads each active body's scale every step (the collision sphere follows it), while a
POINT constraint keeps the pivots it was built with in each body's frame, unscaled: the joint
of the last bead stays on the globule's full-size surface, so a small globule never lends its
linker extra reach (measured: docs/model/search.md#inflate-schedule).
"""
from __future__ import annotations

from typing import Callable

import numpy as np

from ..geom.rigid import euler_xyz
from ..model import helix, hetero, occupancy
from ..model.judgement import clear_miss, near_fit
from .readback import collection_matrices
from .scene import INDEX, LAYER, PROTOFILAMENT, TAG

GRAVITY_SALT = 0x6A5  # the gravity of cycle c >= 1: uniform in [-g, g]^3 from (seed, c, salt)
OVERLAP_TOLERANCE = 0.05  # Å: sphere overlap the fallback judge lets pass (resting contacts)


def cycle_gravity(p, cycle: int, first) -> np.ndarray:
    """The gravity grown under in `cycle`: the seed's own (`first`) for cycle 0."""
    if cycle == 0:
        return np.asarray(first, dtype=float)
    rng = np.random.default_rng([p.seed, cycle, GRAVITY_SALT])
    return rng.uniform(-p.gravity, p.gravity, 3)


def start_scale(p, centres: np.ndarray) -> float:
    """`grow_start`, or less if the start layout's globules would overlap at that scale (in a
    periodic cell, also with the images of the cell's globules). `centres`: every globule, in
    the order of Model.globules (several domains: each grows to its own size, so a pair meets at
    the scale d / (r_i + r_j))."""
    if len(p.domains) > 1:
        return _start_scale_domains(p, centres)
    d = _closest(centres_with_images(p, centres)[0])
    if d is None:
        return p.grow_start
    # a hetero-amyloid: the wider of A and B meets first (p.widest_diameter; one domain: its own)
    return float(min(p.grow_start, max(0.01, 0.95 * d / p.widest_diameter)))


def _start_scale_domains(p, centres: np.ndarray) -> float:
    """start_scale for several domains per chain: the smallest d / (r_i + r_j) over pairs."""
    points, _ = centres_with_images(p, centres)
    # each body's reach, not its Rg sphere's (a sphere's reach is its radius: Domain.reach)
    reach = [d.reach for d in p.domains]
    radii = np.tile(reach, -(-len(points) // len(reach)))[:len(points)]
    order = np.argsort(points[:, 2])
    c, r = points[order], radii[order]
    best, widest = np.inf, 2.0 * float(radii.max(initial=0.0))
    for shift in range(1, len(c)):
        dz = c[shift:, 2] - c[:-shift, 2]
        if dz.min() >= best * widest:
            break
        d = np.linalg.norm(c[shift:] - c[:-shift], axis=1) / (r[shift:] + r[:-shift])
        best = min(best, float(d.min()))
    if not np.isfinite(best):
        return p.grow_start
    return float(min(p.grow_start, max(0.01, 0.95 * best)))


def globule_radii(p, n: int) -> np.ndarray:
    """Full-size radii of n globules in the order of Model.globules, chain after chain (and
    image block after block): globule g is domain g % D (a hetero-amyloid: its chain's, A's
    or B's)."""
    if occupancy.is_hetero(p):
        radii = hetero.globule_radii_by_chain(p)
        return np.tile(radii, -(-n // len(radii)))[:n]
    radii = np.asarray([d.radius for d in p.domains], dtype=float)
    return np.tile(radii, -(-n // len(radii)))[:n]


def globule_scales(p, objects) -> np.ndarray | None:
    """Several domains per chain: each globule object's full size as a scale of domain 1's mesh,
    which they share (builders.layers); None for one domain (every full size is 1). A
    hetero-amyloid's B globules share A's sphere at B's scale (each object's layer and
    protofilament say which)."""
    if occupancy.is_hetero(p):
        b = occupancy.second_domain(p)
        return np.array([hetero.b_scale(p) if b[int(ob[LAYER]), int(ob.get(PROTOFILAMENT, 0))]
                         else 1.0 for ob in objects], dtype=float)
    if len(p.domains) == 1 or p.shape.real:  # real shapes: each its own mesh at full size
        return None
    size = {d.member: d.radius / p.globule_radius for d in p.domains}
    return np.array([size[int(ob[INDEX])] for ob in objects], dtype=float)


def centres_with_images(p, centres: np.ndarray) -> tuple[np.ndarray, int]:
    """The globule centres and, in a periodic cell, their images above it as far as a globule
    can reach (pairs with the images below are the same pairs shifted). Returns (centres, n):
    the first n are the cell's; image-image pairs repeat cell pairs and must not be counted."""
    centres = np.asarray(centres, dtype=float)
    if not p.periodic or not len(centres):
        return centres, len(centres)
    # several domains: each body's reach, as _start_scale_domains counts them; one domain: its
    # sphere's radius, as start_scale and sphere_judge count it (a real shape: its Rg sphere's)
    reach = max(d.reach for d in p.domains) if len(p.domains) > 1 else p.domains[0].radius
    if occupancy.is_hetero(p):  # B's sphere may be the wider
        reach = p.widest_diameter / 2.0
    cells = helix.check_cells(p, centres[:, 2], reach)
    m = np.repeat(np.arange(1, cells + 1, dtype=float), len(centres))
    images = helix.apply_points(p, m, np.tile(centres, (cells, 1)))
    return np.concatenate([centres, images]), len(centres)


def _closest(centres: np.ndarray) -> float | None:
    """The smallest distance between two of the points, found along Z-sorted neighbours."""
    c = np.asarray(centres, dtype=float)
    if len(c) < 2:
        return None
    c = c[np.argsort(c[:, 2])]
    best = np.inf
    for shift in range(1, len(c)):
        dz = c[shift:, 2] - c[:-shift, 2]
        if dz.min() >= best:
            break
        best = min(best, float(np.linalg.norm(c[shift:] - c[:-shift], axis=1).min()))
    return best


def settle_tags(scene) -> None:
    """Evaluate what has been tagged in `scene` (every view layer's depsgraph), at the current
    frame: a bake hook that tags bodies calls this before the next frame is stepped, so the
    step reads settled data whatever order the depsgraph's threads run in."""
    for layer in scene.view_layers:
        if layer.depsgraph is not None:
            layer.update()


def sphere_judge(p, positions: np.ndarray, scored) -> dict:
    """The fallback judgement: no scored globule pair overlapping by more than
    OVERLAP_TOLERANCE and every scored bond within the stretch tolerance. `scored`: bool per
    chain of the model (analysis.scored_chains), or a slice of them."""
    rest = hetero.rest_lengths_by_chain(p)[scored]  # each chain's own (a B chain's last bond)
    stretch = np.linalg.norm(np.diff(positions[scored], axis=1), axis=-1) / rest - 1.0
    worst = float(stretch.max()) if stretch.size else 0.0
    members = [d.member for d in p.domains]
    centres = positions[:, members].reshape(-1, 3)  # one domain: positions[:, -1]
    domains = len(members)
    keep = np.zeros(len(positions), dtype=bool)
    keep[scored] = True
    keep = np.repeat(keep, domains)
    centres, _ = centres_with_images(p, centres)
    keep = np.concatenate([keep, np.zeros(len(centres) - len(keep), dtype=bool)])
    radii = globule_radii(p, len(centres))
    deep, overlap = 0, 0.0
    order = np.argsort(centres[:, 2])
    c, k, r = centres[order], keep[order], radii[order]
    for shift in range(1, len(c)):
        dz = c[shift:, 2] - c[:-shift, 2]
        if dz.min() >= p.widest_diameter:
            break
        d = np.linalg.norm(c[shift:] - c[:-shift], axis=1)
        touch = (p.globule_diameter if domains == 1 and not occupancy.is_hetero(p)
                 else r[shift:] + r[:-shift])
        mine = k[shift:] | k[:-shift]
        hit = (touch - d > OVERLAP_TOLERANCE) & mine
        deep += int(hit.sum())
        if mine.any():
            overlap = max(overlap, float((touch - d)[mine].max()))
    return {"accommodated": deep == 0 and worst <= p.stretch_tolerance,
            "max_bond_stretch": round(worst, 6), "clashing_pairs": deep,
            "max_overlap": round(overlap, 6)}


def compound_children(globules) -> list[list[tuple]]:
    """Per globule of a `spheres` model (in the collection's order): its child spheres, each
    (object, its place in the globule's frame)."""
    index = {ob.session_uid: k for k, ob in enumerate(globules.objects)}
    out = [[] for _ in globules.objects]
    for coll in globules.children:
        for child in coll.objects:
            k = index.get(child.parent.session_uid) if child.parent is not None else None
            if k is not None:
                out[k].append((child, np.array(child.location, dtype=float)))
    return out


def sync_compound_places(objects) -> None:
    """Give each compound globule's own location and rotation its simulated place.

    Tagged, a COMPOUND body is rebuilt from its parent's own location and rotation and its
    children's world matrices; left at the start layout, the children land where the body
    started, not where it is (measured: docs/model/domain-shapes.md#compound-growth)."""
    m = collection_matrices(objects)
    rot = m[:, :3, :3] / np.linalg.norm(m[:, :3, :3], axis=1, keepdims=True)  # unit columns
    objects.foreach_set("location", m[:, :3, 3].astype(np.float32).ravel())
    objects.foreach_set("rotation_euler", euler_xyz(rot).astype(np.float32).ravel())


def place_compound_children(scene, objects, children, s: float) -> None:
    """Write each child sphere's world matrix at the new scale `s` into the evaluated copies
    Bullet rebuilds the compound from: the depsgraph would update them only after the rebuild,
    which then keeps the previous scale's offsets (measured:
    docs/model/domain-shapes.md#compound-growth)."""
    from mathutils import Matrix
    graphs = [vl.depsgraph for vl in scene.view_layers if vl.depsgraph is not None]
    m = collection_matrices(objects)
    m[:, :3, :3] *= s / np.linalg.norm(m[:, :3, :3], axis=1, keepdims=True)
    for parent, kids in zip(m, children):
        for child, local in kids:
            world = parent.copy()
            world[:3, 3] = parent[:3, :3] @ local + parent[:3, 3]
            w = Matrix(world.tolist())  # (not the child's own: that would move its location)
            for dg in graphs:
                child.evaluated_get(dg).matrix_world = w


class Inflate:
    """The schedule as a bake hook (builders/hooks.py). `judge(model)` -> the check's result
    dict (with "accommodated"); None uses sphere_judge."""

    busy = True  # the schedule, not the tutorial's settling, ends this bake

    def __init__(self, model, scene, judge: Callable | None = None):
        self.model, self.p, self.judge, self.scene = model, model.params, judge, scene
        self.globules = next(c for c in model.root.children if c.get(TAG) == "globules")
        self.full = globule_scales(self.p, self.globules.objects)  # None: one domain
        self.compounds = compound_children(self.globules) if self.p.shape.compound else None
        # the scored layers' chains (a mixed fibril: of its decorated subunits)
        layer, _ = occupancy.model_chain_layers(self.p)
        self.scored = (layer >= self.p.score_layers) & (layer < self.p.layers - self.p.score_layers)
        self.cycle, self.grow_from, self.grow_start = 0, None, 1
        self.holding, self.hold_start, self.quiet, self.prev = False, 0, 0, None
        self.finished, self.gravity, self.scale = False, None, None
        self.polishing = False
        self.extended = False  # granted near_cycles (last_cycle)
        self.clear = False  # ended early as a clear miss (clear_miss)
        self.start = self.first = None
        self.cycles: list[dict] = []
        # scene frames per frame of the model (physics.frame_split): a periodic cell's frames
        # are split, so the schedule's frames and speeds are counted in the shorter ones
        self.k = self.p.image_updates if self.p.periodic else 1

    def _set_scale(self, s: float) -> None:
        if s == self.scale:
            return
        objects = self.globules.objects
        if self.compounds is not None:  # before the scale: the parents' places now
            sync_compound_places(objects)
        if self.full is None:
            objects.foreach_set("scale", np.full(3 * len(objects), s, dtype=np.float32))
        else:  # several domains: each its own fraction s of its own full size
            objects.foreach_set("scale", np.repeat(s * self.full, 3).astype(np.float32))
        # foreach_set tags nothing: without this the depsgraph keeps the old scale (measured:
        # matrix_world and Bullet's shape stay at full size)
        for ob in objects:
            ob.update_tag(refresh={"OBJECT"})
        # ...and the tags are evaluated now, in a pass of their own, not inside the frame's
        # step: evaluated together, the scale Bullet read differed by a float32 ulp with the
        # order the depsgraph's threads ran in, and the bake diverged from the first contact
        # (measured: docs/model/search.md#determinism)
        settle_tags(self.scene)
        if self.compounds is not None:  # what the next step rebuilds each compound from
            place_compound_children(self.scene, objects, self.compounds, s)
        self.scale = s

    def before_frame(self, scene, frame: int) -> None:
        p = self.p
        if frame == 1:
            centres = np.array([ob.matrix_world.translation[:] for ob in self.model.globules])
            self.grow_from = self.start = start_scale(p, centres)
            self.first = tuple(scene.gravity)
            self.gravity = cycle_gravity(p, 0, self.first)
        if self.holding:
            return
        t = min(1.0, (frame - self.grow_start) / (p.grow_frames * self.k))
        self._set_scale(self.grow_from + (1.0 - self.grow_from) * t)
        scene.gravity = tuple(self.gravity * (1.0 - t))

    def after_frame(self, scene, frame: int, positions: np.ndarray) -> None:
        p = self.p
        if not self.holding:
            if frame - self.grow_start >= p.grow_frames * self.k:
                self.holding, self.hold_start, self.quiet, self.prev = True, frame + 1, 0, positions.copy()
            return
        speed = float(np.linalg.norm(positions - self.prev, axis=-1).max())
        self.prev = positions.copy()
        self.quiet = self.quiet + 1 if speed < p.settle_speed / self.k else 0
        held = frame - self.hold_start + 1
        if (self.quiet < min(p.settle_frames, p.hold_frames) * self.k
                and held < p.hold_frames * self.k):
            return
        verdict = (self.judge(self.model) if self.judge is not None
                   else sphere_judge(p, positions, self.scored))
        pairs = verdict["clashing_pairs"]
        self.cycles.append({
            "cycle": self.cycle, "judged_at": frame, "grown_from": round(self.grow_from, 4),
            "gravity": [round(float(g), 6) for g in self.gravity],
            "accommodated": bool(verdict["accommodated"]),
            "clashing_pairs": pairs if isinstance(pairs, int) else len(pairs),
            "max_bond_stretch": verdict["max_bond_stretch"],
            "max_overlap": verdict.get("max_overlap"), "polished": self.polishing})
        if self.polishing:
            self._polish(scene, False)
        elif p.polish_factor > 1 and near_fit(p, verdict):
            # nearly there: hold again with finer substeps and more solver iterations, which
            # relieve what the 10 x 10 steps leave of a jam (docs/model/search.md#polish)
            self._polish(scene, True)
            self.hold_start, self.quiet = frame + 1, 0
            return
        if verdict["accommodated"] or self.cycle >= self.last_cycle(verdict):
            self.finished, self.busy = True, False
            return
        if clear_miss(p, verdict):  # no run this far off went on to fit (measured)
            self.finished, self.busy, self.clear = True, False, True
            return
        self.cycle += 1  # jammed: shrink every globule and grow again under a new gravity
        self.grow_from, self.grow_start, self.holding = p.regrow_scale, frame + 1, False
        self.gravity = cycle_gravity(p, self.cycle, None)

    def last_cycle(self, verdict: dict) -> int:
        """The last cycle this run may have: regrow_cycles, or near_cycles more once a layout
        judged at (or after) the last regular cycle is a near miss (near_fit): in a cell the
        usual miss is clash-free with linkers stretched 6-10 %, and more regrows fit it where a
        finer solve did not (docs/model/search.md#near-cycles). A clear miss stops there."""
        p = self.p
        if self.extended or (self.cycle >= p.regrow_cycles and near_fit(p, verdict)):
            self.extended = True
            return p.regrow_cycles + p.near_cycles
        return p.regrow_cycles

    def _polish(self, scene, on: bool) -> None:
        """The world's substeps and solver iterations: polish_factor times the model's, or the
        model's again (physics.setup_world). Measured: changed between frames, they take effect
        from the next frame, the bake goes on from where it was and the kept cache reads back
        the same positions."""
        rbw, f = scene.rigidbody_world, (self.p.polish_factor if on else 1)
        rbw.substeps_per_frame = (self.p.substeps // self.k) * f
        rbw.solver_iterations = self.p.solver_iterations * f
        self.polishing = on

    def summary(self) -> dict:
        """The result's `inflate` block, and `gravity` kept as the seed's (the scene ends with
        none, annealed away)."""
        out = {"inflate": {"start_scale": None if self.start is None else round(self.start, 4),
                           "cycles": self.cycles, "near_cycles_granted": self.extended,
                           "clear_miss": self.clear}}
        if self.start is not None:
            out["gravity"] = [round(float(g), 9) for g in cycle_gravity(self.p, 0, self.first)]
        return out
