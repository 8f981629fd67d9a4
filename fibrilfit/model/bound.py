"""The proven lower bound on the linker: below `impossible_below` residues no layout of this model
is clash-free with intact linkers. Geometry alone, no simulation; plain numpy, no bpy.
Over 400 lines because it is one proof: what a globule holds, how far it reaches, the room the
anchors leave and the search for the shortest linker they allow, said together.

The argument (written out for a referee: docs/model/bound.md#derivation):

1. Intact linkers: every bond is within (1 + stretch_tolerance) of its rest length, so a domain's
   centre lies within (chain_x[domain] − chain_x[anchor])·(1 + tolerance) of its chain's anchor
   (the triangle inequality along the chain; a real shape's rigid joint-to-centre lever is
   counted stretched too, which only loosens the bound).
2. No clash: the verdict's mesh test finds no two globule meshes crossing, so their insides are
   disjoint. Each mesh holds known balls (`inner_balls`): the sphere's 32 × 16 mesh the ball of
   its inradius, a hull every atom's ball and a ball about its centre, covering spheres theirs.
   So the domains' inner bodies are disjoint, and each lies within ρ = reach + ball of its anchor.
3. Outside the core: a domain's inner body enters no layer's core prism deeper than CORE_ENTRY
   (Bullet keeps resting bodies within ~0.05 Å of each other; every result reports the depth it
   found, `core_entry`, so a layout this does not cover is named).
4. So the inner bodies of the judged domains (every layer of a periodic cell's infinite fibril,
   per layer; the scored layers of a finite one) are disjoint sets inside
   U = (∪ anchors' balls of radius ρ) minus the core eroded by CORE_ENTRY, and
   Σ vol(inner bodies) ≤ vol(U). A packing density of 1 (disjoint volumes), not a conjectured one.
   Every subset of protofilaments and of a chain's domains gives such an inequality; the linker
   is impossible where any one fails. vol(U) is bounded from above by counting every voxel that
   can meet U and is not certainly inside the eroded core; an inner body's volume from below
   (a ball's exactly; a union of balls by the voxels certainly inside it).

Lengths are monotone: a longer linker only enlarges U, so the smallest length at which every
inequality holds is the bound, and every shorter one is settled without a run.
"""
from __future__ import annotations

import dataclasses
import json
import math

import numpy as np

from ..geom import polygons, shape as geom_shape
from . import helix, hetero, occupancy
from .chain import chain_x
from .param_spec import GLOBULE_RINGS, GLOBULE_SEGMENTS

# How deep (Å) a domain's inner body may enter the core and still count as outside it: Bullet's
# resting contacts interpenetrate by ~0.05 Å (docs/model/domain-shapes.md#margin); ten times
# that. A layout with a deeper entry is outside the bound's assumptions, and its result says so
# (docs/model/bound.md#assumptions).
CORE_ENTRY = 0.5
# The directions over which a hull's central ball is measured, and a bound of their covering
# angle (chord): every unit vector lies within NET_COVER of one of them (measured: 0.0150 on
# 10^6 random directions for 20,000 Fibonacci points; docs/model/bound.md#hull-ball).
NET_DIRECTIONS, NET_COVER = 20000, 0.02
# The voxel grids: at most this many voxel-anchor distances per grid, so a bound costs about a
# second (docs/model/bound.md#cost); never finer than FINEST Å.
GRID_BUDGET, FINEST = 2.0e7, 0.3
LONGEST = 400  # residues: a linker needing more is reported as "above 400"


# ---- 2. what a globule's mesh holds ----------------------------------------------------------
def inner_balls(p, d) -> np.ndarray:
    """Balls [x, y, z, r] in domain d's body frame (its centre at the origin) that lie inside
    its globule mesh (docs/model/bound.md#inner-bodies)."""
    fraction = uv_fraction()
    if d.rows is None:
        return np.array([[0.0, 0.0, 0.0, d.radius * fraction]])
    rows = np.asarray(d.rows, dtype=float).reshape(-1, 4)
    if d.shape.compound:  # its covering spheres, each drawn as a 32 × 16 UV sphere
        return np.column_stack([rows[:, :3], rows[:, 3] * fraction])
    # a hull: every atom's ball (geom/shape.py: the hull's points lie beyond them), and the
    # largest ball about the centre that the atoms' hull holds
    return np.vstack([rows, [0.0, 0.0, 0.0, central_ball(rows)]])


