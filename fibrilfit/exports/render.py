"""A headless PNG of the model at the current frame: Cycles on the CPU, or Workbench.

Both engines were measured to run headless in the bpy module 4.2.0 and 5.0.1 with no GPU
(Workbench through a software OpenGL context). The scene's own render settings are restored
afterwards, so rendering from the UI changes nothing of the user's.
"""
from __future__ import annotations

import contextlib
import os
import pathlib
import sys
import tempfile
import time

import bpy
import numpy as np

from .. import files
from . import legend
from ..builders import find_model
from ..builders.colours import CLASH_COLOR, COLORS, GRAZE_COLOR, part_colour
from ..builders.periodic import FADE, FADE_TO
from .dressing import SENSOR_MM, dress, model_points

ENGINES = {"cycles": "CYCLES", "workbench": "BLENDER_WORKBENCH"}
MIN_SIZE, MAX_SIZE = 16, 8192
DEFAULT_SIZE = (640, 360)
DEFAULT_SAMPLES = 8


class RenderError(RuntimeError):
    """The render did not produce an image; the message says why."""


def has_denoiser() -> bool:
    """OpenImageDenoise is compiled into this Blender (it is in the PyPI bpy 4.2 and 5.0)."""
    try:
        import _cycles
    except ImportError:
        return False
    return bool(getattr(_cycles, "with_openimagedenoise", False))


def render_png(scene: bpy.types.Scene | None, path, *, model=None, clashing=None,
               size: tuple[int, int] = DEFAULT_SIZE, samples: int = DEFAULT_SAMPLES,
               engine: str = "cycles", grazing=(), result: dict | None = None,
               with_legend: bool = True) -> dict:
    """Render the model at the scene's current frame to `path` (PNG, written atomically), with
    a legend and a scale bar (exports/legend.py) when matplotlib is there.

    `clashing`: layers to colour red first (None keeps the current colours); `grazing`: layers
    whose globules only graze, pale red. `result`: the check's result, for the legend's counts.
    Returns what was done, for the result JSON. Raises RenderError with a one-line reason on
    failure.
    """
    scene = scene or bpy.context.scene
    if engine not in ENGINES:
        raise RenderError(f"engine must be one of {', '.join(ENGINES)} (got {engine!r})")
    width, height = (int(v) for v in size)
    if not (MIN_SIZE <= width <= MAX_SIZE and MIN_SIZE <= height <= MAX_SIZE):
        raise RenderError(f"size must be from {MIN_SIZE} to {MAX_SIZE} pixels each way "
                          f"(got {width}x{height})")
    if int(samples) < 1:
        raise RenderError(f"samples must be at least 1 (got {samples})")
    model = model or find_model(scene)
    if model is None:
        raise RenderError(f"scene '{scene.name}' holds no FibrilFit model to render")
    dressing = dress(scene, model, clashing, aspect=width / height, grazing=grazing)
    why = legend.why_not(width, height) if with_legend else "not asked for"
    drawn = {"drawn": False, "reason": why}
    entries = legend_entries(model, clashing or (), grazing, result)
    scale = angstrom_per_pixel(dressing.camera, model_points(model), width)
    denoise = engine == "cycles" and has_denoiser()
    t = time.perf_counter()
    # Blender's C code prints device probes and per-tile progress on fds 1 and 2: keep them
    # off the terminal, and quote them only if the render fails.
    with captured_output() as log:
        try:
            with applied_settings(scene, render_settings(scene, dressing.camera, engine, width,
                                                   height, samples, denoise)):
                files.atomic_write(path, lambda tmp: render_frame(scene, tmp))
        except Exception as exc:  # Blender reports render failures as RuntimeError
            raise RenderError(one_line(exc) + last_words(log())) from exc
    if why is None:
        drawn = {}
        files.atomic_write(path, lambda tmp: drawn.update(
            legend.compose(path, tmp, entries, scale, note=scale_note(model))))
    return {"path": str(path), "engine": engine, "width": width, "height": height,
            "legend": drawn,
            "samples": samples if engine == "cycles" else None,
            "denoiser": "OpenImageDenoise" if denoise else None,
            "frame": scene.frame_current, "seconds": round(time.perf_counter() - t, 3)}


def legend_entries(model, clashing, grazing, result: dict | None = None) -> list[tuple]:
    """(label, colour) for every colour in the picture: core, linker, each protofilament's
    domains, and the clash and graze colours with how many domains each marks."""
    k = model.params.protofilaments
    band = ((result or {}).get("sphere_check") or {}).get("tolerance")
    within = f" ≤ {band:.2f} Å" if band else ""
    deeper = f" > {band:.2f} Å" if band else ""
    domains = ([("domain", part_colour("globule", 0))] if k == 1 else
               [(f"domain, protofilament {j + 1}", part_colour("globule", j)) for j in range(k)])
    images = []
    if model.params.periodic:  # the cell's screw images, faded towards the backdrop
        faded = tuple(c + FADE * (b - c) for c, b in zip(part_colour("globule", 0), FADE_TO))
        images = [("images of the periodic cell", faded)]
    # a mixed fibril: which subunits carry the domain (the others: no chain, or a bare tail)
    tails = ([("bare tail (subunit without the domain)", COLORS["tail"])] if model.tails else
             [("bare anchor (subunit without the domain)", COLORS["bare_anchor"])]
             if model.bare_anchors else [])
    return [("fibril core", COLORS["slab"]), ("linker", COLORS["residue"]), *domains, *tails,
            *images,
            (f"clash: overlap{deeper} ({len(clashing)})", CLASH_COLOR),
            (f"graze: overlap{within}, mesh resolution ({len(grazing)})", GRAZE_COLOR)]


