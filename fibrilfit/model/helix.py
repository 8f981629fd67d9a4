"""The fibril's helix, the one place that places anything along it: plain numpy, no bpy.

Layer k is turned k·twist about Z and raised k·rise; protofilament j of a layer adds j times the
protofilaments' turn and rise (`layer_transforms`, `chain_transforms`). A periodic cell of M
layers repeats under the screw S (turn M·twist, raise M·rise); S^m is its m-th power, and a point
of chain c in the cell has an image in chain c + m·n_chains of the infinite fibril
(`screw_turn`, `screw_matrix`, `apply_points`, `apply_matrices`, `image_gap`; `turn_matrix` for
any turn and rise; `image_cells`, the order the outputs list images in); the cell `auto` picks
(`auto_cell_layers`) and the period of the inflate start's lattice it holds (`lattice_rows`).
`layer_frame_xy` is the inverse: a point's layer and its position in that layer's own frame.
`handedness` names a twist's hand.

How far a body reaches is the domains' (model/domains.py); which part of gravity a cell feels,
model/gravity.py.
"""
from __future__ import annotations

import math

import numpy as np

from .domains import member_indices


def layer_turn(p, k):
    """Turn (rad) and height (Å) of layer k (an int or a float array): k·twist, k·rise."""
    return k * p.twist, k * p.rise


def handedness(twist: float) -> str:
    """The hand of a helix turning `twist` (rad) per layer, raised along +Z: "right-handed"
    for a positive twist (counter-clockwise seen from above, as layer_turn turns), "left-handed"
    for a negative one, and "no twist" at exactly zero, which has no hand (a flat twist is
    neither, and calling it either would be a guess)."""
    return "no twist" if twist == 0 else ("right-handed" if twist > 0 else "left-handed")


def layer_transforms(p, count: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Angle (rad) and height (Å) of each layer about/along the fibril axis Z."""
    return layer_turn(p, np.arange(p.layers if count is None else count, dtype=float))


def chain_layers(p) -> tuple[np.ndarray, np.ndarray]:
    """(layer, protofilament) of every chain: chain c = layer * K + protofilament."""
    c = np.arange(p.chains)
    return c // p.protofilaments, c % p.protofilaments


def chain_transforms(p) -> tuple[np.ndarray, np.ndarray]:
    """Turn (rad) and height (Å) of every chain: layer k's twist and rise, plus j times the
    protofilaments' turn and rise for protofilament j (exactly the layer's for j = 0), or
    protofilament j's own as measured (Params.pf_offsets)."""
    k, j = chain_layers(p)
    angle, height = layer_turn(p, k.astype(float))
    turns, rises = p.pf_offsets()
    return angle + turns[j], height + rises[j]


def layer_frame_xy(p, positions) -> tuple[np.ndarray, np.ndarray]:
    """The inverse of the layer transform, for positions (..., 3): the layer k whose slice
    (k·rise ± rise/2) holds each height, and the position's x, y turned back by k·twist into that
    layer's own frame (..., 2)."""
    pos = np.asarray(positions, dtype=float)
    k = np.floor(pos[..., 2] / p.rise + 0.5).astype(int)
    back, _ = layer_turn(p, -k)
    return k, turn_xy(pos[..., 0], pos[..., 1], back)


def turn_xy(x, y, angle) -> np.ndarray:
    """x, y turned by `angle` (rad; arrays broadcast) about Z, stacked (..., 2)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * x - s * y, s * x + c * y], -1)


def screw_turn(p, m):
    """Turn (rad) and height (Å) of S^m (m an int or a float array): m·M·twist, m·M·rise."""
    return m * p.periodic * p.twist, m * p.periodic * p.rise


def screw_matrix(p, m: int) -> np.ndarray:
    """S^m as a 4 × 4 matrix (row-major, column vectors): turn m·M·twist, raise m·M·rise."""
    return turn_matrix(*screw_turn(p, m))


def turn_matrix(angle: float, height: float) -> np.ndarray:
    """A turn by `angle` (rad) about Z and a rise by `height` (Å) as a 4 × 4 matrix (row-major,
    column vectors)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0, 0.0], [s, c, 0.0, 0.0], [0.0, 0.0, 1.0, height],
                     [0.0, 0.0, 0.0, 1.0]])


def image_cells(cells: int) -> list[int]:
    """The image cells (m) an output lists after the cell itself (m = 0): -1 .. -N below, then
    1 .. N above (--pdb-images' chains, --pdb-assembly's operators)."""
    return [*range(-1, -cells - 1, -1), *range(1, cells + 1)]