def uv_fraction() -> float:
    """The inradius of the globule's UV sphere over its radius (0.99043 for 32 × 16)."""
    return geom_shape.uv_sphere_inradius(GLOBULE_SEGMENTS, GLOBULE_RINGS)


def central_ball(rows) -> float:
    """A radius r such that the ball of radius r about the origin lies inside the convex hull of
    the atoms' balls: the least support h(u) = max(a·u + r_a) over NET_DIRECTIONS, less its
    Lipschitz slack (max |a|) times NET_COVER between directions; 0 if that is negative."""
    rows = np.asarray(rows, dtype=float).reshape(-1, 4)
    u = geom_shape.directions(NET_DIRECTIONS)
    support = geom_shape.grown_support(rows[:, :3], rows[:, 3], u)
    slack = float(np.linalg.norm(rows[:, :3], axis=1).max()) * NET_COVER
    return max(0.0, float(support.min()) - slack)


def ball_union_volume(balls) -> float:
    """A lower bound of the volume of a union of balls [x, y, z, r] (Å³): exact for one ball; else
    the voxels whose every point lies inside some ball."""
    balls = np.asarray(balls, dtype=float).reshape(-1, 4)
    balls = balls[balls[:, 3] > 0]
    if len(balls) == 0:
        return 0.0
    if len(balls) == 1:
        return 4.0 / 3.0 * math.pi * balls[0, 3] ** 3
    lo = (balls[:, :3] - balls[:, 3:]).min(axis=0)
    hi = (balls[:, :3] + balls[:, 3:]).max(axis=0)
    h = max(0.2, float(np.prod(hi - lo)) ** (1 / 3) / 60.0)
    half = h * math.sqrt(3.0) / 2.0
    axes = [np.arange(a + h / 2, b, h) for a, b in zip(lo, hi)]
    count = 0
    gx, gy = np.meshgrid(axes[0], axes[1], indexing="ij")
    xy = np.column_stack([gx.ravel(), gy.ravel()])
    for z in axes[2]:
        d2 = ((xy[:, None, :] - balls[None, :, :2]) ** 2).sum(-1) + (z - balls[None, :, 2]) ** 2
        inside = (np.sqrt(d2) <= balls[None, :, 3] - half).any(axis=1)
        count += int(inside.sum())
    return count * h ** 3


# ---- 1. how far a domain's inner body reaches from its anchor ----------------------------
def reach_terms(p) -> list[tuple[float, float]]:
    """Per domain (from the core outward) (c, e): at linker L its centre lies within
    ((L − 1)·spacing + c)·(1 + tolerance) of the anchor, and its inner body within e of its centre."""
    x = np.asarray(chain_x(p), dtype=float)
    out = []
    for d in p.domains:
        c = float(x[d.member] - x[0]) - (p.linker - 1) * p.residue_spacing
        balls = inner_balls(p, d)
        e = float((np.linalg.norm(balls[:, :3], axis=1) + balls[:, 3]).max())
        out.append((c, e))
    return out


def reach(p, terms, linker: int) -> list[float]:
    """ρ of each domain at this linker: how far its inner body can be from its anchor."""
    return [((linker - 1) * p.residue_spacing + c) * (1.0 + p.stretch_tolerance) + e
            for c, e in terms]


def pf_reach(p, terms, linker: int) -> np.ndarray:
    """ρ of each domain (K, D) per protofilament, from its own anchor with its own free linker:
    `reach` with the residues protofilament j's own exit spends less than the model's chains
    (exit_spent) given back (interface termini, docs/model/bound.md#interface-termini; without
    them every row is `reach`'s, the same floats)."""
    back = p.exit_spent - p.pf_exit_residues()
    return np.array([reach(p, terms, linker + int(b)) for b in back])