def angstrom_per_pixel(camera, points, width: int) -> float:
    """Å per pixel across the picture at the depth of the model's centre (perspective: the
    scale bar is exact there, nearer parts look larger)."""
    pts = np.asarray(points, dtype=float)
    centre = (pts.min(axis=0) + pts.max(axis=0)) / 2
    m = np.array(camera.matrix_world, dtype=float)
    depth = float((m[:3, 3] - centre) @ m[:3, 2])  # the camera looks along its -Z
    return depth * SENSOR_MM / camera.data.lens / width


def scale_note(model) -> str:
    p = model.params
    mixed = (f", on {len(model.chain)} of {p.chains} subunits" if len(model.chain) < p.chains
             else "")  # a mixed fibril: how many carry the domain
    return (f"{p.layers} layers, linker {p.linker}, domain {p.globule_diameter:g} Å{mixed}; "
            "scale at the fibril axis")


def render_frame(scene, tmp: pathlib.Path) -> None:
    """Render the scene's current frame to `tmp` as it is set up (shared with exports.movie)."""
    scene.render.filepath = str(tmp)
    with bpy.context.temp_override(scene=scene):
        done = bpy.ops.render.render(write_still=True)
    if "FINISHED" not in done or not tmp.is_file() or tmp.stat().st_size == 0:
        raise RenderError(f"Blender's render returned {sorted(done)} and wrote no image")


@contextlib.contextmanager
def captured_output():
    """Send fds 1 and 2 to a temporary file; yields a function returning what was written."""
    with tempfile.TemporaryFile(mode="w+b") as sink:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        saved = [os.dup(1), os.dup(2)]
        try:
            os.dup2(sink.fileno(), 1)
            os.dup2(sink.fileno(), 2)

            def read() -> str:
                sink.seek(0)
                return sink.read().decode("utf-8", "replace")
            yield read
        finally:
            for fd, copy in zip((1, 2), saved):
                os.dup2(copy, fd)
                os.close(copy)


def last_words(log: str) -> str:
    """The last error-looking line Blender printed, to explain a failure."""
    lines = [ln.strip() for ln in log.splitlines() if ln.strip()]
    errors = [ln for ln in lines if "error" in ln.lower()]
    pick = (errors or lines)[-1:]
    return f" ({pick[0][:200]})" if pick else ""


def render_settings(scene, camera, engine, width, height, samples, denoise) -> list:
    """(owner, attribute, value) triples to apply for the render and restore after it."""
    r = scene.render
    s = [(scene, "camera", camera), (r, "engine", ENGINES[engine]),
         (r, "resolution_x", width), (r, "resolution_y", height),
         (r, "resolution_percentage", 100), (r, "pixel_aspect_x", 1.0), (r, "pixel_aspect_y", 1.0),
         (r, "use_border", False), (r, "filepath", ""), (r, "film_transparent", False),
         (r, "use_file_extension", True),
         (r.image_settings, "file_format", "PNG"), (r.image_settings, "color_mode", "RGB"),
         (r.image_settings, "color_depth", "8"),
         # Standard, not AgX/Filmic: "red" must stay red for the reader (and the pixel tests).
         (scene.view_settings, "view_transform", "Standard"), (scene.view_settings, "look", "None"),
         (scene.view_settings, "exposure", 0.0), (scene.view_settings, "gamma", 1.0)]
    if engine == "cycles":
        c = scene.cycles
        s += [(c, "device", "CPU"), (c, "samples", int(samples)),
              (c, "use_adaptive_sampling", True), (c, "use_denoising", denoise),
              (c, "max_bounces", 4), (c, "diffuse_bounces", 2), (c, "glossy_bounces", 2),
              (c, "transmission_bounces", 2), (c, "transparent_max_bounces", 4),
              (c, "seed", 0), (c, "use_animated_seed", False)]
        if denoise:
            s.append((c, "denoiser", "OPENIMAGEDENOISE"))
    else:
        d = scene.display.shading
        s += [(d, "light", "STUDIO"), (d, "color_type", "OBJECT"), (d, "show_shadows", True),
              (d, "show_cavity", False), (d, "show_object_outline", True),
              (scene.display, "render_aa", "8")]
    return s


@contextlib.contextmanager
def applied_settings(scene, triples):
    """The (owner, attribute, value) triples applied while the block runs, then restored."""
    saved = [(owner, attr, getattr(owner, attr)) for owner, attr, _ in triples]
    try:
        for owner, attr, value in triples:
            setattr(owner, attr, value)
        yield
    finally:
        for owner, attr, value in reversed(saved):
            setattr(owner, attr, value)


def one_line(exc: BaseException) -> str:
    """An exception's message on one line (Blender's render errors span several)."""
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    return "; ".join(lines) or type(exc).__name__
