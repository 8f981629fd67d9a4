"""The ensemble's density as a Volume object (builders/density_volume.py;
docs/model/ensemble.md#volume), on every bpy: it lives in the model's collection, found by tag
(a user's object of the same name is never touched), sampling again replaces it and a rebuild
removes it; Blender's own grid holds the map's voxels above the threshold at the map's places
(read back through Blender's Distribute Points in Volume:
tests/realblender/volume_probe.py), reaches over the relaxed layout's
domains, and its radial profile, read from the grid alone, peaks where the sampler's radial
density of domain mass peaks. `run --ensemble-volume --blend` saves it with the file."""
import json

import bpy
import numpy as np
import pytest

from fibrilfit import api, cli, pipeline
from fibrilfit.analysis.verdict import chain_positions, scored_chains
from fibrilfit.builders import density_volume, scene as owned
from fibrilfit.ensemble import system
from realblender.volume_probe import voxels_above

SMALL = dict(layers=6, seed=0)
OPTIONS = dict(sweeps=6, replicas=4, burn_in=4)
STEP = 0.04  # the levels at which the grid is read back (volume fraction)
LEVELS = 15  # STEP … 0.6: the domains' map stays below (the core, 1, is left out)


def _grid_values(volume):
    """The hidden grid mesh's voxel centres and values (what the builder wrote)."""
    grid = next(ob for ob in volume.users_collection[0].objects if ob.type == "MESH")
    n = len(grid.data.vertices)
    co, val = np.empty(3 * n), np.empty(n)
    grid.data.vertices.foreach_get("co", co)
    grid.data.attributes[density_volume.ATTRIBUTE].data.foreach_get("value", val)
    return co.reshape(-1, 3), val


def _top(r, profile, fraction=0.8):
    """Where a radial profile peaks: the profile-weighted mean radius of its part above
    `fraction` of its maximum (both profiles are flat-topped, so an argmax is noise)."""
    r, profile = np.asarray(r, float), np.asarray(profile, float)
    keep = profile >= fraction * profile.max()
    return float((r[keep] * profile[keep]).sum() / profile[keep].sum())


def _ours(kind, role):
    return [d for d in kind if d.get(owned.TAG) == role]


