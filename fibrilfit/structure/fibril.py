"""Measure a fibril: layers, protofilaments, helical axis, rise and twist, core, outline, anchors.

Everything from the coordinates; chain IDs and file order are never trusted.

Over 400 lines: one pipeline, `measure`, whose steps (stacking, axis, rise and twist,
protofilaments, reference layer, anchors) hand each other the same arrays; the parts with a
question of their own are rooms beside it (solenoid.py, one_screw.py, side_contacts.py,
chain_kinds.py, outline.py, exit.py). Splitting the anchors and the layer frame out is the next
step (termini.py and atoms.py read them).
"""
from __future__ import annotations

import copy
import math
from dataclasses import asdict, dataclass, field
from functools import reduce

import numpy as np

from ..geom import rigid as G
from . import (chain_kinds, exit as X, one_screw, outline as O, reading, side_contacts,
               solenoid as S)
from .errors import StructureError

STACK = (4.2, 5.6)  # Å: a residue is stacked when its CA sits this far over the same residue
MIN_STACKED = 4  # stacked residues two chains need to count as neighbouring layers
CORE_GAP = 4  # unstacked residues (turns) allowed inside the core
MIN_SEGMENT = 5  # stacked residues a further ordered segment needs to join the core (a strand)
EXACT_COPIES_RMSD = 0.5  # Å: below it a one-protofilament stack defines a screw axis
BURIED_DEPTH = 6.0  # Å: atoms this much farther out in the anchor's sector bury it
SECTOR = math.radians(15.0)
MAX_AXIS_SPREAD = (5.0, 5.0)  # °, Å: how far the axes of protofilament pairs may disagree


@dataclass
class Anchor:
    protofilament: int
    chain: str
    residue: int
    residue_name: str
    radius: float  # Å from the axis
    position: list  # [x, y] Å in the layer frame
    height: float  # Å along the axis, from the reference layer's plane
    depth: float  # Å: largest radius of a core atom in its ±15° sector minus its own
    buried: bool
    tail_residues: list  # [first, last] outside the core beyond the anchor, or []


@dataclass
class FibrilGeometry:
    """What `inspect --fibril` measures. to_dict() gives the JSON of the issue's key names."""

    file: str
    sha256: str
    axis: dict  # file frame: {"point": layer frame origin, "direction": Z, "x": X}, Å
    rise: float
    rise_sd: float
    twist: float  # rad, positive = right-handed looking along the rise
    twist_sd: float
    protofilaments: int
    pf_rotation: float  # rad, protofilament 1 relative to 0 (0 when one protofilament)
    pf_rise: float  # Å
    layers: int  # chains of the longest protofilament
    core_residues: list  # [first, last]
    core_outline: list  # [[x, y], ...] Å, layer frame, counter-clockwise
    anchors: list  # Anchor per protofilament
    tail_residues: list  # protofilament 0's: [first, last] or []
    terminus: str  # "N", "C" or "residue R"
    layer_chains: list  # per protofilament, chain names from bottom to top
    axis_exact: bool  # False when the axis is only approximate (no screw symmetry)
    pf_offsets: list = field(default_factory=list)  # [[rotation, rise]] per protofilament
    exit: dict = field(default_factory=dict)  # protofilament 0's anchor to the surface (exit.py)
    notes: list = field(default_factory=list)
    warnings: list = field(default_factory=list)
    # every ordered segment of the core, [[first, last], ...] (docs/guide/structures.md#cores-in-pieces)
    core_segments: list = field(default_factory=list)
    # a β-solenoid's rungs per molecule and their spacing along the axis (1 and the rise for a
    # one-rung fibril); a layer is a molecule (docs/guide/structures.md#beta-solenoids)
    rungs: int = 1
    rung_rise: float = 0.0
    rung_rise_sd: float = 0.0

    def to_dict(self) -> dict:
        return asdict(self)


def _stacked(a, b, window=STACK):
    d = np.linalg.norm(a - b, axis=-1)
    return (d >= window[0]) & (d <= window[1])


