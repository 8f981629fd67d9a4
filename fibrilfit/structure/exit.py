"""The anchor's way out: the shortest path from protofilament 0's anchor CA to the core's
surface clear of the core's atoms, as the fibril file has them (geom.exit_path), in the model's
layer frame (docs/model/buried-terminus.md#method). Plain numpy over the read chains.
"""
from __future__ import annotations

import numpy as np

from ..geom import exit_path as E
from ..model import params as P

BEAD_RADIUS = P.DEFAULTS.residue_radius  # Å, 1.75: the model's residue is the exit's bead
BONDED = 3.0  # Å: the anchor's own chain's atoms this near its CA are its peptide bond's
Z_HALF_RISES = 1.0  # the path stays within one rise above and below the anchor's layer


def obstacles(chains, ref, residue: int, side: str, origin, frame) -> tuple:
    """Heavy atoms (n, 3) in the layer frame, their radii, and the anchor CA: every chain of the
    file but for the residues beyond the anchor on the linker's side (they are linker: the
    path stands for them), the anchor residue itself, and its own chain's atoms bonded to its
    CA (the C and O before it: 2.45 and 2.85 Å in 5OQV)."""
    ca = (ref.ca_of([residue])[0] - origin) @ frame.T
    xyz, radii = [], []
    for c in chains:
        local = (c.heavy - origin) @ frame.T
        keep = c.heavy_residue <= residue if side == "C" else c.heavy_residue >= residue
        if c is ref:
            keep &= c.heavy_residue != residue
            keep &= np.linalg.norm(local - ca, axis=1) >= BONDED
        xyz.append(local[keep])
        radii.append(c.heavy_radius[keep])
    return np.concatenate(xyz), np.concatenate(radii), ca


def measure(chains, ref, residue: int, side: str, origin, frame, outline, rise: float,
            bead_radius: float = BEAD_RADIUS) -> dict:
    """The anchor's exit as the fibril's measurement records it: found, its length, the
    anchor's depth below the outline, the path (layer frame, Å, anchor first), the bead radius
    and what the path keeps clear of (JSON-ready)."""
    atoms, radii, ca = obstacles(chains, ref, residue, side, origin, frame)
    found = E.shortest_exit(atoms, radii, ca, np.asarray(outline, float),
                            bead_radius=bead_radius, z_half=Z_HALF_RISES * rise)
    return {"found": found.found,
            "length": round(found.length, 2) if found.found else None,
            "depth": round(found.depth, 2),
            "path": [[round(float(v), 3) for v in p] for p in found.points],
            "bead_radius": bead_radius,
            "clearance": f"bead {bead_radius:g} Å + each heavy atom's van der Waals radius",
            "searched": f"{E.STEP:g} Å grid, within {Z_HALF_RISES:g} rise of the anchor's "
                        f"layer, up to {E.MAX_LENGTH:g} Å"}
