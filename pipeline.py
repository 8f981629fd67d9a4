"""The whole job, build → bake → check, as one function every entry point calls.

headless.py, the operators, sweeps and tests all go through here, so a verdict means the same
wherever it came from.
"""
from __future__ import annotations

import pathlib
import time
import tomllib
from typing import Callable

import bpy
import numpy as np

from . import params as P
from .analysis import StretchLog, check_model, scored_range
from .builders import bake as bake_frames, build_model, draw_gravity, find_model

STAGES = ("build", "bake", "check")


def version() -> str:
    manifest = pathlib.Path(__file__).with_name("blender_manifest.toml")
    return tomllib.loads(manifest.read_text(encoding="utf-8"))["version"]


def build(p: P.Params, scene=None, *, force: bool = False):
    """Build (replacing any earlier model) and return the Model."""
    return build_model(p, scene or bpy.context.scene, force=force)


def bake(model, scene=None, *, on_frame: Callable | None = None) -> dict:
    """Bake the model from a freed cache; track the worst bond stretch over every frame."""
    scene = scene or bpy.context.scene
    p = model.params
    stretch = StretchLog(p.rest_lengths(), p.stretch_tolerance, slice(*scored_range(p)))

    def per_frame(frame, positions):
        stretch.add(positions)
        return bool(on_frame and on_frame(frame, positions))

    stats = bake_frames(scene, model, on_frame=per_frame)
    return {
        "gravity": [round(g, 9) for g in scene.gravity],
        "frames_simulated": stats.frames_simulated,
        "settled_at": stats.settled_at,
        "cancelled": stats.cancelled,
        **stretch.summary(),
    }


def check(model, scene=None) -> dict:
    """Judge the model at the scene's current frame (the bake leaves it on its last frame)."""
    return check_model(model)


def run(p: P.Params | None = None, scene=None, *, stop_after: str = "check", force: bool = False,
        on_frame: Callable | None = None) -> dict:
    """Build, bake and check; return the JSON-ready result (see README, "The result")."""
    if stop_after not in STAGES:
        raise ValueError(f"stop_after must be one of {STAGES}")
    p = P.validate(p or P.DEFAULTS, force=force)
    scene = scene or bpy.context.scene
    result = {
        "fibrilfit_version": version(),
        "blender_version": bpy.app.version_string,
        "params": p.to_dict(),
        "seed": p.seed,
        "gravity": list(draw_gravity(p)),
        "stage": stop_after,
        "timings_s": {},
    }
    t = time.perf_counter()
    model = build(p, scene, force=force)
    result["timings_s"]["build"] = time.perf_counter() - t
    if stop_after == "build":
        return result
    t = time.perf_counter()
    result.update(bake(model, scene, on_frame=on_frame))
    result["timings_s"]["bake"] = time.perf_counter() - t
    if stop_after == "bake" or result["cancelled"]:
        return result
    t = time.perf_counter()
    result.update(check(model, scene))
    result["timings_s"]["check"] = time.perf_counter() - t
    result["timings_s"] = {k: round(v, 4) for k, v in result["timings_s"].items()}
    return result


def current_model(scene=None):
    return find_model(scene or bpy.context.scene)


def save_blend(path, scene=None) -> None:
    """Save the whole file with the bake kept, so it reopens ready to scrub."""
    from .output import atomic_write
    scene = scene or bpy.context.scene
    rbw = scene.rigidbody_world
    if rbw is not None and not rbw.point_cache.is_baked and rbw.point_cache.is_baked is not None:
        # The bake stepped frames into the memory cache; mark it baked so reopening keeps it.
        with bpy.context.temp_override(scene=scene, point_cache=rbw.point_cache):
            bpy.ops.ptcache.bake_from_cache()
    atomic_write(path, lambda tmp: bpy.ops.wm.save_as_mainfile(
        filepath=str(tmp), copy=True, compress=True, check_existing=False))
