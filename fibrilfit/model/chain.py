"""A chain at rest, from its parameters: where each member (anchor, linker residues, domains)
sits along it (`chain_x`), each member's radius (`chain_radii`) and how far its body reaches
(`body_radii`, `chain_reach`), the bonds' rest lengths, and protofilament 0's chain laid out in
the layer's frame (`ChainLayout`, `chain_layout`; each protofilament's own with interface
termini, `pf_layouts`). Plain numpy, no bpy.

A chain is an anchor, `free_linker - 1` residues, then each domain (domains.py: a `Domain`
knows its place along the chain, `member`) with the residues between them. Every room asks
this module for the chain's lengths; `Params.chain_layout` keeps the layout of one Params
(it is asked for by the checks, the start layouts and the builders alike).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..geom import polygons
from .domains import member_indices
from .param_spec import ParamError


def globule_offset(p) -> float:
    """From the last bond's pivot to the first domain's centre: the sphere's radius, or with a
    real shape the joint's distance from the domain's centroid."""
    joint = p.domains[0].joint
    if joint is None:
        return p.globule_radius
    return math.sqrt(sum(x * x for x in p.domain_joint[0]))


def joint_lever(p) -> float:
    """From the last linker bead's centre to the globule's joint: its radius (the sphere's
    surface), or with a real shape one residue spacing (the joint is the domain's terminal
    CA, the next residue along the chain)."""
    return p.residue_spacing if p.shape.real else p.residue_radius


def chain_x(p) -> list[float]:
    """Distance of each chain member (anchor, residues, domains) from the axis, for a radial
    linker (the tutorial's); in general the anchor's distance plus the distance along the
    chain: consecutive residues `residue_spacing` apart, a domain touching its neighbours; a
    real-shaped domain (hull, spheres) joined at its terminal CA, one residue spacing from the
    last bead (joint_lever, globule_offset)."""
    radii, places = chain_radii(p), member_indices(p)
    globules, first = set(places), min(places)
    # several real shapes: into domain k at its joint, out of it at its exit, each one
    # residue spacing from the bead beside it (docs/guide/atoms-and-domains.md#shapes-of-several-domains)
    # (the first domain's joint is globule_offset's, below)
    into = {d.member: p.residue_spacing + float(np.linalg.norm(d.joint))
            for d in p.domains if d.joint is not None}
    out = {d.member: float(np.linalg.norm(d.exit)) + p.residue_spacing
           for d in p.domains if d.exit is not None}
    xs = [p.anchor_x]
    for i in range(len(radii) - 1):
        if i not in globules and i + 1 not in globules:
            step = p.residue_spacing
        elif i + 1 == first:  # the sphere's radius + the bead's, or the real joint
            step = joint_lever(p) + globule_offset(p)
        elif i + 1 in into:
            step = into[i + 1]
        elif i in out:
            step = out[i]
        else:
            step = radii[i] + radii[i + 1]
        xs.append(xs[-1] + step)
    return xs


def chain_radii(p) -> list[float]:
    """Radius of each chain member: a residue's, a domain's at its place (Domain.radius)."""
    radii = [p.residue_radius] * (member_indices(p)[-1] + 1)
    for d in p.domains:
        radii[d.member] = d.radius
    return radii


def chain_members(p) -> int:
    """Members of one chain: its anchor, residues and domains."""
    return member_indices(p)[-1] + 1


def rest_lengths(p) -> list[float]:
    """Rest length of each bond along the chain (`chain_members - 1` bonds)."""
    xs = chain_x(p)
    return [b - a for a, b in zip(xs, xs[1:])]


def body_radii(p) -> np.ndarray:
    """How far each chain member's body reaches from its centre (Å): chain_radii, a real shape's
    globule reaching its shape's reach (the sphere's: its radius, unchanged)."""
    radii = np.asarray(chain_radii(p), dtype=float)
    for d in p.domains:
        radii[d.member] = max(radii[d.member], d.reach)
    return radii


def chain_reach(p) -> np.ndarray:
    """How far along Z each chain member's surface can get from its anchor's height (Å).

    Member i's centre lies within the linker's length up to it (every bond at rest plus the
    stretch tolerance) of the anchor; its surface one radius further.
    """
    x = np.asarray(chain_x(p), dtype=float)
    return (x - x[0]) * (1.0 + p.stretch_tolerance) + body_radii(p)


def tail_members(p) -> int:
    """Members of an undecorated subunit's bare tail the model builds (its buried anchor first):
    `bare_tail` less the residues its exit spends, as for the linker (0: none)."""
    return max(0, p.bare_tail - p.exit_spent) if p.bare_tail else 0


def tail_chain(p):
    """The Params of a bare tail's chain: a one-sphere chain longer than the tail, whose first
    tail_members(p) members (anchor and beads) are the tail's (builders.layers lays it out)."""
    return dataclasses.replace(p, linker=p.exit_spent + tail_members(p) + 1,
                               domain_shape="sphere", domain_diameters=None, domain_linker=None)


def tail_reach(p) -> np.ndarray:
    """How far along Z each bare-tail member's surface can get from its anchor's height (Å),
    as chain_reach for a linker: its beads at rest plus the stretch tolerance, one radius
    further (empty without tails)."""
    n = tail_members(p)
    return chain_reach(tail_chain(p))[:n] if n else np.zeros(0)


def body_reach(p) -> float:
    """The farthest any body of a layer reaches along Z from its own layer's height (Å)."""
    return float(max(chain_reach(p).max(), p.slab[2] / 2.0))