def _paths(n_chains, edges, option):
    """Connected components of the stacking graph, each a path (a protofilament's layers)."""
    nbrs = {i: set() for i in range(n_chains)}
    for i, j in edges:
        nbrs[i].add(j)
        nbrs[j].add(i)
    seen, paths = set(), []
    for start in range(n_chains):
        if start in seen:
            continue
        comp, todo = set(), [start]
        while todo:
            i = todo.pop()
            if i not in comp:
                comp.add(i)
                todo += list(nbrs[i] - comp)
        seen |= comp
        ends = [i for i in comp if len(nbrs[i]) <= 1]
        if any(len(nbrs[i]) > 2 for i in comp) or (len(comp) > 1 and len(ends) != 2):
            raise StructureError(option, "the layers do not stack into protofilaments "
                                         "(a chain stacks on more than two others)")
        path, prev = [min(ends)] if ends else [start], None
        while len(path) < len(comp):
            nxt = [j for j in nbrs[path[-1]] if j != prev]
            prev = path[-1]
            path.append(nxt[0])
        paths.append(path)
    return paths


def _core_segments(stacked_numbers):
    """[[first, last], ...] of the runs of stacked residues (gaps of up to CORE_GAP bridged):
    the longest, and every other of at least MIN_SEGMENT stacked residues (9XBO's 5-65 and
    102-132: docs/guide/structures.md#cores-in-pieces), in chain order."""
    runs, run = [], [stacked_numbers[0]]
    for r in stacked_numbers[1:]:
        if r - run[-1] <= CORE_GAP + 1:
            run.append(r)
        else:
            runs.append(run)
            run = [r]
    runs.append(run)
    best = max(runs, key=len)
    return [[int(q[0]), int(q[-1])] for q in runs if q is best or len(q) >= MIN_SEGMENT]


def _in_core(numbers, segments) -> np.ndarray:
    """Which residue numbers lie in a core segment."""
    numbers = np.asarray(numbers)
    return np.logical_or.reduce([(numbers >= a) & (numbers <= b) for a, b in segments])


def _stacking(chains, name, option, window=STACK, notes=None):
    """Common residues, their CA (chains, residues, 3), the stacked residues of each stacking
    pair of chains (the same residue's CAs `window` Å apart), and the protofilaments as paths
    of chain indices."""
    common = reduce(np.intersect1d, [c.residues for c in chains])
    if len(common) < MIN_STACKED:  # fewer than MIN_STACKED: which kinds of chain, if several
        raise StructureError(option, f"{name}: {chain_kinds.why(chains, len(common))}")
    ca = np.array([c.ca_of(common) for c in chains])
    pairs = {}
    for i in range(len(chains)):
        for j in range(i + 1, len(chains)):
            s = _stacked(ca[i], ca[j], window)
            if s.sum() >= max(MIN_STACKED, 0.1 * len(common)):
                pairs[(i, j)] = s
    pairs = side_contacts.layers_only(pairs, [c.name for c in chains], name, option, notes)
    return chains, common, ca, pairs, _paths(len(chains), pairs, option)


def longest_stack(loaded) -> int:
    """Chains in the longest stack of a loaded file (CA over the same residue's CA 4.2-5.6 Å
    apart, as a fibril's layers), its assembly or NCS copies included: 1 when none stack. A
    globular domain's chains (1GFL's two) do not stack; 6CU7's ten make two stacks of five;
    a β-solenoid's molecules stack rung on rung (2KJ3's ten: one stack)."""
    probe = copy.copy(loaded)  # expand_symmetry rebinds chains and notes: the file's stay
    probe.notes = []
    if len(probe.chains) < 2 and not reading.expand_symmetry(probe):
        return 1
    try:
        *_, paths = _stacking(probe.chains, probe.path.name, "--domain")
        if max(len(q) for q in paths) < 2:  # docs/guide/structures.md#beta-solenoids
            solenoid = _solenoid(probe.chains, probe.path.name, "--domain")
            paths = solenoid[0][-1] if solenoid is not None else paths
    except StructureError:  # too few common residues, or a branching stack: no fibril's layers
        return 1
    return max(len(q) for q in paths)


