"""The model's parameters: one definition of their defaults, units, ranges and validation.
Over 400 lines because the Params class is one declaration: every field's spec in one place.

Everything else (the CLI, the sidebar's PropertyGroup, sweeps, tests) reads this module.
1 Blender unit = 1 Å. Plain Python: importable without bpy. Around it, in their own modules:
the field specs and constants (param_spec.py), reading a typed value (param_values.py), the
refused combinations (param_checks.py), the domains (domains.py) and the chain they make with
the linker (chain.py).
"""
from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..geom import polygons
from . import chain, domains as chain_domains, helix, occupancy
from .param_checks import check_combination, check_twist
from .param_spec import (DOMAIN_SHAPES, MAX_COORDINATE, NUMBER_WORDS, PATTERN_COUNTS, PATTERNS,
                         PROTOCOLS, SEALED, ParamError, rows_spec, spec)
from .param_values import field_value, plain


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
                         "(positive: right-handed)", section="Layers")
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
    # Three or more protofilaments that are not one turn apart each (7QJX's four at 0, 179.5,
    # -118.1 and -13.5°): each one's own turn and rise from protofilament 0, as measured
    # (docs/guide/structures.md#protofilament-turns); none: j × the turn and rise above.
    pf_turns: tuple | None = rows_spec("Each protofilament's turn (rad) and rise (Å) from "
                                       "protofilament 0, measured from --fibril with three or "
                                       "more protofilaments: rows [turn, rise], protofilament 0's "
                                       "first", 2, "j × pf_rotation, j × pf_rise",
                                       section="Layers")
    core_outline: tuple | None = spec(None, -MAX_COORDINATE, MAX_COORDINATE, "Å",
                                       "The core's cross-section: a closed polygon of [x, y] "
                                       "points in the layer's frame (axis at the origin), "
                                       "extruded by the rise; replaces the slab's box",
                                       kind="points", section="Slab",
                                       derived="the slab's X × Y box")
    anchor: tuple | None = spec(None, -MAX_COORDINATE, MAX_COORDINATE, "Å",
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
    exit_path: tuple | None = rows_spec("The exit's path from the buried anchor's CA to the "
                                        "surface, rows [x, y, z] in the layer's frame", 3,
                                        "none: the anchor on the surface", section="Anchor")
    # Interface termini (docs/guide/structures.md#interface-termini): where protofilament 0's
    # chain turned onto protofilament j would start inside the core or on another's anchor,
    # each protofilament's own terminus as measured from --fibril: its anchor (where its own
    # way out, through every protofilament's atoms, leaves the outline) in the layer's frame
    # and the residues that way spends; none: protofilament 0's anchor and exit turned onto each.
    pf_anchors: tuple | None = rows_spec("Each protofilament's own anchor and exit, measured "
                                         "from --fibril: rows [x, y, exit residues] in the "
                                         "layer's frame, protofilament 0's first", 3,
                                         "protofilament 0's turned onto each", section="Anchor")
    pf_exit_paths: tuple | None = rows_spec("Each protofilament's own exit path from its "
                                            "anchor's CA to the surface: rows [protofilament, x, "
                                            "y, z] in the layer's frame", 4,
                                            "protofilament 0's turned onto each",
                                            section="Anchor")

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
                               "tried)", kind=int, section="Search")

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
    domain_atoms: tuple | None = rows_spec("hull: the domain's outermost heavy atoms [x, y, z, r] "
                                           "in its body frame (geom.shape.hull_atoms)", 4,
                                           "none: the sphere")
    domain_spheres: tuple | None = rows_spec("spheres: the covering spheres [x, y, z, r] in the "
                                             "domain's body frame (geom.shape.covering_spheres)",
                                             4, "none: the sphere")
    domain_joint: tuple | None = rows_spec("hull, spheres: the linker's joint in the domain's body "
                                           "frame, its terminal residue's CA: one row [x, y, z]",
                                           3, "on the sphere's surface")
    # Several real-shaped domains per chain (docs/guide/atoms-and-domains.md#shapes-of-several-domains):
    # the domains after the first, each in its own body frame, and where each domain but the
    # last lets its outgoing linker go (its other terminal CA).
    further_atoms: tuple | None = rows_spec("hull, several domains: the outermost heavy atoms of "
                                            "the domains after the first, rows [domain, x, y, z, "
                                            "r] (domain 1 is the second on the chain), each in its "
                                            "own body frame", 5, "none: one domain")
    further_spheres: tuple | None = rows_spec("spheres, several domains: the covering spheres of "
                                              "the domains after the first, rows [domain, x, y, z, "
                                              "r], each in its own body frame", 5,
                                              "none: one domain")
    further_joints: tuple | None = rows_spec("hull, spheres, several domains: the incoming "
                                             "linker's joint (terminal CA) of each domain after "
                                             "the first, one row [x, y, z] each, in its own body "
                                             "frame", 3, "none: one domain")
    domain_exits: tuple | None = rows_spec("hull, spheres, several domains: the outgoing linker's "
                                           "joint (the other terminal CA) of each domain but the "
                                           "last, one row [x, y, z] each, in its own body frame",
                                           3, "none: one domain")

    # ---- mixed fibrils (issue #44): which subunits carry the domain ----------------------
    # (docs/model/occupancy.md#occupancy; the pattern itself: model/occupancy.py)
    occupancy: float = spec(1.0, 1e-6, 1.0, "fraction",
                            "random: the fraction of subunits that carry the domain, an exact "
                            "count round(f·N) of the fibril's (or the cell's) N subunits, drawn "
                            "with the seed", section="Globule", shown_in="%")
    pattern: str = spec("random", None, None, "",
                        "Which subunits carry the domain: random (a seeded draw of occupancy's "
                        "count), periodic (every pattern_period-th subunit) or layers (the "
                        "per-layer pattern pattern_layers, repeated along the fibril)",
                        kind=str, choices=PATTERNS, section="Globule")
    pattern_period: int = spec(1, 1, 10_000, "subunits",
                               "periodic: every k-th subunit carries the domain, from the first",
                               kind=int, section="Globule")
    pattern_across: str = spec("protofilament", None, None, "",
                               "periodic: count subunits along each protofilament (every k-th "
                               "layer of each) or over the fibril (layer-major: a layer's "
                               "protofilaments, then the next layer's)", kind=str,
                               choices=PATTERN_COUNTS, section="Globule", label="Period counts")
    pattern_layers: str = spec("A", None, None, "",
                               "layers: one letter per layer, repeated along the fibril: A "
                               "carries the domain, B the second domain (domain_b_diameter), "
                               "'.' none (e.g. 'A.' every other layer, 'AB' a hetero-amyloid)",
                               kind=str, section="Globule")
    # A hetero-amyloid's second domain (issue #44 item 1): the letter B of pattern_layers
    # (docs/model/occupancy.md#hetero), a sphere on its own linker; A keeps the fields above.
    domain_b_diameter: float | None = spec(None, 0.5, 500.0, "Å",
                                           "layers: diameter of the second domain, a sphere, on "
                                           "the layers lettered B in pattern_layers",
                                           section="Globule", derived="no B domain",
                                           label="Domain B diameter")
    linker_b: int | None = spec(None, 1, 200, "residues",
                                "layers: linker length of the B layers' chains in residues, "
                                "counting the passive anchor (only linker's own length is "
                                "built yet)", kind=int, section="Globule",
                                derived="the same as linker", label="Linker B")
    bare_tail: int = spec(0, 0, 200, "residues",
                          "Undecorated subunits' own disordered tail, a bead chain of this many "
                          "residues from the anchor (0: no tail, nothing is built)", kind=int,
                          section="Globule")

    # ---- derived geometry ---------------------------------------------------------------
    @property
    def globule_radius(self) -> float:
        return self.globule_diameter / 2.0

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

    def pf_offsets(self) -> tuple[np.ndarray, np.ndarray]:
        """Each protofilament's turn (rad) and rise (Å) from protofilament 0 (arrays of K):
        pf_turns as measured, or j × pf_angle and j × pf_rise."""
        if self.pf_turns is None:
            j = np.arange(self.protofilaments, dtype=float)
            return j * self.pf_angle, j * self.pf_rise
        rows = np.asarray(self.pf_turns, dtype=float)
        return rows[:, 0], rows[:, 1]

    @property
    def pf_rise_step(self) -> float:
        """|pf_rise|, or with pf_turns the largest |rise| of any protofilament: (K - 1) times
        it bounds how far a layer's chains spread along the axis."""
        if self.pf_turns is None:
            return abs(self.pf_rise)
        return float(np.abs(self.pf_offsets()[1]).max())

    def pf_exit_residues(self) -> np.ndarray:
        """The residues each protofilament's exit spends (K ints): pf_anchors' own, or
        exit_residues for every protofilament (its copies)."""
        if self.pf_anchors is None:
            return np.full(self.protofilaments, int(self.exit_residues))
        return np.asarray(self.pf_anchors, dtype=float)[:, 2].round().astype(int)

    @property
    def exit_spent(self) -> int:
        """The most residues any protofilament's exit spends: the model's chains all start
        their free linker after this many (the smallest free linker governs the simulation;
        docs/model/bound.md#interface-termini); exit_residues without pf_anchors."""
        if self.pf_anchors is None:
            return int(self.exit_residues)
        return int(max(int(self.exit_residues), self.pf_exit_residues().max()))

    def pf_anchor_xy(self) -> np.ndarray:
        """Each protofilament's anchor in its own frame (K, 2), before its turn
        (pf_offsets): pf_anchors' own turned back by the protofilament's turn, or
        protofilament 0's anchor for every one."""
        if self.pf_anchors is None:
            return np.tile(np.asarray(self.anchor_xy, dtype=float), (self.protofilaments, 1))
        rows = np.asarray(self.pf_anchors, dtype=float)[:, :2]
        return np.array([polygons.rotate(xy, -a) for xy, a in zip(rows, self.pf_offsets()[0])])

    @functools.cached_property
    def pf_layouts(self) -> list[chain.ChainLayout]:
        """Each protofilament's chain in its own frame (chain.pf_layouts): protofilament 0's
        layout for every one without pf_anchors. Raises ParamError."""
        return chain.pf_layouts(self)

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
    def chain_layout(self) -> chain.ChainLayout:
        """Protofilament 0's chain in the layer's frame (chain.chain_layout), kept: the checks,
        the start layouts and the builders each ask for it. Raises ParamError."""
        return chain.chain_layout(self)

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

    @property
    def widest_diameter(self) -> float:
        """The largest domain's diameter (one domain: globule_diameter): what a periodic cell
        must exceed so that no globule meets its own image (a hetero-amyloid: B's too)."""
        return max([self.globule_diameter, *(self.domain_diameters or ()),
                    *((self.domain_b_diameter,) if occupancy.is_hetero(self) else ())])

    @property
    def free_linker(self) -> int:
        """The linker the model simulates: `linker` less the residues spent on a buried
        anchor's exit (exit_spent: exit_residues, or the most any protofilament's own exit
        spends; 0 on the surface), counting the bead at the exit as its passive anchor
        (docs/model/buried-terminus.md#model). Below 1: no exit."""
        return self.linker - self.exit_spent

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

    # ---- conversion ---------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """Every parameter by name, its tuples as lists (as JSON and case files hold them)."""
        return {f.name: plain(getattr(self, f.name)) for f in fields()}

    def replace(self, **changes) -> "Params":
        """A copy with `changes`, validated under the force this one was (a forced model's
        copies stay forced)."""
        return make_params(force=self.__dict__.get(VALIDATED) is True,
                           **{**self.to_dict(), **changes})


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
    auto = isinstance(values.get("periodic"), str) \
        and values["periodic"].strip().lower() == NUMBER_WORDS["periodic"]
    clean = {f.name: field_value(f.name, values[f.name], f.metadata) for f in fields()
             if f.name in values and not (auto and f.name == "periodic")}
    if auto:  # resolved here, once the geometry it depends on is known
        cell = Params(**{**clean, "periodic": 1})
        clean["periodic"] = helix.auto_cell_layers(cell)
        # also a whole number of the pattern's repeats (and of inflate's lattice periods, which
        # auto_cell_layers' cell already holds): the least common multiple
        repeat = occupancy.repeat_layers(cell)
        if repeat and clean["periodic"] % repeat:
            step = math.lcm(repeat, occupancy.lattice_period(cell))
            clean["periodic"] = -(-clean["periodic"] // step) * step
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