# ---- 3, 4. the room the anchors leave -------------------------------------------------------
def core_thickness(p) -> float:
    """The height of a layer's core prism (Å): an outline's is the rise, the box's slab[2]."""
    return p.rise if p.core_outline is not None else float(p.slab[2])


def _grid_step(span_xy: float, span_z: float, anchors: int, rise: float, budget: float) -> float:
    """A voxel edge that divides the rise, within `budget` voxel-anchor distances."""
    h = (span_xy ** 2 * span_z * max(anchors, 1) / budget) ** (1 / 3)
    h = max(h, FINEST)
    return rise / max(1, math.ceil(rise / h - 1e-9))


class Room:
    """The voxels around a set of anchors, each with its distance to the nearest anchor of every
    protofilament and whether it is certainly inside the eroded core."""

    def __init__(self, p, rho_max: float, periodic: bool, lo: int, hi: int,
                 budget: float = 2.0e7):
        self.p = p
        own = p.pf_anchor_xy()  # each protofilament's anchor in its frame (K, 2)
        anchor_r = float(np.hypot(own[:, 0], own[:, 1]).max())
        half_xy = anchor_r + rho_max + 1.0  # every voxel that any anchor's ball can reach
        reach_layers = int(math.ceil((rho_max + p.pf_rise_step * p.protofilaments) / p.rise)) + 2
        if periodic:  # one layer's height of the infinite fibril, every anchor that can reach it
            z0, z1 = -p.rise / 2.0, p.rise / 2.0
            layers = np.arange(-reach_layers, reach_layers + 1)
        else:
            layers = np.arange(lo, hi)
            z0 = lo * p.rise - p.rise / 2.0 - rho_max - p.pf_rise_step * p.protofilaments
            z1 = (hi - 1) * p.rise + p.rise / 2.0 + rho_max + p.pf_rise_step * p.protofilaments
            # whole layers' heights, so every voxel lies in one layer's slice
            z0 = (math.floor(z0 / p.rise - 0.5) + 0.5) * p.rise
            z1 = (math.ceil(z1 / p.rise - 0.5) + 0.5) * p.rise
        n_anchor = len(layers) * p.protofilaments
        near = min(n_anchor, (2 * reach_layers + 1) * p.protofilaments)
        h = _grid_step(2 * half_xy, z1 - z0, near, p.rise, budget)
        self.h, self.half = h, h * math.sqrt(3.0) / 2.0
        self.periodic, self.lo, self.hi = periodic, lo, hi
        axis = np.arange(-half_xy + h / 2, half_xy, h)
        gx, gy = np.meshgrid(axis, axis, indexing="ij")
        xy = np.column_stack([gx.ravel(), gy.ravel()])
        xy32 = xy.astype(np.float32)
        xy2 = (xy32 * xy32).sum(1)
        zs = np.arange(z0 + h / 2, z1 - h / 4, h)
        # anchors: (layer, protofilament) -> world position
        k = np.repeat(layers, p.protofilaments).astype(float)
        j = np.tile(np.arange(p.protofilaments), len(layers))
        ax, ay = own[j, 0], own[j, 1]
        turns, rises = p.pf_offsets()
        angle = k * p.twist + turns[j]
        height = k * p.rise + rises[j]
        anchors = np.column_stack([np.cos(angle) * ax - np.sin(angle) * ay,
                                   np.sin(angle) * ax + np.cos(angle) * ay, height])
        self.anchors, self.pf = anchors, j.astype(int)
        K = p.protofilaments
        dist = np.full((K, len(zs), len(xy)), np.inf, dtype=np.float32)
        core = np.zeros((len(zs), len(xy)), dtype=bool)
        for iz, z in enumerate(zs):
            close = np.abs(anchors[:, 2] - z) <= rho_max + self.half
            for pf in range(K):
                sel = anchors[close & (self.pf == pf)]
                if len(sel):  # |q − a|² by one matrix product (float32: 1e-3 Å at 100 Å)
                    a = sel[:, :2].astype(np.float32)
                    d2 = (xy2[:, None] - 2.0 * (xy32 @ a.T) + (a * a).sum(1)[None]
                          + ((z - sel[:, 2]) ** 2).astype(np.float32)[None])
                    dist[pf, iz] = np.sqrt(np.maximum(d2.min(axis=1), 0.0))
            core[iz] = self._in_core(xy, z, rho_max, dist[:, iz].min(axis=0))
        self.dist, self.core = dist, core

    def _in_core(self, xy, z, rho_max, d) -> np.ndarray:
        """Voxels (centre xy at height z) certainly inside the core eroded by CORE_ENTRY: inside
        the eroded outline of every layer whose slice lies within CORE_ENTRY of the voxel, in
        the stack, and within the prism's height (docs/model/bound.md#voxels)."""
        p, h = self.p, self.h
        out = np.zeros(len(xy), dtype=bool)
        todo = d <= rho_max + self.half  # only voxels U can hold matter
        if not todo.any():
            return out
        t = core_thickness(p)
        k_own = math.floor(z / p.rise + 0.5)
        margin_z = CORE_ENTRY + h / 2.0
        if abs(z - k_own * p.rise) + margin_z > t / 2.0 and t < p.rise:
            return out  # between two prisms' heights
        ks = range(math.floor((z - margin_z) / p.rise + 0.5),
                   math.floor((z + margin_z) / p.rise + 0.5) + 1)
        if not self.periodic and (min(ks) < 0 or max(ks) >= p.layers):
            return out  # within CORE_ENTRY of the stack's end
        ok = todo.copy()
        outline = p.outline()
        margin_xy = CORE_ENTRY + h / math.sqrt(2.0)
        for k in ks:
            back = helix.turn_xy(xy[ok, 0], xy[ok, 1], -k * p.twist)
            inside = polygons.inside_by(outline, back, margin_xy)
            idx = np.nonzero(ok)[0]
            ok[idx[~inside]] = False
        return ok

    def volume(self, pfs, rho) -> float:
        """An upper bound (Å³) of the room: voxels within ρ of an anchor of these protofilaments
        that are not certainly inside the eroded core. `rho`: one for all, or one per
        protofilament of `pfs` (each its own free linker: interface termini)."""
        pfs = list(pfs)
        if np.ndim(rho) == 0:
            d = self.dist[pfs].min(axis=0)
            return float(((d <= rho + self.half) & ~self.core).sum()) * self.h ** 3
        near = np.zeros(self.core.shape, dtype=bool)
        for pf, r in zip(pfs, rho):
            near |= self.dist[pf] <= r + self.half
        return float((near & ~self.core).sum()) * self.h ** 3


