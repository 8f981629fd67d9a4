"""The model's parameters: one definition of their defaults, units, ranges and validation.

Everything else (the CLI, the sidebar's PropertyGroup, sweeps, tests) reads this module.
1 Blender unit = 1 Å. Plain Python: importable without bpy.

Over 400 lines because the Params class is the one definition of every parameter: its field
list alone is some 200 lines, and the geometry every room derives from it (the chain's
members, radii, rest lengths and layout) sits beside the fields it reads. Around it, in their
own modules: the field specs and constants (param_spec.py), reading a typed value
(param_values.py), the refused combinations (param_checks.py), the domains (domains.py).
"""
from __future__ import annotations

import dataclasses
import functools
import json
import math
import pathlib
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..geom import polygons
from . import domains as chain_domains, helix
# The field specs' constants and the checks are read as P.<name> by the rest of the package
from .param_checks import NOT_WITH_PERIODIC, check_combination, check_twist, refuse_beside_periodic  # noqa: F401
from .param_spec import (ANGLE_UNITS, DERIVED_WORDS, DOMAIN_SHAPES, GLOBULE_RINGS,  # noqa: F401
                         GLOBULE_SEGMENTS, MAX_OBJECTS_UNFORCED, MAX_OUTLINE_POINTS,
                         MAX_SHAPE_ROWS, MAX_TWIST, MEMORY_PER_OBJECT_KIB, NUMBER_WORDS,
                         PROTOCOLS,
                         RESIDUE_RINGS, RESIDUE_SEGMENTS, SEALED, SHAPE_ROWS, SHOWN_IN, ParamError,
                         spec)
from .param_values import (angle_value, coerce, list_value, rows_value, split_unit,  # noqa: F401
                           vector_value)

