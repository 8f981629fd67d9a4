"""--movie: the bake as a movie. Workbench, every k-th baked frame and the last, clashing
globules red (grazing ones pale red) on the last frame, which is held for a second; every frame
with the legend and scale bar of exports/legend.py where matplotlib is there.

Each frame is rendered to a PNG with render.py's settings (restored afterwards), then joined:
.mp4 by Blender's own FFmpeg (H.264, through a temporary sequencer scene: no extra library),
.gif by Pillow (not in Blender's Python: refused before the bake when missing). A progress bar
(tqdm, or plain lines where tqdm is missing, as in an installed extension) goes to stderr.
"""
from __future__ import annotations

import contextlib
import pathlib
import sys
import tempfile
import time

import bpy
import numpy as np

from .. import files
from ..exits import missing_packages
from ..analysis import clash_kinds
from ..builders import find_model
from ..builders.colours import colour_globules
from . import dressing, legend, render
from .plans import MOVIE_FORMATS, OptionError

FPS = 24
GIF_FRAME_MS = 40          # GIF counts in hundredths of a second: 25 frames/s, not 24
HOLD_S = 1.0               # the last frame (clashes red) stays this long
ENGINE = "workbench"


class MovieError(RuntimeError):
    """The movie could not be made; the message says why."""


def movie_frames(last: int, step: int) -> list[int]:
    """Frames 1, 1 + step, 1 + 2 step, ... and always `last`."""
    frames = list(range(1, int(last) + 1, int(step)))
    return frames if frames[-1] == last else [*frames, int(last)]


def video_frame_count(n_frames: int, suffix: str) -> int:
    """Frames in the file: an .mp4 repeats the last one for HOLD_S; a .gif shows it longer."""
    return n_frames + (round(HOLD_S * FPS) - 1 if suffix == ".mp4" else 0)


def missing_support(suffix: str) -> str | None:
    """Why this Blender cannot write `suffix`, or None."""
    if suffix == ".mp4" and not bpy.app.ffmpeg.supported:
        return "this Blender was built without FFmpeg; write a .gif instead"
    if suffix == ".gif":
        try:
            import PIL  # noqa: F401
        except ImportError:
            return missing_packages(["PIL"], "a .gif") + "; or write an .mp4 instead"
    return None


def refuse_unsupported(path, stop_after: str = "check") -> None:
    """Refuse, before any work, a movie without a bake, or in a format this Blender cannot
    write (FFmpeg, Pillow). Raises OptionError naming --movie."""
    if stop_after == "build":
        raise OptionError("--movie: needs a bake; not with --stop-after build")
    why = missing_support(pathlib.PurePath(str(path)).suffix.lower())
    if why:
        raise OptionError(f"--movie: {why}")


def write_movie(scene: bpy.types.Scene, result: dict, path, *, step: int,
                size: tuple[int, int], progress: bool = True) -> dict:
    """Render the baked frames of the model in `scene` to `path` (.mp4 or .gif, atomically).
    Returns what was done, for the result JSON; raises MovieError on failure."""
    path = pathlib.Path(path)
    suffix = path.suffix.lower()
    if suffix not in MOVIE_FORMATS:
        raise MovieError(f"the movie must end in {' or '.join(MOVIE_FORMATS)} (got '{path}')")
    if (why := missing_support(suffix)):
        raise MovieError(why)
    model = find_model(scene)
    if model is None:
        raise MovieError(f"scene '{scene.name}' holds no FibrilFit model")
    last = int(result.get("frames_simulated") or scene.frame_current)
    frames = movie_frames(last, step)
    width, height = (int(v) for v in size)
    t = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="fibrilfit-movie-") as tmp:
        pngs = _render_frames(scene, model, result, frames, pathlib.Path(tmp), width, height,
                              progress)
        join = _join_mp4 if suffix == ".mp4" else _join_gif
        files.atomic_write(path, lambda out: join(pngs, out, width, height))
    return {"path": str(path), "format": suffix[1:], "engine": ENGINE, "width": width,
            "height": height, "step": int(step), "frames": frames,
            "fps": FPS if suffix == ".mp4" else 1000 / GIF_FRAME_MS,
            "video_frames": video_frame_count(len(frames), suffix),
            "seconds": round(time.perf_counter() - t, 3)}