# ---- the bound ------------------------------------------------------------------------------
def _subsets(n: int):
    for mask in range(1, 2 ** n):
        yield [i for i in range(n) if mask >> i & 1]


def constraints(p, room: Room, terms, volumes, linker: int, chains_per_pf: int) -> list[dict]:
    """Every inequality at this linker: a subset of protofilaments and of the chain's domains,
    the inner volume its domains need and the room they have (Å³)."""
    rho = reach(p, terms, linker)
    own = None if p.pf_anchors is None else pf_reach(p, terms, linker)
    out = []
    for pfs in _subsets(p.protofilaments):
        for ds in _subsets(len(terms)):
            need = len(pfs) * chains_per_pf * sum(volumes[k] for k in ds)
            have = room.volume(pfs, max(rho[k] for k in ds) if own is None else
                               [own[j, ds].max() for j in pfs])
            out.append({"protofilaments": pfs, "domains": ds, "need": need, "have": have})
    return out


def _settings_key(p) -> str:
    keep = ("slab", "residue_radius", "residue_spacing", "globule_diameter", "layers", "rise",
            "twist", "stretch_tolerance", "score_layers", "protofilaments", "pf_rotation",
            "pf_rise", "pf_turns", "core_outline", "anchor", "periodic", "domain_diameters",
            "pattern", "pattern_layers", "domain_b_diameter", "linker_b",
            "domain_linker", "domain_shape", "domain_atoms", "domain_spheres", "domain_joint",
            "further_atoms", "further_spheres", "further_joints", "domain_exits",
            "exit_residues", "pf_anchors")
    d = p.to_dict()
    return json.dumps({k: d.get(k) for k in keep}, sort_keys=True, default=str)


