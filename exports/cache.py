"""Keep a stepped bake: mark the rigid-body memory cache as baked before anything edits the model.

Any edit to a simulated object (even `ob.color`, or a material on its mesh) invalidates an
unbaked memory cache: measured on bpy 4.2 and 5.0, the next frame change then shows stale
positions instead of the baked ones. A baked cache survives such edits.
"""
from __future__ import annotations

import bpy


def keep_bake(scene: bpy.types.Scene) -> bool:
    """Mark the frames simulated so far as baked (no-op if already baked). Returns is_baked."""
    rbw = scene.rigidbody_world
    if rbw is None or rbw.point_cache is None:
        return False
    cache = rbw.point_cache
    if not cache.is_baked:
        # No data-API path turns a memory cache into a bake: one operator call.
        with bpy.context.temp_override(scene=scene, point_cache=cache):
            bpy.ops.ptcache.bake_from_cache()
    return bool(cache.is_baked)