def measure(path, *, terminus: str = "C", anchor_residue: int | None = None,
            option: str = "--fibril") -> FibrilGeometry:
    loaded = reading.load(path, option, peptides=True)
    name = loaded.path.name
    chains, paths, segments, cca, cen, rungs, core_numbers = _stacked_core(loaded, name, option)
    notes, warnings = list(loaded.notes), []
    u, p, exact = _axis(paths, cca, cen, name, option, warnings, [c.name for c in chains])
    # order every protofilament along the axis; protofilament 0 holds the lowest layer
    height = (cen - p) @ u
    paths = [sorted(q, key=lambda i: height[i]) for q in paths]
    paths.sort(key=lambda q: height[q[0]])
    frame0 = G.frame(u)
    rises, twists = _rise_twist(paths, cca, cen, u, p, frame0, name, option)
    rise, twist = float(np.mean(rises)), float(np.mean(twists))
    steps = S.rung_rise(cca, core_numbers, STACK, u) if rungs > 1 else [rise]
    if rungs > 1 and S.check(rungs, rise, steps):
        raise StructureError(option, f"{name}: not a β-solenoid: {S.check(rungs, rise, steps)}")
    paths, offsets = _protofilament_offsets(paths, cca, cen, u, p, frame0, rise, twist)
    refs, origin, frame, poly = _reference_layer(chains, paths, segments, cen, u, p, frame0,
                                                 height, rise, warnings)
    anchors = _anchors(chains, refs, segments, origin, frame, rise, terminus, anchor_residue, name,
                       warnings)
    sd = (lambda v: float(np.std(v, ddof=1)) if len(v) > 1 else 0.0)
    way_out = X.way_out(chains, [chains[i].name for i in paths[0]], chains[refs[0]],
                        anchors[0].residue, "N" if terminus == "N" else "C", origin, frame,
                        np.round(poly, 2), rise, segments, [chains[i] for i in refs])
    return FibrilGeometry(
        file=name, sha256=loaded.sha256,
        axis={"point": [round(float(v), 3) for v in origin],
              "direction": [round(float(v), 6) for v in u],
              "x": [round(float(v), 6) for v in frame[0]]},
        rise=round(rise, 4), rise_sd=round(sd(rises), 4),
        twist=round(twist, 6), twist_sd=round(sd(twists), 6),
        protofilaments=len(paths),
        pf_rotation=round(offsets[1][0], 6) if len(paths) > 1 else 0.0,
        pf_rise=round(offsets[1][1], 4) if len(paths) > 1 else 0.0,
        layers=max(len(q) for q in paths), core_residues=[segments[0][0], segments[-1][1]],
        core_outline=[[round(float(a), 2), round(float(b), 2)] for a, b in poly],
        anchors=[asdict(a) for a in anchors], tail_residues=anchors[0].tail_residues,
        terminus=f"residue {anchor_residue}" if anchor_residue is not None else terminus,
        layer_chains=[[chains[i].name for i in q] for q in paths], axis_exact=exact,
        pf_offsets=[[round(a, 6), round(b, 4)] for a, b in offsets], exit=way_out, notes=notes,
        warnings=warnings, core_segments=segments, rungs=rungs,
        rung_rise=round(float(np.mean(steps)), 4), rung_rise_sd=round(sd(steps), 4))


def _planar(xyz, p, frame0):
    """Points in the plane across the axis through p (frame0's first two axes)."""
    rel = (xyz - p) @ frame0.T
    return rel[..., :2]


def _solenoid(chains, name: str, option: str):
    """A β-solenoid's stacking (docs/guide/structures.md#beta-solenoids): when every chain
    stacks on itself (rung on rung), the fewest rungs per molecule n for which the molecules
    stack (the same residue n rungs apart); (_stacking's tuple, n) or None."""
    common = reduce(np.intersect1d, [c.residues for c in chains])
    if len(chains) < 2 or len(common) < MIN_STACKED:
        return None
    ca = np.array([c.ca_of(common) for c in chains])
    if not S.self_stacked(ca, common, STACK, MIN_STACKED):
        return None
    for n, window in S.windows(STACK):
        found = _stacking(chains, name, option, window)
        longest = max(found[-1], key=len)
        if len(longest) < 2:
            continue
        cen = found[2].mean(axis=1)  # the molecules' rungs must stack along their stack
        along = cen[longest[-1]] - cen[longest[0]]
        if S.along_share(ca, common, STACK, along / np.linalg.norm(along)) >= S.MIN_ALONG:
            return found, n
    return None