@dataclass(frozen=True)
class Params:
    """One run of the model. Lengths in Å, angles in rad, time in Blender frames."""

    slab: tuple = spec((40.0, 22.0, 4.8), 0.1, 1000.0, "Å",
                        "Size of the cross-β core slab of one layer: width × depth × height",
                        section="Slab")
    residue_radius: float = spec(1.75, 0.1, 20.0, "Å",
                                  "Radius of one linker residue (and of the anchor residue)",
                                  section="Anchor")
    residue_spacing: float = spec(3.5, 0.1, 50.0, "Å",
                                   "Distance between consecutive linker residues at rest, "
                                   "3.5 Å for a stretched-out chain of 1.75 Å beads",
                                   section="Linker")
    linker: int = spec(6, 1, 200, "residues",
                        "Linker length in residues, counting the passive anchor",
                        kind=int, section="Linker", question=True)
    globule_diameter: float = spec(30.0, 0.5, 500.0, "Å",
                                    "Diameter of the tethered globular domain", section="Globule",
                                    question=True)
    layers: int = spec(20, 1, 100_000, "layers",
                        "Number of stacked β-strand layers in the fibril", kind=int,
                        section="Layers", question=True)
    rise: float = spec(4.8, 0.1, 100.0, "Å",
                        "Distance between β-strands along the fibril axis, 4.8 Å in cross-β amyloid",
                        section="Layers")
    twist: float = spec(0.034, -math.pi, math.pi, "rad",
                         "Helical twist between consecutive layers about the fibril axis "
                         "(positive: right-handed)",
                         section="Layers")
    gravity: float = spec(0.5, 0.0, 100.0, "Å/s²",
                           "Bound of the random gravity: each axis is drawn uniform in [-g, g]")
    seed: int = spec(0, 0, 2**31 - 1, "", "Random seed fixing the gravity", kind=int)
    time_scale: float = spec(2.0, 0.01, 100.0, "×", "Rigid-body world speed (tutorial: 2)")
    frames: int = spec(250, 1, 100_000, "frames",
                        "Frames to bake from frame 1 (the cap when settling is on)", kind=int)
    # Substeps and iterations: measured (docs/model/linker-integrity.md#linker-integrity), 10 × 10 is the cheapest
    # setting at which every linker that fits (6-32 residues) ends within 0.2 % of its length and
    # the push-apart is over by frame ~50; 20 × 20 doubles the cost and changes no verdict.
    substeps: int = spec(10, 1, 1000, "per frame",
                          "Physics substeps per frame: more keeps stiff chains from stretching",
                          kind=int)
    solver_iterations: int = spec(10, 1, 1000, "",
                                   "Constraint solver iterations per substep", kind=int)
    stretch_tolerance: float = spec(0.05, 0.0, 10.0, "fraction",
                                     "Largest bond stretch for which the linker counts as intact",
                                     section="Check", shown_in="%")
    # Settling: measured on 147 bakes (docs/model/settling.md#settling), stopping once every body moves less
    # than 0.3 Å/frame for 20 frames gave the 250-frame verdict every time and saved 21 % of the
    # bake time (40 % on the default model). Under the weak random gravity nothing reaches true
    # rest (< 0.01 Å/frame) within 250 frames.
    settle: bool = spec(True, None, None, "",
                         "Stop the bake once every body has settled (--frames is then the cap)",
                         kind=bool)
    settle_speed: float = spec(0.3, 0.0, 100.0, "Å/frame",
                                "A body has settled when it moves less than this per frame")
    settle_frames: int = spec(20, 1, 100_000, "frames",
                               "Frames every body must stay settled to stop the bake", kind=int)
    score_layers: int = spec(0, 0, 50_000, "layers",
                              "Score interior layers only: leave out this many layers at each end "
                              "of the fibril ('all' or 0 scores every layer)",
                              kind=int, section="Check")
    # ---- real fibril geometry (issue #14): protofilaments, core outline, anchor --------------
    protofilaments: int = spec(1, 1, 6, "chains per layer",
                                "Protofilaments: chains (anchor, linker, globule) per layer, "
                                "sharing the layer's core", kind=int, section="Layers")
    pf_rotation: float | None = spec(None, -2 * math.pi, 2 * math.pi, "rad",
                                      "Turn about the fibril axis from one protofilament to the "
                                      "next (a pseudo-2₁ fibril: about 3.13 rad, i.e. 179.3deg)",
                                      section="Layers", derived="2π/K", label="Protofilament turn")
    pf_rise: float = spec(0.0, -50.0, 50.0, "Å",
                           "Rise along the fibril axis from one protofilament to the next "
                           "(a pseudo-2₁ fibril: about 2.3 Å)", section="Layers",
                           label="Protofilament rise")
    core_outline: tuple | None = spec(None, -1000.0, 1000.0, "Å",
                                       "The core's cross-section: a closed polygon of [x, y] "
                                       "points in the layer's frame (axis at the origin), "
                                       "extruded by the rise; replaces the slab's box",
                                       kind="points", section="Slab",
                                       derived="the slab's X × Y box")
    anchor: tuple | None = spec(None, -1000.0, 1000.0, "Å",
                                 "Where protofilament 0's anchor sits in the layer's frame: X Y",
                                 section="Anchor", size=2,
                                 derived="(slab X / 2 + residue radius, 0)")
    # The buried terminus (docs/model/buried-terminus.md#model): the residues a chain spends
    # from its buried anchor to the core's surface, measured from --fibril with their path; the
    # model's chain (anchor, free linker, globule) then starts at the exit, `anchor`.
    exit_residues: int = spec(0, 0, SEALED, "residues",
                              "Residues of the linker spent from a buried anchor to the core's "
                              "surface (measured from --fibril; 0: the anchor is on the "
                              f"surface; {SEALED}: no clear path)", kind=int, section="Anchor",
                              ui=False, cli=False)
    exit_path: tuple | None = spec(None, -1000.0, 1000.0, "Å",
                                   "The exit's path from the buried anchor's CA to the surface, "
                                   "rows [x, y, z] in the layer's frame", kind="rows", size=3,
                                   ui=False, cli=False, section="Anchor",
                                   derived="none: the anchor on the surface")

    # Search protocol (docs/model/search.md#search). `tutorial`
    # starts every globule at full size on a straight chain and lets Bullet push them apart;
    # `inflate` starts the chains fanned out with small globules and grows them. It changes the
    # start layout, so it sits with the build's parameters.
    protocol: str = spec("tutorial", None, None, "",
                          "How the search starts: tutorial (straight chains, full-size globules "
                          "pushed apart) or inflate (fanned chains, globules grown from small)",
                          kind=str, choices=PROTOCOLS, section="Linker", question=True)
    # The inflate schedule, measured (docs/model/search.md#inflate-schedule): grow, hold at full size
    # with the gravity off, judge; a jammed layout is shrunk and grown again under a new gravity.
    grow_start: float = spec(0.3, 0.01, 1.0, "fraction",
                              "inflate: globule scale at the start (smaller if the fanned start "
                              "layout would overlap)", section="Search", label="Start scale")
    grow_frames: int = spec(100, 1, 100_000, "frames",
                             "inflate: frames over which the globules grow to full size",
                             kind=int, section="Search")
    hold_frames: int = spec(60, 1, 100_000, "frames",
                             "inflate: most frames at full size (gravity off) before a layout "
                             "is judged; it is judged earlier once every body has settled",
                             kind=int, section="Search")
    regrow_cycles: int = spec(4, 0, 1000, "cycles",
                               "inflate: times a jammed layout (clash or stretched linker) is "
                               "shrunk and grown again under a new random gravity",
                               kind=int, section="Search")
    regrow_scale: float = spec(0.6, 0.01, 1.0, "fraction",
                                "inflate: globule scale a jammed layout is shrunk to",
                                section="Search", label="Regrow scale")
    near_cycles: int = spec(5, 0, 1000, "cycles",
                             "inflate: more regrow cycles for a layout still nearly accommodated "
                             "after regrow_cycles (deepest overlap at most 1 Å, stretch at most 3 "
                             "times the tolerance); a clear miss gets none",
                             kind=int, section="Search")
    # A clear miss ends the run at its judgement: measured on 173 inflate runs baked to their end
    # (13 systems, fibrils with ends and cells), this rule stopped 85 and none of them went on to
    # fit; it saves 48 % of their frames (docs/benchmarks.md#stopping-rule-gallery)
    clear_miss_pairs: int = spec(8, 0, 1_000_000, "pairs",
                                  "inflate: a judgement that is not a near miss with at least this "
                                  "many clashing pairs ends the run as a miss (0 = never)",
                                  kind=int, section="Search")
    clear_miss_stretch: float = spec(10.0, 0.0, 1000.0, "times",
                                      "inflate: a judgement that is not a near miss with its worst "
                                      "linker bond stretched at least this many times the "
                                      "tolerance ends the run as a miss (0 = never)",
                                      section="Search")
    # Off by default: measured in a cell it rescued 1 of 3 near misses it was tried on and made
    # most polishes worse (docs/model/search.md#polish)
    polish_factor: int = spec(1, 1, 100, "times",
                               "inflate: a jammed layout that is nearly accommodated (deepest "
                               "overlap at most 1 Å, stretch at most 3 times the tolerance) is "
                               "held once more, gravity off, with this many times the substeps "
                               "and solver iterations before it is regrown (1 = off; 4 was "
                               "tried)",
                               kind=int, section="Search")

    periodic: int = spec(0, 0, 10_000, "layers",
                          "Simulate an infinite fibril as a screw-periodic cell of this many layers "
                          "('auto' picks it from the globule and the rise; 0 = off: a fibril of "
                          "--layers layers with two ends)",
                          kind=int, section="Layers", label="Cell layers", question=True)

    # Measured (docs/model/periodic-cell.md#periodic-cell): images one frame behind their originals make every
    # contact across the cell's ends bounce; refreshing them 5 times a frame removes that.
    image_updates: int = spec(5, 1, 1000, "per frame",
                               "With periodic: move the images to their originals this many times "
                               "per frame (each frame is baked as this many shorter frames, with "
                               "the same substep length; must divide substeps)", kind=int)

    # ---- several domains per chain (issue #24): anchor, linker, domain 1, its linker, domain 2 ...
    # Domain 1 is globule_diameter's; these give the domains after it, from the core outward
    # (docs/guide/atoms-and-domains.md#several-domains).
    domain_diameters: tuple | None = spec(None, 0.5, 500.0, "Å",
                                           "Diameters of the domains after the first on each "
                                           "chain (the first is globule_diameter), in chain "
                                           "order from the core outward, comma-separated",
                                           kind="list", item=float, section="Globule")
    domain_linker: tuple | None = spec(None, 0, 500, "residues",
                                        "Residues between consecutive domains of a chain, one "
                                        "per gap, comma-separated", kind="list", item=int,
                                        section="Globule")
    # ---- the domain's real shape (issue #24): docs/model/domain-shapes.md#domain-shapes ----
    domain_shape: str = spec("sphere", None, None, "",
                              "The globule's body: sphere (of globule_diameter, anywhere on its "
                              "surface joined), hull (the convex hull of the domain's atoms grown "
                              "by their van der Waals radius) or spheres (a few overlapping "
                              "spheres covering them); hull and spheres need --domain and join the "
                              "linker at the domain's terminal CA",
                              kind=str, choices=DOMAIN_SHAPES, section="Globule")
    domain_atoms: tuple | None = spec(None, -1000.0, 1000.0, "Å",
                                       "hull: the domain's outermost heavy atoms [x, y, z, r] in "
                                       "its body frame (geom.shape.hull_atoms)",
                                       kind="rows", size=4, ui=False, cli=False, section="Globule",
                                       derived="none: the sphere")
    domain_spheres: tuple | None = spec(None, -1000.0, 1000.0, "Å",
                                         "spheres: the covering spheres [x, y, z, r] in the "
                                         "domain's body frame (geom.shape.covering_spheres)",
                                         kind="rows", size=4, ui=False, cli=False,
                                         section="Globule", derived="none: the sphere")
    domain_joint: tuple | None = spec(None, -1000.0, 1000.0, "Å",
                                       "hull, spheres: the linker's joint in the domain's body "
                                       "frame, its terminal residue's CA: one row [x, y, z]",
                                       kind="rows", size=3, ui=False, cli=False,
                                       section="Globule", derived="on the sphere's surface")
    # Several real-shaped domains per chain (docs/guide/atoms-and-domains.md#shapes-of-several-domains):
    # the domains after the first, each in its own body frame, and where each domain but the
    # last lets its outgoing linker go (its other terminal CA).
    further_atoms: tuple | None = spec(None, -1000.0, 1000.0, "Å",
                                        "hull, several domains: the outermost heavy atoms of the "
                                        "domains after the first, rows [domain, x, y, z, r] "
                                        "(domain 1 is the second on the chain), each in its own "
                                        "body frame", kind="rows", size=5, ui=False, cli=False,
                                        section="Globule", derived="none: one domain")
    further_spheres: tuple | None = spec(None, -1000.0, 1000.0, "Å",
                                          "spheres, several domains: the covering spheres of the "
                                          "domains after the first, rows [domain, x, y, z, r], "
                                          "each in its own body frame", kind="rows", size=5,
                                          ui=False, cli=False, section="Globule",
                                          derived="none: one domain")
    further_joints: tuple | None = spec(None, -1000.0, 1000.0, "Å",
                                         "hull, spheres, several domains: the incoming linker's "
                                         "joint (terminal CA) of each domain after the first, "
                                         "one row [x, y, z] each, in its own body frame",
                                         kind="rows", size=3, ui=False, cli=False,
                                         section="Globule", derived="none: one domain")
    domain_exits: tuple | None = spec(None, -1000.0, 1000.0, "Å",
                                       "hull, spheres, several domains: the outgoing linker's "
                                       "joint (the other terminal CA) of each domain but the "
                                       "last, one row [x, y, z] each, in its own body frame",
                                       kind="rows", size=3, ui=False, cli=False,
                                       section="Globule", derived="none: one domain")

    # ---- derived geometry ---------------------------------------------------------------
    @property
    def globule_radius(self) -> float:
        return self.globule_diameter / 2.0

    @property
    def globule_offset(self) -> float:
        """From the last bond's pivot to the globule's centre: the sphere's radius, or with a real
        shape the joint's distance from the domain's centroid."""
        if self.domains[0].joint is None:
            return self.globule_radius
        return math.sqrt(sum(x * x for x in self.domain_joint[0]))

    @property
    def joint_lever(self) -> float:
        """From the last linker bead's centre to the globule's joint: its radius (the sphere's
        surface), or with a real shape one residue spacing (the joint is the domain's terminal
        CA, the next residue along the chain)."""
        return self.residue_spacing if self.shape.real else self.residue_radius

    @property
    def anchor_x(self) -> float:
        """Distance of the anchor's centre from the fibril axis (21.75 Å by default)."""
        if self.anchor is None:
            return self.slab[0] / 2.0 + self.residue_radius
        return math.hypot(*self.anchor)

    @property
    def anchor_xy(self) -> tuple[float, float]:
        """Protofilament 0's anchor in the layer's frame (default: (anchor_x, 0))."""
        return (self.anchor_x, 0.0) if self.anchor is None else tuple(self.anchor)

    @property
    def pf_angle(self) -> float:
        """The turn between protofilaments in rad: pf_rotation, or 2π/K by default."""
        return 2 * math.pi / self.protofilaments if self.pf_rotation is None else self.pf_rotation

    @property
    def chains(self) -> int:
        """Chains in the model: layers × protofilaments."""
        return self.layers * self.protofilaments

    def outline(self) -> np.ndarray:
        """The core's cross-section as a polygon (n, 2): core_outline, or the slab's box."""
        if self.core_outline is None:
            return polygons.box_outline(self.slab[0], self.slab[1])
        return np.array(self.core_outline, dtype=float)

    @functools.cached_property
    def chain_layout(self) -> "ChainLayout":
        """Protofilament 0's chain in the layer's frame (see ChainLayout). Raises ParamError."""
        return _chain_layout(self)

    @property
    def domain_radii(self) -> list[float]:
        """Radius of each domain of a chain, from the core outward (one: globule_radius)."""
        return [self.globule_radius] + [d / 2.0 for d in self.domain_diameters or ()]

    @property
    def shape(self) -> chain_domains.Shape:
        """The domains' shape (domain_shape's record in domains.SHAPES)."""
        return chain_domains.shape_of(self)

    @functools.cached_property
    def domains(self) -> list[chain_domains.Domain]:
        """The chain's domains, from the core outward (domains.domains; one: a list of one)."""
        return chain_domains.domains(self)

    @property
    def several_shapes(self) -> bool:
        """Several domains per chain, each with its real shape (hull, spheres)."""
        return chain_domains.several_shapes(self)

    def domain_rows(self, k: int) -> np.ndarray:
        """Domain k's (0 nearest the core) shape rows [x, y, z, r] in its body frame."""
        return chain_domains.domain_rows(self, k)

    def domain_joints(self) -> list:
        """Each domain's incoming joint (terminal CA) in its body frame, (3,) each."""
        rows = [self.domain_joint[0], *(self.further_joints or ())]
        return [np.asarray(r, dtype=float) for r in rows]

    @property
    def widest_diameter(self) -> float:
        """The largest domain's diameter (one domain: globule_diameter): what a periodic cell
        must exceed so that no globule meets its own image."""
        return max([self.globule_diameter, *(self.domain_diameters or ())])

    @property
    def free_linker(self) -> int:
        """The linker the model simulates: `linker` less the residues spent on a buried
        anchor's exit (exit_residues; 0 on the surface), counting the bead at the exit as
        its passive anchor (docs/model/buried-terminus.md#model). Below 1: no exit."""
        return self.linker - self.exit_residues

    def globule_members(self) -> list[int]:
        """The member index of each domain along a chain (one domain: [free_linker], the
        last)."""
        out = [self.free_linker]
        for gap in self.domain_linker or ():
            out.append(out[-1] + gap + 1)
        return out

    def chain_x(self) -> list[float]:
        """Distance of each chain member (anchor, residues, globules) from the axis, for a
        radial linker (the tutorial's); in general the anchor's distance plus the distance along
        the chain: consecutive residues `residue_spacing` apart, a globule touching its
        neighbours; a real-shaped domain (hull, spheres) joined at its terminal CA, one residue
        spacing from the last bead (joint_lever, globule_offset)."""
        radii, globules = self.chain_radii(), set(self.globule_members())
        first = min(globules)
        # several real shapes: into domain k at its joint, out of it at its exit, each one
        # residue spacing from the bead beside it (docs/guide/atoms-and-domains.md#shapes-of-several-domains)
        # (the first domain's joint is globule_offset's, below)
        into = {d.member: self.residue_spacing + float(np.linalg.norm(d.joint))
                for d in self.domains if d.joint is not None}
        out = {d.member: float(np.linalg.norm(d.exit)) + self.residue_spacing
               for d in self.domains if d.exit is not None}
        xs = [self.anchor_x]
        for i in range(len(radii) - 1):
            if i not in globules and i + 1 not in globules:
                step = self.residue_spacing
            elif i + 1 == first:  # the sphere's radius + the bead's, or the real joint
                step = self.joint_lever + self.globule_offset
            elif i + 1 in into:
                step = into[i + 1]
            elif i in out:
                step = out[i]
            else:
                step = radii[i] + radii[i + 1]
            xs.append(xs[-1] + step)
        return xs

    def chain_radii(self) -> list[float]:
        members = self.globule_members()
        radii = [self.residue_radius] * (members[-1] + 1)
        for i, r in zip(members, self.domain_radii):
            radii[i] = r
        return radii

    def rest_lengths(self) -> list[float]:
        """Rest length of each bond along the chain (`linker` bonds)."""
        xs = self.chain_x()
        return [b - a for a, b in zip(xs, xs[1:])]

    def bake_frames(self) -> int:
        """The bake's frame cap: `frames` for the tutorial, the whole schedule for inflate."""
        if self.protocol == "inflate":
            # each cycle: grow_frames + 1 frames from the start scale to full size inclusive,
            # then at most hold_frames, and at most hold_frames more when it is polished
            # (near_cycles more cycles for a near miss)
            holds = 2 if self.polish_factor > 1 else 1
            cycles = 1 + self.regrow_cycles + self.near_cycles
            return cycles * (self.grow_frames + 1 + holds * self.hold_frames)
        return self.frames

    def estimated_objects(self) -> int:
        """Objects a build makes: exact without an outline, at most this with one.

        Per layer a slab; per chain an anchor, (linker-1) residues, a globule and `linker`
        constraint empties. An outline's core adds its convex pieces per layer: the n - 2
        triangles of its n corners, fewer where they merge (builders/meshes.convex_pieces)."""
        pieces = 0 if self.core_outline is None else len(self.core_outline) - 2
        members = self.globule_members()[-1] + 1
        return self.layers * (1 + pieces + self.protofilaments * (2 * members - 1))

    # ---- conversion ---------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        d = {f.name: getattr(self, f.name) for f in fields()}
        d["slab"] = list(self.slab)
        for name in ("domain_diameters", "domain_linker"):
            if d[name] is not None:
                d[name] = list(d[name])
        if self.anchor is not None:
            d["anchor"] = list(self.anchor)
        if self.core_outline is not None:
            d["core_outline"] = [list(xy) for xy in self.core_outline]
        for name in (*SHAPE_ROWS, "exit_path"):
            if d[name] is not None:
                d[name] = [list(row) for row in d[name]]
        return d

    def replace(self, **changes) -> "Params":
        """A copy with `changes`, validated under the force this one was (a forced model's
        copies stay forced)."""
        return make_params(force=self.__dict__.get(VALIDATED) is True,
                           **{**self.to_dict(), **changes})


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