class AnchorInside(ParamError):
    """The anchor, or protofilament j's copy of it (turned by `turn`, at `xy`), lies inside the
    core: a structure file's caller can say what the file's own protofilament j measures
    (structure/termini.py)."""

    def __init__(self, message: str, protofilament: int, xy, turn: float):
        super().__init__("anchor", message)
        self.protofilament, self.xy, self.turn = protofilament, np.asarray(xy), float(turn)


class CopiesBlocked(ParamError):
    """Protofilament 0's own chain has a straight way clear of the core, its copies turned onto
    the other protofilaments have none (structure/termini.py measures their own termini)."""


def _blocked_by_copies(p, outline, anchor, offsets) -> str:
    """Why no direction is free, when it is the other protofilaments' copies of the chain that
    block it (docs/guide/structures.md#interface-termini): what the user can do."""
    if p.protofilaments < 2:
        return ""
    try:
        polygons.linker_direction(outline, anchor, offsets, chain_radii(p), [0.0])
    except polygons.GeometryError:
        return ""  # protofilament 0's own chain is blocked: the message as it was
    return (f" (protofilament 0's own chain has a free direction; the copies turned onto the "
            f"other {p.protofilaments - 1} protofilament(s) block every one: give "
            f"--protofilaments 1 to decorate protofilament 0 alone, or --anchor X Y)")


@dataclass(frozen=True)
class ChainLayout:
    """Protofilament 0's chain in the layer's frame: each member's centre (n, 2), the same in
    polar form (radius, angle; exact for the tutorial's radial chain), the chain's direction
    and the rule that chose it (polygons.linker_direction)."""

    xy: np.ndarray
    radius: np.ndarray
    angle: np.ndarray
    direction: np.ndarray
    rule: str


def chain_layout(p) -> ChainLayout:
    """Protofilament 0's chain in the layer's frame (Params.chain_layout keeps it). Raises
    ParamError: an anchor inside the core, or no direction that takes the chain clear of it."""
    if p.pf_anchors is not None:  # each protofilament its own (pf_layouts): protofilament 0's
        return pf_layouts(p)[0]
    outline = p.outline()
    anchor = np.array(p.anchor_xy, dtype=float)
    offsets = np.asarray(chain_x(p)) - p.anchor_x  # along the chain from the anchor
    copies = [float(a) for a in p.pf_offsets()[0]]
    for j, a in enumerate(copies):
        xy = polygons.rotate(anchor, a)
        if polygons.inside(outline, xy[None])[0]:
            where = "" if j == 0 else (f" (protofilament {j}'s copy, turned by "
                                       f"{math.degrees(a):.1f}°, at ({xy[0]:.2f}, {xy[1]:.2f}))")
            raise AnchorInside(f"({anchor[0]:g}, {anchor[1]:g}) Å lies inside the core"
                               f"{where}; the linker must start outside it: put the "
                               f"anchor on or outside the core's outline", j, xy, a)
    try:
        direction, rule = polygons.linker_direction(outline, anchor, offsets, chain_radii(p),
                                                    copies)
    except polygons.GeometryError as exc:
        copies = _blocked_by_copies(p, outline, anchor, offsets)
        raise (CopiesBlocked if copies else ParamError)(
            "anchor", f"at ({anchor[0]:g}, {anchor[1]:g}) Å: {exc}{copies}") from None
    if rule == "radial":
        radius = np.asarray(chain_x(p))
        angle = np.full(radius.size, math.atan2(anchor[1], anchor[0]))
        xy = np.stack([np.cos(angle) * radius, np.sin(angle) * radius], axis=1)
    else:
        xy = anchor[None] + offsets[:, None] * direction[None]
        radius, angle = np.hypot(xy[:, 0], xy[:, 1]), np.arctan2(xy[:, 1], xy[:, 0])
    return ChainLayout(xy, radius, angle, direction, rule)


def pf_layouts(p) -> list[ChainLayout]:
    """Each protofilament's chain in its own frame, before its turn (Params.pf_layouts keeps
    them): protofilament 0's layout for every one, or with pf_anchors (interface termini,
    docs/guide/structures.md#interface-termini) each from its own measured anchor, its chain
    straight out by the rule chain_layout uses, clear of the core at its turn. Raises
    ParamError: an own anchor inside the core, or no direction that takes its chain clear."""
    if p.pf_anchors is None:
        return [p.chain_layout] * p.protofilaments
    outline = p.outline()
    offsets = np.asarray(chain_x(p)) - p.anchor_x  # along the chain from the anchor
    out = []
    for j, (local, turn) in enumerate(zip(p.pf_anchor_xy(), p.pf_offsets()[0])):
        xy = polygons.rotate(local, float(turn))
        if polygons.inside(outline, xy[None])[0]:
            raise ParamError("pf_anchors", f"protofilament {j}'s own anchor ({xy[0]:.2f}, "
                                           f"{xy[1]:.2f}) Å lies inside the core; the linker "
                                           f"must start outside it")
        try:
            direction, rule = polygons.linker_direction(outline, local, offsets,
                                                        chain_radii(p), [float(turn)])
        except polygons.GeometryError as exc:
            raise ParamError("pf_anchors", f"protofilament {j}'s own anchor at ({xy[0]:.2f}, "
                                           f"{xy[1]:.2f}) Å: {exc}") from None
        if rule == "radial":
            radius = offsets + math.hypot(*local)
            angle = np.full(radius.size, math.atan2(local[1], local[0]))
            pts = np.stack([np.cos(angle) * radius, np.sin(angle) * radius], axis=1)
        else:
            pts = local[None] + offsets[:, None] * direction[None]
            radius, angle = np.hypot(pts[:, 0], pts[:, 1]), np.arctan2(pts[:, 1], pts[:, 0])
        out.append(ChainLayout(pts, radius, angle, direction, rule))
    return out
