"""The rigid-body world: random gravity from the seed, and a bake that steps frame by frame."""
from __future__ import annotations

import random
from dataclasses import dataclass

import bpy
import numpy as np

from ..model import params as P
from ..model.chain import chain_members
from ..model.gravity import cell_gravity
from .hooks import frame_hooks, run_after, run_before
from .readback import MatrixReader
from .scene import WORLD_OWNED, is_ours


class SceneConflict(RuntimeError):
    """The scene holds something of the user's that the model would have to change."""


def check_world_free(scene: bpy.types.Scene) -> None:
    rbw = scene.rigidbody_world
    if rbw is None:
        return
    for attr in ("collection", "constraints"):
        coll = getattr(rbw, attr)
        if coll is not None and not is_ours(coll) and len(coll.all_objects):
            raise SceneConflict(
                f"scene '{scene.name}' already simulates your own rigid bodies "
                f"('{coll.name}'); build FibrilFit in a new scene so they are left untouched")


def ensure_world(scene: bpy.types.Scene) -> bpy.types.RigidBodyWorld:
    if scene.rigidbody_world is None:
        # No data-API path creates a rigid-body world: one operator call, not one per object.
        with bpy.context.temp_override(scene=scene):
            bpy.ops.rigidbody.world_add()
        scene[WORLD_OWNED] = True
    return scene.rigidbody_world


def draw_gravity(p: P.Params) -> tuple[float, float, float]:
    """Gravity for this seed: each axis uniform in [-g, g], drawn x, y, z; in a periodic cell
    under the tutorial protocol only the Z of that draw (model.gravity.cell_gravity)."""
    rng = random.Random(p.seed)
    return cell_gravity(p, [rng.uniform(-p.gravity, p.gravity) for _ in range(3)])


def frame_split(p: P.Params) -> int:
    """Scene frames per frame of the model: a periodic cell's images move once per scene frame,
    so its frames are baked as `image_updates` shorter ones (same substeps); else 1."""
    return p.image_updates if p.periodic else 1


def setup_world(scene: bpy.types.Scene, p: P.Params) -> tuple[float, float, float]:
    """Set gravity, speed, quality and the cache range; free the old cache. Returns gravity."""
    rbw = scene.rigidbody_world
    gravity = draw_gravity(p)
    k = frame_split(p)
    scene.use_gravity = True
    scene.gravity = gravity
    rbw.enabled = True
    rbw.time_scale = p.time_scale / k if k > 1 else p.time_scale
    rbw.substeps_per_frame = p.substeps // k
    rbw.solver_iterations = p.solver_iterations
    rbw.point_cache.frame_start = 1
    rbw.point_cache.frame_end = p.bake_frames() * k
    scene.frame_start, scene.frame_end = 1, p.bake_frames() * k
    _free_cache(scene)
    return gravity


def _free_cache(scene):
    cache = scene.rigidbody_world.point_cache
    if cache.is_baked:
        with bpy.context.temp_override(scene=scene, point_cache=cache):
            bpy.ops.ptcache.free_bake()
    # Changing a world setting invalidates the memory cache; going to frame 1 resets the sim.
    scene.frame_set(1)


def keep_bake(scene: bpy.types.Scene) -> bool:
    """Mark the frames simulated so far as baked (no-op if already baked). Returns is_baked.

    Any edit to a simulated object (even ob.color, or a material on its mesh) marks an unbaked
    memory cache outdated: measured on bpy 4.2 and 5.0, the next frame change then shows stale
    positions (3-5 Å off). A baked cache survives such edits, scrubbing, and a saved file.
    """
    rbw = scene.rigidbody_world
    if rbw is None or rbw.point_cache is None:
        return False
    cache = rbw.point_cache
    if not cache.is_baked:
        # No data-API path turns a memory cache into a bake: one operator call.
        with bpy.context.temp_override(scene=scene, point_cache=cache):
            bpy.ops.ptcache.bake_from_cache()
    return bool(cache.is_baked)


@dataclass
class BakeStats:
    frames_simulated: int = 0
    settled_at: int | None = None
    cancelled: bool = False


def bake_steps(scene: bpy.types.Scene, model, stats: BakeStats | None = None, hooks=None):
    """Simulate frames 1..p.bake_frames() one at a time, yielding (frame, chain positions) after each.

    The generator form lets the sidebar's modal operator advance a few frames per timer tick.
    With `p.settle`, stops once every active body moved less than `settle_speed` per frame for
    `settle_frames` frames, unless a hook is `busy`; a hook that is `finished` ends the bake.
    `stats` (updated in place) says how far it got. `hooks` (default: hooks.frame_hooks for the
    model) run before and after every frame. A periodic cell's frames are
    split (frame_split): frames, speeds and counts here are then the scene's shorter ones.
    """
    p = model.params
    k = frame_split(p)
    stats = stats if stats is not None else BakeStats()
    setup_world(scene, p)
    hooks = frame_hooks(model, scene) if hooks is None else list(hooks)
    chain_objects = [ob for members in model.chain for ob in members]
    shape = (len(model.chain), chain_members(p), 3)  # members: linker + 1 per domain
    # One foreach_get over the rigid-body world's objects per frame, not one read per object.
    reader = MatrixReader(chain_objects, (scene.rigidbody_world.collection,))
    prev, quiet = None, 0
    settle_speed, settle_frames = p.settle_speed / k, p.settle_frames * k
    for frame in range(1, p.bake_frames() * k + 1):
        run_before(hooks, scene, frame)
        scene.frame_set(frame)
        pos = reader.positions().reshape(shape)
        run_after(hooks, scene, frame, pos)
        stats.frames_simulated = frame
        yield frame, pos
        if any(getattr(h, "finished", False) for h in hooks):
            return
        if p.settle and prev is not None and not any(getattr(h, "busy", False) for h in hooks):
            speed = np.linalg.norm(pos - prev, axis=-1).max()
            quiet = quiet + 1 if speed < settle_speed else 0
            if quiet >= settle_frames:
                stats.settled_at = frame
                return
        prev = pos
