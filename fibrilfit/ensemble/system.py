"""What a layout of the hard-core model is (docs/model/ensemble.md#the-model-sampled): C chains
of n hard spheres each, member 0 (the anchor) fixed, consecutive members joined by bonds of
fixed length (freely jointed: any angle), every other pair of spheres kept apart (bonded
neighbours may touch or overlap, as Bullet's constraints let them: disable_collisions), the
anchors fixed and so never judged against each other; an obstacle (the core) no sphere but an
anchor may enter; for a periodic cell, the images of every chain under the screw S^m.

`HardCore` holds this for any chains (the closed-form cases of the tests build their own);
`from_params` builds the model's from its Params: the chain of model/chain.py (radii,
rest lengths), the core as its outline extruded layer by layer (`CorePrism`: each layer's
slab, turned and raised by model/helix.py), and the screw images of helix.apply_points.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..geom import polygons
from ..model import chain, helix, occupancy
from ..model.param_spec import ParamError


@dataclass(frozen=True)
class Wall:
    """The half-space below a plane (`normal` · x < `offset`) as an obstacle: a sphere overlaps
    it by r − (normal · x − offset)."""

    normal: tuple = (0.0, 0.0, 1.0)
    offset: float = 0.0

    def depth(self, points: np.ndarray, radii: np.ndarray) -> np.ndarray:
        """How deep each sphere (centres (..., 3), radii broadcasting) enters the obstacle."""
        height = np.asarray(points) @ np.asarray(self.normal, dtype=float) - self.offset
        return np.maximum(radii - height, 0.0)


@dataclass(frozen=True)
class CorePrism:
    """The core as Bullet has it: one slab per layer k, the core's outline (Params.outline)
    extruded `thickness` along Z, turned k·twist and centred at k·rise (helix.layer_turn). A
    finite fibril has layers 0 .. layers - 1; a periodic cell's core is infinite (every k)."""

    outline: np.ndarray
    thickness: float
    layers: int | None  # None: every layer (a periodic cell's infinite core)
    turn: Callable  # k -> (angle, height): helix.layer_turn with the model's Params
    rise: float

    def depth(self, points: np.ndarray, radii: np.ndarray) -> np.ndarray:
        """How deep each sphere (centres (..., 3), radii broadcasting) enters any slab: the
        deepest over the slabs near its height, by the signed distance to each slab's prism."""
        pts = np.asarray(points, dtype=float)
        shape = pts.shape[:-1]
        q = pts.reshape(-1, 3)
        r = np.broadcast_to(np.asarray(radii, dtype=float), shape).reshape(-1)
        out = np.zeros(len(q))
        # only spheres within reach of the outline's farthest corner can touch it
        near = np.hypot(q[:, 0], q[:, 1]) - r < self.bound
        if not near.any():
            return out.reshape(shape)
        out[near] = self._depth(q[near], r[near])
        return out.reshape(shape)

    @functools.cached_property
    def bound(self) -> float:
        """The outline's farthest point from the axis (Å)."""
        return float(np.hypot(self.outline[:, 0], self.outline[:, 1]).max())

    def _depth(self, q: np.ndarray, r: np.ndarray) -> np.ndarray:
        half = self.thickness / 2.0
        k0 = np.floor(q[:, 2] / self.rise + 0.5).astype(int)
        # slab k0 + o lies at least |o|·rise - rise/2 - half from the centre along Z: it can
        # touch only for |o| <= (r + half) / rise + 1/2
        reach = np.floor((r + half) / self.rise + 0.5).astype(int)
        w = int(reach.max())
        point, o = np.nonzero(np.abs(np.arange(-w, w + 1))[None, :] <= reach[:, None])
        k = k0[point] + o - w  # every (sphere, slab) pair that can touch, in one pass
        angle, height = self.turn(k.astype(float))
        xy = helix.turn_xy(q[point, 0], q[point, 1], -angle)  # into layer k's own frame
        dist, _ = polygons.edge_distance(self.outline, xy)
        sd_xy = np.where(polygons.even_odd(self.outline, xy), -dist, dist)
        dz = np.abs(q[point, 2] - height) - half
        sd = np.where((sd_xy > 0) & (dz > 0), np.hypot(sd_xy, dz), np.maximum(sd_xy, dz))
        d = r[point] - sd
        if self.layers is not None:
            d = np.where((k >= 0) & (k < self.layers), d, 0.0)
        out = np.zeros(len(q))
        np.maximum.at(out, point, d)
        return out


