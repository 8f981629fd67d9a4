"""The ensemble's density map, helically averaged, its projection and the width read from it
(docs/model/ensemble.md#density-map). Plain numpy; mrcfile only to write the map.

Helical averaging is exact for the model's symmetry: every domain centre is taken into its own
layer's frame (helix.layer_frame_xy: the layer whose slice holds its height, turned back), all
kept layouts pooled there, and put back into every layer of the map's window (helix.layer_turn),
so each layer of the map holds every layer's domains. The centres' histogram on the voxel grid
is convolved (FFT) with a voxelised solid sphere of the domain's radius: the map is the domains'
volume fraction per voxel (times 0.81 Da/Å³, observables.PROTEIN_DENSITY, a mass density).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model import helix

WIDTH_FRACTION = 0.1  # the width: where the projection's profile falls to this fraction of its peak
SUPERSAMPLE = 4  # per voxel and axis, to voxelise the sphere
MAX_LAYERS = 400  # the longest window a map takes (the default model's turn: 185 layers)


@dataclass
class DensityMap:
    """`data` (z, y, x) volume fraction, `voxel` Å, `origin` (x, y, z) Å of voxel (0, 0, 0)'s
    corner, `layers` the window's layers (rise each)."""

    data: np.ndarray
    voxel: float
    origin: tuple
    layers: int


def layer_frame(p, centres: np.ndarray) -> np.ndarray:
    """Each centre (..., 3) in its own layer's frame: (x', y', z - k·rise), k its layer."""
    c = np.asarray(centres, dtype=float).reshape(-1, 3)
    k, xy = helix.layer_frame_xy(p, c)
    return np.column_stack([xy, c[:, 2] - helix.layer_turn(p, k.astype(float))[1]])


def _ball(radius: float, voxel: float) -> np.ndarray:
    """A solid sphere's occupancy of each voxel (z, y, x), centred, supersampled."""
    half = int(math.ceil(radius / voxel))
    n = (2 * half + 1) * SUPERSAMPLE
    g = ((np.arange(n) + 0.5) / SUPERSAMPLE - (half + 0.5)) * voxel
    inside = (g[:, None, None] ** 2 + g[None, :, None] ** 2 + g[None, None, :] ** 2) <= radius ** 2
    s = SUPERSAMPLE
    m = 2 * half + 1
    return inside.reshape(m, s, m, s, m, s).mean(axis=(1, 3, 5))


def pitch_layers(p) -> int:
    """Layers in one helical turn (2π / |twist|), at most MAX_LAYERS; 1 without twist."""
    return 1 if p.twist == 0 else min(MAX_LAYERS, int(round(2 * math.pi / abs(p.twist))))


