"""A buried anchor's exit drawn: one curve object in the model's root collection, a polyline
per chain along its exit's path (the measured path of protofilament 0's chain, turned and raised
by each chain's pose; with interface termini each protofilament's own measured path, turned and
raised by its layer), beveled to the residue's radius. Not a body: nothing collides with it
(docs/model/buried-terminus.md#model)."""
from __future__ import annotations

import bpy
import numpy as np

from ..model import helix, occupancy
from .scene import tag

NAME = "FibrilFit exit path"
ROLE = "exit_path"


def chain_paths(p) -> list:
    """Every chain's exit path (chains, points, 3): p.exit_path turned and raised by the
    chain's pose (helix.chain_transforms), as rest_positions places the chain's members; with
    interface termini (pf_exit_paths) each protofilament's own path, measured in the layer's
    frame, turned and raised by its layer alone (none for a protofilament on the surface)."""
    if p.pf_exit_paths is not None:
        rows = np.asarray(p.pf_exit_paths, dtype=float)
        angle, height = helix.layer_transforms(p)
        out = []
        for k in range(p.layers):
            for j in range(p.protofilaments):
                path = rows[rows[:, 0] == j, 1:]
                if len(path):
                    xy = helix.turn_xy(path[:, 0], path[:, 1], angle[k])
                    out.append(np.column_stack([xy, path[:, 2] + height[k]]))
        return out
    path = np.asarray(p.exit_path, dtype=float)
    angle, height = helix.chain_transforms(p)
    c, s = np.cos(angle)[:, None], np.sin(angle)[:, None]
    out = np.empty((len(angle), len(path), 3))
    out[..., 0] = c * path[None, :, 0] - s * path[None, :, 1]
    out[..., 1] = s * path[None, :, 0] + c * path[None, :, 1]
    out[..., 2] = path[None, :, 2] + height[:, None]
    return out


def model_chain_paths(p) -> list:
    """The exit path of each of the model's chains (points, 3) in the world, the anchor residue's
    CA first, in model.chain's order (occupancy.model_chain_layers: a mixed fibril's decorated
    subunits'); None for a chain whose anchor is on the surface (it spends no residues)."""
    layer, pf = occupancy.model_chain_layers(p)
    if (p.exit_path is None and p.pf_exit_paths is None) or p.free_linker < 1:
        return [None] * len(layer)
    if p.pf_exit_paths is None:
        paths = chain_paths(p)  # every subunit's: chain c = layer * K + protofilament
        return [paths[k * p.protofilaments + j] for k, j in zip(layer.tolist(), pf.tolist())]
    rows = np.asarray(p.pf_exit_paths, dtype=float)
    angle, height = helix.layer_transforms(p)
    out = []
    for k, j in zip(layer.tolist(), pf.tolist()):
        path = rows[rows[:, 0] == j, 1:]
        out.append(np.column_stack([helix.turn_xy(path[:, 0], path[:, 1], angle[k]),
                                    path[:, 2] + height[k]]) if len(path) else None)
    return out


def build_exit_path(model) -> bpy.types.Object | None:
    """The exit's curve in the model's root collection, or None on a surface anchor."""
    p = model.params
    if (p.exit_path is None and p.pf_exit_paths is None) or p.free_linker < 1:
        return None
    curve = tag(bpy.data.curves.new(NAME, "CURVE"), ROLE)
    curve.dimensions = "3D"
    curve.bevel_depth = p.residue_radius
    for pts in chain_paths(p):
        spline = curve.splines.new("POLY")
        spline.points.add(len(pts) - 1)
        spline.points.foreach_set("co", np.hstack([pts, np.ones((len(pts), 1))]).ravel())
    ob = tag(bpy.data.objects.new(NAME, curve), ROLE)
    model.root.objects.link(ob)
    return ob
