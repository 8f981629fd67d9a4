"""From measurements to model parameters: a pure function over the measured objects."""
from __future__ import annotations

import numpy as np

from ..geom import exit_path, polygons
from ..model import params as P
from .domain import DomainSize
from .fibril import FibrilGeometry

RESIDUE_RADIUS = P.DEFAULTS.residue_radius  # Å, 1.75: the model's anchor bead, said in params

# The model parameters a structure fills (params.py names); an explicit option beside it wins.
FIBRIL_PARAMS = ("rise", "twist", "protofilaments", "pf_rotation", "pf_rise", "pf_turns",
                 "core_outline", "anchor", "exit_residues", "exit_path", "linker")
EXIT_PARAMS = ("exit_residues", "exit_path")  # measured with the anchor: they follow it
# each protofilament's measured turn goes with the protofilaments it describes
PF_PARAMS = ("protofilaments", "pf_rotation", "pf_rise")
DOMAIN_PARAMS = ("globule_diameter", "domain_diameters", "domain_linker", "domain_atoms",
                 "domain_spheres", "domain_joint", "further_atoms", "further_spheres",
                 "further_joints", "domain_exits")


def anchor_outside(outline, ca, residue_radius: float = RESIDUE_RADIUS) -> list:
    """The anchor bead's centre: on the outward normal of the outline point nearest the anchor
    CA, one bead radius out, so that the bead touches the core from outside (as the tutorial's
    anchor touches the slab). The CA itself lies inside the outline (it is core)."""
    poly = np.asarray(outline, float)
    ca = np.asarray(ca, float)
    point, normal = polygons.nearest_on_boundary(poly, ca)
    out = point - ca
    direction = out / np.linalg.norm(out) if np.linalg.norm(out) > 1e-6 else normal
    if direction @ normal < 0:  # the CA outside already (not core): out along the normal
        direction = normal
    xy = point + residue_radius * direction
    for _ in range(100):  # a concave corner: step out until clear of the outline
        if not polygons.even_odd(poly, xy)[0]:
            break
        xy = xy + 0.25 * direction
    return [round(float(xy[0]), 3), round(float(xy[1]), 3)]


def exit_values(fibril: FibrilGeometry, residue_radius: float = RESIDUE_RADIUS,
                residue_spacing: float = P.DEFAULTS.residue_spacing) -> dict:
    """A buried anchor's exit as model values (docs/model/buried-terminus.md#model): the
    residues its path costs at the model's spacing, the path, and the model's anchor one bead
    outside the outline where the path leaves it; {} for an anchor on the surface (its path
    costs nothing: the anchor as anchor_outside puts it), exit_residues SEALED when no path
    was found."""
    way = fibril.exit or {}
    if not way:
        return {}
    if not way["found"]:
        return {"exit_residues": P.SEALED}
    spent = exit_path.residues_spent(way["length"], residue_spacing)
    if spent == 0:
        return {}
    end = way["path"][-1]
    return {"exit_residues": spent, "exit_path": [list(p) for p in way["path"]],
            "anchor": clear_of(fibril.core_outline,
                               anchor_outside(fibril.core_outline, end[:2], residue_radius),
                               residue_radius)}


def clear_of(outline, xy, radius: float) -> list:
    """`xy` moved straight away from the outline's nearest point until a bead of `radius` there
    touches no edge: an exit's end lies in a groove (5OQV's), where the bead anchor_outside puts
    one radius off the nearest edge can overlap the next one (by 0.33 Å there)."""
    poly = np.asarray(outline, float)
    xy = np.asarray(xy, float)
    for _ in range(100):
        dist, _ = polygons.edge_distance(poly, xy[None])
        if dist[0] >= radius - 1e-3 and not polygons.even_odd(poly, xy)[0]:
            break
        point, _ = polygons.nearest_on_boundary(poly, xy)
        away = xy - point
        xy = xy + 0.05 * away / np.linalg.norm(away)
    return [round(float(xy[0]), 3), round(float(xy[1]), 3)]


