"""The run command's pictures and structures, written after the run; a failure here is
reported and never costs the run's other outputs."""
from __future__ import annotations

import bpy

from ..analysis import clashing_layers
from ..builders import find_model
from . import dressing, movie, pdb, render


def prepare(scene: bpy.types.Scene, result: dict, *, aspect: float = 16 / 9) -> None:
    """Colour clashing globules and add materials, camera and light (for --blend and
    --render)."""
    model = find_model(scene)
    if model is not None:
        dressing.dress(scene, model, clashing_layers(result), aspect=aspect)


def write_pdb(scene: bpy.types.Scene, result: dict, path, frames: str = "last",
              images: int = 0) -> dict:
    """--pdb: the last baked frame, or with frames='all' the tutorial's keyframes too."""
    model = find_model(scene)
    if model is None:
        raise pdb.PdbError(f"scene '{scene.name}' holds no FibrilFit model")
    last = int(result.get("frames_simulated") or scene.frame_current)
    wanted = pdb.keyframes(last) if frames == "all" else [last]
    return pdb.write_pdb(path, model, scene, frames=wanted, result=result, images=images)


def write_render(scene: bpy.types.Scene, result: dict, path, options: dict) -> dict:
    """--render: the final frame as a PNG, clashing globules red."""
    return render.render_png(scene, path, clashing=clashing_layers(result),
                             size=options["size"], samples=options["samples"],
                             engine=options["engine"])


def write_movie(scene: bpy.types.Scene, result: dict, path, **options) -> dict:
    """--movie: the bake, every k-th frame, clashing globules red at the end."""
    return movie.write_movie(scene, result, path, **options)


def export(result: dict, key: str, label: str, write, *args, **kwargs) -> str | None:
    """Run `write(*args)` and store what it returns (if anything) as result[key]. On any
    failure store {"error": message} instead and return "<label> failed: <message>"."""
    try:
        info = write(*args, **kwargs)
        if info is not None:
            result[key] = info
        return None
    except Exception as exc:  # noqa: BLE001 - reported; the run's other outputs still follow
        message = " ".join(str(exc).split()) or type(exc).__name__
        result[key] = {"error": message}
        return f"{label} failed: {message}"