def _stacked_core(loaded, name: str, option: str) -> tuple:
    """The chains, their stacks (paths of chain indices, one per protofilament, longest first),
    the core's segments [[first, last], ...], each chain's core CA (chains, residues, 3) and
    centroid, the rungs per molecule (1, or a β-solenoid's) and the core's residue numbers."""
    if len(loaded.chains) < 2 and not reading.expand_symmetry(loaded):
        raise StructureError(option, f"{name}: one layer (chain) and no symmetry operators: "
                                     "give --rise and --twist instead")
    chains, common, ca, pairs, paths = _stacking(loaded.chains, name, option,
                                                 notes=loaded.notes)
    rungs, solenoid = 1, None
    if max(len(q) for q in paths) < 2:  # no two chains stack: a solenoid, or a symmetry's layers
        solenoid = _solenoid(loaded.chains, name, option)
        if solenoid is None and not reading.expand_symmetry(loaded):
            raise StructureError(option, f"{name}: no two chains stack {STACK[0]}-{STACK[1]} Å "
                                         "apart, nor does a chain stack on itself as a "
                                         "β-solenoid's rungs: the layers do not stack (fewer "
                                         "than 2 layers): give --rise and --twist")
        if solenoid is None:
            chains, common, ca, pairs, paths = _stacking(loaded.chains, name, option,
                                                 notes=loaded.notes)
            if max(len(q) for q in paths) < 2:
                solenoid = _solenoid(loaded.chains, name, option)
                if solenoid is None:
                    raise StructureError(option, f"{name}: even with its symmetry operators no "
                                                 "two chains stack: the layers do not stack")
        if solenoid is not None:
            (chains, common, ca, pairs, paths), rungs = solenoid
    if rungs > 1:  # the rungs' residues: stacked on their own chain in every chain
        stacked_all = S.rung_mask(ca, common, STACK)
    else:
        stacked_all = np.logical_and.reduce([pairs[tuple(sorted((p[k], p[k + 1])))]
                                             for p in paths for k in range(len(p) - 1)])
    if stacked_all.sum() < MIN_STACKED:
        raise StructureError(option, f"{name}: fewer than {MIN_STACKED} residues stack in every "
                                     "layer: the layers do not stack")
    segments = _core_segments(common[stacked_all])
    in_core = _in_core(common, segments)
    cca = ca[:, in_core]  # core CA
    paths.sort(key=len, reverse=True)
    return chains, paths, segments, cca, cca.mean(axis=1), rungs, common[in_core]


