"""Measurements behind the inflate schedule's mechanics (docs/model/search.md#inflate-schedule).

    .venv/bin/python bench/inflate_mechanics.py

1. Scale set between frames: foreach_set alone, foreach_set + update_tag (what builders/growth.py
   does), and keyframes (the prototype's way): the evaluated scale, and every body's position
   frame by frame against the keyframed bake.
2. The collision sphere follows the scale: two small globules pressed together by gravity come
   to rest at a centre distance of scale x diameter.
3. The joint between the last bead and its globule stays on the full-size surface: the bead's
   centre sits r + R from the globule's while the globule is small.
"""
from __future__ import annotations

import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
import bpy  # noqa: E402
import numpy as np  # noqa: E402

import fibrilfit as ff  # noqa: E402
P = ff.model.params
FRAMES, GROW = 60, 40


def fresh(**kw):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    p = P.make_params(layers=4, linker=5, protocol="inflate", gravity=0.0, settle=False,
                      grow_start=0.3, grow_frames=GROW, hold_frames=40, regrow_cycles=0, **kw)
    return scene, ff.pipeline.build(p, scene)


def scale_at(frame):
    return 0.3 + 0.7 * min(1.0, (frame - 1) / GROW)


def bake(mode):
    scene, model = fresh()
    globules = model.globules
    if mode == "keyframes":
        for ob in globules:  # a key on every frame: exact values whatever the interpolation
            for f in range(1, GROW + 2):
                ob.scale = (scale_at(f),) * 3
                ob.keyframe_insert("scale", frame=f)
    coll = next(c for c in model.root.children if c.get("fibrilfit") == "globules")

    class SetScale:  # a bake hook, as builders/growth.py sets the scale
        def before_frame(self, scene, frame):
            s = scale_at(frame)
            if mode.startswith("foreach_set"):
                coll.objects.foreach_set("scale", np.full(3 * len(coll.objects), s, np.float32))
                if mode.endswith("update_tag"):
                    for ob in coll.objects:
                        ob.update_tag(refresh={"OBJECT"})
            else:
                for ob in globules:
                    ob.scale = (s,) * 3

    steps = ff.builders.bake_steps(scene, model, hooks=[] if mode == "keyframes" else [SetScale()])
    track, scales = [], []
    for frame, pos in steps:
        if frame >= FRAMES:
            break
        track.append(pos.copy())
        scales.append(globules[0].matrix_world.to_scale()[0])
    steps.close()
    return np.array(track), np.array(scales), model


def main():
    runs = {m: bake(m) for m in ("keyframes", "foreach_set+update_tag", "foreach_set",
                                 "ob.scale one by one")}
    ref, ref_scale, _ = runs["keyframes"]
    print("1. scale set between frames, against keyframes (frames 1-%d)" % (FRAMES - 1))
    for mode, (track, scales, _) in runs.items():
        print(f"   {mode:24s} evaluated scale at frames 1/20/40: "
              f"{scales[0]:.3f}/{scales[19]:.3f}/{scales[39]:.3f}; "
              f"max position difference from keyframes {np.abs(track - ref).max():.4f} Å")

    # 2. two globules pushed together at scale 0.5: their resting distance
    scene, model = fresh()
    p = model.params
    g = model.globules
    for ob in g:
        ob.scale = (0.5,) * 3
        ob.update_tag(refresh={"OBJECT"})
    scene.gravity = (0.0, 0.0, -20.0)
    steps = ff.builders.bake_steps(scene, model, hooks=[])
    for frame, pos in steps:
        scene.gravity = (0.0, 0.0, -20.0)
        if frame >= 80:
            break
    steps.close()
    c = pos[:, -1]
    d = np.linalg.norm(np.diff(c, axis=0), axis=1)
    print(f"2. globules at scale 0.5 (D = {p.globule_diameter:g} Å) pressed by gravity: "
          f"neighbour centre distances {np.round(d, 3).tolist()} (0.5 x D = "
          f"{0.5 * p.globule_diameter:g})")

    # 3. the last bead's distance from its globule while small
    track, scales, model = runs["foreach_set+update_tag"]
    p = model.params
    gap = np.linalg.norm(track[:, :, -1] - track[:, :, -2], axis=-1)
    small = scales < 0.6
    print(f"3. last bead to globule centre while the scale is 0.30-0.60: "
          f"{gap[small].min():.3f}-{gap[small].max():.3f} Å; full-size contact r + R = "
          f"{p.residue_radius + p.globule_radius:g} Å, scaled contact r + s R = "
          f"{p.residue_radius + 0.3 * p.globule_radius:g}-{p.residue_radius + 0.6 * p.globule_radius:g} Å")


if __name__ == "__main__":
    main()
