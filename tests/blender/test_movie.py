"""--movie: the bake as an .mp4 (Blender's FFmpeg) or a .gif (Pillow), read back frame by frame."""
import json
import sys

import bpy
import numpy as np
import pytest
from helpers import run_cli
from PIL import Image

from fibrilfit import cli
from fibrilfit.api import one_run
from fibrilfit.exports import movie

# 4 layers, linker 1: clashes at the end; 30 frames every 5th: 1, 6, ..., 26 and the last, 30
SMALL = ["--layers", "4", "--linker", "1", "--frames", "30", "--no-settle", "--seed", "1",
         "--render-size", "64x36", "--movie-step", "5"]
FRAMES = [1, 6, 11, 16, 21, 26, 30]


def red_share(rgb: np.ndarray) -> float:
    r, g, b = (rgb[..., i].astype(float) for i in range(3))
    return float(((r > 120) & (g < 100) & (b < 100) & (r > 2 * g)).mean())


def test_movie_frames_take_every_kth_and_the_last():
    assert movie.movie_frames(30, 5) == FRAMES
    assert movie.movie_frames(31, 5) == [1, 6, 11, 16, 21, 26, 31]
    assert movie.movie_frames(1, 5) == [1]
    assert movie.movie_frames(7, 1) == list(range(1, 8))
    assert movie.video_frame_count(7, ".mp4") == 7 + 23 and movie.video_frame_count(7, ".gif") == 7


def test_mp4_has_the_expected_frames_and_a_progress_bar(tmp_path):
    out = run_cli("run", *SMALL, "--movie", str(tmp_path / "m.mp4"),
                  "--json", str(tmp_path / "r.json"))
    assert out.returncode == 0, out.stderr
    assert "fibrilfit: movie" in out.stderr and "7/7" in out.stderr  # tqdm's bar
    r = json.loads((tmp_path / "r.json").read_text())
    assert r["verdict"] == "intersection" and r["frames_simulated"] == 30
    info = r["movie"]
    assert info["frames"] == FRAMES and info["format"] == "mp4" and info["step"] == 5
    assert info["video_frames"] == len(FRAMES) + round(movie.HOLD_S * movie.FPS) - 1
    # read back by Blender's FFmpeg decoder: frame count and size
    clip = bpy.data.movieclips.load(str(tmp_path / "m.mp4"))
    try:
        assert clip.frame_duration == info["video_frames"]
        assert tuple(clip.size) == (64, 36)
    finally:
        bpy.data.movieclips.remove(clip)


def test_gif_has_one_frame_per_baked_step_and_turns_red_at_the_end(tmp_path):
    out = run_cli("run", *SMALL, "--movie", str(tmp_path / "m.gif"), "--quiet",
                  "--json", str(tmp_path / "r.json"))
    assert out.returncode == 0, out.stderr
    assert "fibrilfit: movie" not in out.stderr  # --quiet: no bar
    r = json.loads((tmp_path / "r.json").read_text())
    assert r["verdict"] == "intersection" and r["movie"]["frames"] == FRAMES
    with Image.open(tmp_path / "m.gif") as gif:
        assert gif.n_frames == len(FRAMES) == r["movie"]["video_frames"]
        assert gif.size == (64, 36)
        shares, durations = [], []
        for i in range(gif.n_frames):
            gif.seek(i)
            durations.append(gif.info["duration"])
            shares.append(red_share(np.asarray(gif.convert("RGB"))))
    assert all(s == 0 for s in shares[:-1]) and shares[-1] > 0.02  # clashes red at the end
    assert durations[-1] == 1000 * movie.HOLD_S and set(durations[:-1]) == {movie.GIF_FRAME_MS}


@pytest.mark.parametrize("args,says", [
    (["--movie", "x.avi"], "--movie: must be a file ending in .mp4 or .gif"),
    (["--movie", "x.mp4", "--movie-step", "0"], "--movie-step: must be an integer"),
    (["--movie", "x.mp4", "--movie-step", "two"], "--movie-step: must be an integer"),
    (["--movie", "x.gif", "--stop-after", "build"], "--movie: needs a bake"),
])
def test_bad_movie_options_are_refused_before_the_bake(args, says, tmp_path, capsys, monkeypatch):
    baked = []
    monkeypatch.setattr(one_run, "fresh_scene", lambda: baked.append(True))
    args = [str(tmp_path / a) if a.startswith("x.") else a for a in args]
    assert cli.main(["run", *args, "--json", str(tmp_path / "r.json")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"fibrilfit: error: {says}") and err.count("\n") == 1
    assert not baked and not list(tmp_path.iterdir())


def test_a_gif_without_pillow_is_refused_before_the_bake(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "PIL", None)  # as in Blender's own Python
    baked = []
    monkeypatch.setattr(one_run, "fresh_scene", lambda: baked.append(True))
    assert cli.main(["run", "--movie", str(tmp_path / "m.gif")]) == 2
    err = capsys.readouterr().err
    assert err == (f"fibrilfit: error: --movie: a .gif needs the Python package Pillow, which "
                   f"this Python ({sys.executable}) does not have: pip install pillow; or write "
                   f"an .mp4 instead\n")
    assert not baked


@pytest.mark.slow
def test_the_default_model_as_an_mp4_at_the_default_size(tmp_path):
    """The tutorial's model, every 5th frame at 640x360 (about 1.5 minutes here)."""
    out = run_cli("run", "--movie", str(tmp_path / "bake.mp4"), "--json", str(tmp_path / "r.json"))
    assert out.returncode == 0, out.stderr
    r = json.loads((tmp_path / "r.json").read_text())
    info = r["movie"]
    assert info["frames"] == movie.movie_frames(r["frames_simulated"], 5)
    clip = bpy.data.movieclips.load(str(tmp_path / "bake.mp4"))
    try:
        assert clip.frame_duration == info["video_frames"] == len(info["frames"]) + 23
        assert tuple(clip.size) == (640, 360)
    finally:
        bpy.data.movieclips.remove(clip)