def density_map(p, centres: np.ndarray, radius: float, *, voxel: float = 3.0,
                layers: int | None = None, core=None) -> DensityMap:
    """The helically averaged map of the domains (spheres of `radius` at `centres` (..., 3),
    every domain of every kept layout's scored chains) over a window of `layers` layers
    (default: one helical turn, pitch_layers, so its projection sees every azimuth once): each
    layer of the window gets every pooled centre, weighted by 1 / (pooled layer-slices), so a
    layer holds, on average, one layer's domains (protofilaments × domains per chain). `core`:
    an obstacle (system.CorePrism) whose inside (at each voxel centre) is added at volume
    fraction 1 (the linkers' beads are not in the map)."""
    layers = pitch_layers(p) if layers is None else layers
    local = layer_frame(p, centres)
    slices = len(local) / (p.protofilaments * len(p.domains))
    reach = float(np.hypot(local[:, 0], local[:, 1]).max()) + radius + 2 * voxel
    pad = int(math.ceil(radius / p.rise)) + 1  # layers beyond the window whose spheres reach in
    ks = np.arange(-pad, layers + pad, dtype=float)
    angle, height = helix.layer_turn(p, ks)
    pts = np.concatenate([np.column_stack([helix.turn_xy(local[:, 0], local[:, 1], a),
                                           local[:, 2] + h]) for a, h in zip(angle, height)])
    nxy = int(math.ceil(2 * reach / voxel))
    z0, z1 = -0.5 * p.rise - radius - voxel, (layers - 0.5) * p.rise + radius + voxel
    nz = int(math.ceil((z1 - z0) / voxel))
    x0 = -nxy * voxel / 2
    edges_xy = x0 + voxel * np.arange(nxy + 1)
    edges_z = z0 + voxel * np.arange(nz + 1)
    hist, _ = np.histogramdd(pts[:, ::-1], bins=(edges_z, edges_xy, edges_xy))
    ball = _ball(radius, voxel)
    shape = [a + b - 1 for a, b in zip(hist.shape, ball.shape)]
    axes = (0, 1, 2)
    conv = np.fft.irfftn(np.fft.rfftn(hist, shape, axes) * np.fft.rfftn(ball, shape, axes),
                         shape, axes)
    h = [b // 2 for b in ball.shape]
    data = conv[h[0]:h[0] + nz, h[1]:h[1] + nxy, h[2]:h[2] + nxy] / slices
    # keep the window's layers only (the pad layers' own centres are cut off at their ends)
    lo = int(math.floor((-0.5 * p.rise - z0) / voxel))
    hi = int(math.ceil(((layers - 0.5) * p.rise - z0) / voxel))
    data = np.clip(data[lo:hi], 0.0, None)
    origin = (x0, x0, z0 + lo * voxel)
    if core is not None:
        data = data + core_inside(core, origin, data.shape, voxel)
    return DensityMap(data.astype(np.float32), voxel, origin, layers)


def core_inside(core, origin, shape, voxel: float) -> np.ndarray:
    """1 where a voxel's centre lies inside `core` (an obstacle), else 0: (z, y, x) of `shape`,
    the grid's corner at `origin` (x, y, z)."""
    zc = origin[2] + voxel * (np.arange(shape[0]) + 0.5)
    yc = origin[1] + voxel * (np.arange(shape[1]) + 0.5)
    xc = origin[0] + voxel * (np.arange(shape[2]) + 0.5)
    grid = np.stack(np.meshgrid(zc, yc, xc, indexing="ij")[::-1], -1)  # (z, y, x) of (x, y, z)
    return (core.depth(grid, 0.0) > 0).astype(float)


def core_map(p, core, *, voxel: float = 3.0, layers: int | None = None) -> DensityMap:
    """The map of the core alone (no domains: a fibril with nothing tethered, or whose tails are
    not in the map) over the same window as density_map's."""
    layers = pitch_layers(p) if layers is None else layers
    nxy = int(math.ceil(2 * (core.bound + 2 * voxel) / voxel))
    x0 = -nxy * voxel / 2
    z0 = -0.5 * p.rise
    nz = int(math.ceil(layers * p.rise / voxel))
    origin = (x0, x0, z0)
    data = core_inside(core, origin, (nz, nxy, nxy), voxel)
    return DensityMap(data.astype(np.float32), voxel, origin, layers)


def write_mrc(path, dmap: DensityMap) -> None:
    """The map as an MRC file (mrcfile): voxel size and origin (Å) in the header."""
    import mrcfile
    with mrcfile.new(str(path), overwrite=True) as mrc:
        mrc.set_data(dmap.data)
        mrc.voxel_size = dmap.voxel
        mrc.header.origin = dmap.origin


def projection(dmap: DensityMap) -> np.ndarray:
    """The map projected along Y (perpendicular to the fibril axis), (z, x): the domains'
    projected thickness in Å (a negative-stain-like image of the protein's mass)."""
    return dmap.data.sum(axis=1) * dmap.voxel


def profile(dmap: DensityMap) -> tuple[np.ndarray, np.ndarray]:
    """(x, profile): the projection's profile across the axis (Å of projected thickness,
    averaged along the axis) at the voxel centres x (Å)."""
    prof = projection(dmap).mean(axis=0)
    return dmap.origin[0] + dmap.voxel * (np.arange(prof.size) + 0.5), prof


def width_edges(dmap: DensityMap, fraction: float = WIDTH_FRACTION) -> tuple[float, float]:
    """(left, right), Å: the profile's outermost points at `fraction` of its peak, interpolated
    linearly between voxel centres; the width is right − left."""
    x, prof = profile(dmap)
    level = fraction * float(prof.max())
    above = np.flatnonzero(prof >= level)
    i, j = int(above[0]), int(above[-1])
    left = x[i] if i == 0 else np.interp(level, [prof[i - 1], prof[i]], [x[i - 1], x[i]])
    right = (x[j] if j == prof.size - 1 else
             np.interp(level, [prof[j + 1], prof[j]], [x[j + 1], x[j]]))
    return float(left), float(right)


def width(dmap: DensityMap, fraction: float = WIDTH_FRACTION) -> float:
    """The width (Å) read from the projection: its profile across the axis (averaged along the
    axis) and the distance between its outermost points at `fraction` of the profile's peak,
    interpolated linearly between voxel centres (docs/model/ensemble.md#density-map)."""
    left, right = width_edges(dmap, fraction)
    return right - left
