"""The run command's output options for pictures and structures (no bpy: the parser needs none).

    --pdb PATH [--pdb-frames last|all]
    --render PATH.png [--render-size WxH] [--render-samples N] [--render-engine cycles|workbench]
    --movie PATH.mp4|PATH.gif [--movie-step K]
"""
from __future__ import annotations

import argparse
import re

MOVIE_FORMATS = (".mp4", ".gif")
ENGINES = ("cycles", "workbench")     # exports.render.ENGINES, without importing bpy
SIZE_RANGE, SAMPLES_RANGE = (16, 8192), (1, 4096)
DEFAULT_SIZE, DEFAULT_SAMPLES = "640x360", 8
PDB_STEP = 50                        # exports.pdb.KEYFRAME_STEP
MOVIE_STEP, MOVIE_STEP_RANGE = 5, (1, 10000)


class OptionError(ValueError):
    """A bad value for one of these options; the message starts with the option's name."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("pictures and structures")
    group.add_argument("--pdb", metavar="PATH",
                       help="write a coarse-grained PDB: one pseudo-atom per sphere, one chain "
                            "per layer, radius in the B-factor")
    group.add_argument("--pdb-frames", choices=("last", "all"), default="last",
                       help=f"'last': the final frame; 'all': a multi-model PDB with frames 1, "
                            f"{1 + PDB_STEP}, {1 + 2 * PDB_STEP}, ... and the last baked frame "
                            f"(default last)")
    group.add_argument("--pdb-images", metavar="N", type=int, default=0,
                       help="with --periodic: add the cell's images in the N cells below and "
                            "above as extra chains, after the cell's own (default 0: the cell)")
    group.add_argument("--pdb-atoms", metavar="PATH.cif",
                       help="write the decorated fibril in atoms as mmCIF: the core's chains as "
                            "deposited on the model's layers, each domain placed by its "
                            "globule's final transform, linker beads as CA-only residues "
                            "(needs --fibril and/or --domain)")
    group.add_argument("--render", metavar="PATH.png",
                       help="render the final frame to a PNG (clashing globules red)")
    add_render_options(group)
    group.add_argument("--movie", metavar="PATH.mp4|PATH.gif",
                       help="render the bake as a movie (Workbench, --render-size; clashing "
                            "globules red on the last frame, held for a second), with a "
                            "progress bar on stderr")
    group.add_argument("--movie-step", metavar="K", default=str(MOVIE_STEP),
                       help=f"put every K-th baked frame in the movie, and the last "
                            f"(default {MOVIE_STEP})")


def add_render_options(group) -> None:
    """--render-size, --render-samples, --render-engine: how a picture is rendered, for every
    command that renders one (`run`, `report`); render_options reads them back."""
    group.add_argument("--render-size", metavar="WxH", default=DEFAULT_SIZE,
                       help=f"picture size in pixels (default {DEFAULT_SIZE})")
    group.add_argument("--render-samples", metavar="N", default=str(DEFAULT_SAMPLES),
                       help=f"Cycles samples per pixel, denoised (default {DEFAULT_SAMPLES})")
    group.add_argument("--render-engine", choices=ENGINES, default="cycles",
                       help="cycles (CPU, any machine) or workbench (faster; needs a software "
                            "or hardware OpenGL context) (default cycles)")


def render_options(args) -> dict:
    """Validated size, samples and engine. Raises OptionError naming the option."""
    m = re.fullmatch(r"\s*(\d+)\s*[xX×]\s*(\d+)\s*", str(args.render_size))
    lo, hi = SIZE_RANGE
    if not m or not all(lo <= int(v) <= hi for v in m.groups()):
        raise OptionError(f"--render-size: must be WIDTHxHEIGHT, each from {lo} to {hi} "
                          f"pixels (got {args.render_size!r})")
    lo, hi = SAMPLES_RANGE
    try:
        samples = int(str(args.render_samples))
    except ValueError:
        samples = None
    if samples is None or not lo <= samples <= hi:
        raise OptionError(f"--render-samples: must be an integer from {lo} to {hi} "
                          f"(got {args.render_samples!r})")
    width, height = int(m.group(1)), int(m.group(2))
    return {"size": (width, height), "aspect": width / height, "samples": samples,
            "engine": args.render_engine}


def pdb_images(args, p) -> int:
    """--pdb-images, checked: only with --periodic and --pdb, from 0 to 10 cells."""
    n = args.pdb_images
    if n and not p.periodic:
        raise OptionError("--pdb-images: only with --periodic (a fibril with ends has no images)")
    if n and not args.pdb:
        raise OptionError("--pdb-images: only with --pdb")
    if not 0 <= n <= 10:
        raise OptionError(f"--pdb-images: must be an integer from 0 to 10 cells (got {n})")
    return n


def movie_step(args) -> int:
    """Validated --movie-step. Raises OptionError naming the option."""
    lo, hi = MOVIE_STEP_RANGE
    try:
        step = int(str(args.movie_step))
    except ValueError:
        step = None
    if step is None or not lo <= step <= hi:
        raise OptionError(f"--movie-step: must be an integer from {lo} to {hi} "
                          f"(got {args.movie_step!r})")
    return step


def pdb_fits(p) -> None:
    """Refuse, before any work, a fibril taller than PDB's coordinate columns (9999.999 Å)."""
    top = ((p.layers - 1) * p.rise + max(0.0, (p.protofilaments - 1) * p.pf_rise)
           + p.globule_diameter + p.residue_radius)
    if p.layers > 1 and top > 9999.999:
        most = int((9999.999 - p.globule_diameter - p.residue_radius) // p.rise) + 1
        raise OptionError(f"--pdb: a {p.layers}-layer fibril is {top:.0f} Å tall; PDB "
                          f"coordinates stop at 9999.999 Å, so at most {most} layers")