def linker_bound(p, budget: float = GRID_BUDGET) -> dict:
    """The bound for this model's geometry (its linker aside): `impossible_below` B, the shortest
    linker at which every inequality holds (no clash-free layout with intact linkers exists at
    any linker < B), with the inequality that fails one below it (docs/model/bound.md).
    `budget`: voxels per grid (a coarser grid gives a bound as sound, and weaker or equal)."""
    if occupancy.is_mixed(p):  # its inequalities count every subunit decorated: not a proof
        # for a mixed fibril (docs/model/occupancy.md#bound); a mixed hetero-amyloid's: the
        # exit's alone too (docs/model/bound.md#hetero)
        return occupancy.exit_bound(p, hetero=occupancy.is_hetero(p))
    return dict(_linker_bound(_settings_key(p) + f"|{budget:g}", p, budget))


# geometry -> (bound, Setting): a sweep's runs differ by seed, not by geometry
_CACHE: dict = {}


@dataclasses.dataclass(frozen=True)
class Setting:
    """What every inequality of one geometry shares, as the linker bound measured it: the
    model (its linker one that leaves the core), each domain's reach terms and inner volume,
    the judged chains (a periodic cell's one layer, or the scored layers lo..hi-1, with
    chains_per_pf of each protofilament), the first linker that leaves the core, and the voxel
    room (None when no path leaves the anchor). The bound on the fraction reads the same room
    (fibrilfit/model/fraction_bound.py, docs/model/bound.md#fraction)."""
    p: object
    terms: list
    volumes: list
    periodic: bool
    lo: int
    hi: int
    chains_per_pf: int
    first: int
    room: Room | None
    impossible_below: int


def setting(p, budget: float = GRID_BUDGET) -> Setting:
    """The geometry's Setting, measured once with its linker bound (cached like it)."""
    if occupancy.is_hetero(p):  # its volumes are the two letters' shares: not one domain's
        raise ValueError("the fraction bound is not built for a hetero-amyloid "
                         "(docs/model/bound.md#hetero)")
    key = _settings_key(p) + f"|{budget:g}"
    _linker_bound(key, p, budget)
    return _CACHE[key][1]


