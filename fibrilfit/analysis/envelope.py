"""The decorated fibril's envelope: how far from the fibril axis the domains sit.

An EM image of a decorated fibril shows the core inside a cloud of domains; the cloud's width is
what negative-stain and cryo-EM papers report. Here: the radial distance r of every scored domain
centre from the fibril axis (Z, through the origin), its median and 95th percentile (numpy's
default linear interpolation), and outer_diameter = 2 (r95 + R), R the domain's radius. Å.
"""
from __future__ import annotations

import numpy as np


def radii(centres) -> np.ndarray:
    """Distance of each centre from the fibril axis (Z through the origin)."""
    c = np.asarray(centres, dtype=float).reshape(-1, 3)
    return np.hypot(c[:, 0], c[:, 1])


def envelope(centres, radius: float, reach=None) -> dict:
    """{r_median, r95, r_max, outer_diameter, n} of the domain centres given (the scored ones),
    rounded to 0.001 Å; every number is None when there are none. `reach`: with a real domain
    shape, each domain's farthest point from the axis; outer_diameter is then 2 · their 95th
    percentile (docs/model/domain-shapes.md#envelope)."""
    r = radii(centres)
    if r.size == 0:
        return {"r_median": None, "r95": None, "r_max": None, "outer_diameter": None, "n": 0}
    r95 = float(np.percentile(r, 95))
    return {
        "r_median": round(float(np.median(r)), 3),
        "r95": round(r95, 3),
        "r_max": round(float(r.max()), 3),
        "outer_diameter": round(2 * (r95 + radius) if reach is None
                                else 2 * float(np.percentile(reach, 95)), 3),
        "n": int(r.size),
    }