def _axis(paths, cca, cen, name: str, option: str, warnings: list, names=()) -> tuple:
    """The helical axis: its direction u (pointing up the file's dominant axis), a point p on
    it, and whether it is exact (a screw of the layers) or only approximate (warned). When the
    protofilament pairs' axes disagree, the one screw of every layer (one_screw.py)."""
    first = paths[0]
    along = cen[first[-1]] - cen[first[0]]
    exact = True
    if len(paths) >= 2:  # a protofilament pair: its ~2-fold screw pins the axis
        dirs, points = [], []
        for a in first:
            b = min(paths[1], key=lambda j: np.linalg.norm(cen[j] - cen[a]))
            R, t, _ = G.superpose(cca[a], cca[b])
            u, p, _, _ = G.screw_axis(R, t)
            dirs.append(u if u @ along >= 0 else -u)
            points.append(p)
        u = np.mean(dirs, axis=0)
        u /= np.linalg.norm(u)
        ref = cen.mean(axis=0)
        on_plane = [q + ((ref - q) @ d) * d for q, d in zip(points, dirs)]
        p = np.mean(on_plane, axis=0)
        spread = max(math.degrees(math.acos(min(1.0, d @ u))) for d in dirs)
        off = max(np.linalg.norm(q - p) for q in on_plane)
        if spread > MAX_AXIS_SPREAD[0] or off > MAX_AXIS_SPREAD[1]:  # not copies of each other
            u, p, exact = one_screw.axis(paths, cca, cen, along, (spread, off), list(names),
                                         name, option, warnings)
    else:
        a = np.concatenate([cca[i] for i in first[:-1]])
        b = np.concatenate([cca[i] for i in first[1:]])
        R, t, rmsd = G.superpose(a, b)
        u, p, angle, _ = G.screw_axis(R, t)
        if rmsd > EXACT_COPIES_RMSD or angle < math.radians(0.1):
            exact = False
            steps = np.diff(cca[first], axis=0).reshape(-1, 3).mean(axis=0)
            u, p = steps / np.linalg.norm(steps), cca[first].reshape(-1, 3).mean(axis=0)
            warnings.append(f"the layers are not exact helical copies (superposition RMSD "
                            f"{rmsd:.2f} Å): axis approximate, through the core's centroid; "
                            "twist and radii depend on it")
        u = u if u @ along >= 0 else -u
    if u[np.argmax(np.abs(u))] < 0:  # a fixed sign: the file's dominant axis points up
        u = -u
    return u, p, exact


def _rise_twist(paths, cca, cen, u, p, frame0, name: str, option: str) -> tuple:
    """Rise and twist of every consecutive layer pair of every protofilament."""
    rises, twists = [], []
    for q in paths:
        for i, j in zip(q, q[1:]):
            rises.append((cen[j] - cen[i]) @ u)
            twists.append(G.turn_angle(_planar(cca[i], p, frame0), _planar(cca[j], p, frame0)))
    rise = float(np.mean(rises))
    if min(rises) <= 0.5 * rise or max(rises) >= 1.5 * rise:
        raise StructureError(option, f"{name}: the layers do not stack on a common axis (steps "
                                     f"along it from {min(rises):.2f} to {max(rises):.2f} Å)")
    return rises, twists


def _protofilament_offsets(paths, cca, cen, u, p, frame0, rise: float, twist: float) -> tuple:
    """Each protofilament's turn and rise relative to protofilament 0, the protofilaments
    ordered by that turn."""
    offsets = [[0.0, 0.0]]
    for q in paths[1:]:
        rots, dzs = [], []
        for a in paths[0]:
            for b in q:
                dz = (cen[b] - cen[a]) @ u
                m = math.floor((dz + 0.1 * rise) / rise)
                if abs(m) <= 2:
                    dzs.append(dz - m * rise)
                    rots.append(G.wrap(G.turn_angle(_planar(cca[a], p, frame0),
                                                    _planar(cca[b], p, frame0)) - m * twist))
        rot = math.atan2(np.mean(np.sin(rots)), np.mean(np.cos(rots)))
        offsets.append([rot, float(np.mean(dzs))])
    order = [0] + sorted(range(1, len(paths)), key=lambda k: offsets[k][0] % (2 * math.pi))
    return [paths[k] for k in order], [offsets[k] for k in order]


