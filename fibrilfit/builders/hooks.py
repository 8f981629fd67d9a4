"""Work done around every simulated frame of a bake, chosen from the model's parameters.

A hook has `before_frame(scene, frame)` (called before the frame is simulated: e.g. growing
globules) and/or `after_frame(scene, frame, positions)` (called once its chain positions are
read: e.g. images that follow their originals). `frame_hooks` is the one place that decides which
a model gets, so the CLI, the sidebar's modal bake and sweeps bake the same way.
"""
from __future__ import annotations

from typing import Callable

from .growth import Inflate


def frame_hooks(model, scene, *, judge: Callable | None = None) -> list:
    """The hooks a bake of `model` in `scene` runs, in order (none for the tutorial's model).

    `judge(model)` -> the check's result at the current frame, for hooks that judge layouts
    mid-bake (inflate); without it they fall back to sphere depths and bond stretch.

    A hook may also have `busy` (True: settling must not end the bake yet), `finished` (True:
    end the bake after this frame) and `summary()` (fields added to the bake's result).
    """
    hooks: list = []
    if model.params.protocol == "inflate":
        hooks.append(Inflate(model, scene, judge))
    if model.params.periodic:  # images follow their originals (builders/periodic.py)
        from .periodic import ImageFollower
        hooks.append(ImageFollower(model))
    return hooks


def run_before(hooks, scene, frame: int) -> None:
    for hook in hooks:
        before = getattr(hook, "before_frame", None)
        if before is not None:
            before(scene, frame)


def run_after(hooks, scene, frame: int, positions) -> None:
    for hook in hooks:
        after = getattr(hook, "after_frame", None)
        if after is not None:
            after(scene, frame, positions)
