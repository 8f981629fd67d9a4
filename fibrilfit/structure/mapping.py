"""From measurements to model parameters: a pure function over the measured objects."""
from __future__ import annotations

import numpy as np

from ..geom import polygons
from .domain import DomainSize
from .fibril import FibrilGeometry

RESIDUE_RADIUS = 1.75  # Å: the model's anchor bead (params.residue_radius's default)

# The model parameters a structure fills (params.py names); an explicit option beside it wins.
FIBRIL_PARAMS = ("rise", "twist", "protofilaments", "pf_rotation", "pf_rise", "core_outline",
                 "anchor", "linker")
DOMAIN_PARAMS = ("globule_diameter", "domain_atoms", "domain_spheres", "domain_joint")


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


def model_values(fibril: FibrilGeometry | None = None, domain: DomainSize | None = None, *,
                 residue_radius: float = RESIDUE_RADIUS, shape: str = "sphere") -> dict:
    """Parameter name -> value for the model, in its units (Å, rad).

    The layer frame is the fibril's: Z = the helical axis through the origin, layer 0 of the model
    = the structure's reference layer, X along the long axis of its section. `anchor` is the bead
    touching the outline nearest protofilament 0's anchor CA (anchor_outside); `linker` (anchor +
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
        tail = fibril.tail_residues
        if tail:
            values["linker"] = 1 + tail[1] - tail[0] + 1
    if domain is not None:
        values["globule_diameter"] = domain.globule_diameter
        if shape != "sphere" and domain.geometry:
            values.update(domain.geometry)
    return values