def _render_frames(scene, model, result, frames, folder, width, height, progress) -> list:
    """One PNG per frame: the globules neutral until the last frame, then the clashes red; the
    camera framed on every frame of the movie. Returns the PNG paths."""
    dressed = dressing.dress(scene, model, [], aspect=width / height)
    points = []
    for frame in frames:
        scene.frame_set(frame)
        points.append(dressing.model_points(model))
    points = np.concatenate(points)
    dressing.frame_camera(dressed.camera, points, width / height, dressing.view_azimuth(model))
    deep, grazing = clash_kinds(result)
    # every frame carries the legend (its clash and graze counts are the last frame's) and the
    # scale bar of the one camera the whole movie uses
    entries = render.legend_entries(model, deep, grazing, result)
    scale = render.angstrom_per_pixel(dressed.camera, points, width)
    note = render.scale_note(model)
    dressing.aim_light(dressed.light, dressed.camera)
    settings = render.render_settings(scene, dressed.camera, ENGINE, width, height, 1, False)
    pngs = []
    with _progress(len(frames), progress) as tick, render.applied_settings(scene, settings):
        for frame in frames:
            scene.frame_set(frame)
            if frame == frames[-1]:
                colour_globules(model, deep, scene, grazing)
            png = folder / f"frame{frame:06d}.png"
            with render.captured_output() as log:
                try:
                    render.render_frame(scene, png)
                except Exception as exc:
                    raise MovieError(f"frame {frame}: {render.one_line(exc)}"
                                     f"{render.last_words(log())}") from exc
            if legend.why_not(width, height) is None:
                legend.compose(png, png, entries, scale, note=note)
            pngs.append(png)
            tick()
    return pngs


def _join_gif(pngs, out: pathlib.Path, width, height) -> None:
    from PIL import Image
    images = [Image.open(p).convert("RGB").quantize(colors=256, dither=Image.Dither.NONE)
              for p in pngs]
    durations = [GIF_FRAME_MS] * (len(images) - 1) + [round(1000 * HOLD_S)]
    images[0].save(out, format="GIF", save_all=True, append_images=images[1:],
                   duration=durations, loop=0, optimize=False, disposal=1)


def _join_mp4(pngs, out: pathlib.Path, width, height) -> None:
    """Blender's FFmpeg writer, fed the PNGs by an image strip in a temporary scene."""
    movie = bpy.data.scenes.new("FibrilFit movie")
    try:
        editor = movie.sequence_editor_create()
        strips = editor.strips if hasattr(editor, "strips") else editor.sequences  # 4.2: sequences
        strip = strips.new_image("frames", str(pngs[0]), 1, 1)
        hold = [pngs[-1]] * (video_frame_count(len(pngs), ".mp4") - len(pngs))
        for png in [*pngs[1:], *hold]:
            strip.elements.append(png.name)
        r = movie.render
        r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100
        r.fps, r.fps_base = FPS, 1.0
        movie.frame_start, movie.frame_end = 1, len(strip.elements)
        if hasattr(r.image_settings, "media_type"):  # 5.0+: choose video before its format
            r.image_settings.media_type = "VIDEO"
        r.image_settings.file_format = "FFMPEG"
        r.ffmpeg.format, r.ffmpeg.codec = "MPEG4", "H264"
        r.ffmpeg.constant_rate_factor = "HIGH"
        r.use_sequencer, r.use_file_extension = True, False
        # The PNGs already hold display colours: pass them through unchanged.
        movie.view_settings.view_transform = "Standard"
        movie.view_settings.look = "None"
        r.filepath = str(out)
        with render.captured_output() as log:
            with bpy.context.temp_override(scene=movie):
                done = bpy.ops.render.render(animation=True, scene=movie.name)
        if "FINISHED" not in done or not out.is_file() or out.stat().st_size == 0:
            raise MovieError(f"Blender's movie writer returned {sorted(done)} and wrote no "
                             f"file{render.last_words(log())}")
    finally:
        bpy.data.scenes.remove(movie)


@contextlib.contextmanager
def _progress(total: int, show: bool):
    """A callable to call once per rendered frame: a tqdm bar on stderr, or a line every tenth
    frame where tqdm is missing."""
    if not show:
        yield lambda: None
        return
    try:
        from tqdm import tqdm
    except ImportError:
        done = 0

        def tick():
            nonlocal done
            done += 1
            if done == 1 or done == total or done % 10 == 0:
                print(f"fibrilfit: movie frame {done}/{total}", file=sys.stderr, flush=True)
        yield tick
        return
    with tqdm(total=total, desc="fibrilfit: movie", unit="frame", file=sys.stderr,
              leave=True, dynamic_ncols=True) as bar:
        yield lambda: bar.update(1)
