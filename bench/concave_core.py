"""Which Bullet collision shape holds a bead against a concave core: MESH or CONVEX_HULL?

    .venv/bin/python bench/concave_core.py [--frames 250]

A stack of passive U-shaped prisms (the cores of 3 layers, FibrilFit's own mesh builder) and one
active linker bead (r = 1.75 Å) started 0.5 Å from a surface of the notch and pushed onto it by a
strong gravity (20 Å/s², 40x the model's bound). Cases: on the notch's floor, in its corner
(floor and side wall), on the seam between two layers' prisms, and on the outer face (convex,
for comparison). Prints, per shape and case, the bead's worst gap to the outline over the bake
(negative: sunk in by that much), its gap and height Y at the end, and how it ended. A bead
started in the notch is inside a convex hull from the start, so the hull's rows say what Bullet
does with a body started inside it; the last case starts outside both.
"""
from __future__ import annotations

import argparse
import json
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]

U_CORE = [[-20, -11], [20, -11], [20, 11], [8, 11], [8, -3], [-8, -3], [-8, 11], [-20, 11]]
RISE, LAYERS, RADIUS, GRAVITY = 4.8, 3, 1.75, 20.0
# start (x, y, z) and gravity direction (x, y) for each case
CASES = {
    "notch floor": ((0.0, -3 + RADIUS + 0.5, RISE), (0.0, -1.0)),
    "notch corner": ((8 - RADIUS - 0.5, -3 + RADIUS + 0.5, RISE), (0.7071, -0.7071)),
    "floor at a layer seam": ((0.0, -3 + RADIUS + 0.5, RISE / 2), (0.0, -1.0)),
    "outer face (convex)": ((0.0, -11 - RADIUS - 0.5, RISE), (0.0, 1.0)),
    "falls into the notch from outside": ((0.0, 11 + RADIUS + 0.5, RISE), (0.0, -1.0)),
}


def _fibrilfit():
    import bpy  # noqa: F401
    import fibrilfit
    return fibrilfit


def probe(shape: str, case: str, frames: int = 120) -> dict:
    """Bake one bead against the U core with collision shape `shape`; the worst gap and the end."""
    import bpy
    import numpy as np
    ff = _fibrilfit()
    from fibrilfit.geom import polygons
    from fibrilfit.builders import meshes
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    bpy.ops.rigidbody.world_add()
    rbw = scene.rigidbody_world
    rbw.collection = bpy.data.collections.new("bodies")
    rbw.substeps_per_frame, rbw.solver_iterations = 10, 10
    rbw.point_cache.frame_end = scene.frame_end = frames
    mesh = meshes.prism("core", U_CORE, RISE)
    for k in range(LAYERS):
        ob = bpy.data.objects.new(f"core {k}", mesh)
        ob.location.z = k * RISE
        scene.collection.objects.link(ob)
        rbw.collection.objects.link(ob)
        ob.rigid_body.type, ob.rigid_body.collision_shape = "PASSIVE", shape
    bead_mesh = meshes.uv_sphere("bead", RADIUS, 8, 4)
    bead = bpy.data.objects.new("bead", bead_mesh)
    start, (gx, gy) = CASES[case]
    bead.location = start
    scene.collection.objects.link(bead)
    rbw.collection.objects.link(bead)
    bead.rigid_body.type, bead.rigid_body.collision_shape = "ACTIVE", "SPHERE"
    scene.gravity = (GRAVITY * gx, GRAVITY * gy, 0.0)
    worst, inside = np.inf, False
    for f in range(1, frames + 1):
        scene.frame_set(f)
        xyz = np.array(bead.matrix_world.translation)
        gap = float(polygons.edge_distance(U_CORE, xyz[None, :2])[0][0]) - RADIUS
        now_inside = bool(polygons.inside(U_CORE, xyz[None, :2])[0])
        inside |= now_inside
        worst = min(worst, -gap - 2 * RADIUS if now_inside else gap)
    end_gap = float(polygons.edge_distance(U_CORE, xyz[None, :2])[0][0]) - RADIUS
    if polygons.inside(U_CORE, xyz[None, :2])[0]:
        end = "inside the core"
    elif end_gap < -0.1:
        end = "sunk in"
    elif end_gap > 0.05:
        end = f"held {end_gap:.2f} Å off the core"
    else:
        end = "resting on the core"
    return {"shape": shape, "case": case, "worst_gap": round(worst, 3),
            "end_gap": round(end_gap, 3), "end": end, "ever_inside": inside,
            "end_xyz": [round(v, 3) for v in xyz.tolist()], "bpy": bpy.app.version_string}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frames", type=int, default=250)
    args = ap.parse_args(argv)
    rows = [probe(shape, case, args.frames) for shape in ("MESH", "CONVEX_HULL") for case in CASES]
    print(f"| shape | case | worst gap over {args.frames} frames, Å | gap at the end, Å | "
          f"bead centre at the end (x, y, z), Å | end |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['shape']} | {r['case']} | {r['worst_gap']:.3f} | {r['end_gap']:.3f} | "
              f"({', '.join(f'{v:.2f}' for v in r['end_xyz'])}) | {r['end']} |")
    print(json.dumps(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