def _linker_bound(key: str, p, budget: float) -> dict:
    if key in _CACHE:
        return _CACHE[key][0]
    volumes = [ball_union_volume(inner_balls(p, d)) for d in p.domains]
    periodic = bool(p.periodic)
    if periodic:
        lo, hi, chains_per_pf = 0, 1, 1
    else:
        lo, hi = p.score_layers, p.layers - p.score_layers  # analysis/verdict.scored_range
        chains_per_pf = hi - lo
    letters = hetero.letter_shares(p, lo, hi) if occupancy.is_hetero(p) else None
    # a buried anchor's exit spends its residues first: no linker up to them leaves the core
    # (docs/model/buried-terminus.md#model); the model's anchor is where the free linker starts
    # (with interface termini each protofilament's own: the most any spends, Params.exit_spent)
    first = int(p.exit_spent) + 1
    if first > LONGEST:  # sealed: no path leaves the anchor
        result = {"impossible_below": LONGEST + 1, "method": "no exit: no path clear of the "
                  "core's atoms leaves the anchor (docs/model/buried-terminus.md#model)",
                  "over": "every chain", "fails_below": None, "exit_residues": p.exit_residues}
        _CACHE[key] = (result, Setting(p, [], volumes, periodic, lo, hi, chains_per_pf, first,
                                       None, LONGEST + 1))
        return result
    if p.free_linker < 1:  # a linker that leaves the core, for the chain's lengths (its
        p = dataclasses.replace(p, linker=first)  # checks aside: only chain_x is read)
    terms = reach_terms(p)
    shown = volumes
    if letters is not None:  # a hetero-amyloid: A's and B's, each its share of the chains
        q = hetero.b_params(p)
        (b_volume,) = [ball_union_volume(inner_balls(q, d)) for d in q.domains]
        shown = [volumes[0], b_volume]
        terms = terms + reach_terms(q)
        volumes = [v * share for v, share in zip(shown, letters)]
    top = max(8, first)  # not the linker asked: the bound is the geometry's, whatever ran first
    while True:
        rho_top = pf_reach(p, terms, top).ravel()
        room = Room(p, max(rho_top), periodic, lo, hi, budget)
        found = None
        for L in range(first, top + 1):  # monotone: the first length where all hold
            if all(c["need"] <= c["have"] for c in constraints(
                    p, room, terms, volumes, L, chains_per_pf)):
                found = L
                break
        if found is not None or top >= LONGEST:
            break
        top = min(LONGEST, top * 2)
    failing = None
    if found is not None and found > first:
        cs = constraints(p, room, terms, volumes, found - 1, chains_per_pf)
        worst = max(cs, key=lambda c: c["need"] / max(c["have"], 1e-9))
        failing = {"linker": found - 1, "protofilaments": worst["protofilaments"], "domains": worst["domains"],
                   "needed_A3": round(worst["need"], 1), "room_A3": round(worst["have"], 1)}
    result = {
        "impossible_below": found if found is not None else LONGEST + 1,
        "method": ("excluded volume (docs/model/bound.md#derivation)" if letters is None else
                   "excluded volume, A and B each at its own size (docs/model/bound.md#hetero)"),
        "over": ("one layer of the infinite fibril" if periodic
                 else f"the scored layers {lo}-{hi - 1}"),
        "fails_below": failing,
        "inner_volume_A3": [round(v, 1) for v in shown],
        "core_entry": CORE_ENTRY,
        "voxel": round(room.h, 4),
        "exit_residues": int(p.exit_residues),
    }
    if p.pf_anchors is not None:  # each protofilament's own exit, its own free linker
        result["pf_exit_residues"] = [int(v) for v in p.pf_exit_residues()]
    _CACHE[key] = (result, Setting(p, terms, volumes, periodic, lo, hi, chains_per_pf, first,
                                   room, result["impossible_below"]))
    return result


def bound_block(p) -> dict:
    """The result's `bound`: the bound, and whether this run's linker lies below it (settled:
    no layout can exist there, whatever the run finds)."""
    b = linker_bound(p)
    return {**b, "linker": p.linker, "below": p.linker < b["impossible_below"]}


def core_entry(p, matrices, sizes=None) -> float:
    """How deep (Å) the deepest inner ball (`inner_balls`) of any domain enters a core prism, for
    chain members' world matrices (chains, members, 4, 4): the bound's third assumption,
    measured (docs/model/bound.md#assumptions). A ball counts against the prism of the layer
    whose slice holds its centre: its depth is its radius less the centre's distance outside
    the layer's outline (plus the distance inside it); a centre above or below a finite stack's
    end counts nothing. `sizes`: each chain's globule as a scale of the first domain's (a
    hetero-amyloid's B chains: d_B / d_A, their spheres' balls that much larger; default 1)."""
    matrices = np.asarray(matrices, dtype=float)
    outline = p.outline()
    t = core_thickness(p)
    deepest = 0.0
    for d in p.domains:
        balls = inner_balls(p, d)
        m = matrices[:, d.member]
        world = np.einsum("cij,bj->cbi", m[:, :3, :3], balls[:, :3]) + m[:, None, :3, 3]
        k, xy = helix.layer_frame_xy(p, world)
        rows = xy.reshape(-1, 2)
        dist = polygons.edge_distance(outline, rows)[0]
        inside = polygons.even_odd(outline, rows)
        signed = np.where(inside, -dist, dist).reshape(k.shape)
        radius = balls[None, :, 3] if sizes is None else \
            balls[None, :, 3] * np.asarray(sizes, dtype=float)[:, None]
        depth = radius - signed
        in_slice = np.abs(world[..., 2] - k * p.rise) <= t / 2.0
        if not p.periodic:
            in_slice &= (k >= 0) & (k < p.layers)
        if in_slice.any():
            deepest = max(deepest, float(depth[in_slice].max()))
    return round(max(deepest, 0.0), 4)
