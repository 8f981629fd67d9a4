"""The combinations of parameters the model refuses, each in one line naming the parameter to
change (make_params calls check_twist and check_combination once the values are read).
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from . import chain, domains, helix, hetero, occupancy
from .bent_layout import chain_clearance, domain_terminals, real_chain_layout
from .param_spec import MAX_OBJECTS_UNFORCED, MAX_TWIST, MEMORY_PER_OBJECT_KIB, ParamError
from .param_values import split_unit
from .start_layout import rest_positions


def check_twist(raw: Any, twist: float, force: bool) -> None:
    """Refuse a twist beyond ±MAX_TWIST rad per layer unless forced, with its degree reading:
    the commonest slip is a twist in degrees typed as radians (issue #23)."""
    if force or abs(twist) <= MAX_TWIST:
        return
    typed = str(raw).strip() if isinstance(raw, str) else f"{twist:g}"
    if isinstance(raw, str) and split_unit(raw)[1] is not None:
        reading = f"{typed} is {twist:.4g} rad ({math.degrees(twist):.1f}°) per layer"
        hint = "check the value"
    else:
        reading = f"{typed} rad is {math.degrees(twist):.1f}° per layer"
        hint = f"write {typed}deg if you meant degrees"
    raise ParamError("twist", f"{reading}, beyond ±{MAX_TWIST:g} rad (±"
                              f"{math.degrees(MAX_TWIST):.1f}°; measured amyloid fibrils twist "
                              f"0-8° per layer): {hint}, or add --force to build it anyway")

def check_combination(p, force: bool) -> None:
    if p.residue_spacing < p.residue_radius:
        raise ParamError("residue_spacing", f"must be at least the residue radius "
                                            f"({p.residue_radius:g} Å) so that beads cannot pass "
                                            f"through each other (got {p.residue_spacing:g})")
    _check_pf_turns(p)
    _check_pf_anchors(p)
    if p.periodic:
        _check_periodic(p)
    domains.check_shapes(p)
    occupancy.check_pattern(p)
    if 2 * p.score_layers >= p.layers:
        raise ParamError("score_layers", f"must leave at least one layer: from 0 to "
                                         f"{(p.layers - 1) // 2} for {p.layers} layers "
                                         f"(got {p.score_layers})")
    if p.free_linker < 1:  # no exit: a verdict, settled without a model (model/terminus.py)
        return
    _check_domains(p)
    p.chain_layout  # the anchor outside the core, the chain clear of it (raises ParamError)
    if occupancy.is_hetero(p):  # the B chains' too, laid out with B's size before any build
        try:
            hetero.b_params(p).chain_layout
        except ParamError as exc:
            raise ParamError("domain_b_diameter", f"the B chains ({p.domain_b_diameter:g} Å): "
                                                  f"{exc}") from None
    check_anchors_apart(p)
    n = estimated_objects(p)
    if n > MAX_OBJECTS_UNFORCED and not force:
        most = MAX_OBJECTS_UNFORCED // (1 + p.protofilaments * (2 * chain.chain_members(p) - 1))
        chains = f" × {p.protofilaments} protofilaments" if p.protofilaments > 1 else ""
        raise ParamError("layers", f"{p.layers} layers{chains} × linker {p.linker} would make "
                                   f"{'up to ' if p.core_outline is not None else ''}{n} objects "
                                   f"(~{n * MEMORY_PER_OBJECT_KIB / 1024:.0f} MiB); at most {most} layers without "
                                   f"--force")
    check_real_start(p)


def estimated_objects(p) -> int:
    """Objects a build makes: exact without an outline, at most this with one.

    Per layer a slab; per decorated chain an anchor, (linker-1) residues, a globule and `linker`
    constraint empties; per undecorated subunit its bare tail's beads and bonds. An outline's
    core adds its convex pieces per layer: the n - 2 triangles of its n corners, fewer where
    they merge (builders/meshes.convex_pieces)."""
    pieces = 0 if p.core_outline is None else len(p.core_outline) - 2
    if p.pattern == "random" and p.occupancy == 1.0:  # every subunit decorated (as before #44)
        return p.layers * (1 + pieces + p.protofilaments * (2 * chain.chain_members(p) - 1))
    decorated = int(occupancy.decorated(p).sum())  # a mixed fibril: the bare tails' beads
    tail = chain.tail_members(p)
    return (p.layers * (1 + pieces) + decorated * (2 * chain.chain_members(p) - 1)
            + (p.chains - decorated) * max(0, 2 * tail - 1))


def check_real_start(p) -> None:
    """Several real-shaped domains at full size from frame 1 (the tutorial protocol): refuse,
    before anything is built, a chain that no turn of its domains lays out clear of itself
    (bent_layout.real_chain_layout): the covering spheres bulge past the atoms by up to 6.4 Å
    (docs/model/domain-shapes.md#spheres), and one residue between two domains cannot hold
    them apart. Under inflate the domains start small (growth.start_scale). Decided from the
    parameters alone, with the other checks, so a refused model is refused before any build."""
    if not p.several_shapes or p.protocol != "tutorial":
        return
    pos, _, rot = real_chain_layout(p, rest_positions(p)[:1])
    gap = float(chain_clearance(p, pos, rot, domain_terminals(p))[0])
    if gap <= 0:
        raise ParamError("domain_linker", f"{', '.join(map(str, p.domain_linker))} residue(s) "
                                            f"between the domains cannot start the chain clear "
                                            f"of itself with {p.shape.name} ({-gap:.1f} Å "
                                            f"into each other at the best of its turns): give "
                                            f"more residues, or --protocol inflate (the "
                                            f"domains start small)")


def _check_domains(p) -> None:
    """Several domains per chain: one linker per gap. They run under every protocol and in a
    periodic cell: inflate grows each globule to its own size, a cell images every member
    (docs/guide/atoms-and-domains.md#several-domains)."""
    more, gaps = len(p.domain_diameters or ()), len(p.domain_linker or ())
    if gaps != more:
        raise ParamError("domain_linker", f"needs one value per gap between consecutive "
                                          f"domains: {more + 1} domain(s) per chain have {more} "
                                          f"gap(s), got {gaps} value(s)")

def _check_pf_turns(p) -> None:
    """pf_turns: one row per protofilament, protofilament 0's at no turn and no rise."""
    if p.pf_turns is None:
        return
    if len(p.pf_turns) != p.protofilaments or any(abs(v) > 1e-9 for v in p.pf_turns[0]):
        raise ParamError("pf_turns", f"needs one row [turn, rise] per protofilament "
                                     f"({p.protofilaments}), the first [0, 0] (got "
                                     f"{len(p.pf_turns)} rows, the first {list(p.pf_turns[0])})")
    if any(abs(a) > 2 * math.pi for a, _ in p.pf_turns):
        raise ParamError("pf_turns", "every turn must lie within ±2π rad")


def _check_pf_anchors(p) -> None:
    """pf_anchors (interface termini): one row [x, y, residues] per protofilament, protofilament
    0's the anchor and exit_residues; pf_exit_paths' rows name a protofilament."""
    if p.pf_anchors is None:
        if p.pf_exit_paths is not None:
            raise ParamError("pf_exit_paths", "needs pf_anchors (each protofilament's own "
                                              "anchor and exit)")
        return
    rows = np.asarray(p.pf_anchors, dtype=float)
    if len(rows) != p.protofilaments:
        raise ParamError("pf_anchors", f"needs one row [x, y, exit residues] per protofilament "
                                       f"({p.protofilaments}), got {len(rows)}")
    if (np.abs(rows[0, :2] - np.asarray(p.anchor_xy)).max() > 1e-6
            or round(rows[0, 2]) != p.exit_residues):
        raise ParamError("pf_anchors", f"the first row is protofilament 0's: the anchor "
                                       f"{list(p.anchor_xy)} and its exit_residues "
                                       f"{p.exit_residues} (got {list(rows[0])}); an anchor "
                                       f"given takes the measured rows away")
    if (rows[:, 2] < 0).any() or (rows[:, 2] != rows[:, 2].round()).any():
        raise ParamError("pf_anchors", "exit residues must be whole numbers, 0 or more")
    if p.pf_exit_paths is not None:
        js = np.asarray(p.pf_exit_paths, dtype=float)[:, 0]
        if ((js < 0) | (js >= p.protofilaments) | (js != js.round())).any():
            raise ParamError("pf_exit_paths", f"each row starts with its protofilament, 0 to "
                                              f"{p.protofilaments - 1}")


def _check_periodic(p) -> None:
    if p.score_layers:
        raise ParamError("score_layers", "cannot be used with periodic: a periodic cell has no "
                                         "ends, every layer is interior")
    if p.substeps % p.image_updates:
        raise ParamError("image_updates", f"must divide substeps ({p.substeps}), so that a "
                                          f"frame's substeps split evenly between image updates "
                                          f"(got {p.image_updates})")
    least = helix.min_cell_layers(p)
    if p.periodic < least:
        raise ParamError("periodic", f"a cell of {p.periodic} layers is too short for "
                                     f"{p.widest_diameter:g} Å globules at a rise of {p.rise:g} Å: "
                                     f"at least {least} layers (cell × rise must exceed the "
                                     f"widest globule's diameter), or 'auto'")

class AnchorsTogether(ParamError):
    """Protofilaments a and b would start with their anchors on top of each other: a structure
    file's caller can say what the file's own protofilaments measure (structure/termini.py)."""

    def __init__(self, a: int, b: int, apart: float, message: str):
        super().__init__("pf_rotation", message)
        self.protofilaments, self.apart = (a, b), apart


def check_anchors_apart(p) -> None:
    """Anchors of different protofilaments must not start on top of each other (in 3-D,
    over the first few layers: the model repeats layer by layer)."""
    if p.protofilaments < 2:
        return
    k_max = min(p.layers - 1, int(math.ceil((p.protofilaments * p.pf_rise_step
                                             + 2 * p.residue_radius) / p.rise)) + 1)
    q = dataclasses.replace(p, layers=k_max + 1)
    angle, height = helix.chain_transforms(q)
    _, pf = helix.chain_layers(q)
    first = np.array([[lay.angle[0], lay.radius[0]] for lay in q.pf_layouts])[pf]
    xy = (np.stack([np.cos(angle + first[:, 0]), np.sin(angle + first[:, 0])], 1)
          * first[:, 1:])
    pts = np.column_stack([xy, height])
    d = np.linalg.norm(pts[:, None] - pts[None], axis=-1)
    clash = (d < 2 * p.residue_radius - 1e-9) & (pf[:, None] != pf[None, :])
    if clash.any():
        a, b = np.argwhere(clash)[0]
        raise AnchorsTogether(int(pf[a]), int(pf[b]), float(d[a, b]),
                              f"protofilaments {pf[a]} and {pf[b]} would start with "
                              f"their anchors {d[a, b]:.2f} Å apart, less than two "
                              f"residue radii ({2 * p.residue_radius:g} Å): change "
                              f"--pf-rotation, --pf-rise or --anchor")


# Options that make no sense beside a periodic cell, and why (one line each, for the CLI and sweeps).
NOT_WITH_PERIODIC = {
    "layers": "cannot be given with periodic: the model is then a cell of M = periodic layers of "
              "an infinite fibril, which has no length to set",
    "score_layers": "cannot be given with periodic: a periodic cell has no ends, so every layer "
                    "is interior and scored",
}


def refuse_beside_periodic(given: dict) -> None:
    """Raise ParamError when `given` (the options a user set: name -> value or list of values)
    turns periodic on and also sets an option that a periodic cell replaces."""
    values = given.get("periodic")
    values = values if isinstance(values, (list, tuple)) else [values]
    if not any(v is not None and str(v).strip() not in ("0", "0.0", "") for v in values):
        return
    for name, why in NOT_WITH_PERIODIC.items():
        if given.get(name) is not None:
            raise ParamError(name, why)
