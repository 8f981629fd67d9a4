"""The ensemble's density over the fibril as a Volume object (docs/model/ensemble.md#volume).

No .vdb file and no OpenVDB Python module (the bpy wheels 4.2 has none, and no OpenVDB package
with Python bindings is on PyPI): Blender makes the grid itself. The map's voxels are the
vertices of a hidden mesh (`density_grid`, one vertex at each voxel centre, its value in the
point attribute "density"); the Volume object (`density_volume`) has a Geometry Nodes modifier
whose Volume Cube node samples that attribute at its own voxel centres (Sample Nearest, then
Sample Index: the grids coincide, so each voxel takes its own value), zero below the group's
Threshold input. The grid is an OpenVDB float grid named "density", as a loaded .vdb's is; the
material's Principled Volume reads it. Both objects live in a collection of the model's root
(tag `density`), found by tag, replaced when sampled again and removed with the model.
"""
from __future__ import annotations

import bpy
import numpy as np

from .scene import TAG, find_root, is_ours, new_collection, tag

ROLE = "density"            # the collection (under the model's root) and the Volume object
GRID_ROLE = "density_grid"  # the hidden mesh holding the map's voxels
ATTRIBUTE = "density"       # the point attribute and the grid's name (a .vdb's usual one)
THRESHOLD = 0.02            # volume fraction below which a voxel is empty (the docs' #volume)
DENSITY_SCALE = 0.08        # the material's density per volume fraction (per Å: 1 BU = 1 Å)
COLOUR = (0.25, 0.45, 0.9, 1.0)


def remove(scene) -> None:
    """The density collection, its objects and their data, if the model has them."""
    root = find_root(scene)
    if root is None:
        return
    colls = [c for c in root.children_recursive if c.get(TAG) == ROLE]
    objects = {ob for c in colls for ob in c.objects if is_ours(ob)}
    groups = {m.node_group for ob in objects for m in ob.modifiers
              if m.type == "NODES" and m.node_group is not None and is_ours(m.node_group)}
    bpy.data.batch_remove(objects)
    bpy.data.batch_remove(colls)
    bpy.data.batch_remove([g for g in groups if g.users == 0])  # before their material
    for kinds in ((bpy.data.meshes, bpy.data.volumes), (bpy.data.materials,)):
        bpy.data.batch_remove([d for kind in kinds for d in kind if is_ours(d) and d.users == 0])


def voxel_centres(dmap) -> np.ndarray:
    """(z·y·x, 3) the map's voxel centres (x, y, z) in the data's (z, y, x) order, Å."""
    nz, ny, nx = dmap.data.shape
    x0, y0, z0 = dmap.origin
    axes = [o + dmap.voxel * (np.arange(n) + 0.5) for o, n in ((z0, nz), (y0, ny), (x0, nx))]
    z, y, x = np.meshgrid(*axes, indexing="ij")
    return np.column_stack([x.ravel(), y.ravel(), z.ravel()])


def _grid_object(dmap) -> bpy.types.Object:
    """The hidden mesh: a vertex at every voxel centre, the map's value as "density"."""
    me = tag(bpy.data.meshes.new("ensemble density grid"), GRID_ROLE)
    co = voxel_centres(dmap).astype(np.float32)
    me.vertices.add(len(co))
    me.vertices.foreach_set("co", co.ravel())
    me.attributes.new(ATTRIBUTE, "FLOAT", "POINT").data.foreach_set(
        "value", np.ascontiguousarray(dmap.data, dtype=np.float32).ravel())
    me.update()
    ob = tag(bpy.data.objects.new("ensemble density grid", me), GRID_ROLE)
    ob.hide_viewport = ob.hide_render = True
    return ob