def model_values(fibril: FibrilGeometry | None = None, domain: DomainSize | None = None, *,
                 residue_radius: float = RESIDUE_RADIUS, more_domains=(),
                 shape: str = "sphere",
                 residue_spacing: float = P.DEFAULTS.residue_spacing) -> dict:
    """Parameter name -> value for the model, in its units (Å, rad).

    The layer frame is the fibril's: Z = the helical axis through the origin, layer 0 of the model
    = the structure's reference layer, X along the long axis of its section. `anchor` is the bead
    touching the outline nearest protofilament 0's anchor CA (anchor_outside), or for a buried
    anchor where its exit leaves the outline (exit_values); `linker` (anchor +
    tail) only when the file models residues beyond the anchor (e.g. 2N0A's 98-140), since they
    are linker too. A `shape` other than the sphere also takes the domain's real shape and
    joint (docs/model/domain-shapes.md#domain-shapes); the sphere's model keeps its values.
    """
    values = {}
    if fibril is not None:
        values.update(rise=fibril.rise, twist=fibril.twist,
                      protofilaments=fibril.protofilaments,
                      pf_rotation=fibril.pf_rotation, pf_rise=fibril.pf_rise,
                      core_outline=[list(p) for p in fibril.core_outline],
                      anchor=anchor_outside(fibril.core_outline, fibril.anchors[0]["position"],
                                            residue_radius))
        if fibril.protofilaments >= 3:  # each at its own turn (docs/guide/structures.md#protofilament-turns)
            values["pf_turns"] = [list(o) for o in fibril.pf_offsets]
        values.update(exit_values(fibril, residue_radius, residue_spacing))
        tail = fibril.tail_residues
        if tail:
            values["linker"] = 1 + tail[1] - tail[0] + 1
    if domain is not None:
        values["globule_diameter"] = domain.globule_diameter
        if shape != "sphere" and domain.geometry:
            values.update({k: v for k, v in domain.geometry.items() if k != "exit"})
    numbered = linker_from_numbering(fibril, domain)
    if numbered is not None:  # covers a modelled tail too: the residues between, all of them
        values["linker"] = numbered[0]
    if more_domains:  # several domains per chain, in chain order from the core outward
        values["domain_diameters"] = [d.globule_diameter for d in more_domains]
        gaps = domain_gaps([domain, *more_domains],
                           "N" if fibril is not None and fibril.terminus == "N" else "C")
        if gaps is not None:
            values["domain_linker"] = gaps
        if shape != "sphere" and domain is not None:
            values.update(further_shapes([domain, *more_domains]))
    return values


def further_shapes(domains: list) -> dict:
    """The real shapes of several domains (chain order from the core outward) as the model's
    parameters: the domains after the first, each row led by its domain's index, their joints,
    and the exit of every domain but the last
    (docs/guide/atoms-and-domains.md#shapes-of-several-domains)."""
    more = list(enumerate(domains))[1:]
    out = {"further_atoms": [[k, *row] for k, d in more for row in d.geometry["domain_atoms"]],
           "further_spheres": [[k, *row] for k, d in more
                               for row in d.geometry["domain_spheres"]],
           "further_joints": [d.geometry["domain_joint"] for _, d in more]}
    exits = [d.geometry.get("exit") for d in domains[:-1]]
    if all(e is not None for e in exits):
        out["domain_exits"] = exits
    return out


def domain_gaps(domains: list, side: str = "C"):
    """Residues between consecutive domains (chain order from the core outward) from their
    numbering, or None when the numbering does not run that way (then --domain-linker is
    needed)."""
    gaps = []
    for near, far in zip(domains, domains[1:]):
        gap = (far.residues[0] - near.residues[1] - 1 if side == "C" else
               near.residues[0] - far.residues[1] - 1)
        if gap < 0:
            return None
        gaps.append(int(gap))
    return gaps


def linker_from_numbering(fibril: FibrilGeometry | None, domain: DomainSize | None):
    """(linker, why) when the two files share the protein's numbering, else None.

    The linker is every residue between the core's anchor and the domain's first modelled
    residue (its last when the linker leaves the core's N side), plus the anchor itself, which
    the model's `linker` counts: 6CU7's K97 and a domain starting at 128 give 30 residues
    between, linker 31 (docs/guide/atoms-and-domains.md#linker-from-numbering). The files share
    the numbering when the domain lies wholly beyond the anchor on the linker's side, and beyond
    any tail the fibril file models there."""
    why = numbering_note(fibril, domain)
    if why is None or not why[0]:
        return None
    return why[1], why[2]


def numbering_note(fibril, domain):
    """(usable, linker, text) of linker_from_numbering, or None without both files; `text`
    says where the linker came from, or why the numbering was not used."""
    if fibril is None or domain is None:
        return None
    anchor = fibril.anchors[0]
    res, name = int(anchor["residue"]), anchor["residue_name"]
    first, last = (int(v) for v in domain.residues)
    tail = fibril.tail_residues
    if fibril.terminus == "N":
        between, beyond = res - last - 1, last < res and (not tail or last < tail[0])
        end = f"last residue {last}"
    else:
        between, beyond = first - res - 1, first > res and (not tail or first > tail[1])
        end = f"first residue {first}"
    where = f"{name}{res} ({fibril.file}) and the domain's {end} ({domain.file})"
    if not beyond:
        return (False, None, f"not from numbering: the domain's residues {first}-{last} do not "
                             f"follow the anchor {name}{res}"
                             + (f" and the modelled tail {tail[0]}-{tail[1]}" if tail else "")
                             + " (another numbering?)")
    return (True, between + 1, f"numbering: {between} residues between {where}; "
                               f"linker {between + 1} with the anchor")


def linker_source(fibril, domain, *, explicit: bool) -> str:
    """Where the run's linker came from, in words (the result's `sources` entry)."""
    note = numbering_note(fibril, domain)
    if explicit:
        return "the --linker option" + (f" (the numbering gives {note[1]}: {note[2]})"
                                        if note and note[0] else "")
    if note is not None and note[0]:
        return note[2]
    tail = fibril.tail_residues if fibril is not None else []
    if tail:
        return (f"the fibril file's modelled tail {tail[0]}-{tail[1]} beyond the anchor: "
                f"linker {tail[1] - tail[0] + 2} with the anchor"
                + (f"; {note[2]}" if note else ""))
    return "the default" + (f"; {note[2]}" if note else "")