def _chain_layout(p: "Params") -> ChainLayout:
    outline = p.outline()
    anchor = np.array(p.anchor_xy, dtype=float)
    offsets = np.asarray(p.chain_x()) - p.anchor_x  # along the chain from the anchor
    copies = [j * p.pf_angle for j in range(p.protofilaments)]
    for j, a in enumerate(copies):
        xy = polygons.rotate(anchor, a)
        if polygons.inside(outline, xy[None])[0]:
            where = "" if j == 0 else (f" (protofilament {j}'s copy, turned by "
                                       f"{math.degrees(a):.1f}°, at ({xy[0]:.2f}, {xy[1]:.2f}))")
            raise ParamError("anchor", f"({anchor[0]:g}, {anchor[1]:g}) Å lies inside the core"
                                       f"{where}; the linker must start outside it: put the "
                                       f"anchor on or outside the core's outline")
    try:
        direction, rule = polygons.linker_direction(outline, anchor, offsets, p.chain_radii(),
                                                    copies)
    except polygons.GeometryError as exc:
        raise ParamError("anchor", f"at ({anchor[0]:g}, {anchor[1]:g}) Å: {exc}") from None
    if rule == "radial":
        radius = np.asarray(p.chain_x())
        angle = np.full(radius.size, math.atan2(anchor[1], anchor[0]))
        xy = np.stack([np.cos(angle) * radius, np.sin(angle) * radius], axis=1)
    else:
        xy = anchor[None] + offsets[:, None] * direction[None]
        radius, angle = np.hypot(xy[:, 0], xy[:, 1]), np.arctan2(xy[:, 1], xy[:, 0])
    return ChainLayout(xy, radius, angle, direction, rule)


