"""The whole job, build → bake → check, as one function every entry point calls.

headless.py, the operators, sweeps and tests all go through here, so a verdict means the same
wherever it came from.
"""
from __future__ import annotations

import time
from typing import Callable

import bpy

from .model import bracket, hetero, occupancy, params as P
from .model import terminus, version as model_version
from .model.answer import free_end_warnings
from .analysis import StretchLog, check_model, scored_chains
from .builders import (BakeStats, bake_steps, build_model, draw_gravity, find_model, keep_bake,
                       set_stage)
from .builders.hooks import frame_hooks
from .builders.physics import frame_split

STAGES = ("build", "bake", "check")


def version() -> str:
    return model_version.fibrilfit_version()


def build(p: P.Params, scene=None, *, force: bool = False):
    """Build (replacing any earlier model) and return the Model."""
    return build_model(p, scene or bpy.context.scene, force=force)


class Baking:
    """A bake advanced one frame at a time, logging the worst bond stretch of every frame.

    bake() runs it through; the sidebar's modal operator steps it from a timer, so both judge
    the same frames the same way.
    """

    def __init__(self, model, scene=None):
        self.model, self.scene = model, scene or bpy.context.scene
        p = model.params
        self.stretch = StretchLog(hetero.rest_lengths_by_chain(p), p.stretch_tolerance,
                                  scored_chains(p))
        self.stats = BakeStats()
        # Hooks that judge a layout mid-bake (inflate) use the same check as the verdict.
        self.hooks = frame_hooks(model, self.scene, judge=check_model)
        self._frames = bake_steps(self.scene, model, self.stats, self.hooks)
        self.done = False

    @property
    def total(self) -> int:
        """Scene frames the bake may take (a periodic cell's frames are split, frame_split)."""
        return self.model.params.bake_frames() * frame_split(self.model.params)

    def step(self):
        """Simulate the next frame; return (frame, chain positions), or None once finished."""
        if self.done:
            return None
        try:
            frame, positions = next(self._frames)
        except StopIteration:
            self._finish()
            return None
        self.stretch.add(positions)
        return frame, positions

    def cancel(self) -> None:
        """Stop here: the frames so far stay in the memory cache; the model is not marked baked."""
        self._frames.close()
        self.stats.cancelled = True
        self.done = True

    def _finish(self):
        self.done = True
        keep_bake(self.scene)
        set_stage(self.model, "baked", last_frame=self.stats.frames_simulated)

    def result(self) -> dict:
        out = {
            "gravity": [round(g, 9) for g in self.scene.gravity],
            "frames_simulated": self.stats.frames_simulated,
            "settled_at": self.stats.settled_at,
            "cancelled": self.stats.cancelled,
            **self.stretch.summary(),
        }
        for hook in self.hooks:
            if hasattr(hook, "summary"):
                out.update(hook.summary())
        return out


def bake(model, scene=None, *, on_frame: Callable | None = None) -> dict:
    """Bake the model from a freed cache; track the worst bond stretch over every frame.

    `on_frame(frame, chain_positions)` may return True to cancel.
    """
    baking = Baking(model, scene)
    while (stepped := baking.step()) is not None:
        if on_frame is not None and on_frame(*stepped):
            baking.cancel()
    return baking.result()


def check(model, scene=None) -> dict:
    """Judge the model at the scene's current frame (the bake leaves it on its last frame), with
    the bracket's proven side: impossible below the bound (docs/model/bound.md#derivation)."""
    checked = check_model(model)
    # a finite fibril's answer is the short fibril's (docs/model/end-effects.md#end-effects)
    checked["warnings"] = free_end_warnings(model.params) + checked["warnings"]
    return {**checked, "bound": bracket.bound_block(model.params, checked.get("accommodated"))}


def describe(p: P.Params) -> dict:
    """The head of every result: versions, every parameter, the seed and its gravity."""
    return {
        **model_version.code_key(),  # FibrilFit and model versions (what a resume matches)
        "blender_version": bpy.app.version_string,
        "params": p.to_dict(),
        "seed": p.seed,
        "gravity": list(draw_gravity(p)),
        # a mixed fibril: which subunits carry the domain, drawn with the seed (none at f = 1);
        # a hetero-amyloid: which carry A and which B (docs/model/occupancy.md#hetero)
        **({"occupancy": occupancy.occupancy_block(p)}
           if occupancy.is_mixed(p) or occupancy.is_hetero(p) else {}),
    }


def run_model(p: P.Params | None = None, scene=None, *, stop_after: str = "check",
              force: bool = False, on_frame: Callable | None = None) -> dict:
    """Build, bake and check; return the JSON-ready result (docs/guide/headless.md#result-json)."""
    if stop_after not in STAGES:
        raise ValueError(f"stop_after must be one of {STAGES}")
    p = P.validate(p or P.DEFAULTS, force=force)
    scene = scene or bpy.context.scene
    result = {**describe(p), "stage": stop_after, "timings_s": {}}

    def timed(stage, work):
        t = time.perf_counter()
        out = work()
        result["timings_s"][stage] = round(time.perf_counter() - t, 4)
        return out

    if p.free_linker < 1:  # no exit: the linker cannot reach the surface; nothing to build
        return {**result, **terminus.no_exit_result(p),
                "bound": timed("bound", lambda: bracket.bound_block(p, False))}
    model = timed("build", lambda: build(p, scene, force=force))
    if stop_after == "build":
        return result
    result.update(timed("bake", lambda: bake(model, scene, on_frame=on_frame)))
    if stop_after == "bake" or result["cancelled"]:
        return result
    result.update(timed("check", lambda: check(model, scene)))
    return result


def current_model(scene=None):
    return find_model(scene or bpy.context.scene)

