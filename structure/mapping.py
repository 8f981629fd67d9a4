"""From measurements to model parameters: a pure function over the measured objects."""
from __future__ import annotations

from .domain import DomainSize
from .fibril import FibrilGeometry

# The model parameters a structure fills (params.py names); an explicit option beside it wins.
FIBRIL_PARAMS = ("rise", "twist", "protofilaments", "pf_rotation", "pf_rise", "core_outline",
                 "anchor", "linker")
DOMAIN_PARAMS = ("globule_diameter",)


def model_values(fibril: FibrilGeometry | None = None, domain: DomainSize | None = None) -> dict:
    """Parameter name -> value for the model, in its units (Å, rad).

    The layer frame is the fibril's: Z = the helical axis through the origin, layer 0 of the model
    = the structure's reference layer, X along the long axis of its section. `anchor` is
    protofilament 0's anchor CA; `linker` (anchor + tail) only when the file models residues
    beyond the anchor (e.g. 2N0A's 98-140), since they are linker too.
    """
    values = {}
    if fibril is not None:
        values.update(rise=fibril.rise, twist=fibril.twist,
                      protofilaments=fibril.protofilaments,
                      pf_rotation=fibril.pf_rotation, pf_rise=fibril.pf_rise,
                      core_outline=[list(p) for p in fibril.core_outline],
                      anchor=list(fibril.anchors[0]["position"]))
        tail = fibril.tail_residues
        if tail:
            values["linker"] = 1 + tail[1] - tail[0] + 1
    if domain is not None:
        values["globule_diameter"] = domain.globule_diameter
    return values
