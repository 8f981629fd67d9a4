"""Chain members whose centre lies inside a core prism: a bead or globule that got through the
core's collision shape (docs/model/protofilaments.md#stretched-linkers)."""
from __future__ import annotations

import numpy as np

from ..geom import polygons


def members_inside_core(p, positions: np.ndarray) -> list[list[int]]:
    """[chain, member] of every chain member (anchor, beads, globule) whose centre lies inside
    the core of the layer whose prism holds its height (layer k spans k·rise ± rise/2, turned
    by k·twist), for positions (chains, members, 3). Members above or below the fibril's end
    layers are outside every core."""
    pos = np.asarray(positions, dtype=float)
    z = pos[..., 2]
    k = np.floor(z / p.rise + 0.5).astype(int)
    in_stack = (k >= 0) & (k < p.layers)
    back = -k * p.twist
    c, s = np.cos(back), np.sin(back)
    xy = np.stack([c * pos[..., 0] - s * pos[..., 1], s * pos[..., 0] + c * pos[..., 1]], -1)
    inside = polygons.inside(p.outline(), xy.reshape(-1, 2)).reshape(z.shape) & in_stack
    return np.argwhere(inside).tolist()