def _node_group(grid: bpy.types.Object, dmap, threshold: float,
                material: bpy.types.Material) -> bpy.types.NodeTree:
    """Volume Cube over the map's voxel centres, each voxel the grid object's value at it, with
    `material` (a volume made by nodes carries only the material a Set Material node gives)."""
    ng = tag(bpy.data.node_groups.new("FibrilFit ensemble density", "GeometryNodeTree"), ROLE)
    ng.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    ng.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    level = ng.interface.new_socket("Threshold", in_out="INPUT", socket_type="NodeSocketFloat")
    level.default_value = threshold
    level.description = "volume fraction below which a voxel is empty"
    nodes, link = ng.nodes, ng.links.new
    given, out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    info = nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = grid
    info.transform_space = "ORIGINAL"  # the voxels' own coordinates: the model's frame
    nearest = nodes.new("GeometryNodeSampleNearest")
    nearest.domain = "POINT"
    link(info.outputs["Geometry"], nearest.inputs["Geometry"])
    link(nodes.new("GeometryNodeInputPosition").outputs[0], nearest.inputs["Sample Position"])
    named = nodes.new("GeometryNodeInputNamedAttribute")
    named.data_type = "FLOAT"
    named.inputs["Name"].default_value = ATTRIBUTE
    value = nodes.new("GeometryNodeSampleIndex")
    value.data_type, value.domain = "FLOAT", "POINT"
    link(info.outputs["Geometry"], value.inputs["Geometry"])
    link(named.outputs[0], value.inputs["Value"])
    link(nearest.outputs[0], value.inputs["Index"])
    above = nodes.new("ShaderNodeMath")
    above.operation = "GREATER_THAN"
    link(value.outputs[0], above.inputs[0])
    link(given.outputs["Threshold"], above.inputs[1])
    kept = nodes.new("ShaderNodeMath")
    kept.operation = "MULTIPLY"
    link(value.outputs[0], kept.inputs[0])
    link(above.outputs[0], kept.inputs[1])
    cube = nodes.new("GeometryNodeVolumeCube")
    link(kept.outputs[0], cube.inputs["Density"])
    nz, ny, nx = dmap.data.shape
    first = np.asarray(dmap.origin) + dmap.voxel / 2
    cube.inputs["Min"].default_value = tuple(first)
    cube.inputs["Max"].default_value = tuple(first + dmap.voxel * (np.array([nx, ny, nz]) - 1))
    for axis, n in zip("XYZ", (nx, ny, nz)):
        cube.inputs[f"Resolution {axis}"].default_value = int(n)
    dressed = nodes.new("GeometryNodeSetMaterial")
    dressed.inputs["Material"].default_value = material
    link(cube.outputs[0], dressed.inputs["Geometry"])
    link(dressed.outputs[0], out.inputs[0])
    return ng


def _material() -> bpy.types.Material:
    """Principled Volume reading the "density" grid, DENSITY_SCALE per volume fraction."""
    mat = tag(bpy.data.materials.new("FibrilFit ensemble density"), ROLE)
    if bpy.app.version < (5, 0, 0):  # from 5.0 every material has nodes (use_nodes deprecated)
        mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    shader = nodes.new("ShaderNodeVolumePrincipled")
    shader.inputs["Color"].default_value = COLOUR
    shader.inputs["Absorption Color"].default_value = COLOUR  # tinted, not black, where it absorbs
    shader.inputs["Density"].default_value = DENSITY_SCALE
    shader.inputs["Density Attribute"].default_value = ATTRIBUTE
    out = nodes.new("ShaderNodeOutputMaterial")
    mat.node_tree.links.new(shader.outputs[0], out.inputs["Volume"])
    return mat


def build(scene, dmap, threshold: float = THRESHOLD) -> dict:
    """The map `dmap` (ensemble.density.DensityMap, the model's frame) as a Volume object in
    the model's collection of `scene`, replacing any earlier one. Returns what the result
    records of it (`scene`: None, the context's). Raises ValueError when the scene holds no
    model."""
    scene = scene or bpy.context.scene
    root = find_root(scene)
    if root is None:
        raise ValueError("the scene holds no FibrilFit model to put the density over")
    remove(scene)
    coll = new_collection("ensemble density", ROLE, root)
    grid = _grid_object(dmap)
    material = _material()
    volume = tag(bpy.data.volumes.new("ensemble density"), ROLE)
    volume.materials.append(material)
    ob = tag(bpy.data.objects.new("ensemble density", volume), ROLE)
    modifier = ob.modifiers.new("ensemble density", "NODES")
    modifier.node_group = _node_group(grid, dmap, threshold, material)
    for o in (grid, ob):
        coll.objects.link(o)
    data = dmap.data
    return {"object": ob.name, "grid": ATTRIBUTE, "threshold": threshold,
            "units": "volume fraction of protein per voxel", "voxel": float(dmap.voxel),
            "origin": [round(float(v), 3) for v in dmap.origin], "shape_zyx": list(data.shape),
            "window_layers": int(dmap.layers), "peak": round(float(data.max()), 4),
            "voxels_above_threshold": int((data > threshold).sum()),
            "material_density_per_fraction": DENSITY_SCALE}


def find(scene) -> bpy.types.Object | None:
    """The model's density Volume object in `scene` (by tag), or None."""
    root = find_root(scene)
    for coll in ([] if root is None else root.children_recursive):
        for ob in coll.objects:
            if ob.get(TAG) == ROLE and ob.type == "VOLUME":
                return ob
    return None
