"""The real structure's CA trace in the model's layer frame (Z = the fibril axis through the
origin, layer 0 = the reference layer): for drawing it beside the coarse model."""
from __future__ import annotations

import numpy as np

from . import reading
from .fibril import FibrilGeometry


def layer_frame(fibril: FibrilGeometry) -> tuple:
    """(origin, 3×3 rows X, Y, Z) of the layer frame, in the file's coordinates."""
    z = np.array(fibril.axis["direction"], float)
    x = np.array(fibril.axis["x"], float)
    return np.array(fibril.axis["point"], float), np.array([x, np.cross(z, x), z])


def ca_trace(path, fibril: FibrilGeometry, option: str = "--fibril") -> list:
    """[(chain, residue numbers, CA (n, 3) in the layer frame)] for every layer of the file,
    bottom to top per protofilament (symmetry copies built as for the measurement)."""
    loaded = reading.load(path, option)
    if len(loaded.chains) < 2:
        reading.expand_symmetry(loaded)
    origin, frame = layer_frame(fibril)
    chains = {c.name: c for c in loaded.chains}
    return [(name, chains[name].residues, (chains[name].ca - origin) @ frame.T)
            for q in fibril.layer_chains for name in q]