def test_the_ensembles_density_as_a_volume_over_the_fibril(scene):
    result = api.run(**SMALL)  # in a fresh scene
    scene = bpy.context.scene
    # a user's object with the volume's own name: never looked up, never touched
    mine = bpy.data.objects.new("ensemble density", None)
    scene.collection.objects.link(mine)
    block = api.ensemble(result, **OPTIONS, ensemble_volume=True)
    info = block["volume"]
    ob = density_volume.find(scene)
    assert ob is not None and ob is not mine and ob.type == "VOLUME"
    assert ob.name == info["object"] and mine.name == "ensemble density"
    model = pipeline.current_model(scene)
    # in the model's own collection, tagged
    coll = ob.users_collection[0]
    assert coll.get(owned.TAG) == density_volume.ROLE and coll.name in model.root.children
    # Blender's grid: a float grid named "density", not empty
    ev = ob.evaluated_get(bpy.context.evaluated_depsgraph_get())
    assert [(g.name, g.data_type) for g in ev.data.grids] == [("density", "FLOAT")]
    # the evaluated volume carries the material (a node-made volume has only what Set
    # Material gives it), a Principled Volume reading the grid
    assert [m.get(owned.TAG) for m in ev.data.materials] == [density_volume.ROLE]
    shader = next(n for n in ev.data.materials[0].node_tree.nodes
                  if n.bl_idname == "ShaderNodeVolumePrincipled")
    assert shader.inputs["Density Attribute"].default_value == density_volume.ATTRIBUTE
    read = voxels_above(ob, info["voxel"])
    active = read(info["threshold"])
    assert len(active) == info["voxels_above_threshold"] > 100
    # exactly the map's voxels above a level, at the map's places
    centres, values = _grid_values(ob)
    for level in (info["threshold"], 0.2):
        want = {tuple(c) for c in np.round(centres[values > level], 2)}
        assert {tuple(c) for c in np.round(read(level), 2)} == want
    # over the fibril: the relaxed layout's scored domain centres (those within the window's
    # layers) lie inside the grid's active voxels' box, and the grid reaches as far out
    domains = chain_positions(model)[scored_chains(model.params), -1]
    lo, hi = active.min(0), active.max(0)
    inside_window = (domains[:, 2] >= lo[2]) & (domains[:, 2] <= hi[2])
    assert inside_window.sum() >= 2
    assert np.all((domains[inside_window] >= lo - 1e-6) & (domains[inside_window] <= hi + 1e-6))
    assert np.hypot(*active[:, :2].T).max() >= np.hypot(*domains[:, :2].T).max()
    # its radial profile from Blender's grid alone (the sum over levels of the voxels above
    # each: a layer-cake integral), outside the core, peaks where the sampler's does
    core = system.from_params(model.params).obstacle
    outside = core.depth(centres, 0.0) <= 0
    shell = 3.0
    edges = np.arange(0.0, np.hypot(*centres[:, :2].T).max() + shell, shell)
    voxels = np.histogram(np.hypot(*centres[outside, :2].T), edges)[0]
    total = np.zeros(len(edges) - 1)
    for k in range(1, LEVELS + 1):
        pts = read(k * STEP)
        pts = pts[core.depth(pts, 0.0) <= 0]
        total += STEP * np.histogram(np.hypot(*pts[:, :2].T), edges)[0]
    mid = 0.5 * (edges[1:] + edges[:-1])
    profile = np.divide(total, voxels, out=np.zeros_like(total), where=voxels > 0)
    rd = block["radial_density"]
    assert _top(mid, profile) == pytest.approx(_top(rd["r"], rd["volume_fraction"]), abs=3.0)
    # sampled again: replaced, not added
    api.ensemble(result, **OPTIONS, ensemble_volume=True)
    for kind, role in ((bpy.data.objects, density_volume.ROLE),
                       (bpy.data.objects, density_volume.GRID_ROLE),
                       (bpy.data.volumes, density_volume.ROLE),
                       (bpy.data.node_groups, density_volume.ROLE),
                       (bpy.data.materials, density_volume.ROLE)):
        assert len(_ours(kind, role)) == 1, (kind, role)
    # a rebuild removes it, and the user's object stays
    pipeline.build(model.params, scene, force=True)
    assert density_volume.find(scene) is None
    assert not _ours(bpy.data.volumes, density_volume.ROLE)
    assert not _ours(bpy.data.node_groups, density_volume.ROLE)
    assert not _ours(bpy.data.meshes, density_volume.GRID_ROLE)
    assert not _ours(bpy.data.materials, density_volume.ROLE)
    assert scene.objects.get("ensemble density") == mine


def test_run_ensemble_volume_is_saved_with_the_blend(scene, tmp_path):
    blend, out = tmp_path / "r.blend", tmp_path / "r.json"
    assert cli.main(["run", "--layers", "6", "--ensemble", "6", "--ensemble-replicas", "4",
                     "--ensemble-burn-in", "4", "--ensemble-volume", "--quiet",
                     "--json", str(out), "--blend", str(blend)]) == 0
    info = json.loads(out.read_text())["ensemble"]["volume"]
    bpy.ops.wm.open_mainfile(filepath=str(blend))
    ob = density_volume.find(bpy.context.scene)
    ev = ob.evaluated_get(bpy.context.evaluated_depsgraph_get())
    assert [g.name for g in ev.data.grids] == ["density"]
    assert len(voxels_above(ob, info["voxel"])(info["threshold"])) == info["voxels_above_threshold"]


def test_a_volume_needs_an_ensemble(scene, capsys):
    assert cli.main(["run", "--layers", "6", "--ensemble-volume"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "ensemble_volume" in err.replace("-", "_"), err
