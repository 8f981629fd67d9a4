"""Read a FibrilFit density Volume object's grid back through Blender's own nodes (Distribute
Points in Volume, grid mode, one voxel apart: a vertex at each voxel above a level). Imported by
tests/blender/test_ensemble_volume.py; run by the real Blender on a saved .blend
(tests/realblender/test_volume.py):

    blender -b FILE.blend --factory-startup -P tests/realblender/volume_probe.py -- OUT.json
"""
import json
import sys

import bpy
import numpy as np


def voxels_above(volume, voxel: float):
    """A function level -> (n, 3) centres of `volume`'s voxels above the level, through a
    probe object linked to the scene's master collection (a test's, not the model's)."""
    probe = bpy.data.objects.new("probe", bpy.data.meshes.new("probe"))
    bpy.context.scene.collection.objects.link(probe)
    ng = bpy.data.node_groups.new("probe", "GeometryNodeTree")
    ng.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    ng.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    info = ng.nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = volume
    info.transform_space = "ORIGINAL"
    points = ng.nodes.new("GeometryNodeDistributePointsInVolume")
    if hasattr(points, "mode"):  # 4.2, 4.3; a menu socket from 5.0 on
        points.mode = "DENSITY_GRID"
    else:
        points.inputs["Mode"].default_value = "Grid"
    points.inputs["Spacing"].default_value = (voxel,) * 3
    vertices = ng.nodes.new("GeometryNodePointsToVertices")
    out = ng.nodes.new("NodeGroupOutput")
    ng.links.new(info.outputs["Geometry"], points.inputs["Volume"])
    ng.links.new(points.outputs[0], vertices.inputs[0])
    ng.links.new(vertices.outputs[0], out.inputs[0])
    probe.modifiers.new("probe", "NODES").node_group = ng

    def above(level: float) -> np.ndarray:
        points.inputs["Threshold"].default_value = level
        ev = probe.evaluated_get(bpy.context.evaluated_depsgraph_get())
        co = np.empty(3 * len(ev.data.vertices))
        ev.data.vertices.foreach_get("co", co)
        return co.reshape(-1, 3)
    return above


def main(out: str) -> None:
    volumes = [ob for ob in bpy.context.scene.objects
               if ob.get("fibrilfit") == "density" and ob.type == "VOLUME"]
    report = {"volumes": len(volumes), "blender": bpy.app.version_string}
    if volumes:
        ob = volumes[0]
        ev = ob.evaluated_get(bpy.context.evaluated_depsgraph_get())
        report["grids"] = [[g.name, g.data_type] for g in ev.data.grids]
        threshold = ob.modifiers[0].node_group.interface.items_tree["Threshold"].default_value
        report["threshold"] = threshold
        report["voxels_above_threshold"] = len(voxels_above(ob, 3.0)(threshold))
        report["collection_role"] = ob.users_collection[0].get("fibrilfit")
    with open(out, "w", encoding="utf-8") as f:
        json.dump(report, f)


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1])