@dataclass(frozen=True)
class HardCore:
    """C chains of n hard spheres: `radii` (n,), `bonds` (n - 1,) fixed lengths, member 0 fixed;
    `obstacle` (anything with depth(points, radii)) or None; `images`: maps (..., 3) -> (..., 3),
    each a screw image S^m (m ≠ 0) of the whole cell, both signs (a pair with an image below is
    the same pair seen from the image above: counting both is consistent, old and new alike);
    `tolerance` (Å): two spheres may overlap by this much (0: hard spheres)."""

    radii: np.ndarray
    bonds: np.ndarray
    obstacle: object | None = None
    images: tuple = ()
    tolerance: float = 0.0
    domains: tuple = ()  # members that are domains (observables read these)
    notes: dict = field(default_factory=dict)

    @property
    def members(self) -> int:
        return len(self.radii)

    def with_rest_bonds(self, positions: np.ndarray) -> np.ndarray:
        """Positions (..., n, 3) rebuilt from the anchor along each bond's direction at its
        fixed length: a relaxed layout (bonds stretched up to the tolerance) made one of this
        model's (docs/model/ensemble.md#start)."""
        pos = np.array(positions, dtype=float)
        out = pos.copy()
        for i, b in enumerate(self.bonds):
            d = pos[..., i + 1, :] - pos[..., i, :]
            norm = np.linalg.norm(d, axis=-1, keepdims=True)
            out[..., i + 1, :] = out[..., i, :] + b * d / np.where(norm > 0, norm, 1.0)
        return out


def image_cells(p) -> int:
    """How many cells up and down a member can meet an image: a chain reaches at most its
    length plus its widest radius from its anchor along Z, so two members are within
    2·(that) + the cell's own spread of heights (exact bound, as helix.check_cells)."""
    x = np.asarray(chain.chain_x(p))
    reach = float(x[-1] - x[0]) + float(max(chain.chain_radii(p)))
    spread = (p.periodic - 1) * p.rise + (p.protofilaments - 1) * p.pf_rise_step
    return int(math.floor((spread + 2.0 * reach) / (p.periodic * p.rise))) + 1


def refuse(p) -> None:
    """Raise ParamError for what the sampler does not model (one line each, what is allowed)."""
    if p.shape.real:
        raise ParamError("domain_shape", f"the ensemble samples sphere domains only, not "
                                         f"'{p.domain_shape}' (docs/model/ensemble.md#scope)")
    if occupancy.is_mixed(p) or occupancy.is_hetero(p):
        raise ParamError("occupancy", "the ensemble samples fully decorated fibrils of one "
                                      "domain only (docs/model/ensemble.md#scope)")
    if p.bare_tail:
        raise ParamError("bare_tail", "the ensemble does not sample bare tails: give 0 "
                                      "(docs/model/ensemble.md#scope)")


def from_params(p) -> HardCore:
    """The model's hard-core system: its chain (chain_radii, rest_lengths), its core prism and,
    for a periodic cell, the screw images S^m, m = ±1 .. image_cells(p)."""
    refuse(p)
    radii = np.asarray(chain.chain_radii(p), dtype=float)
    core = CorePrism(p.outline(), float(p.slab[2]), None if p.periodic else p.layers,
                     functools.partial(helix.layer_turn, p), float(p.rise))
    images = ()
    if p.periodic:
        cells = image_cells(p)
        images = tuple(functools.partial(helix.apply_points, p, m)
                       for m in helix.image_cells(cells))
    return HardCore(radii, np.asarray(chain.rest_lengths(p), dtype=float), core, images,
                    domains=tuple(d.member for d in p.domains),
                    notes={"image_cells": len(images) // 2})