def read_outline(path) -> tuple:
    """A core outline from a JSON file: a list of [x, y] in Å. Raises ParamError."""
    try:
        text = pathlib.Path(path).expanduser().read_text(encoding="utf-8")
        data = json.loads(text)
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise ParamError("core_outline", f"cannot read '{path}' as a JSON list of [x, y] points "
                                         f"({' '.join(str(reason).split())})") from None
    return _outline_value(data, f" in '{path}'")


def _outline_value(value, where: str = "") -> tuple:
    meta = field_spec("core_outline")
    try:
        points = polygons.clean_outline(value)
    except polygons.GeometryError as exc:
        raise ParamError("core_outline", f"the outline{where} {exc}") from None
    if len(points) > MAX_OUTLINE_POINTS:
        raise ParamError("core_outline", f"the outline{where} has {len(points)} points; at most "
                                         f"{MAX_OUTLINE_POINTS}")
    if np.abs(points).max() > meta["max"]:
        raise ParamError("core_outline", f"the outline{where} reaches {np.abs(points).max():g} Å "
                                         f"from the axis; coordinates must be from "
                                         f"{meta['min']:g} to {meta['max']:g} Å")
    return tuple((float(x), float(y)) for x, y in points)


def fields() -> tuple[dataclasses.Field, ...]:
    return dataclasses.fields(Params)


