"""How far each linker bond is pulled beyond its rest length."""
from __future__ import annotations

import numpy as np


def bond_stretch(positions: np.ndarray, rest_lengths) -> np.ndarray:
    """Stretch of each bond, (distance − rest) / rest, for chain positions (layers, members, 3).

    Rest lengths are the sums of the two members' radii in the tutorial's model.
    Returns (layers, members − 1); negative means compressed.
    """
    dist = np.linalg.norm(np.diff(positions, axis=1), axis=-1)
    rest = np.asarray(rest_lengths, dtype=float)
    return dist / rest - 1.0
