"""Chain members whose centre lies inside a core prism: a bead or globule that got through the
core's collision shape (docs/model/protofilaments.md#stretched-linkers)."""
from __future__ import annotations

import numpy as np

from ..geom import polygons
from ..model import helix


def members_inside_core(p, positions: np.ndarray) -> list[list[int]]:
    """[chain, member] of every chain member (anchor, beads, globule) whose centre lies inside
    the core of the layer whose prism holds its height (layer k spans k·rise ± rise/2, turned
    by k·twist), for positions (chains, members, 3). Members above or below the fibril's end
    layers are outside every core."""
    k, xy = helix.layer_frame_xy(p, positions)
    in_stack = (k >= 0) & (k < p.layers)
    inside = polygons.inside(p.outline(), xy.reshape(-1, 2)).reshape(k.shape) & in_stack
    return np.argwhere(inside).tolist()