def apply_points(p, m, points: np.ndarray) -> np.ndarray:
    """S^m of points (..., 3); `m` an int or an array broadcasting against points[..., 0]."""
    points = np.asarray(points, dtype=float)
    angle, height = screw_turn(p, np.asarray(m, dtype=float))
    c, s = np.cos(angle), np.sin(angle)
    x, y, z = points[..., 0], points[..., 1], points[..., 2]
    return np.stack([c * x - s * y, s * x + c * y, z + height], axis=-1)


def apply_matrices(p, m: int, matrices: np.ndarray) -> np.ndarray:
    """S^m · matrices (n, 4, 4): world matrices of the images of objects."""
    return np.einsum("ij,njk->nik", screw_matrix(p, m), np.asarray(matrices, dtype=float))


def min_cell_layers(p) -> int:
    """The shortest cell: M·rise > D (the widest domain's), so a globule clears its own image
    in the next cell."""
    return int(math.floor(p.widest_diameter / p.rise)) + 1


# The shortest cell `auto` takes: M = ceil(AUTO_FACTOR · D / rise), and never below the minimum.
# Measured (docs/notebook/periodic-cell.md#agreement, 30 Å globules, the cell feeling only
# gravity's axial part, cell_gravity): at linker 7, where the answer is a probability, 13 layers
# fit 91 of 100 seeds, the interior of 200 layers 38 of 40 (under the same gravity), 26 layers 82
# of 100 (p = 0.10; why longer cells may fit less is not known); linkers 6, 8 and 12 give the
# same verdict at 13, 26 and 50. (Under the sideways gravity cells felt before, 13 fitted 38 %
# and `auto` was 8·D/rise = 50.)
AUTO_FACTOR = 2.0


def lattice_rows(p) -> int:
    """Rows of chains on each side of the inflate start's lattice in a cell: round(D / (2·rise)),
    at least 1, so that a row's chains (2 rows' worth of layers apart) stand about a diameter
    apart along the axis. Its period, 2 rows' worth of layers, is what a cell must hold whole
    for the lattice start (model/start_layout.py, lattice_columns). 0 (no lattice) for several
    domains per chain or a real domain shape: measured on one sphere per chain only."""
    if len(member_indices(p)) > 1 or p.shape.real:
        return 0
    return max(1, int(round(p.widest_diameter / (2.0 * p.rise))))


def base_cell_layers(p) -> int:
    """The measured margin: ceil(AUTO_FACTOR · D / rise), and never below the minimum."""
    return max(min_cell_layers(p), int(math.ceil(AUTO_FACTOR * p.widest_diameter / p.rise - 1e-9)))


def auto_cell_layers(p) -> int:
    """The cell `auto` picks: the measured margin (base_cell_layers), and under the inflate
    protocol the shortest cell at or above it that holds whole periods of the inflate start's
    lattice (2 · lattice_rows layers). Why: one cell length decided the answer (20 Å globules
    at linker 4, inflate, seeds 0-4: 0 of 5 in the 9-layer cell, 2 of 5 in a 12-layer one), and
    the layout found repeats every 4 layers, which a cell of 9 cannot hold
    (docs/model/periodic-cell.md#auto-cell)."""
    if getattr(p, "protocol", "tutorial") != "inflate" or not lattice_rows(p):
        return base_cell_layers(p)
    period = 2 * lattice_rows(p)
    return -(-base_cell_layers(p) // period) * period


def image_gap(p, m: int, k: int) -> float:
    """Height gap (Å) between layer k of image cell m (m ≠ 0: k·rise plus S^m's rise) and the
    nearest layer of the cell (its top layer for m > 0, layer 0 for m < 0)."""
    z = layer_turn(p, k)[1] + screw_turn(p, m)[1]
    return z - (p.periodic - 1) * p.rise if m > 0 else -z


def image_layers(p, reach: float) -> list[tuple[int, int]]:
    """(m, layer) of every image layer, m ≠ 0, lying within `reach` along Z of some cell layer."""
    M = p.periodic
    out = []
    m = 1
    while (m * M - (M - 1)) * p.rise <= reach:  # the nearest layer of image cell m
        for sign in (1, -1):
            for k in range(M):
                if image_gap(p, sign * m, k) <= reach:
                    out.append((sign * m, k))
        m += 1
    return sorted(out)


def check_cells(p, centres_z: np.ndarray, radius: float) -> int:
    """How many cells up the check must look: every image m ≥ 1 that can hold a globule within
    2·radius of a cell globule, given the globules' heights now (exact, not a bound)."""
    z = np.asarray(centres_z, dtype=float)
    span = float(z.max() - z.min()) if z.size else 0.0
    return max(1, int(math.floor((span + 2.0 * radius) / (p.periodic * p.rise))) + 1)