def field_spec(name: str) -> dict:
    return Params.__dataclass_fields__[name].metadata


def is_angle(name: str) -> bool:
    """Whether parameter `name` is an angle (in rad, also accepted with a unit: angle_value)."""
    f = Params.__dataclass_fields__.get(name)
    return f is not None and f.metadata["unit"] == "rad"


def make_params(*, force: bool = False, **values) -> Params:
    """Validate `values` (missing ones take their defaults) and return a Params.

    Raises ParamError, naming the parameter and its allowed range, for any bad value,
    an unknown name, or a combination the model cannot build.
    """
    known = {f.name for f in fields()}
    for name in values:
        if name not in known:
            shown = name if str(name).isidentifier() else repr(name)  # keep the message one line
            raise ParamError(shown, f"unknown parameter; known: {', '.join(sorted(known))}")
    clean = {}
    for f in fields():
        if f.name not in values:
            continue
        value, meta = values[f.name], f.metadata
        word = isinstance(value, str) and value.strip().lower() == NUMBER_WORDS.get(f.name)
        if word and f.name == "score_layers":
            value = 0
        if word and f.name == "periodic":
            continue  # resolved below, once the geometry it depends on is known
        if meta["derived"] and (value is None or (isinstance(value, str)
                                                  and value.strip().lower() in DERIVED_WORDS)):
            clean[f.name] = None
        elif meta["kind"] == "rows":
            clean[f.name] = None if value is None else rows_value(f.name, value, meta)
        elif meta["kind"] == "points":
            if isinstance(value, str) and value.strip().startswith("["):
                try:
                    value = json.loads(value)
                except ValueError:
                    raise ParamError(f.name, f"is not a JSON list of [x, y] points "
                                             f"(got {value[:40]!r})") from None
            clean[f.name] = (read_outline(value) if isinstance(value, (str, pathlib.Path))
                             else _outline_value(value))
        elif meta["kind"] == "list":
            clean[f.name] = list_value(f.name, value, meta)
        elif f.name == "slab" or meta["size"]:
            clean[f.name] = vector_value(f.name, value, meta, meta["size"] or 3)
        else:
            clean[f.name] = coerce(f.name, value, meta)
    if isinstance(values.get("periodic"), str) \
            and values["periodic"].strip().lower() == NUMBER_WORDS["periodic"]:
        clean["periodic"] = helix.auto_cell_layers(Params(**{**clean, "periodic": 1}))
    if clean.get("periodic"):
        clean["layers"] = clean["periodic"]  # the model is the cell: M layers
    p = Params(**clean)
    check_twist(values.get("twist", p.twist), p.twist, force)
    check_combination(p, force)
    object.__setattr__(p, VALIDATED, force)  # trusted from here on: see validate()
    return p


# make_params marks what it made with the `force` it checked under. A Params is validated once
# and trusted after: validate() returns a marked one as it is, unless it was checked with
# force and is now asked for without (force lifts the object-count limit). A Params built
# directly, or copied with dataclasses.replace, carries no mark and is checked in full.
VALIDATED = "validated_with_force"


def validate(p: Params, *, force: bool = False) -> Params:
    """An existing Params, validated: as it is if make_params made it (under a `force` at least as
    strict), else checked in full (e.g. one built directly)."""
    checked = p.__dict__.get(VALIDATED)
    if checked is False or (checked is True and force):
        return p
    return make_params(force=force, **p.to_dict())


DEFAULTS = make_params()  # validated, so a run of the defaults trusts it like any other