def _reference_layer(chains, paths, segments, cen, u, p, frame0, height, rise: float,
                     warnings: list) -> tuple:
    """The reference layer (one chain per protofilament), the model's frame at it (origin on
    the axis, x along the core's long principal axis) and the core section's outline."""
    ref0 = paths[0][(len(paths[0]) - 1) // 2]
    refs = [ref0]
    for q in paths[1:]:
        refs.append(min(q, key=lambda b: abs(((cen[b] - cen[ref0]) @ u) - 0.4 * rise)))
    origin = p + height[ref0] * u
    core_heavy = []
    for i in refs:
        c = chains[i]
        keep = _in_core(c.heavy_residue, segments)
        core_heavy.append((c.heavy[keep], c.heavy_radius[keep]))
    xyz = np.concatenate([h for h, _ in core_heavy])
    radii = np.concatenate([r for _, r in core_heavy])
    flat = _planar(xyz, p, frame0)
    centred = flat - flat.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    e1 = vt[0] @ frame0[:2]  # long principal axis, back in 3-D
    if (_planar(core_heavy[0][0], p, frame0).mean(axis=0) @ vt[0]) < 0:
        e1 = -e1
    frame = G.frame(u, e1)
    section = ((xyz - origin) @ frame.T)[:, :2]
    poly, stray = O.polygon(section, radii)
    if stray > 0.05:
        warnings.append(f"the core section is in pieces: {stray:.0%} of its atoms lie outside "
                        "the outline of the largest piece")
    return refs, origin, frame, poly


def _anchors(chains, refs, segments, origin, frame, rise: float, terminus: str,
             anchor_residue: int | None, name: str, warnings: list) -> list:
    """Each protofilament's anchor residue in the model's frame, with its depth below the
    core's surface in its sector (warned when buried) and the tail beyond it."""
    def layer(xyz):
        return (xyz - origin) @ frame.T

    all_core = np.concatenate([c.heavy[_in_core(c.heavy_residue, segments)] for c in chains])
    all_core = layer(all_core)
    all_r = np.hypot(all_core[:, 0], all_core[:, 1])
    all_phi = np.arctan2(all_core[:, 1], all_core[:, 0])
    anchors = []
    for k, i in enumerate(refs):
        c = chains[i]
        if anchor_residue is not None:
            if anchor_residue not in c.residues:
                raise StructureError("--anchor-residue", f"residue {anchor_residue} is not in "
                                     f"chain {c.name} of {name} (residues {c.residues[0]}-"
                                     f"{c.residues[-1]})")
            res = int(anchor_residue)
        else:
            present = c.residues[_in_core(c.residues, segments)]  # every segment's
            res = int(present[-1] if terminus == "C" else present[0])
        x, y, z = layer(c.ca_of([res]))[0]
        r = math.hypot(x, y)
        phi = math.atan2(y, x)
        near = (np.abs(all_core[:, 2] - z) <= rise) & \
               (np.abs(np.angle(np.exp(1j * (all_phi - phi)))) <= SECTOR)
        depth = max(0.0, float(all_r[near].max() - r)) if near.any() else 0.0
        if terminus == "N" and anchor_residue is None:
            tail = c.residues[(c.residues < res) & (c.residues < segments[0][0])]
        else:  # an unordered stretch between segments is inside the fibril, not linker
            tail = c.residues[(c.residues > res) & (c.residues > segments[-1][1])]
        anchor = Anchor(k, c.name, res, c.names[int(np.searchsorted(c.residues, res))],
                        round(r, 3), [round(float(x), 3), round(float(y), 3)],
                        round(float(z), 3), round(depth, 2), depth > BURIED_DEPTH,
                        [int(tail[0]), int(tail[-1])] if len(tail) else [])
        if anchor.buried:
            warnings.append(f"anchor {c.name} {anchor.residue_name}{res} (protofilament {k}) is "
                            f"buried: core atoms reach {depth:.1f} Å farther out in its sector; "
                            "the linker's way out is measured (the result's `exit`)")
        anchors.append(anchor)
    return anchors


def layer_frame(geometry: FibrilGeometry) -> tuple[np.ndarray, np.ndarray]:
    """(origin, frame): the model's layer-0 frame in the file's coordinates. A file point xyz
    is (xyz - origin) @ frame.T in the model (frame rows: X, Y, Z = the helical axis)."""
    ax = geometry.axis
    origin = np.asarray(ax["point"], float)
    return origin, G.frame(np.asarray(ax["direction"], float), np.asarray(ax["x"], float))


def reference_chains(path, geometry: FibrilGeometry, option: str = "--fibril") -> list:
    """Each protofilament's reference chain (reading.ChainAtoms, file coordinates), as `measure`
    chose it (the chains of a one-chain file built from its symmetry as `measure` built them)."""
    loaded = reading.load(path, option, peptides=True)
    chains = _stacked_core(loaded, loaded.path.name, option)[0]
    by_name = {c.name: c for c in chains}
    return [by_name[a["chain"]] for a in geometry.anchors]
